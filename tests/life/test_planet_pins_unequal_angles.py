"""Planet pin and central-shaft bearings where the sun and ring meshes have different working pressure angles.

Profile-shifted planetary stages (the NREL 5 MW stage: alpha_w 28.1 deg at the sun, 17.2 deg at the ring) have
alpha_w,sp != alpha_w,rp. The planet is an idler on one base cylinder, so its moment balance about its own
axis, F_bt,sp r_b,p = F_bt,rp r_b,p, gives both meshes the same transverse line force F_bt, and each mesh's
tangential, separating and axial forces follow from it at its own working circle:

    F_t = F_bt cos(alpha_w),  F_r = F_bt sin(alpha_w),  F_a = F_bt tan(beta_b)

So on a pin (most loaded planet, K_gamma): tangential K F_bt (cos a_sp + cos a_rp), net radial (outwards)
K F_bt (sin a_sp - sin a_rp), axial 0 (the two meshes' F_a are equal and opposite), tilting moment
K F_bt tan(beta_b) (r_w,p,sp + r_w,p,rp) with r_w,p = r_b,p / cos(alpha_w) on each mesh. The carrier takes no
axial force; the sun's locating bearing N F_bt tan(beta_b).

Scene (not a shipped config): sun 26 (left hand, x 0.5) driven, 3 planets 20 (right hand, x 0.3), ring 67 held
(x from concentricity, computed below), m_n 4, alpha_n 20 deg, beta 8 deg, 2500 N m on the carrier, K_gamma 1.15;
each pin on two bearings 20 mm either side of the planet's mid-plane. Every expected number is computed here
from ISO 21771 geometry and statics, none taken from the code.
"""

from __future__ import annotations

import math

from numpy.testing import assert_allclose

from tests.life.scenes import design_of
from tests.reference.heavy_hand import inv as _inv
from tests.reference.heavy_hand import inv_inverse as _inv_solve

Z_S, Z_P, Z_R, N, M_N, ALPHA_N, BETA = 26, 20, 67, 3, 4.0, 20.0, 8.0
X_S, X_P = 0.5, 0.3
T_OUT, K_GAMMA, HALF_SPAN = 2500.0, 1.15, 20.0

AN, B = math.radians(ALPHA_N), math.radians(BETA)
AT = math.atan(math.tan(AN) / math.cos(B))
MT = M_N / math.cos(B)
BETA_B = math.atan(math.tan(B) * math.cos(AT))
# sun-planet working angle and centre distance (ISO 21771 external pair)
A_SP = _inv_solve(_inv(AT) + 2 * math.tan(AN) * (X_S + X_P) / (Z_S + Z_P))
A_W = 0.5 * (Z_S + Z_P) * MT * math.cos(AT) / math.cos(A_SP)
# planet-ring: the same centre distance (concentricity) sets its working angle, and with it the ring's shift
# (internal pair, ISO 21771 signs: z_r negative, inv a_w = inv a_t + 2 tan a_n (x_p + x_r) / (z_p - z_r))
A_RP = math.acos(0.5 * (Z_R - Z_P) * MT * math.cos(AT) / A_W)
X_R = (_inv(A_RP) - _inv(AT)) * (Z_P - Z_R) / (2 * math.tan(AN)) - X_P
R_B_S = 0.5 * Z_S * MT * math.cos(AT)
R_B_P = 0.5 * Z_P * MT * math.cos(AT)
T_SUN = T_OUT * 1e3 / (1 + Z_R / Z_S)  # N mm, ring held, no losses
F_BT = T_SUN / (N * R_B_S)  # per planet, N

SCENE = f"""
materials = {{ steel = {{ density_kg_m3 = 7850, youngs_modulus_MPa = 206000, poisson_ratio = 0.3, treatment = "case_carburized", contact_fatigue_limit_MPa = 1500, bending_fatigue_limit_MPa = 480 }} }}

[[stage]]
type = "planetary"
fixed = "ring"
input = "sun"
normal_module_mm = {M_N}
normal_pressure_angle_deg = {ALPHA_N}
helix_angle_deg = {BETA}
sun    = {{ teeth = {Z_S}, face_width_mm = 60, hand = "left", profile_shift = {X_S}, material = "steel", flank_roughness_Rz_um = 3, root_roughness_Rz_um = 10, axial_position_mm = 100 }}
planet = {{ teeth = {Z_P}, face_width_mm = 58, hand = "right", profile_shift = {X_P}, count = {N}, material = "steel", flank_roughness_Rz_um = 3, root_roughness_Rz_um = 10, axial_position_mm = 100 }}
ring   = {{ teeth = {Z_R}, face_width_mm = 58, hand = "right", profile_shift = {X_R!r}, material = "steel", flank_roughness_Rz_um = 5, root_roughness_Rz_um = 16 }}
accuracy_grade = 6

[input]
speed_rpm = 1500
rotation = "cw"

[load]
torque_Nm = {T_OUT}

[lubricant]
viscosity_40C_mm2_s = 220

[rating]
required_life_h = 20000
load_sharing_factor = {K_GAMMA}

[[bearing]]
planet_stage = 1
position_mm = {100 - HALF_SPAN}
dynamic_load_rating_kN = 40
kind = "roller"
locating = true

[[bearing]]
planet_stage = 1
position_mm = {100 + HALF_SPAN}
dynamic_load_rating_kN = 40
kind = "roller"
locating = false

[[bearing]]
shaft = 1
position_mm = 0
dynamic_load_rating_kN = 30
kind = "ball"
locating = true

[[bearing]]
shaft = 1
position_mm = 200
dynamic_load_rating_kN = 30
kind = "ball"
locating = false

[[bearing]]
shaft = 2
position_mm = 60
dynamic_load_rating_kN = 100
kind = "roller"
locating = true

[[bearing]]
shaft = 2
position_mm = 260
dynamic_load_rating_kN = 100
kind = "roller"
locating = false
"""


def _bearings():
    _, result = design_of(SCENE)
    stage = result.stages[0]
    angles = [math.radians(stage.working_pressure_angle_deg),
              math.radians(stage.planetary.planet_ring.working_pressure_angle_deg)]
    return result.bearings, angles


def test_the_scene_has_the_unequal_working_angles_it_is_for():
    _, (a_sp, a_rp) = _bearings()
    assert_allclose([a_sp, a_rp], [A_SP, A_RP], rtol=1e-9)
    assert math.degrees(A_SP - A_RP) > 2.5  # 24.46 deg against 21.56 deg


def test_pin_carries_the_same_line_force_from_both_meshes():
    bearings, _ = _bearings()
    pin_a, pin_b = bearings[0], bearings[1]
    tangential = K_GAMMA * F_BT * (math.cos(A_SP) + math.cos(A_RP))
    radial_out = K_GAMMA * F_BT * (math.sin(A_SP) - math.sin(A_RP))
    # z is tangential, y radial from the carrier's axis: the reactions oppose the planet's loads
    assert_allclose(abs(pin_a.radial_z_N + pin_b.radial_z_N), tangential, rtol=1e-9)
    assert_allclose(pin_a.radial_y_N + pin_b.radial_y_N, -radial_out, rtol=1e-9)
    assert_allclose([pin_a.radial_z_N, pin_b.radial_z_N], [pin_b.radial_z_N, pin_a.radial_z_N], rtol=1e-12)
    # the meshes' axial forces cancel on the pin, their tilting moment is a couple on the two bearings
    assert abs(pin_a.axial_N) < 1e-9 * tangential
    moment = K_GAMMA * F_BT * math.tan(BETA_B) * (R_B_P / math.cos(A_SP) + R_B_P / math.cos(A_RP))
    assert_allclose(abs(pin_a.radial_y_N - pin_b.radial_y_N) / 2, moment / (2 * HALF_SPAN), rtol=1e-9)


def test_central_shafts_axial_forces():
    bearings, _ = _bearings()
    sun_locating, carrier_locating = bearings[2], bearings[4]
    assert_allclose(abs(sun_locating.axial_N), N * F_BT * math.tan(BETA_B), rtol=1e-9)
    assert abs(carrier_locating.axial_N) < 1e-9 * N * F_BT  # the planets' axial forces cancel on their pins
    for b in bearings[2:]:
        assert b.radial_N < 1e-9 * N * F_BT  # equally spaced identical planets: no net radial load
