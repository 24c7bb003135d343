"""A torque drive whose torque the load does not balance at the nominal speed is said (design check
``torque_drive_balance``), with where the train goes, checked by hand and against the simulated train.

Scene: one spur stage 20/40 (ratio u = 2, lossless), a torque drive, a fan-type load T_L (n / n_0)^2 with
T_L = 100 N·m at the nominal output speed (n_0 = 1500 rpm at the input). The load needs T_req = T_L / u = 50 N·m
at the input. With T_in = 60 N·m the rigid train settles where T_in = T_req (n / n_0)^2:
n* = 1500 √(60 / 50) = 1643.17 rpm. With a constant load (p = 0) nothing balances it: it accelerates.
"""

from __future__ import annotations

import math

from numpy.testing import assert_allclose

from gearcli import api

SCENE = """
title = "torque drive against a fan load"
[[stage]]
normal_module_mm = 3
normal_pressure_angle_deg = 20
pinion = {{ teeth = 20, face_width_mm = 20, hand = "spur", inertia_kg_m2 = 0.002 }}
gear   = {{ teeth = 40, face_width_mm = 20, hand = "spur", inertia_kg_m2 = 0.02 }}
[input]
drive = "torque"
speed_rpm = 1500
torque_Nm = {t_in}
[load]
torque_Nm = 100
speed_exponent = {p}
[simulation]
duration_s = 0.6
steps = 1200
"""


def _balance(tmp_path, t_in, p, sets=()):
    path = tmp_path / "fan.toml"
    path.write_text(SCENE.format(t_in=t_in, p=p))
    loaded, design = api.load_and_design(str(path), list(sets))
    found = [d for d in design.diagnostics if d.data.get("check") == "torque_drive_balance"]
    return loaded, design, found


def test_a_balanced_torque_drive_is_not_warned(tmp_path):
    _, design, found = _balance(tmp_path, 50.0, 2)
    assert_allclose(design.input_torque_Nmm, 50e3, rtol=1e-12)  # T_L / u, lossless
    assert found == []
    _, _, found = _balance(tmp_path, 50.4, 0)  # 0.8 %: within the 1 % tolerance
    assert found == []


def test_an_unbalanced_torque_drive_names_the_speed_the_fan_load_settles_at(tmp_path):
    _, _, found = _balance(tmp_path, 60.0, 2)
    assert len(found) == 1
    settle = 1500.0 * math.sqrt(60.0 / 50.0)  # by hand: 1643.17 rpm
    assert "settles at 1643.2 rpm" in found[0].message, found[0].message
    assert found[0].data["required_input_torque_Nm"] == 50.0 and found[0].data["input_torque_Nm"] == 60.0
    # the simulated train goes there: the mean input speed over the last 0.2 s (the rigid train's time
    # constant J_eff n_0 / (2 T_req) = (0.002 + 0.02 / 4) 157 / 100 = 11 ms, so 0.4 s is ~36 of them)
    loaded, design, _ = _balance(tmp_path, 60.0, 2, ["simulation.window_start_s=0.4"])
    result = api.simulate(loaded.design, design)
    assert_allclose(result.input_speed_deg_s / 6.0, settle, rtol=1e-4)  # °/s to rpm; mesh vibration only
    assert any("torque_drive_balance" == w.data.get("check") for w in result.diagnostics)


def test_a_constant_load_cannot_balance_it(tmp_path):
    _, _, found = _balance(tmp_path, 60.0, 0)
    assert len(found) == 1 and "accelerates for the whole run" in found[0].message
    _, _, found = _balance(tmp_path, 40.0, 0)
    assert len(found) == 1 and "decelerates" in found[0].message
