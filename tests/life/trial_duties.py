"""Design files of the life trial (tests/life/test_trial_duties.py): one case-carburized helical stage
(z 21/67, m_n 3, beta 12 deg, b 40/38 mm, grade 6) on two bearings per shaft, and duties written for it."""

from __future__ import annotations

from pathlib import Path

STAGE = """
title = "one-stage trial reducer"

[materials.steel]
density_kg_m3 = 7850
youngs_modulus_MPa = 206000
poisson_ratio = 0.3
treatment = "case_carburized"
contact_fatigue_limit_MPa = 1500
bending_fatigue_limit_MPa = 500

[[stage]]
normal_module_mm = 3
normal_pressure_angle_deg = 20
helix_angle_deg = 12
accuracy_grade = 6
center_angle_deg = 0
pinion = { teeth = 21, face_width_mm = 40, hand = "left", material = "steel", flank_roughness_Rz_um = 3, root_roughness_Rz_um = 10, axial_position_mm = 80 }
gear = { teeth = 67, face_width_mm = 38, hand = "right", material = "steel", flank_roughness_Rz_um = 3, root_roughness_Rz_um = 10, axial_position_mm = 80 }

[lubricant]
viscosity_40C_mm2_s = 220

[rating]
required_life_h = 10000

[[bearing]]
shaft = 1
position_mm = 0
dynamic_load_rating_kN = 120
kind = "ball"
locating = true
factors = { e = 0.3, X = 0.56, Y = 1.5 }

[[bearing]]
shaft = 1
position_mm = 160
dynamic_load_rating_kN = 120
kind = "ball"

[[bearing]]
shaft = 2
position_mm = 0
dynamic_load_rating_kN = 90
kind = "roller"
locating = true
factors = { e = 0.4, X = 0.4, Y = 1.5 }

[[bearing]]
shaft = 2
position_mm = 160
dynamic_load_rating_kN = 90
kind = "roller"
"""

SPEED_DRIVE = """
[input]
speed_rpm = 1460
ramp_s = 0.05

[load]
torque_Nm = 1000
ramp_s = 0.05

[simulation]
duration_s = 0.3
steps = 600
"""

# a belt conveyor: 22 kW four-pole motor direct on line, the drum and belt 40 kg m^2 on an elastic coupling; the
# loaded start takes about 2.5 s to 98 % of the operating speed, longer than the file's 2 s run
MOTOR_DRIVE = """
[input]
speed_rpm = 1460
drive = "motor"
motor = { rated_power_kW = 22, rated_speed_rpm = 1460, synchronous_speed_rpm = 1500, breakdown_torque_ratio = 2.8, locked_rotor_torque_ratio = 2.3 }
starting = "direct"
inertia_kg_m2 = 0.12
coupling_stiffness_Nm_rad = 8e3
coupling_damping_Nms_rad = 3

[load]
torque_Nm = 400
inertia_kg_m2 = 40
coupling_stiffness_Nm_rad = 2e5
coupling_damping_Nms_rad = 150

[simulation]
duration_s = 2.0
steps = 4000
"""


def duty(*points: dict) -> str:
    """[[duty]] tables of ``points`` (name, hours, one torque key, speed_rpm, optional starts)."""
    out = []
    for p in points:
        lines = ["[[duty]]"]
        for k, v in p.items():
            lines.append(f'{k} = "{v}"' if isinstance(v, str) else f"{k} = {v!r}")
        out.append("\n".join(lines))
    return "\n\n" + "\n\n".join(out) + "\n"


def write(path: Path, drive: str, *points: dict) -> Path:
    path.write_text(STAGE + drive + duty(*points))
    return path
