"""The internal gear's root (ISO 6336-3 method B, 60° tangent) in its closed-form limit: a very large ring is a
rack, whose critical section, fillet and load angle follow from straight flanks and one fillet circle by hand."""

from __future__ import annotations

import math

import pytest
from numpy.testing import assert_allclose

from gearcli.design import rating_root as rr

M, ALPHA = 4.0, math.radians(20.0)


@pytest.mark.parametrize("rack", [(1.25, 0.38), (1.25, 0.30), (1.4, 0.25)])
@pytest.mark.parametrize("shift", [0.0, -0.5, 0.3])
def test_a_huge_ring_is_a_rack(rack, shift):
    """z → ∞: the fillet circle (radius ρ_fP, centre ρ_fP above the root line and ρ_fP off the flank) touched by
    the line at 60° to the tooth axis: s_Fn = 2 m [π/4 + (h_fP* − ρ_fP*) tan α + ρ_fP*/cos α − ρ_fP*/2] (the tooth
    is π m/2 thick h_fP above its root whatever x is), the section ρ_fP (1 − sin 60°) above the root circle,
    ρ_F = ρ_fP, and the load angle α_Fen → α_n (straight flanks)."""
    z = 200000
    h, rho = rack
    d = z * M
    tip = d - 2.0 * M * (1.0 + shift)  # the ring's tip inside its reference circle
    root = d + 2.0 * M * (h - shift)
    f = rr.internal_tooth_form(z, M, ALPHA, 0.0, 0.0, shift, tip, d, 1.6, rack)
    s_rack = 2.0 * M * (math.pi / 4.0 + (h - rho) * math.tan(ALPHA) + rho / math.cos(ALPHA) - rho / 2.0)
    assert_allclose(f["s_Fn"], s_rack, rtol=1e-4)
    assert_allclose(0.5 * (root - f["d_sFn"]), rho * M * (1.0 - math.sin(math.pi / 3.0)), atol=2e-3 * M)
    assert f["rho_F"] == rho * M
    assert_allclose(f["alpha_Fen"], ALPHA, atol=1e-3)


def test_a_finite_cutter_rounds_the_fillet_towards_the_rack_as_it_grows():
    """ρ_F of a pinion-type cutter's fillet exceeds the rack's and falls back to ρ_fP as z_0 → ∞."""
    args = (56, 45.0, ALPHA, 0.0, 0.0, -0.5013, 2475.118, 2520.0, 1.278, (1.25, 0.30))
    radii = [rr.internal_tooth_form(*args, cutter_teeth=z0)["rho_F"] for z0 in (20, 36, 100, 1e7)]
    assert radii == sorted(radii, reverse=True)
    assert_allclose(radii[-1], 0.30 * 45.0, rtol=1e-5)
    assert radii[0] > 0.30 * 45.0
