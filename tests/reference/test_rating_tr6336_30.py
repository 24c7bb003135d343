"""ISO 6336-2 pitting rating against ISO/TR 6336-30:2017, Annex A, example 1 (the worked example of ISO 6336).

The TR itself is not public; its printed values are quoted verbatim as the "Reference" column of the public
re-implementation by G. Rebouças (NTNU), ``MATISO_6336.m``, ``example_01`` (github.com/gfsReboucas/Drivetrain),
the same source the ISO 6336-1 stiffness test (``test_design_iso6336.py``, source A) uses.

Inputs: single helical case-carburized pair, m_n 8, α_n 20°, β 15.8°, z 17/103, b 100, x 0.145/0, a_w 500, ISO 53
profile D, grade 5, T1 9000 N·m at n1 360 rpm, K_A 1.0, 50 000 h, ν40 320 mm²/s, tip relief C_a 70 µm,
σ_Hlim 1500 N/mm², S_Hmin 1 (so σ_HP = σ_HG), K_Hβ 1.16 (the TR's own method C value, given here), flank
roughness R_a 1 µm, i.e. R_z = 6 µm (ISO's R_z ≈ 6 R_a; with it Z_R agrees to the five digits quoted).

Two inputs of the TR are not in the quote: its tip diameters (it implies ε_α = 1.5491, gearcli's ISO 21771 tips
with the tip alteration give 1.5479) and its backlash (a_w = 500 exactly; gearcli's no-backlash a_w is 499.998).
They move Z_ε by 0.039 % and Z_H by 1.5e-5; the assertions on Z_ε, σ_H0, σ_H and S_H say so.
"""

from __future__ import annotations

import math

from numpy.testing import assert_allclose

from gearcli.config.schema import DesignFile
from gearcli.design import compute_design

STEEL = {"density_kg_m3": 7800.0, "youngs_modulus_MPa": 206000.0, "poisson_ratio": 0.3,
         "treatment": "case_carburized", "contact_fatigue_limit_MPa": 1500.0, "bending_fatigue_limit_MPa": 500.0}
ROUGH = {"flank_roughness_Rz_um": 6.0, "root_roughness_Rz_um": 10.0}
TR_EPS_ALPHA = 1.5491  # implied by the TR's c_γα (test_design_iso6336.py)


def _example_1():
    stage = {"normal_module_mm": 8.0, "helix_angle_deg": 15.8, "accuracy_grade": 5, "tip_relief_um": 70.0,
             "basic_rack": {"addendum": 1.0, "dedendum": 1.4, "root_radius": 0.39},
             "pinion": {"teeth": 17, "face_width_mm": 100.0, "profile_shift": 0.145, "hand": "right", **ROUGH},
             "gear": {"teeth": 103, "face_width_mm": 100.0, "profile_shift": 0.0, "hand": "left", **ROUGH}}
    doc = {"materials": {"steel": STEEL}, "stage": [stage], "input": {"speed_rpm": 360.0},
           "load": {"torque_Nm": 9000.0 * 103 / 17}, "lubricant": {"viscosity_40C_mm2_s": 320.0},
           "rating": {"required_life_h": 50000.0, "face_load_factor": 1.16, "min_safety_pitting": 1.0}}
    stage_result = compute_design(DesignFile.model_validate(doc)).stages[0]
    return stage_result, stage_result.rating


def test_load_speed_and_cycles():
    st, r = _example_1()
    assert_allclose(st.static_force_N.tangential, 127352.0, rtol=5e-6)  # F_t
    assert_allclose(math.pi * st.pinion.pitch_diameter_mm * 360.0 / 60000.0, 2.664, atol=5e-4)  # v
    assert_allclose(r.pinion.load_cycles, 1.080e9, rtol=5e-4)  # N_L1
    assert_allclose(r.gear.load_cycles, 1.783e8, rtol=3e-4)  # N_L2


def test_load_factors():
    _, r = _example_1()
    assert r.K_A == 1.0 and r.K_Hbeta == 1.16  # K_Hβ as the TR computes it
    assert_allclose(r.K_v, 1.003, atol=5e-4)  # K_v
    assert (r.K_Halpha, r.K_Falpha) == (1.0, 1.0)  # K_Hα, K_Fα
    # K_Fβ 1.12803; gearcli 1.12837 from b/h with h = the rack's 2.4 m_n (the TR's value implies h = 2.428 m_n,
    # a depth it does not quote): 3e-4 relative
    assert_allclose(r.K_Fbeta, 1.12803, rtol=5e-4)


def test_pitting_factors():
    st, r = _example_1()
    assert_allclose(r.Z_E, 189.81170, atol=5e-6)  # Z_E
    assert_allclose(r.Z_beta, 1.01944, atol=5e-6)  # Z_β
    assert_allclose(r.Z_L, 1.04739, atol=5e-6)  # Z_L
    assert_allclose(r.Z_V, 0.96911, atol=5e-6)  # Z_v
    assert_allclose(r.Z_R, 0.96599, atol=5e-6)  # Z_R
    assert r.Z_W == 1.0 and r.pinion.Z_X == r.gear.Z_X == 1.0  # Z_W, Z_X
    assert r.pinion.Z_BD == r.gear.Z_BD == 1.0  # Z_B, Z_D
    assert_allclose(r.pinion.Z_NT, 0.91, atol=5e-3)  # Z_NT1 (printed 0.91)
    assert_allclose(r.gear.Z_NT, 0.962, atol=5e-4)  # Z_NT2
    # Z_H 2.39533: a_w 499.998 (no backlash) against the TR's 500.000 moves it by 1.5e-5
    assert_allclose(r.Z_H, 2.39533, rtol=2e-5)
    # Z_ε = √(1/ε_α) (ε_β = 1.083 ≥ 1): 0.803 at the TR's ε_α, 0.8038 at gearcli's
    assert_allclose(r.Z_eps, 1.0 / math.sqrt(st.contact_ratio_transverse), rtol=1e-12)
    assert_allclose(1.0 / math.sqrt(TR_EPS_ALPHA), 0.803, atol=5e-4)


def test_stresses_and_safeties():
    st, r = _example_1()
    # σ_HP = σ_HG (S_Hmin = 1): 1338.48050 / 1414.52551, to the TR's Z_NT 0.91005/0.96176 (7e-7)
    assert_allclose([r.pinion.sigma_HP_MPa, r.gear.sigma_HP_MPa], [1338.48050, 1414.52551], rtol=2e-6)
    assert_allclose([r.pinion.sigma_HG_MPa, r.gear.sigma_HG_MPa], [1338.48050, 1414.52551], rtol=2e-6)
    # σ_H0 1206.58207 once Z_ε and Z_H are taken at the TR's ε_α and a_w (see the module docstring)
    at_tr = r.sigma_H0_MPa * math.sqrt(st.contact_ratio_transverse / TR_EPS_ALPHA) * 2.39533 / r.Z_H
    assert_allclose(at_tr, 1206.58207, rtol=2e-5)
    assert_allclose(r.sigma_H0_MPa, 1206.58207, rtol=5e-4)  # as computed: 0.039 % from Z_ε
    # σ_H1 = σ_H2 = 1301.35343 and S_H 1.02853 / 1.08696: 0.039 % (Z_ε) and 0.02 % (K_v 1.00319 against the
    # TR's 1.00281, both printed 1.003): 7e-4
    assert_allclose([r.pinion.sigma_H_MPa, r.gear.sigma_H_MPa], [1301.35343, 1301.35343], rtol=7e-4)
    assert_allclose([r.pinion.S_H, r.gear.S_H], [1.02853, 1.08696], rtol=7e-4)
