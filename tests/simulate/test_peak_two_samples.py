"""A run of two output samples (``simulation.steps = 1``: t = 0 and the end) sees nothing of its run-up: its
``peak_tangential_N`` is the end sample's and its ``runup_factor`` 1, where the true run-up peak is higher. The
sampling estimate needs a sample between the ends, so it said nothing; the run now warns ``peak_undersampled``
for every loaded stage, with no estimate (``estimated_error_N`` null) and the steps that sample the scene.

Reference by hand: a spur pair driven at a prescribed speed ω0 S(t) against a load T_L S(t), both STEP-ramped over
T (S = s²(3 − 2s), s = t/T), the gear's inertia J alone on the driven side. Rigidly, the mesh carries the load and
the gear's acceleration, F_t = (T_L S + J ω0/i Ṡ) / r_g, over the static T_L / r_g:
run-up factor = max_s [s²(3 − 2s) + 6 c s(1 − s)], c = J ω0 / (i T_L T) — 1.28572 here (at s = 0.743). The
stiff mesh follows the rigid force: a run of 600 steps meets it to 1e-4."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner

from gearcli.cli import cli
from tests.cli.test_cli_design_consumer import scene_text

# one spur pair, i = 40/20, the gear's inertia given (the pinion's speed is prescribed, so its own is moot)
SCENE = scene_text("spur stage run-up", [(3, 20, 0, 1.0, (20, 40), (0.0, 0.0), (30, 30), (None, None), ("st", "st"))],
                   "speed_rpm = 1500\nramp_s = 0.1", "torque_Nm = 100\nramp_s = 0.1",
                   "[simulation]\nduration_s = 0.3\nsteps = 1").replace("gear = { teeth = 40,",
                                                                       "gear = { inertia_kg_m2 = 0.05, teeth = 40,")


def _hand_runup() -> float:
    omega_out = 1500 * 2 * np.pi / 60 / 2.0  # rad/s at the gear, i = 40/20
    c = 0.05 * omega_out / (100.0 * 0.1)
    s = np.linspace(0.0, 1.0, 200_001)
    return float(np.max(s * s * (3 - 2 * s) + 6 * c * s * (1 - s)))


def _simulate(tmp_path, steps: int) -> dict:
    path = tmp_path / "spur.toml"
    assert "inertia_kg_m2 = 0.05" in SCENE
    path.write_text(SCENE)
    res = CliRunner().invoke(cli, ["simulate", str(path), "--format", "json", "--set", f"simulation.steps={steps}"])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def test_two_samples_warn_that_the_run_up_peak_is_not_seen(tmp_path):
    hand = _hand_runup()
    assert hand == pytest.approx(1.28572, abs=1e-5)
    fine = _simulate(tmp_path, 600)["summary"]["stages"][0]
    assert fine["runup_factor"] == pytest.approx(hand, rel=1e-4)  # the reference holds for the model
    doc = _simulate(tmp_path, 1)
    stage = doc["summary"]["stages"][0]
    assert stage["runup_factor"] < 0.8 * hand  # the two samples miss the run-up (they give 1.0)
    (peak,) = [w for w in doc["warnings"] if w["code"] == "peak_undersampled"]
    assert peak["stage"] == 1 and peak["estimated_error_N"] is None and peak["relative_error"] is None
    assert peak["peak_N"] == pytest.approx(stage["peak_tangential_N"], rel=1e-12)
    assert isinstance(peak["steps"], int) and peak["steps"] > 600
    assert f"simulation.steps={peak['steps']}" in peak["message"]
