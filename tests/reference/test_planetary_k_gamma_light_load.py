"""A planetary stage rated at K_γ at a light load: the most loaded planet's ISO 6336-1 stiffness is its own.

ISO 6336-1 rates a planetary stage's meshes at the most loaded planet's force, K_γ times the mean planet's, and
every load-dependent factor reads that force: K_v's B_p = c′ f_pb,eff / (K_A F_t / b), N_S, F_m = F_t K_A K_γ K_v in
K_Hβ, F_tH in K_Hα. Below 100 N/mm the single-pair stiffness depends on the load too, c′ = c′_full (F_t K_A / b /
100)^0.25 (clause 9), so the rated planet's c′ (and c_γα, c_γβ, n_E1 ∝ √c_γα) is the one at K_γ F_t. gearcli took
the design's c′, the mean planet's, beside the rated planet's line load: at 31 N/mm mean and K_γ = 1.3 its K_Hβ
came out 2.178 where the standard's chain gives 2.249 (c_γβ 6.4 % low: 1.3^0.25 = 1.068), and the sun–planet mesh took N_S at the
mean load while the planet–ring mesh took it at the rated one.

Scene of our own: sun 21 / planet 30 / ring 81, m_n 3, 3 planets, ring held, sun driving at 1500 rpm, 400 N·m
on the carrier, K_A 1.5, K_γ 1.3, case-carburized, grade 6, "optimum" quality over 20 000 h (Z_NT = Y_NT = 1 on
every member, so the two-wheel hand calculation's cycle count does not enter): F_t = 400 000 / (1 + 81/21) /
(31.5 · 3) = 871.46 N per planet, K_A F_t / b = 31.12 N/mm for the mean planet, 40.46 N/mm for the rated one.
"""

from __future__ import annotations

import math

from numpy.testing import assert_allclose

from gearcli.config.schema import DesignFile
from gearcli.design import compute_design
from tests.reference.rating_hand import Member, Pair, rate

CARBURIZED = {"density_kg_m3": 7850.0, "youngs_modulus_MPa": 206000.0, "poisson_ratio": 0.3,
              "treatment": "case_carburized", "contact_fatigue_limit_MPa": 1500.0, "bending_fatigue_limit_MPa": 500.0}
TORQUE_NM, K_A, K_GAMMA, SUN_RPM = 400.0, 1.5, 1.3, 1500.0
F_T = TORQUE_NM * 1e3 / (1.0 + 81.0 / 21.0) / (31.5 * 3)  # N per planet, on the sun's reference circle


def _doc(torque_nm: float, k_gamma: float | None) -> dict:
    def member(z: int, x: float) -> dict:
        return {"teeth": z, "face_width_mm": 42.0, "profile_shift": x, "material": "cc", "flank_roughness_Rz_um": 3.0,
                "root_roughness_Rz_um": 8.0}

    rating = {"required_life_h": 20000.0, "material_quality": "optimum"}
    if k_gamma is not None:
        rating["load_sharing_factor"] = k_gamma
    return {"materials": {"cc": CARBURIZED},
            "stage": [{"type": "planetary", "normal_module_mm": 3.0, "normal_pressure_angle_deg": 20.0,
                       "accuracy_grade": 6, "sun": member(21, 0.2), "planet": {**member(30, -0.2), "count": 3},
                       "ring": member(81, 0.2), "fixed": "ring", "input": "sun"}],
            "input": {"speed_rpm": SUN_RPM}, "load": {"torque_Nm": torque_nm, "application_factor": K_A},
            "lubricant": {"viscosity_40C_mm2_s": 220.0}, "rating": rating}


def _stage(torque_nm: float, k_gamma: float | None):
    return compute_design(DesignFile.model_validate(_doc(torque_nm, k_gamma))).stages[0]


def test_the_scene_is_light_and_shared():
    st = _stage(TORQUE_NM, K_GAMMA)
    assert_allclose(st.static_force_N.tangential, F_T, rtol=1e-12)
    assert K_A * F_T / 42.0 < K_GAMMA * K_A * F_T / 42.0 < 100.0  # both below c′'s full-load line load


def test_sun_planet_factors_against_the_hand_calculation_at_the_rated_planets_load():
    """rating_hand (ISO 6336:2006 typed by hand) of the sun–planet pair in the carrier's frame at K_γ F_t, its
    c′ (F_t K_A / b / 100)^0.25 at that force: K_Hβ (method C, c_γβ), K_Fβ, K_Hα, K_Fα, σ_H, σ_F and the
    safeties (the planet's root with Y_M 0.7). K_v as the design gives it (the planetary m_red is not the hand
    module's two-wheel one; the next test checks K_v)."""
    r = _stage(TORQUE_NM, K_GAMMA).rating
    relative = SUN_RPM * (1.0 - 21.0 / 102.0)  # the sun relative to the carrier
    q = Pair(Member(21, 42.0, "case_carburized", 1500.0, 500.0, 3.0, 8.0, x=0.2),
             Member(30, 42.0, "case_carburized", 1500.0, 500.0, 3.0, 8.0, x=-0.2), mn=3.0, alpha_n_deg=20.0,
             beta_deg=0.0, grade=6, torque_pinion_Nm=K_GAMMA * F_T * 31.5e-3, n1_rpm=relative, k_a=K_A, nu40=220.0,
             life_h=20000.0, quality="optimum")
    hand = rate(q, k_v_given=r.K_v)
    for key in ("K_Hbeta", "K_Fbeta", "K_Halpha", "K_Falpha", "Z_eps", "sigma_H"):
        got = r.sigma_H_MPa if key == "sigma_H" else getattr(r, key)
        assert_allclose(got, hand[key], rtol=1e-9, err_msg=key)
    assert_allclose(r.K_Hbeta, 2.24933, atol=1e-5)  # the mean planet's c′ gave 2.17812
    y_m = {"pinion": 1.0, "gear": 0.7}  # the planet, an idler
    for part in ("pinion", "gear"):
        mine, theirs = getattr(r, part), hand[part]
        assert_allclose(mine.sigma_F_MPa, theirs["sigma_F"], rtol=1e-9, err_msg=part)
        assert_allclose(mine.S_H, theirs["S_H"], rtol=1e-9, err_msg=part)
        assert_allclose(mine.S_F, theirs["S_F"] * y_m[part], rtol=1e-9, err_msg=part)


def test_the_rated_planet_is_a_planet_carrying_k_gamma_times_the_load():
    """Both meshes' load factors, stresses and safeties at K_γ = 1.3 are those of the same stage without load
    sharing at 1.3 times the torque (whose design's c′, N and N_S are then at the rated planet's line load): the
    most loaded planet is rated as a planet carrying its own force. Only ISO's nominal σ_H0, σ_F0 differ (the
    mean planet's: √K_γ and K_γ)."""
    shared, scaled = _stage(TORQUE_NM, K_GAMMA), _stage(K_GAMMA * TORQUE_NM, None)
    meshes = ((shared.rating, scaled.rating),
              (shared.planetary.planet_ring.rating, scaled.planetary.planet_ring.rating))
    for a, b in meshes:
        for key in ("K_v", "K_Hbeta", "K_Fbeta", "K_Halpha", "K_Falpha", "sigma_H_MPa"):
            assert_allclose(getattr(a, key), getattr(b, key), rtol=1e-12, err_msg=key)
        assert_allclose(a.sigma_H0_MPa * math.sqrt(K_GAMMA), b.sigma_H0_MPa, rtol=1e-12)
        for part in ("pinion", "gear"):
            x, y = getattr(a, part), getattr(b, part)
            for key in ("sigma_H_MPa", "sigma_F_MPa", "S_H", "S_F"):
                assert_allclose(getattr(x, key), getattr(y, key), rtol=1e-12, err_msg=f"{part}.{key}")
            assert_allclose(x.sigma_F0_MPa * K_GAMMA, y.sigma_F0_MPa, rtol=1e-12)


def test_the_design_keeps_the_mean_planets_stiffness():
    """The design's own figures (JSON c′, c_γα, n_E1, N, N_S of both meshes) stay the mean planet's: K_γ moves the
    rating only."""
    shared, plain = _stage(TORQUE_NM, K_GAMMA), _stage(TORQUE_NM, None)
    for a, b in ((shared, plain), (shared.planetary.planet_ring, plain.planetary.planet_ring)):
        for key in ("iso6336_single_pair_stiffness_N_mm_um", "iso6336_mesh_stiffness_N_mm_um", "resonance_speed_rpm",
                    "resonance_ratio", "resonance_lower_limit"):
            assert getattr(a, key) == getattr(b, key), key
