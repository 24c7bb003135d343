"""Torsional spring-damper: a coupling or a flexible shaft (r_a = r_b = 1, deflection = twist, rad).

``F = k delta + c delta'`` (N m), linear in both; the damper dissipates ``c delta'^2``. Stiffness of a
solid round shaft, for reference: ``k = G pi d^4 / (32 L)`` (torsion of a circular bar).
"""

from __future__ import annotations

import numpy as np

from gearcli.model.elements import N_PARAM, adopt, plain

adopt(plain, globals())  # linear, unphased, never excited: the protocol's defaults (its own functions below)

NAME = "spring"
SIGNS = (1.0, -1.0)  # twist = theta_a - theta_b
PARAMS = ("stiffness_Nm_rad", "damping_Nms_rad")
CHANNELS: tuple[str, ...] = ()
I_K, I_C = 0, 1


def pack(spec) -> np.ndarray:
    """The parameter row of a :class:`gearcli.model.spec.SpringSpec`."""
    row = np.zeros(N_PARAM)
    row[I_K], row[I_C] = spec.stiffness_Nm_rad, spec.damping_Nms_rad
    return row


def force(P, d, dd, phi, wphi):
    """Torque k d + c dd, its partials, the damping power c dd^2 (no phase, no time-varying stiffness)."""
    k = P[I_K]
    c = P[I_C]
    return k * d + c * dd, k, c, 0.0, 0.0, c * dd * dd, 0.0, 0.0


def power_gradient(P, d, dd, phi, wphi):
    """Partials of (p_damp, p_elastic_tv, p_te) by (d, dd, phi, wphi)."""
    return 0.0, 2.0 * P[I_C] * dd, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0


def potential(P, d, phi):
    """Stored energy k d^2 / 2, J."""
    return 0.5 * P[I_K] * d * d


def channel(P, i, d, phi):
    """No channels of its own."""
    return 0.0


def static_deflection(P, F):
    """Twist that carries the torque F."""
    return F / P[I_K]


def deflection_scale(P, F, floor):
    """Scale of the twist for the absolute tolerance: the static twist, floored."""
    return max(abs(static_deflection(P, F)), floor)


def tangent(P, F, stiffest_phase=False):
    """(k, c, static twist) at the torque |F|: the law is linear."""
    d0 = static_deflection(P, abs(F))
    _, k, cd, _, _, _, _, _ = force(P, d0, 0.0, 0.0, 0.0)
    return k, cd, d0


def damped(P) -> bool:
    return P[I_C] > 0.0
