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
from typing import TYPE_CHECKING

from gearcli import diagnostics as dg
from gearcli.diagnostics import Diagnostic
from gearcli.model.assembly import Layout
from gearcli.model.damping import (
    STEADY_T,
    back_driving_Nm,
    breakaway_Nm,
    falling_zero,
    net_torque_scan,
    reflected_load_Nm,
)
from gearcli.model.elements import machine

if TYPE_CHECKING:
    from gearcli.model.spec import MotorSpec

RAD_S_TO_RPM = 60.0 / (2.0 * math.pi)
LOAD_OFF_DESIGN = 0.01  # a speed-dependent load met more than 1 % off the design's load is warned (as a torque drive)
SPEED_OFF_DESIGN = 0.02  # a motor running more than 2 % off speed_rpm is warned (as a life point off its speed)
#: a motor whose steady torque exceeds its rated torque (rated power over rated speed) by more than this is warned:
#: an IEC motor's S1 rating (service factor 1.0) is for its rated torque continuously; 5 % covers the nameplate's
#: rounding and the load's estimate, and already means ~10 % more winding (I²R) losses (docs/motors.md)
OVERLOAD_MARGIN = 0.05


#: why a VFD runs off its speed_rpm, and what to give (a VFD's supply is set for the rated torque: docs/physics.md)
VFD_OFF_SPEED = ("a VFD's supply is set so that the motor runs at speed_rpm at its rated torque (the rated slip speed "
                 "above it; above the motor's base speed the field weakens and its rated torque slips further): at "
                 "another load it slips less or more (a converter with slip compensation would hold speed_rpm; the "
                 "model's does not)")
#: why a VFD on a torque_speed table runs off its speed_rpm: no rated point to set its supply by (docs/physics.md)
TABLE_VFD_OFF_SPEED = ("a VFD's supply follows speed_rpm with a nameplate motor only (its rated slip speed sets the "
                       "supply); this torque_speed table runs at its own synchronous speed: give speed_rpm the speed it "
                       "runs at, or the motor's nameplate")


def vfd_off_speed(table: bool) -> str:
    """Why a VFD runs off its speed_rpm, and what to give: a nameplate motor's supply is set for its rated torque
    (:data:`VFD_OFF_SPEED`), a ``torque_speed`` table's is its own synchronous speed (:data:`TABLE_VFD_OFF_SPEED`)."""
    return TABLE_VFD_OFF_SPEED if table else VFD_OFF_SPEED


def _load_off_design(lay: Layout, w_op: float, vfd: bool = False) -> list[Diagnostic]:
    """A speed-dependent load that the motor meets at another speed than ``speed_rpm``: the design's static forces
    assume the load at ``speed_rpm``, the run carries the load at the motor's own operating speed (which the
    dynamic factors refer to: :func:`gearcli.simulate.run.simulated_static_tangential_N`). Warned beyond
    LOAD_OFF_DESIGN of the load (a fan 1 % off in speed: 2 %). A VFD (``vfd``) too: its supply follows speed_rpm
    at the rated torque only, a fan at part load runs faster."""
    w_nom = lay.drive.speed_rad_s
    nominal = reflected_load_Nm(lay, w_nom)
    if not lay.load_law or w_nom <= 0.0 or nominal == 0.0:
        return []
    ratio = reflected_load_Nm(lay, w_op) / nominal
    if abs(ratio - 1.0) <= LOAD_OFF_DESIGN:
        return []
    motor = lay.drive.motor
    limit = motor.start_parameters[1] if vfd and motor is not None else 0.0
    why = (vfd_off_speed(motor is not None and bool(motor.table)) if vfd else
           "give the speed the motor runs at (or starting = \"vfd\", whose supply follows speed_rpm)")
    if limit > 0.0 and nominal >= limit:  # not slip: the converter's torque limit holds the motor below speed_rpm
        why = (f"the VFD's torque_limit_Nm {limit:.4g} N·m is below the load reflected to the motor at speed_rpm, "
               f"{nominal:.4g} N·m: the limit holds the motor where the load has fallen to it; a torque_limit_Nm "
               f"above {nominal:.4g} N·m (or a smaller load)")
    return [dg.warning(dg.MOTOR_SPEED_MISMATCH, f"the motor runs at {w_op * RAD_S_TO_RPM:.5g} rpm, not [input] speed_rpm "
                       f"= {w_nom * RAD_S_TO_RPM:.5g}: the speed-dependent load there is {ratio:.4g}x the design's, so "
                       "the design's static forces are off by that much (the dynamic factors refer to the load "
                       "at the operating speed); " + why,
                       operating_speed_rpm=w_op * RAD_S_TO_RPM, speed_rpm=w_nom * RAD_S_TO_RPM, load_ratio=ratio)]


def _speed_off_design(lay: Layout, motor: MotorSpec, w_op: float) -> list[Diagnostic]:
    """A motor whose operating point lies more than SPEED_OFF_DESIGN from ``[input] speed_rpm``, whatever its load
    law: the design's speeds, mesh frequencies, resonance checks and the rating's K_v and load cycles are at
    speed_rpm, the run at the motor's own speed (a constant load's forces agree, nothing else does). A nameplate
    VFD's supply follows speed_rpm (off by its slip at other loads than the rated torque, by design); a torque_speed
    table has no rated point to set its supply by and runs at its own synchronous speed."""
    w_nom = lay.drive.speed_rad_s
    vfd = motor.starting == "vfd"
    if w_nom <= 0.0 or abs(w_op - w_nom) <= SPEED_OFF_DESIGN * w_nom or (vfd and not motor.table):
        return []  # a nameplate VFD follows speed_rpm to within its rated slip speed (no slip compensation)
    rpm = RAD_S_TO_RPM
    nominal = reflected_load_Nm(lay, w_nom)
    why = (TABLE_VFD_OFF_SPEED if vfd else
           "give [input] speed_rpm the speed the motor runs at (or starting = \"vfd\", whose supply follows it)")
    return [dg.warning(dg.MOTOR_SPEED_MISMATCH, f"the motor runs at {w_op * rpm:.5g} rpm, not [input] speed_rpm = "
                       f"{w_nom * rpm:.5g} ({100 * (w_op / w_nom - 1):+.3g} %): the design's speeds, mesh frequencies "
                       "and resonance checks and the rating's K_v and load cycles are at speed_rpm, the run at the "
                       f"motor's own speed; {why}", operating_speed_rpm=w_op * rpm, speed_rpm=w_nom * rpm,
                       load_ratio=reflected_load_Nm(lay, w_op) / nominal if nominal else 1.0)]


def off_design_speed(lay: Layout, motor: MotorSpec, w_op: float) -> list[Diagnostic]:
    """``motor_speed_mismatch`` of a motor whose operating point ``w_op`` (rad/s, on the stable branch) lies off
    ``[input] speed_rpm``: a speed-dependent load met at another load than the design's, else a speed more than
    SPEED_OFF_DESIGN away (``simulate`` after its run; ``design`` from the curves, :func:`motor_start_diagnostics`)."""
    return _load_off_design(lay, w_op, motor.starting == "vfd") or _speed_off_design(lay, motor, w_op)


def overloaded(motor: MotorSpec, torque_Nm: float, where: str) -> list[Diagnostic]:
    """``motor_overloaded``: the steady torque ``torque_Nm`` the motor carries (``where`` says whose figure it is)
    beyond OVERLOAD_MARGIN above its nameplate's rated torque P_rated / w_rated (S1, continuous duty; a converter's
    supply above the base speed: P_rated over the speed, :attr:`MotorSpec.continuous_torque_Nm`); nothing for
    a motor without a rated point (a ``torque_speed`` table). A start's overshoot is no steady load: not judged."""
    rated = motor.continuous_torque_Nm
    if not rated > 0.0 or not abs(torque_Nm) > (1.0 + OVERLOAD_MARGIN) * rated:
        return []
    ratio = abs(torque_Nm) / rated
    what = ("rated_power_kW / rated_speed_rpm" if rated == motor.rated_torque_Nm else
            f"rated_power_kW over {motor.rated_speed_rad_s * RAD_S_TO_RPM:.5g} rpm, where the converter's supply above "
            "the base speed puts the rated slip: in field weakening the motor's rating is its power")
    return [dg.warning(dg.MOTOR_OVERLOADED, f"the motor carries {abs(torque_Nm):.4g} N·m in steady operation ({where}), {ratio:.3g}x "
                       f"its rated torque {rated:.4g} N·m ({what}): beyond the "
                       f"{100 * OVERLOAD_MARGIN:g} % margin on its S1 (continuous duty) rating its winding runs hotter "
                       "than its insulation class allows; a larger motor (rated torque above the load) or a smaller "
                       "load", torque_Nm=abs(torque_Nm), rated_torque_Nm=rated, overload_ratio=ratio)]


def field_weakening_advice(lay: Layout, motor: MotorSpec) -> str:
    """Why a VFD above its motor's base speed cannot carry its load, in words ("" otherwise): the weakened breakdown
    torque (w_B / w_s')^2 T_b at its supply below the load reflected to the motor at ``speed_rpm``."""
    k = motor.field_weakening
    load = reflected_load_Nm(lay, lay.drive.speed_rad_s)
    if motor.starting != "vfd" or motor.table or not k < 1.0 or motor.peak_torque_Nm >= load:
        return ""
    rpm = RAD_S_TO_RPM
    return (f"above its base speed {motor.base_speed_rad_s * rpm:.5g} rpm the converter weakens the field: at its "
            f"supply's {motor.synchronous_speed_rad_s * rpm:.5g} rpm synchronous the breakdown torque is {k:.3g} x "
            f"{motor.breakdown_torque_Nm:.4g} = {motor.peak_torque_Nm:.4g} N·m, below the load at speed_rpm "
            f"({load:.4g} N·m): a lower speed_rpm, a motor of a higher base speed, ")


def _as_design(diags: list[Diagnostic]) -> list[Diagnostic]:
    """``design``'s form of a motor warning: code ``design``, ``check`` the warning's own code."""
    return [dg.warning(dg.DESIGN, f"input: motor: {d.message}", check=d.code, **d.data) for d in diags]


def _first_crossing(grid, f, net) -> float | None:
    """The first speed from rest where the net torque falls through 0 (None: it never does up to the scan's end)."""
    for i in range(grid.size - 1):
        if f[i] > 0.0 >= f[i + 1]:
            return falling_zero(net, float(grid[i]), float(grid[i + 1]))[1]
    return None


def holding_fraction(torque_Nm: float, t0_Nm: float, u0: float) -> float:
    """The initial voltage fraction whose torque at standstill, u² of the locked-rotor torque (``t0_Nm`` at ``u0``),
    equals ``torque_Nm`` (1 where the motor gives none)."""
    return math.sqrt(torque_Nm / t0_Nm) * u0 if t0_Nm > 0.0 else 1.0


def motor_start_diagnostics(lay: Layout) -> tuple[Diagnostic, ...]:
    """The design's warnings of a motor drive that cannot start its load (module text): code ``design``, check
    ``motor_cannot_start`` (with ``stall_speed_rpm``, 0 at standstill, and the motor's and the reflected load's
    torques there) and ``soft_start_rolls_back``; a motor that starts, ``motor_speed_mismatch`` where its operating point
    lies off ``[input] speed_rpm`` (:func:`off_design_speed`, as ``simulate`` warns after its run). Nothing for any
    other drive."""
    motor = lay.drive.motor
    if motor is None:
        return ()
    if not lay.motor_drive:  # a prescribed speed with a motor described: it must carry the design's input torque
        w_nom = lay.drive.speed_rad_s
        return tuple(_as_design(overloaded(motor, reflected_load_Nm(lay, w_nom), "the design's input torque at "
                                           "speed_rpm"))) if w_nom > 0.0 else ()
    row = lay.motor_row
    grid, f, w_b, net = net_torque_scan(lay, row)
    found: list[Diagnostic] = []
    start = motor.starting
    switch = motor.start_parameters[0] if start == "star_delta" else 0.0
    # a load table's breakaway (its torque at standstill) holds the train until the motor's torque there exceeds
    # it; the model's table, turning with the rotation, is 0 at rest (a converter's start is simulate's to judge)
    held = breakaway_Nm(lay) if start != "vfd" else 0.0
    stuck = 0.0 < held and machine.motor_torque(row, STEADY_T, 0.0)[0] <= held
    stall = 0.0 if f[0] <= 0.0 or stuck else _first_crossing(grid, f, net)
    cannot = stall is not None and (stall == 0.0 or stall < w_b or stall < switch)
    if cannot:
        assert stall is not None
        t_m = machine.motor_torque(row, STEADY_T, stall)[0]
        load = held if stuck else reflected_load_Nm(lay, stall)
        where = (f"at standstill: its {start} start gives {t_m:.4g} N·m there"
                 + (", not above the load table's breakaway torque (its first point, the torque at standstill)"
                    if stuck else "") if stall == 0.0 else
                 f"at {stall * RAD_S_TO_RPM:.5g} rpm, in star below its switch-over speed "
                 f"{switch * RAD_S_TO_RPM:.5g} rpm (a third of its torque), so it never switches to delta"
                 if stall < switch else
                 f"at {stall * RAD_S_TO_RPM:.5g} rpm, below its breakdown speed {w_b * RAD_S_TO_RPM:.5g} rpm, where "
                 "its torque falls short of the load")
        found.append(dg.warning(
            dg.DESIGN, f'input: drive = "motor": the motor cannot start its load: it stalls {where}, against the load '
            f"reflected to the motor (through the train's ratio and efficiencies) of {load:.4g} N·m; "
            + field_weakening_advice(lay, motor) + "a larger motor, "
            + ("a direct start, " if start == "star_delta" else "") + "or a smaller load",
            check="motor_cannot_start", starting=start, stall_speed_rpm=stall * RAD_S_TO_RPM, motor_torque_Nm=t_m,
            load_torque_Nm=load, breakdown_speed_rpm=w_b * RAD_S_TO_RPM))
    elif stall is not None:  # it runs up to its operating point: is that where the design's speeds are?
        found += [dg.warning(dg.DESIGN, f'input: drive = "motor": {d.message}', check="motor_speed_mismatch", **d.data)
                  for d in off_design_speed(lay, motor, stall)]
        found += _as_design(overloaded(motor, reflected_load_Nm(lay, stall), "the load reflected to it at its "
                                       f"operating point {stall * RAD_S_TO_RPM:.5g} rpm"))
    if start == "soft_start" and not cannot:
        u0 = motor.start_parameters[1]
        t0, load = machine.motor_torque(row, 0.0, 0.0)[0], reflected_load_Nm(lay, 0.0)
        # the load turns the train backwards only past what reaches the motor with the power flowing back (its
        # torque times eta / i): between that and the forward load / (i eta) the train's losses hold it at rest
        back = back_driving_Nm(lay, load)
        if 0.0 < load and t0 < back:
            found.append(dg.warning(
                dg.DESIGN, f'input: drive = "motor": the soft start\'s initial voltage fraction {u0:g} gives {t0:.4g} '
                f"N·m at standstill (u0² of the locked-rotor torque), below the load reflected to the motor as it "
                f"drives the train backwards through its losses, {back:.4g} N·m (to start forward: {load:.4g} "
                "N·m): the load turns the train backwards, and the motor's torque falls as it does (a slip above 1), "
                "so it runs back well past the voltage whose torque at standstill would hold it; an "
                f"initial_voltage_fraction of at least {holding_fraction(back, t0, u0):.3g} holds the train at rest "
                f"({holding_fraction(load, t0, u0):.3g} starts it forward at once), or a backstop or a brake holding the load "
                "until the motor's torque exceeds it",
                check="soft_start_rolls_back", initial_voltage_fraction=u0, start_torque_Nm=t0, load_torque_Nm=load,
                back_driving_torque_Nm=back))
    return tuple(found)
