"""Tooth-thickness allowances on a planetary stage's planet–ring (internal) mesh, by hand (docs/planetary.md,
"Tooth-thickness allowances"; ISO 21771:2007 internal gears, DIN 3967 backlash).

Scene A: a spur stage, m 3, z 21/30/81, x +0.25/−0.25/+0.25 (Σx = 0 in both meshes: every working pressure angle is
20°), three planets, A_sn = [−0.060, −0.100] sun, [−0.070, −0.115] planet, [−0.120, −0.200] ring, the planet's tip
A_da = [0, −0.1]. Scene B: a helical stage, m_n 2.5, β 25°, z 17/25/67, x +0.4/+0.1/−0.6 (z_r − z_p = z_s + z_p, so
x_r = −x_s − 2 x_p keeps the planet on one carrier radius with α′ = α_wt of the sun mesh, 24.5715°), allowances on
the planet [−0.04, −0.09] (tip [0, −0.15]) and the ring [−0.08, −0.15].

Written out here, independent of gearcli.design.allowances_internal:
- x_E = x + A_sn/(2 m_n tan α_n) for the ring as for the planet (ISO 21771's internal-gear sign of x: a positive
  x thickens the ring's tooth on the reference circle, s_n = m_n (π/2 + 2 x tan α_n)); the ring's root, cut deeper
  into the rim by a thinner tooth: d_f = d + 2 m_n (h_fP* − x_E).
- The backlash as geometry: on the working circles (d_w = d cos α_t / cos α′ at the carrier's radius a′) the
  planet's tooth s_wp = d_wp (s_tp/d_p + inv α_t − inv α′), the ring's tooth s_wr = d_wr (s_tr/d_r − inv α_t + inv α′)
  (an internal tooth thickens outwards), the pitch p_w = π d_wp/z_p; j_t = p_w − s_wp − s_wr (the ring's space less
  the planet's tooth). j_n = j_t cos α′ cos β_b.
- DIN 3967 to first order: j_t = −(A_sn,p + A_sn,r)/cos β · cos α_t/cos α′ (spur at α′ = α: j_n = −ΣA_sn cos α).
- ε_α = [√(r_ap² − r_bp²) − √(r_ar² − r_br²) + a′ sin α′]/(π m_t cos α_t).
"""

from __future__ import annotations

import json
import math

import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli
from gearcli.design import rating_root as rr

SPUR = """
title = "spur planetary, allowances on sun, planet and ring"
[materials.steel]
density_kg_m3 = 7850
youngs_modulus_MPa = 206000
poisson_ratio = 0.3
treatment = "case_carburized"
contact_fatigue_limit_MPa = 1500
bending_fatigue_limit_MPa = 460
[[stage]]
type = "planetary"
normal_module_mm = 3
normal_pressure_angle_deg = 20
helix_angle_deg = 0
accuracy_grade = 6
sun    = { teeth = 21, face_width_mm = 40, profile_shift = 0.25, material = "steel", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 16, tooth_thickness_allowance_mm = [-0.060, -0.100] }
planet = { teeth = 30, face_width_mm = 40, profile_shift = -0.25, count = 3, material = "steel", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 16, tooth_thickness_allowance_mm = [-0.070, -0.115], tip_diameter_allowance_mm = [0.0, -0.1] }
ring   = { teeth = 81, face_width_mm = 40, profile_shift = 0.25, material = "steel", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 16, tooth_thickness_allowance_mm = [-0.120, -0.200] }
fixed = "ring"
input = "sun"
[input]
speed_rpm = 1450
[load]
torque_Nm = 2500
[lubricant]
viscosity_40C_mm2_s = 220
[rating]
required_life_h = 20000
"""

HELICAL = """
title = "helical planetary, beta 25, shifted, allowances on planet and ring"
[materials.steel]
density_kg_m3 = 7850
youngs_modulus_MPa = 206000
poisson_ratio = 0.3
[[stage]]
type = "planetary"
normal_module_mm = 2.5
normal_pressure_angle_deg = 20
helix_angle_deg = 25
sun    = { teeth = 17, face_width_mm = 30, profile_shift = 0.4, hand = "left", material = "steel" }
planet = { teeth = 25, face_width_mm = 30, profile_shift = 0.1, hand = "right", count = 3, material = "steel", tooth_thickness_allowance_mm = [-0.04, -0.09], tip_diameter_allowance_mm = [0.0, -0.15] }
ring   = { teeth = 67, face_width_mm = 30, profile_shift = -0.6, hand = "right", material = "steel", tooth_thickness_allowance_mm = [-0.08, -0.15] }
fixed = "ring"
input = "sun"
[input]
speed_rpm = 3000
[load]
torque_Nm = 300
"""


def _inv(a: float) -> float:
    return math.tan(a) - a


def _inv_inverse(v: float) -> float:
    a = 0.5
    for _ in range(100):  # Newton on tan a − a − v
        a -= (_inv(a) - v) / math.tan(a) ** 2
    return a


class Scene:
    """One stage's planet–ring mesh by hand."""

    def __init__(self, m_n: float, beta_deg: float, z: tuple[int, int, int], x: tuple[float, float, float],
                 planet_a: tuple[float, float], ring_a: tuple[float, float], planet_tip_a: tuple[float, float]):
        self.m_n, self.alpha = m_n, math.radians(20.0)
        self.beta = math.radians(beta_deg)
        self.z, self.x, self.planet_a, self.ring_a, self.tip_a = z, x, planet_a, ring_a, planet_tip_a
        self.m_t = m_n / math.cos(self.beta)
        self.alpha_t = math.atan(math.tan(self.alpha) / math.cos(self.beta))
        self.beta_b = math.atan(math.tan(self.beta) * math.cos(self.alpha_t))
        self.d = tuple(zi * self.m_t for zi in z)  # sun, planet, ring
        self.d_b = tuple(di * math.cos(self.alpha_t) for di in self.d)
        # the carrier's radius: the sun–planet working centre distance
        self.alpha_w = _inv_inverse(_inv(self.alpha_t) + 2 * math.tan(self.alpha) * (x[0] + x[1]) / (z[0] + z[1]))
        self.a_w = 0.5 * (self.d[0] + self.d[1]) * math.cos(self.alpha_t) / math.cos(self.alpha_w)
        k = (self.a_w - 0.5 * (self.d[0] + self.d[1])) / m_n - (x[0] + x[1])  # tip alteration of the sun mesh
        self.planet_tip = self.d[1] + 2 * m_n * (1 + x[1] + k)
        self.ring_tip = self.d[2] - 2 * m_n * (1 + x[2])  # no tip alteration on the ring

    def x_e(self, member: int, j: int) -> float:
        a = (self.planet_a, self.ring_a)[member - 1][j]
        return self.x[member] + a / (2 * self.m_n * math.tan(self.alpha))

    def ring_root(self, j: int) -> float:
        return self.d[2] + 2 * self.m_n * (1.25 - self.x_e(2, j))

    def backlash(self, j: int) -> float:
        """Pitch on the planet's working circle less the planet's and the ring's tooth thicknesses there."""
        alpha = math.acos((self.d_b[2] - self.d_b[1]) / (2 * self.a_w))
        d_wp, d_wr = self.d_b[1] / math.cos(alpha), self.d_b[2] / math.cos(alpha)
        s_tp = self.m_t * (math.pi / 2 + 2 * self.x_e(1, j) * math.tan(self.alpha))
        s_tr = self.m_t * (math.pi / 2 + 2 * self.x_e(2, j) * math.tan(self.alpha))
        s_wp = d_wp * (s_tp / self.d[1] + _inv(self.alpha_t) - _inv(alpha))
        s_wr = d_wr * (s_tr / self.d[2] - _inv(self.alpha_t) + _inv(alpha))
        return math.pi * d_wp / self.z[1] - s_wp - s_wr

    def to_normal(self) -> float:
        return math.cos(math.acos((self.d_b[2] - self.d_b[1]) / (2 * self.a_w))) * math.cos(self.beta_b)

    def eps(self, planet_tip: float) -> float:
        alpha = math.acos((self.d_b[2] - self.d_b[1]) / (2 * self.a_w))
        path = (math.sqrt(planet_tip ** 2 - self.d_b[1] ** 2) / 2 - math.sqrt(self.ring_tip ** 2 - self.d_b[2] ** 2) / 2
                + self.a_w * math.sin(alpha))
        return path / (math.pi * self.m_t * math.cos(self.alpha_t))


A = Scene(3.0, 0.0, (21, 30, 81), (0.25, -0.25, 0.25), (-0.070, -0.115), (-0.120, -0.200), (0.0, -0.1))
B = Scene(2.5, 25.0, (17, 25, 67), (0.4, 0.1, -0.6), (-0.04, -0.09), (-0.08, -0.15), (0.0, -0.15))


def _run(tmp_path, text: str, *args: str):
    path = tmp_path / "ring_allowances.toml"
    path.write_text(text)
    return CliRunner().invoke(cli, ["design", str(path), *args])


def _design(tmp_path, text: str, *args: str) -> dict:
    res = _run(tmp_path, text, "--format", "json", *args)
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


@pytest.mark.parametrize(("text", "hand"), [(SPUR, A), (HELICAL, B)], ids=["spur", "helical"])
def test_ring_generating_shift_and_root_by_hand(tmp_path, text, hand):
    st = _design(tmp_path, text)["stages"][0]
    assert_allclose(st["ring"]["generating_profile_shift"], [hand.x_e(2, 0), hand.x_e(2, 1)], rtol=0, atol=1e-12)
    assert_allclose(st["ring"]["manufactured_root_diameter_mm"], [hand.ring_root(0), hand.ring_root(1)],
                    rtol=1e-12)
    # the thinner tooth is cut deeper into the rim: the lower allowance's root is the larger diameter
    assert st["ring"]["manufactured_root_diameter_mm"][1] > st["ring"]["manufactured_root_diameter_mm"][0] \
        > st["ring"]["root_diameter_mm"]


@pytest.mark.parametrize(("text", "hand"), [(SPUR, A), (HELICAL, B)], ids=["spur", "helical"])
def test_planet_ring_backlash_from_the_tooth_thicknesses(tmp_path, text, hand):
    """j_t [max, min]: the thinnest teeth (x_E,i of planet and ring) and the thickest, on the carrier's radius."""
    mesh = _design(tmp_path, text)["stages"][0]["meshes"][1]
    assert mesh["name"] == "planet_ring"
    j = [hand.backlash(1), hand.backlash(0)]
    assert_allclose(mesh["backlash_circumferential_mm"], j, rtol=1e-9)
    assert_allclose(mesh["backlash_normal_mm"], [v * hand.to_normal() for v in j], rtol=1e-9)


def test_planet_ring_backlash_against_din_3967(tmp_path):
    """First order in the allowances (exact here up to round-off: the planet sits where both meshes are
    backlash-free with nominal teeth): j_t = −(A_sn,p + A_sn,r)/cos β · cos α_t/cos α′; spur: j_n = −ΣA_sn cos α."""
    spur = _design(tmp_path, SPUR)["stages"][0]["meshes"][1]
    assert_allclose(spur["backlash_circumferential_mm"], [0.115 + 0.200, 0.070 + 0.120], rtol=1e-9)
    assert_allclose(spur["backlash_normal_mm"], [0.315 * math.cos(A.alpha), 0.190 * math.cos(A.alpha)], rtol=1e-9)
    helical = _design(tmp_path, HELICAL)["stages"][0]["meshes"][1]
    scale = math.cos(B.alpha_t) / (math.cos(B.beta) * math.cos(B.alpha_w))
    assert_allclose(helical["backlash_circumferential_mm"], [0.24 * scale, 0.12 * scale], rtol=1e-9)
    assert_allclose(helical["working_pressure_angle_deg"], 24.571487714713086, rtol=1e-12)  # α′ = α_wt, hand


@pytest.mark.parametrize(("text", "hand"), [(SPUR, A), (HELICAL, B)], ids=["spur", "helical"])
def test_planet_ring_contact_ratio_with_the_planet_tip_allowance(tmp_path, text, hand):
    mesh = _design(tmp_path, text)["stages"][0]["meshes"][1]
    tips = [hand.planet_tip + hand.tip_a[0], hand.planet_tip + 0.5 * sum(hand.tip_a), hand.planet_tip + hand.tip_a[1]]
    assert_allclose(mesh["contact_ratio_transverse_with_allowances"], [hand.eps(t) for t in tips], rtol=1e-9)
    assert_allclose(mesh["contact_ratio_transverse"], hand.eps(hand.planet_tip), rtol=1e-9)


def test_ring_root_rated_at_its_generating_shift(tmp_path):
    """ISO 6336-3: the ring's root at x_E of the chosen allowance (default the lower: the thinnest tooth), at x with
    "nominal"; the thinner tooth carries the higher nominal root stress."""
    stress = {}
    for choice, x in (("lower", A.x_e(2, 1)), ("upper", A.x_e(2, 0)), ("nominal", A.x[2])):
        st = _design(tmp_path, SPUR, "--set", f'rating.root_profile_shift="{choice}"')["stages"][0]
        mesh = st["meshes"][1]
        ring = mesh["rating"]["gear"]
        form = rr.internal_tooth_form(81, 3.0, A.alpha, 0.0, 0.0, x, st["ring"]["tip_diameter_mm"], 243.0,
                                      mesh["contact_ratio_transverse"], (1.25, 0.38))
        assert_allclose([ring["Y_F"], ring["Y_S"]], [form["Y_F"], form["Y_S"]], rtol=1e-12)
        stress[choice] = ring["sigma_F0_MPa"]
    assert stress["lower"] > stress["upper"] > stress["nominal"]


def test_only_the_sun_s_allowances_add_nothing_to_the_ring_mesh(tmp_path):
    text = SPUR.replace(", tooth_thickness_allowance_mm = [-0.070, -0.115], tip_diameter_allowance_mm = [0.0, -0.1]",
                        "").replace(", tooth_thickness_allowance_mm = [-0.120, -0.200]", "")
    st = _design(tmp_path, text)["stages"][0]
    assert "backlash_circumferential_mm" in st["meshes"][0]
    assert "backlash_circumferential_mm" not in st["meshes"][1]
    assert "generating_profile_shift" not in st["ring"]


def test_the_ring_alone_gives_the_planet_ring_backlash(tmp_path):
    """Only the ring thinned: j_t = −A_sn,r on the spur mesh (the planet at its nominal x)."""
    text = SPUR.replace(", tooth_thickness_allowance_mm = [-0.070, -0.115], tip_diameter_allowance_mm = [0.0, -0.1]",
                        "")
    mesh = _design(tmp_path, text)["stages"][0]["meshes"][1]
    assert_allclose(mesh["backlash_circumferential_mm"], [0.200, 0.120], rtol=1e-9)
    assert_allclose(mesh["contact_ratio_transverse_with_allowances"], [mesh["contact_ratio_transverse"]] * 3,
                    rtol=1e-12)


def test_thickened_ring_teeth_jam_and_warn(tmp_path):
    """Positive ring allowances [+0.3, +0.1] with the planet's [−0.070, −0.115]: j_t = [0.015, −0.230] mm."""
    data = _design(tmp_path, SPUR.replace("[-0.120, -0.200]", "[0.3, 0.1]"))
    assert_allclose(data["stages"][0]["meshes"][1]["backlash_circumferential_mm"], [0.015, -0.230], atol=1e-12)
    jam = [w for w in data["warnings"] if w.get("check") == "backlash_negative"]
    assert len(jam) == 1 and jam[0]["mesh"] == "planet_ring"
    assert_allclose(jam[0]["backlash_min_mm"], -0.230, atol=1e-12)


def test_a_planet_tip_allowance_that_interrupts_the_ring_contact_warns(tmp_path):
    """A_da,i = −8 mm on the planet (m 3) drops ε_α,i of the ring mesh below 1 (by hand) while the nominal is 2.08."""
    data = _design(tmp_path, SPUR.replace("tip_diameter_allowance_mm = [0.0, -0.1]",
                                          "tip_diameter_allowance_mm = [0.0, -8.0]"))
    eps_i = A.eps(A.planet_tip - 8.0)
    assert eps_i < 1.0
    mesh = data["stages"][0]["meshes"][1]
    assert_allclose(mesh["contact_ratio_transverse_with_allowances"][2], eps_i, rtol=1e-9)
    found = [w.get("mesh") for w in data["warnings"] if w.get("check") == "contact_ratio_allowances"]
    assert found.count("planet_ring") == 1  # (the sun–planet mesh's, which the same tip interrupts, is "sun_planet")


@pytest.mark.parametrize(("new", "key"), [
    ("[-0.200, -0.120]", "stage[0].ring"),  # upper below lower
    ("[nan, -0.1]", "stage[0].ring.tooth_thickness_allowance_mm[0]"),
    ('["thin", -0.1]', "stage[0].ring.tooth_thickness_allowance_mm[0]"),
    ("[5.0, 4.9]", "stage[0].ring.tooth_thickness_allowance_mm"),  # x_E +2.5: the root cut inside the tip
])
def test_bad_ring_allowances_exit_2_naming_file_and_key(tmp_path, new, key):
    res = _run(tmp_path, SPUR.replace("[-0.120, -0.200]", new), "--format", "json")
    assert res.exit_code == 2, res.output
    assert key in res.output and "ring_allowances.toml" in res.output and "Traceback" not in res.output


def _ring_tip_thickness_by_hand(z: int, m: float, x: float, tip: float) -> float:
    """Spur: the ring's tooth is the tooth space of the external gear of the same z cut at −x (the internal gear is
    the external one's negative): e_y = π d_y/z − d_y (s(−x)/d + inv α − inv α_y), s(−x) = m (π/2 − 2 x tan α)."""
    alpha = math.radians(20.0)
    d = z * m
    alpha_y = math.acos(d * math.cos(alpha) / tip)
    s_minus = m * (math.pi / 2 - 2 * x * math.tan(alpha))
    return math.pi * tip / z - tip * (s_minus / d + _inv(alpha) - _inv(alpha_y))


def test_a_ring_thinned_to_a_thin_tip_warns(tmp_path):
    """A_sn,r = [−2.3, −2.5] mm (m 3): x_E,i = 0.25 − 2.5/(6 tan 20°) = −0.8947; the ring's tip thickness at
    d_a = 235.5 mm by hand, 0.3777 mm < 0.2 m = 0.6 mm: warned (`tip_thickness`, member ring); the nominal ring
    (x = 0.25: 2.80 mm) is not."""
    x_e = 0.25 - 2.5 / (6 * math.tan(math.radians(20.0)))
    s = _ring_tip_thickness_by_hand(81, 3.0, x_e, 235.5)
    assert_allclose(s, 0.3777, atol=1e-4)
    data = _design(tmp_path, SPUR.replace("[-0.120, -0.200]", "[-2.3, -2.5]"))
    found = [w for w in data["warnings"] if w.get("check") == "tip_thickness" and w.get("member") == "ring"]
    assert len(found) == 1
    assert_allclose(found[0]["tip_thickness_mm"], s, rtol=1e-9)
    assert_allclose(found[0]["generating_profile_shift"], x_e, rtol=1e-12)
    assert _ring_tip_thickness_by_hand(81, 3.0, 0.25, 235.5) > 0.6
    nominal = _design(tmp_path, SPUR)
    assert not [w for w in nominal["warnings"] if w.get("check") == "tip_thickness"]


def test_the_ring_tip_thickness_tends_to_the_rack_s():
    """z → ∞: the rack's tooth at its tip, π m/2 − 2 h_a tan α with h_a = m (1 + x) measured from a reference line
    the shift moves by x m: π m/2 − 2 m tan α whatever x."""
    from gearcli.design.allowances_internal import internal_normal_tip_thickness_mm

    m, z = 4.0, 200000
    for x in (-0.5, 0.0, 0.3):
        s = internal_normal_tip_thickness_mm(z, m, x, 0.0, math.radians(20.0), z * m - 2 * m * (1 + x))
        assert_allclose(s, m * (math.pi / 2 - 2 * math.tan(math.radians(20.0))), rtol=1e-4)


def test_a_thickened_ring_s_root_under_the_planet_tip_warns(tmp_path):
    """Ring A_sn = [+0.8, +0.6] (m 3): x_E,e = 0.25 + 0.8/(6 tan 20°) = 0.61633, its root d_f,e = 243 + 6 (1.25 −
    0.61633) = 246.802 mm; the planet's largest tip (d_a + A_dae = 94.5 mm) on the carrier's radius 76.5 mm leaves
    c = 246.802/2 − 76.5 − 94.5/2 = −0.349 mm: warned (`tip_clearance`, mesh planet_ring, member planet). The ring's
    tip against the planet's highest root, 235.5/2 − 76.5 − d_f,e,p/2 = +0.846 mm, is not; neither is in the JSON."""
    x_e = 0.25 + 0.8 / (6 * math.tan(math.radians(20.0)))
    c_planet = (243 + 6 * (1.25 - x_e)) / 2 - 76.5 - A.planet_tip / 2
    assert_allclose(c_planet, -0.349, atol=5e-4)
    planet_root = A.d[1] + 2 * 3.0 * (A.x_e(1, 0) - 1.25)
    assert_allclose(A.ring_tip / 2 - 76.5 - planet_root / 2, 0.846, atol=5e-4)
    data = _design(tmp_path, SPUR.replace("[-0.120, -0.200]", "[0.8, 0.6]"))
    found = [w for w in data["warnings"] if w.get("check") == "tip_clearance"]
    assert len(found) == 1 and found[0]["mesh"] == "planet_ring" and found[0]["member"] == "planet"
    assert_allclose(found[0]["tip_clearance_mm"], c_planet, rtol=1e-9)
    assert "tip_clearance_with_allowances_mm" not in data["stages"][0]["meshes"][1]
    assert not [w for w in _design(tmp_path, SPUR)["warnings"] if w.get("check") == "tip_clearance"]
