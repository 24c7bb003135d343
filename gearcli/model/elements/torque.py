"""Harmonic torques on the end bodies: the input torque ripple and the load fluctuation (docs/elements.md "Excitation").

Input ripple, orders per revolution of the input body (the motor, or shaft 1 without one), on a torque
drive only (a speed drive prescribes the motion, so a torque ripple there would do nothing):

    T_in = T_in,ramp (1 + sum_k a_k cos(n_k theta_in)),    a_k = amplitude_percent / 100, n_k = order,

cosine of the input angle, so the ripple peaks where the input body starts (theta = 0). Load fluctuation
in time, a sine so that it starts at the load's own value:

    T_L = T_L,ramp (1 + sum_k b_k sin(2 pi f_k t)),      b_k = amplitude_percent / 100, f_k = frequency_Hz.

Both rows are flat tuples ``(a_1, n_1, a_2, n_2, ...)`` / ``(b_1, f_1, ...)``, in plain ``math`` on floats
(numba-compatible, like the connector laws). The drive and load works integrate the actual torques, so the
energy balance holds without a term of its own.
"""

from __future__ import annotations

import math


def ripple(R, theta):
    """(1 + sum a_k cos(n_k theta), its d/dtheta) for the ripple row R."""
    f = 1.0
    df = 0.0
    for k in range(len(R) // 2):
        a = R[2 * k]
        n = R[2 * k + 1]
        f += a * math.cos(n * theta)
        df -= a * n * math.sin(n * theta)
    return f, df


def fluctuation(F, t):
    """1 + sum b_k sin(2 pi f_k t) for the fluctuation row F."""
    f = 1.0
    for k in range(len(F) // 2):
        f += F[2 * k] * math.sin(2.0 * math.pi * F[2 * k + 1] * t)
    return f


def flat(pairs) -> tuple[float, ...]:
    """((a, n), ...) -> (a, n, ...), as Python floats."""
    return tuple(float(v) for pair in pairs for v in pair)
