"""The tip-thickness check's limit follows the member's hardening (Niemann/Winter, Maschinenelemente II; KISSsoft's
defaults): s_an ≥ 0.2 m_n for through-hardened and softer members, ≥ 0.4 m_n for surface-hardened ones (case
carburized, nitrided, nitrocarburized, induction or flame hardened: the hard case would run through a thinner tip and
leave it brittle). Until 2026-12-01 every member was held to 0.2 m_n, so a case-carburized pinion with a 0.38 m_n
tip passed unwarned.

The hand figures: spur, m_n 3, α_n 20°, z 17/60, x_1 0.65, x_2 0: inv α_wt = inv α_t + 2 tan α_n Σx / Σz,
a_w = a cos α_t / cos α_wt, tip alteration k = (a_w − a)/m_n − Σx, d_a1 = d_1 + 2 m_n (1 + x_1 + k); s_t = m_t (π/2 +
2 x tan α_n), s_at = d_a (s_t/d + inv α_t − inv α_at), cos α_at = d_b/d_a (ISO 21771).
"""

from __future__ import annotations

import math

import pytest
from numpy.testing import assert_allclose

from tests.life.scenes import design_of
from tests.reference.heavy_hand import inv, inv_inverse

TREATED = ("case_carburized", "nitrided", "nitrocarburized", "induction_hardened", "flame_hardened")


def scene(treatment: str) -> str:
    material = ("materials.steel = { density_kg_m3 = 7850, youngs_modulus_MPa = 206000, poisson_ratio = 0.3"
                + (f', treatment = "{treatment}"' if treatment else "") + " }")
    return "\n".join([material, "input = { speed_rpm = 1450 }", "load = { torque_Nm = 300 }", "[[stage]]",
                      "normal_module_mm = 3", "normal_pressure_angle_deg = 20",
                      'pinion = { teeth = 17, face_width_mm = 40, profile_shift = 0.65, material = "steel" }',
                      'gear = { teeth = 60, face_width_mm = 40, material = "steel" }'])


def hand_tip_thickness_mm() -> float:
    m, a, z1, z2, x1 = 3.0, math.radians(20.0), 17, 60, 0.65
    d1, centre = z1 * m, (z1 + z2) * m / 2
    a_w = centre * math.cos(a) / math.cos(inv_inverse(inv(a) + 2 * math.tan(a) * x1 / (z1 + z2)))
    d_a = d1 + 2 * m * (1 + x1 + (a_w - centre) / m - x1)
    s_t = m * (math.pi / 2 + 2 * x1 * math.tan(a))
    return d_a * (s_t / d1 + inv(a) - inv(math.acos(d1 * math.cos(a) / d_a)))


def _tip_warnings(treatment: str):
    d = design_of(scene(treatment))[1]
    return [dg for dg in d.diagnostics if dg.data.get("check") == "tip_thickness"]


def test_hand_tip_thickness_lies_between_the_two_limits():
    assert_allclose(hand_tip_thickness_mm() / 3.0, 0.3786, atol=1e-4)


@pytest.mark.parametrize("treatment", TREATED)
def test_a_surface_hardened_pinion_needs_0_4_module(treatment):
    found = _tip_warnings(treatment)
    assert len(found) == 1
    data = found[0].data
    assert (data["member"], data["treatment"]) == ("pinion", treatment)
    assert_allclose([data["tip_thickness_mm"], data["min_tip_thickness_mm"]], [hand_tip_thickness_mm(), 1.2],
                    rtol=1e-9)
    assert "< 0.4 m_n = 1.2 mm" in found[0].message and treatment in found[0].message


@pytest.mark.parametrize("treatment", ["", "through_hardened", "structural_steel"])
def test_a_through_hardened_pinion_keeps_0_2_module(treatment):
    assert _tip_warnings(treatment) == []
