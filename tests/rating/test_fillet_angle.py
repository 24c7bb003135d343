"""θ of ISO 6336-3 method B (the 30° tangent to the root fillet) solves θ = 2G/z_n tan θ − H. The standard iterates
from π/6; the iteration converges only where |2G/z_n sec² θ| < 1. Before this test gearcli took the 100th iterate
whether or not it had converged: a far-shifted small tooth at a low pressure angle was rated with a θ that solves
nothing (α_n 35°, a stub rack h_fP* 0.8, ρ_fP* 0.45, z 13, x 1.5, β 20°: Y_F 0.18, Y_S 3.50, where no 30° tangent
exists at all). Now a diverging iteration falls back to bisection of the same equation in (0, π/2), and where no root
is there the rating is exit 2 naming the member's profile shift."""

from __future__ import annotations

import math

import pytest
from numpy.testing import assert_allclose
from scipy.optimize import brentq

from gearcli.config.schema import DesignFile
from gearcli.design import compute_design
from gearcli.design import rating_root as rr
from gearcli.errors import DesignError


def _doc(alpha_n: float, rack: tuple[float, float, float], z: int, x: float, beta: float) -> dict:
    steel = {"density_kg_m3": 7850, "youngs_modulus_MPa": 206000, "poisson_ratio": 0.3,
             "treatment": "case_carburized", "contact_fatigue_limit_MPa": 1500, "bending_fatigue_limit_MPa": 430}
    member = {"face_width_mm": 40, "material": "s", "flank_roughness_Rz_um": 3, "root_roughness_Rz_um": 10}
    hands = ({"hand": "left"}, {"hand": "right"}) if beta else ({}, {})
    stage = {"normal_module_mm": 4, "normal_pressure_angle_deg": alpha_n, "helix_angle_deg": beta,
             "accuracy_grade": 6, "basic_rack": dict(zip(("addendum", "dedendum", "root_radius"), rack, strict=True)),
             "pinion": {**member, **hands[0], "teeth": z, "profile_shift": x},
             "gear": {**member, **hands[1], "teeth": 61}}
    return {"materials": {"s": steel}, "stage": [stage], "input": {"speed_rpm": 1500}, "load": {"torque_Nm": 800},
            "lubricant": {"viscosity_40C_mm2_s": 220}, "rating": {"required_life_h": 20000}}


def test_no_thirty_degree_tangent_is_exit_2_naming_the_profile_shift():
    cfg = DesignFile.model_validate(_doc(35.0, (0.8, 0.8, 0.45), 13, 1.5, 20.0))
    with pytest.raises(DesignError) as info:
        compute_design(cfg)
    assert info.value.key == "stage[0].pinion.profile_shift"
    assert "no critical section" in info.value.message and "13-tooth" in info.value.message


def test_diverging_iteration_is_solved_by_bisection():
    """α_n 10°, h_fP* 1.6, ρ_fP* 0.1, z 5, x −0.95: 2G/z_n = 2 (0.1 − 1.6 − 0.95)/5 = −0.98, the fixed-point iteration
    oscillates away; the root in (0, π/2) by scipy's brentq gives s_Fn/m_n = z_n sin(π/3 − θ) + √3 (G/cos θ − ρ_fP*),
    which the tooth form must reproduce (here a negative s_Fn: the tooth is undercut, as the design then says)."""
    an, hf, rf, z, x = math.radians(10.0), 1.6, 0.1, 5, -0.95
    e = math.pi / 4 - hf * math.tan(an) - (1 - math.sin(an)) * rf / math.cos(an)
    g = rf - hf + x
    h = 2 / z * (math.pi / 2 - e) - math.pi / 3
    theta = math.pi / 6
    for _ in range(1000):
        theta = 2 * g / z * math.tan(theta) - h
    assert abs(2 * g / z * math.tan(theta) - h - theta) > 1e-3  # the standard's iteration alone does not converge
    root = brentq(lambda t: 2 * g / z * math.tan(t) - h - t, 0.2, 0.45, xtol=1e-15)
    form = rr.tooth_form(z, 1.0, an, 0.0, 0.0, x, z + 2 * (1 + x), z, 1.3, (hf, rf))
    assert abs(form["theta_residual"]) < 1e-12
    assert_allclose(form["s_Fn"], z * math.sin(math.pi / 3 - root) + math.sqrt(3) * (g / math.cos(root) - rf),
                    rtol=1e-9)
