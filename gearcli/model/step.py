"""The MSC Adams STEP function and the motion of a STEP-ramped speed (docs/physics.md, "Torsional model").

``STEP(x, x0, h0, x1, h1) = h0 + (h1 - h0) s^2 (3 - 2 s)``, ``s = (x - x0)/(x1 - x0)`` clamped to
[0, 1]: a cubic with zero slope at both ends. A speed ramped as ``v STEP(t, 0, 0, T, 1)`` has the
exact angle ``v T (s^3 - s^4/2)`` during the ramp (``v T / 2 + v (t - T)`` after it) and the
acceleration ``6 v s (1 - s) / T``, largest (``1.5 v / T``) at ``t = T/2``. A ramp of 0 s means the
full value from ``t = 0``.
"""

from __future__ import annotations

import numpy as np


def step(x, x0: float, h0: float, x1: float, h1: float):
    """Adams ``STEP(x, x0, h0, x1, h1)`` for a float or an array ``x`` (``x1 > x0``)."""
    s = np.clip((np.asarray(x, dtype=float) - x0) / (x1 - x0), 0.0, 1.0)
    out = h0 + (h1 - h0) * s * s * (3.0 - 2.0 * s)
    return float(out) if out.ndim == 0 else out


def ramp(t, ramp_s: float, value: float):
    """``STEP(t, 0, 0, ramp_s, value)``; ``ramp_s = 0``: ``value`` from ``t = 0`` on."""
    if ramp_s <= 0.0:
        out = np.full(np.shape(t), float(value))
        return float(out) if out.ndim == 0 else out
    return step(t, 0.0, 0.0, ramp_s, value)


def ramp_motion(t, ramp_s: float, speed: float):
    """Angle, speed and acceleration of a shaft whose speed is ``ramp(t, ramp_s, speed)``, exact.

    Works on a float or an array ``t >= 0``; returns a tuple of three of the same shape.
    """
    t = np.asarray(t, dtype=float)
    omega, alpha = _rates(t, ramp_s, speed)
    if ramp_s <= 0.0:
        angle = speed * t
    else:
        s = np.clip(t / ramp_s, 0.0, 1.0)
        angle = np.where(t < ramp_s, speed * ramp_s * (s**3 - 0.5 * s**4), speed * (t - 0.5 * ramp_s))
    if t.ndim == 0:
        return float(angle), float(omega), float(alpha)
    return angle, omega, alpha


def ramp_rates(t, ramp_s: float, speed: float):
    """Speed and acceleration of :func:`ramp_motion` alone (the same numbers, without the angle): for a float or an
    array ``t >= 0``, a tuple of two of its shape."""
    t = np.asarray(t, dtype=float)
    omega, alpha = _rates(t, ramp_s, speed)
    if t.ndim == 0:
        return float(omega), float(alpha)
    return omega, alpha


def _rates(t: np.ndarray, ramp_s: float, speed: float) -> tuple[np.ndarray, np.ndarray]:
    if ramp_s <= 0.0:
        return np.full(t.shape, float(speed)), np.zeros(t.shape)
    s = np.clip(t / ramp_s, 0.0, 1.0)
    return speed * s * s * (3.0 - 2.0 * s), 6.0 * speed * s * (1.0 - s) / ramp_s
