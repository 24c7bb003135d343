"""The contact law's coefficient K, the static approach, and ISO 6336-1 edge cases (zero load, K_A).

Seed stage 1 numbers used below (hand calculations in tests/reference/test_design_seed.py):
F_t = 1851.098 N, F_n = 2013.906 N, b = 180 mm, β_b = 11.26652°, cos² β_b = 0.961829,
c_γα = 10.70303 N/(mm·µm), Hertz K = 1.439239e6 N/mm^1.5.
"""

from __future__ import annotations

import copy
import math
import tomllib
from pathlib import Path

import pytest
from numpy.testing import assert_allclose

from gearcli.config.schema import Contact, DesignFile
from gearcli.design import compute_design, contact_stiffness_N_mm_e
from gearcli.design import stiffness as stf

SEED = Path(__file__).resolve().parents[2] / "configs" / "concrete_mixer.toml"
with SEED.open("rb") as _fh:
    SEED_DOC = tomllib.load(_fh)

# k_n = c_γα b / cos² β_b = 10.70303 · 180 · 1000 / 0.961829 = 2.003002e6 N/mm
K_N_STAGE1 = 2.003002e6


def design(contact=None, load_Nmm=None, k_a=None, stage_mesh=None):
    doc = copy.deepcopy(SEED_DOC)
    if contact is not None:
        doc["contact"] = {**doc["contact"], **contact}
    if load_Nmm is not None:
        doc["load"]["torque_Nmm"] = load_Nmm
    if k_a is not None:
        doc["load"]["application_factor"] = k_a
    if stage_mesh is not None:
        doc["stage"][0]["mesh"] = stage_mesh
    cfg = DesignFile.model_validate(doc)
    return cfg, compute_design(cfg)


def test_hertz_law_gives_the_hertz_coefficient_whatever_the_exponent():
    cfg, r = design()
    s = r.stages[0]
    for e in (1.0, 1.5, 2.2):
        assert_allclose(contact_stiffness_N_mm_e(s, Contact(stiffness="hertz", exponent=e)),
                        1.439239e6, rtol=1e-6)  # 4/3 √R E*, used as-is


def test_numeric_law_is_that_number():
    _, r = design()
    assert_allclose(contact_stiffness_N_mm_e(r.stages[1], Contact(stiffness=3.5e5, exponent=1.2)), 3.5e5, rtol=0)


def test_iso6336_linear_law_is_the_iso_normal_stiffness():
    cfg, r = design(contact={"stiffness": "iso6336", "exponent": 1.0})
    s = r.stages[0]
    k = contact_stiffness_N_mm_e(s, cfg.contact_for(0))
    assert_allclose(k, K_N_STAGE1, rtol=1e-6)
    # the stage's static point follows the stage's own law: h0 = F_n / k_n = 2013.906 / 2.003002e6 = 1.005444e-3 mm
    assert_allclose(s.static_approach_mm, 1.005444e-3, rtol=1e-6)
    assert_allclose(s.linearised_stiffness_N_mm, K_N_STAGE1, rtol=1e-6)  # e = 1: k_lin = K


def test_iso6336_nonlinear_law_has_the_iso_tangent_at_the_static_load():
    cfg, r = design(contact={"stiffness": "iso6336", "exponent": 1.5})
    s = r.stages[0]
    k = contact_stiffness_N_mm_e(s, cfg.contact_for(0))
    # the tangent is calibrated (DESIGN section 13): e K h0^(e-1) = k_n with K h0^e = F_n, so h0 = e F_n / k_n
    # = 1.5 · 2013.906 / 2.003002e6 = 1.508166e-3 mm (1.5x ISO's F_n/k_n) and
    # K = F_n / h0^1.5 = 2013.906 / 5.856978e-5 = 3.438473e7 N/mm^1.5
    assert_allclose(k, 3.438473e7, rtol=1e-6)
    assert_allclose(s.static_approach_mm, 1.508166e-3, rtol=1e-6)
    # k_lin = 1.5 K √h0 = 1.5 · 3.438473e7 · 0.03883511 = 2.003002e6 = k_n
    assert_allclose(s.linearised_stiffness_N_mm, K_N_STAGE1, rtol=1e-6)
    ms = s.mesh_stiffness
    assert ms.law == "iso6336" and ms.exponent == 1.5
    assert_allclose([ms.K, ms.linearised_N_mm, ms.iso_N_mm], [3.438473e7, K_N_STAGE1, K_N_STAGE1], rtol=1e-6)


def test_stage_mesh_override_applies_to_that_stage_only():
    cfg, r = design(stage_mesh={"stiffness": 2.0e6, "exponent": 1.0})
    # stage 1: linear 2e6 N/mm -> h0 = 2013.906 / 2e6 = 1.006953e-3 mm; stage 2 keeps Hertz e = 1.5
    assert_allclose(r.stages[0].static_approach_mm, 1.006953e-3, rtol=1e-6)
    assert_allclose(r.stages[0].linearised_stiffness_N_mm, 2.0e6, rtol=0)
    assert_allclose(contact_stiffness_N_mm_e(r.stages[1], cfg.contact_for(1)), r.stages[1].hertz_stiffness_N_mm1_5,
                    rtol=0)


def test_application_factor_raises_the_iso_line_load():
    _, r = design(k_a=1.5)
    # F_t K_A / b = 1851.098 · 1.5 / 180 = 15.4258 N/mm: factor 0.154258^0.25 = 0.626703
    # c' = 12.94139 · 0.626703 = 8.110411 (12.94139 = full-load c', see the reference test)
    assert_allclose(r.stages[0].iso6336_single_pair_stiffness_N_mm_um, 8.110411, rtol=1e-6)


def test_full_load_factor_is_one_above_100_N_per_mm():
    assert stf.low_load_factor(100.0) == 1.0 and stf.low_load_factor(250.0) == 1.0  # min(…, 1) exactly
    assert_allclose(stf.low_load_factor(50.0), 0.5 ** 0.25, rtol=1e-15)


def test_c_gamma_alpha_is_not_reduced_below_1_2():
    # c' = 10: ε_α = 1.3 -> 10 (0.975 + 0.25) = 12.25; ε_α = 1.1 -> 10 (0.825 + 0.25) = 10.75 (no 0.9 factor:
    # KISSsoft prints the unreduced product at ε_α = 1.115, tests/reference/test_design_iso6336_kisssoft.py)
    assert_allclose(stf.mesh_stiffness_N_mm_um(10.0, 1.3), 12.25, rtol=1e-15)
    assert_allclose(stf.mesh_stiffness_N_mm_um(10.0, 1.1), 10.75, rtol=1e-15)


def test_basic_rack_factor():
    # h_fP = 1.25 m_n: C_B = 1 + 0.5 (1.2 − 1.25) = 0.975
    # α_n = 25°: × (1 − 0.02 · (−5)) = 0.975 · 1.1 = 1.0725
    assert_allclose(stf.basic_rack_factor(20.0), 0.975, rtol=1e-15)
    assert_allclose(stf.basic_rack_factor(25.0), 1.0725, rtol=1e-15)


def test_q_prime_profile_shift_terms():
    # z_n = 30/60, x = 0.5/−0.2:
    # q' = 0.04723 + 0.15551/30 + 0.25791/60 − 0.00635·0.5 − 0.11654·0.5/30 − 0.00193·(−0.2)
    #      − 0.24188·(−0.2)/60 + 0.00529·0.25 + 0.00182·0.04
    #    = 0.04723 + 0.00518367 + 0.00429850 − 0.003175 − 0.00194233 + 0.000386 + 0.00080627
    #      + 0.0013225 + 0.0000728 = 0.05418241
    assert_allclose(stf.flexibility_q_prime(30.0, 60.0, 0.5, -0.2), 0.05418241, rtol=1e-6)


# ------------------------------------------------------------------------------------- zero load
def test_zero_load_hertz_law_has_zero_approach_and_zero_tangent_stiffness():
    _, r = design(load_Nmm=0.0)
    s = r.stages[0]
    assert s.static_force_N.tangential == 0.0 and s.static_approach_mm == 0.0  # exact zeros: 0/r, 0^(2/3)
    assert s.linearised_stiffness_N_mm == 0.0
    assert r.input_torque_Nmm == 0.0


def test_zero_load_iso6336_is_evaluated_at_one_newton_per_mm():
    cfg, r = design(load_Nmm=0.0, contact={"stiffness": "iso6336", "exponent": 1.5})
    s = r.stages[0]
    # floored F_t = 1 N/mm · 180 mm = 180 N, K_A = 1: factor (1/100)^0.25 = 0.3162278
    # c' = 12.94139 · 0.3162278 = 4.092426; c_γα = 4.092426 · 1.460450 = 5.976785
    assert_allclose(s.iso6336_single_pair_stiffness_N_mm_um, 4.092426, rtol=1e-6)
    assert_allclose(s.iso6336_mesh_stiffness_N_mm_um, 5.976785, rtol=1e-6)
    # F_n0 = 180 / (cos 20° cos 12°) = 195.8314 N; k_n = 5.976785 · 180000 / 0.961829 = 1.118516e6 N/mm
    # tangent calibration: h0 = 1.5 F_n0 / k_n = 2.626221e-4 mm, K = F_n0 / h0^1.5 = 195.8314 / 4.255954e-6
    # = 4.601351e7 N/mm^1.5
    k = contact_stiffness_N_mm_e(s, cfg.contact_for(0))
    assert math.isfinite(k) and k > 0
    assert_allclose(k, 4.601351e7, rtol=5e-6)  # 6-7 digit intermediates above
    # mesh_stiffness reports the law at the load it is calibrated at (floored): its tangent is ISO's there
    assert_allclose(s.mesh_stiffness.linearised_N_mm, 1.118516e6, rtol=5e-6)
    assert s.static_approach_mm == 0.0 and s.linearised_stiffness_N_mm == 0.0  # e > 1 and no load


def test_zero_load_linear_law_keeps_its_stiffness():
    _, r = design(load_Nmm=0.0, contact={"stiffness": 1.0e6, "exponent": 1.0})
    assert r.stages[2].linearised_stiffness_N_mm == 1.0e6  # e = 1: k_lin = K exactly, h0 = 0


@pytest.mark.parametrize("law", ["hertz", "iso6336"])
def test_load_reversal_mirrors_forces_and_keeps_the_approach(law):
    _, fwd = design(contact={"stiffness": law})
    _, rev = design(load_Nmm=-5.31e6, contact={"stiffness": law})
    for a, b in zip(fwd.stages, rev.stages, strict=True):
        assert_allclose([b.static_force_N.tangential, b.static_force_N.normal],
                        [-a.static_force_N.tangential, -a.static_force_N.normal], rtol=1e-12)  # sign only
        assert_allclose(b.static_approach_mm, a.static_approach_mm, rtol=1e-12)  # back flank, same |F_n|
        assert_allclose(b.iso6336_mesh_stiffness_N_mm_um, a.iso6336_mesh_stiffness_N_mm_um, rtol=1e-12)
