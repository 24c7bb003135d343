"""The drive's and the load's STEP profiles as plain scalar math: one source for both engines.

The generated Python (:mod:`gearcli.model.codegen`) calls these by name and the compiled kernel compiles this
module as it compiles the element laws (:mod:`gearcli.engine.laws`), so the two engines evaluate the same
operations in the same order. :mod:`gearcli.model.step` holds the same profiles for arrays of times (outputs,
plots); tests/unit/test_profile_laws.py checks the two agree.

``STEP(t, 0, 0, T, value) = value s^2 (3 - 2 s)``, ``s = t / T`` clamped to [0, 1] (MSC Adams); a speed ramped so
has the exact angle ``v T (s^3 - s^4 / 2)`` during the ramp, ``v (t - T / 2)`` after it, and the acceleration
``6 v s (1 - s) / T``.
"""

from __future__ import annotations


def ramp(t, value, ramp_s):
    """``STEP(t, 0, 0, ramp_s, value)``; ``ramp_s <= 0`` (or a zero value): ``value`` from ``t = 0`` on."""
    if ramp_s <= 0.0 or value == 0.0:
        return value
    if t < ramp_s:
        s = t * (1.0 / ramp_s)
        return value * s * s * (3.0 - 2.0 * s)
    return value


def input_motion(t, v, T, start):
    """(angle, speed, acceleration) of the speed drive whose speed is ``ramp(t, v, T)``, exact, from the start
    angle ``start`` (added only when it is not 0)."""
    if T <= 0.0:
        th = v * t
    elif t < T:
        s = t * (1.0 / T)
        th = (v * T) * s * s * s * (1.0 - 0.5 * s)
        if start != 0.0:
            th = th + start
        return th, v * s * s * (3.0 - 2.0 * s), (6.0 * v / T) * s * (1.0 - s)
    else:
        th = v * (t - 0.5 * T)
    if start != 0.0:
        th = th + start
    return th, v, 0.0
