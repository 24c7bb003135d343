"""A periodic steady state carries an error estimate: its orbit found again at rtol / 10.

tr20c: `steady = "periodic"` took its statistics from the converged orbit with no check pass. A linear single-DOF mesh
oscillator forced by its transmission error at resonance with damping ratio 1e-3 (the F_t amplitude 50x the mean)
came out 4.4e-3 of the mean off its closed form in min and max at DOP853 rtol 1e-6, with no estimate and no warning.
The shooting's own test bounds an orbit's drift over a period, (M - I) dx, which a resonant orbit keeps small for a
start error 1 / (1 - |mu|) ~ 160 times larger. The check finds the orbit again at rtol / 10 (one full Newton step,
then Newton's test) and judges every statistic as a window's check pass does.

Independent reference: the oscillator's closed form (data/linear_te_resonance.toml's docstring):
    m_e q'' + c q' + k q = F_0 + m_e Omega^2 e_1 cos(Omega t), F_t = (k q + c q') cos(alpha) about F_0 cos(alpha).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from click.testing import CliRunner
from te_oscillator import orbit

from gearcli.cli import cli

SCENE = Path(__file__).parent / "data" / "linear_te_resonance.toml"
ZETA, RPM = 1e-3, 2398.3


def _run(*sets: str) -> dict:
    res = CliRunner().invoke(cli, ["simulate", str(SCENE), "--format", "json", "-q", "--set",
                                   f"contact.damping_ratio={ZETA}", "--set", f"input.speed_rpm={RPM}",
                                   *(x for s in sets for x in ("--set", s))])
    assert res.exit_code == 0, res.stderr
    return json.loads(res.stdout)


def _closed_form() -> dict[str, float]:
    mean, amplitude, _ = orbit(ZETA, RPM)
    return {"mean": mean, "min": mean - amplitude, "max": mean + amplitude, "std": amplitude / math.sqrt(2)}


@pytest.mark.parametrize("method", ["DOP853", "Radau"])
def test_the_estimate_bounds_the_orbit_error(method):
    ref = _closed_form()
    doc = _run(f"simulation.method={method}")
    stage = doc["summary"]["stages"][0]
    estimate = stage["error_estimate"]
    assert estimate is not None and doc["solver"]["check_pass"]["finished"]
    for key in ("min", "max", "std"):
        true = abs(stage["tangential_N"][key] - ref[key]) / ref["mean"]
        assert true > 5e-4  # the run is visibly off the closed form (DOP853 4e-3, Radau 8e-4) ...
        assert true <= estimate["relative"][key] <= 2 * true, key  # ... and the estimate bounds it, within 2x
    assert "statistics_unresolved" in [w["code"] for w in doc["warnings"]]


def test_the_suggested_rtol_resolves_the_orbit():
    loose = _run("simulation.method=DOP853")
    suggested = loose["summary"]["stages"][0]["error_estimate"]["suggested_rtol"]
    assert suggested is not None
    doc = _run("simulation.method=DOP853", f"simulation.rtol={suggested:g}")
    assert "statistics_unresolved" not in [w["code"] for w in doc["warnings"]]
    ref = _closed_form()
    for key in ("min", "max", "std"):
        assert abs(doc["summary"]["stages"][0]["tangential_N"][key] - ref[key]) <= 1e-3 * ref["mean"], key
