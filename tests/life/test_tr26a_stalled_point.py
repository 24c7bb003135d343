"""A duty point whose motor cannot drive its load: `gearcli life` says so, not "lengthen simulation.duration_s".

The defect: a DOL motor whose curve stays below a point's load at every speed stalls (the load holds the train
almost at rest), so the point's steady window holds no whole mesh cycle. `gearcli life` stopped with exit 2 naming
`simulation.duration_s`, "the steady window holds no whole mesh cycle ...; lengthen simulation.duration_s": a wrong
reason and a wrong remedy (a longer run only counts the stalled motor's creep, at the point's speed_rpm), where
`design` (`motor_cannot_start`) and `simulate` (`motor_stalls`) name the motor. The life of such a point cannot be
computed, and the refusal now says why: the motor stalls, with `simulate`'s words and numbers.

Reference (by hand): the extended Kloss curve's largest torque is its breakdown torque T_b = k_b T_r,
T_r = P_r / (2 pi n_r / 60) (docs/physics.md, "Induction motor"); the point's table load (scaled to the point's
torque at its nominal output speed, docs/life.md) at standstill, reflected to the motor forward through the stage,
T_L(0) / (i eta), exceeds T_b: no speed at which the motor carries the load.
"""

from __future__ import annotations

import math

from click.testing import CliRunner

from gearcli.cli import cli
from tests.life.tr26a_scene import ETA, K_B, N_RATED, P_KW, Z1, Z2, scene

TABLE = [[0.0, 1200.0], [0.01, 1300.0], [349.125, 1300.0]]  # output rpm, N m: a breakaway load, flat when moving
T_POINT = 2600.0  # N m at the point's nominal output speed 1470 * 19/80 = 349.125 rpm: the table times 2

SCENE = scene("a DOL motor that cannot drive its conveyor's breakaway load", f"torque_speed = {TABLE}", 0.3, f"""
[[duty]]
name = "jammed"
hours = 100
speed_rpm = {N_RATED}
torque_Nm = {T_POINT}  # the table scaled by 2: 2400 N m at standstill""")


def test_the_scene_is_a_stall_by_hand() -> None:
    rated_Nm = P_KW * 1e3 / (2.0 * math.pi * N_RATED / 60.0)
    breakdown_Nm = K_B * rated_Nm  # the curve's largest torque: 272.8 N m
    scale = T_POINT / TABLE[-1][1]  # the table at the nominal output speed 349.125 rpm is its last torque
    reflected_Nm = scale * TABLE[0][1] / (Z2 / Z1) / ETA  # 581.6 N m at standstill
    assert reflected_Nm > 2.0 * breakdown_Nm


def test_a_point_whose_motor_stalls_is_refused_naming_the_stall(tmp_path) -> None:
    path = tmp_path / "jammed.toml"
    path.write_text(SCENE, encoding="utf-8")
    out = tmp_path / "life.json"
    res = CliRunner().invoke(cli, ["life", str(path), "--format", "json", "-o", str(out)])
    assert res.exit_code == 2, res.output
    assert "Traceback" not in res.output
    message = res.output
    assert "duty[0] (jammed)" in message
    assert "cannot carry the load" in message and "stalls at" in message  # simulate's motor_stalls, its speed
    assert "lengthen simulation.duration_s" not in message  # the wrong remedy
    assert "simulation.duration_s:" not in message  # nor blamed on the run's duration
    assert not out.exists()  # a failed run leaves no output
