"""life --plots: pitting.png and bending.png show the S–N curves of ISO 6336-2/-3 and the duty's spectrum.

Read back from the figure's lines: the curves' ratios between cycle counts are the life factors' of ISO 6336-2
(Z_NT, case-carburised: 1.6 at 1e5, 1 at the knee 5e7, 0.85 at 1e10, slope continued) and ISO 6336-3 (Y_NT: 2.5
at 1e3, 1 at 3e6, 0.85 at 1e10), written here from the standard's table; the cumulative spectrum's steps are the
bins' cycles summed from the highest stress down (numpy on the JSON's bins). A start's peak classes have a few
tens of cycles: the spectrum's first step ran from a fixed 1e3 cycles backwards to them, drawing a thousand cycles
at the start's peak stress.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("matplotlib")

from gearcli import api  # noqa: E402
from gearcli.life.result import Bin  # noqa: E402

SCENE = Path(__file__).parent / "data" / "two_stage_duty.toml"
#: ISO 6336-2 Table (Z_NT) and ISO 6336-3 Table (Y_NT), case-carburised, normal quality: (N, factor)
NODES = {"pitting": ((1e5, 1.6), (5e7, 1.0), (1e10, 0.85)), "bending": ((1e3, 2.5), (3e6, 1.0), (1e10, 0.85))}


def _factor(mode: str, n: float, variant: str = "iso") -> float:
    """The life factor at ``n`` cycles: a power law between the table's nodes, the last slope continued beyond;
    below the knee ISO 6336-6's Miner elementary continues the finite-life exponent k, Miner modified (Haibach)
    takes 2k - 1."""
    (n0, y0), (n1, y1), (n2, y2) = NODES[mode]
    k = math.log(n1 / n0) / math.log(y0 / y1)
    if n < n1:
        return y0 * (n0 / n) ** (1 / k)
    if variant == "elementary":
        return (n1 / n) ** (1 / k)
    if variant == "modified":
        return (n1 / n) ** (1 / (2 * k - 1))
    return y1 * (n1 / n) ** (math.log(y1 / y2) / math.log(n2 / n1))


@pytest.fixture(scope="module")
def static_life():
    session = api.prepare_life(str(SCENE))
    return api.life(session, static=True)


def _figures(result, tmp_path, monkeypatch):
    """The two figures as drawn (saving captured, the PNG written too)."""
    from gearcli.io import life_plots

    figs = []
    real = life_plots._save
    monkeypatch.setattr(life_plots, "_save", lambda fig, path: figs.append(fig) or real(fig, path))
    paths = life_plots.write_life_plots(result, str(tmp_path))
    assert [p.name for p in paths] == ["pitting.png", "bending.png"]
    assert all(p.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" for p in paths)
    return dict(zip(("pitting", "bending"), figs, strict=True))


def _line(ax, label):
    (line,) = [ln for ln in ax.get_lines() if ln.get_label() == label]
    return np.asarray(line.get_xdata(), float), np.asarray(line.get_ydata(), float)


def _at(x, y, n):
    """The curve's stress at ``n`` cycles, log-log interpolated (exact on a power-law segment)."""
    return float(np.exp(np.interp(np.log(n), np.log(x), np.log(y))))


@pytest.mark.parametrize("variant", ["iso", "elementary", "modified"])
def test_sn_curves_are_the_iso_life_factor_curves(static_life, tmp_path, monkeypatch, variant):
    result = static_life if variant == "iso" else api.life(api.prepare_life(str(SCENE)), static=True, variant=variant)
    figs = _figures(result, tmp_path, monkeypatch)
    for mode, probes in (("pitting", (2e5, 1e6, 3e7, 1e9, 1e11)), ("bending", (1e4, 1e5, 1e8, 1e9, 1e11))):
        for ax, st in zip(figs[mode].axes, result.stages, strict=True):
            for member in ("pinion", "gear"):
                x, y = _line(ax, f"{member} S–N")
                endurance = getattr(getattr(st, member), mode).bins[0].endurance_MPa  # the knee's stress
                for n in probes:
                    assert _at(x, y, n) == pytest.approx(endurance * _factor(mode, n, variant), rel=2e-3), \
                        (mode, member, n)


def test_the_spectrum_steps_are_the_cumulative_cycles_down_from_a_starts_peak(static_life, tmp_path, monkeypatch):
    st = static_life.stages[0]
    bending = st.pinion.bending
    top = max(b.stress_MPa for b in bending.bins)
    # a start's peak classes, as the dynamic route adds them: tens of cycles above the steady classes
    starts = (Bin("full (start)", 0.0, 1.25 * top, 43.6, None, 0.0, bending.bins[0].endurance_MPa),
              Bin("full (start)", 0.0, 1.10 * top, 21.8, None, 0.0, bending.bins[0].endurance_MPa))
    bins = (*bending.bins, *starts)
    pinion = dataclasses.replace(st.pinion, bending=dataclasses.replace(bending, bins=bins))
    result = dataclasses.replace(static_life, stages=(dataclasses.replace(st, pinion=pinion), *static_life.stages[1:]))
    figs = _figures(result, tmp_path, monkeypatch)
    x, y = _line(figs["bending"].axes[0], f"pinion spectrum (D = {bending.damage:.3g})")
    ranked = sorted(bins, key=lambda b: -b.stress_MPa)
    cumulative = np.cumsum([b.cycles for b in ranked])
    assert list(x[1:]) == pytest.approx(list(cumulative))  # 43.6, 65.4, then the steady classes' cycles
    assert list(y) == pytest.approx([ranked[0].stress_MPa, *(b.stress_MPa for b in ranked)])
    assert x[0] < x[1] and np.all(np.diff(x) >= 0)  # the top step runs forwards, up to its 43.6 cycles
    sn_x, _ = _line(figs["bending"].axes[0], "pinion S–N")
    assert sn_x[0] == pytest.approx(x[0])  # the curve is drawn over the same cycles


def test_a_planetarys_bending_figure_shows_the_planet_root_over_both_meshes(tmp_path, monkeypatch):
    """docs/life.md: ``planet_root`` (the planet's root bending over both meshes, the figure to judge its root by)
    was missing from bending.png, which drew each mesh's root side apart. Its spectrum is the cumulative cycles of
    its bins (numpy here), its curve the S–N curve; pitting.png has no such member."""
    root = Path(__file__).resolve().parents[2]
    result = api.life(api.prepare_life(str(root / "configs" / "planetary_duty.toml")), static=True)
    st = result.stages[0]
    assert st.planet_root is not None
    figs = _figures(result, tmp_path, monkeypatch)
    label = "planet root (both meshes)"
    ax = figs["bending"].axes[0]
    x, y = _line(ax, f"{label} spectrum (D = {st.planet_root.damage:.3g})")
    ranked = sorted(st.planet_root.bins, key=lambda b: -b.stress_MPa)
    assert list(x[1:]) == pytest.approx(list(np.cumsum([b.cycles for b in ranked])))
    assert list(y[1:]) == pytest.approx([b.stress_MPa for b in ranked])
    assert _line(ax, f"{label} S–N")[1].size > 0
    assert not [ln for ln in figs["pitting"].axes[0].get_lines() if ln.get_label().startswith(label)]
    for fig in figs.values():  # the legend (ten entries) beside the axes, covering none of the curves
        fig.canvas.draw()
        for a in fig.axes:
            legend = a.get_legend().get_window_extent()
            assert not legend.overlaps(a.get_window_extent()) and legend.x1 <= fig.bbox.x1 + 0.5
