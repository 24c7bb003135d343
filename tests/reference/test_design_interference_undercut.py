"""Undercut and tip interference of small pinions, by hand (independent of the code's geometry module).

References:
1. Shigley's Mechanical Engineering Design (Budynas & Nisbett), eq. 13-11: the largest gear that meshes with a
   full-depth (addendum k m = m) spur pinion of N_P teeth without interference is
   N_G = (N_P² sin² φ − 4 k²) / (4 k − 2 N_P sin² φ); at φ = 20°: 13 → 16, 14 → 26, 15 → 45, 16 → 101 teeth.
   The condition is that the gear's tip must not cross the line of action beyond the pinion's base tangent point
   T1 (SDP/SI, "Elements of Metric Gear Technology", 4.3: "any tooth addendum that extends beyond the tangent
   points T and T' ... interferes with the root fillet area of the mating tooth").
2. ISO 21771 / DIN 3960: a rack with dedendum h_fP and root radius ρ_fP generates the involute down to the end
   of its straight flank, h_FfP = h_fP − ρ_fP (1 − sin α_n) above its datum line; undercut starts when that
   point passes T: z_min = 2 (h_FfP/m_n − x) cos β / sin² α_t. AutoCAD Mechanical's gear generator sizes the
   rack's root radius by exactly this relation, ρ* = (h_fP* − h_aP*) / (1 − sin α), so that h_FfP = h_aP.
"""

from __future__ import annotations

import json
import math

import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli
from gearcli.config.schema import DesignFile
from gearcli.design import compute_design


def design(z1, z2, *, m_n=2.0, alpha_n=20.0, beta=0.0, x=(0.0, 0.0), rack=None):
    hands = ("right", "left") if beta else (None, None)
    stage = {"normal_module_mm": m_n, "normal_pressure_angle_deg": alpha_n, "helix_angle_deg": beta,
             "pinion": {"teeth": z1, "face_width_mm": 10 * m_n, "profile_shift": x[0]},
             "gear": {"teeth": z2, "face_width_mm": 10 * m_n, "profile_shift": x[1]}}
    if beta:
        stage["pinion"]["hand"], stage["gear"]["hand"] = hands
    if rack:
        stage["basic_rack"] = dict(zip(("addendum", "dedendum", "root_radius"), rack, strict=True))
    doc = {"stage": [stage], "input": {"speed_rpm": 100.0}, "load": {"torque_Nm": 10.0}}
    return compute_design(DesignFile.model_validate(doc))


def checks(result, check):
    return [w for w in result.diagnostics if w.data.get("check") == check]


@pytest.mark.parametrize(("z_pinion", "z_gear_max"), [(13, 16), (14, 26), (15, 45), (16, 101)])
def test_shigley_largest_gear_without_interference(z_pinion, z_gear_max):
    phi = math.radians(20.0)
    n_g = (z_pinion ** 2 * math.sin(phi) ** 2 - 4.0) / (4.0 - 2.0 * z_pinion * math.sin(phi) ** 2)
    assert math.floor(n_g) == z_gear_max  # the book's table, from its formula
    assert checks(design(z_pinion, z_gear_max), "interference") == []
    over = checks(design(z_pinion, z_gear_max + 1), "interference")
    assert [w.data["member"] for w in over] == ["pinion"]


def test_usable_contact_ratio_of_an_8_tooth_pinion_stops_at_its_base_tangent_point():
    # m = 2, 20°, z = 8/40, x = 0: a = 48, T1T2 = a sin α; the gear's tip point lies beyond T1 (undercut pinion:
    # its involute ends no lower than T1), so the usable path runs from T1 to the pinion's tip point
    m, a = 2.0, math.radians(20.0)
    r1, r2 = 8.0, 40.0
    rb1, rb2 = r1 * math.cos(a), r2 * math.cos(a)
    line = (r1 + r2) * math.sin(a)
    g_a1 = math.sqrt((r1 + m) ** 2 - rb1 ** 2)
    g_a2 = math.sqrt((r2 + m) ** 2 - rb2 ** 2)
    p_b = math.pi * m * math.cos(a)
    eps_formula = (g_a1 + g_a2 - line) / p_b  # ISO 21771's ε_α from the tips: 1.510
    eps_usable = g_a1 / p_b  # 1.117
    result = design(8, 40)
    stage = result.stages[0]
    assert_allclose(stage.contact_ratio_transverse, eps_formula, rtol=1e-12)  # ε_α stays the contract's formula
    (w,) = checks(result, "interference")
    assert w.data["member"] == "pinion"
    assert_allclose(w.data["contact_ratio_transverse_usable"], eps_usable, rtol=1e-12)
    assert_allclose(w.data["depth_mm"], g_a2 - line, rtol=1e-12)
    assert w.data["form_diameter_mm"] is None  # undercut: the involute's lowest point is not the rack's
    assert "1.117" in w.message and "1.510" in w.message
    assert "give the pinion a larger profile shift" in w.message  # the cure of an undercut flank


def test_interference_into_the_root_fillet_of_a_non_undercut_member():
    # a rack whose straight flank stops short of the mate's tip: h_aP* = 1, h_fP* = 1.1, ρ_fP* = 0.38 →
    # h_FfP* = 1.1 − 0.38 (1 − sin 20°) = 0.850; 60/60 teeth, m = 4: no undercut (z_min = 14.5), but the mate's
    # tip (1.0 m_n) reaches below the form circle on both members (0.6 mm along the line of action)
    m, a = 4.0, math.radians(20.0)
    h_ff = 1.1 - 0.38 * (1.0 - math.sin(a))
    r = 120.0
    rb = r * math.cos(a)
    line = 2 * r * math.sin(a)
    q = r * math.sin(a) - h_ff * m / math.sin(a)  # form point from T
    g_a = math.sqrt((r + m) ** 2 - rb ** 2)
    start = line - g_a
    d_ff = 2 * math.sqrt(rb ** 2 + q ** 2)
    usable = (min(g_a, line - q) - max(line - g_a, q)) / (math.pi * m * math.cos(a))
    result = design(60, 60, m_n=m, rack=(1.0, 1.1, 0.38))
    assert checks(result, "undercut") == []
    found = checks(result, "interference")
    assert [w.data["member"] for w in found] == ["pinion", "gear"]
    for w in found:
        assert_allclose(w.data["form_diameter_mm"], d_ff, rtol=1e-12)
        assert_allclose(w.data["depth_mm"], q - start, rtol=1e-12)
        assert_allclose(w.data["contact_ratio_transverse_usable"], usable, rtol=1e-12)
        assert "shorten the" in w.message and "larger profile shift" not in w.message  # a higher shift hurts here
    # ISO 53 profile A on the same pair: the form circle lies below the mate's reach, no warning
    assert checks(design(60, 60, m_n=m), "interference") == []


def test_speed_increaser_names_its_small_driven_gear():
    # the 40-tooth wheel drives the 14-tooth one: the interference is on the driven 'gear'
    found = checks(design(40, 14), "interference")
    assert [w.data["member"] for w in found] == ["gear"]


def test_positive_shift_cures_interference_and_undercut():
    # x_min = 1 − 8 sin² 20° / 2 = 0.532 (ISO profile A, h_FfP* = 0.99997); x = 0.55 leaves no undercut and the
    # gear's tip now meets the pinion above its form circle
    result = design(8, 40, x=(0.55, 0.0))
    assert checks(result, "undercut") == [] and checks(result, "interference") == []


@pytest.mark.parametrize(("rack", "z_ok", "z_cut"), [
    ((0.8, 1.0, 0.3), 14, 13),  # stub: h_FfP* = 1 − 0.3 (1 − sin 20°) = 0.8026 → z_min = 13.72
    ((1.0, 1.4, 0.39), 20, 19),  # ISO 53 profile D: h_FfP* = 1.4 − 0.39 (1 − sin 20°) = 1.1434 → z_min = 19.55
])
def test_undercut_limit_follows_the_basic_rack(rack, z_ok, z_cut):
    a = math.radians(20.0)
    z_min = 2.0 * (rack[1] - rack[2] * (1.0 - math.sin(a))) / math.sin(a) ** 2
    assert z_cut < z_min < z_ok
    assert checks(design(z_ok, 60, rack=rack), "undercut") == []
    (w,) = checks(design(z_cut, 60, rack=rack), "undercut")
    assert f"z_min = {z_min:.1f}" in w.message


def test_helical_undercut_limit_in_the_transverse_section():
    # β = 30°, α_n = 20°: tan α_t = tan 20° / cos 30°; z_min = 2 h_FfP* cos β / sin² α_t = 11.5 (profile A)
    a_n, beta = math.radians(20.0), math.radians(30.0)
    a_t = math.atan(math.tan(a_n) / math.cos(beta))
    h_ff = 1.25 - 0.38 * (1.0 - math.sin(a_n))
    z_min = 2.0 * h_ff * math.cos(beta) / math.sin(a_t) ** 2
    assert 11 < z_min < 12
    assert checks(design(12, 50, beta=30.0), "undercut") == []
    (w,) = checks(design(11, 50, beta=30.0), "undercut")
    assert f"z_min = {z_min:.1f}" in w.message


def test_interference_in_json_and_on_stderr(tmp_path):
    path = tmp_path / "small_pinion.toml"
    path.write_text("[[stage]]\nnormal_module_mm = 2\npinion = { teeth = 8, face_width_mm = 20 }\n"
                    "gear = { teeth = 40, face_width_mm = 20 }\n[input]\nspeed_rpm = 1000\n[load]\ntorque_Nm = 100\n",
                    encoding="utf-8")
    res = CliRunner().invoke(cli, ["design", str(path), "--format", "json"], catch_exceptions=False)
    assert res.exit_code == 0
    (w,) = [w for w in json.loads(res.stdout)["warnings"] if w.get("check") == "interference"]
    assert w["code"] == "design" and w["stage"] == 1 and w["member"] == "pinion"
    assert w["form_diameter_mm"] is None  # undercut: JSON null
    assert f"warning: {w['message']}" in res.stderr
