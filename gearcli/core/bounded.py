"""Brent's bounded scalar minimisation on Python floats.

:func:`minimise_bounded` is the algorithm of ``scipy.optimize.minimize_scalar(method="bounded")`` (Forsythe,
Malcolm and Moler's ``fmin``: golden-section steps and parabolic interpolation, Brent 1973) step for step: the same
points evaluated in the same order, so the same minimum bit for bit (tests/unit/test_bounded.py holds it against
scipy's), without scipy's per-call set-up and its numpy scalar arithmetic in the loop (a sweep point's rigid start
refines three peaks with it: scipy's overhead was ~0.2 ms of a 8 ms point).
"""

from __future__ import annotations

import math
from collections.abc import Callable

SQRT_EPS = math.sqrt(2.2e-16)
GOLDEN_MEAN = 0.5 * (3.0 - math.sqrt(5.0))


def _sign_or_one(v: float) -> float:
    """``np.sign(v) + (v == 0)``: 1 for v >= 0, -1 below, nan for nan."""
    if v != v:
        return v
    return 1.0 if v >= 0.0 else -1.0


def minimise_bounded(func: Callable[[float], float], lo: float, hi: float, xatol: float = 1e-5,
                     maxfun: int = 500) -> tuple[float, float, int]:
    """(x, func(x), evaluations) at the minimum of ``func`` on [lo, hi] to within ``xatol`` (module text)."""
    if not (math.isfinite(lo) and math.isfinite(hi)):
        raise ValueError("the bounds must be finite")
    if lo > hi:
        raise ValueError("the lower bound exceeds the upper bound")
    a, b = lo, hi
    fulc = a + GOLDEN_MEAN * (b - a)
    nfc, xf = fulc, fulc
    rat = e = 0.0
    x = xf
    fx = func(x)
    num = 1
    ffulc = fnfc = fx
    xm = 0.5 * (a + b)
    tol1 = SQRT_EPS * abs(xf) + xatol / 3.0
    tol2 = 2.0 * tol1
    while abs(xf - xm) > (tol2 - 0.5 * (b - a)):
        golden = True
        if abs(e) > tol1:  # a parabola through the three best points
            golden = False
            r = (xf - nfc) * (fx - ffulc)
            q = (xf - fulc) * (fx - fnfc)
            p = (xf - fulc) * q - (xf - nfc) * r
            q = 2.0 * (q - r)
            if q > 0.0:
                p = -p
            q = abs(q)
            r = e
            e = rat
            if abs(p) < abs(0.5 * q * r) and p > q * (a - xf) and p < q * (b - xf):  # acceptable
                rat = (p + 0.0) / q
                x = xf + rat
                if (x - a) < tol2 or (b - x) < tol2:
                    rat = tol1 * _sign_or_one(xm - xf)
            else:
                golden = True
        if golden:  # a golden-section step
            e = a - xf if xf >= xm else b - xf
            rat = GOLDEN_MEAN * e
        step = abs(rat)
        x = xf + _sign_or_one(rat) * (step if step != step or step > tol1 else tol1)
        fu = func(x)
        num += 1
        if fu <= fx:
            if x >= xf:
                a = xf
            else:
                b = xf
            fulc, ffulc = nfc, fnfc
            nfc, fnfc = xf, fx
            xf, fx = x, fu
        else:
            if x < xf:
                a = x
            else:
                b = x
            if fu <= fnfc or nfc == xf:
                fulc, ffulc = nfc, fnfc
                nfc, fnfc = x, fu
            elif fu <= ffulc or fulc == xf or fulc == nfc:
                fulc, ffulc = x, fu
        xm = 0.5 * (a + b)
        tol1 = SQRT_EPS * abs(xf) + xatol / 3.0
        tol2 = 2.0 * tol1
        if num >= maxfun:
            break
    return xf, fx, num
