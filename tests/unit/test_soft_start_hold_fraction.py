"""The soft start's roll-back warning (`design`, check `soft_start_rolls_back`) names the initial voltage that cures
it, and no false end of the roll-back.

configs/motor_soft_start.toml: a 15 kW motor (T_N = 15 kW / 1460 rpm = 98.11 N m, locked rotor 2.3 T_N = 225.6 N m)
soft-started at u0 = 0.5 (u² of the locked-rotor torque at standstill: 56.4 N m) on two stages 75/19 and 68/19, each
98 % efficient, against 1300 N m. By hand, at the motor: the load turns the train back with 1300 eta² / i = 88.38 N m
(the losses hold against it), and starts forward with 1300 / (i eta²) = 95.81 N m. So an initial voltage fraction of
sqrt(88.38 / 225.6) = 0.626 holds the train at rest, and 0.652 starts it forward at once. The warning said the
train turns backwards "until the voltage has risen to 0.652 of full": once it turns backwards the motor runs at a
slip above 1, where the Kloss curve 2 T_b / (s / s_b + s_b / s) falls below its standstill value, so the roll-back
runs on well past that voltage (the run: still -700 rpm at u = 0.70, forward again only at u = 0.84). The warning now
says what holds it, and following that clears it."""

from __future__ import annotations

import json
import math
from pathlib import Path

from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

CONFIG = Path(__file__).resolve().parents[2] / "configs" / "motor_soft_start.toml"
T_LOCKED = 2.3 * 15e3 / (1460 * 2 * math.pi / 60)
RATIO = 75 / 19 * 68 / 19
BACK = 1300 * 0.98**2 / RATIO  # the load turning the train backwards, at the motor
FORWARD = 1300 / (RATIO * 0.98**2)  # the load to start forward, at the motor
U_HOLD = math.sqrt(BACK / T_LOCKED)  # u0² T_lr = BACK
U_FORWARD = math.sqrt(FORWARD / T_LOCKED)


def _warned(*sets: str) -> list[dict]:
    res = CliRunner().invoke(cli, ["design", str(CONFIG), "--format", "json", "-q",
                                   *[a for s in sets for a in ("--set", s)]])
    assert res.exit_code == 0, res.output
    return [w for w in json.loads(res.stdout)["warnings"] if w.get("check") == "soft_start_rolls_back"]


def test_the_warning_names_the_initial_voltage_that_holds_the_train_and_following_it_clears_it():
    assert 0.625 < U_HOLD < 0.627 and 0.651 < U_FORWARD < 0.653
    (w,) = _warned()
    assert_allclose(w["back_driving_torque_Nm"], BACK, rtol=1e-9)
    assert f"initial_voltage_fraction of at least {U_HOLD:.3g} holds the train at rest" in w["message"]
    assert f"({U_FORWARD:.3g} starts it forward at once)" in w["message"]
    assert "until the voltage has risen to" not in w["message"]  # the run turns back well past it (module text)
    assert _warned(f"input.initial_voltage_fraction={0.998 * U_HOLD!r}")
    assert not _warned(f"input.initial_voltage_fraction={1.002 * U_HOLD!r}")


def test_the_kloss_curve_past_standstill_is_below_its_locked_rotor_torque():
    # why the roll-back outlasts the standstill balance: the simple Kloss curve of this nameplate (T_b = 2.8 T_N, the
    # breakdown slip s_b where it gives 2.3 T_N at s = 1) is lower at every slip beyond 1, i.e. turning backwards
    t_b = 2.8 / 2.3 * T_LOCKED
    s_b = (t_b / T_LOCKED) - math.sqrt((t_b / T_LOCKED) ** 2 - 1.0)  # 2 t_b / (1/s_b + s_b) = T_lr, root below 1
    assert_allclose(2 * t_b / (1 / s_b + s_b), T_LOCKED, rtol=1e-12)
    for s in (1.1, 1.47, 2.0):  # 1.47: -700 rpm on 1500 rpm synchronous
        assert 2 * t_b / (s / s_b + s_b / s) < T_LOCKED


def test_the_run_turns_back_past_the_forward_voltage_and_names_the_holding_one():
    # the simulation: the motor still runs backwards when the ramp u = 0.5 + 0.5 t / 0.8 passes U_FORWARD (t = 0.24 s),
    # which the old design message gave as the roll-back's end; simulate's motor_rolls_back names U_HOLD as the cure
    res = CliRunner().invoke(cli, ["simulate", str(CONFIG), "--set", "simulation.error_estimate=false", "--series",
                                   "--format", "json", "-q"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    t_forward = (U_FORWARD - 0.5) / 0.5 * 0.8
    t, w = doc["series"]["time_s"], doc["series"]["motor_speed_rpm"]
    i = min(range(len(t)), key=lambda k: abs(t[k] - t_forward))
    assert w[i] < -100.0  # rpm: well into the roll-back
    (warn,) = [x for x in doc["warnings"] if x["code"] == "motor_rolls_back"]
    assert f"an initial_voltage_fraction of at least {U_HOLD:.3g}" in warn["message"]
