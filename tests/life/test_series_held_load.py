"""A history's torque held at standstill (zero speed, nonzero torque: a brake or a stalled drive holding the load)
reaches the bearings' ISO 76 static safety s_0 (it was dropped with the idle rows, so a 6000 N·m hold beside a
2400 N·m duty left s_0 at the 2400 N·m figure); it adds no revolutions, no load cycles and no damage.

By hand, the rated scene made spur (helix 0, no profile shift, so alpha_wt = 20 deg): the gear (z = 60, m = 4 mm,
d = 240 mm) sits at 70 mm between shaft 2's bearings at 0 and 200 mm; at an output torque T it carries
F = 2 T / d / cos 20 deg, a simply supported shaft: R_1 = F (200 - 70) / 200, R_2 = F 70 / 200; no axial force, so
ISO 76's P_0 = F_r and s_0 = C_0 / P_0.
"""

from __future__ import annotations

import json
import math

import pytest
from click.testing import CliRunner

from gearcli.cli import cli
from tests.life.scenes import RATED

C0_KN = 200.0
SPUR = (RATED.replace("helix_angle_deg = 15", "helix_angle_deg = 0")
        .replace('hand = "left"', 'hand = "spur"').replace('hand = "right"', 'hand = "spur"')
        .replace('kind = "roller"', f'kind = "roller"\nstatic_load_rating_kN = {C0_KN}'))


def s0_by_hand(torque_Nm: float) -> list[float]:
    f = 2 * torque_Nm * 1e3 / 240.0 / math.cos(math.radians(20.0))
    return [C0_KN * 1e3 / (f * 130 / 200), C0_KN * 1e3 / (f * 70 / 200)]


def life(tmp_path, history: str) -> dict:
    design, series = tmp_path / "rated.toml", tmp_path / "history.csv"
    design.write_text(SPUR, encoding="utf-8")
    series.write_text(history, encoding="utf-8")
    res = CliRunner().invoke(cli, ["life", str(design), "--static", "--series", str(series), "--format", "json"])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def shaft2_s0(doc: dict) -> list[float]:
    return [b["static_safety"] for b in doc["life"]["bearings"] if b["shaft"] == 2]


@pytest.mark.parametrize("held", [6000.0, -6000.0])
def test_a_held_torque_sets_the_static_safety(tmp_path, held):
    # 10 h at 2400 N·m and 1500 rpm, then 10 min held at 6000 N·m (either sign) at standstill
    turning = life(tmp_path, "time_s,torque_Nm,speed_rpm\n0,2400,1500\n36000,0,0\n36600,0,0\n")
    with_hold = life(tmp_path, f"time_s,torque_Nm,speed_rpm\n0,2400,1500\n36000,{held},0\n36600,0,0\n")
    assert shaft2_s0(turning) == pytest.approx(s0_by_hand(2400.0), rel=1e-9)
    assert shaft2_s0(with_hold) == pytest.approx(s0_by_hand(6000.0), rel=1e-9)  # 2.5x the load: s_0 / 2.5
    # no revolutions and no damage: the bearings' L10 and every member's damage are the turning duty's
    for a, b in zip(turning["life"]["bearings"], with_hold["life"]["bearings"], strict=True):
        assert b["L10_Mrev"] == pytest.approx(a["L10_Mrev"], rel=1e-12)
        assert b["revolutions"] == pytest.approx(a["revolutions"], rel=1e-12)
    assert with_hold["life"]["stages"] == turning["life"]["stages"]
    assert with_hold["life"]["hours"] == turning["life"]["hours"] == pytest.approx(10.0, rel=1e-12)
    held_notes = [w for w in with_hold["warnings"] if "held at standstill" in w["message"]]
    assert len(held_notes) == 1 and f"{held:g} N·m" in held_notes[0]["message"]
    assert not [w for w in turning["warnings"] if "held at standstill" in w["message"]]


def test_idle_rows_without_torque_add_nothing(tmp_path):
    idle = life(tmp_path, "time_s,torque_Nm,speed_rpm\n0,2400,1500\n36000,0,0\n36600,0,0\n")
    assert shaft2_s0(idle) == pytest.approx(s0_by_hand(2400.0), rel=1e-9)
