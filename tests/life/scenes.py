"""Small design files for the shaft statics and life tests, written as TOML text."""

from __future__ import annotations

import io

from gearcli.config import load_design
from gearcli.design import compute_design


def design_of(toml: str, overrides: tuple[str, ...] = ()):
    """(DesignFile, DesignResult) of a TOML text."""
    loaded = load_design("-", overrides, stdin=io.BytesIO(toml.encode()))
    return loaded.design, compute_design(loaded.design)


ONE_STAGE = """
[[stage]]
normal_module_mm = 4
normal_pressure_angle_deg = 20
helix_angle_deg = 15
center_angle_deg = 0
pinion = { teeth = 20, face_width_mm = 40, hand = "left", axial_position_mm = 100 }
gear = { teeth = 60, face_width_mm = 40, hand = "right", axial_position_mm = 70 }

[input]
speed_rpm = 1500
rotation = "cw"

[load]
torque_Nm = 600

[[bearing]]
shaft = 2
position_mm = 0
dynamic_load_rating_kN = 40
kind = "ball"
locating = true
factors = { e = 0.3, X = 0.56, Y = 1.5 }

[[bearing]]
shaft = 2
position_mm = 200
dynamic_load_rating_kN = 40
kind = "ball"
"""

COUNTERSHAFT = """
[[stage]]
normal_module_mm = 3
normal_pressure_angle_deg = 20
helix_angle_deg = 12
center_angle_deg = 0
pinion = { teeth = 19, face_width_mm = 30, hand = "right", axial_position_mm = 50 }
gear = { teeth = 57, face_width_mm = 30, hand = "left", axial_position_mm = 50 }

[[stage]]
normal_module_mm = 4
normal_pressure_angle_deg = 20
helix_angle_deg = 10
center_angle_deg = 90
pinion = { teeth = 17, face_width_mm = 45, hand = "left", axial_position_mm = 180 }
gear = { teeth = 68, face_width_mm = 45, hand = "right", axial_position_mm = 180 }

[input]
speed_rpm = 1450
rotation = "ccw"

[load]
torque_Nm = 900

[[bearing]]
shaft = 2
position_mm = 0
dynamic_load_rating_kN = 30
kind = "roller"

[[bearing]]
shaft = 2
position_mm = 240
dynamic_load_rating_kN = 30
kind = "roller"
locating = true
"""

# A rated single helical stage (case-carburized, grade 6) with a three-point duty and bearings on both shafts.
RATED = """
title = "rated stage"

[materials.steel]
density_kg_m3 = 7800
youngs_modulus_MPa = 206000
poisson_ratio = 0.3
treatment = "case_carburized"
contact_fatigue_limit_MPa = 1500
bending_fatigue_limit_MPa = 430

[[stage]]
normal_module_mm = 4
normal_pressure_angle_deg = 20
helix_angle_deg = 15
accuracy_grade = 6
pinion = { teeth = 20, face_width_mm = 40, hand = "left", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 16, axial_position_mm = 100 }
gear = { teeth = 60, face_width_mm = 40, hand = "right", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 16, axial_position_mm = 70 }

[contact]
stiffness = "iso6336"
exponent = 1.0
damping_ratio = 0.05

[input]
speed_rpm = 1500
ramp_s = 0.05

[load]
torque_Nm = 2400
ramp_s = 0.05

[lubricant]
viscosity_40C_mm2_s = 220

[rating]
required_life_h = 20000

[simulation]
duration_s = 0.3
steps = 600

[[bearing]]
shaft = 1
position_mm = 0
dynamic_load_rating_kN = 60
kind = "ball"
locating = true
factors = { e = 0.3, X = 0.56, Y = 1.5 }

[[bearing]]
shaft = 1
position_mm = 200
dynamic_load_rating_kN = 60
kind = "ball"

[[bearing]]
shaft = 2
position_mm = 0
dynamic_load_rating_kN = 120
kind = "roller"
locating = true

[[bearing]]
shaft = 2
position_mm = 200
dynamic_load_rating_kN = 120
kind = "roller"

[[duty]]
name = "light"
hours = 8000
torque_Nm = 1500
speed_rpm = 1500

[[duty]]
name = "nominal"
hours = 10000
torque_Nm = 2400
speed_rpm = 1500

[[duty]]
name = "peak"
hours = 2000
power_kW = 140
speed_rpm = 1200
"""

# the same stage excited by a transmission error near its mesh resonance (a ringing scene)
EXCITED = RATED.replace("damping_ratio = 0.05", "damping_ratio = 0.05\ntransmission_error_um = [1.0, 0.0, 1.0]")
