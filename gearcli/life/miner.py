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
    None when no multiplier in [lo, hi] reaches D = 1 (a spectrum entirely below a flat endurance limit)."""
    from scipy.optimize import brentq  # lazy: scipy, start-up time

    def g(log_s: float) -> float:
        d = damage_at(math.exp(log_s))
        return math.log(d) if d > 0.0 else -1e3

    a, b = math.log(lo), math.log(hi)
    if g(b) < 0.0:
        return None
    if g(a) > 0.0:
        return lo
    return math.exp(brentq(g, a, b, xtol=1e-12, rtol=1e-12))
