"""Profile-shifted spur pairs by hand (ISO 21771 and ISO 6336-1/-2): a V-pair with Σx = 0.70 (13/37, m 4: the working
pressure angle, the working centre distance, the tip alteration that keeps the rack's clearance, the shortened
tips, ε_α, c′ with the shift terms of q′, Z_H at α_wt) and a V-zero pair with x1 = −x2 (a_w = a, α_wt = α_t: only
the tips, the roots, q′ and the root move).

Worked figures of the Σx = 0.70 pair (printed so a reader can follow on paper):
inv α_wt = inv 20° + 2 tan 20° · 0.70/50 = 0.0149044 + 0.0101911 = 0.0250955 → α_wt = 23.6312°;
a_w = 100 cos 20°/cos α_wt = 102.5703 mm; k m_n = a_w − a − Σx m_n = −0.22968 mm (k = −0.057421);
d_a1 = 52 + 2·4 (1 + 0.45 + k) = 63.1406 mm, d_a2 = 148 + 8 (1 + 0.25 + k) = 157.5406 mm.
"""

from __future__ import annotations

import math

import pytest
from numpy.testing import assert_allclose

from gearcli.config.schema import DesignFile
from gearcli.design import compute_design

MN, ALPHA = 4.0, math.radians(20.0)


def _doc(z: tuple[int, int], x: tuple[float, float]) -> dict:
    steel = {"density_kg_m3": 7850, "youngs_modulus_MPa": 206000, "poisson_ratio": 0.3,
             "treatment": "case_carburized", "contact_fatigue_limit_MPa": 1500, "bending_fatigue_limit_MPa": 460}
    member = {"face_width_mm": 40, "material": "s", "flank_roughness_Rz_um": 3, "root_roughness_Rz_um": 10}
    stage = {"normal_module_mm": MN, "normal_pressure_angle_deg": 20, "helix_angle_deg": 0, "accuracy_grade": 7,
             "pinion": {**member, "teeth": z[0], "profile_shift": x[0]},
             "gear": {**member, "teeth": z[1], "profile_shift": x[1]}}
    return {"materials": {"s": steel}, "stage": [stage], "input": {"speed_rpm": 960},
            "load": {"torque_Nm": 300 * z[1] / z[0], "application_factor": 1.5},
            "lubricant": {"viscosity_40C_mm2_s": 220}, "rating": {"required_life_h": 30000}}


def _solve_inv(value: float) -> float:
    """α with tan α − α = value (Newton from 0.5 rad)."""
    a = 0.5
    for _ in range(50):
        a -= (math.tan(a) - a - value) / math.tan(a) ** 2
    return a


def _hand(z: tuple[int, int], x: tuple[float, float]) -> dict:
    d = [zi * MN for zi in z]
    db = [di * math.cos(ALPHA) for di in d]
    a = 0.5 * (d[0] + d[1])
    awt = _solve_inv(math.tan(ALPHA) - ALPHA + 2 * math.tan(ALPHA) * (x[0] + x[1]) / (z[0] + z[1]))
    aw = a * math.cos(ALPHA) / math.cos(awt)
    k = (aw - a) / MN - (x[0] + x[1])
    da = [d[i] + 2 * MN * (1 + x[i] + k) for i in (0, 1)]
    df = [d[i] - 2 * MN * (1.25 - x[i]) for i in (0, 1)]
    ea = (sum(math.sqrt(da[i] ** 2 - db[i] ** 2) / 2 for i in (0, 1)) - aw * math.sin(awt)) / (
        math.pi * MN * math.cos(ALPHA))
    # ISO 6336-1 clause 9: q′ with every shift term, index 1 the smaller wheel; F_t K_A/b > 100 N/mm here
    c = (0.04723, 0.15551, 0.25791, -0.00635, -0.11654, -0.00193, -0.24188, 0.00529, 0.00182)
    q = (c[0] + c[1] / z[0] + c[2] / z[1] + c[3] * x[0] + c[4] * x[0] / z[0] + c[5] * x[1] + c[6] * x[1] / z[1]
         + c[7] * x[0] ** 2 + c[8] * x[1] ** 2)
    cp = 1 / q * 0.8 * 1.0 * (1 + 0.5 * (1.2 - 1.25))  # C_M 0.8, C_R 1, C_B = [1 + 0.5 (1.2 − 1.25)] [1 − 0]
    z_h = math.sqrt(2 * math.cos(awt) / (math.cos(ALPHA) ** 2 * math.sin(awt)))
    return {"alpha_wt": math.degrees(awt), "a_w": aw, "k": k, "d_a": da, "d_f": df, "eps_a": ea, "c_prime": cp,
            "c_gamma": cp * (0.75 * ea + 0.25), "Z_H": z_h}


def test_worked_figures_of_the_v_pair():
    h = _hand((13, 37), (0.45, 0.25))
    assert_allclose(h["alpha_wt"], 23.6312, atol=5e-5)
    assert_allclose(h["a_w"], 102.5703, atol=5e-5)
    assert_allclose(h["k"], -0.057421, atol=5e-7)
    assert_allclose(h["d_a"], [63.1406, 157.5406], atol=5e-5)


@pytest.mark.parametrize("z, x", [((13, 37), (0.45, 0.25)), ((23, 47), (0.3, -0.3)), ((17, 71), (0.6, 0.4)),
                                  ((19, 19), (0.2, 0.5))])
def test_shifted_pair_geometry_stiffness_and_zone_factor(z, x):
    """Geometry, c′, c_γα and Z_H against the hand calculation, to round-off. (19/19: equal tooth counts, the
    smaller shift is ISO's index 1.)"""
    st = compute_design(DesignFile.model_validate(_doc(z, x))).stages[0]
    # q′ is not symmetric in x1, x2: ISO's index 1 is the smaller wheel, for equal tooth counts the smaller shift
    h = _hand(z, tuple(sorted(x)) if z[0] == z[1] else x)
    assert_allclose(st.working_pressure_angle_deg, h["alpha_wt"], rtol=1e-12)
    assert_allclose(st.center_distance_mm, h["a_w"], rtol=1e-12)
    assert_allclose(st.tip_alteration_coefficient, h["k"], rtol=1e-9, atol=1e-12)
    tips = sorted([st.pinion.tip_diameter_mm, st.gear.tip_diameter_mm])
    assert_allclose(tips, sorted(h["d_a"]), rtol=1e-12)
    assert_allclose(sorted([st.pinion.root_diameter_mm, st.gear.root_diameter_mm]), sorted(h["d_f"]), rtol=1e-12)
    assert_allclose(st.contact_ratio_transverse, h["eps_a"], rtol=1e-12)
    assert_allclose(st.iso6336_single_pair_stiffness_N_mm_um, h["c_prime"], rtol=1e-12)
    assert_allclose(st.iso6336_mesh_stiffness_N_mm_um, h["c_gamma"], rtol=1e-12)
    assert_allclose(st.rating.Z_H, h["Z_H"], rtol=1e-12)


def test_v_zero_pair_keeps_the_reference_centre_distance():
    """x1 = −x2: inv α_wt = inv α_t, a_w = a = (23 + 47) · 4/2 = 140 mm, k = 0, Z_H = √(2/(cos 20° sin 20°)) = 2.4946."""
    st = compute_design(DesignFile.model_validate(_doc((23, 47), (0.3, -0.3)))).stages[0]
    assert_allclose(st.center_distance_mm, 140.0, rtol=1e-12)
    assert_allclose(st.working_pressure_angle_deg, 20.0, rtol=1e-12)
    assert abs(st.tip_alteration_coefficient) < 1e-12
    assert_allclose(st.rating.Z_H, math.sqrt(2 / (math.cos(ALPHA) * math.sin(ALPHA))), rtol=1e-12)
