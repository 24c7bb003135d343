"""The planet–ring mesh's interference with the planet's root fillet, by hand (DIN 3960 / ISO 21771: the start of
the active profile d_Nf of the planet must not lie below its root form circle d_Ff).

The planet is cut by the stage's basic rack (ISO 53 profile A: h_fP* 1.25, ρ_fP* 0.38), whose straight flank ends
h_FfP* = 1.25 − 0.38 (1 − sin α_n) m_n below the reference line: the planet's involute reaches down to
q = r_p sin α_t − (h_FfP* − x_p) m_n / sin α_t from its base tangent point T1 along the transverse line of action.
The ring's tip circle crosses that line g_r = √(r_ar² − r_br²) from the ring's tangent point T2, i.e. g_r − a_w sin
α_wt from T1. An internal mate's concave tip circle reaches deeper into the planet than the rack that cut it, so a
ring of ordinary proportions can meet the planet's fillet although it clears the planet's base circle: until
2026-12-01 only the base circle (involute interference) was checked, and a 20/20/60 stage with x = 0.1/0/−0.1 had
no warning while its ring's tip met the planet 1.2 mm (along the line of action) inside the fillet and its ε_α
1.904 counted 0.136 of path that carries no involute contact.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from numpy.testing import assert_allclose

from gearcli.api import design, load
from tests.life.scenes import design_of
from tests.reference.heavy_hand import inv as _inv
from tests.reference.heavy_hand import inv_inverse as _inv_inverse

Z_S, Z_P, Z_R, M_N = 20, 20, 60, 3.0


def scene(x_s: float, x_r: float, beta_deg: float = 0.0) -> str:
    """Four planets (80/4 = 20), the ring held, the sun driving; x_p = 0."""
    hands = ("", "") if beta_deg == 0 else (', hand = "left"', ', hand = "right"')
    member = 'face_width_mm = 40, material = "steel"'
    return "\n".join([
        "materials.steel = { density_kg_m3 = 7850, youngs_modulus_MPa = 206000, poisson_ratio = 0.3 }",
        "input = { speed_rpm = 1450 }", "load = { torque_Nm = 800 }", "[[stage]]", 'type = "planetary"',
        f"normal_module_mm = {M_N}", f"helix_angle_deg = {beta_deg}", 'fixed = "ring"', 'input = "sun"',
        f"sun = {{ teeth = {Z_S}, profile_shift = {x_s}, {member}{hands[0]} }}",
        f"planet = {{ teeth = {Z_P}, count = 4, {member}{hands[1]} }}",
        f"ring = {{ teeth = {Z_R}, profile_shift = {x_r}, {member} }}"])


def hand(x_s: float, x_r: float, beta_deg: float) -> dict[str, float]:
    """The ring's tip point and the planet's lowest involute point on the planet–ring line of action (x_p = 0)."""
    a_n, beta = math.radians(20.0), math.radians(beta_deg)
    a_t = math.atan(math.tan(a_n) / math.cos(beta))
    m_t = M_N / math.cos(beta)
    r_p, r_r = Z_P * m_t / 2, Z_R * m_t / 2
    rb_p, rb_r = r_p * math.cos(a_t), r_r * math.cos(a_t)
    # the planet's tip: the sun–planet pair's tip alteration k (ISO 21771), d_a = d + 2 m_n (1 + x + k)
    a_sp = (Z_S + Z_P) * m_t / 2
    aw_sp = a_sp * math.cos(a_t) / math.cos(_inv_inverse(_inv(a_t) + 2 * math.tan(a_n) * x_s / (Z_S + Z_P)))
    k = (aw_sp - a_sp) / M_N - x_s
    ra_p = r_p + M_N * (1 + k)
    # the planet–ring mesh: inv α_wt = inv α_t + 2 tan α_n (x_p + x_r)/(z_p − z_r), a_w cos α_wt = r_br − r_bp
    aw_t = _inv_inverse(_inv(a_t) + 2 * math.tan(a_n) * x_r / (Z_P - Z_R))
    line = (rb_r - rb_p) * math.tan(aw_t)  # T2T1 = a_w sin α_wt
    ra_r = r_r - M_N * (1 + x_r)
    start = math.sqrt(ra_r**2 - rb_r**2) - line
    h_ff = 1.25 - 0.38 * (1 - math.sin(a_n))
    q = r_p * math.sin(a_t) - h_ff * M_N / math.sin(a_t)
    p_bt = math.pi * m_t * math.cos(a_t)
    return {"start": start, "q": q, "depth": q - start, "d_ff": 2 * math.hypot(rb_p, q),
            "d_min": math.hypot(2 * rb_r, 2 * (line + q)), "tip": 2 * ra_r,
            "usable": (math.sqrt(ra_p**2 - rb_p**2) - max(start, q)) / p_bt,
            "eps": (math.sqrt(ra_p**2 - rb_p**2) - math.sqrt(ra_r**2 - rb_r**2) + line) / p_bt}


@pytest.mark.parametrize(("x_s", "x_r", "beta_deg"), [(0.1, -0.1, 0.0), (0.3, -0.3, 0.0), (0.1, -0.1, 15.0)])
def test_a_ring_tip_in_the_planets_root_fillet_warns_with_the_figures(x_s, x_r, beta_deg):
    ref = hand(x_s, x_r, beta_deg)
    assert 0.0 < ref["start"] < ref["q"]  # clear of the planet's base circle, inside its fillet
    d = design_of(scene(x_s, x_r, beta_deg))[1]
    hits = [dg for dg in d.diagnostics if dg.data.get("check") == "interference"]
    assert len(hits) == 1
    data = hits[0].data
    assert (data["stage"], data["mesh"], data["member"]) == (1, "planet_ring", "planet")
    assert_allclose([data["depth_mm"], data["form_diameter_mm"], data["min_tip_diameter_mm"], data["tip_diameter_mm"]],
                    [ref["depth"], ref["d_ff"], ref["d_min"], ref["tip"]], rtol=1e-9)
    assert_allclose([data["contact_ratio_transverse"], data["contact_ratio_transverse_usable"]],
                    [ref["eps"], ref["usable"]], rtol=1e-9)
    assert "root fillet" in hits[0].message and f"{ref['d_ff']:.4g} mm" in hits[0].message
    assert "involute interference" not in hits[0].message


def test_figures_of_the_first_case():
    """x = 0.1/0/−0.1, spur: 1.205 mm inside the fillet (d_Ff 56.46 mm), ε_α 1.904 of which 1.768 is usable."""
    ref = hand(0.1, -0.1, 0.0)
    assert_allclose([ref["depth"], ref["d_ff"], ref["eps"], ref["usable"]], [1.2048, 56.460, 1.9037, 1.7676], atol=5e-4)


def test_a_ring_tip_clear_of_the_fillet_does_not_warn():
    """x = 0.5/0/−0.5: the ring's tip point lies beyond the planet's lowest involute point (no warning)."""
    ref = hand(0.5, -0.5, 0.0)
    assert ref["start"] > ref["q"]
    d = design_of(scene(0.5, -0.5))[1]
    assert not [dg for dg in d.diagnostics if dg.data.get("check") == "interference"]


def test_the_sun_planet_contact_ratio_warning_names_its_mesh():
    """configs/planetary_stage.toml (NREL 5 MW stage 1: 19/17/56, m_n 45, x 0.617/0.8021/−0.5013): the sun–planet
    ε_α by hand (tip alteration k = (a_w − a)/m_n − Σx) is 1.115 < 1.2; the warning said "stage 1: transverse
    contact ratio", which of a planetary stage's two meshes left unsaid (the planet–ring's says so)."""
    a_t, z, x, m = math.radians(20.0), (19, 17), (0.617, 0.8021), 45.0
    a = m * sum(z) / 2
    a_wt = _inv_inverse(_inv(a_t) + 2 * math.tan(a_t) * sum(x) / sum(z))
    a_w = a * math.cos(a_t) / math.cos(a_wt)
    k = (a_w - a) / m - sum(x)
    reach = sum(math.sqrt((zi * m / 2 + m * (1 + xi + k)) ** 2 - (zi * m / 2 * math.cos(a_t)) ** 2)
                for zi, xi in zip(z, x, strict=True))
    eps = (reach - a_w * math.sin(a_wt)) / (math.pi * m * math.cos(a_t))
    d = design(load(str(Path(__file__).resolve().parents[2] / "configs" / "planetary_stage.toml")))
    hits = [dg for dg in d.diagnostics if dg.data.get("check") == "contact_ratio"]
    assert len(hits) == 1
    assert_allclose(hits[0].data["contact_ratio_transverse"], eps, rtol=1e-9)
    assert hits[0].data["mesh"] == "sun_planet"
    assert hits[0].message.startswith(f"stage 1 sun–planet mesh: transverse contact ratio ε_α = {eps:.3f} < 1.2")


def test_a_jammed_sun_planet_mesh_says_so_without_a_centre_distance_to_widen():
    """Sun +0.05, planet +0.03 mm upper tooth-thickness allowances (spur): on the working circles of the nominal a_w
    the pitch less both tooth thicknesses s_w = d_w (s_t/d + inv α_t − inv α_wt), s_t = m (π/2 + 2 x tan α_n) + A_sn,
    is −0.0804 mm; a planetary stage has no centre-distance allowance (the carrier's radius), so the warning's advice
    is the teeth, and it names the sun–planet mesh (it read "stage 1: … or widen the centre distance")."""
    text = scene(0.1, -0.1).replace('profile_shift = 0.1, face', 'profile_shift = 0.1, tooth_thickness_allowance_mm = '
                                    '[0.05, -0.05], face').replace(
        "count = 4,", "count = 4, tooth_thickness_allowance_mm = [0.03, -0.05],")
    a = math.radians(20.0)
    a_wt = _inv_inverse(_inv(a) + 2 * math.tan(a) * 0.1 / (Z_S + Z_P))
    widths = [Z * M_N * math.cos(a) / math.cos(a_wt) * ((M_N * (math.pi / 2 + 2 * x * math.tan(a)) + allowance)
                                                         / (Z * M_N) + _inv(a) - _inv(a_wt))
              for Z, x, allowance in ((Z_S, 0.1, 0.05), (Z_P, 0.0, 0.03))]
    j_min = math.pi * Z_S * M_N * math.cos(a) / math.cos(a_wt) / Z_S - sum(widths)
    d = design_of(text)[1]
    found = [dg for dg in d.diagnostics if dg.data.get("check") == "backlash_negative"
             and dg.data.get("mesh") == "sun_planet"]
    assert len(found) == 1
    assert_allclose(found[0].data["backlash_min_mm"], j_min, rtol=1e-9)
    assert_allclose(j_min, -0.0804, atol=1e-4)
    assert found[0].message.startswith("stage 1 sun–planet mesh: the minimum circumferential backlash")
    assert "centre distance" not in found[0].message


def test_the_sun_planet_interference_carries_its_mesh():
    """Sun 12 (undercut: z < 17.1), planets 24, ring 60, x = 0: the planet's tip starts contact a sin α −
    √(r_ap² − r_bp²) = 54 sin 20° − √(39² − (36 cos 20°)²) = −0.937 mm beyond the sun's base tangent point."""
    text = scene(0.0, 0.0).replace("teeth = 20,", "teeth = 12,", 1).replace("teeth = 20,", "teeth = 24,", 1).replace(
        "count = 4", "count = 3")  # sun, then planet (Z_S = Z_P)
    depth = math.sqrt(39.0**2 - (36 * math.cos(math.radians(20))) ** 2) - 54 * math.sin(math.radians(20))
    d = design_of(text)[1]
    found = [dg.data for dg in d.diagnostics if dg.data.get("check") == "interference"
             and dg.data.get("mesh") == "sun_planet"]
    assert len(found) == 1 and found[0]["member"] == "pinion"  # the pair's member: the sun
    assert_allclose(found[0]["depth_mm"], depth, rtol=1e-9)
    assert_allclose(depth, 0.937, atol=1e-3)
