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
