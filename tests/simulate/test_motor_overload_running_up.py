"""`motor_overloaded` judges the torque the motor carries in steady operation, not the torque that still runs the
train up in the window (docs/motors.md). A window that begins after the start's 98 % time (the start counts as
settled) while the train still accelerates carries the acceleration torque on top of the load: a DOL start whose
load is 1.03x the motor's rating at the motor read a window mean of 1.065x and was warned as overloaded (tr27e's
trial); one at 1.10x was said to carry 1.119x.

configs/motor_direct_start.toml (a 15 kW motor, rated 1460 rpm: T_N = 15 kW / 152.89 rad/s = 98.11 N·m; two
stages 75/19 and 68/19, each 98 % efficient) with a 25 kg m² driven machine on a stiff coupling. By hand the load
the motor carries in steady operation is T_L / (i eta²), whatever the inertias and however far the window is
from the start; the product's figure must be that (summed with the rigid mode's weights the bodies' equations give
mean motor torque - reflected load = the change of the train's reflected momentum over the window's length)."""

from __future__ import annotations

import json
import math
from pathlib import Path

from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

CONFIG = Path(__file__).resolve().parents[2] / "configs" / "motor_direct_start.toml"
T_RATED = 15e3 / (1460 * 2 * math.pi / 60)
TRAIN = 75 / 19 * 68 / 19 * 0.98**2  # output torque per N m at the motor, losses included


def _run(load_ratio: float, window_start_s: float) -> dict:
    sets = [f"load.torque_Nm={load_ratio * T_RATED * TRAIN!r}", "load.inertia_kg_m2=25",
            "load.coupling_stiffness_Nm_rad=2e6", "load.coupling_damping_Nms_rad=2000",
            f"simulation.window_start_s={window_start_s!r}", f"simulation.duration_s={window_start_s + 0.1!r}",
            "simulation.steps=1000"]
    res = CliRunner().invoke(cli, ["simulate", str(CONFIG), "--format", "json", "-q",
                                   *[a for s in sets for a in ("--set", s)]])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def _overloaded(doc: dict) -> list[dict]:
    return [w for w in doc["warnings"] if w["code"] == "motor_overloaded"]


def test_a_window_still_running_up_is_not_read_as_an_overload():
    doc = _run(1.03, 0.25)
    s = doc["summary"]
    assert s["start_time_s"] < 0.25  # the start reached 98 % before the window: judged on the window's torque
    assert s["motor"]["mean_torque_Nm"] > 1.05 * T_RATED  # which still carries the run-up's acceleration
    assert not _overloaded(doc)  # the load it carries, 1.03 T_N, is within the 5 % margin


def test_an_overload_is_the_load_the_motor_carries():
    doc = _run(1.10, 0.27)
    assert doc["summary"]["start_time_s"] < 0.27
    (w,) = _overloaded(doc)
    assert_allclose(w["torque_Nm"], 1.10 * T_RATED, rtol=1e-5)  # T_L / (i eta²) by hand
    assert_allclose(w["overload_ratio"], 1.10, rtol=1e-5)
    assert_allclose(w["rated_torque_Nm"], T_RATED, rtol=1e-12)
