"""A rating standard's S–N curve is checked where the standard returns it (docs/plugins.md, the rating standard's
protocol): a curve of two nodes, nodes out of order or a NaN endurance strength was gearcli's internal error in
``gearcli life`` (a division by zero in the finite-life exponent, a NaN refused by the strict JSON), far from the
plug-in that returned it (tr19a). ISO 6336's own curves pass the same check, and a flat segment past the knee (a
standard's endurance limit written as nodes) is an endurance limit, not a division by zero."""

from __future__ import annotations

import math

import pytest
from numpy.testing import assert_allclose

from gearcli.design.rating_factors import TREATMENTS, ynt_curve, znt_curve
from gearcli.errors import PluginError
from gearcli.rating.guard import Guarded
from gearcli.rating.sn import VARIANTS, SNCurve, curve_problem

GOOD = ((1e5, 1.6), (5e7, 1.0), (1e10, 1.0))


class _Std:
    """A standard whose sn_curve returns the curve it is given (only what the guard asks of it)."""

    name, title = "test_sn_checks", "S-N checks (a test standard)"

    def __init__(self, curve):
        self.curve = curve

    def sn_curve(self, cfg, member, treatment, mode, variant):
        return self.curve


@pytest.mark.parametrize("treatment", TREATMENTS)
@pytest.mark.parametrize("variant", VARIANTS)
@pytest.mark.parametrize("optimum", [False, True])
def test_iso_6336_curves_pass_the_check(treatment, variant, optimum):
    for nodes in (znt_curve(treatment), ynt_curve(treatment)):
        assert curve_problem(SNCurve(nodes, 1000.0, variant, optimum)) is None


@pytest.mark.parametrize("curve, why", [
    (SNCurve(GOOD[:2], 1500.0, "iso", True), "nodes are 2, not at least 3"),
    (SNCurve(tuple(reversed(GOOD)), 1500.0, "iso", True), "cycles N do not rise"),
    (SNCurve(((1e5, 1.0), (5e7, 1.0), (1e10, 0.9)), 1500.0), "no finite-life slope"),
    (SNCurve(((1e5, 1.6), (5e7, 1.1), (1e10, 1.0)), 1500.0), "knee (the second-last node) is at factor 1.1, not 1"),
    (SNCurve(((1e5, 1.6), (5e7, 1.0), (1e10, math.nan)), 1500.0), "not finite and > 0"),
    (SNCurve(GOOD, math.nan, "iso", True), "endurance_MPa is nan"),
    (SNCurve(GOOD, 0.0, "iso", True), "endurance_MPa is 0.0"),
    (SNCurve(GOOD, 1500.0, "palmgren"), "variant is 'palmgren'"),
])
def test_a_standard_returning_a_broken_curve_is_named(curve, why):
    with pytest.raises(PluginError) as err:
        Guarded(_Std(curve)).sn_curve(None, None, "case_carburized", "pitting", "iso")
    text = str(err.value)
    assert text.startswith('rating standard "test_sn_checks" (') and "sn_curve returned the pitting curve" in text
    assert why in text


def test_a_good_curve_is_returned_as_it_is():
    curve = SNCurve(GOOD, 1500.0, "iso", True)
    assert Guarded(_Std(curve)).sn_curve(None, None, "case_carburized", "pitting", "iso") is curve


def test_a_flat_segment_past_the_knee_is_an_endurance_limit():
    """Nodes (1e5, 1.6), (5e7, 1.0), (1e10, 1.0) without ``optimum``: on the finite-life branch N = 1e5 (1.6 / y)^k,
    k = ln(5e7 / 1e5) / ln 1.6 (by hand, Basquin through the static node and the knee); below the knee no damage."""
    curve = SNCurve(GOOD, 1500.0, "iso", False)
    k = math.log(5e7 / 1e5) / math.log(1.6)
    for stress in (1600.0, 1800.0, 2300.0):
        assert_allclose(curve.cycles_to_failure(stress), 1e5 * (1.6 / (stress / 1500.0)) ** k, rtol=1e-12)
    assert curve.cycles_to_failure(1499.0) == math.inf
    assert curve.cycles_to_failure(900.0) == math.inf
    assert_allclose(curve.stress_at(1e9), 1500.0, rtol=1e-15)
