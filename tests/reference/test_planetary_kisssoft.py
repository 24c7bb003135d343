"""A planetary stage against a public commercial rating report: geometry (ISO 21771, internal gear included),
kinematics and ISO 6336-1 stiffness of both meshes.

Source: the KISSsoft report ``@NREL_5MW/stage_01.rtf`` ("CALCULATION OF A SPUR PLANETARY GEAR STAGE",
"KISSsoft Release 03/2017 A", academic licence NTNU, "ISO 6336:2006 Method B", geometry "according to ISO
21771:2007") of the NREL 5 MW reference gearbox's first stage, published in the public repository
github.com/gfsReboucas/Drivetrain, commit 2a41bf1ce829b76800693e2b52c91e5f74d074d4 (the same report whose
sun–planet mesh ``test_design_iso6336_kisssoft.py`` checks as a two-wheel pair; here the whole stage is one
``type = "planetary"`` stage).

Inputs as printed: m_n 45, α_n 20°, spur, z 19 / 17 / −56 (sun, planet, internal ring), b 491 each,
x 0.6170 / 0.8021 / −0.5013, ISO 53 profile A on sun and planet (h_fP* 1.25, h_aP* 1.0), the ring profile B
(same h_fP* and h_aP*: the diameters and C_B do not see the root radius), 3 planets, ring held, carrier
12.1 rpm driving, sun 47.8 rpm, sun torque 999650.9 N·m, K_A 1.25, inner diameters 482.33 / 408.99,
E 206000, ν 0.3. "C_R, bs/b 0.862 (0.250)" is printed for both meshes: b_s = 0.25 b and s_R = 3.5 m_n (as
inferred in the sister test) on sun and planet; gearcli takes the mean of the two members' C_R, so the ring
is given the same web and rim (its printed C_R is the planet's).

Each assertion carries the printed value; tolerances are half a unit of the last printed digit, widened only
where the report's own inputs are printed rounded (profile shifts to 4 decimals), as said beside it.
"""

from __future__ import annotations

import math

from numpy.testing import assert_allclose

from gearcli.config.schema import DesignFile
from gearcli.design import compute_design

STEEL = {"density_kg_m3": 7830.0, "youngs_modulus_MPa": 206000.0, "poisson_ratio": 0.3}
WEB = {"rim_thickness_mm": 157.5, "web_thickness_mm": 122.75}
U = 56 / 19
SUN_RPM = 47.8


def nrel_stage_1(load_sharing_factor: float | None = None) -> dict:
    stage = {"type": "planetary", "normal_module_mm": 45.0, "normal_pressure_angle_deg": 20.0,
             "sun": {"teeth": 19, "face_width_mm": 491.0, "profile_shift": 0.6170, "bore_diameter_mm": 482.33, **WEB},
             "planet": {"teeth": 17, "face_width_mm": 491.0, "profile_shift": 0.8021, "bore_diameter_mm": 408.99,
                        "count": 3, **WEB},
             "ring": {"teeth": 56, "face_width_mm": 491.0, "profile_shift": -0.5013, **WEB},
             "fixed": "ring", "input": "carrier"}
    doc = {"stage": [stage], "materials": {"steel": STEEL},
           "input": {"speed_rpm": SUN_RPM / (1 + U)}, "load": {"torque_Nm": 999650.9, "application_factor": 1.25}}
    return doc


def _stage():
    return compute_design(DesignFile.model_validate(nrel_stage_1())).stages[0]


def test_kinematics_and_torques():
    st = _stage()
    p = st.planetary
    assert p is not None and (p.fixed, p.input, p.output) == ("ring", "carrier", "sun")
    assert_allclose(p.ratio, 0.253, atol=5e-4)  # itot printed 0.253 (carrier speed over sun speed)
    assert_allclose(p.willis_ratio, -56 / 19, rtol=1e-15)
    assert_allclose(p.sun.speed_rpm, 47.8, rtol=1e-12)
    assert_allclose(p.carrier.speed_rpm, 12.1, atol=0.05)  # nSteg printed 12.1
    assert_allclose(abs(p.planet.speed_rpm), 39.9, atol=0.05)  # "speed difference for planet bearing" 39.9
    assert p.ring.speed_rpm == 0.0
    assert_allclose(p.carrier.torque_Nm, 3945990.316, atol=0.5)  # TSteg (from T_sun printed to 0.1 N·m: ±0.2)
    assert_allclose(p.ring.torque_Nm, 2946339.4, atol=0.2)  # T ring
    assert p.equal_spacing  # "Planetary axles can be placed in regular pitch: 120°"


def test_sun_planet_mesh_geometry_and_stiffness():
    st = _stage()
    # x printed to 4 decimals: a_w and the diameters move by up to 2 m_n · 5e-5 = 4.5e-3 mm
    assert_allclose(st.center_distance_mm, 863.000, atol=4.5e-3)
    assert_allclose(st.tip_alteration_coefficient * 45.0, -10.861, atol=4.5e-3)
    assert_allclose([st.pinion.tip_diameter_mm, st.gear.tip_diameter_mm], [978.808, 905.470], atol=4.5e-3)
    assert_allclose([st.pinion.root_diameter_mm, st.gear.root_diameter_mm], [798.030, 724.692], atol=4.5e-3)
    # alfwt 28.118: the report sets a = 863.000 and α_wt = acos(a_d cos α_t / a); gearcli takes α_wt from the
    # printed x (Σx to ±1e-4 moves α_wt by 2 tan α_n Δx/(Σz tan² α_wt) = 4.1e-4°)
    assert_allclose(st.working_pressure_angle_deg, 28.118, atol=5e-4 + 4.1e-4)
    assert_allclose(math.degrees(math.acos(810.0 * math.cos(math.radians(20.0)) / 863.0)), 28.118, atol=5e-4)
    assert_allclose(st.contact_ratio_transverse, 1.115, atol=5e-4)
    assert_allclose(st.static_force_N.tangential, 779454.877, rtol=1e-6)  # Ft per planet mesh
    assert_allclose(st.iso6336_factors.C_R, 0.862, atol=5e-4)
    assert_allclose(st.iso6336_single_pair_stiffness_N_mm_um, 12.362, atol=5e-4)  # c'
    assert_allclose(st.iso6336_mesh_stiffness_N_mm_um, 13.426, atol=5e-4)  # cgalf
    assert_allclose(st.iso6336_mesh_stiffness_beta_N_mm_um, 11.412, atol=5e-4)  # cgbet


def test_ring_geometry_iso_21771():
    p = _stage().planetary
    assert p is not None
    ring = p.ring
    assert_allclose(ring.pitch_diameter_mm, 2520.000, atol=5e-4)  # d
    assert_allclose(ring.base_diameter_mm, 2368.025, atol=5e-4)  # db
    # da = d − 2 m_n (h_aP* + x), df = d + 2 m_n (h_fP* − x): x printed to 4 decimals, 2 m_n · 5e-5 = 4.5e-3 mm
    assert_allclose(ring.tip_diameter_mm, 2475.118, atol=4.5e-3)
    assert_allclose(ring.root_diameter_mm, 2677.618, atol=4.5e-3)
    # hand check of the same formulas from the printed inputs
    assert_allclose(ring.tip_diameter_mm, 56 * 45 - 2 * 45 * (1.0 - 0.5013), rtol=1e-14)
    assert_allclose(ring.root_diameter_mm, 56 * 45 + 2 * 45 * (1.25 + 0.5013), rtol=1e-14)


def test_planet_ring_mesh_geometry_and_stiffness():
    p = _stage().planetary
    assert p is not None
    m = p.planet_ring
    assert_allclose(m.working_pressure_angle_deg, 17.161, atol=5e-4)  # alfwt (planet–ring)
    # the report's one centre distance 863.000 for both meshes (concentric); x to 4 decimals: 4.5e-3 mm
    assert_allclose(m.center_distance_mm, 863.000, atol=4.5e-3)
    assert abs(p.concentricity_mm) < 4.5e-3
    assert_allclose(m.contact_ratio_transverse, 1.278, atol=5e-4)  # eps_a (planet–ring)
    # the path of contact g_alpha = 169.815 mm printed: ε_α p_bt with p_bt = 132.846 printed
    assert_allclose(m.contact_ratio_transverse * m.transverse_base_pitch_mm, 169.815, atol=5e-3)
    assert_allclose(m.transverse_base_pitch_mm, 132.846, atol=5e-4)
    assert_allclose(m.static_force_N.tangential, 779454.877, rtol=1e-6)  # the same F_t printed for both meshes
    assert_allclose(m.iso6336_factors.C_R, 0.862, atol=5e-4)
    assert_allclose(m.iso6336_single_pair_stiffness_N_mm_um, 13.289, atol=5e-4)  # c'
    assert_allclose(m.iso6336_mesh_stiffness_N_mm_um, 16.063, atol=5e-4)  # cgalf
    assert_allclose(m.iso6336_mesh_stiffness_beta_N_mm_um, 13.653, atol=5e-4)  # cgbet


def test_planet_ring_single_stiffness_by_hand():
    """q' of ISO 6336-1 with z_n2 = ∞ for the internal gear: only C1, C2/zn1, C4 x1, C5 x1/zn1, C6 x2, C8 x1²,
    C9 x2² remain; c' = C_M C_R C_B / q'."""
    p = _stage().planetary
    assert p is not None
    x1, x2, zn1 = 0.8021, -0.5013, 17.0
    q = (0.04723 + 0.15551 / zn1 - 0.00635 * x1 - 0.11654 * x1 / zn1 - 0.00193 * x2
         + 0.00529 * x1 ** 2 + 0.00182 * x2 ** 2)
    c_r = 1 + math.log(0.25) / (5 * math.exp(3.5 / 5))
    assert_allclose(p.planet_ring.iso6336_single_pair_stiffness_N_mm_um, 0.8 * c_r * 0.975 / q, rtol=1e-12)


def test_load_sharing_factor_scales_the_rated_force_only():
    doc = nrel_stage_1()
    doc["stage"][0]["accuracy_grade"] = 6
    for member in ("sun", "planet", "ring"):
        doc["stage"][0][member] |= {"flank_roughness_Rz_um": 4.8, "root_roughness_Rz_um": 20.0}
    doc["materials"]["steel"] |= {"treatment": "case_carburized", "contact_fatigue_limit_MPa": 1500.0,
                                  "bending_fatigue_limit_MPa": 430.0}
    doc["lubricant"] = {"viscosity_40C_mm2_s": 220.0}
    rated = []
    for k_gamma in (1.0, 1.1):
        doc["rating"] = {"required_life_h": 175200.0, "face_load_factor": 1.15, "dynamic_factor": 1.01,
                         "load_sharing_factor": k_gamma}
        st = compute_design(DesignFile.model_validate(doc)).stages[0]
        assert st.planetary is not None and st.planetary.load_sharing_factor == k_gamma
        assert_allclose(st.static_force_N.tangential, 779454.877, rtol=1e-6)  # nominal, per planet
        assert st.rating is not None and st.planetary.planet_ring.rating is not None  # rated (test_planet_ring_rating_kisssoft.py)
        rated.append(st.rating)
    # ISO's nominal σ_H0 is the nominal force's (K_gamma is a load factor beside K_A, K_v, K_Hβ, K_Hα):
    # unchanged by K_gamma; σ_H = σ_H0 √(K_A K_gamma K_v K_Hβ K_Hα) rises by √1.1
    assert_allclose(rated[1].sigma_H0_MPa, rated[0].sigma_H0_MPa, rtol=1e-12)
    assert (rated[0].K_gamma, rated[1].K_gamma) == (1.0, 1.1)
    assert_allclose(rated[1].sigma_H_MPa / rated[0].sigma_H_MPa, math.sqrt(1.1), rtol=1e-12)
    r = rated[1]
    assert_allclose(r.sigma_H_MPa, r.sigma_H0_MPa * math.sqrt(r.K_A * r.K_gamma * r.K_v * r.K_Hbeta * r.K_Halpha),
                    rtol=1e-12)
