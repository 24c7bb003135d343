"""Allowances on a steep helical pair near undercut and a spur pair with thickened teeth, by hand (ISO 21771,
DIN 3967, ISO 6336-3:2006 method B), independent of gearcli.design.allowances and gearcli.design.rating_root.

Scene H: m_n 4, α_n 20°, β 35°, z 13/47, x +0.35/−0.12, b 40/38, asymmetric allowances A_sn = [−0.05, −0.11]
(pinion), [−0.09, −0.16] (wheel), the wheel's tip A_da = [0, −0.08], centre distance [+0.035, −0.010] mm.
Scene S: spur m 3, z 11/40, x +0.5/0, the pinion thickened A_sn = [+0.6, +0.5], the wheel's allowance zero.
"""

from __future__ import annotations

import json
import math

from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

HELICAL = """
title = "helical 35 deg, shifted, asymmetric allowances"
[materials.steel]
density_kg_m3 = 7850
youngs_modulus_MPa = 210000
poisson_ratio = 0.3
treatment = "case_carburized"
contact_fatigue_limit_MPa = 1500
bending_fatigue_limit_MPa = 460
[[stage]]
normal_module_mm = 4
accuracy_grade = 6
normal_pressure_angle_deg = 20
helix_angle_deg = 35
center_distance_allowance_mm = [0.035, -0.010]
pinion = { teeth = 13, face_width_mm = 40, profile_shift = 0.35, hand = "left", material = "steel", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 16, tooth_thickness_allowance_mm = [-0.05, -0.11] }
gear = { teeth = 47, face_width_mm = 38, profile_shift = -0.12, hand = "right", material = "steel", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 16, tooth_thickness_allowance_mm = [-0.09, -0.16], tip_diameter_allowance_mm = [0.0, -0.08] }
[input]
speed_rpm = 1500
[load]
torque_Nm = 200
[lubricant]
viscosity_40C_mm2_s = 220
[rating]
required_life_h = 20000
"""

SPUR = """
title = "spur z=11, the pinion thickened, the wheel's allowance zero"
[materials.steel]
density_kg_m3 = 7850
youngs_modulus_MPa = 210000
poisson_ratio = 0.3
[[stage]]
normal_module_mm = 3
normal_pressure_angle_deg = 20
helix_angle_deg = 0
pinion = { teeth = 11, face_width_mm = 30, profile_shift = 0.5, material = "steel", tooth_thickness_allowance_mm = [0.6, 0.5] }
gear = { teeth = 40, face_width_mm = 30, profile_shift = 0.0, material = "steel", tooth_thickness_allowance_mm = [0.0, 0.0] }
[input]
speed_rpm = 1500
[load]
torque_Nm = 50
"""


def _inv(a: float) -> float:
    return math.tan(a) - a


def _inv_inverse(v: float) -> float:
    a = 0.5
    for _ in range(100):
        a -= (_inv(a) - v) / math.tan(a) ** 2
    return a


class Pair:
    """An external pair by hand (ISO 21771 with tip alteration)."""

    def __init__(self, m_n, beta_deg, z, x, a_sn, a_a=(0.0, 0.0), a_da=((0.0, 0.0), (0.0, 0.0))):
        self.m_n, self.an, self.b = m_n, math.radians(20.0), math.radians(beta_deg)
        self.z, self.x, self.a_sn, self.a_a, self.a_da = z, x, a_sn, a_a, a_da
        self.m_t = m_n / math.cos(self.b)
        self.at = math.atan(math.tan(self.an) / math.cos(self.b))
        self.bb = math.atan(math.tan(self.b) * math.cos(self.at))
        self.d = (z[0] * self.m_t, z[1] * self.m_t)
        self.db = (self.d[0] * math.cos(self.at), self.d[1] * math.cos(self.at))
        self.awt = _inv_inverse(_inv(self.at) + 2 * math.tan(self.an) * sum(x) / sum(z))
        self.a0 = 0.5 * sum(self.d)
        self.aw = self.a0 * math.cos(self.at) / math.cos(self.awt)
        k = (self.aw - self.a0) / m_n - sum(x)
        self.da = (self.d[0] + 2 * m_n * (1 + x[0] + k), self.d[1] + 2 * m_n * (1 + x[1] + k))

    def x_e(self, i, j):
        return self.x[i] + self.a_sn[i][j] / (2 * self.m_n * math.tan(self.an))

    def root(self, i, j):
        return self.d[i] + 2 * self.m_n * (self.x_e(i, j) - 1.25)

    def backlash(self, j, a):
        """Pitch on the working circle at a less both tooth thicknesses there (j = 0 thickest, 1 thinnest)."""
        alpha = math.acos(self.a0 * math.cos(self.at) / a)
        dw = (self.db[0] / math.cos(alpha), self.db[1] / math.cos(alpha))
        s = [dw[i] * (self.m_t * (math.pi / 2 + 2 * self.x_e(i, j) * math.tan(self.an)) / self.d[i]
                      + _inv(self.at) - _inv(alpha)) for i in (0, 1)]
        return math.pi * dw[0] / self.z[0] - s[0] - s[1], math.cos(alpha) * math.cos(self.bb)

    def eps(self, tips, a):
        alpha = math.acos(self.a0 * math.cos(self.at) / a)
        return ((math.sqrt(tips[0] ** 2 - self.db[0] ** 2) + math.sqrt(tips[1] ** 2 - self.db[1] ** 2)) / 2
                - a * math.sin(alpha)) / (math.pi * self.m_t * math.cos(self.at))


H = Pair(4.0, 35.0, (13, 47), (0.35, -0.12), ((-0.05, -0.11), (-0.09, -0.16)), (0.035, -0.010),
         ((0.0, 0.0), (0.0, -0.08)))
S = Pair(3.0, 0.0, (11, 40), (0.5, 0.0), ((0.6, 0.5), (0.0, 0.0)))


def _design(tmp_path, text: str, *args: str) -> dict:
    path = tmp_path / "steep.toml"
    path.write_text(text)
    res = CliRunner().invoke(cli, ["design", str(path), "--format", "json", *args])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def test_steep_helix_generating_shifts_roots_backlash_and_contact(tmp_path):
    st = _design(tmp_path, HELICAL)["stages"][0]
    for i, member in enumerate(("pinion", "gear")):
        assert_allclose(st[member]["generating_profile_shift"], [H.x_e(i, 0), H.x_e(i, 1)], rtol=0, atol=1e-13)
        assert_allclose(st[member]["manufactured_root_diameter_mm"], [H.root(i, 0), H.root(i, 1)], rtol=1e-13)
    # x_E of the pinion: 0.35 − 0.05/(8 tan 20°) = 0.332828, 0.35 − 0.11/2.911762 = 0.312222
    assert_allclose(st["pinion"]["generating_profile_shift"], [0.332828, 0.312222], atol=1e-6)
    j_max, to_n_max = H.backlash(1, H.aw + 0.035)  # thinnest teeth, largest centre distance
    j_min, to_n_min = H.backlash(0, H.aw - 0.010)  # thickest, smallest
    assert_allclose(st["backlash_circumferential_mm"], [j_max, j_min], rtol=1e-9)
    assert_allclose(st["backlash_normal_mm"], [j_max * to_n_max, j_min * to_n_min], rtol=1e-9)
    # DIN 3967 to first order: −ΣA_sn/cos β · cos α_t/cos α_wt + 2 A_a tan α_wt (0.36390, 0.16275 mm)
    lin = [(-s / math.cos(H.b)) * math.cos(H.at) / math.cos(H.awt) + 2 * a * math.tan(H.awt)
           for s, a in ((-0.27, 0.035), (-0.14, -0.010))]
    assert_allclose(st["backlash_circumferential_mm"], lin, rtol=1e-3)
    tips = [(H.da[0], H.da[1] + t) for t in (0.0, -0.04, -0.08)]
    eps = [H.eps(tips[0], H.aw - 0.010), H.eps(tips[1], H.aw + 0.0125), H.eps(tips[2], H.aw + 0.035)]
    assert_allclose(st["contact_ratio_transverse_with_allowances"], eps, rtol=1e-10)


def _method_b(z, x, m, beta, da, eps_alpha):
    """ISO 6336-3:2006 method B, external gear, basic rack h_fP 1.25 m, ρ_fP 0.38 m, no protuberance."""
    an = math.radians(20.0)
    bb = math.asin(math.sin(beta) * math.cos(an))
    zn = z / (math.cos(bb) ** 2 * math.cos(beta))
    e = math.pi / 4 * m - 1.25 * m * math.tan(an) - (1 - math.sin(an)) * 0.38 * m / math.cos(an)
    g = 0.38 - 1.25 + x
    h = 2 / zn * (math.pi / 2 - e / m) - math.pi / 3
    th = math.pi / 6
    for _ in range(200):
        th = 2 * g / zn * math.tan(th) - h
    s_fn = m * (zn * math.sin(math.pi / 3 - th) + math.sqrt(3) * (g / math.cos(th) - 0.38))
    rho_f = m * (0.38 + 2 * g * g / (math.cos(th) * (zn * math.cos(th) ** 2 - 2 * g)))
    d = z * m / math.cos(beta)
    dn = d / math.cos(bb) ** 2
    dbn, dan = dn * math.cos(an), dn + da - d
    eps_an = eps_alpha / math.cos(bb) ** 2
    den = 2 * math.hypot(math.sqrt(dan ** 2 - dbn ** 2) / 2 - math.pi * d * math.cos(beta) * math.cos(an) / z
                         * (eps_an - 1), dbn / 2)
    aen = math.acos(dbn / den)
    ge = (0.5 * math.pi + 2 * x * math.tan(an)) / zn + _inv(an) - _inv(aen)
    afen = aen - ge
    hfe = 0.5 * m * ((math.cos(ge) - math.sin(ge) * math.tan(afen)) * den / m - zn * math.cos(math.pi / 3 - th)
                     - g / math.cos(th) + 0.38)
    y_f = 6 * hfe / m * math.cos(afen) / ((s_fn / m) ** 2 * math.cos(an))
    ell = s_fn / hfe
    y_s = (1.2 + 0.13 * ell) * (s_fn / (2 * rho_f)) ** (1 / (1.21 + 2.3 / ell))
    return y_f, y_s


def test_steep_helix_root_rated_at_the_generating_shift(tmp_path):
    """ISO 6336-3 rates the root of the tooth as cut: Y_F, Y_S at x_E (the lower allowance by default, the upper on
    request), at x with "nominal"; the tip and ε_α stay the nominal ones. z 13 at β 35°: z_n 21.9."""
    eps = _design(tmp_path, HELICAL)["stages"][0]["contact_ratio_transverse"]
    assert_allclose(eps, H.eps(H.da, H.aw), rtol=1e-10)
    for choice, j in (("lower", 1), ("upper", 0), ("nominal", None)):
        rating = _design(tmp_path, HELICAL, "--set", f'rating.root_profile_shift="{choice}"')["stages"][0]["rating"]
        for i, member in enumerate(("pinion", "gear")):
            x = H.x[i] if j is None else H.x_e(i, j)
            y_f, y_s = _method_b(H.z[i], x, 4.0, H.b, H.da[i], eps)
            assert_allclose([rating[member]["Y_F"], rating[member]["Y_S"]], [y_f, y_s], rtol=1e-9)
    # the thinner the cut tooth, the larger Y_F: the pinion's 1.158 (x) → 1.190 (x_E,e) → 1.228 (x_E,i)
    assert _method_b(13, H.x_e(0, 1), 4.0, H.b, H.da[0], eps)[0] > _method_b(13, 0.35, 4.0, H.b, H.da[0], eps)[0]


def test_thickened_spur_pinion_jams_and_its_mate_s_tip_runs_into_its_root(tmp_path):
    """Positive allowances are legal (a thick tooth on a thin mate) but here every pair jams: j_t = −0.509 /
    −0.611 mm (the zero allowance of the wheel: x_E = x). The wheel's tip against the pinion's raised root,
    c = a_w − d_a2/2 − d_f1,e/2 = −0.0742 mm: warned, the pinion's upper thickness allowance named as the cause."""
    data = _design(tmp_path, SPUR)
    st = data["stages"][0]
    assert st["gear"]["generating_profile_shift"] == [0.0, 0.0]
    j = [S.backlash(1, S.aw)[0], S.backlash(0, S.aw)[0]]
    assert_allclose(st["backlash_circumferential_mm"], j, rtol=1e-9)
    assert_allclose(j, [-0.5092, -0.6110], atol=1e-4)
    assert_allclose(st["contact_ratio_transverse_with_allowances"], [st["contact_ratio_transverse"]] * 3, rtol=1e-12)
    by_check = {w.get("check"): w for w in data["warnings"]}
    assert_allclose(by_check["backlash_negative"]["backlash_max_mm"], j[0], rtol=1e-9)
    clearance = S.aw - S.da[1] / 2 - S.root(0, 0) / 2
    assert_allclose(clearance, -0.0742, atol=1e-4)
    w = by_check["tip_clearance"]
    assert w["member"] == "gear" and "tooth_thickness_allowance_mm" in w["message"]
    assert "tip_diameter_allowance_mm" not in w["message"]  # no tip allowance in this file
    assert_allclose(w["tip_clearance_mm"], clearance, rtol=1e-9)


def test_a_wide_centre_distance_tolerance_is_named_as_the_clearance_s_cause(tmp_path):
    """A_a = ±5 mm on scene H: the pinion's tip against the wheel's root at a_w − 5, c = −3.876 mm by hand."""
    data = _design(tmp_path, HELICAL.replace("[0.035, -0.010]", "[5, -5]"))
    w = [w for w in data["warnings"] if w.get("check") == "tip_clearance" and w["member"] == "pinion"][0]
    assert_allclose(w["tip_clearance_mm"], H.aw - 5 - H.da[0] / 2 - H.root(1, 0) / 2, rtol=1e-9)
    assert "center_distance_allowance_mm" in w["message"] and "tip_diameter_allowance_mm" not in w["message"]


def test_a_centre_distance_allowance_alone_leaves_the_root_rating(tmp_path):
    """The teeth are the nominal ones when only the centre distance has a tolerance: the root stress is the same (K_Fβ's
    tooth depth is the nominal (d_a − d_f)/2 on both paths, ISO 6336-1:2006 7.7)."""
    plain = HELICAL.replace("center_distance_allowance_mm = [0.035, -0.010]\n", "").replace(
        ", tooth_thickness_allowance_mm = [-0.05, -0.11]", "").replace(
        ", tooth_thickness_allowance_mm = [-0.09, -0.16], tip_diameter_allowance_mm = [0.0, -0.08]", "")
    centre_only = plain.replace("helix_angle_deg = 35\n", "helix_angle_deg = 35\ncenter_distance_allowance_mm = "
                                "[0.035, -0.010]\n")
    a = _design(tmp_path, plain)["stages"][0]["rating"]
    b = _design(tmp_path, centre_only)["stages"][0]["rating"]
    assert "backlash_circumferential_mm" in _design(tmp_path, centre_only)["stages"][0]
    assert b["K_Fbeta"] == a["K_Fbeta"]


def _span_mm(z: int, k: int, x: float, m_n: float, beta: float) -> float:
    """Base tangent length over k teeth (ISO 21771): W_k = m_n cos α_n [(k − 0.5) π + z inv α_t] + 2 x m_n sin α_n."""
    an = math.radians(20.0)
    at = math.atan(math.tan(an) / math.cos(beta))
    return m_n * math.cos(an) * ((k - 0.5) * math.pi + z * _inv(at)) + 2 * x * m_n * math.sin(an)


def test_the_generating_shift_is_the_one_the_span_measures(tmp_path):
    """How the workshop checks a thickness allowance: the span over k teeth shrinks by A_sn cos α_n (the tooth
    thinned by A_sn in the normal section, seen along the base tangent). The x_E gearcli prints must give exactly
    that span: W_k(x_E) = W_k(x) + A_sn cos α_n, for both limits of both members (k = 3 and 6 teeth)."""
    st = _design(tmp_path, HELICAL)["stages"][0]
    for i, (member, k) in enumerate((("pinion", 3), ("gear", 6))):
        nominal = _span_mm(H.z[i], k, H.x[i], 4.0, H.b)
        for j in (0, 1):
            cut = _span_mm(H.z[i], k, st[member]["generating_profile_shift"][j], 4.0, H.b)
            assert_allclose(cut, nominal + H.a_sn[i][j] * math.cos(math.radians(20.0)), rtol=0, atol=1e-12)
