"""`gearcli design` warns where a mesh's static approach exceeds 10 % of its normal module (check
``static_approach``): a load or a contact stiffness orders of magnitude off, seen before any simulation."""

from __future__ import annotations

import math

from gearcli.config.schema import DesignFile
from gearcli.design import compute_design


def _design(torque_Nm: float):
    doc = {"materials": {"steel": {"density_kg_m3": 7800, "youngs_modulus_MPa": 2.07e5, "poisson_ratio": 0.29}},
           "stage": [{"normal_module_mm": 3.0, "normal_pressure_angle_deg": 20.0, "helix_angle_deg": 0.0,
                      "pinion": {"teeth": 20, "face_width_mm": 30.0}, "gear": {"teeth": 60, "face_width_mm": 30.0}}],
           "contact": {"stiffness": 1.0e6, "exponent": 1.0},  # K = 1e6 N/mm: h0 = F_n / K exactly
           "input": {"speed_rpm": 1000.0}, "load": {"torque_Nm": torque_Nm}}
    return compute_design(DesignFile.model_validate(doc))


def _hand_approach_mm(torque_Nm: float) -> float:
    """h0 = F_n / K: F_t = 2 T_out / d_2 (d_2 = 3 x 60 = 180 mm), F_n = F_t / cos(20 deg) on a spur pair."""
    f_t = 2.0 * torque_Nm * 1e3 / 180.0
    return f_t / math.cos(math.radians(20.0)) / 1.0e6


def _checks(design) -> list[dict]:
    return [d.data for d in design.diagnostics if d.data.get("check") == "static_approach"]


def test_a_load_that_pushes_the_teeth_a_third_of_a_millimetre_together_is_warned():
    torque = 30_000.0  # h0 = 0.3549 mm, 11.8 % of m_n = 3 mm
    design = _design(torque)
    (found,) = _checks(design)
    assert math.isclose(found["static_approach_mm"], _hand_approach_mm(torque), rel_tol=1e-9)
    assert found["normal_module_mm"] == 3.0 and found["stage"] == 1
    assert any("static approach" in w and "10 %" in w for w in design.warnings)


def test_a_realistic_load_is_not_warned():
    torque = 500.0  # h0 = 5.9 um, 0.2 % of m_n
    assert _hand_approach_mm(torque) < 0.01
    assert _checks(_design(torque)) == []
