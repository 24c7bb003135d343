"""The one-stage DOL conveyor drive of tests/life/test_tr26a_stalled_point.py and test_tr26a_idle_starts.py: a 15 kW
four-pole motor (breakdown 2.8, locked rotor 2.0 times its rated torque) on a helical 19/80 stage (eta 0.98)."""

from __future__ import annotations

Z1, Z2, ETA, M_N, BETA = 19, 80, 0.98, 4.0, 12.0
P_KW, N_RATED, K_B, K_L = 15.0, 1470.0, 2.8, 2.0


def scene(title: str, load: str, duration_s: float, duty: str) -> str:
    """The one-stage DOL drive of the tr26a life tests with its ``load`` line, run length and ``duty`` tables."""
    return f"""
title = "{title}"

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
{load}
inertia_kg_m2 = 20
coupling_stiffness_Nm_rad = 2.0e5
coupling_damping_Nms_rad = 60

[rating]
required_life_h = 20000

[simulation]
duration_s = {duration_s}
steps = 2000

{duty}
"""
