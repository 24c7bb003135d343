"""A test-only element with the loss hook: a torsional spring-damper coupling that passes on ``eta`` of the
torque it transmits in the power-flow direction (an idealised slipping coupling).

The whole of a lossy element: this module (the law and the loss hook of :mod:`gearcli.model.elements`, the
only gearcli module it imports) plus one ``register`` call; the assembly, the generated Python and the outputs
find its loss by name. Its loss law, written out here as the reference: the driving side takes ``f``, the
driven side ``eta f``, the power-flow sign ``s = tanh(f v / W)`` (``v`` the mean of the two sides' speeds):
``f_a = f (1 - c (1 - s))``, ``f_b = f (1 - c (1 + s))``, ``c = (1 - eta) / 2``.
"""

from __future__ import annotations

import math

import numpy as np

from gearcli.model.elements import N_PARAM, adopt, plain

adopt(plain, globals())  # linear, unphased, never excited

NAME = "test_lossy_coupling"
SIGNS = (1.0, -1.0)  # twist = theta_a - theta_b
PARAMS = ("stiffness_Nm_rad", "damping_Nms_rad", "efficiency", "loss_width_W")
CHANNELS: tuple[str, ...] = ()
I_K, I_C, I_ETA, I_LW = 0, 1, 2, 3
LOSS_WIDTH = 1e-3


def pack(spec) -> np.ndarray:
    k, c, eta = spec
    row = np.zeros(N_PARAM)
    row[I_K], row[I_C], row[I_ETA] = k, c, eta
    return row


def force(P, d, dd, phi, wphi):
    k, c = P[I_K], P[I_C]
    return k * d + c * dd, k, c, 0.0, 0.0, c * dd * dd, 0.0, 0.0


def power_gradient(P, d, dd, phi, wphi):
    return 0.0, 2.0 * P[I_C] * dd, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0


def potential(P, d, phi):
    return 0.5 * P[I_K] * d * d


def channel(P, i, d, phi):
    return 0.0


def static_deflection(P, F):
    return F / P[I_K]


def deflection_scale(P, F, floor):
    return max(abs(F / P[I_K]), floor)


def tangent(P, F, stiffest_phase=False):
    return P[I_K], P[I_C], abs(F) / P[I_K]


def damped(P) -> bool:
    return P[I_C] > 0.0


# ------------------------------------------------------------------------------------------ the loss hook
def lossy(P) -> bool:
    return bool(0.0 < P[I_ETA] < 1.0)


def efficiency(P):
    return P[I_ETA]


def loss_sides(P):
    return ((0, 1.0),), ((1, 1.0),)  # the input side (slot 0) drives forward, the output side (slot 1) is driven


def loss_factors(P, f, va, vb):
    v = 0.5 * (va + vb)
    w = P[I_LW]
    s = math.tanh(f * v / w)
    c = 0.5 * (1.0 - P[I_ETA])
    ga, gb = 1.0 - c * (1.0 - s), 1.0 - c * (1.0 + s)
    gx = c * (1.0 - s * s) / w
    return f * ga, f * gb, ga + f * gx * v, f * f * gx, gb - f * gx * v, -f * f * gx


def with_loss_width(P, width_W):
    Q = np.array(P, dtype=float)
    Q[I_LW] = width_W
    return Q
