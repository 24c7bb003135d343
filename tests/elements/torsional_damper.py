"""A test-only element: a pure torsional viscous damper between two bodies, T = c (theta_a' - theta_b').

The whole of a new element type: this module (the law, in the element protocol of
:mod:`gearcli.model.elements`, the only gearcli module it imports) plus one ``register`` call. It stores
no energy, carries no static torque and dissipates ``c delta'^2``.
"""

from __future__ import annotations

import numpy as np

from gearcli.model.elements import N_PARAM, adopt, plain

adopt(plain, globals())  # linear, unphased, never excited: the protocol's defaults

NAME = "test_torsional_damper"
SIGNS = (1.0, -1.0)  # twist = theta_a - theta_b
PARAMS = ("damping_Nms_rad",)
CHANNELS: tuple[str, ...] = ()
I_C = 0


def pack(damping_Nms_rad) -> np.ndarray:
    row = np.zeros(N_PARAM)
    row[I_C] = float(damping_Nms_rad)
    return row


def force(P, d, dd, phi, wphi):
    c = P[I_C]
    return c * dd, 0.0, c, 0.0, 0.0, c * dd * dd, 0.0, 0.0


def power_gradient(P, d, dd, phi, wphi):
    return 0.0, 2.0 * P[I_C] * dd, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0


def potential(P, d, phi):
    return 0.0


def channel(P, i, d, phi):
    return 0.0


def static_deflection(P, F):
    return 0.0  # a damper carries no static torque


def deflection_scale(P, F, floor):
    return floor


def tangent(P, F, stiffest_phase=False):
    return 0.0, P[I_C], 0.0


def damped(P) -> bool:
    return P[I_C] > 0.0
