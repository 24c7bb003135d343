"""The seed reducer (configs/concrete_mixer.toml) against the seed paper's corrected numbers and hand
calculations (docs/physics.md, "Design calculations"). Every expected value is worked out in the comment beside it;
none is copied from gearcli's own output.

Hand-calculation constants, stage 1 (m_n = 12, α_n = 20°, β = 12°, z = 21/51, b = 190/180):
  cos 12° = 0.978148, tan 20° = 0.363970, tan 12° = 0.212557
  m_t = 12 / 0.978148 = 12.26809 mm
  α_t = atan(0.363970 / 0.978148) = atan(0.372102) = 20.4103°
  d1 = 21 · 12.26809 = 257.6298 mm, d2 = 51 · 12.26809 = 625.6724 mm
"""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import pytest
from numpy.testing import assert_allclose

from gearcli.config.schema import DesignFile
from gearcli.design import compute_design
from gearcli.design.stiffness import flexibility_q_prime, virtual_teeth

SEED = Path(__file__).resolve().parents[2] / "configs" / "concrete_mixer.toml"


@pytest.fixture(scope="module")
def seed():
    with SEED.open("rb") as fh:
        return compute_design(DesignFile.model_validate(tomllib.load(fh)))


# ------------------------------------------------------------------------ kinematics (seed 1, 4.1)
def test_ratios_and_speeds(seed):
    # i = 51/21 · 50/17 · 53/17 = 135150/6069 = 22.26891 (seed: 22.269)
    assert_allclose(seed.total_ratio, 135150 / 6069, rtol=1e-12)  # exact rational: only rounding error
    assert_allclose(seed.total_ratio, 22.2689, rtol=5e-6)  # acceptance value, 6 digits
    # gear 2: 3600 · 21/51 = 1482.35 °/s (the paper's Table 1 says 1492: erratum)
    assert_allclose(seed.stages[0].gear.speed_deg_s, 1482.35, rtol=5e-6)  # 6 significant digits given
    # gear 4: 1482.353 · 17/50 = 504.00 °/s exactly (3600 · 21 · 17 / (51 · 50) = 504)
    assert_allclose(seed.stages[1].gear.speed_deg_s, 504.0, rtol=1e-12)  # exact
    # output: 3600 / 22.26891 = 161.66 °/s = 26.94 rpm
    assert_allclose(seed.output_speed_deg_s, 161.66, rtol=5e-5)  # 5 significant digits given
    assert_allclose(seed.output_speed_rpm, 26.94, rtol=2e-4)  # 4 significant digits given
    assert [sh.index for sh in seed.shafts] == [1, 2, 3, 4]
    assert_allclose([sh.speed_rpm for sh in seed.shafts], [600, 600 * 21 / 51, 84, 600 / (135150 / 6069)],
                    rtol=1e-12)  # 600 rpm input; 504 °/s = 84 rpm on shaft 3


def test_mesh_frequencies(seed):
    # f_z = z_pinion · n_pinion: 21 · 600/60 = 210 Hz; 17 · (600·21/51)/60 = 70 Hz; 17 · 84/60 = 23.8 Hz
    assert_allclose([s.mesh_frequency_Hz for s in seed.stages], [210.0, 70.0, 23.8], rtol=1e-12)  # exact


def test_torques_and_static_forces(seed):
    # T_in = 5.31e6 / 22.26891 = 2.3845e5 N·mm (seed 4.2: 2.384e5)
    assert_allclose(seed.input_torque_Nmm, 2.3845e5, rtol=5e-5)  # 5 significant digits
    assert_allclose(seed.output_torque_Nmm, 5.31e6, rtol=1e-12)  # the load itself
    # shaft 2 carries gear 2 = pinion 3: 5.31e6 / (50/17 · 53/17) = 5.31e6 / 9.16955 = 5.7909e5 N·mm
    assert_allclose(seed.shafts[1].torque_Nmm, 5.7909e5, rtol=5e-5)  # 5 significant digits
    f = seed.stages[0].static_force_N
    # F_t = 2 T_in / d1 = 2 · 238449.06 / 257.6298 = 1851.1 N (seed: 1851)
    assert_allclose(f.tangential, 1851.1, rtol=1e-4)  # 5 significant digits
    # F_r = F_t tan 20° / cos 12° = 1851.1 · 0.363970 / 0.978148 = 688.8 N (seed: 689)
    assert_allclose(f.radial, 688.8, rtol=2e-4)  # 4 significant digits
    # F_a = F_t tan 12° = 1851.1 · 0.212557 = 393.5 N (seed: 393)
    assert_allclose(f.axial, 393.5, rtol=2e-4)  # 4 significant digits
    # F_n = F_t / (cos 20° cos 12°) = 1851.1 / (0.939693 · 0.978148) = 2013.9 N
    assert_allclose(f.normal, 2013.9, rtol=1e-4)  # 5 significant digits


# ----------------------------------------------------------------------- geometry, stage 1 by hand
def test_stage1_geometry_by_hand(seed):
    s = seed.stages[0]
    assert_allclose(s.transverse_module_mm, 12.26809, rtol=1e-6)  # 12 / cos 12°
    assert_allclose(s.transverse_pressure_angle_deg, 20.410, rtol=5e-5)  # atan(tan 20°/cos 12°)
    # β_b = atan(tan 12° cos 20.4103°) = atan(0.212557 · 0.937224) = atan(0.199213) = 11.2665°
    assert_allclose(s.base_helix_angle_deg, 11.266, rtol=1e-4)
    assert_allclose(s.working_pressure_angle_deg, s.transverse_pressure_angle_deg, rtol=1e-12)  # x1 = x2 = 0
    # r_b1 = 128.8149 · cos 20.4103° = 128.8149 · 0.937224 = 120.728 mm
    assert_allclose(s.pinion.base_diameter_mm / 2, 120.73, rtol=5e-5)
    # a = m_n (z1 + z2) / (2 cos β) = 12 · 72 / 1.956295 = 441.651 mm (the brief's 441.67 is a slip)
    assert_allclose(s.center_distance_mm, 441.651, rtol=5e-6)
    # d_a = d + 2 m_n: 257.630 + 24 = 281.630, 625.672 + 24 = 649.672; d_f = d − 30: 227.630, 595.672
    assert_allclose([s.pinion.tip_diameter_mm, s.gear.tip_diameter_mm], [281.630, 649.672], rtol=5e-6)
    assert_allclose([s.pinion.root_diameter_mm, s.gear.root_diameter_mm], [227.630, 595.672], rtol=5e-6)
    # p_bt = π m_t cos α_t = π · 12.26809 · 0.937224 = 36.1217 mm
    assert_allclose(s.transverse_base_pitch_mm, 36.1217, rtol=5e-6)


def test_stage1_contact_ratios_by_hand(seed):
    s = seed.stages[0]
    # √(140.8149² − 120.7278²) = √5253.64 = 72.4820; √(324.8362² − 293.1961²) = √19554.6 = 139.8378
    # a sin α_t = 441.6511 · 0.348745 = 154.0217; ε_α = (72.4820 + 139.8378 − 154.0217) / 36.1217 = 1.6139
    assert_allclose(s.contact_ratio_transverse, 1.6139, rtol=5e-5)
    # ε_β = b sin β / (π m_n) = 180 · 0.207912 / (12 π) = 37.4242 / 37.6991 = 0.99271 (b = smaller width)
    assert_allclose(s.overlap_ratio, 0.99271, rtol=5e-6)
    assert_allclose(s.contact_ratio_total, 1.6139 + 0.99271, rtol=5e-5)
    assert_allclose(s.face_width_mm, 180.0, rtol=0)  # min(190, 180), exact


# ---------------------------------------------------------------------- Hertz (seed 3.3, corrected)
def test_hertz_stiffness_corrected(seed):
    s = seed.stages[0]
    # R = r1 r2 / (r1 + r2) = 128.8149 · 312.8362 / 441.6511 = 91.244 mm (seed, with rounded radii: 91.36)
    assert_allclose(s.equivalent_radius_mm, 91.244, rtol=2e-5)
    # 1/E* = 2 (1 − 0.29²) / 2.07e5 = 8.8493e-6 /MPa -> E* = 1.1300e5 MPa (seed's 1.144e5: erratum)
    assert_allclose(s.effective_modulus_MPa, 1.130e5, rtol=5e-4)  # acceptance value, 4 digits
    assert_allclose(s.effective_modulus_MPa, 2.07e5 / (2 * (1 - 0.29 ** 2)), rtol=1e-12)  # closed form
    # K = 4/3 √91.244 · 1.13004e5 = 4/3 · 9.55217 · 1.13004e5 = 1.4392e6 N/mm^1.5 (seed's 2.87e6: erratum)
    assert_allclose(s.hertz_stiffness_N_mm1_5, 1.439e6, rtol=5e-4)  # acceptance value, 4 digits
    # seed law e = 1.5: h0 = (F_n/K)^(2/3) = (2013.91 / 1.43924e6)^(2/3) = (1.39929e-3)^(2/3) = 0.012510 mm
    assert_allclose(s.static_approach_mm, 0.012510, rtol=5e-5)
    # k_lin = e K √h0 = 1.5 · 1.43924e6 · 0.111850 = 2.4147e5 N/mm
    assert_allclose(s.linearised_stiffness_N_mm, 2.4147e5, rtol=5e-5)


# ---------------------------------------------------------------------- ISO 6336-1, stage 1 by hand
def test_stage1_iso6336_by_hand(seed):
    s = seed.stages[0]
    beta, beta_b = math.radians(12.0), math.radians(s.base_helix_angle_deg)
    # cos² β_b cos β = 0.961831 · 0.978148 = 0.940811; z_n1 = 21/0.940811 = 22.321, z_n2 = 51/0.940811 = 54.209
    zn1, zn2 = virtual_teeth(21, beta, beta_b), virtual_teeth(51, beta, beta_b)
    assert_allclose([zn1, zn2], [22.321, 54.209], rtol=5e-5)
    # q' = 0.04723 + 0.15551/22.321 + 0.25791/54.209 = 0.04723 + 0.0069670 + 0.0047577 = 0.058955
    assert_allclose(flexibility_q_prime(zn1, zn2, 0.0, 0.0), 0.058955, rtol=5e-5)
    # c'_th = 1/0.058955 = 16.962; C_B = 1 + 0.5 (1.2 − 1.25) = 0.975; full-load c' = 16.962 · 0.8 · 0.975 ·
    # 0.978148 = 12.941; F_t K_A / b = 1851.10/180 = 10.284 N/mm < 100: × (0.10284)^0.25 = 0.56629
    # c' = 12.941 · 0.56629 = 7.3284 N/(mm·µm)
    assert_allclose(s.iso6336_single_pair_stiffness_N_mm_um, 7.3284, rtol=1e-4)
    # c_γα = c' (0.75 ε_α + 0.25) = 7.3284 · (0.75 · 1.61393 + 0.25) = 7.3284 · 1.46045 = 10.703 (ε_α ≥ 1.2)
    assert_allclose(s.iso6336_mesh_stiffness_N_mm_um, 10.703, rtol=1e-4)


# ------------------------------------------------------------------------ inertia and warnings
def test_gear6_solid_disc_inertia(seed):
    # d6 = 25 · 53 / cos 9° = 1325 / 0.987688 = 1341.52 mm, b = 310 mm, ρ = 7800 kg/m³
    # J = π ρ b d⁴ / 32 = π · 7800 · 0.31 · 1.34152⁴ / 32
    #   = π · 7800 · 0.31 · 3.23882 / 32 = 768.85 kg·m²
    gear6 = seed.stages[2].gear
    assert_allclose(gear6.pitch_diameter_mm, 1341.52, rtol=5e-6)
    assert_allclose(gear6.inertia_kg_m2, 768.85, rtol=5e-5)
    assert not gear6.inertia_given
    assert_allclose(seed.shafts[-1].inertia_kg_m2, gear6.inertia_kg_m2, rtol=1e-12)  # output shaft = gear 6


def test_seed_warns_about_the_missed_target_and_its_point_contact_stiffness(seed):
    # 26.943 rpm vs 23 rpm: (26.943 − 23)/23 = +17.1 % > 5 % tolerance
    assert len(seed.warnings) == 4, seed.warnings
    w = seed.warnings[0]
    assert "26.94 rpm" in w and "23 rpm" in w and "+17.1 %" in w
    # the seed's IMPACT law (point-contact Hertz, e = 1.5) is far softer than ISO 6336-1's mesh stiffness: stage 1's
    # k_lin = 2.4147e5 N/mm (above) against k_n = c_γα b / cos² β_b = 10.70303 · 180 · 1000 / 0.961829
    # = 2.003002e6 N/mm, -88 % (DESIGN section 13 warns beyond 25 %), with both numbers
    d = [x for x in seed.diagnostics if x.code == "stiffness_not_iso"]
    assert [x.data["stage"] for x in d] == [1, 2, 3]
    assert_allclose([d[0].data["linearised_N_mm"], d[0].data["iso_N_mm"]], [2.4147e5, 2.003002e6], rtol=5e-5)
    assert "2.415e+05 N/mm" in d[0].message and "2.003e+06 N/mm" in d[0].message and "-88 %" in d[0].message


def test_seed_hands_and_stage_numbering(seed):
    assert [(s.pinion.hand, s.gear.hand) for s in seed.stages] == [("left", "right"), ("right", "left"),
                                                                   ("left", "right")]
    assert [s.index for s in seed.stages] == [1, 2, 3]
