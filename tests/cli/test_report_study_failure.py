"""`gearcli report` whose accuracy study fails (its reference run diverges, or the study is out of its budget): the
report is still written, whole and atomically, with theory against simulation complete and the accuracy section
saying that the study failed and why; exit 1, as a sweep in which a point failed (docs/output.md, "Exit codes").

The failure is forced: the reference pair (rtol <= 1e-10) raises what a diverging run raises, or the report's
budget is set to nothing. The report's numbers are checked against the seed reducer by hand (docs/errata.md's
corrected theory): i = (51 50 53) / (21 17 17), n_out = 3600 deg/s / i, T_in = T_out / i on pinion 1 and
T_k = T_in times the ratios before stage k, F_t = 2 T_k / d_k with d_k = m_n z_k / cos beta (no profile shift),
F_r = F_t tan(alpha_t), tan(alpha_t) = tan(alpha_n) / cos(beta), F_a = F_t tan(beta); the simulated window means
within 0.5 % of them (seed section 4.1-4.2: a settled window's mean force is the static one)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

import gearcli.report.build as build
from gearcli.cli import cli
from gearcli.errors import SimulationError

ROOT = Path(__file__).resolve().parents[2]
SEED = str(ROOT / "configs" / "concrete_mixer.toml")
DIVERGED = "the integration diverged at t = 0.0123 s (forced by the test)"
STAGES = [(12, 21, 51, 12), (18, 17, 50, 11), (25, 17, 53, 9)]  # m_n, z_pinion, z_gear, beta
T_OUT, W_IN = 5.31e6, 3600.0  # N mm, deg/s


def _hand() -> dict:
    ratio = math.prod(zg / zp for _, zp, zg, _ in STAGES)
    out = {(None, "ratio"): ratio, (None, "output_speed_deg_s"): W_IN / ratio}
    torque = T_OUT / ratio
    for k, (m, zp, zg, beta) in enumerate(STAGES, start=1):
        b = math.radians(beta)
        ft = 2 * torque / (m * zp / math.cos(b))
        out[(k, "tangential_N")] = ft
        out[(k, "radial_N")] = ft * math.tan(math.radians(20)) / math.cos(b)
        out[(k, "axial_N")] = ft * math.tan(b)
        torque *= zg / zp
    return out


@pytest.fixture
def diverging_reference(monkeypatch):
    real = build.run_simulation

    def run(cfg, design, **kw):
        if kw.get("rtol", 1.0) <= 1e-10:  # the study's reference and its check
            raise SimulationError(DIVERGED)
        return real(cfg, design, **kw)

    monkeypatch.setattr(build, "run_simulation", run)


def _report(tmp_path: Path, name: str, *args: str):
    out = tmp_path / name
    res = CliRunner().invoke(cli, ["report", SEED, "--rtols", "1e-4", "-o", str(out), *args])
    assert res.exit_code == 1, res.output
    assert "Traceback" not in res.output
    assert sorted(p.name for p in tmp_path.iterdir()) == [name]  # the report alone: no temporary file left
    return res, out.read_text(encoding="utf-8")


def _check_numbers(doc: dict) -> None:
    rows = {(r["stage"], r["quantity"]): r for r in doc["comparison"]}
    for key, value in _hand().items():
        assert_allclose(rows[key]["theory"], value, rtol=1e-9, err_msg=str(key))
        assert_allclose(rows[key]["simulated"], value, rtol=5e-3, err_msg=str(key))


def test_a_diverging_reference_leaves_the_report_with_its_theory_and_simulation(tmp_path, diverging_reference):
    res, text = _report(tmp_path, "report.json")
    doc = json.loads(text)  # whole: it parses
    _check_numbers(doc)
    assert doc["accuracy"] is None
    assert doc["accuracy_failure"].startswith("accuracy reference run (DOP853, rtol 1e-12) failed: ")
    assert DIVERGED in doc["accuracy_failure"]
    (failed,) = [w for w in doc["warnings"] if w["code"] == "accuracy" and w.get("failed")]
    assert "the accuracy study failed" in failed["message"] and DIVERGED in failed["message"]
    # one error line, the file named (other "gearcli: " lines may announce a first build of the compiled engine)
    (line,) = [x for x in res.stderr.splitlines() if x.startswith(f"gearcli: {SEED}: ")]
    assert line.startswith(f"gearcli: {SEED}: the report is written without its accuracy study, which failed: ")
    assert "warning: the accuracy study failed" not in res.stderr  # said once


def test_the_markdown_report_says_the_study_failed(tmp_path, diverging_reference):
    _, text = _report(tmp_path, "report.md", "-q")
    assert "## Theory against simulation" in text
    assert "## Numerical accuracy\n\n**The accuracy study failed**: accuracy reference run (DOP853" in text
    assert DIVERGED in text and "Skipped (`--quick`)" not in text


def test_a_study_out_of_its_budget_is_a_failed_section_not_a_lost_report(tmp_path, monkeypatch):
    """The budget projected from the file's own run (StudyTooLong, exit 2 before, the report lost)."""
    monkeypatch.setattr(build, "REPORT_WORK_CAP_S", 1e-9)
    res, text = _report(tmp_path, "report.json", "-q")
    doc = json.loads(text)
    _check_numbers(doc)
    assert doc["accuracy"] is None and doc["accuracy_failure"].startswith("the accuracy study would need about")
    assert "use --quick" in doc["accuracy_failure"]
    assert "the report is written without its accuracy study" in res.stderr  # -q: the error is still said
