"""Z_ε of a very high transverse contact ratio (ε_α > 3), with the numbers by hand (ISO 21771, ISO 6336-2).

ISO 6336-2:2006, 8 gives Z_ε = √((4 − ε_α)/3 (1 − ε_β) + ε_β/ε_α) for ε_β < 1 and √(1/ε_α) for ε_β ≥ 1. The spur term
(4 − ε_α)/3 equals 1/ε_α at ε_α = 1 and 3, lies above it between, and falls to 0 at ε_α = 4: a long-addendum spur
pair at a low pressure angle (ε_α 3.99) was rated at Z_ε 0.065, σ_H 66 MPa for about 510, and at ε_α ≥ 4 the design
stopped with "internal error: ValueError: math domain error" (exit 1). Such a mesh is outside ISO 6336-2's scope
(ε_αn ≥ 2.5, which the design warns about); gearcli then takes Z_ε at least √(1/ε_α), the load shared equally by
ε_α pairs, the standard's own value where the load is spread over the overlap (ε_β ≥ 1). Below ε_α = 3 nothing
changes (the ε_β < 1 form is a weighted mean of (4 − ε_α)/3 and 1/ε_α, so at least 1/ε_α there).
"""

from __future__ import annotations

import math

import pytest
from numpy.testing import assert_allclose

from gearcli.config.schema import DesignFile
from gearcli.design import compute_design
from gearcli.design.rating_factors import contact_ratio_factor

MN, Z1, Z2, X, B = 3.0, 90, 180, 0.1, 40.0
E, NU = 206000.0, 0.3
T_OUT_NMM = 4.0e6


def _doc(alpha_n: float, addendum: float, helix: float = 0.0) -> dict:
    """A spur (or helical) 90/180 pair, m_n 3, x 0.1/0.1, a long-addendum rack (h_fP* = h_aP* + 0.25, ρ_fP* 0.2)."""
    mat = {"density_kg_m3": 7850, "youngs_modulus_MPa": E, "poisson_ratio": NU, "treatment": "case_carburized",
           "contact_fatigue_limit_MPa": 1500, "bending_fatigue_limit_MPa": 450}
    hands = ({"hand": "left"}, {"hand": "right"}) if helix else ({}, {})
    member = {"face_width_mm": B, "material": "c", "profile_shift": X, "flank_roughness_Rz_um": 3,
              "root_roughness_Rz_um": 8}
    stage = {"normal_module_mm": MN, "normal_pressure_angle_deg": alpha_n, "helix_angle_deg": helix,
             "accuracy_grade": 5, "basic_rack": {"addendum": addendum, "dedendum": addendum + 0.25, "root_radius": 0.2},
             "pinion": {"teeth": Z1, **member, **hands[0]}, "gear": {"teeth": Z2, **member, **hands[1]}}
    return {"materials": {"c": mat}, "stage": [stage], "input": {"speed_rpm": 1000},
            "load": {"torque_Nmm": T_OUT_NMM}, "lubricant": {"viscosity_40C_mm2_s": 220},
            "rating": {"required_life_h": 20000, "face_load_factor": 1.2}}


def _inv(a: float) -> float:
    return math.tan(a) - a


def _by_hand(alpha_n_deg: float, addendum: float, helix_deg: float = 0.0) -> dict:
    """ISO 21771 (working centre distance from x1 + x2, tip alteration, ε_α, ε_β) and ISO 6336-2's σ_H0, with Z_ε
    taken as √(1/ε_α)."""
    an, beta = math.radians(alpha_n_deg), math.radians(helix_deg)
    at = math.atan(math.tan(an) / math.cos(beta))
    mt = MN / math.cos(beta)
    d1, d2 = Z1 * mt, Z2 * mt
    inv_wt = _inv(at) + 2.0 * math.tan(an) * (2 * X) / (Z1 + Z2)
    awt = 0.4
    for _ in range(60):  # Newton on inv α = inv_wt
        awt -= (_inv(awt) - inv_wt) / math.tan(awt) ** 2
    a = 0.5 * (d1 + d2)
    aw = a * math.cos(at) / math.cos(awt)
    k = (aw - a) / MN - 2 * X
    da1, da2 = d1 + 2 * MN * (addendum + X + k), d2 + 2 * MN * (addendum + X + k)
    db1, db2 = d1 * math.cos(at), d2 * math.cos(at)
    eps_a = (0.5 * math.sqrt(da1**2 - db1**2) + 0.5 * math.sqrt(da2**2 - db2**2) - aw * math.sin(awt)) \
        / (math.pi * mt * math.cos(at))
    eps_b = B * math.sin(beta) / (math.pi * MN)
    bb = math.atan(math.tan(beta) * math.cos(at))
    z_h = math.sqrt(2 * math.cos(bb) * math.cos(awt) / (math.cos(at) ** 2 * math.sin(awt)))
    z_e = math.sqrt(1 / (math.pi * 2 * (1 - NU**2) / E))
    z_eps = math.sqrt(1 / eps_a)
    f_t = T_OUT_NMM / (Z2 / Z1) / (0.5 * d1)
    u = Z2 / Z1
    sigma_h0 = z_h * z_e * z_eps / math.sqrt(math.cos(beta)) * math.sqrt(f_t / (d1 * B) * (u + 1) / u)
    return {"eps_a": eps_a, "eps_b": eps_b, "Z_eps": z_eps, "sigma_H0": sigma_h0,
            "spur_term": (4 - eps_a) / 3 * (1 - eps_b) + eps_b / eps_a}


@pytest.mark.parametrize(("alpha_n", "addendum", "helix"), [
    (12.0, 1.6, 0.0),   # ε_α 3.99: the spur term 0.0042 (Z_ε 0.065) where 1/ε_α is 0.25
    (10.0, 2.0, 0.0),   # ε_α 5.3: the spur term negative (the math domain error)
    (10.0, 2.0, 5.0),   # helical, ε_β 0.37 < 1: the weighted term negative as well
    (14.5, 1.4, 0.0),   # ε_α 3.15, just past the crossing at 3
])
def test_contact_ratio_factor_never_below_equal_sharing(alpha_n, addendum, helix):
    hand = _by_hand(alpha_n, addendum, helix)
    assert hand["eps_a"] > 3.0 and hand["eps_b"] < 1.0 and hand["spur_term"] < 1.0 / hand["eps_a"]
    design = compute_design(DesignFile.model_validate(_doc(alpha_n, addendum, helix)))
    st = design.stages[0]
    assert_allclose(st.contact_ratio_transverse, hand["eps_a"], rtol=1e-12)
    r = st.rating
    assert_allclose(r.Z_eps, hand["Z_eps"], rtol=1e-12)
    assert_allclose(r.sigma_H0_MPa, hand["sigma_H0"], rtol=1e-9)
    # K_Hα's cap ε_γ/(ε_α Z_ε²) stays finite and at least 1 (it divided by Z_ε² = 0 at ε_α = 4)
    assert 1.0 <= r.K_Halpha <= (hand["eps_a"] + hand["eps_b"]) / (hand["eps_a"] * hand["Z_eps"] ** 2) + 1e-12
    # the scope warning that covers these figures is still given
    assert any(d.code == "rating_out_of_range" and d.data.get("quantity") == "contact_ratio_virtual"
               for d in design.diagnostics)


def test_below_three_the_standard_formula_stands():
    """ε_α 2.5 < 3 (α_n 20°, addendum 1.6): Z_ε is ISO's spur form √((4 − ε_α)/3), above √(1/ε_α)."""
    hand = _by_hand(20.0, 1.6)
    assert 2.0 < hand["eps_a"] < 3.0
    r = compute_design(DesignFile.model_validate(_doc(20.0, 1.6))).stages[0].rating
    assert_allclose(r.Z_eps, math.sqrt((4 - hand["eps_a"]) / 3), rtol=1e-12)
    assert r.Z_eps > math.sqrt(1 / hand["eps_a"])


@pytest.mark.parametrize(("eps_a", "eps_b"), [(0.6, 0.0), (0.5114523, 0.0185185), (0.9, 0.5), (1.5, 0.3), (2.95, 0.0)])
def test_up_to_three_every_z_eps_is_the_standards(eps_a, eps_b):
    """Below ε_α = 1 (a warned discontinuous mesh) 1/ε_α lies above ISO's term as well: the floor must not reach
    there (it raised Z_ε 1.085 to 1.399 at ε_α 0.51 in a first version of this fix), nor anywhere up to 3."""
    assert_allclose(contact_ratio_factor(eps_a, eps_b), math.sqrt((4 - eps_a) / 3 * (1 - eps_b) + eps_b / eps_a),
                    rtol=1e-15)
