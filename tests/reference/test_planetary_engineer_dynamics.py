"""The dynamics, modes, life and simulated rating of the engineer's own planetary scene A (sun 24 / planets 36 /
ring 96, m_n 4, b 40, sun in at 1500 rpm, ring held, 5000 N·m on the carrier), checked by hand: a hand-assembled
eigenproblem, the rigid limit of the simulation, load cycles, ISO 6336-2 nominal stresses and a series-spring
model of load sharing. The scene and its hand geometry: tests/reference/test_planetary_engineer_hand.py.
"""

from __future__ import annotations

import math

from numpy.testing import assert_allclose

from tests.reference.test_planetary_engineer_hand import (
    A_W,
    ALPHA,
    J_PLANET,
    J_SUN,
    M_N,
    M_PLANET,
    N_IN,
    P_BT,
    R_P,
    R_R,
    R_S,
    RB_P,
    RB_R,
    RB_S,
    T_OUT,
    Z_P,
    Z_R,
    Z_S,
    B,
    U,
    _hand_k_sp_k_pr,
    _run_json,
    scene_a,
)


def test_modes_against_a_hand_assembled_eigenproblem(tmp_path):
    """Bodies (absolute angles): sun, N planets, carrier (its inertia N m_p a^2: no own inertia, no load inertia).
    Along planet j's sun mesh d = r_bs (th_s - th_c) + r_bp (th_j - th_c); along its ring mesh (ring held)
    d = -r_bp (th_j - th_c) - r_br th_c, both from the pitch-point kinematics in the carrier's frame. K = sum k v v^T,
    J diagonal, w^2 from det(K - w^2 J) = 0; clamped_input holds the sun. The modes are load-independent here as
    the iso6336 law is calibrated to the tangent k_n at the static load (DESIGN section 13)."""
    import numpy as np
    from scipy.linalg import eigh

    data = _run_json(tmp_path, "modes", scene_a())
    k_sp, k_pr = _hand_k_sp_k_pr()
    rb_s, rb_p, rb_r = RB_S * 1e-3, RB_P * 1e-3, RB_R * 1e-3
    n = 3
    k = np.zeros((n + 2, n + 2))  # sun, planets, carrier
    for j in range(n):
        v = np.zeros(n + 2)
        v[0], v[1 + j], v[-1] = rb_s, rb_p, -(rb_s + rb_p)
        k += k_sp * np.outer(v, v)
        v = np.zeros(n + 2)
        v[1 + j], v[-1] = -rb_p, rb_p - rb_r
        k += k_pr * np.outer(v, v)
    j_c = n * M_PLANET * (A_W * 1e-3) ** 2
    m = np.diag([J_SUN, *(n * [J_PLANET]), j_c])
    free = np.sqrt(np.abs(eigh(k, m, eigvals_only=True))) / (2 * math.pi)
    clamped = np.sqrt(eigh(k[1:, 1:], m[1:, 1:], eigvals_only=True)) / (2 * math.pi)
    got = {b: sorted(x["frequency_Hz"] for x in modes) for b, modes in data["boundaries"].items()}
    assert_allclose(got["clamped_input"], clamped, rtol=1e-9)
    assert_allclose(got["free"][1:], free[1:], rtol=1e-9)
    assert got["free"][0] == 0.0
    # the planet mode, N - 1 fold, in closed form: sun and carrier still, w^2 = (k_sp + k_pr) r_bp^2 / J_p
    planet_mode = math.sqrt((k_sp + k_pr) * rb_p**2 / J_PLANET) / (2 * math.pi)
    assert_allclose(sorted(got["clamped_input"])[1:3], [planet_mode] * 2, rtol=1e-9)


def test_simulate_rigid_limit_mean_forces_equal_the_static_design(tmp_path):
    """No excitation, constant stiffness, no losses: over the settled window the mean of every planet's sun- and
    ring-mesh F_t equals T_sun / (N r_s), the mean input torque T_out / i, the speed ratio 1 + u (conservation of
    the mean; energy residual small)."""
    text = scene_a() + "\n[simulation]\nduration_s = 0.2\nsteps = 2000\n"
    text = text.replace(f"speed_rpm = {N_IN}", f"speed_rpm = {N_IN}\nramp_s = 0.04").replace(
        f"torque_Nm = {T_OUT}", f"torque_Nm = {T_OUT}\nramp_s = 0.04")
    s = _run_json(tmp_path, "simulate", text)["summary"]
    f_t = T_OUT / (1 + U) * 1e3 / (3 * R_S)
    st = s["stages"][0]
    means = [p[m]["tangential_N"]["mean"] for p in st["planets"] for m in ("sun", "ring")]
    assert_allclose(means, [f_t] * 6, rtol=1e-7)  # the settled window's integral mean; solver rtol 1e-6
    assert_allclose(st["load_sharing_factor"], 1.0, atol=1e-9)
    assert_allclose(s["input_torque_Nm"], T_OUT / (1 + U), rtol=1e-7)
    assert_allclose(s["ratio"], 1 + U, rtol=1e-9)


def test_life_static_load_cycles_of_every_member_by_hand(tmp_path):
    """Cycles per duty point: sun h 60 |n_s - n_c| N, planet (either flank) h 60 |n_p,rel|, ring h 60 |n_r - n_c| N;
    ring held, sun 1500 rpm: n_c = 300, n_p,rel = 24/36 x 1200 = 800 rpm."""
    rated = scene_a().replace('material = "steel"', 'material = "steel", flank_roughness_Rz_um = 4, '
                                                    'root_roughness_Rz_um = 16')
    rated = rated.replace(f"normal_module_mm = {M_N}", f"normal_module_mm = {M_N}\naccuracy_grade = 6")
    rated = rated.replace("poisson_ratio = 0.3", 'poisson_ratio = 0.3\ntreatment = "case_carburized"\n'
                          "contact_fatigue_limit_MPa = 1500\nbending_fatigue_limit_MPa = 430")
    rated += ("\n[lubricant]\nviscosity_40C_mm2_s = 220\n\n[rating]\nrequired_life_h = 20000\nface_load_factor = 1.15"
              "\nload_sharing_factor = 1.1\n\n[[duty]]\nname = \"full\"\nhours = 1000\ntorque_Nm = 5000\n"
              "speed_rpm = 1500\n")
    stage = _run_json(tmp_path, "life", rated, "--static")["life"]["stages"][0]
    h = 1000.0
    cycles = {"pinion": h * 60 * 1200 * 3, "gear": h * 60 * 800, "ring": h * 60 * 300 * 3,
              "planet_ring_side": h * 60 * 800}
    for member, n_l in cycles.items():
        for mode in ("pitting", "bending"):
            assert_allclose([b["cycles"] for b in stage[member][mode]["bins"]], [n_l], rtol=1e-12)
    # the rated force is the mean planet's (K_gamma acts in the stress): T_sun / (N r_s)
    assert_allclose(stage["pinion"]["pitting"]["bins"][0]["force_N"], 1000e3 / (3 * R_S), rtol=1e-12)


# ------------------------------------------------- the planet–ring rating at the simulated K_v keeps ISO's books
def _rated_a(dynamic_factor: str) -> str:
    text = scene_a().replace('material = "steel"', 'material = "steel", flank_roughness_Rz_um = 4, '
                                                   'root_roughness_Rz_um = 16')
    text = text.replace(f"normal_module_mm = {M_N}", f"normal_module_mm = {M_N}\naccuracy_grade = 6")
    text = text.replace("poisson_ratio = 0.3", 'poisson_ratio = 0.3\ntreatment = "case_carburized"\n'
                        "contact_fatigue_limit_MPa = 1500\nbending_fatigue_limit_MPa = 430")
    return text + ("\n[lubricant]\nviscosity_40C_mm2_s = 220\n\n[rating]\nrequired_life_h = 20000\n"
                   f"face_load_factor = 1.15\nload_sharing_factor = 1.1\ndynamic_factor = {dynamic_factor}\n"
                   "\n[simulation]\nduration_s = 0.2\nsteps = 2000\n")


def test_planet_ring_rating_at_the_simulated_k_v_lists_k_gamma_and_the_nominal_stress(tmp_path):
    """ISO 6336-2 for the internal planet–ring mesh (spur, x = 0): sigma_H0 = Z_H Z_E Z_eps sqrt(F_t/(d_p b) (u - 1)/u),
    u = z_r/z_p, F_t the MEAN planet's force (nominal); Z_H = sqrt(2 cos(b_b) cos(a_wt) / (cos^2(a_t) sin(a_wt)))
    = sqrt(2 / (cos a sin a)) at beta = 0, a_wt = a_t; Z_E = sqrt(E / (2 pi (1 - nu^2)));
    Z_eps = sqrt((4 - e_a)/3). sigma_H = sigma_H0 sqrt(K_A K_gamma K_v K_Hb K_Ha): K_gamma applied once and listed.
    With dynamic_factor = "simulated", simulate's planet_ring_rating listed K_gamma = 1 and a sigma_H0 inflated by
    sqrt(K_gamma) (the sun mesh's and the design's ring rating did it right)."""
    ra_p, ra_r = R_P + M_N, R_R - M_N
    e_pr = (math.sqrt(ra_p**2 - RB_P**2) - math.sqrt(ra_r**2 - RB_R**2) + A_W * math.sin(ALPHA)) / P_BT
    z_h = math.sqrt(2.0 / (math.cos(ALPHA) * math.sin(ALPHA)))
    z_e = math.sqrt(206000.0 / (2 * math.pi * (1 - 0.3**2)))
    z_eps = math.sqrt((4 - e_pr) / 3)
    f_t = T_OUT / (1 + U) * 1e3 / (3 * R_S)
    u = Z_R / Z_P
    sigma_h0 = z_h * z_e * z_eps * math.sqrt(f_t / (2 * R_P * B) * (u - 1) / u)
    design = _run_json(tmp_path, "design", _rated_a('"iso"'))["stages"][0]["meshes"][1]["rating"]
    sim = _run_json(tmp_path, "simulate", _rated_a('"simulated"'))["summary"]["stages"][0]["planet_ring_rating"]
    for r in (design, sim):
        assert r["K_gamma"] == 1.1
        assert_allclose(r["sigma_H0_MPa"], sigma_h0, rtol=1e-12)
        assert_allclose(r["sigma_H_MPa"], sigma_h0 * math.sqrt(r["K_A"] * 1.1 * r["K_v"] * r["K_Hbeta"]
                                                               * r["K_Halpha"]), rtol=1e-12)
    assert sim["K_v_source"] == "simulated" and design["K_v_source"] == "iso"
    # the sun–planet mesh (external): sigma_H0 = Z_H Z_E Z_eps sqrt(F_t/(d_s b) (u + 1)/u), u = z_p/z_s, and
    # F_t K_gamma in sigma_H: the most loaded planet's T_sun K_gamma / (N r_s)
    ra_s, ra_p = R_S + M_N, R_P + M_N
    e_sp = (math.sqrt(ra_s**2 - RB_S**2) + math.sqrt(ra_p**2 - RB_P**2) - A_W * math.sin(ALPHA)) / P_BT
    u_sp = Z_P / Z_S
    sigma_h0_sp = z_h * z_e * math.sqrt((4 - e_sp) / 3) * math.sqrt(f_t / (2 * R_S * B) * (u_sp + 1) / u_sp)
    sun = _run_json(tmp_path, "design", _rated_a('"iso"'))["stages"][0]["meshes"][0]["rating"]
    assert sun["K_gamma"] == 1.1
    assert_allclose(sun["sigma_H0_MPa"], sigma_h0_sp, rtol=1e-12)
    assert_allclose(sun["sigma_H_MPa"], sigma_h0_sp * math.sqrt(sun["K_A"] * 1.1 * sun["K_v"] * sun["K_Hbeta"]
                                                                * sun["K_Halpha"]), rtol=1e-12)


def test_an_unloaded_planetary_has_no_load_sharing_factor(tmp_path):
    """At zero load every planet's window-mean sun-mesh force is round-off (~1e-10 N against a run-up peak of the
    inertia torques): their ratio (it read 1.0006) is no load sharing; null. A light load (50 N·m on the carrier:
    F_t = 50/5 / (3 x 0.048) = 69.44 N per planet) is shared equally: 1."""
    base = scene_a() + "\n[simulation]\nduration_s = 0.2\nsteps = 2000\n"
    base = base.replace(f"speed_rpm = {N_IN}", f"speed_rpm = {N_IN}\nramp_s = 0.04")
    zero = _run_json(tmp_path, "simulate", base.replace(f"torque_Nm = {T_OUT}", "torque_Nm = 0"))
    assert zero["summary"]["stages"][0]["load_sharing_factor"] is None
    light = _run_json(tmp_path, "simulate", base.replace(f"torque_Nm = {T_OUT}", "torque_Nm = 50"))["summary"]
    assert_allclose([p["sun"]["tangential_N"]["mean"] for p in light["stages"][0]["planets"]],
                    [50 / (1 + U) * 1e3 / (3 * R_S)] * 3, rtol=1e-6)
    assert_allclose(light["stages"][0]["load_sharing_factor"], 1.0, atol=1e-9)


def test_two_planets_with_a_position_error_share_as_the_series_spring_model_says(tmp_path):
    """Linear meshes (exponent 1, k_n = c_ga b). A planet is a free lever: its sun- and ring-mesh forces are equal,
    and delta_sp + delta_pr = r_bs th_s - (r_bs + r_br) th_c + e_j is the same for every planet but its error e_j,
    so F_j = k_eq (X + e_j) with k_eq = k_sp k_pr / (k_sp + k_pr): F_j = F_mean + k_eq (e_j - mean e) along the line
    of action, times cos(alpha) as F_t. Two planets, e = (10, 0) um: +-k_eq 5 um cos 20 deg about T_sun/(2 r_s)."""
    k_sp, k_pr = _hand_k_sp_k_pr()  # N/m
    k_eq = k_sp * k_pr / (k_sp + k_pr)
    text = scene_a(2, planet=", position_error_um = [10, 0]") + "\n[contact]\nexponent = 1\n"
    text += "\n[simulation]\nduration_s = 0.2\nsteps = 2000\n"
    text = text.replace(f"speed_rpm = {N_IN}", f"speed_rpm = {N_IN}\nramp_s = 0.04").replace(
        f"torque_Nm = {T_OUT}", f"torque_Nm = {T_OUT}\nramp_s = 0.04")
    st = _run_json(tmp_path, "simulate", text)["summary"]["stages"][0]
    mean = T_OUT / (1 + U) * 1e3 / (2 * R_S)
    shift = k_eq * 5e-6 * math.cos(ALPHA)
    for m in ("sun", "ring"):
        assert_allclose([p[m]["tangential_N"]["mean"] for p in st["planets"]], [mean + shift, mean - shift], rtol=1e-6)
    assert_allclose(st["load_sharing_factor"], (mean + shift) / mean, rtol=1e-6)
