"""inverse_involute at small working pressure angles: Newton on tan α − α − v never met its tolerance below
α ≈ 4.7° (inv α < 1.8e-4), where tan α − α cancels, and a valid design file (α_n = 10.35°, negative profile
shifts, inv α_wt = 1.4e-5) ended as an internal error (exit 1). Reference: the angle itself, its involute from
the Taylor series of tan α − α (α³/3 + 2α⁵/15 + 17α⁷/315 + 62α⁹/2835 + 1382α¹¹/155925, Abramowitz & Stegun
4.3.67) below 0.02 rad and from tan α − α above, both in extended precision (numpy longdouble)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from gearcli.config.schema import DesignFile
from gearcli.design import compute_design
from gearcli.design.geometry import inverse_involute


def involute_extended(alpha: np.longdouble) -> np.longdouble:
    if alpha < 0.02:
        a2 = alpha * alpha
        coeffs = [np.longdouble(n) / np.longdouble(d) for n, d in ((1, 3), (2, 15), (17, 315), (62, 2835),
                                                                    (1382, 155925))]
        return alpha * a2 * sum(c * a2 ** j for j, c in enumerate(coeffs))
    return np.tan(alpha) - alpha


@pytest.mark.parametrize("alpha", np.geomspace(1e-5, 1.55, 400))
def test_inverse_involute_recovers_the_angle(alpha):
    a = np.longdouble(alpha)
    # 1e-12: the involute's value is rounded to a double before inversion; d ln α / d ln inv = α/(3 inv) ≈ 1/3
    # at small α, so the double's 1.1e-16 maps to ~4e-17 in α; the margin covers tan's rounding near π/2
    assert_allclose(inverse_involute(float(involute_extended(a))), alpha, rtol=1e-12)


def test_design_with_a_tiny_working_pressure_angle_computes():
    stage = {"normal_module_mm": 1.0, "normal_pressure_angle_deg": 10.354943793843917,
             "basic_rack": {"addendum": 0.6125372467696261, "dedendum": 1.2690326550124993,
                            "root_radius": 0.22006969722163836},
             "pinion": {"teeth": 52, "face_width_mm": 50.0, "profile_shift": -0.46466510882915957},
             "gear": {"teeth": 149, "face_width_mm": 50.0, "profile_shift": -0.6241081784753868}}
    cfg = DesignFile.model_validate({"stage": [stage], "input": {"speed_rpm": 1000.0}, "load": {"torque_Nm": 100.0}})
    s = compute_design(cfg).stages[0]
    # ISO 21771: inv α_wt = inv α_t + 2 tan α_n (x1 + x2)/(z1 + z2), checked on the result's own α_wt
    a_n = math.radians(10.354943793843917)
    target = (math.tan(a_n) - a_n) + 2 * math.tan(a_n) * (-0.46466510882915957 - 0.6241081784753868) / 201
    a_wt = np.longdouble(math.radians(s.working_pressure_angle_deg))
    assert_allclose(float(involute_extended(a_wt)), target, rtol=1e-9)  # degrees round trip: ~1e-15 in α
    assert_allclose(s.center_distance_mm, 100.5 * math.cos(a_n) / math.cos(float(a_wt)), rtol=1e-14)
