"""A motor that cannot start under a load that overhauls it: the stall warning says the train was driven backwards.

Scene: one helical stage 23/97 (i = 4.217, η 0.985), a 22 kW 4-pole motor (1475 rpm rated: T_r = 22000 / (1475 π/30)
= 142.4 N·m; locked-rotor 2.2 T_r = 313.4 N·m, breakdown 2.6 T_r = 370.3 N·m) on a coupling, 3000 N·m on an 8 kg·m²
drum. Reflected to the motor the load is 3000 / (4.217 · 0.985) = 722.2 N·m, above even the breakdown torque: the
motor cannot start, and the constant load turns the whole train backwards. The warning said only "it stalls at
standstill: it cannot start" while the motor reached −16900 rpm (11x synchronous, backwards) and the run's window
means, dynamic factors and speeds were printed as if of an operating point; `motor_rolls_back` is left out where
the stall is warned (one warning for one cause), so the stall's now says it.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from gearcli import api
from gearcli.core.channels import Channel

SCENE = """
title = "stalled motor driven back"
[materials.steel]
density_kg_m3 = 7850
youngs_modulus_MPa = 2.1e5
poisson_ratio = 0.3
[[stage]]
normal_module_mm = 4
normal_pressure_angle_deg = 20
helix_angle_deg = 15
efficiency = 0.985
pinion = { teeth = 23, face_width_mm = 60, hand = "left",  material = "steel", profile_shift = 0.2 }
gear   = { teeth = 97, face_width_mm = 55, hand = "right", material = "steel", profile_shift = -0.1 }
[input]
speed_rpm = 1475
drive = "motor"
motor = { rated_power_kW = 22, rated_speed_rpm = 1475, synchronous_speed_rpm = 1500, breakdown_torque_ratio = 2.6, locked_rotor_torque_ratio = 2.2 }
starting = "direct"
inertia_kg_m2 = 0.12
coupling_stiffness_Nm_rad = 3.0e4
coupling_damping_Nms_rad = 6
[load]
torque_Nm = 3000
inertia_kg_m2 = 8.0
coupling_stiffness_Nm_rad = 2.0e5
coupling_damping_Nms_rad = 80
[simulation]
duration_s = 0.5
steps = 1000
"""


def test_a_stalled_motor_that_the_load_turns_backwards_is_told_so(tmp_path):
    t_rated = 22000 / (1475 * math.pi / 30)
    reflected = 3000 / (97 / 23 * 0.985)
    assert 2.6 * t_rated < reflected  # by hand: not even the breakdown torque carries it
    path = tmp_path / "stall.toml"
    path.write_text(SCENE, encoding="utf-8")
    loaded = api.load(str(path))
    run = api.simulate(loaded.design, api.design(loaded))
    stall = [d for d in run.diagnostics if d.code == "motor_stalls"]
    assert len(stall) == 1
    w = run.series[Channel("speed", "motor")] * 30 / math.pi  # rpm, the run's own motor speed
    assert w.min() < -0.01 * 1500  # it was driven back
    assert stall[0].data["reverse_speed_rpm"] == pytest.approx(float(np.min(w)), rel=1e-9)
    assert "drives the train backwards" in stall[0].message and "no forward operating point" in stall[0].message
