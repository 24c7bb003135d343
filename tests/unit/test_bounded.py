"""gearcli.core.bounded.minimise_bounded against scipy's bounded Brent (minimize_scalar(method="bounded")), the
algorithm it transcribes: the same minimum bit for bit and the same count of evaluations, on functions that take
each of its branches (parabolic steps, golden steps, a minimum at a bound, a kink, a flat function)."""

from __future__ import annotations

import math

import pytest
from scipy.optimize import minimize_scalar

from gearcli.core.bounded import minimise_bounded

FUNCTIONS = {
    "quadratic": (lambda x: (x - 0.3) ** 2 + 1.0, -2.0, 3.0),
    "quartic off centre": (lambda x: (x - 1.7) ** 4 - x, 0.0, 4.0),
    "kink": (lambda x: abs(x - 0.123456789), -1.0, 1.0),
    "monotone: minimum at the upper bound": (lambda x: -math.exp(x), 0.0, 2.0),
    "monotone: minimum at the lower bound": (lambda x: x**3, 1.0, 5.0),
    "flat": (lambda x: 2.5, 0.0, 1.0),
    "oscillating": (lambda x: math.sin(7.0 * x) + 0.1 * x, 0.0, 2.0),
    "a peak of a narrow bracket": (lambda x: -(1.0 - 4e6 * (x - 1.2345e-3) ** 2), 1.2e-3, 1.3e-3),
}


@pytest.mark.parametrize("name", FUNCTIONS)
@pytest.mark.parametrize("xatol", [1e-5, 1e-9, 1e-12])
def test_the_same_minimum_as_scipys_bounded_brent(name, xatol):
    f, lo, hi = FUNCTIONS[name]
    ref = minimize_scalar(f, bounds=(lo, hi), method="bounded", options={"xatol": xatol})
    x, fx, nfev = minimise_bounded(f, lo, hi, xatol)
    assert (x, fx, nfev) == (float(ref.x), float(ref.fun), ref.nfev)  # the same steps: equal, not close


def test_the_evaluations_are_capped_and_bad_bounds_refused():
    x, fx, nfev = minimise_bounded(lambda x: math.sin(50 * x), 0.0, 10.0, 1e-14, maxfun=7)
    assert nfev == 7 and fx == math.sin(50 * x)
    with pytest.raises(ValueError, match="lower bound"):
        minimise_bounded(abs, 1.0, 0.0)
    with pytest.raises(ValueError, match="finite"):
        minimise_bounded(abs, 0.0, math.inf)
