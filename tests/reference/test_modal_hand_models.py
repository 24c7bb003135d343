"""`gearcli modes` and `simulate` on scenes of this file against linear models assembled here by hand.

Round 5's premise: modes reported 49 % off with the default mesh law and damping 0.2-110 % off. Every scene here
is this file's own (not configs/); the hand models write the mass, stiffness and damping matrices out with numpy
from the scene's numbers (inertias, couplings, base radii from ISO 21771 written out below) and solve them with
scipy.linalg.eig. The one number taken from gearcli is ISO 6336-1's c_gamma_alpha (design JSON
``iso6336_mesh_stiffness_N_mm_um``), which the ISO tests check; the hand model turns it into the mesh's normal
stiffness k_n = c_gamma_alpha b / cos^2 beta_b (DESIGN section 13) and its transverse tangent k_t = c_gamma_alpha b.

Damping: DESIGN section 6 sizes a viscous mesh c = 2 zeta sqrt(k_lin m_e) with k_lin the normal tangent k_n and
m_e = J_p J_g / (J_p r_bg^2 + J_g r_bp^2); the force c q' acts along the transverse line of action on the
transverse DTE q (gearcli/model/elements/mesh.py). A lone mesh's modal damping ratio is then
c / (2 sqrt(k_t m_e)) = zeta / cos beta_b (docs/physics.md), checked here in closed form.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from modal_hand import (
    ALPHA_N,
    BETA,
    C_L,
    C_M,
    J_FAN,
    J_G,
    J_PLANET,
    J_ROTOR,
    J_SUN,
    K_L,
    K_M,
    M_N,
    M_PLANET,
    N_IN,
    RATIO,
    STAGES,
    T_FAN,
    T_LOAD,
    Z2,
    B,
    _add,
    _base_radius_m,
    _cos_beta_b,
    _damped,
    _elastic,
    _lone_gear,
    _planetary,
    _planetary_hand,
    _run,
    _single,
    _single_hand,
    _static_normal_force_N,
    _two_stage,
    _two_stage_hand,
    _undamped_Hz,
)
from numpy.testing import assert_allclose


@pytest.mark.parametrize("exponent", [1.0, 1.5, 2.0])
def test_single_stage_modes_against_the_hand_model(tmp_path, exponent):
    """Frequencies of both boundaries and the mesh's tangent for e = 1, 1.5 (default), 2: the tangent is k_n."""
    contact = "" if exponent == 1.5 else f"[contact]\nexponent = {exponent}\n"
    text = _single(contact)
    design = _run(tmp_path, text, "design")
    cga = design["stages"][0]["iso6336_mesh_stiffness_N_mm_um"]
    J, K, C, k_n = _single_hand(cga, 0.05)
    out = _run(tmp_path, text, "modes")
    ms = out["meshes"][0]["mesh_stiffness"]
    assert ms["law"] == "iso6336" and ms["exponent"] == exponent
    assert_allclose(ms["iso_N_mm"], k_n / 1000, rtol=1e-9)  # c_gamma_alpha b / cos^2 beta_b
    assert_allclose(ms["linearised_N_mm"], k_n / 1000, rtol=1e-9)  # the tangent stays k_n for every e
    # K = k_n^e / (e^e F_n0^(e-1)), F_n0 = T / (r_bg cos beta_b)
    F_n0 = T_LOAD / _base_radius_m(Z2, M_N, ALPHA_N, BETA) / _cos_beta_b(ALPHA_N, BETA)
    K_law = (k_n / 1000) ** exponent / (exponent**exponent * F_n0 ** (exponent - 1))
    assert_allclose(ms["K"], K_law, rtol=1e-9)
    assert not any(w["code"] == "stiffness_not_iso" for w in out["warnings"])
    # free: (motor, shaft 1, shaft 2, drum); clamped_input: the motor held (it follows the prescribed speed)
    hand_free = _undamped_Hz(J, K)[1:]  # the rigid mode first
    hand_clamped = _undamped_Hz(J[1:], K[1:, 1:])
    assert_allclose([m["frequency_Hz"] for m in _elastic(out, "free")], hand_free, rtol=1e-8)
    assert_allclose([m["frequency_Hz"] for m in _elastic(out, "clamped_input")], hand_clamped, rtol=1e-8)


@pytest.mark.parametrize("zeta", [0.02, 0.1])
def test_single_stage_damping_ratios_against_the_hand_eigenvalues(tmp_path, zeta):
    """Each mode's damping ratio is -Re lambda / |lambda| of the hand model's damped eigenvalue."""
    text = _single(f"[contact]\ndamping_ratio = {zeta}\n")
    cga = _run(tmp_path, text, "design")["stages"][0]["iso6336_mesh_stiffness_N_mm_um"]
    J, K, C, _ = _single_hand(cga, zeta)
    out = _run(tmp_path, text, "modes")
    for boundary, sl in (("free", slice(0, 4)), ("clamped_input", slice(1, 4))):
        lam = _damped(J[sl], K[sl, sl], C[sl, sl])
        tool = _elastic(out, boundary)
        assert len(tool) == len(lam)
        assert_allclose([m["damping_ratio"] for m in tool], [-z.real / abs(z) for z in lam], rtol=1e-6,
                        err_msg=boundary)
        assert_allclose([m["frequency_Hz"] for m in tool], _undamped_Hz(J[sl], K[sl, sl])[-len(lam):], rtol=1e-8)


def test_lone_mesh_modal_damping_is_zeta_over_cos_beta_b(tmp_path):
    """One DOF: omega^2 = k_t r_bg^2 / J_G, and c = 2 zeta sqrt(k_n m_e) on the transverse q' with m_e = J_G / r_bg^2
    (the speed-driven pinion infinitely heavy) gives the modal ratio c / (2 sqrt(k_t m_e)) = zeta / cos beta_b."""
    zeta = 0.05
    text = _lone_gear("", "duration_s = 0.1")
    cga = _run(tmp_path, text, "design")["stages"][0]["iso6336_mesh_stiffness_N_mm_um"]
    rg, cbb = _base_radius_m(Z2, M_N, ALPHA_N, BETA), _cos_beta_b(ALPHA_N, BETA)
    k_t = cga * B * 1e6
    w_n = math.sqrt(k_t * rg**2 / J_G)
    (mode,) = _elastic(_run(tmp_path, text, "modes"), "clamped_input")
    assert_allclose(mode["frequency_Hz"], w_n / (2 * math.pi), rtol=1e-9)
    assert_allclose(mode["damping_ratio"], zeta / cbb, rtol=1e-9)


@pytest.mark.parametrize("exponent", [1.0, 1.5, 2.0])
def test_motor_driven_two_stage_train_against_the_hand_model(tmp_path, exponent):
    """Frequencies and damping ratios, free and with the motor held, for e = 1, 1.5 (default), 2."""
    contact = "" if exponent == 1.5 else f"[contact]\nexponent = {exponent}\n"
    text = _two_stage(contact)
    design = _run(tmp_path, text, "design")
    assert not design["warnings"], design["warnings"]  # the table carries the fan at 1450 rpm: balanced
    J, K, C = _two_stage_hand([s["iso6336_mesh_stiffness_N_mm_um"] for s in design["stages"]], 0.05)
    out = _run(tmp_path, text, "modes")
    for ms in out["meshes"]:
        assert_allclose(ms["mesh_stiffness"]["linearised_N_mm"], ms["mesh_stiffness"]["iso_N_mm"], rtol=1e-9)
    for boundary, sl in (("free", slice(0, 5)), ("clamped_input", slice(1, 5))):
        Cb = C[sl, sl].copy()
        lam = _damped(J[sl], K[sl, sl], Cb)
        tool = _elastic(out, boundary)
        assert len(tool) == len(lam) == (4 if boundary == "free" else 4)
        assert_allclose([m["frequency_Hz"] for m in tool], _undamped_Hz(J[sl], K[sl, sl])[-4:], rtol=1e-8,
                        err_msg=boundary)
        assert_allclose([m["damping_ratio"] for m in tool], [-z.real / abs(z) for z in lam], rtol=1e-6,
                        err_msg=boundary)


@pytest.mark.parametrize("exponent", [1.0, 1.5, 2.0])
def test_planetary_modes_against_the_hand_model(tmp_path, exponent):
    contact = "" if exponent == 1.5 else f"[contact]\nexponent = {exponent}\n"
    text = _planetary(contact)
    design = _run(tmp_path, text, "design")
    st = design["stages"][0]
    assert_allclose(st["carrier"]["planets_translational_inertia_kg_m2"], 3 * M_PLANET * 0.072**2, rtol=1e-12)
    cga = {m["name"]: m["iso6336_mesh_stiffness_N_mm_um"] for m in st["meshes"]}
    k_sp, k_pr = cga["sun_planet"] * 30e6, cga["planet_ring"] * 30e6  # spur: k_n = k_t = c_gamma_alpha b
    out = _run(tmp_path, text, "modes")
    for ms in out["meshes"]:
        k = ms["mesh_stiffness"]
        assert_allclose(k["linearised_N_mm"], k["iso_N_mm"], rtol=1e-9)
        assert_allclose(k["iso_N_mm"], (k_sp if ms["mesh"] == "sun_planet" else k_pr) / 1000, rtol=1e-9)
        assert k["exponent"] == exponent
    J, K, C = _planetary_hand(k_sp, k_pr, 0.05)
    for boundary, sl in (("free", slice(0, 5)), ("clamped_input", slice(0, 4))):
        tool = _elastic(out, boundary)
        lam = _damped(J[sl], K[sl, sl], C[sl, sl])
        assert len(tool) == len(lam) == 4
        # the planet mode (sun and carrier still) is twofold, N - 1 = 2
        assert_allclose([m["frequency_Hz"] for m in tool], _undamped_Hz(J[sl], K[sl, sl])[-4:], rtol=1e-8,
                        err_msg=boundary)
        assert_allclose([m["damping_ratio"] for m in tool], [-z.real / abs(z) for z in lam], rtol=1e-6,
                        err_msg=boundary)


def test_motor_driven_train_with_a_flexible_intermediate_shaft(tmp_path):
    """[stage.shaft] on stage 1: shaft 2 splits into its gear end (J_g1) and pinion end (J_p2) on a 20 kN m/rad,
    0.5 N m s/rad spring; each mesh's m_e then takes the end it touches."""
    text = _two_stage().replace(
        'hand = "right", material = "steel", inertia_kg_m2 = 0.02 }',
        'hand = "right", material = "steel", inertia_kg_m2 = 0.02 }\nshaft = { stiffness_Nm_rad = 20000, '
        'damping_Nms_rad = 0.5 }', 1)
    design = _run(tmp_path, text, "design")
    out = _run(tmp_path, text, "modes")
    assert out["bodies"] == ["motor", "shaft 1", "shaft 2 gear end", "shaft 2 pinion end", "shaft 3", "drum"]
    (_, _, _, _, _, jp1, jg1), (_, _, _, _, _, jp2, jg2) = STAGES
    J = np.array([J_ROTOR, jp1, jg1, jp2, jg2, J_FAN])
    K, C = np.zeros((6, 6)), np.zeros((6, 6))
    _add(K, {0: 1.0, 1: -1.0}, K_M)
    _add(C, {0: 1.0, 1: -1.0}, C_M)
    for (m, beta, zp, zg, b, _, _), st, (p, g) in zip(STAGES, design["stages"], ((1, 2), (3, 4)), strict=True):
        rp, rg = _base_radius_m(zp, m, 20.0, beta), _base_radius_m(zg, m, 20.0, beta)
        k_t = st["iso6336_mesh_stiffness_N_mm_um"] * b * 1e6
        m_e = J[p] * J[g] / (J[p] * rg**2 + J[g] * rp**2)
        _add(K, {p: rp, g: -rg}, k_t)
        _add(C, {p: rp, g: -rg}, 2 * 0.05 * math.sqrt(k_t / _cos_beta_b(20.0, beta) ** 2 * m_e))
    _add(K, {2: 1.0, 3: -1.0}, 20000.0)
    _add(C, {2: 1.0, 3: -1.0}, 0.5)
    _add(K, {4: 1.0, 5: -1.0}, K_L)
    _add(C, {4: 1.0, 5: -1.0}, C_L)
    C[0, 0] += 300.0 / (100 * math.pi / 30)
    C[5, 5] += 2 * T_FAN / (N_IN * math.pi / 30 / RATIO)
    tool = _elastic(out, "free")
    assert_allclose([m["frequency_Hz"] for m in tool], _undamped_Hz(J, K)[1:], rtol=1e-8)
    assert_allclose([m["damping_ratio"] for m in tool], [-z.real / abs(z) for z in _damped(J, K, C)], rtol=1e-6)


def test_impact_damped_mesh_modal_damping_at_its_static_penetration(tmp_path):
    """The IMPACT law (DESIGN section 4): F_n = K h^e + STEP(h, 0, 0, d, C) h'. At the static approach h0 (inside the
    ramp here, s = h0 / d) the normal damping is C s^2 (3 - 2 s); along delta (h = cos beta_b delta, F_bt = cos beta_b
    F_n) it is cos^2 beta_b times that, so the lone gear's modal ratio is cos^2 beta_b c_n / (2 sqrt(k_t m_e))."""
    C_Ns_mm, d_mm = 10.0, 0.02
    text = _lone_gear(f"[contact]\ndamping_Ns_mm = {C_Ns_mm}\nfull_damping_penetration_mm = {d_mm}\n",
                      "duration_s = 0.1")
    st = _run(tmp_path, text, "design")["stages"][0]
    (mode,) = _elastic(out := _run(tmp_path, text, "modes"), "clamped_input")
    ms = out["meshes"][0]["mesh_stiffness"]
    rg, cbb = _base_radius_m(Z2, M_N, ALPHA_N, BETA), _cos_beta_b(ALPHA_N, BETA)
    k_t = st["iso6336_mesh_stiffness_N_mm_um"] * B * 1e6
    h0 = 1.5 * _static_normal_force_N() / (k_t / cbb**2 / 1000)  # mm: the default e = 1.5, tangent k_n
    assert_allclose(ms["static_approach_mm"], h0, rtol=1e-9)
    s = h0 / d_mm
    assert 0 < s < 1  # inside the ramp
    c_n = C_Ns_mm * 1000 * s * s * (3 - 2 * s)  # N s/m
    m_e = J_G / rg**2
    assert_allclose(mode["frequency_Hz"], math.sqrt(k_t / m_e) / (2 * math.pi), rtol=1e-9)
    assert_allclose(mode["damping_ratio"], cbb**2 * c_n / (2 * math.sqrt(k_t * m_e)), rtol=1e-9)


def test_torque_driven_planetary_damping_takes_the_free_carrier(tmp_path):
    """With a torque drive no member is prescribed: a planet mesh's m_e = 1 / sum r_j^2 / J_j over the three bodies it
    joins (sun or held ring, planet, carrier with lever r_bs + r_bp or r_br - r_bp and its N m_p r_c^2)."""
    text = _planetary().replace("speed_rpm = 300", f"speed_rpm = 300\ndrive = \"torque\"\ntorque_Nm = {100 * (1 + 75 / 21)!r}")
    st = _run(tmp_path, text, "design")["stages"][0]
    cga = {m["name"]: m["iso6336_mesh_stiffness_N_mm_um"] for m in st["meshes"]}
    k_sp, k_pr = cga["sun_planet"] * 30e6, cga["planet_ring"] * 30e6
    J, K, _ = _planetary_hand(k_sp, k_pr, 0.05)
    a = math.radians(20.0)
    rbs, rbp, rbr = (z * 1.5 * math.cos(a) / 1000 for z in (21, 27, 75))
    c_sp = 0.1 * math.sqrt(k_sp / (rbs**2 / J_SUN + rbp**2 / J_PLANET + (rbs + rbp) ** 2 / J[4]))
    c_pr = 0.1 * math.sqrt(k_pr / (rbp**2 / J_PLANET + (rbr - rbp) ** 2 / J[4]))
    C = np.zeros((5, 5))
    for p in (1, 2, 3):
        _add(C, {0: rbs, p: rbp, 4: -(rbs + rbp)}, c_sp)
        _add(C, {p: rbp, 4: rbr - rbp}, c_pr)
    tool = _elastic(_run(tmp_path, text, "modes"), "free")
    assert_allclose([m["frequency_Hz"] for m in tool], _undamped_Hz(J, K)[1:], rtol=1e-8)
    assert_allclose([m["damping_ratio"] for m in tool], [-z.real / abs(z) for z in _damped(J, K, C)], rtol=1e-6)

