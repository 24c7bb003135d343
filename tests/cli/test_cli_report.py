"""CLI tests for `gearcli report`: formats, plots, exit codes, and the accuracy study on a short scene.

Most tests use --quick (one simulation). The full ladder runs on a SHORT scene (the seed cut to
0.25 s, three rungs) so the suite stays fast; the full seed ladder is measured by hand (README).
"""

from __future__ import annotations

import json
import statistics
import struct
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]
SEED = str(ROOT / "configs" / "concrete_mixer.toml")
SHORT = ("--set", "simulation.duration_s=0.25")
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


@pytest.fixture
def runner() -> CliRunner:
    return CliRunner()


def run(runner, *args, input=None):
    return runner.invoke(cli, list(args), input=input, catch_exceptions=False)


def rows_by_key(doc):
    return {(r["stage"], r["quantity"]): r for r in doc["comparison"]}


@pytest.fixture(scope="module")
def quick_json():
    res = run(CliRunner(), "report", SEED, "--quick", "--format", "json")
    assert res.exit_code == 0, res.stderr
    return json.loads(res.stdout), res.stderr


@pytest.fixture(scope="module")
def short_ladder(tmp_path_factory):
    """The full accuracy study, on the seed cut to 0.25 s with three rungs, plus the plots."""
    plots = tmp_path_factory.mktemp("plots")
    res = run(CliRunner(), "report", SEED, *SHORT, "--rtols", "1e-3,1e-5,1e-7", "--format", "json",
              "--plots", str(plots))
    assert res.exit_code == 0, res.stderr
    return json.loads(res.stdout), res.stderr, plots


# ------------------------------------------------------------------------------ theory vs simulation
def test_quick_json_reproduces_the_seed_comparison_with_corrected_theory(quick_json):
    doc, stderr = quick_json
    rows = rows_by_key(doc)
    # corrected theory (docs/errata.md): i = 135150/6069 = 22.2689, F_t = 1851.1 N, F_r = 688.8 N, F_a = 393.5 N
    assert_allclose(rows[(None, "ratio")]["theory"], 135150 / 6069, rtol=1e-12)
    assert_allclose(rows[(1, "tangential_N")]["theory"], 1851.1, rtol=1e-4)
    assert_allclose(rows[(1, "radial_N")]["theory"], 688.8, rtol=2e-4)
    assert_allclose(rows[(1, "axial_N")]["theory"], 393.5, rtol=2e-4)
    # acceptance: the simulated means within 0.5 % of the static values (seed section 4.1-4.2)
    for key, row in rows.items():
        if row["error_percent"] is not None:
            assert abs(row["error_percent"]) < 0.5, (key, row)
    assert doc["accuracy"] is None
    assert "misses the target 23 rpm" in stderr  # the design warning still reaches stderr


def test_quick_json_has_fluctuation_spectrum_and_summaries(quick_json):
    doc, _ = quick_json
    assert len(doc["dynamics"]) == 3
    for st in doc["dynamics"]:
        assert st["tangential_N"]["std"] >= 0 and st["dynamic_factor"] >= 1.0
        sp = st["spectrum"]
        # window 0.244-0.5 s: resolution 1/T ~ 3.9 Hz; samples every 0.25 ms: Nyquist 2000 Hz
        assert_allclose(sp["resolution_Hz"], 1 / 0.256, rtol=0.02)
        assert_allclose(sp["nyquist_Hz"], 2000.0, rtol=1e-3)
    assert [s["mesh_frequency_Hz"] for s in doc["design"]["stages"]] == pytest.approx([210.0, 70.0, 23.8], rel=1e-6)
    assert doc["simulation"]["solver"]["nfev"] > 0
    assert isinstance(doc["energy_residual"], float)
    assert len(doc["input_sha256"]) == 64 and doc["gearcli_version"]


# ------------------------------------------------------------------------------------------ formats
def test_markdown_in_a_pipe_by_default(runner):
    res = run(runner, "report", SEED, "--quick")
    assert res.exit_code == 0, res.stderr
    assert res.stdout.startswith("# gearcli report:")
    assert "## Theory against simulation" in res.stdout and "| stage | quantity |" in res.stdout
    assert "Skipped (`--quick`)" in res.stdout


def test_table_format_is_plain_text_in_a_pipe(runner):
    res = run(runner, "report", SEED, "--quick", "--format", "table")
    assert res.exit_code == 0, res.stderr
    assert "Theory against simulation" in res.stdout and "┃" in res.stdout


@pytest.mark.parametrize("suffix, check", [(".json", lambda t: json.loads(t)["comparison"]),
                                           (".md", lambda t: t.startswith("# gearcli report")),
                                           (".txt", lambda t: "Theory against simulation" in t)])
def test_output_file_format_from_suffix(runner, tmp_path, suffix, check):
    out = tmp_path / f"report{suffix}"
    res = run(runner, "report", SEED, "--quick", "-o", str(out))
    assert res.exit_code == 0, res.stderr
    assert res.stdout == ""
    assert check(out.read_text())


def test_no_progress_output_when_stderr_is_not_a_terminal(quick_json):
    _, stderr = quick_json
    assert stderr and all(line.startswith("warning: ") for line in stderr.splitlines()), stderr


# ------------------------------------------------------------------------------------------- errors
@pytest.mark.parametrize("args", [("--format", "csv"), ("--rtols", "abc"), ("--rtols", "1e-1"),
                                  ("--accuracy", "2")])
def test_bad_usage_exits_2(runner, args):
    res = run(runner, "report", SEED, "--quick", *args)
    assert res.exit_code == 2


def test_bad_design_file_exits_2(runner):
    res = run(runner, "report", "-", "--quick", input="title = 1\n")
    assert res.exit_code == 2 and "gearcli:" in res.stderr and "Traceback" not in res.stderr


# -------------------------------------------------------------------------------------------- plots
def png_size(path: Path) -> tuple[int, int]:
    head = path.read_bytes()[:24]
    assert head[:8] == PNG_SIGNATURE and head[12:16] == b"IHDR", path
    return struct.unpack(">II", head[16:24])


def test_plots_four_pngs_from_the_full_report(short_ladder):
    pytest.importorskip("matplotlib")
    _, stderr, plots = short_ladder
    names = sorted(p.name for p in plots.iterdir())
    # issue 21: the report's engineering part has the Campbell diagram too
    assert names == ["campbell.png", "mesh_forces.png", "spectrum.png", "speeds.png", "work_precision.png"]
    for p in plots.iterdir():
        width, height = png_size(p)
        assert p.stat().st_size > 20_000, p.name
        assert width >= 800 and height >= 300, (p.name, width, height)
    assert "wrote" in stderr


def test_plots_without_matplotlib_warn_and_exit_0(runner, tmp_path, monkeypatch):
    for name in [m for m in sys.modules if m == "matplotlib" or m.startswith("matplotlib.")]:
        monkeypatch.delitem(sys.modules, name)
    monkeypatch.setitem(sys.modules, "matplotlib", None)
    res = run(runner, "report", SEED, "--quick", "--format", "json", "--plots", str(tmp_path / "p"))
    assert res.exit_code == 0
    assert "pip install 'gearcli[plot]'" in res.stderr
    assert json.loads(res.stdout)["comparison"], "everything else is still produced"
    assert not (tmp_path / "p").exists()


# ---------------------------------------------------------------------------------- accuracy study
def test_short_ladder_errors_fall_as_the_tolerance_tightens(short_ladder):
    doc, _, _ = short_ladder
    acc = doc["accuracy"]
    ref = acc["reference"]
    assert ref["uncertainty"] < 1e-6, "the reference and its check agree"
    assert ref["check_method"] != ref["method"]
    methods = {r["method"] for r in acc["runs"]}
    assert "auto" in methods and len(methods) >= 3
    for m in methods:
        ladder = sorted((r for r in acc["runs"] if r["method"] == m and r["failure"] is None),
                        key=lambda r: -r["rtol"])
        loose, tight = ladder[0], ladder[-1]
        for q in ("error_speed", "error_mean_force", "error_peak_force"):
            if not tight["below_reference_resolution"][q.removeprefix("error_")]:
                assert tight[q] < loose[q], (m, q, loose[q], tight[q])
    assert sum(r["file_settings"] for r in acc["runs"]) == 1
    rec = acc["recommended"]
    assert rec is not None and rec["meets_accuracy"]
    # the contract: no setting meeting the target is cheaper, where a run's price is its evaluations at
    # its method's median seconds per evaluation over the ladder (one run's wall time is too noisy to
    # rank neighbouring rungs); within one method that is simply the fewest evaluations
    ok = [r for r in acc["runs"] if r["meets_accuracy"]]
    assert rec["nfev"] == min(r["nfev"] for r in ok if r["method"] == rec["method"])
    rate = {m: statistics.median(r["wall_s"] / r["nfev"] for r in acc["runs"]
                                 if r["method"] == m and r["nfev"] and r["failure"] is None)
            for m in methods}
    assert all(rec["nfev"] * rate[rec["method"]] <= r["nfev"] * rate[r["method"]] for r in ok)
    assert acc["requested_accuracy"] == 1e-4


def test_below_resolution_flags_agree_with_the_numbers(short_ladder):
    """Each quantity's flag against the reference's own resolution of it, its difference from the check run
    (docs/output.md), which the largest of them, the reference's uncertainty, bounds."""
    doc, _, _ = short_ladder
    acc = doc["accuracy"]
    ref = acc["reference"]
    assert all(d <= ref["uncertainty"] for d in ref["differences"].values())
    for r in acc["runs"]:
        for q, flag in r["below_reference_resolution"].items():
            assert flag == (r[f"error_{q}"] < ref["differences"][q])
