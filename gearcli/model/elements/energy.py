"""The energy quadratures' integrands as plain scalar math: one source for both engines.

The run integrates, beside the motion, the work the drive puts in, the work the load takes out, what the dampers
and mesh losses dissipate and what the time-varying springs receive (the energy balance of docs/numerics.md). The
generated Python (:mod:`gearcli.model.codegen`) calls these by name and the compiled kernel compiles this module
as it compiles the element laws (:mod:`gearcli.engine.laws`), so both evaluate the same operations in the same
order; the sums over connectors are the assembly's (each connector's own power comes from its element).
"""

from __future__ import annotations


def speed_drive_power(reaction, inertia, a0, w0):
    """The power a speed drive puts in: (the connectors' torque on body 0 + J_0 a_0) w_0 — the torque that makes
    body 0 follow its prescribed motion, times its speed."""
    return (reaction + inertia * a0) * w0


def torque_power(torque, w):
    """The power of a torque ``torque`` on a body turning at ``w`` (the torque drive's input, the load's output)."""
    return torque * w
