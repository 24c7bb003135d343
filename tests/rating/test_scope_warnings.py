"""Where a rated mesh leaves ISO 6336's scope, the design says so (``rating_out_of_range``), with the numbers by hand.

- ISO 6336-2:2006, Scope: its formulae hold for teeth of other basic racks while the virtual contact ratio
  ε_αn = ε_α / cos² β_b stays below 2.5. A high-contact-ratio helical pair (α_n 15°, a long-addendum rack) passes it.
- ISO 6336-3:2006, clause 10: the rim factor of an external gear, Y_B = 1.6 ln(2.242 h_t/s_R), holds for
  0.5 < s_R/h_t < 1.2; a thinner rim is held at 0.5 (as the code documents) and must not pass silently.
"""

from __future__ import annotations

import math

from numpy.testing import assert_allclose

from gearcli.config.schema import DesignFile
from gearcli.design import compute_design


def _doc(*, alpha_n=15.0, rack=(1.2, 1.45, 0.25), pinion_extra=None) -> dict:
    """Helical 41/83, m_n 2, β 15°: a case-carburized pinion on a nodular-iron wheel (E 170 GPa)."""
    mat = {"density_kg_m3": 7850, "youngs_modulus_MPa": 206000, "poisson_ratio": 0.3, "treatment": "case_carburized",
           "contact_fatigue_limit_MPa": 1500, "bending_fatigue_limit_MPa": 460}
    iron = {"density_kg_m3": 7100, "youngs_modulus_MPa": 170000, "poisson_ratio": 0.28, "treatment": "nodular_iron",
            "contact_fatigue_limit_MPa": 600, "bending_fatigue_limit_MPa": 260}
    pinion = {"teeth": 41, "face_width_mm": 30, "hand": "left", "material": "p", "flank_roughness_Rz_um": 3,
              "root_roughness_Rz_um": 10, **(pinion_extra or {})}
    gear = {"teeth": 83, "face_width_mm": 28, "hand": "right", "material": "w", "flank_roughness_Rz_um": 5,
            "root_roughness_Rz_um": 16}
    stage = {"normal_module_mm": 2, "normal_pressure_angle_deg": alpha_n, "helix_angle_deg": 15, "accuracy_grade": 6,
             "basic_rack": {"addendum": rack[0], "dedendum": rack[1], "root_radius": rack[2]},
             "pinion": pinion, "gear": gear}
    return {"materials": {"p": mat, "w": iron}, "stage": [stage], "input": {"speed_rpm": 1500},
            "load": {"torque_Nm": 250, "application_factor": 1.25}, "lubricant": {"viscosity_40C_mm2_s": 150},
            "rating": {"required_life_h": 20000}}


def _out_of_range(doc: dict, quantity: str) -> list:
    design = compute_design(DesignFile.model_validate(doc))
    return [d for d in design.diagnostics if d.code == "rating_out_of_range" and d.data.get("quantity") == quantity]


def _virtual_contact_ratio_by_hand(alpha_n_deg: float, addendum: float) -> float:
    """ε_αn of the 41/83 pair at x = 0 (a_w = a, tips d + 2 h_aP* m_n), ISO 21771 written out."""
    mn, beta, z1, z2 = 2.0, math.radians(15.0), 41, 83
    a_t = math.atan(math.tan(math.radians(alpha_n_deg)) / math.cos(beta))
    m_t = mn / math.cos(beta)
    d1, d2 = z1 * m_t, z2 * m_t
    rb1, rb2 = 0.5 * d1 * math.cos(a_t), 0.5 * d2 * math.cos(a_t)
    ra1, ra2 = 0.5 * d1 + addendum * mn, 0.5 * d2 + addendum * mn
    a = 0.5 * (d1 + d2)
    eps_a = (math.sqrt(ra1 ** 2 - rb1 ** 2) + math.sqrt(ra2 ** 2 - rb2 ** 2) - a * math.sin(a_t)) / (
        math.pi * m_t * math.cos(a_t))
    beta_b = math.atan(math.tan(beta) * math.cos(a_t))
    return eps_a / math.cos(beta_b) ** 2


def test_virtual_contact_ratio_beyond_iso_6336_2_scope_warns():
    """α_n 15°, h_aP* 1.2: ε_α = 2.3659, β_b = 14.4775°, ε_αn = 2.36589 / 0.93749 = 2.5236 ≥ 2.5: one warning naming
    the stage and ε_αn."""
    eps_an = _virtual_contact_ratio_by_hand(15.0, 1.2)
    assert_allclose(eps_an, 2.5236, atol=1e-4)  # the figure above, so the scene stays past the limit
    found = _out_of_range(_doc(), "contact_ratio_virtual")
    assert len(found) == 1 and found[0].data["stage"] == 1
    assert_allclose(found[0].data["value"], eps_an, rtol=1e-12)
    assert "ε_αn" in found[0].message and "2.5" in found[0].message


def test_ordinary_contact_ratio_has_no_scope_warning():
    """The same pair on ISO 53 profile A at α_n 20°: ε_αn = 1.78 by hand, well inside."""
    eps_an = _virtual_contact_ratio_by_hand(20.0, 1.0)
    assert eps_an < 2.0
    assert _out_of_range(_doc(alpha_n=20.0, rack=(1.0, 1.25, 0.38)), "contact_ratio_virtual") == []


def test_rim_thinner_than_half_the_tooth_depth_warns():
    """h_t = (d_a − d_f)/2 = (1.2 + 1.45) m_n = 5.3 mm at x = 0; a 2 mm rim is s_R/h_t = 0.3774 < 0.5, so Y_B is
    held at 1.6 ln(2.242/0.5) = 2.40082 and the design says so; a 3 mm rim (0.566) is inside, Y_B = 1.6 ln(2.242 ·
    5.3/3) = 2.20223, no warning."""
    body = {"web_thickness_mm": 12.0, "bore_diameter_mm": 30.0}
    thin = _doc(pinion_extra={**body, "rim_thickness_mm": 2.0})
    found = _out_of_range(thin, "rim_ratio")
    assert len(found) == 1 and found[0].data["member"] == "pinion"
    assert_allclose(found[0].data["value"], 2.0 / 5.3, rtol=1e-12)
    design = compute_design(DesignFile.model_validate(thin))
    assert_allclose(design.stages[0].rating.pinion.Y_B, 1.6 * math.log(2.242 / 0.5), rtol=1e-12)
    inside = _doc(pinion_extra={**body, "rim_thickness_mm": 3.0})
    assert _out_of_range(inside, "rim_ratio") == []
    design = compute_design(DesignFile.model_validate(inside))
    assert_allclose(design.stages[0].rating.pinion.Y_B, 1.6 * math.log(2.242 * 5.3 / 3.0), rtol=1e-12)
