"""sweep --plots: what distributions.png shows is the samples, read back from the figure's artists.

The histograms' bar heights of each curve sum to its number of samples, each bar holds the samples between its
edges (counted here with numpy on the same edges), and the ECDF is the textbook one: 0 below the first sample, i/n
from the i-th sample on. A tolerance study of a single sample (or a curve whose samples share one value, on a panel
whose other curves spread over thousands of newtons) drew nothing: a bar 2e-6 of its value wide, an ECDF of one
point (a step line of one vertex is no line).
"""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("matplotlib")

from matplotlib.colors import to_rgba  # noqa: E402

from gearcli.io.sweep_plots import DISTRIBUTION_STATS, FAMILIES, _distributions  # noqa: E402


def _rows(values: dict[int, np.ndarray]) -> list[dict]:
    """Sample rows of a two-stage scene; ``values[k]`` the stage's peak F_t, the other statistics from it."""
    n = len(values[1])
    return [{"status": "ok", "direction": "none",
             **{f"stage{k}_{c}": float(v[i]) * f for k, v in values.items()
                for c, f in (("tangential_N_max", 1.0), ("tangential_N_std", 0.2), ("dynamic_factor", 3e-4),
                             ("dte_um_rms", 1e-4), ("tangential_N_mean", 0.6), ("dte_um_mean", 1e-3))}}
            for i in range(n)]


def _panels(fig, xlabel):
    hist, ecdf = (ax for ax in fig.axes if ax.get_xlabel() == xlabel)
    return hist, ecdf


def _bars_by_colour(ax) -> dict:
    out: dict = {}
    for bar in ax.patches:
        out.setdefault(to_rgba(bar.get_facecolor())[:3], []).append(bar)  # the colour without the alpha
    return out


def test_histogram_counts_and_ecdf_are_the_samples():
    rng = np.random.default_rng(7)
    values = {1: rng.normal(4400.0, 250.0, 37), 2: rng.normal(9800.0, 500.0, 37)}
    fig = _distributions(_rows(values), 2)
    hist, ecdf = _panels(fig, "peak F_t in window (N)")
    bars = _bars_by_colour(hist)
    assert len(bars) == 2
    for (colour, patches), line in zip(bars.items(), ecdf.get_lines(), strict=True):
        assert to_rgba(line.get_color())[:3] == colour
        x = np.sort(np.asarray(line.get_xdata(), float)[1:])
        k = 1 if np.allclose(x, np.sort(values[1])) else 2
        assert np.allclose(x, np.sort(values[k]))
        heights = [p.get_height() for p in patches]
        assert sum(heights) == 37  # every sample counted once
        # len(patches) equal bins from the smallest sample to the largest, counted by numpy
        counts, edges = np.histogram(values[k], bins=len(patches))
        assert list(counts) == heights
        assert [p.get_x() for p in patches] == pytest.approx(list(edges[:-1]), abs=1e-9 * edges[-1])
        # the ECDF: 0 below the first sample, i/37 from the i-th on
        assert list(line.get_ydata()) == pytest.approx(np.arange(0, 38) / 37)
        assert line.get_xdata()[0] == x[0] and line.get_drawstyle() == "steps-post"


def test_a_single_sample_is_a_visible_bar_and_an_ecdf_rise_on_every_panel():
    fig = _distributions(_rows({1: np.array([4421.0]), 2: np.array([9873.0])}), 2)
    assert fig._suptitle.get_text() == "distributions over 1 random sample"
    for _, xlabel in DISTRIBUTION_STATS:
        hist, ecdf = _panels(fig, xlabel)
        lo, hi = hist.get_xlim()
        bars = _bars_by_colour(hist)
        assert len(bars) == 2, xlabel
        for patches in bars.values():
            (bar,) = [p for p in patches if p.get_height() > 0]
            assert bar.get_height() == 1
            assert bar.get_width() >= 0.01 * (hi - lo), xlabel  # a bar you can see, not 2e-6 of its value
        for line in ecdf.get_lines():
            x, y = line.get_xdata(), line.get_ydata()
            assert x[0] == x[-1] and list(y) == [0.0, 1.0], xlabel  # the one sample's rise from 0 to 1


# ------------------------------------------------------------------ the CLI's figures against its own rows

RATTLE = Path(__file__).parent / "data" / "rattle.toml"
SPEEDS = (900.0, 1500.0, 2100.0)


def _sweep(tmp_path, monkeypatch, *args):
    """``gearcli sweep`` in-process: its result, the figures it saved (by file name)."""
    from click.testing import CliRunner

    from gearcli.cli import cli
    from gearcli.io import sweep_plots

    figs: dict = {}
    real = sweep_plots._save
    monkeypatch.setattr(sweep_plots, "_save", lambda fig, path: figs.setdefault(path.name, fig) and real(fig, path))
    res = CliRunner().invoke(cli, ["sweep", str(RATTLE), "--jobs", "1", *args])
    return res, figs


def test_response_curves_are_the_sweeps_columns(tmp_path, monkeypatch):
    """The rattling stage's speed sweep: every response panel's curves are the CSV's columns at the swept speeds
    (contact loss included: 50-80 % of the window), the output speed the input over the ratio 50/20."""
    out, plots = tmp_path / "r.csv", tmp_path / "plots"
    res, figs = _sweep(tmp_path, monkeypatch, "--vary", f"input.speed_rpm={','.join(map(str, SPEEDS))}",
                       "-o", str(out), "--plots", str(plots))
    assert res.exit_code == 0, res.output
    assert sorted(p.name for p in plots.iterdir()) == ["campbell.png", "response_input_speed_rpm.png"]
    assert not list(tmp_path.glob("plots/.*"))  # no temporary file left
    rows = list(csv.DictReader(line for line in out.read_text().splitlines() if not line.startswith("#")))
    assert [float(r["input.speed_rpm"]) for r in rows] == list(SPEEDS) and {r["status"] for r in rows} == {"ok"}
    fig = figs["response_input_speed_rpm.png"]
    checked = 0
    for title, cols in FAMILIES:
        ax = next(a for a in fig.axes if a.get_title() == f"stage 1: {title}")
        lines = ax.get_lines()
        assert len(lines) == len(cols), title
        for line, suffix in zip(lines, cols, strict=True):
            if len(cols) > 1:  # mean, min, max by their legend label (a one-curve family has none)
                assert line.get_label() == suffix.rsplit("_", 1)[-1], title
            assert list(line.get_xdata()) == list(SPEEDS), title
            column = f"stage1_{suffix}"
            assert list(line.get_ydata()) == pytest.approx([float(r[column]) for r in rows], rel=1e-12), column
            checked += 1
    assert checked == 3 + 1 + 3 + 1 + 1 + 1 + 1  # F_t mean/min/max, std, DTE mean/min/max, rms, loss, K_v, run-up
    loss = next(ax for ax in fig.axes if ax.get_title().startswith("stage 1: contact loss"))
    assert min(loss.get_lines()[0].get_ydata()) > 0.3  # it rattles: the panel is not a flat zero
    (speed,) = next(ax for ax in fig.axes if ax.get_title() == "output speed (rpm)").get_lines()
    assert list(speed.get_ydata()) == pytest.approx([n * 20 / 50 for n in SPEEDS], rel=1e-3)  # the ratio 50/20


def test_a_sweep_whose_every_point_failed_writes_no_figures_and_no_directory(tmp_path, monkeypatch):
    plots = tmp_path / "plots"
    res, figs = _sweep(tmp_path, monkeypatch, "--vary", "stage.0.pinion.teeth=3,4", "-o", str(tmp_path / "f.csv"),
                       "--plots", str(plots))
    assert res.exit_code == 1 and "2 failed" in res.stderr
    assert "no figures" in res.stderr and "Traceback" not in res.output
    assert figs == {} and not plots.exists()


@pytest.mark.parametrize("spelling", ["stage[0].backlash_mm", "stage.0.backlash_mm"])
def test_the_check_before_the_sweep_names_the_response_file_it_writes(tmp_path, monkeypatch, spelling):
    """--plots is checked before any point runs: no figure may land on a directory. The check named
    ``response_stage[0]_backlash_mm.png`` for the bracket spelling while the sweep writes
    ``response_stage_0_backlash_mm.png``: a directory there passed the check, the whole sweep ran, and the figure's
    write failed at the end (exit 1). Both spellings are refused up front (exit 2, no row written)."""
    plots = tmp_path / "plots"
    (plots / "response_stage_0_backlash_mm.png").mkdir(parents=True)
    out = tmp_path / "rows.csv"
    res, figs = _sweep(tmp_path, monkeypatch, "--vary", f"{spelling}=0.05,0.1", "-o", str(out), "--plots", str(plots))
    assert res.exit_code == 2, res.output
    assert "response_stage_0_backlash_mm.png" in res.stderr and "Traceback" not in res.output
    assert not out.exists() and figs == {}
