"""The periodic steady state: the excitation period, the Poincare map over it, subharmonics.

Excitation period. Every excitation of the scene has its own period at the steady operating speed (the
nominal input speed, after the ramps; a motor's operating point, :func:`steady_input_speed_rad_s`): a mesh
whose stiffness or transmission error varies with its phase ``phi = z_p theta_p`` repeats every mesh period
``60 / (z_p n_p)`` (n_p the pinion's speed in rpm); an input torque ripple of order o every
``1 / (o n_in / 60)``; a load fluctuation of frequency f every ``1 / f``.
:func:`excitation_periods` lists them from the scene's elements (each says whether it excites and the
period of its cycle) and arrays (``drive_ripple``, ``load_fluct``), :func:`common_period` combines them: the least common period when the ratios of
the periods are rational within a tolerance and their common period spans at most
:data:`MAX_COMMON_OVER_SLOWEST` slowest periods, else the slowest one, and it says which. A scene without any excitation has an equilibrium as its steady state;
its period is then the slowest mesh period (any period would do).

Poincare map. Past the ramps the run is integrated period by period, continuing from the state at the
last boundary (:func:`gearcli.simulate.solver.integrate` with ``t0``, ``y0``); the dynamic states
(deflections and free speeds: not the work quadratures, not the growing input angle) at consecutive
boundaries are compared in the run's own error norm, ``max_i |y_i(n) - y_i(n-k)| / (rtol |y_i(n)| +
atol_i)`` with the solver's atol vector (:func:`boundary_residual`). The response is periodic with
period k T (k = 1 .. :data:`MAX_SUBHARMONIC`) when that residual is at most 1 at two consecutive
boundaries; for k = 1 the slow approach of a lightly damped transient is also accounted for: the
distance left to the fixed point, ``r rho / (1 - rho)`` with the contraction ``rho`` of the last
residuals, must be within the tolerance too (:func:`detect_period`). Up to :data:`MAX_PERIODS` periods
or as many as end by ``simulation.duration_s`` (and within the run's evaluation budget), after which the
response is reported as not periodic ("none"): chaotic or quasi-periodic, or still settling. The
statistics are then taken over the last k periods (``MAX_SUBHARMONIC`` when none repeated) of the search,
integrated again from the boundary state with fine samples.
"""

from __future__ import annotations

import math
from dataclasses import replace
from fractions import Fraction
from functools import reduce

import numpy as np

from gearcli.config.bounds import PERIODIC_STATISTICS_SAMPLES
from gearcli.core.records import record
from gearcli.errors import ConfigError
from gearcli.model.damping import operating_speed_rad_s
from gearcli.simulate.results import SteadyState
from gearcli.simulate.solver import STATUS_BUDGET, STATUS_FINISHED, integrate

MAX_PERIODS = 2000  # cap on the excitation periods integrated past the ramps
MAX_SUBHARMONIC = 8  # period-k responses looked for, k = 1 .. 8
RATIO_RTOL = 1e-9  # relative tolerance of a rational period ratio
MAX_COMMON_OVER_SLOWEST = 1000  # a least common period beyond this many slowest periods is not useful
CONVERGED = 1.0  # residual (in units of the tolerance) at or below which two states are the same


@record
class Excitation:
    """One excitation of the scene and its period."""

    label: str  # "stage 1 mesh", "input torque ripple order 2", "load fluctuation 3 Hz"
    period_s: float


@record
class CommonPeriod:
    """The scene's common excitation period and how it was formed."""

    period_s: float
    source: str  # how it was formed
    exact: bool  # True when it is a common period of every excitation
    excited: bool = True  # False: nothing excites the scene (its steady state is an equilibrium)


def mesh_period_s(pinion_teeth: float, pinion_speed_rad_s: float) -> float:
    """One mesh cycle, 2 pi / (z_p w_p) = 60 / (z_p n_p) s."""
    return 2.0 * math.pi / (pinion_teeth * abs(pinion_speed_rad_s))


def ripple_period_s(order: float, input_speed_rad_s: float) -> float:
    """An input torque ripple of ``order`` per input revolution: 1 / (order n_in / 60) s."""
    return 2.0 * math.pi / (abs(order) * abs(input_speed_rad_s))


def excitation_periods(layout) -> list[Excitation]:
    """The periods of the scene's excitations at its steady operating speed (see the module text).

    An element that makes an excitation (``makes_excitation``: a mesh whose stiffness varies in time or
    with a transmission-error or stiffness harmonic) adds the period of its own cycle at its first body's
    nominal speed (``cycle_period_s``: the mesh period); the drive's ripple rows (amplitude, order) and the
    load's fluctuation rows (amplitude, frequency_Hz) with a non-zero amplitude each add theirs. The input
    body's speed is :func:`steady_input_speed_rad_s` (a motor's operating point).
    """
    cached = layout.__dict__.get("_excitation_periods")
    if cached is None:  # the layout's own (frozen): worked out once (the period, the statistics grid ask for them)
        cached = _excitation_periods(layout)
        object.__setattr__(layout, "_excitation_periods", cached)
    return list(cached)


def steady_input_speed_rad_s(layout) -> float:
    """The input body's speed in the steady state: a speed drive's nominal speed, a motor's operating point (the
    stable crossing of its curve with the load reflected to it), a torque drive's balance with a speed-dependent
    load (:func:`operating_speed_rad_s`), where it runs, not at ``[input] speed_rpm``: a mesh period from the
    nominal 1470 rpm of a motor running at 1472 rpm is 0.14 % short, and the response, whose mesh phases follow
    the motor, never repeats over it."""
    if layout.speed_drive:
        return layout.drive.speed_rad_s
    return operating_speed_rad_s(layout)


def _excitation_periods(layout) -> tuple[Excitation, ...]:
    """:func:`excitation_periods` of a layout, worked out (the drive's ripple and the load's fluctuation rows as
    the model's arrays hold them, without building the arrays)."""
    w_in = steady_input_speed_rad_s(layout)
    out: list[Excitation] = []
    if w_in == 0.0:
        return ()
    ripple = np.array(layout.ripple, float).reshape(-1, 2)  # = layout.arrays(...).drive_ripple, .load_fluct
    fluct = np.array(layout.fluctuation, float).reshape(-1, 2)
    for x in layout.connectors:
        if x.element.makes_excitation(x.params):
            out.append(Excitation(x.label, x.element.cycle_period_s(x.params, layout.bodies[x.a].ratio * w_in)))
    for amplitude, order in ripple:
        if amplitude != 0.0 and order != 0.0:
            out.append(Excitation(f"input torque ripple order {order:g}", ripple_period_s(order, w_in)))
    for amplitude, frequency in fluct:
        if amplitude != 0.0 and frequency != 0.0:
            out.append(Excitation(f"load fluctuation {frequency:g} Hz", 1.0 / abs(frequency)))
    return tuple(out)


def unexcited_period(layout) -> float:
    """The period used when nothing excites the scene: the slowest element cycle, a mesh period (the steady
    state is an equilibrium, which repeats over any period)."""
    w_in = steady_input_speed_rad_s(layout)
    periods = [x.element.cycle_period_s(x.params, layout.bodies[x.a].ratio * w_in)
               for x in layout.connectors if w_in != 0.0]
    return max((p for p in periods if p > 0.0), default=1.0)


def _ratio(a: float, b: float) -> Fraction | None:
    """a / b (a <= b: a period over the slowest one) as p / q with p <= MAX_COMMON_OVER_SLOWEST when b / a is
    within RATIO_RTOL of q / p, else None. The bound is on p, the slowest periods the pair's common period p b = q a
    spans, not on q, the count of the faster periods in it: a 116.4 Hz mesh beside a 20.3 Hz load fluctuation
    (p / q = 203 / 1164) repeat together every 10 s, 203 of the slower periods."""
    x = b / a
    f = Fraction(x).limit_denominator(MAX_COMMON_OVER_SLOWEST)
    return 1 / f if abs(float(f) - x) <= RATIO_RTOL * x else None


def common_period(excitations: list[Excitation]) -> CommonPeriod | None:
    """The least common period of ``excitations`` (see the module text); None when there are none.

    Each period is written as ``T_i = T_s p_i / q_i`` against the slowest one ``T_s``; the least common
    period is ``T_s lcm(p_i) / gcd(q_i)``. When a pair has no common period within
    :data:`MAX_COMMON_OVER_SLOWEST` slowest periods (its ratio is no fraction p / q with p up to that, within
    RATIO_RTOL), or all of them together would exceed that many, the slowest period is returned with
    ``exact = False`` and a source that says so.
    """
    if not excitations:
        return None
    slowest = max(excitations, key=lambda e: e.period_s)
    fractions = []
    for e in excitations:
        f = _ratio(e.period_s, slowest.period_s)
        if f is None:
            return CommonPeriod(slowest.period_s, f"the slowest excitation ({slowest.label}): {e.label} has no common "
                                f"period with it within {MAX_COMMON_OVER_SLOWEST} of its periods (period ratio "
                                f"{e.period_s / slowest.period_s:.10g}, no fraction p / q with p up to "
                                f"{MAX_COMMON_OVER_SLOWEST}), so the excitations have no usable common period", False)
        fractions.append(f)
    lcm_p = reduce(math.lcm, (f.numerator for f in fractions))
    gcd_q = reduce(math.gcd, (f.denominator for f in fractions))
    multiple = Fraction(lcm_p, gcd_q)
    if multiple > MAX_COMMON_OVER_SLOWEST:
        return CommonPeriod(slowest.period_s, f"the slowest excitation ({slowest.label}): the common period of "
                            f"all excitations is {float(multiple):.6g} of its periods, too long to use", False)
    labels = ", ".join(e.label for e in excitations)
    if len(excitations) == 1:
        return CommonPeriod(slowest.period_s, f"{slowest.label}", True)
    return CommonPeriod(slowest.period_s * float(multiple),
                        f"least common period of {labels} ({float(multiple):g} x the slowest)", True)


def boundary_residual(y_now: np.ndarray, y_then: np.ndarray, rtol: float, atol: np.ndarray) -> float:
    """``max_i |y_now_i - y_then_i| / (rtol |y_now_i| + atol_i)``: 1 is the run's tolerance."""
    scale = rtol * np.abs(y_now) + atol
    return float(np.max(np.abs(y_now - y_then) / scale)) if y_now.size else 0.0


@record
class Repeat:
    """After how many periods the state repeats, and the residual that decided it."""

    k: int  # the state repeats after k periods; 0: no repeat found
    residual: float  # the residual that decided it (units of the tolerance)


def detect_period(boundaries: list[np.ndarray], rtol: float, atol: np.ndarray,
                  max_k: int = MAX_SUBHARMONIC) -> Repeat:
    """The smallest k for which the last boundary states repeat after k periods (see the module text).

    ``boundaries`` are the dynamic states at consecutive period boundaries, oldest first (the last
    :func:`history_needed` of them suffice). Returns ``Repeat(0, r1)`` (r1 the last one-period residual)
    when none repeats yet.
    """
    n = len(boundaries)
    r1 = boundary_residual(boundaries[-1], boundaries[-2], rtol, atol) if n >= 2 else math.inf
    for k in range(1, max_k + 1):
        if n < k + 2:
            break
        now = boundary_residual(boundaries[-1], boundaries[-1 - k], rtol, atol)
        before = boundary_residual(boundaries[-2], boundaries[-2 - k], rtol, atol)
        if now > CONVERGED or before > CONVERGED:
            continue
        if k == 1 and not _settled(boundaries, rtol, atol):
            continue
        if k > 1 and not _stationary(boundaries, k, rtol, atol):
            continue
        return Repeat(k, now)
    return Repeat(0, r1)


def history_needed(max_k: int = MAX_SUBHARMONIC) -> int:
    """Boundary states :func:`detect_period` looks back over."""
    return SUBHARMONIC_SPANS * max_k + 2


SUBHARMONIC_SPANS = 3  # a period-k orbit must keep its one-period residuals over 3 k periods
STATIONARY_SLACK = 0.01  # relative change of the one-period residual allowed over those spans
SUBHARMONIC_SEPARATION = 10.0  # a period-k orbit's points lie this many tolerances apart, at least


def _stationary(boundaries: list[np.ndarray], k: int, rtol: float, atol: np.ndarray) -> bool:
    """A period-k orbit, not a transient caught in phase: a decaying free vibration whose frequency is
    nearly a multiple of 1 / (k T) also repeats after k periods to within the tolerance while it dies out
    (the one-period residual then shrinks); on a period-k orbit the one-period residual repeats too,
    ``r1(n) = r1(n - j k)`` for j = 1 .. SUBHARMONIC_SPANS, to within 2 tolerance units and
    :data:`STATIONARY_SLACK`; its points lie :data:`SUBHARMONIC_SEPARATION` tolerances apart (closer,
    it is a period-1 response still settling); and the state repeats after 2k and 3k periods as well (a
    quasi-periodic response whose frequency ratio is near a fraction with denominator k repeats after k
    periods within the tolerance but drifts away over more)."""
    if len(boundaries) < SUBHARMONIC_SPANS * k + 2:
        return False

    def r1(j: int) -> float:  # the one-period residual ending j boundaries before the last
        return boundary_residual(boundaries[-1 - j], boundaries[-2 - j], rtol, atol)

    now = r1(0)
    if now < SUBHARMONIC_SEPARATION:  # the k points of the orbit are not told apart from one: period-1 settling
        return False
    spans = range(1, SUBHARMONIC_SPANS + 1)
    if any(boundary_residual(boundaries[-1], boundaries[-1 - j * k], rtol, atol) > CONVERGED for j in spans):
        return False  # a quasi-periodic response near a k-fold repeat drifts away over 2k, 3k periods
    return all(abs(now - r1(j * k)) <= 2.0 * CONVERGED + STATIONARY_SLACK * now for j in spans)


def _settled(boundaries: list[np.ndarray], rtol: float, atol: np.ndarray) -> bool:
    """The one-period fixed point is within tolerance: the residuals shrink by rho per period, so the
    distance left is about r rho / (1 - rho); rho from the last three residuals (noise-level residuals,
    below 1/10 of the tolerance, count as settled)."""
    if len(boundaries) < 4:
        return False
    r = [boundary_residual(boundaries[-j], boundaries[-j - 1], rtol, atol) for j in (1, 2, 3)]
    if r[0] <= 0.1 * CONVERGED:
        return True
    rho = max(r[0] / r[1] if r[1] > 0 else 0.0, r[1] / r[2] if r[2] > 0 else 0.0)
    if rho >= 1.0:
        return False
    return r[0] * rho / (1.0 - rho) <= CONVERGED


# ----------------------------------------------------------------------------------------- the run
MIN_SAMPLES_PER_FASTEST = 64  # statistics samples per period of the fastest excitation, at least
FIRST_CHUNK, LAST_CHUNK = 4, 64  # periods integrated per solver start while looking for the repeat


@record
class PeriodicRun:
    """The run-up samples ``[0, t_start]`` followed by the statistics periods ``[t_n, t_n + k T]``."""

    run: object  # gearcli.simulate.solver.Integration (the two sampled parts; counters of all parts)
    window_s: tuple[float, float]  # the statistics periods, whole
    mask_window_s: tuple[float, float]  # the same without its last sample (the first one of the next period)
    steady: object  # gearcli.simulate.results.SteadyState
    period: CommonPeriod
    energy_from: int = 0  # first sample of the energy balance (a Newton correction is no motion: after it)


def scene_period(layout) -> CommonPeriod:
    """:func:`common_period` of the scene's excitations, or the unexcited scene's period (worked out once per
    layout: a run asks for it at every step of its way)."""
    cached = layout.__dict__.get("_scene_period")
    if cached is not None:
        return cached
    found = common_period(excitation_periods(layout))
    if found is None:
        found = CommonPeriod(unexcited_period(layout), "no excitation: the steady state is an equilibrium, checked "
                             "over the slowest mesh period", True, excited=False)
    object.__setattr__(layout, "_scene_period", found)  # the layout is frozen; its period is a function of it
    return found


def poincare_atol(layout, atol: np.ndarray, rtol: float, fastest_rad_s: float) -> np.ndarray:
    """Absolute tolerances of the dynamic states for the boundary comparison: the solver's, with each
    deflection's raised to what the speed tolerance allows it.

    The deflection of a stiff connector follows from the difference of two speeds, each held to rtol x
    its size: a deflection rate error of ``rtol (|r_a w_a| + |r_b w_b|)`` (the force-noise argument of
    :func:`gearcli.simulate.guards.force_noise`) moves the deflection by that over ``1 / w_max`` of a
    vibration (``w_max`` the fastest natural angular frequency). Below that the boundary states differ
    by integration noise, not by the dynamics: on a linear, damped, time-varying mesh the deflection
    residual stays at 10-300 x the solver's deflection atol while the speeds repeat to 0.01-1 x theirs.
    """
    out = np.array(atol[layout.state.mechanical], dtype=float)
    if fastest_rad_s <= 0:
        return out
    w = [b.ratio * layout.drive.speed_rad_s for b in layout.bodies]
    for c, x in enumerate(layout.connectors):
        rate = rtol * (abs(x.ra * w[x.a]) + abs(x.rb * w[x.b]))
        out[c] = max(out[c], rate / fastest_rad_s)
    return out


#: a motor's run-up lasts at least this many times its rigid drivetrain's start (to 98 % of the operating speed)
START_MARGIN = 1.25


def run_up_end(model, sim, from_rest: bool) -> float | None:
    """The ``window_start_s`` a run of the file's ``[simulation]`` ``sim`` takes: the file's, and where
    ``steady = "periodic"``, where its sampled run-up ends (:func:`run_up`): for a start from rest that no ramp bounds (no ramps, where the drive's and the load's steps
    at t = 0 ring on after them, or a motor, whose start lasts until it reaches its operating point) the fixed
    window's default start (docs/numerics.md), a motor's no earlier than :data:`START_MARGIN` times its rigid
    drivetrain's start (:mod:`gearcli.simulate.rigid_start`), so the start-up's samples give its peaks, its
    ``runup_factor``, ``summary.start`` and the motor's ``start_time_s`` as a window run's do; else None (the run-up
    ends with the ramps). A later end that leaves no whole period before ``duration_s`` is not taken."""
    spec, lay = model.spec, model.layout
    duration_s, window_start_s = sim.duration_s, sim.window_start_s
    ramps = max(spec.drive.ramps_end_s, spec.load.ramp_s)
    motor = spec.drive.kind == "motor"
    if sim.steady != "periodic" or window_start_s is not None or not from_rest or (ramps > 0 and not motor) \
            or ramps >= duration_s:
        return window_start_s
    from gearcli.simulate import stats  # lazy: a periodic run from rest only

    ends = [stats.steady_window(spec, duration_s, None)[0][0]]
    if motor:
        from gearcli.simulate import motor as motor_mod  # lazy: scipy.optimize, a motor's periodic run only
        from gearcli.simulate import rigid_start  # lazy: a motor's periodic run only

        rigid = rigid_start.integrate(lay, duration_s)
        started = motor_mod.start_time(rigid.time_s, rigid.speed_rad_s, motor_mod.operating_point(lay).speed_rad_s)
        ends = ([START_MARGIN * started] if started is not None else []) + ends
    T = scene_period(lay).period_s
    return max((e for e in ends if periods_cap(duration_s, max(e, ramps), T) >= 1), default=None)


def run_up(model, method: str, rtol: float, *, steps: int, duration_s: float, window_start_s: float | None,
           y0: np.ndarray | None, max_nfev: int, engine: str, samples: int | None = None):
    """The run from 0 to the end of the ramps (or ``window_start_s``), sampled as a window run would be (at
    most ``steps`` samples; ``samples``: that many); refused when not one excitation period fits between it and
    ``duration_s`` (the search may not run past the run's duration)."""
    lay = model.layout
    t_start = max(lay.drive.ramps_end_s, lay.load.ramp_s, window_start_s or 0.0)
    T = scene_period(lay).period_s
    if periods_cap(duration_s, t_start, T) == 0:
        raise ConfigError(f"steady = \"periodic\" needs at least one excitation period ({T:.4g} s) between the end "
                          f"of the ramps and window start ({t_start:.4g} s) and the end of the run "
                          f"({duration_s:.4g} s); set simulation.duration_s ≥ {t_start + T:.4g} (a few periods "
                          "more let the search find the repeat), or shorten the ramps", key="simulation.duration_s")
    n_a = min(steps, max(1, round(steps * t_start / duration_s))) if t_start > 0 else 0  # at most `steps` samples
    n_a = n_a if samples is None or t_start <= 0 else max(1, samples)
    return integrate(model, np.linspace(0.0, t_start, n_a + 1), method, rtol, y0=y0, max_nfev=max_nfev,
                     engine=engine)


def statistics_grid(layout, period_s: float, k: int, steps: int) -> int:
    """Samples over the k statistics periods: ``steps`` per k periods, at least
    :data:`MIN_SAMPLES_PER_FASTEST` per period of the fastest excitation, within the memory bound."""
    per = max(math.ceil(steps / k), math.ceil(MIN_SAMPLES_PER_FASTEST * period_s / _fastest(layout, period_s)))
    return min(per * k, max(steps, PERIODIC_STATISTICS_SAMPLES))  # the memory bound config.bounds checked


def search(model, method: str, rtol: float, parts: list, t_start: float, y_start: np.ndarray, period: CommonPeriod,
           atol: np.ndarray, *, steps: int, cap: int, max_nfev: int, used: int, engine: str,
           periods_before: int = 0, shooting=None, cap_total: int | None = None):
    """The brute-force search from ``(t_start, y_start)``: period by period until the state repeats (at most
    ``cap`` periods), then the statistics periods. ``parts[0]`` is the run-up (its samples lead the result's);
    ``periods_before`` periods were integrated before (by the shooting, whose summary ``shooting`` the
    result's steady state carries on; ``cap_total`` the cap reported, that of the whole run)."""
    lay = model.layout
    T = period.period_s
    dyn = lay.state.n_mechanical
    turn = _input_turn(lay, period)
    states, times = [y_start], [t_start]
    base = (t_start, 0)  # boundaries t0 + (n - n0) T since the period was last re-timed
    repeat, chunk, exhausted = Repeat(0, math.inf), FIRST_CHUNK, False
    while len(states) - 1 < cap and repeat.k == 0 and not exhausted:
        n = len(states) - 1
        m = min(chunk, cap - n)
        t_n = times[-1]
        r = integrate(model, base[0] + T * np.arange(n - base[1], n - base[1] + m + 1), method, rtol, y0=states[-1],
                      t0=t_n, max_nfev=max(1, max_nfev - used), engine=engine)
        used += r.nfev
        parts.append(r)
        if r.status == STATUS_BUDGET:
            exhausted = True
        elif r.status != STATUS_FINISHED:
            return _joined(parts, r.t[:1], r.y[:, :1], status_from=r)
        for j in range(1, m + 1):
            if not np.all(np.isfinite(r.y[:, j])):
                break
            states.append(r.y[:, j])
            times.append(float(r.t[j]))
            repeat = detect_period([s[:dyn] for s in states[-history_needed():]], rtol, atol)
            if repeat.k:
                break
        if turn is not None and len(states) >= 2:  # the period the input's mean speed over the last one gives
            i, advance = turn
            gone = float(states[-1][i] - states[-2][i])
            if gone > 0.0 and abs(advance / gone - 1.0) < RETIME_LIMIT:
                T, base = T * advance / gone, (times[-1], len(states) - 1)
        chunk = min(2 * chunk, LAST_CHUNK)
    n = len(states) - 1
    k = repeat.k or MAX_SUBHARMONIC
    k = min(k, n) if n > 0 else 1
    t_n = times[n - k] if n >= k else times[-1]
    y_n = states[n - k] if n >= k else states[-1]
    if T != period.period_s:
        period = replace(period, period_s=T, source=f"{period.source}, at the motion's mean input speed "
                         f"({period.period_s / T - 1.0:+.3g} relative to the operating point's)")
    total = statistics_grid(lay, T, k, steps)
    fine = t_n + k * T * np.arange(total + 1) / total
    stats_run = integrate(model, fine, method, rtol, y0=y_n, t0=t_n, engine=engine)
    parts.append(stats_run)
    if stats_run.status != STATUS_FINISHED:
        return _joined(parts, stats_run.t[:1], stats_run.y[:, :1], status_from=stats_run)
    first = parts[0]
    joined = _joined(parts, np.concatenate([first.t, fine]), np.hstack([first.y, stats_run.y]))
    steady = _steady(period, repeat, n, k, total // k, exhausted, cap if cap_total is None else cap_total,
                     periods_before, shooting)
    return PeriodicRun(joined, (float(fine[0]), float(fine[-1])), (float(fine[0]), float(fine[-2])), steady, period)


#: a re-timed period stays within this fraction of the operating point's (a start still far from it is not timed)
RETIME_LIMIT = 0.05


def _input_turn(layout, period: CommonPeriod) -> tuple[int, float] | None:
    """``(i, advance)`` where the period follows the motion's own input speed, else None.

    Without a prescribed speed (a torque drive, a motor) every excitation but a load fluctuation is a
    function of the input angle (a mesh phase, a torque ripple), so the motion repeats over the input's angle
    ``advance`` = the operating speed x the common period, and its period is that angle over the motion's mean
    input speed, which the fluctuations and the mesh losses move off the rigid operating point: a spur mesh
    with a 2 um transmission error and a 10 % torque ripple of order 2 (torque drive, quadratic load) runs at
    1499.8615 rpm, not 1500, and its state, compared 0.04 s apart, never repeated (9.2e-5 short a period, the
    mesh phase drifts). ``i`` is the input angle's state. None with a speed drive, a load fluctuation (a time
    clock of its own), no angle state or no common period."""
    st = layout.state
    if layout.speed_drive or st.i_theta is None or not period.exact or not period.excited:
        return None
    fluct = np.array(layout.fluctuation, float).reshape(-1, 2)
    if np.any((fluct[:, 0] != 0.0) & (fluct[:, 1] != 0.0)):
        return None
    w_in = steady_input_speed_rad_s(layout)
    return (st.i_theta, abs(w_in) * period.period_s) if w_in != 0.0 else None


def _fastest(layout, T: float) -> float:
    found = excitation_periods(layout)
    return min((e.period_s for e in found), default=T)


def periods_cap(duration_s: float, t_start: float, period_s: float) -> int:
    """Periods the search may integrate past ``t_start``: as many as end by ``duration_s``, at most
    :data:`MAX_PERIODS` (so ``simulation.duration_s`` bounds the cost, as in a window run)."""
    fit = math.floor((duration_s - t_start) / period_s * (1.0 + 1e-12)) if duration_s > t_start else 0
    return max(0, min(MAX_PERIODS, fit))


def _steady(period: CommonPeriod, repeat: Repeat, n: int, k: int, per: int, exhausted: bool, cap: int,
            periods_before: int = 0, shooting=None, cap_total: int | None = None):
    kind = "none" if repeat.k == 0 else f"period-{repeat.k}"
    source = period.source + ("" if not exhausted else "; the search stopped at the run's evaluation budget")
    extra = {} if shooting is None else {"iterations": shooting.iterations, "note": "; ".join(shooting.notes),
                                         "attempts": shooting.attempts,
                                         "monodromy": shooting.monodromy if shooting.attempts else None}
    # every period integrated past the ramps: the search's n, the k statistics periods integrated again from
    # their boundary state, and the shooting's before a fallback
    return SteadyState(mode="periodic", period_s=period.period_s, periods_to_converge=n + k + periods_before,
                       periodicity=kind, converged=repeat.k > 0,
                       residual=float(repeat.residual) if math.isfinite(repeat.residual) else None,
                       period_source=source, window_periods=k, samples_per_period=per, cap_periods=cap,
                       method="brute force", **extra)


def _joined(parts, t: np.ndarray, y: np.ndarray, status_from=None):
    """One Integration with the samples ``(t, y)`` and the counters of all ``parts``."""
    last = status_from or parts[-1]
    return replace(parts[0], t=t, y=y, nfev=sum(p.nfev for p in parts), njev=sum(p.njev for p in parts),
                   nlu=sum(p.nlu for p in parts), steps=sum(p.steps for p in parts),
                   wall_s=sum(p.wall_s for p in parts), status=last.status, message=last.message,
                   t_fail=last.t_fail)
