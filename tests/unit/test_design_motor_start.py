"""`gearcli design` warns of a motor drive that cannot start its load (check `motor_cannot_start`), from the curves.

configs/motor_direct_start.toml: a 15 kW motor (rated 1460 rpm, locked-rotor 2.3 and breakdown 2.8 times the rated
torque) on two stages (75/19, 68/19, each 98 % efficient). By hand: T_N = 15 kW / (1460 rpm) = 98.11 N m, the
locked-rotor torque 2.3 T_N = 225.6 N m; the output's load reflected to the motor is T_L / (i eta²). The extended
Kloss curve falls monotonically from its breakdown torque to the locked-rotor torque between the breakdown slip and
standstill (dT/ds has the sign of s_b² - s²), so a constant load below the locked-rotor torque is carried all the way
to the stable branch and one above it cannot be started. A star start gives a third of the curve."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

CONFIG = Path(__file__).resolve().parents[2] / "configs" / "motor_direct_start.toml"
T_RATED = 15e3 / (1460 * 2 * math.pi / 60)
T_LOCKED = 2.3 * T_RATED
TRAIN = 75 / 19 * 68 / 19 * 0.98**2  # ratio times the efficiencies: load torque at the output per N m at the motor


def _design(*sets: str) -> list[dict]:
    res = CliRunner().invoke(cli, ["design", str(CONFIG), "--format", "json", "-q",
                                   *[a for s in sets for a in ("--set", s)]])
    assert res.exit_code == 0, res.output
    return [w for w in json.loads(res.stdout)["warnings"] if w.get("check") == "motor_cannot_start"]


def test_a_load_above_the_locked_rotor_torque_cannot_be_started():
    found = _design(f"load.torque_Nm={1.1 * T_LOCKED * TRAIN!r}")
    assert len(found) == 1
    w = found[0]
    assert w["code"] == "design" and w["stall_speed_rpm"] == 0.0 and w["starting"] == "direct"
    assert_allclose(w["motor_torque_Nm"], T_LOCKED, rtol=1e-9)
    assert_allclose(w["load_torque_Nm"], 1.1 * T_LOCKED, rtol=1e-9)
    assert "cannot start its load" in w["message"] and "standstill" in w["message"]


def test_a_load_below_the_locked_rotor_torque_starts_directly_but_not_in_star():
    load = f"load.torque_Nm={0.5 * T_LOCKED * TRAIN!r}"  # half the locked-rotor torque: above the star's third
    assert not _design(load)
    found = _design(load, 'input.starting="star_delta"', "input.switch_speed_rpm=1300")
    assert len(found) == 1
    w = found[0]
    assert w["stall_speed_rpm"] == 0.0 and w["starting"] == "star_delta"
    assert_allclose(w["motor_torque_Nm"], T_LOCKED / 3, rtol=1e-9)
    assert_allclose(w["load_torque_Nm"], 0.5 * T_LOCKED, rtol=1e-9)


def test_a_fan_load_rising_past_the_curve_stalls_below_the_breakdown_speed():
    # a quadratic load of 8 T_N at the 1460 rpm nominal speed: 0 at rest, so it starts; it reaches the locked-rotor
    # torque 2.3 T_N at 1460 sqrt(2.3/8) = 783 rpm and the breakdown torque 2.8 T_N at 864 rpm, so it meets the curve
    # (between those torques from standstill to its breakdown speed) between 783 and 864 rpm, below the breakdown
    # speed 1500 (1 - s_b) = 993 rpm (s_b = 0.338 of this nameplate's Kloss fit): the unstable branch
    found = _design(f"load.torque_Nm={8 * T_RATED * TRAIN!r}", "load.speed_exponent=2")
    assert len(found) == 1
    w = found[0]
    n = w["stall_speed_rpm"]
    assert 1460 * math.sqrt(2.3 / 8) < n < 1460 * math.sqrt(2.8 / 8) < w["breakdown_speed_rpm"] < 1500
    assert_allclose(w["load_torque_Nm"], 8 * T_RATED * (n / 1460) ** 2, rtol=1e-9)  # the fan law, by hand
    assert_allclose(w["motor_torque_Nm"], w["load_torque_Nm"], rtol=1e-6)  # the crossing
    assert T_LOCKED < w["motor_torque_Nm"] < 2.8 * T_RATED


@pytest.mark.parametrize("sets", [(), ('input.drive="speed"',)])
def test_a_motor_that_carries_its_load_or_a_speed_drive_is_not_warned(sets):
    assert not _design(*sets, f"load.torque_Nm={1.1 * T_LOCKED * TRAIN!r}" if sets else "load.torque_Nm=1300")


def test_a_soft_start_below_the_load_at_standstill_is_warned_from_its_initial_voltage():
    # u0 = 0.5: 0.25 T_lr = 56.4 N m at standstill, below the 1300 N m load's 95.8 N m at the motor (as
    # tests/unit/test_motor_rollback.py's run shows it turning backwards); the full curve carries it
    res = CliRunner().invoke(cli, ["design", str(CONFIG.with_name("motor_soft_start.toml")), "--format", "json", "-q"])
    assert res.exit_code == 0, res.output
    found = [w for w in json.loads(res.stdout)["warnings"] if w.get("check") == "soft_start_rolls_back"]
    assert len(found) == 1
    assert_allclose(found[0]["start_torque_Nm"], 0.25 * T_LOCKED, rtol=1e-9)
    assert_allclose(found[0]["load_torque_Nm"], 1300 / TRAIN, rtol=1e-9)
    assert "sqrt" not in found[0]["message"]
    assert f"({math.sqrt(1300 / TRAIN / T_LOCKED):.3g} starts it forward at once)" in found[0]["message"]  # sqrt(T_L / T_lr)


def test_the_stall_speed_is_where_simulate_finds_the_motor_settling():
    # simulate's own operating point (gearcli.simulate.motor, brentq on the same curves) stops at the same crossing
    from gearcli import api
    from gearcli.model.assembly import Layout
    from gearcli.simulate.motor import operating_point

    sets = [f"load.torque_Nm={8 * T_RATED * TRAIN!r}", "load.speed_exponent=2"]
    loaded, design = api.load_and_design(str(CONFIG), sets)
    op = operating_point(Layout.of(api.model_spec(loaded.design, design)))
    assert op.speed_rad_s is not None and not op.reaches
    (w,) = _design(*sets)
    assert_allclose(w["stall_speed_rpm"], op.speed_rad_s * 60 / (2 * math.pi), rtol=1e-9)


def _mismatch(*sets: str) -> list[dict]:
    res = CliRunner().invoke(cli, ["design", str(CONFIG), "--format", "json", "-q",
                                   *[a for s in sets for a in ("--set", s)]])
    assert res.exit_code == 0, res.output
    return [w for w in json.loads(res.stdout)["warnings"] if w.get("check") == "motor_speed_mismatch"]


def test_a_speed_rpm_off_the_motors_operating_point_is_warned_before_any_run():
    # the rated torque at the motor (T_N x the train at the output): the nameplate's curve carries it at its rated
    # 1460 rpm, so a design at speed_rpm = 1300 has every speed, mesh frequency and K_v 11 % low
    rated = f"load.torque_Nm={T_RATED * TRAIN!r}"
    (w,) = _mismatch(rated, "input.speed_rpm=1300")
    assert w["code"] == "design" and w["speed_rpm"] == 1300.0
    assert_allclose(w["operating_speed_rpm"], 1460.0, rtol=1e-6)
    assert "runs at 1460 rpm" in w["message"]
    assert not _mismatch(rated)  # speed_rpm where the curve carries the load
    assert not _mismatch(rated, "input.speed_rpm=1440")  # within 2 %


@pytest.mark.parametrize(("start_Nm", "rolls"), [(85.0, True), (92.0, False)])
def test_a_soft_start_held_by_the_train_s_losses_is_not_said_to_roll_back(start_Nm, rolls):
    """The load turns the train backwards only where it overcomes the motor through the train with the power flowing
    back: 1300 N m eta² / i = 88.36 N m at the motor; to start forward the motor needs 1300 / (i eta²) = 95.80 N m.
    Between the two the losses hold the train at rest until the voltage rises (a soft start at 92 N m was warned as
    rolling back; simulate shows it standing, no motor_rolls_back)."""
    back, forward = 1300 * TRAIN / (75 / 19 * 68 / 19) ** 2, 1300 / TRAIN
    assert back < 88.5 < 95.7 < forward and (start_Nm < back) is rolls
    u0 = math.sqrt(start_Nm / T_LOCKED)
    res = CliRunner().invoke(cli, ["design", str(CONFIG.with_name("motor_soft_start.toml")), "--format", "json", "-q",
                                   "--set", f"input.initial_voltage_fraction={u0!r}"])
    assert res.exit_code == 0, res.output
    found = [w for w in json.loads(res.stdout)["warnings"] if w.get("check") == "soft_start_rolls_back"]
    assert bool(found) is rolls
    if rolls:
        assert_allclose(found[0]["start_torque_Nm"], start_Nm, rtol=1e-9)
        assert_allclose(found[0]["back_driving_torque_Nm"], back, rtol=1e-9)
        assert_allclose(found[0]["load_torque_Nm"], forward, rtol=1e-9)


def test_a_load_table_s_breakaway_above_the_locked_rotor_torque_cannot_be_started():
    """A `torque_speed` load table's first point is its torque at standstill, the breakaway a start must exceed. By
    hand: a breakaway of 1.1 T_lr at the motor (T_lr i eta² at the output) falling to 0.3 T_lr at 5 rpm of the output,
    a Stribeck drop: it holds the train, the direct start's 225.6 N m short of 248.2 N m. The model's table turns with
    the rotation (tanh over 0.5 % of the nominal output speed, 0 at rest), and the drop within a few of those widths
    lowered the regularised peak below the locked-rotor torque: no warning was given (the run starts in 0.3 s). At
    0.9 T_lr the motor breaks the load away and nothing is warned."""
    for share, warned in ((1.1, True), (0.9, False)):
        table = [[0, share * T_LOCKED * TRAIN], [5, 0.3 * T_LOCKED * TRAIN], [60, 0.35 * T_LOCKED * TRAIN]]
        found = _design(f"load.torque_speed={table!r}")
        assert bool(found) == warned, found
        if warned:
            w = found[0]
            assert w["stall_speed_rpm"] == 0.0 and "breakaway" in w["message"]
            assert_allclose(w["motor_torque_Nm"], T_LOCKED, rtol=1e-9)
            assert_allclose(w["load_torque_Nm"], share * T_LOCKED, rtol=1e-9)
