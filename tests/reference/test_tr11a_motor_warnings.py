"""Motor warnings that must be true and actionable (tr11a). A VFD whose torque limit is below the load cannot
start however slowly its supply ramps: the stall warning names the limit, and the ramp warning ("lengthen
ramp_s") is not given beside it, where it said the ramp outran the motor because the load had turned the stalled
motor backwards. A start that rolls back and then runs up before the statistics window says so, where it said
the run's numbers were no forward operating point."""

from __future__ import annotations

import json
import math

import pytest
from click.testing import CliRunner
from scipy.optimize import brentq, fsolve

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


def _run(tmp_path, *sets: str) -> dict:
    (tmp_path / "vfd.toml").write_text(SCENE)
    overrides = [arg for s in sets for arg in ("--set", s)]
    res = CliRunner().invoke(cli, ["-q", "simulate", str(tmp_path / "vfd.toml"), "--format", "json", *overrides])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def _warnings(tmp_path, *sets: str) -> list[dict]:
    return _run(tmp_path, *sets)["warnings"]


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


def _kloss_slip_speed_rpm(torque_Nm: float) -> float:
    """The nameplate's extended Kloss curve (15 kW, 1460/1500 rpm, k_b 2.8, k_l 2.3) solved by hand: s_b and a
    from the rated and locked-rotor points, then the slip speed (rpm, constant V/f: the curve's shape in slip
    speed) where it gives ``torque_Nm`` on its stable branch."""
    t_r = 15e3 / (1460 * math.pi / 30)

    def kloss(s, sb, a):
        return 2 * 2.8 * t_r * (1 + a * sb) * s * sb / (s * s + sb * sb + 2 * a * sb * sb * abs(s))

    sb, a = fsolve(lambda x: [kloss(1 - 1460 / 1500, *x) / t_r - 1, kloss(1.0, *x) / t_r - 2.3], [0.1, 0.5])
    return 1500 * brentq(lambda s: kloss(s, sb, a) - torque_Nm, 1e-9, sb)


def test_a_vfd_start_that_rolls_back_then_runs_up_says_its_window_is_an_operating_point(tmp_path):
    # a VFD set to 1000 rpm: its supply starts at 0 Hz (no torque at standstill), the 300 N m load turns the train
    # back until the supply's frequency gives 75.9 N m; then it runs up to the rated slip speed above 1000 rpm
    doc = _run(tmp_path, "input.ramp_s=0.5", "input.speed_rpm=1000")
    back = [w for w in doc["warnings"] if w["code"] == "motor_rolls_back"]
    assert len(back) == 1 and back[0]["start_torque_Nm"] == 0.0
    window = doc["summary"]["window_s"]
    assert doc["summary"]["start_time_s"] < window[0]
    assert "no forward operating point" not in back[0]["message"]
    assert f"({window[0]:.4g} s on)" in back[0]["message"]
    assert "initial_voltage_fraction" not in back[0]["message"]  # a soft start's cure, not a VFD's
    # and the window is the operating point: the supply 1000 + 40 rpm (the rated slip speed) less the slip speed
    # of 75.9 N m on the same curve
    by_hand = 1000 + (1500 - 1460) - _kloss_slip_speed_rpm(LOAD_AT_MOTOR)
    assert doc["summary"]["motor"]["operating_speed_rpm"] == pytest.approx(by_hand, rel=1e-7)


def test_a_soft_start_still_rolling_back_into_the_window_is_no_operating_point(tmp_path):
    # u0 = 0.3: 0.09 x 2.3 x 98.1 N m = 20.3 N m at standstill against 75.9 N m; the window from 0.3 s, before the
    # 1 s voltage ramp has lifted the torque: the motor still turns backwards there
    doc = _run(tmp_path, 'input.starting="soft_start"', "input.voltage_ramp_s=1.0",
               "input.initial_voltage_fraction=0.3", "simulation.window_start_s=0.3")
    back = [w for w in doc["warnings"] if w["code"] == "motor_rolls_back"]
    assert len(back) == 1
    assert back[0]["start_torque_Nm"] == pytest.approx(0.09 * 2.3 * 15e3 / (1460 * math.pi / 30), rel=1e-9)
    assert "no forward operating point" in back[0]["message"]
    assert "initial_voltage_fraction" in back[0]["message"]


@pytest.mark.parametrize(("speed_rpm", "table", "warned"), [
    (1000.0, False, True),    # DOL at its curve's 1471.18 rpm: 47 % off, the design's speeds all at 1000 rpm
    (1460.0, False, False),   # the nameplate's rated speed: 0.8 % off at 77 % of the rated torque
    (1000.0, True, True),     # a VFD with a table motor: its supply does not follow speed_rpm
])
def test_a_motor_running_off_speed_rpm_is_warned_whatever_its_load(tmp_path, speed_rpm, table, warned):
    sets = [f"input.speed_rpm={speed_rpm}"]
    if table:  # the table's last segment (1450, 120)-(1500, 0) meets 75.9 N m at 1500 - 75.9 x 50 / 120 rpm
        sets += ["input.motor={torque_speed=[[0,200],[1000,180],[1300,260],[1450,120],[1500,0]]}", "input.ramp_s=0.5"]
        by_hand = 1500 - LOAD_AT_MOTOR * 50 / 120
    else:
        sets += ['input.starting="direct"']
        by_hand = 1500 - _kloss_slip_speed_rpm(LOAD_AT_MOTOR)
    doc = _run(tmp_path, *sets)
    assert doc["summary"]["motor"]["operating_point_rpm"] == pytest.approx(by_hand, rel=1e-8)
    found = [w for w in doc["warnings"] if w["code"] == "motor_speed_mismatch"]
    assert (abs(by_hand / speed_rpm - 1) > 0.02) is warned
    assert len(found) == (1 if warned else 0), found
    if warned:
        assert found[0]["operating_speed_rpm"] == pytest.approx(by_hand, rel=1e-8)
        assert found[0]["speed_rpm"] == pytest.approx(speed_rpm)
        assert found[0]["load_ratio"] == 1.0  # a constant load: the forces agree, the speeds do not
        assert ("torque_speed table" in found[0]["message"]) is table
    # the run turns at the motor's own speed, not at speed_rpm (the window's mean holds the start's tail: 1e-3)
    assert doc["summary"]["output_speed_rpm"] == pytest.approx(by_hand * 21 / 83, rel=1e-3)


def test_a_motor_stalled_in_star_is_not_also_told_to_move_its_window(tmp_path):
    # star: a third of the locked-rotor torque, 2.3 x 98.11 / 3 = 75.22 N m, against 75.90 N m: it cannot start, and
    # the load turns the train backwards; "it would be settled from about 0.575 s (simulation.window_start_s)" was
    # given beside the stall, but no window of this run is an operating point
    t_star = 2.3 * 15e3 / (1460 * math.pi / 30) / 3
    assert t_star < LOAD_AT_MOTOR
    doc = _run(tmp_path, 'input.starting="star_delta"', "input.switch_speed_rpm=1300", "simulation.duration_s=2.0")
    codes = [w["code"] for w in doc["warnings"]]
    stall = next(w for w in doc["warnings"] if w["code"] == "motor_stalls")
    assert f"{t_star:.4g} N·m" in stall["message"]
    assert "window_not_settled" not in codes, doc["warnings"]
    assert doc["summary"]["motor"]["operating_speed_rpm"] < 0.0  # driven backwards: no forward operating point
