"""The dynamic factor's static reference under a speed-dependent load, against the operating point by hand.

A load T_L = T_n (n_out / n_out,n)^2 (`load.speed_exponent = 2`, T_n at the nominal output speed) settles where the
drive meets it, not at the nominal speed:
- a torque drive T_in: T_in = T_L(n) / (i eta), so n = n_0 sqrt(T_in i eta / T_n) (DESIGN section 9; `gearcli
  design` warns the same speed);
- a motor with a torque-speed table: where the table's (linear) torque meets T_L(n) / (i eta), bisected here.
The steady mesh force there is T_L(n) through the train with the stage efficiencies, on the pinion's pitch
circle r = z m_n / (2 cos beta), walked up from the load with each gear getting eta of its pinion's force. `dynamic_factor` (DESIGN section 8: the steady window's max |F_t| over the static F_t at
the simulated load) is then 1 on a steady run.

A defect this pins: the reference was the static force at the nominal load, so the torque drive below, settling
at 1924 rpm against a nominal 1500 rpm, carried 1.65x that force and reported a dynamic factor of 1.65 on a run
whose F_t varied by 1e-7 N; configs/fan_drive.toml (motor operating point 0.35 % above its nominal speed) 1.0069
for 1.00005.
"""

from __future__ import annotations

import json
import math

import pytest
from click.testing import CliRunner

from gearcli.cli import cli
from tests.reference import lossy_train
from tests.reference.lossy_train import pitch_radius_m

STAGES = ((4, 15, 19, 67, 0.96, 0.004, 0.08, 40), (6, 10, 17, 71, 0.97, 0.02, 1.5, 60))  # lossy_train's tuples
TRAIN_TAIL = """[load]
torque_Nm = 500
ramp_s = 0.05
speed_exponent = 2
[simulation]
duration_s = 3.0
steps = 3000
"""
TORQUE = """[input]
drive = "torque"
torque_Nm = 60
speed_rpm = 1500
ramp_s = 0.05
"""
MOTOR = """[input]
drive = "motor"
speed_rpm = 1470
motor = { torque_speed = [[0, 90], [1400, 100], [1450, 70], [1500, 0]] }
"""
RATIO = math.prod(s[3] / s[2] for s in STAGES)
ETA = math.prod(s[4] for s in STAGES)


def _hand_forces(load_Nm: float) -> list[float]:
    """F_t of each stage's pinion in the steady state: walked up from the load, each gear getting eta of its
    pinion's force, so the pinion's force is the gear's torque over eta and the gear's pitch radius."""
    out, torque = [], load_Nm
    for mn, beta, zp, zg, eta, *_ in reversed(STAGES):
        f = torque / (eta * pitch_radius_m(zg, mn, beta))
        out.insert(0, f)
        torque = f * pitch_radius_m(zp, mn, beta)
    return out


def _motor_speed_rpm() -> float:
    """Where the table (1450 rpm, 70 N m; 1500 rpm, 0) meets 500 (n / 1470)^2 / (i eta), bisected."""
    lo, hi = 1450.0, 1500.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        net = 70.0 * (1500.0 - mid) / 50.0 - 500.0 * (mid / 1470.0) ** 2 / (RATIO * ETA)
        lo, hi = (mid, hi) if net > 0.0 else (lo, mid)
    return 0.5 * (lo + hi)


@pytest.mark.parametrize("drive", ["torque", "motor"])
def test_dynamic_factor_refers_to_the_load_at_the_operating_speed(tmp_path, drive):
    if drive == "torque":
        n_in, nominal = 1500.0 * math.sqrt(60.0 * RATIO * ETA / 500.0), 1500.0
    else:
        n_in, nominal = _motor_speed_rpm(), 1470.0
    load = 500.0 * (n_in / nominal) ** 2
    hand = _hand_forces(load)
    path = tmp_path / "scene.toml"
    path.write_text(lossy_train.scene(STAGES, (TORQUE if drive == "torque" else MOTOR) + TRAIN_TAIL))
    res = CliRunner().invoke(cli, ["simulate", str(path), "--format", "json", "-q"])
    assert res.exit_code == 0, res.output
    summary = json.loads(res.stdout)["summary"]
    assert summary["input_speed_rpm"] == pytest.approx(n_in, rel=1e-6)
    for stage, f in zip(summary["stages"], hand, strict=True):
        assert stage["simulated_static_tangential_N"] == pytest.approx(f, rel=1e-6)
        assert stage["tangential_N"]["mean"] == pytest.approx(f, rel=1e-5)
        assert stage["dynamic_factor"] == pytest.approx(1.0, abs=1e-5)
        # the design's static force stays the nominal load's (the contract's static F_t)
        assert stage["static_tangential_N"] == pytest.approx(f * 500.0 / load, rel=1e-9)
