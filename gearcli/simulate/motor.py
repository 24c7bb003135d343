"""The motor's side of a run: its steady operating point from the curves, the start time and slip of the
simulated start, and the warnings (stall, a ramp beyond the breakdown torque, an unsettled start).

Operating point: the motor torque T_m(w) (after its start: full voltage, star-delta in delta, the VFD at its
full synchronous speed and torque limit) against the load reflected to the motor, ``T_L(w rho_N) rho_N / prod
eta`` (power flowing forward through every lossy mesh), rho_N the output's speed over the motor's. From rest
the motor accelerates while ``T_m > T_refl``; it settles at the first speed where the net torque reaches 0. The
motor's stable branch lies above its breakdown speed (the curve's largest torque); a motor whose first
crossing from rest is not on that branch (or that cannot start at all) stalls: a warning. An overhauling load
(net torque still positive at the synchronous speed) is sought on the generating branch, up to slip -1: the
motor brakes it there as a generator (a hoist lowering), and runs away only where no crossing exists.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from gearcli import diagnostics as dg
from gearcli.core.records import record
from gearcli.diagnostics import Diagnostic
from gearcli.model.assembly import Layout
from gearcli.model.damping import (
    SPEED_SAMPLES,
    STEADY_T,
    back_driving_Nm,
    curve_peak,
    net_torque_scan,
    vfd_ramp_starts,
)
from gearcli.model.damping import reflected_load_Nm as reflected_load
from gearcli.model.elements import machine
from gearcli.model.motor_start import field_weakening_advice, holding_fraction, off_design_speed, overloaded
from gearcli.model.spec import MotorSpec
from gearcli.simulate.rigid_start import downstream_losses
from gearcli.simulate.sampling import MAX_STEPS, TARGET, up_to_two_figures
from gearcli.simulate.stats import window_means

START_FRACTION = 0.98  # start time: to 98 % of the operating speed
RAD_S_TO_RPM = 60.0 / (2.0 * math.pi)
ROLLBACK = 0.01  # a motor turning backwards faster than 1 % of its synchronous speed is driven back by the load
RUNAWAY = 1.1  # a motor above 1.1 x its synchronous speed runs away (generating, an induction motor stays near it)


@record
class OperatingPoint:
    speed_rad_s: float | None  # where the motor settles from rest: the first crossing (None: it cannot start)
    stable_rad_s: float | None  # the crossing on the curve's stable branch (above the breakdown speed); None: none
    breakdown_rad_s: float  # the speed of the curve's largest torque
    synchronous_rad_s: float

    @property
    def reaches(self) -> bool:
        """The motor runs up to its stable branch: the first crossing from rest is the stable one."""
        return self.speed_rad_s is not None and self.speed_rad_s == self.stable_rad_s


def operating_point(lay: Layout, samples: int = SPEED_SAMPLES) -> OperatingPoint:
    """The motor's steady operating point against the reflected load (module text)."""
    row = lay.motor_row if lay.motor_drive else machine.motor_row(lay.drive.motor)
    ws = row[machine.M_WS]
    grid, f, w_b, net = net_torque_scan(lay, row, samples)
    down = [i for i in range(grid.size - 1) if f[i] > 0.0 >= f[i + 1]]  # net torque falls through 0: stable crossings
    crossings = [float(brentq(net, grid[i], grid[i + 1], xtol=1e-12 * ws)) if f[i + 1] < 0.0 else float(grid[i + 1])
                 for i in down]
    stable = [c for c in crossings if c >= w_b]
    first = None if f[0] <= 0.0 or not crossings else crossings[0]
    if first is None and stable and vfd_ramp_starts(lay):  # the ramp from 0 Hz runs it up to its stable crossing
        first = stable[-1]
    return OperatingPoint(first, stable[-1] if stable else None, w_b, ws)


def _net_at(lay: Layout, w: float) -> float:
    row = lay.motor_row if lay.motor_drive else machine.motor_row(lay.drive.motor)
    return machine.motor_torque(row, STEADY_T, w)[0] - reflected_load(lay, w)


def start_time(t: np.ndarray, w: np.ndarray, operating_rad_s: float | None) -> float | None:
    """The first time the motor reaches 98 % of its operating speed (None: never in the run)."""
    if operating_rad_s is None or operating_rad_s <= 0:
        return None
    hit = np.nonzero(w >= START_FRACTION * operating_rad_s)[0]
    if hit.size == 0:
        return None
    i = int(hit[0])
    if i == 0:
        return float(t[0])
    w0, w1 = w[i - 1], w[i]  # linear between the samples
    return float(t[i - 1] + (t[i] - t[i - 1]) * (START_FRACTION * operating_rad_s - w0) / (w1 - w0))


def start_time_error(t: np.ndarray, w: np.ndarray, operating_rad_s: float | None) -> float:
    """The estimated error (s) of :func:`start_time`'s linear interpolation between two output samples: its largest
    difference from the crossing of the parabola through those two samples and the one before or after (the linear
    rule errs as h^2, the parabola's as h^3). A direct start of configs/motor_direct_start.toml sampled every 10 ms:
    0.10294 s linear, 0.10183 s sampled every 25 us, estimated 1.3e-3 s (tests/simulate/test_start_time_sampling.py)."""
    if operating_rad_s is None or operating_rad_s <= 0:
        return 0.0
    target = START_FRACTION * operating_rad_s
    hit = np.nonzero(w >= target)[0]
    if hit.size == 0 or int(hit[0]) == 0:
        return 0.0
    i = int(hit[0])
    linear = start_time(t, w, operating_rad_s)
    assert linear is not None
    worst = 0.0
    for a in ((i - 2, i - 1, i), (i - 1, i, i + 1)):
        if a[0] < 0 or a[-1] >= t.size:
            continue
        roots = np.roots(np.polyfit(t[list(a)] - t[i - 1], w[list(a)] - target, 2)) + t[i - 1]
        inside = [float(r.real) for r in roots if abs(r.imag) < 1e-12 and t[i - 1] <= r.real <= t[i]]
        if inside:
            worst = max(worst, min(abs(r - linear) for r in inside))
    return worst


def _start_undersampled(t: np.ndarray, w: np.ndarray, operating_rad_s: float | None,
                        t_start: float | None) -> list[Diagnostic]:
    """``statistics_undersampled`` for ``summary.start_time_s`` where its interpolation between the output samples
    (:func:`start_time_error`) may err by more than the sampling's 1e-3 of it, with the ``simulation.steps`` that
    brings it below half that (the error falls as h^2; 1.25 margin)."""
    err = start_time_error(t, w, operating_rad_s)
    if t_start is None or not t_start > 0.0 or err <= TARGET * t_start:
        return []
    steps = (t.size - 1) * math.sqrt(err / (0.5 * TARGET * t_start)) * 1.25
    want = up_to_two_figures(steps) if steps <= MAX_STEPS else None
    fix = (f"--set simulation.steps={want} resolves it" if want is not None else
           f"no simulation.steps up to the schema's {MAX_STEPS} resolves it: shorten duration_s")
    return [dg.warning(dg.STATISTICS_UNDERSAMPLED, f"the motor's start time {t_start:.5g} s is interpolated between "
                       f"output samples {float(t[1] - t[0]):.3g} s apart and may be {err:.2g} s ({err / t_start:.1e}) "
                       f"off; {fix}", statistic="start_time_s", estimated_error_s=err,
                       relative_error=err / t_start, steps=want)]


def momentum_weights(lay: Layout) -> np.ndarray:
    """Per body, its weight c_i in the train's momentum reflected to the motor, p = sum_i c_i w_i: J_0 for the
    motor's body, f J_i rho_i / g_i for the others (f = 1 / the train's efficiency, g_i the losses between body i
    and the load, as the rigid start: :func:`gearcli.simulate.rigid_start.downstream_losses`). In the rigid limit
    p = J_eff w, and the bodies' equations summed with these weights give T_m - f rho_N T_L = dp/dt (exact for a
    lossless train, elastic or not: every connector's internal torques cancel in the rigid mode's weights)."""
    rho = np.array([b.ratio for b in lay.bodies], float)
    J = np.asarray(lay.inertias, float) / downstream_losses(lay)
    f0 = 1.0 / lay.train_efficiency(True) if lay.load.torque_Nm >= 0 else lay.train_efficiency(False)
    c = f0 * J * rho
    c[0] = J[0]
    return c


def _accelerating_Nm(lay: Layout, t: np.ndarray, omega: np.ndarray | None, mask: np.ndarray,
                     periodic: bool) -> float:
    """The part of the window's mean motor torque that changed the train's momentum (:func:`momentum_weights`):
    (p(t_1) - p(t_0)) / (t_1 - t_0) over the window; 0 for a periodic window (an orbit: p returns) or without the
    bodies' speeds. A window that begins while the train still runs up carries it on top of the load: a 15 kW DOL
    start 0.005 s after its 98 % time read 94.24 N·m against the 89.36 N·m load it carries there."""
    idx = np.flatnonzero(mask)
    if omega is None or periodic or idx.size < 2 or not t[idx[-1]] > t[idx[0]]:
        return 0.0
    c = momentum_weights(lay)
    return float(c @ (omega[:, idx[-1]] - omega[:, idx[0]])) / float(t[idx[-1]] - t[idx[0]])


def summary(lay: Layout, t: np.ndarray, w_motor: np.ndarray, t_motor: np.ndarray, mask: np.ndarray,
            window: tuple[float, float], periodic: bool = False,
            omega: np.ndarray | None = None) -> tuple[dict[str, float | None], list[Diagnostic]]:
    """The JSON ``summary.motor`` object and the motor's warnings of one run; its window means (speed, torque) are
    the integral over the window (trapezoid rule, DESIGN section 7) as every mean of simulate. ``omega``: every
    body's speed (bodies, samples), for the steady torque ``motor_overloaded`` judges (:func:`_accelerating_Nm`)."""
    motor = lay.drive.motor
    assert motor is not None
    op = operating_point(lay)
    diags: list[Diagnostic] = []
    ws = op.synchronous_rad_s
    if lay.speed_drive:  # a prescribed ramp: can the described motor deliver what it needs?
        need = float(np.max(t_motor))
        if need > motor.peak_torque_Nm:
            i = int(np.argmax(t_motor))
            diags.append(dg.warning(dg.RAMP_OVER_BREAKDOWN, f"the prescribed speed ramp needs {need:.4g} N·m at "
                                    f"{t[i]:.3g} s, {need / motor.peak_torque_Nm:.2f}x the motor's breakdown torque "
                                    f"({motor.peak_torque_Nm:.4g} N·m): the motor cannot follow it; lengthen "
                                    "[input] ramp_s or simulate drive = \"motor\"", torque_Nm=need,
                                    breakdown_torque_Nm=motor.peak_torque_Nm))
        diags += overloaded(motor, float(t_motor[mask].mean()), "the mean torque the prescribed speed needs over the "
                            "steady window")
        return {"synchronous_speed_rpm": ws * RAD_S_TO_RPM, "peak_required_torque_Nm": need}, diags
    rpm = RAD_S_TO_RPM
    driven = op.speed_rad_s is None and op.stable_rad_s is None and _net_at(lay, 0.0) > 0.0
    # a star-delta motor whose star curve meets the load below the switch-over speed never switches to delta: it
    # runs on in star (a third of its torque), though the crossing is on the stable branch
    in_star = (motor.starting == "star_delta" and op.speed_rad_s is not None
               and op.speed_rad_s < motor.start_parameters[0])
    reaches = op.reaches and not in_star
    if driven:  # the net torque never falls to 0 up to synchronous speed: the load drives the motor on
        diags += _runaway(t, w_motor, ws) or [dg.warning(
            dg.MOTOR_RUNS_AWAY, f"the motor's net torque stays positive up to its synchronous speed {ws * rpm:.5g} rpm "
            "(the load drives it): it would run away past it; the run ended before", synchronous_speed_rpm=ws * rpm)]
    elif not reaches:
        where = ("at standstill: it cannot start" if op.speed_rad_s is None else
                 f"at {op.speed_rad_s * rpm:.5g} rpm, below its breakdown speed {op.breakdown_rad_s * rpm:.5g} rpm"
                 if op.speed_rad_s < op.breakdown_rad_s else  # a table's dip (its largest torque at or below it)
                 f"at {op.speed_rad_s * rpm:.5g} rpm, where its curve dips below the load (a pull-up torque short "
                 "of it)")
        if motor.starting == "star_delta" and (op.speed_rad_s or 0.0) < motor.start_parameters[0]:
            where = _in_star(lay, motor, op.speed_rad_s)
        where = _fell_out_of_ramp(motor, t, w_motor, op) or where
        aim_rad_s = _delta_point(lay, motor, op) if in_star else op.stable_rad_s
        aim = ("" if aim_rad_s is None else f", so it never reaches its operating point {aim_rad_s * rpm:.5g} rpm")
        back = _driven_back(t, w_motor, ws)
        diags.append(dg.warning(dg.MOTOR_STALLS, "the motor's curve cannot carry the load (reflected through the "
                                f"reducer, losses included): it stalls {where}{aim}{back[0]}; "
                                f"{_limit_advice(lay, motor, op.speed_rad_s or 0.0)}"
                                f"{field_weakening_advice(lay, motor)}a larger motor or a smaller load",
                                stall_speed_rpm=None if op.speed_rad_s is None else op.speed_rad_s * rpm,
                                operating_point_rpm=None if aim_rad_s is None else aim_rad_s * rpm,
                                reverse_speed_rpm=back[1]))
    if not driven:
        diags += _runaway(t, w_motor, ws, op.stable_rad_s)
    t_start = start_time(t, w_motor, op.speed_rad_s)
    diags += _start_undersampled(t, w_motor, op.speed_rad_s, t_start)
    if not any(d.code == dg.MOTOR_STALLS for d in diags):  # a motor that cannot start at all is said so already
        recovered = reaches and t_start is not None and t_start <= window[0]
        diags += _rolls_back(lay, t, w_motor, ws, window[0] if recovered else None)
    diags += _reswitches(motor, t, w_motor)
    if reaches:  # a motor whose steady curve cannot carry the load stalls however slowly its supply ramps: the
        diags += _vfd_outrun(lay, motor, t, w_motor)  # stall warning names why; "lengthen ramp_s" would mislead
    if reaches and (t_start is None or t_start > window[0]):
        when = (f"does not reach 98 % of its operating speed within the run (to {float(t[-1]):.4g} s)" if t_start is None
                else f"reaches 98 % of its operating speed at {t_start:.4g} s, after the statistics window starts")
        diags.append(dg.warning(dg.START_NOT_SETTLED, f"the motor start {when}: the window (from {window[0]:.4g} s) is "
                                "not steady; lengthen duration_s or set simulation.window_start_s", start_time_s=t_start))
    if reaches and op.speed_rad_s is not None:
        diags += off_design_speed(lay, motor, op.speed_rad_s)
    w_mean, t_mean = (float(x) for x in window_means(t[mask], np.vstack([w_motor[mask], t_motor[mask]]), periodic))
    if reaches and op.speed_rad_s is not None:  # a start's overshoot is not judged, only the steady torque
        settled = t_start is not None and t_start <= window[0]
        accel = _accelerating_Nm(lay, t, omega, mask, periodic) if settled else 0.0
        what = ("its mean torque over the steady window" if abs(accel) <= 1e-3 * abs(t_mean) else
                f"its mean torque over the steady window, {t_mean:.4g} N·m, less the {accel:.4g} N·m that "
                "changed the train's momentum over it: the train still runs up in the window")
        diags += overloaded(motor, t_mean - accel if settled else reflected_load(lay, op.speed_rad_s),
                            what if settled else "the load reflected to it at "
                            f"its operating point {op.speed_rad_s * rpm:.5g} rpm; the window is not steady yet")
    out: dict[str, float | None] = {"start_time_s": t_start, "operating_speed_rpm": w_mean * RAD_S_TO_RPM,
           "operating_slip": (ws - w_mean) / ws,
           "operating_point_rpm": None if op.speed_rad_s is None else op.speed_rad_s * RAD_S_TO_RPM,
           "synchronous_speed_rpm": ws * RAD_S_TO_RPM,
           "mean_torque_Nm": t_mean}
    return out, diags


def _vfd_outrun(lay: Layout, motor: MotorSpec, t: np.ndarray, w_motor: np.ndarray) -> list[Diagnostic]:
    """A VFD whose speed ramp outruns the motor: the supply's synchronous speed w_s STEP(t, 0, 0, ramp_s, 1) runs
    ahead of the rotor by more than the curve's breakdown slip speed (w_s less the speed of the bare curve's
    largest torque, unchanged along the ramp at constant V/f): the motor has fallen out onto the unstable side of
    its moving curve, its torque falls as the supply pulls away, and it runs up only once the ramp has ended (a
    real converter trips on current or stretches the ramp). The speed-drive ramp's warning, for the VFD's ramp."""
    ramp = motor.start_parameters[0]
    if motor.starting != "vfd" or ramp <= 0.0:
        return []
    row = lay.motor_row if lay.motor_drive else machine.motor_row(motor)
    ws = row[machine.M_WS]
    grid = np.linspace(0.0, ws, 4001)
    w_b = curve_peak(lambda w: machine.motor_curve(row, w, ws)[0], grid,
                     int(np.argmax([machine.motor_curve(row, w, ws)[0] for w in grid])))
    slip_b = ws - w_b
    x = np.clip(t / ramp, 0.0, 1.0)
    ahead = ws * x * x * (3.0 - 2.0 * x) - w_motor  # machine._step01, vectorised
    i = int(np.argmax(ahead))
    if not ahead[i] > slip_b * (1.0 + 1e-3):
        return []
    rpm = RAD_S_TO_RPM
    return [dg.warning(dg.RAMP_OVER_BREAKDOWN, f"the VFD's speed ramp (ramp_s = {ramp:.4g} s) outruns the motor: the "
                       f"supply runs {ahead[i] * rpm:.4g} rpm ahead of the rotor at {float(t[i]):.4g} s, past the "
                       f"breakdown slip speed {slip_b * rpm:.4g} rpm (the curve's largest torque): the motor falls "
                       "out behind its supply and runs up only after the ramp (a real converter trips on current or "
                       "stretches the ramp); lengthen [input] ramp_s", slip_speed_rpm=ahead[i] * rpm,
                       breakdown_slip_speed_rpm=slip_b * rpm, at_s=float(t[i]))]


def _fell_out_of_ramp(motor: MotorSpec, t: np.ndarray, w_motor: np.ndarray, op: OperatingPoint) -> str:
    """A VFD whose full supply's curve carries the load at no speed (no crossing from rest, none on its stable
    branch), but whose ramp ran the motor up at a lower supply frequency first: it did start, and fell out behind
    its supply (a stall "at standstill" would misstate the run). "" otherwise."""
    if motor.starting != "vfd" or op.speed_rad_s is not None or op.stable_rad_s is not None or not w_motor.size:
        return ""
    i = int(np.argmax(w_motor))
    if not w_motor[i] > ROLLBACK * op.synchronous_rad_s:
        return ""
    weak = " as the field weakened above its base speed" if motor.field_weakening < 1.0 else ""
    return (f"after the VFD's ramp ran it up to {w_motor[i] * RAD_S_TO_RPM:.5g} rpm (at {float(t[i]):.4g} s): it fell "
            f"out behind its supply{weak}, and the full supply's curve carries the load at no speed")


def _delta_point(lay: Layout, motor: MotorSpec, op: OperatingPoint) -> float | None:
    """Where the full (delta) curve meets the load on its stable branch: the operating point a star-delta motor
    stuck in star never reaches (None: no crossing there)."""
    def net(w: float) -> float:
        return motor.curve(w) - reflected_load(lay, w)
    lo, hi = max(op.breakdown_rad_s, op.speed_rad_s or 0.0), op.synchronous_rad_s
    if not net(lo) > 0.0 > net(hi):
        return None
    return float(brentq(net, lo, hi, xtol=1e-12 * hi))


def _limit_advice(lay: Layout, motor: MotorSpec, w: float) -> str:
    """A VFD whose torque limit is below the load where the motor stalls: the limit, not the motor, is short."""
    limit = motor.start_parameters[1] if motor.starting == "vfd" else 0.0
    load = reflected_load(lay, w)
    if not 0.0 < limit < load:
        return ""
    return (f"the VFD's torque_limit_Nm {limit:.4g} N·m is below the load there ({load:.4g} N·m): a torque_limit_Nm "
            f"above it, ")


def _in_star(lay: Layout, motor: MotorSpec, stall_rad_s: float | None) -> str:
    """Where a star-delta motor stalls in star, in words: at standstill (a third of the locked-rotor torque is
    short of the load), or on the star curve below the switch-over speed, which it then never reaches."""
    sw = motor.start_parameters[0] * RAD_S_TO_RPM
    if stall_rad_s is None:
        row = lay.motor_row if lay.motor_drive else machine.motor_row(motor)
        return (f"at standstill: in star it gives {machine.motor_torque(row, STEADY_T, 0.0)[0]:.4g} N·m (a third of "
                f"its locked-rotor torque) against {reflected_load(lay, 0.0):.4g} N·m: it cannot start")
    return (f"in star at {stall_rad_s * RAD_S_TO_RPM:.5g} rpm, where a third of its torque meets the load, below its "
            f"switch-over speed {sw:.5g} rpm: it never switches to delta (a lower switch_speed_rpm, or another start)")


def _driven_back(t: np.ndarray, w_motor: np.ndarray, ws: float) -> tuple[str, float | None]:
    """A stalled motor that the load then turned backwards (faster than ``ROLLBACK`` of its synchronous speed): the
    stall warning's words for it and the lowest speed (rpm); ("", None) when it did not."""
    if w_motor.size == 0 or not float(w_motor.min()) < -ROLLBACK * ws:
        return "", None
    i = int(np.argmin(w_motor))
    low = float(w_motor[i]) * RAD_S_TO_RPM
    return (f"; the load drives the train backwards (the motor at {low:.4g} rpm at {float(t[i]):.4g} s): the run's "
            "numbers are no forward operating point", low)


#: what lifts a start's torque at standstill above the load, per starting method (a VFD's supply starts at 0 Hz)
STANDSTILL_CURE = {"soft_start": "a higher initial_voltage_fraction (u0² of the locked-rotor torque above the load), or ",
                   "star_delta": "a direct start (the full locked-rotor torque), or "}


def _cure(motor: MotorSpec, t0: float, back: float) -> str:
    """What lifts the start's torque at standstill above what turns the train back: a soft start's initial voltage
    fraction named by its figure, sqrt(back / T_lr) (design's ``soft_start_rolls_back`` names the same)."""
    if motor.starting == "soft_start" and t0 > 0.0:
        return (f"an initial_voltage_fraction of at least {holding_fraction(back, t0, motor.start_parameters[1]):.3g} "
                "(u0² of the locked-rotor torque above the load turning it back), or ")
    return STANDSTILL_CURE.get(motor.starting, "")


def _rolls_back(lay: Layout, t: np.ndarray, w_motor: np.ndarray, ws: float,
                window_from_s: float | None = None) -> list[Diagnostic]:
    """The load turns the train backwards during the start: the starting method's torque at standstill (a soft
    start's u0² of the locked-rotor torque, a star start's third, a VFD's 0 at 0 Hz) is below the load reflected to
    the motor as it drives the train backwards through its losses (T_L η / i, design's ``soft_start_rolls_back``),
    though the full curve carries it. Named with how far back it ran and the torques at standstill at t = 0.
    ``window_from_s``: the statistics window's start where the motor had reached its operating speed before
    it (the window's numbers are then an operating point's; only the start's include the roll-back)."""
    i = int(np.argmin(w_motor))
    low = float(w_motor[i])
    motor = lay.drive.motor
    assert motor is not None
    row = lay.motor_row if lay.motor_drive else machine.motor_row(motor)
    t0, load = machine.motor_torque(row, 0.0, 0.0)[0], reflected_load(lay, 0.0)
    back = back_driving_Nm(lay, load)  # what turns it back (design's check)
    # a swing back on a coupling or a shaft is no roll-back where the start's torque at standstill exceeds what turns
    # the train back: between that and the forward load the losses hold it (a load's step swings it, ±25 rpm)
    if not low < -ROLLBACK * ws or load <= 0.0 or t0 >= back:
        return []
    turns = float(np.nonzero(w_motor < 0.0)[0].size) / max(w_motor.size, 1)
    consequence = ("the run's numbers are no forward operating point" if window_from_s is None else
                   "the start's time and peak forces include the roll-back; the motor then runs up, before the "
                   f"statistics window ({window_from_s:.4g} s on), whose numbers are the operating point's")
    return [dg.warning(dg.MOTOR_ROLLS_BACK, f"the load turns the train backwards during the start: the motor reaches "
                       f"{low * RAD_S_TO_RPM:.4g} rpm at {float(t[i]):.4g} s ({100 * turns:.2g} % of the run backwards): "
                       f"its {motor.starting} start gives {t0:.4g} N·m at standstill at t = 0, below the load reflected "
                       f"to the motor as it drives the train backwards through its losses, {back:.4g} N·m (to start "
                       f"forward: {load:.4g} N·m); {consequence}; it needs {_cure(motor, t0, back)}"
                       "a backstop or a brake holding the load until the motor's torque exceeds it",
                       reverse_speed_rpm=low * RAD_S_TO_RPM, start_torque_Nm=t0, load_torque_Nm=load,
                       back_driving_torque_Nm=back)]


def _reswitches(motor: MotorSpec, t: np.ndarray, w_motor: np.ndarray) -> list[Diagnostic]:
    """A star-delta motor that falls back through its whole switch band after it first reached the switch-over
    speed: the model's switch is a function of speed (docs/physics.md), so it runs in star again, a third of the
    torque, and a rotor swinging on its coupling can toggle star and delta on every swing. A real starter (a timer
    or a latching speed relay) stays in delta: the start's forces past the first switch-over are the model's."""
    found = reswitches(motor, t, w_motor)
    if found is None:
        return []
    switched, entries, first, slowest = found
    w_sw = motor.start_parameters[0]
    rpm = RAD_S_TO_RPM
    return [dg.warning(dg.STAR_DELTA_RESWITCH, f"the star-delta motor reached its switch-over speed {w_sw * rpm:.5g} "
                       f"rpm at {switched:.4g} s and fell back below it into star {entries} time(s), first at "
                       f"{first:.4g} s, down to {slowest * rpm:.5g} rpm: the model switches on speed, a real starter "
                       "(timer or latching relay) stays in delta, so the start's forces after the first switch-over "
                       "include a star-delta toggling no contactor makes; a switch speed nearer the operating speed, "
                       "or a stiffer or better damped input coupling", switch_speed_rpm=w_sw * rpm,
                       switch_time_s=switched, reswitches=entries, first_reswitch_s=first,
                       min_speed_after_switch_rpm=slowest * rpm)]


def reswitches(motor: MotorSpec, t: np.ndarray, w_motor: np.ndarray) -> tuple[float, int, float, float] | None:
    """(time of the first switch-over, entries into star after it, time of the first, the lowest speed after the
    switch-over) of a star-delta motor that falls below its switch band after reaching the switch-over speed;
    None for any other start."""
    if motor.starting != "star_delta":
        return None
    w_sw = motor.start_parameters[0]
    low = w_sw - machine.STAR_DELTA_WIDTH * motor.synchronous_speed_rad_s  # below it: fully in star
    up = np.nonzero(w_motor >= w_sw)[0]
    if up.size == 0:
        return None
    after = w_motor[int(up[0]):]
    below = after < low
    if not below.any():
        return None
    times = t[int(up[0]):]
    # each entry into star is a fall from above the band's lower edge to below it
    entries = int(np.count_nonzero(below[1:] & ~below[:-1])) + int(below[0])
    return float(times[0]), entries, float(times[int(np.argmax(below))]), float(after.min())


def _runaway(t: np.ndarray, w_motor: np.ndarray, ws: float, generating_rad_s: float | None = None) -> list[Diagnostic]:
    """The motor far past its synchronous speed: a load that drives it beyond the curve's generating
    breakdown, or a curve that never brakes it. Named, with where it got to. A generating operating point
    above the synchronous speed moves the limit with it (0.1 x the synchronous speed beyond it)."""
    i = int(np.argmax(w_motor))
    top = float(w_motor[i])
    limit = RUNAWAY * ws
    if generating_rad_s is not None and generating_rad_s > ws:
        limit = generating_rad_s + (RUNAWAY - 1.0) * ws
    if not top > limit:
        return []
    at = float(t[int(np.argmax(w_motor > limit))])
    return [dg.warning(dg.MOTOR_RUNS_AWAY, f"the motor runs away: it passes {limit / ws:.3g} x its synchronous speed "
                       f"{ws * RAD_S_TO_RPM:.5g} rpm at {at:.4g} s and reaches {top * RAD_S_TO_RPM:.5g} rpm at "
                       f"{float(t[i]):.4g} s; nothing brakes it there (the load drives the motor past its curve): "
                       "the run's numbers are not an operating point", max_speed_rpm=top * RAD_S_TO_RPM,
                       synchronous_speed_rpm=ws * RAD_S_TO_RPM)]
