"""Planetary trains the shipped configs do not have, checked by hand (a drivetrain engineer's own scenes).

Scene A: a simple spur planetary, sun 24 / planets 36 / ring 96 (z_r = z_s + 2 z_p: no profile shift needed),
m_n 4, b 40, steel, sun driven at 1500 rpm, ring held, carrier out, 5000 N·m on the carrier; N = 3 planets unless
a test says otherwise ((z_s + z_r)/N = 120/N whole for N = 1 ... 6; the tips clash from N = 5).

Hand formulas (ISO 21771, ISO 6336-1, Willis) written out in each test; no expected number is taken from the code.
"""

from __future__ import annotations

import math

import pytest
from numpy.testing import assert_allclose

from tests.life.scenes import design_of as _design_of


def design_of(toml: str, overrides: tuple[str, ...] = ()):
    return _design_of(toml, overrides)[1]


Z_S, Z_P, Z_R, M_N, B = 24, 36, 96, 4.0, 40.0
N_IN, T_OUT = 1500.0, 5000.0


def scene_a(count: int = 3, planet: str = "", bearings: str = "", sun: str = "") -> str:
    return f"""
[materials.steel]
density_kg_m3 = 7850
youngs_modulus_MPa = 206000
poisson_ratio = 0.3

[[stage]]
type = "planetary"
normal_module_mm = {M_N}
sun    = {{ teeth = {Z_S}, face_width_mm = {B}, material = "steel"{sun} }}
planet = {{ teeth = {Z_P}, face_width_mm = {B}, count = {count}, material = "steel"{planet} }}
ring   = {{ teeth = {Z_R}, face_width_mm = {B}, material = "steel" }}
fixed = "ring"
input = "sun"

[input]
speed_rpm = {N_IN}

[load]
torque_Nm = {T_OUT}
{bearings}
"""


SUN_BEARINGS = """
[[bearing]]
shaft = 1
position_mm = 0
dynamic_load_rating_kN = 100
kind = "ball"
locating = true

[[bearing]]
shaft = 1
position_mm = 200
dynamic_load_rating_kN = 100
kind = "ball"
"""


# ------------------------------------------------------------------------ unequal spacing: the sun's bearings
@pytest.mark.parametrize("angles", [(0.0, 120.0), (60.0, 180.0), (0.0, 117.0)])
def test_unequally_spaced_planets_load_the_sun_bearings_with_their_resultant(angles):
    """Two planets declared at psi_1, psi_2 (whole multiples of 360/(z_s + z_r) = 3 deg apart): each pushes the sun
    with its in-plane mesh force F_t / cos(alpha) (tangential F_t = T_sun / (N r_s), radial F_t tan(alpha)) at its
    own angle, so the sun carries the resultant 2 (F_t / cos alpha) cos((psi_2 - psi_1)/2), shared equally by two
    bearings symmetric about the sun's plane. Equal spacing (psi = 0, 180) would cancel it; the statics placed the
    planets at 360 j/N whatever angles_deg declared and gave 0 N."""
    extra = f", angles_deg = [{angles[0]}, {angles[1]}], axial_position_mm = 100"
    d = design_of(scene_a(2, planet=extra, sun=", axial_position_mm = 100", bearings=SUN_BEARINGS))
    t_sun = T_OUT / (1.0 + Z_R / Z_S)  # N·m, ring held
    f_t = t_sun * 1e3 / (2 * 0.5 * Z_S * M_N)  # N per planet, r_s = z_s m / 2
    in_plane = f_t / math.cos(math.radians(20.0))
    resultant = 2.0 * in_plane * math.cos(math.radians(angles[1] - angles[0]) / 2.0)
    radial = [b.radial_N for b in d.bearings]
    assert_allclose(radial, [resultant / 2.0] * 2, rtol=1e-12)  # closed form; round-off only
    # the resultant turns with the planets: its direction rotated by psi_1 from the (0, 120) case's
    y, z = sum(b.radial_y_N for b in d.bearings), sum(b.radial_z_N for b in d.bearings)
    ref = design_of(scene_a(2, planet=", angles_deg = [0, 120], axial_position_mm = 100",
                            sun=", axial_position_mm = 100", bearings=SUN_BEARINGS))
    y0, z0 = sum(b.radial_y_N for b in ref.bearings), sum(b.radial_z_N for b in ref.bearings)
    half = math.radians(angles[1] - angles[0]) / 2.0 - math.radians(60.0)  # the bisector moves with the gap too
    turn = math.radians(angles[0]) + half
    scale = math.cos(math.radians(angles[1] - angles[0]) / 2.0) / math.cos(math.radians(60.0))
    assert_allclose([y, z], [scale * (y0 * math.cos(turn) - z0 * math.sin(turn)),
                             scale * (y0 * math.sin(turn) + z0 * math.cos(turn))], rtol=1e-9, atol=1e-6)


def test_one_planet_loads_the_sun_bearings_with_its_whole_mesh_force():
    """A single planet: nothing balances its mesh force on the sun, F_t / cos(alpha) with F_t = T_sun / r_s, half on
    each of two bearings symmetric about the sun's plane."""
    d = design_of(scene_a(1, planet=", axial_position_mm = 100", sun=", axial_position_mm = 100",
                          bearings=SUN_BEARINGS))
    f_t = T_OUT / (1.0 + Z_R / Z_S) * 1e3 / (0.5 * Z_S * M_N)
    assert_allclose([b.radial_N for b in d.bearings], [f_t / math.cos(math.radians(20.0)) / 2.0] * 2, rtol=1e-12)


def test_equally_spaced_planets_declared_or_implied_leave_the_sun_unloaded():
    """Three planets at 0/120/240 (declared, or implied by equal spacing) and two at 0/180: no net radial force."""
    for count, extra in ((3, ", angles_deg = [0, 120, 240]"), (3, ""), (2, ", angles_deg = [0, 180]")):
        d = design_of(scene_a(count, planet=extra + ", axial_position_mm = 100", sun=", axial_position_mm = 100",
                              bearings=SUN_BEARINGS))
        assert [b.radial_N for b in d.bearings] == [0.0, 0.0]
        assert d.stages[0].planetary.equal_spacing


def test_declared_unequal_spacing_is_not_reported_as_equal_spacing():
    """Two planets at 0 and 120 deg: (z_s + z_r)/2 = 60 is whole (they could be equally spaced) but they are not;
    equal_spacing said true."""
    d = design_of(scene_a(2, planet=", angles_deg = [0, 120]"))
    assert not d.stages[0].planetary.equal_spacing


# ------------------------------------------------------------------------------------------ hostile inputs
def _cli(tmp_path, text: str, *args: str):
    from click.testing import CliRunner

    from gearcli.cli import cli

    path = tmp_path / "hostile.toml"
    path.write_text(text, encoding="utf-8")
    return path, CliRunner().invoke(cli, ["design", str(path), *args], catch_exceptions=False)


@pytest.mark.parametrize(("old", "new", "key", "says"), [
    # a ring with fewer teeth than the sun: the planets cannot fit (z_r must be about z_s + 2 z_p = 96)
    (f"teeth = {Z_R},", "teeth = 20,", "stage[0]", "ring.teeth (20)"),
    ("count = 3,", "count = -3,", "stage[0].planet.count", "must be ≥ 1"),
    # five planets: (24 + 96)/5 = 24 spaces them, but 2 a sin 36° = 141.07 mm < d_a = (36 + 2) 4 = 152 mm
    ("count = 3,", "count = 5,", "stage[0].planet.count", "141.0685 mm"),
    # seven: 120/7 = 17.14 is not whole
    ("count = 3,", "count = 7,", "stage[0].planet.count", "(24 + 96)/7"),
    # two planets declared 30° apart: 2 a sin 15° = 62.1166 mm < 152 mm; the declared angles place them
    ("count = 3,", "count = 2, angles_deg = [0, 30],", "stage[0].planet.angles_deg", "62.1166 mm"),
    # an internal ring has no bore (the key was accepted and ignored)
    (f"teeth = {Z_R},", f"teeth = {Z_R}, bore_diameter_mm = 500,", "stage[0].ring.bore_diameter_mm", "has no bore"),
])
def test_a_planetary_that_cannot_be_built_is_exit_2_naming_file_and_key(tmp_path, old, new, key, says):
    path, res = _cli(tmp_path, scene_a().replace(old, new, 1))
    assert res.exit_code == 2, res.stderr
    assert f"{path.name}: {key}" in res.stderr and says in res.stderr
    assert "Traceback" not in res.stderr


def test_helical_planetary_hands_external_pair_and_ring(tmp_path):
    """The sun and planet (an external pair) need opposite hands; the ring (internal) the planet's."""
    helical = scene_a().replace("normal_module_mm = 4", "normal_module_mm = 4\nhelix_angle_deg = 15")
    same = helical.replace(f"teeth = {Z_S},", f'teeth = {Z_S}, hand = "left",').replace(
        f"teeth = {Z_P},", f'teeth = {Z_P}, hand = "left",')
    path, res = _cli(tmp_path, same)
    assert res.exit_code == 2 and f"{path.name}: stage[0].planet.hand" in res.stderr and "Traceback" not in res.stderr
    ring = same.replace(f'teeth = {Z_P}, hand = "left",', f'teeth = {Z_P}, hand = "right",').replace(
        f"teeth = {Z_R},", f'teeth = {Z_R}, hand = "left",')
    path, res = _cli(tmp_path, ring)
    assert res.exit_code == 2 and f"{path.name}: stage[0].ring.hand" in res.stderr and "Traceback" not in res.stderr
    path, res = _cli(tmp_path, ring.replace(f'teeth = {Z_R}, hand = "left",', f'teeth = {Z_R}, hand = "right",'))
    assert res.exit_code == 0, res.stderr


# --------------------------------------------------------------------------------- scene A by hand: statics
ALPHA = math.radians(20.0)
R_S, R_P, R_R = 0.5 * Z_S * M_N, 0.5 * Z_P * M_N, 0.5 * Z_R * M_N  # pitch radii, mm (spur, x = 0)
RB_S, RB_P, RB_R = (r * math.cos(ALPHA) for r in (R_S, R_P, R_R))
A_W = R_S + R_P  # = R_R - R_P: concentric without shifts
P_BT = math.pi * M_N * math.cos(ALPHA)
U = Z_R / Z_S


def _willis(fixed: str, driven: str) -> dict[str, float]:
    """Member speeds for a unit speed of the driven member, from w_s - w_c = -u (w_r - w_c) with the held one at 0,
    solved here by linear algebra (an independent route from the code's table of the three arrangements)."""
    import numpy as np

    order = ("sun", "carrier", "ring")
    a = np.array([[1.0, -(1.0 + U), U],  # w_s - (1 + u) w_c + u w_r = 0
                  [float(m == fixed) for m in order],
                  [float(m == driven) for m in order]])
    w = np.linalg.solve(a, [0.0, 0.0, 1.0])
    return dict(zip(order, w, strict=True))


@pytest.mark.parametrize(("fixed", "driven"), [("ring", "sun"), ("ring", "carrier"), ("carrier", "sun"),
                                               ("carrier", "ring"), ("sun", "ring"), ("sun", "carrier")])
def test_member_speeds_torques_and_per_planet_force_by_hand(fixed, driven):
    """Willis speeds; lossless torques from the members' power balance (sum T w = 0 with sum T = 0: the sun's share
    1, the ring's u, the carrier's -(1 + u)); the planet's speed relative to the carrier (z_s/z_p)|w_s - w_c|;
    F_t = T_sun / (N r_s) per planet on both meshes; mesh frequency z_s |n_s - n_c| / 60 = z_r |n_r - n_c| / 60."""
    text = scene_a().replace('fixed = "ring"', f'fixed = "{fixed}"').replace('input = "sun"', f'input = "{driven}"')
    st = design_of(text).stages[0]
    p = st.planetary
    w = {m: v * N_IN for m, v in _willis(fixed, driven).items()}  # rpm
    out = next(m for m in ("sun", "carrier", "ring") if m not in (fixed, driven))
    share = {"sun": 1.0, "ring": U, "carrier": 1.0 + U}
    t_sun = T_OUT / share[out]  # N·m, the load on the output member
    assert_allclose([p.sun.speed_rpm, p.carrier.speed_rpm, p.ring.speed_rpm], [w["sun"], w["carrier"], w["ring"]],
                    rtol=1e-13, atol=1e-9)
    assert_allclose(st.ratio, abs(w[driven] / w[out]), rtol=1e-13)
    assert_allclose([p.sun.torque_Nm, p.ring.torque_Nm, p.carrier.torque_Nm],
                    [t_sun, U * t_sun, (1 + U) * t_sun], rtol=1e-13)
    moments = p.moment_balance_Nm
    assert_allclose(moments["carrier"], -(moments["sun"] + moments["ring"]), rtol=1e-13)  # T_c = -(T_s + T_r)
    assert_allclose(abs(p.planet.speed_rpm), Z_S / Z_P * abs(w["sun"] - w["carrier"]), rtol=1e-13)
    f_t = t_sun * 1e3 / (3 * R_S)
    assert_allclose([st.static_force_N.tangential, p.planet_ring.static_force_N.tangential], [f_t, f_t], rtol=1e-13)
    assert_allclose(p.planet.torque_Nm, f_t * R_P / 1e3, rtol=1e-13)  # one planet's flank torque
    f_z = Z_S * abs(w["sun"] - w["carrier"]) / 60.0
    assert_allclose([st.mesh_frequency_Hz, p.planet_ring.mesh_frequency_Hz], [f_z, f_z], rtol=1e-12)
    assert_allclose(f_z, Z_R * abs(w["ring"] - w["carrier"]) / 60.0, rtol=1e-12)


def test_contact_ratios_and_iso_stiffness_of_both_meshes_by_hand():
    """ISO 21771: external e_a = (sqrt(r_a1^2 - r_b1^2) + sqrt(r_a2^2 - r_b2^2) - a sin a) / p_bt; internal
    e_a = (sqrt(r_ap^2 - r_bp^2) - sqrt(r_ar^2 - r_br^2) + a sin a) / p_bt with the ring's tip r_ar = r_r - m.
    ISO 6336-1: q' = C1 + C2/z_n1 + C3/z_n2 (x = 0), z_n2 = inf for the ring; c' = C_M C_B / q' (C_R 1, spur,
    F_t/b = 174 N/mm > 100: no load correction); C_B = 1 + 0.5 (1.2 - 1.25) = 0.975; c_ga = c' (0.75 e_a + 0.25)."""
    st = design_of(scene_a()).stages[0]
    pr = st.planetary.planet_ring
    ra_s, ra_p, ra_r = R_S + M_N, R_P + M_N, R_R - M_N
    e_sp = (math.sqrt(ra_s**2 - RB_S**2) + math.sqrt(ra_p**2 - RB_P**2) - A_W * math.sin(ALPHA)) / P_BT
    e_pr = (math.sqrt(ra_p**2 - RB_P**2) - math.sqrt(ra_r**2 - RB_R**2) + A_W * math.sin(ALPHA)) / P_BT
    assert_allclose([st.contact_ratio_transverse, pr.contact_ratio_transverse], [e_sp, e_pr], rtol=1e-12)
    assert_allclose([e_sp, e_pr], [1.6472, 1.9324], atol=5e-5)  # the figures worked on paper
    c_b, c_m = 1.0 + 0.5 * (1.2 - 1.25), 0.8
    c_sp = c_m * c_b / (0.04723 + 0.15551 / Z_S + 0.25791 / Z_P)
    c_pr = c_m * c_b / (0.04723 + 0.15551 / Z_P)
    assert_allclose([st.iso6336_single_pair_stiffness_N_mm_um, pr.iso6336_single_pair_stiffness_N_mm_um],
                    [c_sp, c_pr], rtol=1e-12)
    assert_allclose([st.iso6336_mesh_stiffness_N_mm_um, pr.iso6336_mesh_stiffness_N_mm_um],
                    [c_sp * (0.75 * e_sp + 0.25), c_pr * (0.75 * e_pr + 0.25)], rtol=1e-12)
    # the ring: d_a = d - 2 m, d_f = d + 2.5 m; the concave-convex Hertz radius r_p r_r / (r_r - r_p)
    assert_allclose([st.planetary.ring.tip_diameter_mm, st.planetary.ring.root_diameter_mm],
                    [2 * R_R - 2 * M_N, 2 * R_R + 2.5 * M_N], rtol=1e-14)
    assert_allclose(pr.equivalent_radius_mm, R_P * R_R / (R_R - R_P), rtol=1e-14)


# one planet: the disc of pitch diameter and face width (the model's default); the sun likewise
RHO, B_M = 7850.0, B * 1e-3
M_PLANET = RHO * math.pi / 4 * (2 * R_P * 1e-3) ** 2 * B_M
J_PLANET = 0.5 * M_PLANET * (R_P * 1e-3) ** 2
J_SUN = RHO * math.pi / 32 * B_M * (2 * R_S * 1e-3) ** 4


@pytest.mark.parametrize("count", [1, 2, 3, 4])
def test_carrier_inertia_and_planet_clearance_with_one_to_four_planets(count):
    """The carrier carries the planets' translation N m_p a^2; neighbours' tips clear by 2 a sin(pi/N) - d_a,p
    (d_a,p = (z_p + 2) m = 152 mm), and one planet has no neighbour."""
    p = design_of(scene_a(count)).stages[0].planetary
    assert_allclose(p.carrier.planets_translational_inertia_kg_m2, count * M_PLANET * (A_W * 1e-3) ** 2, rtol=1e-12)
    assert_allclose(p.planet.inertia_kg_m2, J_PLANET, rtol=1e-12)
    if count == 1:
        assert p.tip_clearance_between_planets_mm is None  # no neighbour (was 0.0, read as tips touching)
    else:
        assert_allclose(p.tip_clearance_between_planets_mm, 2 * A_W * math.sin(math.pi / count) - (Z_P + 2) * M_N,
                        rtol=1e-12)


# ------------------------------------------------------------------ scene A by hand: modes, simulate, life
def _run_json(tmp_path, command: str, text: str, *args: str) -> dict:
    import json

    from click.testing import CliRunner

    from gearcli.cli import cli

    path = tmp_path / "scene.toml"
    path.write_text(text, encoding="utf-8")
    res = CliRunner().invoke(cli, [command, str(path), "--format", "json", *args], catch_exceptions=False)
    assert res.exit_code == 0, res.stderr
    return json.loads(res.stdout)


def _hand_k_sp_k_pr() -> tuple[float, float]:
    """k_n = c_ga b (N/m) of both meshes from the hand formulas of the test above."""
    ra_s, ra_p, ra_r = R_S + M_N, R_P + M_N, R_R - M_N
    e_sp = (math.sqrt(ra_s**2 - RB_S**2) + math.sqrt(ra_p**2 - RB_P**2) - A_W * math.sin(ALPHA)) / P_BT
    e_pr = (math.sqrt(ra_p**2 - RB_P**2) - math.sqrt(ra_r**2 - RB_R**2) + A_W * math.sin(ALPHA)) / P_BT
    c_sp = 0.8 * 0.975 / (0.04723 + 0.15551 / Z_S + 0.25791 / Z_P) * (0.75 * e_sp + 0.25)
    c_pr = 0.8 * 0.975 / (0.04723 + 0.15551 / Z_P) * (0.75 * e_pr + 0.25)
    return c_sp * B * 1e6, c_pr * B * 1e6


# ------------------------------------------- scene B: a helical, profile-shifted planetary, then a helical stage
SCENE_B = """
[materials.steel]
density_kg_m3 = 7850
youngs_modulus_MPa = 206000
poisson_ratio = 0.3

[[stage]]
type = "planetary"
normal_module_mm = 3
helix_angle_deg = 15
sun    = { teeth = 21, face_width_mm = 45, hand = "left", profile_shift = 0.3 }
planet = { teeth = 30, face_width_mm = 42, hand = "right", profile_shift = 0.2, count = 3 }
ring   = { teeth = 81, face_width_mm = 42, profile_shift = -0.7 }
fixed = "ring"
input = "sun"

[[stage]]
normal_module_mm = 4
helix_angle_deg = 12
pinion = { teeth = 19, face_width_mm = 60, hand = "left" }
gear   = { teeth = 77, face_width_mm = 55, hand = "right" }

[input]
speed_rpm = 1500

[load]
torque_Nm = 8000
"""


def _inv(a: float) -> float:
    return math.tan(a) - a


def _inv_inverse(v: float) -> float:
    from scipy.optimize import brentq

    return brentq(lambda a: _inv(a) - v, 1e-6, 1.5)


def test_helical_profile_shifted_planetary_geometry_by_hand():
    """ISO 21771 with z_r - z_p = z_s + z_p (51): the ring's shift x_r = -(x_s + 2 x_p) = -0.7 gives the internal
    mesh the sun mesh's working pressure angle, hence the same working centre distance (concentric).
    Sun mesh: inv a_wt = inv a_t + 2 tan a_n (x_s + x_p)/(z_s + z_p), a_w = (z_s + z_p) m_t cos a_t / (2 cos a_wt),
    tip alteration k = (a_w - a_d)/m_n - (x_s + x_p), d_a = d + 2 m_n (1 + x + k). Ring: d_a = d - 2 m_n (1 + x_r),
    inv a_wt = inv a_t + 2 tan a_n (x_p + x_r)/(z_p - z_r). Contact ratios as in scene A; overlap b sin(beta)/(pi m_n).
    ISO 6336-1 with z_n = z / (cos^2 b_b cos b), the shifts' terms C4..C9, cos(beta), and the load correction
    (F_t/b / 100)^0.25 since F_t/b = 98.9 N/mm < 100."""
    d = design_of(SCENE_B)
    st, nxt = d.stages
    p, pr = st.planetary, st.planetary.planet_ring
    m_n, a_n, beta = 3.0, math.radians(20.0), math.radians(15.0)
    m_t, a_t = m_n / math.cos(beta), math.atan(math.tan(a_n) / math.cos(beta))
    zs, zp, zr, xs, xp, xr = 21, 30, 81, 0.3, 0.2, -0.7
    a_wt = _inv_inverse(_inv(a_t) + 2 * math.tan(a_n) * (xs + xp) / (zs + zp))
    a_w = (zs + zp) * m_t * math.cos(a_t) / (2 * math.cos(a_wt))
    k = (a_w - 0.5 * (zs + zp) * m_t) / m_n - (xs + xp)
    d_s, d_p, d_r = zs * m_t, zp * m_t, zr * m_t
    da_s, da_p, da_r = d_s + 2 * m_n * (1 + xs + k), d_p + 2 * m_n * (1 + xp + k), d_r - 2 * m_n * (1 + xr)
    db_s, db_p, db_r = (x * math.cos(a_t) for x in (d_s, d_p, d_r))
    a_wt_r = _inv_inverse(_inv(a_t) + 2 * math.tan(a_n) * (xp + xr) / (zp - zr))
    a_w_r = (zr - zp) * m_t * math.cos(a_t) / (2 * math.cos(a_wt_r))
    p_bt = math.pi * m_t * math.cos(a_t)
    e_sp = (math.sqrt(da_s**2 - db_s**2) / 2 + math.sqrt(da_p**2 - db_p**2) / 2 - a_w * math.sin(a_wt)) / p_bt
    e_pr = (math.sqrt(da_p**2 - db_p**2) / 2 - math.sqrt(da_r**2 - db_r**2) / 2 + a_w_r * math.sin(a_wt_r)) / p_bt
    assert_allclose([st.working_pressure_angle_deg, pr.working_pressure_angle_deg], [math.degrees(a_wt)] * 2,
                    rtol=1e-12)
    assert_allclose([st.center_distance_mm, pr.center_distance_mm, a_w_r], [a_w] * 3, rtol=1e-12)
    assert_allclose([p.sun.tip_diameter_mm, p.planet.tip_diameter_mm, p.ring.tip_diameter_mm], [da_s, da_p, da_r],
                    rtol=1e-12)
    assert_allclose(p.ring.root_diameter_mm, d_r + 2 * m_n * (1.25 - xr), rtol=1e-12)
    assert_allclose([st.contact_ratio_transverse, pr.contact_ratio_transverse], [e_sp, e_pr], rtol=1e-11)
    assert_allclose([st.overlap_ratio, pr.overlap_ratio], [42 * math.sin(beta) / (math.pi * m_n)] * 2, rtol=1e-12)
    # forces: T_sun = T_out / (i_1 i_2), F_t = T_sun / (N r_s) at the reference pitch circle, F_a = F_t tan(beta)
    i_1, i_2 = 1 + zr / zs, 77 / 19
    t_sun = 8000e3 / (i_1 * i_2)
    f_t = t_sun / (3 * d_s / 2)
    for f in (st.static_force_N, pr.static_force_N):
        assert_allclose([f.tangential, f.axial, f.radial], [f_t, f_t * math.tan(beta), f_t * math.tan(a_t)],
                        rtol=1e-12)
    # ISO 6336-1, index 1 the smaller wheel (the sun; the planet against the ring)
    b_b = math.atan(math.tan(beta) * math.cos(a_t))
    c = (0.04723, 0.15551, 0.25791, -0.00635, -0.11654, -0.00193, -0.24188, 0.00529, 0.00182)

    def q(z1, z2, x1, x2):
        zn1 = z1 / (math.cos(b_b) ** 2 * math.cos(beta))
        inv2 = 0.0 if z2 is None else math.cos(b_b) ** 2 * math.cos(beta) / z2
        return (c[0] + c[1] / zn1 + c[2] * inv2 + c[3] * x1 + c[4] * x1 / zn1 + c[5] * x2 + c[6] * x2 * inv2
                + c[7] * x1**2 + c[8] * x2**2)

    correction = (f_t / 42 / 100) ** 0.25
    assert f_t / 42 < 100
    c_sp = 0.8 * 0.975 * math.cos(beta) * correction / q(zs, zp, xs, xp)
    c_pr = 0.8 * 0.975 * math.cos(beta) * correction / q(zp, None, xp, xr)
    assert_allclose([st.iso6336_single_pair_stiffness_N_mm_um, pr.iso6336_single_pair_stiffness_N_mm_um],
                    [c_sp, c_pr], rtol=1e-12)
    assert_allclose([st.iso6336_mesh_stiffness_N_mm_um, pr.iso6336_mesh_stiffness_N_mm_um],
                    [c_sp * (0.75 * e_sp + 0.25), c_pr * (0.75 * e_pr + 0.25)], rtol=1e-12)
    # the helical stage after it runs on the carrier: n = 1500 / i_1, T = T_sun i_1
    assert_allclose([nxt.pinion.speed_rpm, nxt.pinion.torque_Nm], [1500 / i_1, t_sun * i_1 / 1e3], rtol=1e-12)
    assert_allclose(nxt.static_force_N.tangential, t_sun * i_1 / (19 * 4.0 / math.cos(math.radians(12)) / 2),
                    rtol=1e-12)
    assert p.ring.hand == "right"  # an omitted ring hand takes the planet's


# ------------------------------------------------------------------- the internal pair's involute interference
@pytest.mark.parametrize(("shifts", "interferes"), [((0.0, 0.0, 0.0), False), ((0.9, -0.9, 0.9), True),
                                                    ((0.5, -0.5, 0.5), False)])
def test_ring_tip_inside_the_planet_tangent_point_warns_involute_interference(shifts, interferes):
    """Along the line of action the ring's tip point lies sqrt(r_ar^2 - r_br^2) from the ring's tangent point T2,
    the planet's tangent point T1 lies a_w sin(a_wt) from T2; a ring tip nearer T2 than T1 meets the planet below
    its base circle: involute interference, d_a,r < sqrt(d_b,r^2 + (2 a_w sin a_wt)^2). Shifts (x_s, x_p, x_r) with
    x_s + x_p = 0 = x_p + x_r keep a_w = 120 mm and a_wt = 20 deg on both meshes; the ring tip
    d_a = d - 2 m (1 + x_r) = 384 - 8 (1 + x_r): 376 (x_r 0), 368.8 (x_r 0.9, interferes), 372 (x_r 0.5)
    against d_a,min = sqrt(360.842^2 + (240 sin 20 deg)^2) = 370.06 mm."""
    x_s, x_p, x_r = shifts
    text = scene_a(sun=f", profile_shift = {x_s}", planet=f", profile_shift = {x_p}").replace(
        f"teeth = {Z_R},", f"teeth = {Z_R}, profile_shift = {x_r},")
    d = design_of(text)
    d_min = math.hypot(2 * RB_R, 2 * A_W * math.sin(ALPHA))
    assert_allclose(d_min, 370.061, atol=5e-4)
    assert_allclose(d.stages[0].planetary.ring.tip_diameter_mm, 2 * R_R - 2 * M_N * (1 + x_r), rtol=1e-14)
    hits = [w for w in d.warnings if "involute interference" in w]
    assert bool(hits) == interferes
    if interferes:
        assert "368.8 mm" in hits[0] and "370.1 mm" in hits[0]


def test_a_small_planet_in_a_large_ring_interferes():
    """Sun 60, six planets of 12, ring 84 (x = 0, m 4): d_a,r = 328 mm < sqrt((336 cos 20)^2 + (2 x 144 sin 20)^2)
    = 330.75 mm: the classic small-pinion internal-gear interference."""
    text = scene_a(6).replace(f"teeth = {Z_S},", "teeth = 60,").replace(f"teeth = {Z_P},", "teeth = 12,").replace(
        f"teeth = {Z_R},", "teeth = 84,")
    d = design_of(text)
    d_min = math.hypot(336 * math.cos(ALPHA), 2 * 144 * math.sin(ALPHA))
    assert_allclose(d_min, 330.745, atol=5e-4)
    assert any("involute interference" in w and "330.7 mm" in w for w in d.warnings)


def test_planet_ring_mesh_in_its_main_resonance_warns_as_any_mesh():
    """ISO 6336-1 for the planet–ring mesh: m_red = the planet's m* = J_p / (b r_bp^2) (the ring infinitely heavy;
    J_p of ISO's body, a disc of d_m = (d_a + d_f)/2 = (152 + 134)/2 mm), n_E1 = 30000/(pi z_p) sqrt(c_ga / m_red)
    in the planet's rpm relative to the carrier, N = n_p / n_E1, main resonance N_S = 0.85 < N <= 1.15. The sun
    mesh has its own N (here 0.41: no warning); the ring mesh's N went unchecked (and had no resonance_range)."""
    _, k_pr = _hand_k_sp_k_pr()
    c_ga = k_pr / B / 1e6  # N/(mm um)
    j_body = RHO * math.pi * B_M * (0.5 * (152 + 134) * 1e-3) ** 4 / 32 * 1e6  # kg mm^2
    m_red = j_body / (B * RB_P**2)  # kg/mm
    n_e1 = 30000 / (math.pi * Z_P) * math.sqrt(c_ga / m_red)
    n_sun = n_e1 / (Z_S / Z_P * (1 - 1 / (1 + U)))  # the planet at n_E1 relative to the carrier: N = 1
    d = design_of(scene_a().replace(f"speed_rpm = {N_IN}", f"speed_rpm = {n_sun!r}"))
    pr = d.stages[0].planetary.planet_ring
    assert_allclose([pr.resonance_speed_rpm, pr.resonance_ratio], [n_e1, 1.0], rtol=1e-9)
    assert pr.resonance_range == "main resonance"
    hits = [x for x in d.diagnostics if x.data.get("check") == "iso6336_resonance"]
    assert [x.data["mesh"] for x in hits] == ["planet_ring"] and "main resonance range" in hits[0].message
    calm = design_of(scene_a())  # 1500 rpm: N = 800 / n_E1 = 0.158
    assert calm.stages[0].planetary.planet_ring.resonance_range == "subcritical"
    assert not [x for x in calm.diagnostics if x.data.get("check") == "iso6336_resonance"]
