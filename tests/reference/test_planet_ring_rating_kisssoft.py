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

Tolerances: half a unit of the printed last digit, widened where stated beside the assertion. Not compared: the
planet's σ_FG, σ_FP and S_F (the report applies Y_M = 0.7 to the idler planet; gearcli uses 1), and the ring's
root (Y_F 1.27, Y_S 2.13, σ_F0 95.32 printed): gearcli does not rate the internal gear's tooth root.
"""

from __future__ import annotations

from numpy.testing import assert_allclose

from gearcli.config.schema import DesignFile
from gearcli.design import compute_design
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


def test_ring_root_is_not_rated_and_says_so():
    ring = _rating(_doc()).gear
    assert ring.Y_F is None and ring.S_F is None and ring.sigma_F_MPa is None
    assert "not rated" in ring.bending_not_rated


def test_load_sharing_factor_scales_the_ring_mesh_like_the_sun_mesh():
    """K_γ multiplies the most loaded planet's force on both meshes: σ_H0 ∝ √K_γ, σ_F0 ∝ K_γ."""
    base, shared = _rating(_doc()), _rating(_doc(1.1))
    assert_allclose(shared.sigma_H0_MPa / base.sigma_H0_MPa, 1.1 ** 0.5, rtol=1e-12)
    assert_allclose(shared.pinion.sigma_F0_MPa / base.pinion.sigma_F0_MPa, 1.1, rtol=1e-12)


def test_iso_dynamic_factor_takes_the_sun_planet_meshs():
    doc = _doc()
    doc["rating"]["dynamic_factor"] = "iso"
    st = compute_design(DesignFile.model_validate(doc)).stages[0]
    assert st.planetary is not None and st.rating is not None
    r = st.planetary.planet_ring.rating
    assert r is not None and r.K_v_source == "sun_planet" and r.K_v == st.rating.K_v


def test_ring_pitting_below_minimum_is_a_warning():
    """The report's ring S_H 0.96 is below S_Hmin 1.25: a ``pitting_safety_low`` warning naming the ring's mesh."""
    result = compute_design(DesignFile.model_validate(_doc()))
    hits = [d for d in result.diagnostics if d.code == "pitting_safety_low" and d.data.get("mesh") == "planet_ring"]
    assert [d.data["member"] for d in hits] == ["ring"]
    assert "planet–ring" in hits[0].message
