"""The planet–ring (internal) mesh's ISO 6336-2/-3 rating against a public commercial rating report.

Source: the KISSsoft report ``@NREL_5MW/stage_01.rtf`` ("CALCULATION OF A SPUR PLANETARY GEAR STAGE", "KISSsoft
Release 03/2017 A", "ISO 6336:2006 Method B") of the NREL 5 MW gearbox's first stage, public repository
github.com/gfsReboucas/Drivetrain, commit 2a41bf1ce829b76800693e2b52c91e5f74d074d4; the second column of its
sections 3 and 4 (planet / ring). The stage's geometry inputs are those of ``test_planetary_kisssoft.py``; the rating
inputs as printed: planet 18CrNiMo7-6 case-carburized (σ_Hlim 1500, σ_Flim 430), ring 34CrNiMo6 through-hardened
(σ_Hlim 700, σ_Flim 290, HBW 240, given here as HV 240/0.95), Rz flank 4.8 / 8.0 µm, Rz root 20 µm, oil ν40 220,
grade 6, 175 200 h, K_A 1.25 and K_γ 1.10 (given as K_A 1.375, as the sister sun–planet test does, so that σ_H0 and
σ_F0 are the report's nominal stresses), K_v user 1.05 (the report's for this mesh), K_Hβ user 1.15, S_Hmin 1.25,
S_Fmin 1.56.

Tolerances: half a unit of the printed last digit, widened where stated beside the assertion. The planet's
σ_FG carries Y_M = 0.7 (an idler), as the report's "Alternating bending factor YM 0.700" does. The ring's root:
the report computes the internal gear's root geometry with its pinion-type cutter ("z0 = 36, x0 = 0,
rofP* = 0.300") and the ring's own reference profile (ρ_fP* 0.30, profile B), and prints the ring's Y_B 1.00
("Outer diameter of gear rim 0.00"), which the NREL design's rim, 157.5 mm = 3.5 m_n, also gives (ISO 6336-3's
internal gear: Y_B = 1 from s_R/m_n = 3.5); a gearcli stage has one basic rack (here the sun's and planet's
ρ_fP* 0.38) and no cutter key, so the ring's Y_F, Y_S are compared at the level of ``internal_tooth_form`` with the
report's ring inputs, and end to end only the factors that do not depend on them.
"""

from __future__ import annotations

import math

from numpy.testing import assert_allclose

from gearcli.config.schema import DesignFile
from gearcli.design import compute_design
from gearcli.design import rating_root as rr
from tests.reference.test_planetary_kisssoft import nrel_stage_1

ROUGH = {"flank_roughness_Rz_um": 4.8, "root_roughness_Rz_um": 20.0}
ELASTIC = {"density_kg_m3": 7830.0, "youngs_modulus_MPa": 206000.0, "poisson_ratio": 0.3}


def _doc(load_sharing_factor: float | None = None) -> dict:
    doc = nrel_stage_1()
    st = doc["stage"][0]
    st["accuracy_grade"] = 6
    for part in ("sun", "planet"):
        st[part].update(ROUGH, material="case")
    st["ring"].update({"flank_roughness_Rz_um": 8.0, "root_roughness_Rz_um": 20.0, "material": "ring"})
    doc["materials"] = {
        "case": {**ELASTIC, "treatment": "case_carburized", "contact_fatigue_limit_MPa": 1500.0,
                 "bending_fatigue_limit_MPa": 430.0},
        "ring": {**ELASTIC, "treatment": "through_hardened", "contact_fatigue_limit_MPa": 700.0,
                 "bending_fatigue_limit_MPa": 290.0, "surface_hardness_HV": 240.0 / 0.95}}
    doc["load"]["application_factor"] = 1.375
    doc["lubricant"] = {"viscosity_40C_mm2_s": 220.0}
    doc["rating"] = {"required_life_h": 175200.0, "face_load_factor": 1.15, "min_safety_pitting": 1.25,
                     "min_safety_bending": 1.56, "material_quality": "normal", "dynamic_factor": 1.05}
    if load_sharing_factor is not None:
        doc["rating"]["load_sharing_factor"] = load_sharing_factor
    return doc


def _rating(doc: dict):
    st = compute_design(DesignFile.model_validate(doc)).stages[0]
    assert st.planetary is not None
    r = st.planetary.planet_ring.rating
    assert r is not None
    return r


def test_planet_ring_pitting():
    r = _rating(_doc())
    planet, ring = r.pinion, r.gear
    assert (r.K_v, r.K_v_source, r.K_Hbeta) == (1.05, "given", 1.15)
    assert r.Z_beta == 1.0 and r.Y_beta == 1.0  # spur
    assert_allclose(r.Z_H, 2.71, atol=5e-3)  # ZH at the internal mesh's α_wt 17.161°
    assert_allclose(r.Z_E, 189.81, atol=5e-3)  # ZE
    assert_allclose(r.Z_eps, 0.952, atol=5e-4)  # Zeps from ε_α 1.278
    # sigH0 588.62 with (|u| − 1)/|u|; the profile shifts printed to 4 decimals move α_wt and Z_H (see
    # test_planetary_kisssoft.py): gearcli 588.614, within 1e-2
    assert_allclose(r.sigma_H0_MPa, 588.62, atol=1e-2)
    assert_allclose(r.sigma_H_MPa, 758.46, atol=2e-2)  # sigHw: σ_H0's offset × √(K_A K_v K_Hβ K_Hα)
    assert_allclose([planet.Z_BD, ring.Z_BD], [1.00, 1.00], atol=5e-3)  # ZB (planet), ZD = 1 (internal gear)
    assert_allclose([planet.sigma_H_MPa, ring.sigma_H_MPa], [758.46, 758.46], atol=2e-2)  # sigHB, sigHD
    assert_allclose([r.Z_L, r.Z_V, r.Z_R, r.Z_W], [1.038, 0.916, 1.025, 1.135], atol=5e-4)  # ZL ZV ZR ZW(ring)
    # NL 419.0 / 381.6 million: the sun speed is printed to 0.1 rpm (±1e-3 relative, ±0.4 million)
    assert_allclose([planet.load_cycles / 1e6, ring.load_cycles / 1e6], [419.0, 381.6], atol=0.5)
    assert_allclose([planet.Z_NT, ring.Z_NT], [0.937, 0.940], atol=5e-4)  # ZNT
    # sigHG 1368.95 / 727.36 and sigHP 1095.16 / 581.89: gearcli 2e-5 higher (the product of Z_L Z_V Z_R Z_NT,
    # each printed to 3 decimals only; the report interpolates them "logarithmically ... based on the number of
    # load cycles"), so 5e-5 relative
    assert_allclose([planet.sigma_HG_MPa, ring.sigma_HG_MPa], [1368.95, 727.36], rtol=5e-5)
    assert_allclose([planet.sigma_HP_MPa, ring.sigma_HP_MPa], [1095.16, 581.89], rtol=5e-5)
    assert_allclose([planet.S_H, ring.S_H], [1.80, 0.96], atol=5e-3)  # SHBD


def test_planet_root_on_the_ring_side():
    planet = _rating(_doc()).pinion
    assert_allclose([planet.Y_F, planet.Y_S], [1.14, 2.38], atol=5e-3)  # YF, YS (planet, ring side)
    assert_allclose(planet.sigma_F0_MPa, 95.70, atol=5e-3)  # sigF0
    # sigF 154.50: K_Fβ from the rack's tooth depth (1.1184) against the report's 1.1182 (printed 1.12), 2e-4
    assert_allclose(planet.sigma_F_MPa, 154.50, rtol=3e-4)
    assert_allclose([planet.Y_delta_rel_T, planet.Y_R_rel_T, planet.Y_X, planet.Y_NT],
                    [1.005, 0.957, 0.800, 0.906], atol=5e-4)  # YdrelT, YRrelT, YX, YNT


def test_load_sharing_factor_scales_the_ring_mesh_like_the_sun_mesh():
    """K_γ multiplies the most loaded planet's force on both meshes: σ_H ∝ √K_γ, σ_F ∝ K_γ; ISO's nominal σ_H0 and
    σ_F0 (the nominal force's) stay, K_γ is listed with the load factors."""
    base, shared = _rating(_doc()), _rating(_doc(1.1))
    assert shared.K_gamma == 1.1 and base.K_gamma == 1.0
    assert_allclose(shared.sigma_H0_MPa, base.sigma_H0_MPa, rtol=1e-12)
    assert_allclose(shared.sigma_H_MPa / base.sigma_H_MPa, 1.1 ** 0.5, rtol=1e-12)
    for member in ("pinion", "gear"):  # the planet's and the ring's root
        a, b = getattr(base, member), getattr(shared, member)
        assert_allclose(b.sigma_F0_MPa, a.sigma_F0_MPa, rtol=1e-12)
        assert_allclose(b.sigma_F_MPa / a.sigma_F_MPa, 1.1, rtol=1e-12)


def test_ring_pitting_below_minimum_is_a_warning():
    """The report's ring S_H 0.96 is below S_Hmin 1.25: a ``pitting_safety_low`` warning naming the ring's mesh."""
    result = compute_design(DesignFile.model_validate(_doc()))
    hits = [d for d in result.diagnostics if d.code == "pitting_safety_low" and d.data.get("mesh") == "planet_ring"]
    assert [d.data["member"] for d in hits] == ["ring"]
    assert "planet–ring" in hits[0].message


def _stage(doc: dict):
    st = compute_design(DesignFile.model_validate(doc)).stages[0]
    assert st.planetary is not None and st.rating is not None
    return st


def test_planet_is_an_idler_in_both_meshes():
    """Y_M = 0.7 on the planet's σ_FG, sun side and ring side alike (report: YM 1.000 / 0.700 / 1.000;
    sigFG 586.11 / 419.35 / 429.14; sigFP 375.71 / 268.82 / 275.09; SF 3.33 / 2.48 / 2.71 / 2.79)."""
    st = _stage(_doc())
    sun, planet_sun_side = st.rating.pinion, st.rating.gear
    planet = st.planetary.planet_ring.rating.pinion
    assert (sun.Y_M, planet_sun_side.Y_M, planet.Y_M) == (1.0, 0.7, 0.7)
    # by hand: σ_FG = σ_Flim Y_ST Y_NT Y_δrelT Y_RrelT Y_X Y_M = 430 · 2 · 0.906 · 1.005 · 0.957 · 0.800 · 0.7
    hand = 430.0 * 2.0 * planet.Y_NT * planet.Y_delta_rel_T * planet.Y_R_rel_T * planet.Y_X * 0.7
    assert_allclose(planet.sigma_FG_MPa, hand, rtol=1e-12)
    assert_allclose([planet.sigma_FG_MPa, planet_sun_side.sigma_FG_MPa], [419.35, 419.35], atol=5e-3)  # sigFG
    # sigFP 268.82 is the unrounded σ_FG/1.56: 419.35/1.56 = 268.814, so 1e-2
    assert_allclose(planet.sigma_FP_MPa, 268.82, atol=1e-2)
    assert_allclose(planet.S_F, 2.71, atol=5e-3)  # SF on the ring side, σ_F 154.50 as printed
    assert_allclose(planet.S_F, planet.sigma_FG_MPa / planet.sigma_F_MPa, rtol=1e-12)
    assert_allclose(planet_sun_side.S_F, planet_sun_side.sigma_FG_MPa / planet_sun_side.sigma_F_MPa, rtol=1e-12)


def test_ring_root_geometry_against_the_report():
    """The ring's root by ISO 6336-3's internal gear method with the report's ring inputs (z 56, m_n 45,
    x −0.5013, d_a 2475.118, ε_α 1.278, ρ_fP* 0.30, cutter z0 36). Printed: hF* 1.742, alfFen 19.59°,
    sFn* 2.875, roF* 0.494, dsFn −2673.522, alfsFn 60°, YF 1.27, YS 2.13."""
    m = 45.0
    f = rr.internal_tooth_form(56, m, math.radians(20.0), 0.0, 0.0, -0.5013, 2475.118, 2520.0, 1.278, (1.25, 0.30),
                               cutter_teeth=36)
    # the load point is pure involute geometry (outer point of single contact of the ring, d-B.e 2497.731)
    assert_allclose(math.degrees(f["alpha_Fen"]), 19.59, atol=5e-3)
    assert_allclose(f["d_en"], 2497.731, atol=0.2)  # ε_α printed to 3 decimals: ±0.0005 p_bt = ±0.07 mm roll
    # the fillet: gearcli takes the standard's rack-generated trochoid at the 60° tangent (z_n < 0) with the
    # cutter's z0 in ρ_F; the report computes Y_F, Y_S "with pinion type cutter" from its own tooth form.
    # s_Fn 0.6 %, ρ_F 0.7 %,
    # h_Fe 0.9 % and the section's diameter 0.07 % apart, so 1e-2 (1e-3 for d_sFn)
    assert_allclose([f["s_Fn"] / m, f["rho_F"] / m, f["h_Fe"] / m], [2.875, 0.494, 1.742], rtol=1e-2)
    assert_allclose(f["d_sFn"], 2673.522, rtol=1e-3)
    # hence Y_F 2 % above the printed 1.27 (Y_F ∝ h_Fe/s_Fn²), Y_S within 0.5 %
    assert_allclose(f["Y_F"], 1.27, rtol=2.5e-2)
    assert_allclose(f["Y_S"], 2.13, rtol=5e-3)
    # the method-B expressions themselves, fed the report's printed root geometry, give its Y_F and Y_S
    s, h, rho, alpha = 2.875, 1.742, 0.494, math.radians(19.59)
    ell, q = s / h, s / (2.0 * rho)
    assert_allclose(6.0 * h * math.cos(alpha) / (s * s * math.cos(math.radians(20.0))), 1.27, atol=5e-3)
    assert_allclose((1.2 + 0.13 * ell) * q ** (1.0 / (1.21 + 2.3 / ell)), 2.13, atol=5e-3)


def test_ring_root_without_cutter_takes_the_substitute_racks_fillet():
    """Without a cutter the fillet is the substitute rack's: ρ_F = ρ_fP exactly; a finite cutter rounds it more
    (ρ_F > ρ_fP, the internal gear's fillet is generated by a convex tool tip rolling inside it), so Y_S is
    larger (conservative) with the rack."""
    args = (56, 45.0, math.radians(20.0), 0.0, 0.0, -0.5013, 2475.118, 2520.0, 1.278, (1.25, 0.30))
    rack, cutter = rr.internal_tooth_form(*args), rr.internal_tooth_form(*args, cutter_teeth=36)
    assert rack["rho_F"] == 0.30 * 45.0
    assert cutter["rho_F"] > rack["rho_F"] and rack["Y_S"] > cutter["Y_S"]
    assert rack["s_Fn"] == cutter["s_Fn"] and rack["Y_F"] == cutter["Y_F"]  # ρ_F enters Y_S only


def test_internal_rim_factor_by_hand():
    """Y_B of an internal gear: 1.15 ln(8.324 m_n/s_R) for 1.75 < s_R/m_n < 3.5, 1 from 3.5 (continuous there to
    3 decimals), held at its 1.75 value below; no rim given: 1 (the report's ring, Y_B 1.00)."""
    assert rr.internal_rim_factor(None, 45.0) == 1.0
    assert rr.internal_rim_factor(157.5, 45.0) == 1.0  # the NREL ring: 3.5 m_n
    assert_allclose(rr.internal_rim_factor(2.5 * 100.0, 100.0), 1.15 * math.log(8.324 / 2.5), rtol=1e-12)
    assert_allclose(1.15 * math.log(8.324 / 3.5), 1.0, atol=5e-3)
    assert rr.internal_rim_factor(4.0 * 100.0, 100.0) == 1.0
    assert rr.internal_rim_factor(100.0, 100.0) == rr.internal_rim_factor(175.0, 100.0)


def test_ring_root_end_to_end():
    """The ring's root in the design: the factors independent of the cutter and of the ring's own rack match the
    report (YRrelT 0.957, YX 0.850, YNT 0.907, YM 1.000, σ_F/σ_F0 = 153.89/95.32); the ring's rim, 157.5 mm =
    3.5 m_n, gives the report's Y_B 1.00 (before 2026-12-01 gearcli measured it in tooth depths, s_R/h_t = 1.56, and
    held Y_B at 1.15 ln(8.324/1.75) = 1.79)."""
    st = _stage(_doc())
    r = st.planetary.planet_ring.rating
    planet, ring = r.pinion, r.gear
    assert ring.S_F is not None and ring.Y_M == 1.0
    assert_allclose([ring.Y_R_rel_T, ring.Y_X, ring.Y_NT], [0.957, 0.850, 0.907], atol=5e-4)
    assert ring.Y_B == 1.0
    # the mesh's load factors act on both roots alike: K_A K_v K_Fβ K_Fα = 153.89/95.32 = 1.61446 (±1e-4 from
    # the printed digits), the planet's 154.50/95.70
    assert_allclose(ring.sigma_F_MPa / ring.sigma_F0_MPa, 153.89 / 95.32, rtol=2e-4)
    assert_allclose(ring.sigma_F_MPa / ring.sigma_F0_MPa, planet.sigma_F_MPa / planet.sigma_F0_MPa, rtol=1e-12)
    # σ_F0 = F_t/(b m_n) Y_F Y_S Y_β Y_B Y_DT with the planet's F_t/(b m_n) (the same force on both flanks)
    nominal = planet.sigma_F0_MPa / (planet.Y_F * planet.Y_S)
    assert_allclose(ring.sigma_F0_MPa, nominal * ring.Y_F * ring.Y_S * ring.Y_B, rtol=1e-12)
    # σ_FG/Y_δrelT = 580 · 0.907 · 0.957 · 0.850 = 429.14/1.003 (the report interpolates Y_δrelT by N_L and takes
    # the slip layer from the ring's yield point; gearcli's Y_δrelT is the fatigue value of a typical grade)
    assert_allclose(ring.sigma_FG_MPa / ring.Y_delta_rel_T, 429.14 / 1.003, rtol=1e-3)
    assert_allclose(ring.S_F, ring.sigma_FG_MPa / ring.sigma_F_MPa, rtol=1e-12)


def test_internal_mesh_resonance_against_the_report():
    """The planet–ring mesh's own ISO 6336-1 resonance: m_red = the planet's m* (ring infinitely heavy),
    printed mRed 2.4597 kg/mm, nE1 1435 rpm, N 0.028 (c_γα 16.063, z_p 17, planet 39.9 rpm relative)."""
    mesh = _stage(_doc()).planetary.planet_ring
    assert_allclose(mesh.reduced_mass_kg_mm, 2.4597, atol=5e-5)
    assert_allclose(mesh.resonance_speed_rpm, 1435.0, atol=0.5)
    assert_allclose(mesh.resonance_ratio, 0.028, atol=5e-4)
    # by hand from the printed c_γα and m_red: n_E1 = 30000/(π z_p) √(c_γα/m_red)
    assert_allclose(30000.0 / (math.pi * 17) * math.sqrt(16.063 / 2.4597), 1435.0, atol=0.5)


def test_internal_mesh_dynamic_factor_by_hand():
    """K_v of the planet–ring mesh from its own N (subcritical, ISO 6336-1 method B), by hand from the report's
    printed figures: c′ 13.289, f_pb 35.70 (the ring's fpbT), f_fα 40.00 (the ring's ffaT), y_α 5.419, y_f 6.071,
    F_t 779 454.877 N × K_A K_γ 1.375 over b 491, ε_γ 1.278 (C_v1 0.32, C_v2 0.34, C_v3 0.23), no tip relief
    (B_k = 1), N = 39.9/1435. The report itself uses a given K_v 1.05 for this mesh."""
    doc = _doc()
    doc["rating"]["dynamic_factor"] = "iso"
    st = _stage(doc)
    r = st.planetary.planet_ring.rating
    assert r is not None and r.K_v_source == "iso"
    line_load = 779454.877 * 1.375 / 491.0
    b_p, b_f = 13.289 * (35.70 - 5.419) / line_load, 13.289 * (40.00 - 6.071) / line_load
    hand = 1.0 + 39.9 / 1435.0 * (0.32 * b_p + 0.34 * b_f + 0.23 * 1.0)
    assert_allclose(r.K_v, hand, atol=2e-5)  # N printed to 3 digits: ±1e-3 relative of K_v − 1 ≈ 0.01
    assert r.K_v != st.rating.K_v  # no longer the sun–planet mesh's


def test_ring_rim_below_the_standards_range_is_a_warning():
    """A 67.5 mm rim, s_R/m_n = 67.5/45 = 1.5 < 1.75: outside ISO 6336-3's internal-gear Y_B, said as
    rating_out_of_range and Y_B held at 1.15 ln(8.324/1.75); the design's 157.5 mm, 3.5 m_n (s_R/h_t 1.56), is
    inside (Y_B = 1) and quiet, and so is 2 m_n (90 mm, s_R/h_t 0.89), rated at 1.15 ln(8.324/2)."""
    def hits(doc):
        result = compute_design(DesignFile.model_validate(doc))
        return [d for d in result.diagnostics if d.code == "rating_out_of_range" and d.data.get("member") == "ring"]

    assert hits(_doc()) == []
    doc = _doc()
    doc["stage"][0]["ring"]["rim_thickness_mm"] = 67.5
    found = hits(doc)
    assert [d.data["quantity"] for d in found] == ["rim_ratio"]
    assert_allclose(found[0].data["value"], 1.5, rtol=1e-12)
    assert_allclose(_stage(doc).planetary.planet_ring.rating.gear.Y_B, 1.15 * math.log(8.324 / 1.75), rtol=1e-12)
    doc["stage"][0]["ring"]["rim_thickness_mm"] = 90.0
    assert hits(doc) == []
    assert_allclose(_stage(doc).planetary.planet_ring.rating.gear.Y_B, 1.15 * math.log(8.324 / 2.0), rtol=1e-12)


def test_sun_counts_one_load_cycle_per_planet():
    """The sun meets all three planets per turn relative to the carrier: N_L = N · 60 |n_s − n_c| H, and the
    report's sun life factors follow from it (ZNT 0.909, YNT 0.888, against 0.940 and 0.908 for one meeting);
    σ_HG 1368.61 and σ_FG 586.11 printed for gear 1 (the sun)."""
    st = compute_design(DesignFile.model_validate(_doc())).stages[0]
    assert st.planetary is not None and st.rating is not None
    sun = st.rating.pinion
    n_rel = abs(st.pinion.speed_rpm)  # the sun's speed in the carrier's frame, rpm
    assert_allclose(sun.load_cycles, 3 * 60.0 * n_rel * 175200.0, rtol=1e-12)
    assert_allclose([sun.Z_NT, sun.Y_NT], [0.909, 0.888], atol=5e-4)
    assert_allclose([sun.sigma_HG_MPa, sun.sigma_FG_MPa], [1368.61, 586.11], atol=1.5e-2)


def test_sun_planet_mesh_reduced_mass_is_the_planetary_form():
    """ISO 6336-1's planetary form for the sun–planet mesh of a planetary stage: the sun meets N = 3 planets, so
    m_red = m*_s m*_p / (m*_s + N m*_p) and n_E1 = 30000/(π z_sun) √(c_γα/m_red): the report's mRed 0.6606 kg/mm,
    nE1 2266 rpm and N 0.016 (the two-wheel form gave 1.289 kg/mm)."""
    st = compute_design(DesignFile.model_validate(_doc())).stages[0]
    assert_allclose(st.reduced_mass_kg_mm, 0.6606, atol=5e-5)
    assert_allclose(st.resonance_speed_rpm, 2266, atol=0.5)
    assert_allclose(st.resonance_ratio, 0.016, atol=5e-4)


def test_the_rings_cutter_sets_its_root_fillet():
    """`ring.cutter_teeth` (the pinion-type cutter's z_0, 36 in the report) reaches the ring's root rating: its
    Y_F, Y_S are internal_tooth_form's with that cutter (the function checked against the report's printed ring
    root above), the fillet is larger than the substitute rack's, so Y_S and σ_F fall."""
    doc = _doc()
    rack = _rating(doc).gear
    doc["stage"][0]["ring"]["cutter_teeth"] = 36
    st = compute_design(DesignFile.model_validate(doc)).stages[0]
    cut = st.planetary.planet_ring.rating.gear
    ring, mesh = st.planetary.ring, st.planetary.planet_ring
    form = rr.internal_tooth_form(ring.teeth, st.normal_module_mm, math.radians(st.normal_pressure_angle_deg),
                                  math.radians(st.helix_angle_deg), math.radians(st.base_helix_angle_deg),
                                  ring.profile_shift, ring.tip_diameter_mm, ring.pitch_diameter_mm,
                                  mesh.contact_ratio_transverse, (1.25, 0.38), cutter_teeth=36)
    assert_allclose([cut.Y_F, cut.Y_S], [form["Y_F"], form["Y_S"]], rtol=1e-12)
    assert cut.Y_S < rack.Y_S and cut.sigma_F_MPa < rack.sigma_F_MPa and cut.S_F > rack.S_F
