"""A VFD whose torque limit is below the load cannot start however slowly its supply ramps (tr11a): the stall
warning names the limit, and the ramp warning ("lengthen ramp_s") is not given beside it, where it said the
ramp outran the motor because the load had turned the stalled motor backwards."""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

from gearcli.cli import cli

# a 15 kW four-pole motor, rotor 0.09 kg m² on a coupling, one stage 21/83, 300 N m on a drum on its coupling
SCENE = """
input = { speed_rpm = 1460, drive = "motor", starting = "vfd", inertia_kg_m2 = 0.09, coupling_stiffness_Nm_rad = 2.0e4, coupling_damping_Nms_rad = 5, motor = { rated_power_kW = 15, rated_speed_rpm = 1460, synchronous_speed_rpm = 1500, breakdown_torque_ratio = 2.8, locked_rotor_torque_ratio = 2.3 } }
load = { torque_Nm = 300, inertia_kg_m2 = 2.0, coupling_stiffness_Nm_rad = 5e4, coupling_damping_Nms_rad = 20 }
simulation = { duration_s = 1.0 }
[[stage]]
normal_module_mm = 3
helix_angle_deg = 15
pinion = { teeth = 21, face_width_mm = 40, hand = "left" }
gear = { teeth = 83, face_width_mm = 38, hand = "right" }
"""
LOAD_AT_MOTOR = 300.0 * 21 / 83  # N m, lossless: 75.90


def _warnings(tmp_path, *sets: str) -> list[dict]:
    (tmp_path / "vfd.toml").write_text(SCENE)
    overrides = [arg for s in sets for arg in ("--set", s)]
    res = CliRunner().invoke(cli, ["-q", "simulate", str(tmp_path / "vfd.toml"), "--format", "json", *overrides])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)["warnings"]


@pytest.mark.parametrize("ramp_s", [0.3, 5.0])
def test_a_torque_limit_below_the_load_is_a_stall_not_a_ramp_too_fast(tmp_path, ramp_s):
    limit = 70.0
    assert limit < LOAD_AT_MOTOR
    found = _warnings(tmp_path, f"input.ramp_s={ramp_s}", f"input.torque_limit_Nm={limit}")
    codes = [w["code"] for w in found]
    assert "motor_stalls" in codes
    stall = next(w for w in found if w["code"] == "motor_stalls")
    assert f"torque_limit_Nm {limit:.4g}" in stall["message"]
    assert f"({LOAD_AT_MOTOR:.4g} N·m)" in stall["message"]
    assert "ramp_over_breakdown" not in codes, found


def test_a_limit_above_the_load_starts_and_is_not_warned(tmp_path):
    # 200 N m > 75.9 N m: the motor runs up on a 0.3 s ramp (its breakdown slip speed s_b n_s ~ 500 rpm is never
    # exceeded by the 0.09 + 0.14 kg m² train, 1500 rpm in 0.3 s needing ~120 N m of acceleration torque on average)
    found = _warnings(tmp_path, "input.ramp_s=0.3", "input.torque_limit_Nm=200")
    assert not {"motor_stalls", "ramp_over_breakdown"} & {w["code"] for w in found}, found
