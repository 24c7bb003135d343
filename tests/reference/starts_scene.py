"""A two-stage 11 kW agitator drive whose every inertia is given in the file (motor rotor on its coupling, the four
gear bodies, the agitator on its coupling), so a rigid-drivetrain start and the start's load cycles can be written
by hand from the file's numbers (tests/reference/test_starts_rigid_engineer.py, tests/life/test_starts_engineer.py).
Lossless stages: the rigid drivetrain is then exact (docs/physics.md, "Rigid-body start")."""

import math

DRIVE_SCENE = """
title = "11 kW agitator drive, explicit inertias"

[materials.steel]
density_kg_m3 = 7850
youngs_modulus_MPa = 2.06e5
poisson_ratio = 0.3
treatment = "case_carburized"
contact_fatigue_limit_MPa = 1500
bending_fatigue_limit_MPa = 500

[[stage]]
normal_module_mm = 2.5
normal_pressure_angle_deg = 20
helix_angle_deg = 15
efficiency = 1.0
accuracy_grade = 6
pinion = { teeth = 21, face_width_mm = 40, hand = "left",  material = "steel", profile_shift = 0.25, flank_roughness_Rz_um = 4, root_roughness_Rz_um = 12, inertia_kg_m2 = 0.0015, axial_position_mm = 60 }
gear   = { teeth = 83, face_width_mm = 36, hand = "right", material = "steel", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 12, inertia_kg_m2 = 0.12, axial_position_mm = 60 }

[[stage]]
normal_module_mm = 4
normal_pressure_angle_deg = 20
helix_angle_deg = 12
efficiency = 1.0
accuracy_grade = 6
pinion = { teeth = 19, face_width_mm = 70, hand = "right", material = "steel", profile_shift = 0.3, flank_roughness_Rz_um = 4, root_roughness_Rz_um = 12, inertia_kg_m2 = 0.008, axial_position_mm = 180 }
gear   = { teeth = 77, face_width_mm = 65, hand = "left",  material = "steel", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 12, inertia_kg_m2 = 0.9, axial_position_mm = 180 }

[input]
speed_rpm = 1460
drive = "motor"
motor = { rated_power_kW = 11, rated_speed_rpm = 1460, synchronous_speed_rpm = 1500, breakdown_torque_ratio = 2.9, locked_rotor_torque_ratio = 2.2 }
starting = "direct"
inertia_kg_m2 = 0.045
coupling_stiffness_Nm_rad = 8.0e3
coupling_damping_Nms_rad = 3

[load]
torque_Nm = 1000
inertia_kg_m2 = 25
coupling_stiffness_Nm_rad = 2.5e5
coupling_damping_Nms_rad = 60

[simulation]
duration_s = 3.0
steps = 6000
window_start_s = 2.0

[lubricant]
viscosity_40C_mm2_s = 220

[rating]
required_life_h = 20000

[[bearing]]
shaft = 1
position_mm = 10
dynamic_load_rating_kN = 30
static_load_rating_kN = 18
kind = "ball"
locating = true
[[bearing]]
shaft = 1
position_mm = 240
dynamic_load_rating_kN = 30
static_load_rating_kN = 18
kind = "ball"
[[bearing]]
shaft = 2
position_mm = 10
dynamic_load_rating_kN = 90
static_load_rating_kN = 100
kind = "roller"
locating = true
[[bearing]]
shaft = 2
position_mm = 240
dynamic_load_rating_kN = 90
static_load_rating_kN = 100
kind = "roller"
[[bearing]]
shaft = 3
position_mm = 10
dynamic_load_rating_kN = 150
static_load_rating_kN = 180
kind = "roller"
locating = true
[[bearing]]
shaft = 3
position_mm = 240
dynamic_load_rating_kN = 150
static_load_rating_kN = 180
kind = "roller"
"""

RPM = 2.0 * math.pi / 60.0
# the file's numbers, written out once
J_MOTOR, J_P1, J_G1, J_P2, J_G2, J_LOAD = 0.045, 0.0015, 0.12, 0.008, 0.9, 25.0
TEETH = (21, 83, 19, 77)
MODULE_MM = (2.5, 4.0)
HELIX_DEG = (15.0, 12.0)
MOTOR = dict(P_kW=11.0, n_r=1460.0, n_s=1500.0, kb=2.9, kl=2.2)
SPEED_RPM = 1460.0
LOAD_NM = 1000.0
DURATION_S = 3.0
WINDOW_START_S = 2.0
