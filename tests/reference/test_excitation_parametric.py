"""Stiffness harmonics without transmission error: the principal parametric instability of the mesh
(Hill's equation) where Floquet theory puts it, computed in this test independently of gearcli.

With no backlash and exponent 1 the oscillator of tests/reference/oscillator.py obeys

    q'' + 2 zeta w_n q' + w_n^2 (1 - s_j cos(j Omega t)) q = w_n^2 p0,

Omega the mesh frequency. The homogeneous part's monodromy matrix over one period 2 pi / Omega (two
unit initial states integrated by scipy at rtol 1e-12) has a multiplier of modulus > 1 inside the
instability tongue around j Omega = 2 w_n (Omega = 2 w_n / j), whose edges are found by bisection. gearcli's
model must grow inside the tongue and stay bounded just outside it.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from oscillator import WN, mesh_rad_s, oscillator, run, tail
from scipy.integrate import solve_ivp

ZETA = 0.01
S = 0.2  # stiffness harmonic: K (1 -/+ 20 %)


def max_multiplier(om: float, j: int) -> float:
    """Largest |Floquet multiplier| of the damped Hill equation at mesh frequency ``om``."""
    def f(t, y):  # (q, q' / w_n)
        q, u = y
        return [WN * u, -2 * ZETA * WN * u - WN * (1 - S * math.cos(j * om * t)) * q]

    T = 2 * math.pi / om
    cols = [solve_ivp(f, (0, T), y0, rtol=1e-12, atol=1e-14).y[:, -1] for y0 in ([1.0, 0.0], [0.0, 1.0])]
    M = np.column_stack(cols)
    return float(np.max(np.abs(np.linalg.eigvals(M))))


def tongue(j: int) -> tuple[float, float]:
    """Edges (in Omega / w_n) of the instability region around 2 / j, by bisection on |multiplier| = 1."""
    centre = 2.0 / j
    assert max_multiplier(centre * WN, j) > 1.0

    def edge(outside: float) -> float:
        lo, hi = centre, outside  # lo unstable, hi stable
        assert max_multiplier(hi * WN, j) < 1.0
        for _ in range(24):  # 0.3 x 2^-24: far finer than the margins below
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if max_multiplier(mid * WN, j) > 1.0 else (lo, mid)
        return 0.5 * (lo + hi)

    return edge(centre * 0.85), edge(centre * 1.15)


def growth(r: float, j: int) -> float:
    """gearcli: the DTE's oscillation over the last 10 mesh periods of 150 / j over the first 10."""
    ks = (0.0,) * (j - 1) + (S,)
    model = oscillator(r, ks=ks, zeta=ZETA, p0_m=10e-6)
    periods = 150
    t, q, _, _ = run(model, periods, q0=10.1e-6)  # 1 % off the static deflection: a seed to grow
    first = q[:10 * 40]
    return float(np.ptp(tail(q, 10)) / np.ptp(first))


@pytest.mark.parametrize("j", [1, 2])
def test_principal_parametric_instability_where_floquet_puts_it(j):
    lo, hi = tongue(j)
    centre = 2.0 / j
    # the undamped first-order width is 2/j (1 -/+ S / 4); damping narrows it
    assert centre * (1 - S / 4) < lo < centre < hi < centre * (1 + S / 4)
    width = hi - lo
    # inside: the multiplier at the centre, mu, grows the response by ~mu^periods
    assert growth(centre, j) > 1e3
    assert growth(lo + 0.25 * width, j) > 10.0 and growth(hi - 0.25 * width, j) > 10.0
    # just outside (15 % of the width beyond either edge): bounded, the start's offset decays
    assert growth(lo - 0.15 * width, j) < 1.0
    assert growth(hi + 0.15 * width, j) < 1.0
    assert mesh_rad_s(oscillator(centre)) == pytest.approx(centre * WN, rel=1e-12)
