"""Tooth-thickness and centre-distance allowances on scenes of their own, checked against hand calculations written
out here (independent of gearcli.design.allowances), and hostile allowances: exit 2 naming the key, or a warning.

Scene 1: a helical industrial stage, m_n 4, α_n 20°, β 12°, z 23/71, x +0.3/−0.1, b 60/55, DIN 3967 allowances
A_sn = [−0.070, −0.130] mm (pinion), [−0.100, −0.170] mm (wheel), centre distance js7 ±0.023 mm.
Scene 2: a spur planetary stage, m 3, z 21/30/81, x +0.25/−0.25/+0.25, three planets, allowances on sun and planet.

References:
- ISO 21771 / DIN 3960: x_E = x + A_sn/(2 m_n tan α_n); d_f = d + 2 x_E m_n − 2 h_fP.
- The transverse backlash on the working circle as pitch minus both tooth thicknesses there (DIN 3960):
  s_wt = d_w (s_t/d + inv α_t − inv α_wt), s_t = m_t (π/2 + 2 x_E tan α_n), p_wt = π d_w1/z1.
- DIN 3967 (first order): j_t = −(A_sn1 + A_sn2)/cos β · (d_w/d) + 2 A_a tan α_wt; j_n = j_t cos α_wt cos β_b.
- ε_α = (√(r_a1² − r_b1²) + √(r_a2² − r_b2²) − a′ sin α′)/p_bt at a′ with cos α′ = a cos α_t / a′.
- ISO 6336-3:2006 method B Y_F, Y_S written out below (basic rack 1.25/0.38, no protuberance), at x_E,i.
"""

from __future__ import annotations

import json
import math
import os
import tempfile
from pathlib import Path

import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

HELICAL = """
title = "helical allowances"
[materials.steel]
density_kg_m3 = 7850
youngs_modulus_MPa = 206000
poisson_ratio = 0.3
treatment = "case_carburized"
contact_fatigue_limit_MPa = 1500
bending_fatigue_limit_MPa = 460

[[stage]]
normal_module_mm = 4
normal_pressure_angle_deg = 20
helix_angle_deg = 12
accuracy_grade = 6
center_distance_allowance_mm = [0.023, -0.023]
pinion = { teeth = 23, face_width_mm = 60, profile_shift = 0.3, hand = "right", material = "steel", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 16, tooth_thickness_allowance_mm = [-0.070, -0.130] }
gear = { teeth = 71, face_width_mm = 55, profile_shift = -0.1, hand = "left", material = "steel", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 16, tooth_thickness_allowance_mm = [-0.100, -0.170] }

[input]
speed_rpm = 1480
[load]
torque_Nm = 1200
application_factor = 1.25
[lubricant]
viscosity_40C_mm2_s = 220
[rating]
required_life_h = 20000
"""

PLANETARY = """
title = "spur planetary with allowances"
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
accuracy_grade = 6
sun    = { teeth = 21, face_width_mm = 40, profile_shift = 0.25, material = "steel", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 16, tooth_thickness_allowance_mm = [-0.060, -0.100] }
planet = { teeth = 30, face_width_mm = 40, profile_shift = -0.25, count = 3, material = "steel", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 16, tooth_thickness_allowance_mm = [-0.070, -0.115] }
ring   = { teeth = 81, face_width_mm = 40, profile_shift = 0.25, material = "steel", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 16 }
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

M, ALPHA, BETA = 4.0, math.radians(20.0), math.radians(12.0)
Z = (23, 71)
X = (0.3, -0.1)
A_SN = ((-0.070, -0.130), (-0.100, -0.170))
A_A = (0.023, -0.023)


def _inv(a: float) -> float:
    return math.tan(a) - a


def _inv_inverse(v: float) -> float:
    a = 0.5
    for _ in range(100):  # Newton on tan a − a − v, d/da = tan² a
        a -= (_inv(a) - v) / math.tan(a) ** 2
    return a


def _run(text: str, *args: str):
    fd, name = tempfile.mkstemp(prefix="allow_hand_", suffix=".toml")  # a file of its own per xdist worker
    os.close(fd)
    path = Path(name)
    try:
        path.write_text(text)
        return CliRunner().invoke(cli, ["design", str(path), *args])
    finally:
        path.unlink(missing_ok=True)


def _design(text: str) -> dict:
    res = _run(text, "--format", "json")
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


class Hand:
    """The helical scene's geometry by hand (DIN 3960 / ISO 21771)."""

    m_t = M / math.cos(BETA)
    alpha_t = math.atan(math.tan(ALPHA) / math.cos(BETA))
    beta_b = math.atan(math.tan(BETA) * math.cos(alpha_t))
    d = (Z[0] * m_t, Z[1] * m_t)
    d_b = (d[0] * math.cos(alpha_t), d[1] * math.cos(alpha_t))
    alpha_w = _inv_inverse(_inv(alpha_t) + 2 * math.tan(ALPHA) * sum(X) / sum(Z))
    a = 0.5 * sum(d)
    a_w = a * math.cos(alpha_t) / math.cos(alpha_w)
    k = (a_w - a) / M - sum(X)  # tip alteration (negative: tips shortened)
    d_a = (d[0] + 2 * M * (1 + X[0] + k), d[1] + 2 * M * (1 + X[1] + k))

    @staticmethod
    def x_e(i: int, j: int) -> float:
        return X[i] + A_SN[i][j] / (2 * M * math.tan(ALPHA))

    @classmethod
    def backlash_by_thickness(cls, x_e: tuple[float, float], a_prime: float) -> float:
        """p_wt − s_wt1 − s_wt2 on the working circle at a′ (DIN 3960's tooth thickness at any diameter)."""
        alpha = math.acos(cls.a * math.cos(cls.alpha_t) / a_prime)
        d_w = [di * math.cos(cls.alpha_t) / math.cos(alpha) for di in cls.d]
        s_t = [cls.m_t * (math.pi / 2 + 2 * x * math.tan(ALPHA)) for x in x_e]
        s_w = [d_w[i] * (s_t[i] / cls.d[i] + _inv(cls.alpha_t) - _inv(alpha)) for i in (0, 1)]
        return math.pi * d_w[0] / Z[0] - s_w[0] - s_w[1]

    @classmethod
    def contact_ratio(cls, a_prime: float, tips: tuple[float, float]) -> float:
        alpha = math.acos(cls.a * math.cos(cls.alpha_t) / a_prime)
        p_bt = math.pi * cls.m_t * math.cos(cls.alpha_t)
        return (sum(math.sqrt(tips[i] ** 2 - cls.d_b[i] ** 2) / 2 for i in (0, 1)) - a_prime * math.sin(alpha)) / p_bt


def _y_f_y_s(z: int, m: float, alpha_n: float, beta: float, x: float, d_a: float, eps_alpha: float,
             h_fp: float = 1.25, rho_fp: float = 0.38) -> tuple[float, float]:
    """ISO 6336-3:2006 method B, eqs. (10)-(24) for an external gear cut by a rack without protuberance, loaded at
    the outer point of single-pair contact; z_n = z/(cos² β_b cos β)."""
    alpha_t = math.atan(math.tan(alpha_n) / math.cos(beta))
    beta_b = math.atan(math.tan(beta) * math.cos(alpha_t))
    z_n = z / (math.cos(beta_b) ** 2 * math.cos(beta))
    e = math.pi / 4 * m - h_fp * m * math.tan(alpha_n) - (1 - math.sin(alpha_n)) * rho_fp * m / math.cos(alpha_n)
    g = rho_fp - h_fp + x
    h = 2 / z_n * (math.pi / 2 - e / m) - math.pi / 3
    theta = math.pi / 6
    for _ in range(200):
        theta = 2 * g / z_n * math.tan(theta) - h
    s_fn = z_n * math.sin(math.pi / 3 - theta) + math.sqrt(3) * (g / math.cos(theta) - rho_fp)
    rho_f = rho_fp + 2 * g ** 2 / (math.cos(theta) * (z_n * math.cos(theta) ** 2 - 2 * g))
    d = z * m / math.cos(beta)
    eps_an = eps_alpha / math.cos(beta_b) ** 2
    d_n = z_n * m
    d_bn, d_an = d_n * math.cos(alpha_n), d_n + d_a - d
    d_en = 2 * math.sqrt((math.sqrt(d_an ** 2 / 4 - d_bn ** 2 / 4)
                          - math.pi * d * math.cos(beta) * math.cos(alpha_n) / z * (eps_an - 1)) ** 2 + d_bn ** 2 / 4)
    alpha_en = math.acos(d_bn / d_en)
    gamma_e = (0.5 * math.pi + 2 * x * math.tan(alpha_n)) / z_n + _inv(alpha_n) - _inv(alpha_en)
    alpha_fen = alpha_en - gamma_e
    h_fe = 0.5 * ((math.cos(gamma_e) - math.sin(gamma_e) * math.tan(alpha_fen)) * d_en / m
                  - z_n * math.cos(math.pi / 3 - theta) - g / math.cos(theta) + rho_fp)
    y_f = 6 * h_fe * math.cos(alpha_fen) / (s_fn ** 2 * math.cos(alpha_n))
    big_l, q_s = s_fn / h_fe, s_fn / (2 * rho_f)
    return y_f, (1.2 + 0.13 * big_l) * q_s ** (1 / (1.21 + 2.3 / big_l))


# ------------------------------------------------------------------------------------------- helical stage
@pytest.fixture(scope="module")
def helical() -> dict:
    return _design(HELICAL)


def test_helical_generating_shifts_and_roots(helical):
    st = helical["stages"][0]
    # pinion: 0.3 − 0.070/(8 tan 20°) = 0.3 − 0.024040 = 0.275960; 0.3 − 0.130/2.911762 = 0.255353
    assert_allclose(st["pinion"]["generating_profile_shift"], [0.275960, 0.255353], atol=1e-6)
    assert_allclose(st["gear"]["generating_profile_shift"], [-0.134343, -0.158384], atol=1e-6)
    for i, part in enumerate(("pinion", "gear")):
        d_f = [Hand.d[i] + 2 * Hand.x_e(i, j) * M - 2 * 1.25 * M for j in (0, 1)]
        assert_allclose(st[part]["manufactured_root_diameter_mm"], d_f, rtol=1e-12)
    assert_allclose(st["pinion"]["manufactured_root_diameter_mm"][0], 86.2630, atol=1e-4)  # 94.0553 − 7.7923


def test_helical_backlash_from_tooth_thicknesses(helical):
    """Exact: pitch on the working circle less both cut thicknesses there; max at x_E,i and a_w + A_ae, min at
    x_E,e and a_w + A_ai."""
    st = helical["stages"][0]
    assert_allclose(Hand.a_w, st["center_distance_mm"], rtol=1e-12)
    j_max = Hand.backlash_by_thickness((Hand.x_e(0, 1), Hand.x_e(1, 1)), Hand.a_w + A_A[0])
    j_min = Hand.backlash_by_thickness((Hand.x_e(0, 0), Hand.x_e(1, 0)), Hand.a_w + A_A[1])
    assert_allclose(st["backlash_circumferential_mm"], [j_max, j_min], rtol=1e-9)
    # j_n = j_t cos α′ cos β_b at each limit's own centre distance
    cos_a = [Hand.a * math.cos(Hand.alpha_t) / (Hand.a_w + da) for da in A_A]
    assert_allclose(st["backlash_normal_mm"], [j_max * cos_a[0] * math.cos(Hand.beta_b),
                                               j_min * cos_a[1] * math.cos(Hand.beta_b)], rtol=1e-9)


def test_helical_backlash_against_din_3967(helical):
    """DIN 3967's first-order sum: j_t = −ΣA_sn/cos β · cos α_t/cos α_wt ± 2 |A_a| tan α_wt. The second-order
    terms are (A_a/a)·j ~ 1e-4 relative: 2e-4 here."""
    st = helical["stages"][0]
    scale = math.cos(Hand.alpha_t) / math.cos(Hand.alpha_w) / math.cos(BETA)
    centre = 2 * A_A[0] * math.tan(Hand.alpha_w)  # 0.046 tan 21.03° = 0.017685 mm
    j_max = -(A_SN[0][1] + A_SN[1][1]) * scale + centre  # 0.300 · 1.02654 + 0.0177 = 0.3257
    j_min = -(A_SN[0][0] + A_SN[1][0]) * scale - centre  # 0.170 · 1.02654 − 0.0177 = 0.1568
    assert_allclose(st["backlash_circumferential_mm"], [j_max, j_min], rtol=2e-4)
    assert_allclose(st["backlash_circumferential_mm"], [0.3257, 0.1568], atol=1e-4)
    # DIN 3967's reference-circle conversion j_n ≈ j_t cos α_n cos β is within 0.5 % of j_t cos α_wt cos β_b here
    assert_allclose(st["backlash_normal_mm"],
                    [j * math.cos(ALPHA) * math.cos(BETA) for j in st["backlash_circumferential_mm"]], rtol=5e-3)


def test_helical_contact_ratio_with_allowances(helical):
    st = helical["stages"][0]
    tips = (Hand.d_a[0], Hand.d_a[1])
    expected = [Hand.contact_ratio(Hand.a_w + A_A[1], tips), Hand.contact_ratio(Hand.a_w, tips),
                Hand.contact_ratio(Hand.a_w + A_A[0], tips)]
    assert_allclose(st["contact_ratio_transverse_with_allowances"], expected, rtol=1e-9)
    assert_allclose(expected, [1.57426, 1.56893, 1.56361], atol=1e-5)


def test_helical_root_rated_at_the_lower_generating_shift(helical):
    """Default [rating] root_profile_shift = "lower": Y_F, Y_S of method B at x_E,i; K_Fβ with N_F from the deepest
    cut tooth h = (d_a − d_f,i)/2 (here the wheel's)."""
    st = helical["stages"][0]
    r = st["rating"]
    eps = st["contact_ratio_transverse"]
    for i, part in enumerate(("pinion", "gear")):
        y_f, y_s = _y_f_y_s(Z[i], M, ALPHA, BETA, Hand.x_e(i, 1), st[part]["tip_diameter_mm"], eps)
        assert_allclose([r[part]["Y_F"], r[part]["Y_S"]], [y_f, y_s], rtol=1e-9)
        nominal = _y_f_y_s(Z[i], M, ALPHA, BETA, X[i], st[part]["tip_diameter_mm"], eps)
        assert r[part]["Y_F"] > nominal[0]  # the thinned tooth is weaker: Y_F 1.273 vs 1.190 on the pinion
    h = max((st[p]["tip_diameter_mm"] - st[p]["manufactured_root_diameter_mm"][1]) / 2 for p in ("pinion", "gear"))
    b_h = 55.0 / h
    n_f = b_h ** 2 / (1 + b_h + b_h ** 2)
    assert_allclose(r["K_Fbeta"], r["K_Hbeta"] ** n_f, rtol=1e-12)


# ------------------------------------------------------------------------------------------- planetary stage
def test_planetary_sun_planet_backlash_and_roots():
    """x_s + x_p = 0: the working circle is the reference circle; j_t = −ΣA_sn (spur), j_n = j_t cos 20°. The planet
    root is rated at its x_E,i in both its meshes (each with its own ε_α)."""
    doc = _design(PLANETARY)
    st = doc["stages"][0]
    sun_planet, planet_ring = st["meshes"]
    assert_allclose(sun_planet["backlash_circumferential_mm"], [0.100 + 0.115, 0.060 + 0.070], rtol=1e-9)
    assert_allclose(sun_planet["backlash_normal_mm"], [0.215 * math.cos(ALPHA), 0.130 * math.cos(ALPHA)], rtol=1e-9)
    x_e = {"sun": 0.25 - 0.100 / (6 * math.tan(ALPHA)), "planet": -0.25 - 0.115 / (6 * math.tan(ALPHA))}
    assert_allclose(st["sun"]["generating_profile_shift"][1], x_e["sun"], rtol=1e-12)
    assert_allclose(st["planet"]["manufactured_root_diameter_mm"][1], 90 + 6 * x_e["planet"] - 7.5, rtol=1e-12)
    for mesh, part, member, z in ((sun_planet, "pinion", "sun", 21), (sun_planet, "gear", "planet", 30),
                                  (planet_ring, "pinion", "planet", 30)):
        y_f, y_s = _y_f_y_s(z, 3.0, ALPHA, 0.0, x_e[member], st[member]["tip_diameter_mm"],
                            mesh["contact_ratio_transverse"])
        assert_allclose([mesh["rating"][part]["Y_F"], mesh["rating"][part]["Y_S"]], [y_f, y_s], rtol=1e-9)
    # its one warning: the ring's tip (d_a = 243 − 6 × 1.25 = 235.5 mm) meets the planet (x = −0.25: its involute form
    # circle high) 1.788 mm along the line of action inside its root fillet (tests/reference/
    # test_planet_ring_fillet_interference.py has the hand formulas)
    assert [(w["check"], w["mesh"]) for w in doc["warnings"]] == [("interference", "planet_ring")]
    assert_allclose(doc["warnings"][0]["depth_mm"], 1.788, atol=1e-3)


# ------------------------------------------------------------------------------------------- hostile inputs
@pytest.mark.parametrize("text, old, new, key, words", [
    # the smallest centre distance below r_b1 + r_b2: no line of action
    (HELICAL, "[0.023, -0.023]", "[0.023, -20]", "stage[0].center_distance_allowance_mm", "(d_b1 + d_b2)/2"),
    # the largest centre distance so far apart that the tips never meet (ε_α < 0)
    (HELICAL, "[0.023, -0.023]", "[45, 40]", "stage[0].center_distance_allowance_mm", "lose contact"),
    # a lower tip below the base circle
    (HELICAL, "[-0.070, -0.130] }", "[-0.070, -0.130], tip_diameter_allowance_mm = [0, -20] }",
     "stage[0].pinion.tip_diameter_allowance_mm", "base circle"),
    # thinned so far that no backlash-free mesh of the cut teeth exists
    (HELICAL, "[-0.070, -0.130]", "[-6, -8]", "stage[0].pinion.tooth_thickness_allowance_mm", "x_E1 + x_E2"),
    # thickened so far that the root is cut above the tip
    (HELICAL, "[-0.070, -0.130]", "[50, 40]", "stage[0].pinion.tooth_thickness_allowance_mm", "no tooth depth"),
    # a planetary stage names its members as the file does
    (PLANETARY, "[-0.060, -0.100]", "[-2.0, -3.0]", "stage[0].sun.tooth_thickness_allowance_mm", "x_E1 + x_E2"),
    (PLANETARY, "[-0.070, -0.115]", "[40, 30]", "stage[0].planet.tooth_thickness_allowance_mm", "no tooth depth"),
])
def test_impossible_allowances_exit_2_naming_the_key(text, old, new, key, words):
    assert old in text
    res = _run(text.replace(old, new, 1), "--format", "json")
    assert res.exit_code == 2, res.output
    assert f"{key}: " in res.output and words in res.output and "Traceback" not in res.output
    assert res.stdout == ""


def _warnings(text: str, check: str) -> list[dict]:
    return [w for w in _design(text)["warnings"] if w.get("check") == check]


def test_thinned_into_undercut_and_a_pointed_tip_warn():
    """A_sn = −5 mm on m_n 4: x_E,i = 0.3 − 5/2.911762 = −1.4172; undercut limit z_min = 2 (1 − x_E) cos β /
    sin² α_t = 38.9 > 23, and the tip comes to a point. The nominal x = +0.3 warns of neither."""
    text = HELICAL.replace("[-0.070, -0.130]", "[-3.0, -5.0]")
    (under,) = _warnings(text, "undercut")
    assert under["member"] == "pinion" and "x_E,i = -1.417" in under["message"]
    assert_allclose(under["generating_profile_shift"], 0.3 - 5.0 / (8 * math.tan(ALPHA)), rtol=1e-12)
    alpha_t = Hand.alpha_t
    assert f"z_min = {2 * (1 - under['generating_profile_shift']) * math.cos(BETA) / math.sin(alpha_t) ** 2:.1f}" \
        in under["message"]
    (tip,) = _warnings(text, "tip_thickness")
    assert tip["member"] == "pinion" and "pointed tooth" in tip["message"]
    assert _warnings(HELICAL, "undercut") == [] and _warnings(HELICAL, "tip_thickness") == []


def test_an_upper_tip_allowance_that_points_the_tooth_warns():
    """d_a + 6 mm = 110.4 mm on the pinion: s_an at x_E,i on that tip is negative (the flanks meet below it)."""
    text = HELICAL.replace("[-0.070, -0.130] }", "[-0.070, -0.130], tip_diameter_allowance_mm = [6.0, 0.0] }")
    (tip,) = _warnings(text, "tip_thickness")
    assert "d_a + A_dae = 110.4 mm" in tip["message"]


@pytest.mark.parametrize("text, old, new, eps_i", [
    # the pinion's lower tip 12 mm small at a_w + 0.023: ε_α,i by hand below
    (HELICAL, "[-0.070, -0.130] }", "[-0.070, -0.130], tip_diameter_allowance_mm = [0.0, -12.0] }", None),
    (PLANETARY, "[-0.060, -0.100] }", "[-0.060, -0.100], tip_diameter_allowance_mm = [0, -6] }", None),
])
def test_contact_lost_at_the_allowances_warns(text, old, new, eps_i):
    assert old in text
    (w,) = _warnings(text.replace(old, new), "contact_ratio_allowances")
    eps = w["contact_ratio_transverse_with_allowances"]
    assert min(eps) < 1.0 and f"ε_α,i = {min(eps):.3f} < 1" in w["message"]
    if text is HELICAL:
        assert_allclose(eps[2], Hand.contact_ratio(Hand.a_w + A_A[0], (Hand.d_a[0] - 12.0, Hand.d_a[1])), rtol=1e-9)
    assert _warnings(text, "contact_ratio_allowances") == []


def test_thicker_than_nominal_teeth_jam_and_say_so():
    """Positive allowances: both backlash limits negative, by the same tooth-thickness sum as above."""
    text = HELICAL.replace("[-0.070, -0.130]", "[0.130, 0.070]").replace("[-0.100, -0.170]", "[0.170, 0.100]")
    doc = _design(text)
    st = doc["stages"][0]
    x_thick = (0.3 + 0.130 / (8 * math.tan(ALPHA)), -0.1 + 0.170 / (8 * math.tan(ALPHA)))
    assert_allclose(st["backlash_circumferential_mm"][1], Hand.backlash_by_thickness(x_thick, Hand.a_w - 0.023),
                    rtol=1e-9)
    assert max(st["backlash_circumferential_mm"]) < 0
    (w,) = [w for w in doc["warnings"] if w.get("check") == "backlash_negative"]
    assert "jam" in w["message"] and "every pair within the tolerances jams" in w["message"]
    assert w["backlash_max_mm"] == st["backlash_circumferential_mm"][0]


def test_a_tip_into_the_mate_s_root_warns():
    """Pinion tip +6 mm: c = a_w + A_ai − (d_a1 + A_dae)/2 − d_f2,e/2 = 192.9655 − 55.216 − 139.635 = −1.886 mm."""
    text = HELICAL.replace("[-0.070, -0.130] }", "[-0.070, -0.130], tip_diameter_allowance_mm = [6.0, 0.0] }")
    (w,) = _warnings(text, "tip_clearance")
    d_f2e = Hand.d[1] + 2 * Hand.x_e(1, 0) * M - 2.5 * M
    assert_allclose(w["tip_clearance_mm"], Hand.a_w - 0.023 - (Hand.d_a[0] + 6.0) / 2 - d_f2e / 2, rtol=1e-9)
    assert_allclose(w["tip_clearance_mm"], -1.886, atol=1e-3)
    assert w["member"] == "pinion" and "runs into the mate's root" in w["message"]
    assert _warnings(HELICAL, "tip_clearance") == []


def test_one_member_only_and_the_centre_distance_only():
    """A member without the key has zero allowance (x_E = x); the centre distance alone gives ±2 A_a tan α_wt."""
    text = HELICAL.replace(", tooth_thickness_allowance_mm = [-0.100, -0.170]", "")
    st = _design(text)["stages"][0]
    assert st["gear"]["generating_profile_shift"] == [-0.1, -0.1]
    j_max = Hand.backlash_by_thickness((Hand.x_e(0, 1), X[1]), Hand.a_w + 0.023)
    assert_allclose(st["backlash_circumferential_mm"][0], j_max, rtol=1e-9)
    text = text.replace(", tooth_thickness_allowance_mm = [-0.070, -0.130]", "")
    st = _design(text)["stages"][0]
    assert_allclose(st["backlash_circumferential_mm"], [Hand.backlash_by_thickness(X, Hand.a_w + 0.023),
                                                        Hand.backlash_by_thickness(X, Hand.a_w - 0.023)], rtol=1e-9)
    assert_allclose(st["backlash_circumferential_mm"], [2 * 0.023 * math.tan(Hand.alpha_w),
                                                        -2 * 0.023 * math.tan(Hand.alpha_w)], rtol=1e-3)


def test_iso_21771_sum_of_generating_shifts_from_the_normal_backlash():
    """ISO 21771:2007 eqs. (62)/(63) as worked in a published calculation sheet ("Gear Generating Profile Shift
    Calculations": z 31/30, m_n 3.5, α_n 20°, β 21°, a_w 116.5 mm; α_t 21.2990642859°, α_wt 23.8707609654°,
    Σx = 0.651877131252, and for j_n = 0.030 mm Σx_E = 0.639346541, i.e. Σx − Σx_E = j_n / (2 m_n sin α_n)).
    gearcli's backlash of teeth cut at that Σx_E (all of the thinning on the pinion) is j_n = 0.030 mm."""
    sum_x, sum_x_e, m_n = 0.651877131252, 0.639346541, 3.5
    assert_allclose(sum_x - sum_x_e, 0.030 / (2 * m_n * math.sin(ALPHA)), rtol=1e-6)  # the sheet's eq. (63)
    a_sn = (sum_x_e - sum_x) * 2 * m_n * math.tan(ALPHA)  # −0.031925 mm
    text = (HELICAL.replace("normal_module_mm = 4", "normal_module_mm = 3.5").replace("helix_angle_deg = 12",
                                                                                      "helix_angle_deg = 21")
            .replace("center_distance_allowance_mm = [0.023, -0.023]\n", "")
            .replace("teeth = 23", "teeth = 31").replace("teeth = 71", "teeth = 30")
            .replace("profile_shift = 0.3,", "profile_shift = 0.291,")
            .replace("profile_shift = -0.1,", f"profile_shift = {sum_x - 0.291!r},")
            .replace("[-0.070, -0.130]", f"[{a_sn!r}, {a_sn!r}]")
            .replace(", tooth_thickness_allowance_mm = [-0.100, -0.170]", ""))
    st = _design(text)["stages"][0]
    assert_allclose(st["center_distance_mm"], 116.5, atol=1e-9)
    assert_allclose([st["transverse_pressure_angle_deg"], st["working_pressure_angle_deg"]],
                    [21.2990642859, 23.8707609654], atol=1e-9)
    assert_allclose(sum(xe[1] for xe in (st["pinion"]["generating_profile_shift"],
                                         st["gear"]["generating_profile_shift"])), sum_x_e, rtol=1e-12)
    assert_allclose(st["backlash_normal_mm"], [0.030, 0.030], rtol=1e-7)  # the sheet's Σx_E has 9 digits
