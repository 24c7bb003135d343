"""The closed form of data/linear_te_resonance.toml, a linear single-DOF mesh oscillator forced by its transmission
error (the pinion speed-prescribed, the gear free; no backlash):

    m_e q'' + c q' + k q = F_0 + m_e Omega^2 e_1 cos(Omega t),   m_e = J / r_b^2,  c = 2 zeta sqrt(k m_e),  Omega = z n,
    |q| = m_e Omega^2 e_1 / sqrt((k - m_e Omega^2)^2 + (c Omega)^2),
    F_t = F_0 cos(alpha) + its amplitude sqrt(k^2 + (c Omega)^2) |q| cos(alpha),

and its Floquet multipliers exp(lambda T), lambda = -zeta w_n + i w_n sqrt(1 - zeta^2), T = 2 pi / Omega.
"""

from __future__ import annotations

import cmath
import math

ALPHA, R, J, K, E1, TEETH, TORQUE = math.radians(20.0), 25 * 3e-3 / 2, 0.0063, 2e8, 5e-6, 25, 350.0


def orbit(zeta: float, rpm: float) -> tuple[float, float, complex]:
    """(the static F_t, the steady F_t amplitude, the multiplier with Im > 0)."""
    rb = R * math.cos(ALPHA)
    me = J / rb ** 2
    c = 2 * zeta * math.sqrt(K * me)
    omega = TEETH * rpm * 2 * math.pi / 60
    q = me * omega ** 2 * E1 / math.hypot(K - me * omega ** 2, c * omega)
    wn = math.sqrt(K / me)
    lam = complex(-zeta * wn, wn * math.sqrt(1 - zeta ** 2))
    return TORQUE / R, math.hypot(K, c * omega) * q * math.cos(ALPHA), cmath.exp(lam * 2 * math.pi / omega)


def mesh_hz(rpm: float) -> float:
    return TEETH * rpm / 60
