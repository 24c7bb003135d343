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

Z1, Z2, ETA = 19, 80, 0.98
P_KW, N_RATED, K_B, K_L = 15.0, 1470.0, 2.8, 2.0
TABLE = [[0.0, 1200.0], [0.01, 1300.0], [349.125, 1300.0]]  # output rpm, N m: a breakaway load, flat when moving
T_POINT = 2600.0  # N m at the point's nominal output speed 1470 * 19/80 = 349.125 rpm: the table times 2

SCENE = f"""
title = "a DOL motor that cannot drive its conveyor's breakaway load"

[materials]
steel = {{ treatment = "case_carburized", contact_fatigue_limit_MPa = 1500, bending_fatigue_limit_MPa = 500, density_kg_m3 = 7850, youngs_modulus_MPa = 206000, poisson_ratio = 0.3 }}

[[stage]]
normal_module_mm = 4
normal_pressure_angle_deg = 20
helix_angle_deg = 12
accuracy_grade = 6
efficiency = {ETA}
pinion = {{ teeth = {Z1}, face_width_mm = 60, hand = "left", material = "steel", profile_shift = 0.3, flank_roughness_Rz_um = 3, root_roughness_Rz_um = 10 }}
gear   = {{ teeth = {Z2}, face_width_mm = 55, hand = "right", material = "steel", flank_roughness_Rz_um = 3, root_roughness_Rz_um = 10 }}

[lubricant]
viscosity_40C_mm2_s = 220

[input]
speed_rpm = {N_RATED}
drive = "motor"
motor = {{ rated_power_kW = {P_KW}, rated_speed_rpm = {N_RATED}, synchronous_speed_rpm = 1500, breakdown_torque_ratio = {K_B}, locked_rotor_torque_ratio = {K_L} }}
starting = "direct"
inertia_kg_m2 = 0.08
coupling_stiffness_Nm_rad = 5.0e3
coupling_damping_Nms_rad = 2

[load]
torque_speed = {TABLE}
inertia_kg_m2 = 20
coupling_stiffness_Nm_rad = 2.0e5
coupling_damping_Nms_rad = 60

[rating]
required_life_h = 20000

[simulation]
duration_s = 0.3
steps = 2000

[[duty]]
name = "jammed"
hours = 100
speed_rpm = {N_RATED}
torque_Nm = {T_POINT}  # the table scaled by 2: 2400 N m at standstill
"""


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
