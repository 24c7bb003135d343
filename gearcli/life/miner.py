"""Palmgren–Miner damage on a standard's S–N curves, ISO 6336-6 (docs/life.md, "Damage").

The curves themselves (:class:`SNCurve`, the Miner variants below the knee) live in :mod:`gearcli.rating.sn`: a
rating standard returns them per member and mode, and life reads them without knowing the standard.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

from gearcli.rating.sn import VARIANT_NAMES, VARIANTS, SNCurve

__all__ = ["VARIANTS", "VARIANT_NAMES", "SNCurve", "miner_damage", "spectrum_safety"]


def miner_damage(stresses_MPa: Sequence[float], cycles: Sequence[float], curves: Sequence[SNCurve]) -> float:
    """D = sum n_i / N_i (a bin whose N_i is unbounded adds nothing)."""
    return sum(n / c.cycles_to_failure(s) for s, n, c in zip(stresses_MPa, cycles, curves, strict=True))


def spectrum_safety(damage_at: Callable[[float], float], *, lo: float = 1e-3, hi: float = 1e3) -> float | None:
    """The load multiplier s with D(s) = 1, by a bracketed root find on ln s (scipy's brentq, xtol 1e-12).

    The bracket starts at [lo, hi] and is widened (by 10^3 a step, to e^±700) until it holds the root: D grows with
    s, so a gross overload's multiplier lies below lo and a light spectrum's above hi. Until 2026-12-01 a spectrum
    already past D = 1 at lo was reported as s = lo (0.001 where D = 1 needs 6.0e-5: its stress safety 0.032 for
    0.0078), and one still below D = 1 at hi as unbounded. None only when no finite multiplier reaches D = 1 (every
    class at zero stress, or below a flat endurance limit at every multiplier up to e^700)."""
    from scipy.optimize import brentq  # lazy: scipy, start-up time

    def g(log_s: float) -> float:
        d = damage_at(math.exp(log_s))
        return math.log(d) if d > 0.0 else -1e3

    a, b = math.log(lo), math.log(hi)
    step, limit = math.log(1e3), 700.0
    while g(b) < 0.0:
        if b >= limit:
            return None
        a, b = b, min(b + step, limit)
    while g(a) > 0.0:
        if a <= -limit:
            return math.exp(a)
        a, b = max(a - step, -limit), a
    return math.exp(brentq(g, a, b, xtol=1e-12, rtol=1e-12))
