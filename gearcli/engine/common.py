"""What both integrators share with scipy's ``_ivp/common.py``: the initial step (``select_initial_step``)."""

from __future__ import annotations

from gearcli.engine.linalg import _rms
from gearcli.engine.numba_cache import jit
from gearcli.engine.rhs import rhs


@jit
def select_initial_step(t0, y0, t_bound, f0, rtol, atol, model, th, fc, y1, f1, scale, diff, tmp, exponent, max_step):
    """scipy's ``select_initial_step`` (forward direction; ``exponent`` 1 / (error order + 1); ``max_step`` the
    solver's, ``math.inf`` for none)."""
    n = y0.size
    interval = abs(t_bound - t0)
    if interval == 0.0:
        return 0.0
    for i in range(n):
        scale[i] = atol[i] + abs(y0[i]) * rtol[i]
    d0 = _rms(y0, scale, tmp)
    d1 = _rms(f0, scale, tmp)
    if d0 < 1e-5 or d1 < 1e-5:
        h0 = 1e-6
    else:
        h0 = 0.01 * d0 / d1
    h0 = min(h0, interval)
    for i in range(n):
        y1[i] = y0[i] + h0 * f0[i]
    rhs(t0 + h0, y1, f1, model, th, fc)
    for i in range(n):
        diff[i] = f1[i] - f0[i]
    d2 = _rms(diff, scale, tmp) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** exponent
    return min(100 * h0, h1, interval, max_step)
