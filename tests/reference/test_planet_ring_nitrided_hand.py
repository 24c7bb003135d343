"""The planet–ring (internal) mesh of a small planetary stage with a nitrided ring, by hand (ISO 21771, ISO 6336-2/-3).

Sun 21, planet 30, ring 81, m 2, spur, 3 planets, ring held, sun driven at 1500 rpm, 300 N·m on the carrier, case-
carburized sun and planets, a nitrided ring (σ_Hlim 1000, σ_Flim 400), K_Hβ given 1.2, 10 000 h. What is checked and
not in the published-report tests (their ring is through-hardened): the ring's life curves of the nitrided group
(ISO 6336-2 Table 2: (1e5, 1.3), (2e6, 1), (1e10, 0.85); ISO 6336-3 Table 3: (1e3, 1.6), (3e6, 1), (1e10, 0.85)) at the
ring's own cycles N planets × |n_ring − n_carrier|, the internal pair's ε_α, σ_H0 with (|u| − 1)/|u|, Z_ε, and the
planet's Z_B against the concave ring flank from the curvature ratio at B and C.

Worked figures: n_c = 1500/(1 + 81/21) = 308.824 rpm; planet relative 833.824 rpm; sun torque 300/4.857 = 61.765 N·m;
F_t per planet 61 764.7/(3 · 21) = 980.39 N; ε_α = (15.142 − 21.154 + 17.443)/5.9043 = 1.9361; σ_H0 = 251.94 MPa.
"""

from __future__ import annotations

import math

import pytest
from numpy.testing import assert_allclose

from gearcli.config.schema import DesignFile
from gearcli.design import compute_design

ALPHA = math.radians(20.0)
ZS, ZP, ZR, M, B, N_PLANETS = 21, 30, 81, 2.0, 25.0, 3
LIFE_H, N_SUN, T_CARRIER_NMM = 10000.0, 1500.0, 300e3


def _doc() -> dict:
    eh = {"density_kg_m3": 7850, "youngs_modulus_MPa": 206000, "poisson_ratio": 0.3, "treatment": "case_carburized",
          "contact_fatigue_limit_MPa": 1500, "bending_fatigue_limit_MPa": 460}
    nt = {**eh, "treatment": "nitrided", "contact_fatigue_limit_MPa": 1000, "bending_fatigue_limit_MPa": 400}
    rough = {"flank_roughness_Rz_um": 3, "root_roughness_Rz_um": 10}
    stage = {"type": "planetary", "normal_module_mm": M, "normal_pressure_angle_deg": 20, "accuracy_grade": 6,
             "sun": {"teeth": ZS, "face_width_mm": B, "material": "eh", **rough},
             "planet": {"teeth": ZP, "face_width_mm": B, "count": N_PLANETS, "material": "eh", **rough},
             "ring": {"teeth": ZR, "face_width_mm": B, "material": "nt", "flank_roughness_Rz_um": 4,
                      "root_roughness_Rz_um": 12},
             "fixed": "ring", "input": "sun"}
    return {"materials": {"eh": eh, "nt": nt}, "stage": [stage], "input": {"speed_rpm": N_SUN},
            "load": {"torque_Nm": T_CARRIER_NMM / 1000}, "lubricant": {"viscosity_40C_mm2_s": 150},
            "rating": {"required_life_h": LIFE_H, "face_load_factor": 1.2}}


def _power_law(nodes, n):
    for (na, ya), (nb, yb) in zip(nodes, nodes[1:], strict=False):
        if n <= nb:
            return ya * (n / na) ** (math.log(yb / ya) / math.log(nb / na))
    return nodes[-1][1]


def _hand() -> dict:
    n_c = N_SUN / (1 + ZR / ZS)
    n_p = (N_SUN - n_c) * ZS / ZP  # relative to the carrier
    t_sun = T_CARRIER_NMM / (1 + ZR / ZS)
    f_t = t_sun / (N_PLANETS * ZS * M / 2)
    dp, dr = ZP * M, ZR * M
    rbp, rbr = dp / 2 * math.cos(ALPHA), dr / 2 * math.cos(ALPHA)
    rap, rar = dp / 2 + M, dr / 2 - M  # the ring's tip inside its pitch circle
    a = (dr - dp) / 2
    pbt = math.pi * M * math.cos(ALPHA)
    roll_p = math.sqrt(rap ** 2 - rbp ** 2)
    eps = (roll_p - math.sqrt(rar ** 2 - rbr ** 2) + a * math.sin(ALPHA)) / pbt
    u = ZR / ZP
    z_h = math.sqrt(2 / (math.cos(ALPHA) * math.sin(ALPHA)))
    z_e = math.sqrt(1 / (math.pi * 2 * (1 - 0.3 ** 2) / 206000))
    z_eps = math.sqrt((4 - eps) / 3)
    s_h0 = z_h * z_e * z_eps * math.sqrt(f_t / (dp * B) * (u - 1) / u)
    # Z_B: the planet's inner point of single contact B lies p_bt inside its tip along the line of action; the
    # ring's radius of curvature there is the planet's plus a sin α (the tangency points T1, T2 a sin α apart)
    rho_c, rho_b = rbp * math.tan(ALPHA), roll_p - pbt
    shift = a * math.sin(ALPHA)
    z_b = math.sqrt((1 / rho_b - 1 / (rho_b + shift)) / (1 / rho_c - 1 / (rho_c + shift)))
    cycles_ring = 60 * N_PLANETS * n_c * LIFE_H
    return {"n_c": n_c, "n_p": n_p, "F_t": f_t, "eps": eps, "sigma_H0": s_h0, "Z_eps": z_eps, "Z_B": z_b,
            "cycles_planet": 60 * n_p * LIFE_H, "cycles_ring": cycles_ring,
            "Z_NT_ring": _power_law(((1e5, 1.3), (2e6, 1.0), (1e10, 0.85)), cycles_ring),
            "Y_NT_ring": _power_law(((1e3, 1.6), (3e6, 1.0), (1e10, 0.85)), cycles_ring),
            "Y_R_ring": 4.299 - 3.259 * (12 + 1) ** 0.0058}


@pytest.fixture(scope="module")
def stage():
    return compute_design(DesignFile.model_validate(_doc())).stages[0]


def test_worked_figures():
    h = _hand()
    for key, printed, half_digit in (("n_c", 308.824, 5e-4), ("n_p", 833.824, 5e-4), ("F_t", 980.39, 5e-3),
                                     ("eps", 1.9361, 5e-5), ("sigma_H0", 251.94, 5e-3)):
        assert_allclose(h[key], printed, atol=half_digit, err_msg=key)


def test_planet_ring_mesh_by_hand(stage):
    h = _hand()
    mesh = stage.planetary.planet_ring
    r = mesh.rating
    assert_allclose(mesh.contact_ratio_transverse, h["eps"], rtol=1e-12)
    assert_allclose(r.sigma_H0_MPa, h["sigma_H0"], rtol=1e-12)
    assert_allclose(r.Z_eps, h["Z_eps"], rtol=1e-12)
    assert_allclose(r.pinion.Z_BD, h["Z_B"], rtol=1e-12)  # the planet, against the concave ring flank
    assert r.gear.Z_BD == 1.0  # Z_D = 1 for the internal gear
    assert_allclose([r.pinion.load_cycles, r.gear.load_cycles], [h["cycles_planet"], h["cycles_ring"]], rtol=1e-12)
    assert_allclose(r.gear.Z_NT, h["Z_NT_ring"], rtol=1e-12)
    assert_allclose(r.gear.Y_NT, h["Y_NT_ring"], rtol=1e-12)
    assert_allclose(r.gear.Y_R_rel_T, h["Y_R_ring"], rtol=1e-12)
    assert_allclose([r.gear.Z_NT, r.gear.Y_NT], [0.89819, 0.90066], atol=5e-6)  # the nitrided curves, as printed
