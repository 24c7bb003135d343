"""A VFD on a `torque_speed` table meeting a fan load off `speed_rpm`: `motor_speed_mismatch` says why it runs
there (the table has no rated point to set the supply by: it runs at its own synchronous speed, docs/motors.md),
not the nameplate converter's "supply set for the rated torque" (tr27e's trial: a table VFD fan 1.5 % off
speed_rpm was told its supply puts the rated torque at speed_rpm, which a table has not).

configs/motor_direct_start.toml (two stages 75/19, 68/19, each 98 % efficient, speed_rpm 1460) with the table
[[0, 200], [1200, 260], [1400, 150], [1490, 0], [1550, -120]] on a VFD: its synchronous speed is 1490 rpm. A fan
load of L = 20 N m at the motor at 1460 rpm, reflected T = L (n / 1460)^2, meets the segment 1400-1490 rpm,
T = 150 (1490 - n) / 90, where 20 (n/1460)^2 + (150/90) n - 1490 (150/90) = 0 (a quadratic by hand); there the
load is (n / 1460)^2 of the design's (above the 1 % the warning allows)."""

from __future__ import annotations

import json
import math
from pathlib import Path

from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

CONFIG = Path(__file__).resolve().parents[2] / "configs" / "motor_direct_start.toml"
TRAIN = 75 / 19 * 68 / 19 * 0.98**2  # output torque per N m at the motor, losses included
TABLE = "input.motor={torque_speed=[[0,200],[1200,260],[1400,150],[1490,0],[1550,-120]]}"
L_MOTOR = 20.0  # the fan's torque at the motor at speed_rpm


def _hand_crossing_rpm() -> float:
    a, b, c = L_MOTOR / 1460.0**2, 150.0 / 90.0, -1490.0 * 150.0 / 90.0
    return (-b + math.sqrt(b * b - 4 * a * c)) / (2 * a)


def _mismatch(command: str) -> dict:
    sets = [TABLE, 'input.starting="vfd"', "input.ramp_s=0.3", "load.speed_exponent=2",
            f"load.torque_Nm={L_MOTOR * TRAIN!r}"]
    if command == "simulate":
        sets += ["simulation.duration_s=0.6", "simulation.window_start_s=0.5", "simulation.steps=600"]
    res = CliRunner().invoke(cli, [command, str(CONFIG), "--format", "json", "-q",
                                   *[a for s in sets for a in ("--set", s)]])
    assert res.exit_code == 0, res.output
    (w,) = [w for w in json.loads(res.stdout)["warnings"]
            if "motor_speed_mismatch" in (w["code"], w.get("check"))]
    return w


def _check(w: dict) -> None:
    n = _hand_crossing_rpm()
    assert 1400.0 < n < 1490.0 and (n / 1460.0) ** 2 > 1.01  # on the segment, and past the warning's 1 %
    assert_allclose(w["operating_speed_rpm"], n, rtol=1e-6)
    assert_allclose(w["load_ratio"], (n / 1460.0) ** 2, rtol=1e-5)
    assert "torque_speed table runs at its own synchronous speed" in w["message"]
    assert "rated torque" not in w["message"]  # a table has no rated point


def test_design_says_a_table_vfd_runs_at_its_own_synchronous_speed():
    _check(_mismatch("design"))


def test_simulate_says_a_table_vfd_runs_at_its_own_synchronous_speed():
    _check(_mismatch("simulate"))
