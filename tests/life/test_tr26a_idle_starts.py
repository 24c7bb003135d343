"""An idle duty point's starts: each start class is rated at its own load, not given a stress of 0.

The defect: a point of zero torque (a conveyor run empty) has no static tooth force, and a class's stress was its
rating scaled by the class's force over the static force, so every class of its start from rest (the DOL motor
accelerating the empty belt's inertia: peaks of several kN) stood at 0 MPa with no damage, a silent 0 where
docs/life.md ("Starts") rates each class at its own load, as `gearcli design` rates the stage at the class's torque.
Now such a point's classes above ISO 6336's 1 N/mm floor are rated from the point's design at a reference load, every
load-dependent factor at the class's own force; its window's round-off (no load) stays at 0.

Reference (by hand): the class's torque from its force, T_out = F_t d_1 / 2 u eta (d_1 = z_1 m_n / cos beta, u =
z_2 / z_1); `gearcli design` at that torque (K_A = 1, K_v = 1) gives F_t back and the class's sigma_H, sigma_F.
"""

from __future__ import annotations

import json
import math

from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli
from tests.life.tr26a_scene import BETA, ETA, M_N, N_RATED, Z1, Z2, scene

STARTS = 20000

SCENE = scene("a DOL conveyor drive started empty 20000 times", "torque_Nm = 300", 1.0, f"""
[[duty]]
name = "empty"
hours = 1000
torque_Nm = 0
speed_rpm = {N_RATED}
starts = {STARTS}""")


def _run(tmp_path, *args: str) -> dict:
    path = tmp_path / "empty.toml"
    path.write_text(SCENE, encoding="utf-8")
    res = CliRunner().invoke(cli, [*args[:1], str(path), *args[1:], "--format", "json"])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def test_an_idle_points_start_classes_are_rated_at_their_own_load(tmp_path) -> None:
    life = _run(tmp_path, "life")["life"]
    start = life["points"][0]["start"]
    assert start["damage"][0]["pinion"]["pitting"] > 0.0  # was 0: every class at 0 MPa
    pitting = {b["force_N"]: b for b in life["stages"][0]["pinion"]["pitting"]["bins"] if b["point"] == "empty (start)"}
    bending = {b["force_N"]: b for b in life["stages"][0]["pinion"]["bending"]["bins"] if b["point"] == "empty (start)"}
    top = max(pitting)
    assert top > 20 * 55.0  # a start peak far above the 1 N/mm floor (55 mm face): a real load
    d1 = Z1 * M_N / math.cos(math.radians(BETA))
    for force in (top, sorted(pitting)[len(pitting) // 2]):
        torque = force * d1 / 2000.0 * (Z2 / Z1) * ETA  # the class's output torque, N m
        rated = _run(tmp_path, "design", "--set", f"load.torque_Nm={torque!r}", "--set", "rating.dynamic_factor=1")
        st = rated["stages"][0]
        assert_allclose(st["static_force_N"]["tangential"], force, rtol=1e-9)
        assert_allclose(pitting[force]["stress_MPa"], st["rating"]["pinion"]["sigma_H_MPa"], rtol=1e-9)
        assert_allclose(bending[force]["stress_MPa"], st["rating"]["pinion"]["sigma_F_MPa"], rtol=1e-9)
    window = [b for b in life["stages"][0]["pinion"]["pitting"]["bins"] if b["point"] == "empty"]
    assert all(b["stress_MPa"] == 0.0 and b["damage"] == 0.0 for b in window)  # the idle window: no load, no damage
