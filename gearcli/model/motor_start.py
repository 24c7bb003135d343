"""Whether a motor drive can start its load, from the curves alone (``gearcli design``; numpy, never scipy).

The same physics as ``simulate``'s ``motor_stalls`` (:mod:`gearcli.simulate.motor`), judged before any run: the
motor's steady torque ``T_m(w)`` with its starting method (full voltage; a star-delta motor in star below its
switch-over speed; a converter at its full frequency and torque limit) against the load reflected to the motor,
``T_L(w rho_N) rho_N / prod eta`` (:func:`gearcli.model.damping.reflected_load_Nm`: the train's ratio and the
efficiencies of its lossy meshes, power flowing forward). From rest the motor accelerates while ``T_m`` exceeds
it; it cannot start when ``T_m(0)`` does not (a direct start's locked-rotor torque, a star start's third of it),
and it stalls when the first speed where the net torque falls to 0 lies below the curve's breakdown speed (the
unstable branch: a pull-up torque short of the load, or a load rising faster than the curve) or, for a star-delta
start, below the switch-over speed (it never switches to delta). A soft start's initial voltage u0 gives u0² of
the locked-rotor torque at t = 0: below the load, the load turns the train backwards until the voltage has risen
(``simulate``'s ``motor_rolls_back`` when it does): a second check. A converter's start (0 Hz at t = 0) depends on
how fast its supply ramps against the inertias, which only ``simulate`` judges.
"""

from __future__ import annotations

import math

from gearcli import diagnostics as dg
from gearcli.diagnostics import Diagnostic
from gearcli.model.assembly import Layout
from gearcli.model.damping import STEADY_T, net_torque_scan, reflected_load_Nm
from gearcli.model.elements import machine

RAD_S_TO_RPM = 60.0 / (2.0 * math.pi)
BISECTIONS = 200  # to the last bit of a crossing bracketed by the scan


def _first_crossing(grid, f, net) -> float | None:
    """The first speed from rest where the net torque falls through 0 (None: it never does up to the scan's end)."""
    for i in range(grid.size - 1):
        if f[i] > 0.0 >= f[i + 1]:
            lo, hi = float(grid[i]), float(grid[i + 1])
            for _ in range(BISECTIONS):
                mid = 0.5 * (lo + hi)
                if mid in (lo, hi):
                    break
                lo, hi = (mid, hi) if net(mid) > 0.0 else (lo, mid)
            return hi
    return None


def motor_start_diagnostics(lay: Layout) -> tuple[Diagnostic, ...]:
    """The design's warnings of a motor drive that cannot start its load (module text): code ``design``, check
    ``motor_cannot_start`` (with ``stall_speed_rpm``, 0 at standstill, and the motor's and the reflected load's
    torques there) and ``soft_start_rolls_back``. Nothing for any other drive."""
    motor = lay.drive.motor
    if not lay.motor_drive or motor is None:
        return ()
    row = lay.motor_row
    grid, f, w_b, net = net_torque_scan(lay, row)
    found: list[Diagnostic] = []
    start = motor.starting
    switch = motor.start_parameters[0] if start == "star_delta" else 0.0
    stall = 0.0 if f[0] <= 0.0 else _first_crossing(grid, f, net)
    if stall is not None and (stall == 0.0 or stall < w_b or stall < switch):
        t_m = machine.motor_torque(row, STEADY_T, stall)[0]
        load = reflected_load_Nm(lay, stall)
        where = (f"at standstill: its {start} start gives {t_m:.4g} N·m there" if stall == 0.0 else
                 f"at {stall * RAD_S_TO_RPM:.5g} rpm, in star below its switch-over speed "
                 f"{switch * RAD_S_TO_RPM:.5g} rpm (a third of its torque), so it never switches to delta"
                 if stall < switch else
                 f"at {stall * RAD_S_TO_RPM:.5g} rpm, below its breakdown speed {w_b * RAD_S_TO_RPM:.5g} rpm, where "
                 "its torque falls short of the load")
        found.append(dg.warning(
            dg.DESIGN, f'input: drive = "motor": the motor cannot start its load: it stalls {where}, against the load '
            f"reflected to the motor (through the train's ratio and efficiencies) of {load:.4g} N·m; a larger motor, "
            + ("a direct start, " if start == "star_delta" else "") + "or a smaller load",
            check="motor_cannot_start", starting=start, stall_speed_rpm=stall * RAD_S_TO_RPM, motor_torque_Nm=t_m,
            load_torque_Nm=load, breakdown_speed_rpm=w_b * RAD_S_TO_RPM))
    elif start == "soft_start":
        u0 = motor.start_parameters[1]
        t0, load = machine.motor_torque(row, 0.0, 0.0)[0], reflected_load_Nm(lay, 0.0)
        if 0.0 < load and t0 < load:
            found.append(dg.warning(
                dg.DESIGN, f'input: drive = "motor": the soft start\'s initial voltage fraction {u0:g} gives {t0:.4g} '
                f"N·m at standstill (u0² of the locked-rotor torque), below the load reflected to the motor, "
                f"{load:.4g} N·m: the load turns the train backwards until the voltage has risen to "
                f"{math.sqrt(load / t0) * u0 if t0 > 0.0 else 1.0:.3g} of full; a higher initial_voltage_fraction, or "
                "a backstop or a brake holding the load until the motor's torque exceeds it",
                check="soft_start_rolls_back", initial_voltage_fraction=u0, start_torque_Nm=t0, load_torque_Nm=load))
    return tuple(found)
