"""Is the statistics window settled? A test on the window's own mesh forces, and the run extended until it is.

Every dynamic verdict (the life route's spectra, the simulated K_v, a sweep row, the report's comparison) takes
the window's max |F_t| or its cycle peaks, which a run-up transient inflates long after the ramps: a DOL start
leaves the drivetrain's slow modes ringing, and the window's first periods carry them. The window is shown to
be settled when no decaying oscillation is left in it. Two tests, both must pass: (model-free) the max |F_t|
of the window's first quarter must not exceed its last half's by more than :data:`SETTLED_FRACTION` of the
static force; (modal) the window's F_t of every stage is fitted by least squares with a constant plus the free decay of the oscillating modes of the linearised chain (the slowest
decaying first, their decay rates refined to the record's envelope: :func:`gearcli.simulate.ringing.fit_transient`)
and the fitted amplitude at the window's start must stay below :data:`SETTLED_FRACTION` of the stage's static
force; (drift) a window shorter than half a period of a mode that has not decayed since t = 0, which the fit
cannot see, is unsettled when a stage's F_t drifts across it by more than that fraction. A motor whose start
reaches 98 % of its operating speed only after the window starts is unsettled too.

An unsettled window names the time from which it would be settled (the largest transient decayed to the
fraction: ``t0 + ln(a0 / (f F)) / sigma``; a motor that has not reached its operating speed within the run:
the run's end). :func:`settled_run` repeats the run with its window from there
(the window's length kept, the samples scaled with it), at most :data:`MAX_RUNS` times and within
:data:`MAX_DURATION_FACTOR` times the first run's duration; where that budget cannot settle it, the periodic
steady state is sought (shooting where it applies, within the same duration) and taken when it converges; a
window still unsettled then is reported (``steady.settled = false`` and the ``window_not_settled`` warning),
never silently taken for steady. The warning carries the fitted transients' share of that stage's window mean
(``mean_bias_N``, :func:`gearcli.simulate.ringing.window_mean`) and names the mean where it exceeds ``MEAN_TARGET``.

A periodic steady state (``steady = "periodic"``) is settled when it converged.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace
from typing import TYPE_CHECKING, TypeGuard

import numpy as np

from gearcli import diagnostics as dg
from gearcli.core.records import record
from gearcli.core.text import rounded_up
from gearcli.diagnostics import Diagnostic
from gearcli.errors import GearcliError
from gearcli.model.damping import decay_rate
from gearcli.simulate import leftover as leftover_mod
from gearcli.simulate import ringing, sampling
from gearcli.simulate.estimate import MEAN_TARGET
from gearcli.simulate.results import SimulationExtra, SimulationResult, SteadyState

if TYPE_CHECKING:
    from gearcli.model import TorsionalModel
    from gearcli.simulate.choice import Choice

SETTLED_FRACTION = 0.01  # transient amplitude at the window's start, of the stage's static force (1 % of K_v)
DECAYED = 12.0  # decay exponent since t = 0 past which a mode is taken as settled (e^-12 = 6e-6)
MAX_MODES = 6  # the slowest-decaying oscillating modes fitted at once
MAX_RUNS = 3  # runs after the first one, each with a later window
MAX_DURATION_FACTOR = 8.0  # the longest run, in units of the first run's duration
MAX_DURATION_S = 600.0
GROWTH_SEGMENTS = 8  # equal parts of the window whose oscillations must grow one after the other (_growth)
GROWTH_FACTOR = 2.0  # the last part's peak to peak over the first's
SEEN_DECAY = 0.2  # a rigid mode decaying by less than e^-0.2 over the window: its amplitude and the operating point
# cannot be told apart by a fit (_speed_approach)
NEUTRAL = 1e-6  # a mode decaying by less than this per period is undamped (e-fold after a million periods)


@record
class Settling:
    """The settle test of one window: ``settled``, the largest transient at the window's start (fraction of the
    static force, its stage and mode frequency), and the time from which the window would be settled (None:
    settled, or no estimate)."""

    settled: bool
    transient_fraction: float
    stage: int | None = None
    frequency_Hz: float | None = None
    settle_time_s: float | None = None
    cause: str = ""
    growing: bool = False  # the oscillation grows through the window (_growth), not a decaying transient
    # the fitted start-up transients' share of the stage's window-mean F_t, relative to its reference force
    # (ringing.window_mean, every mode fitted summed): the mean is named where it exceeds MEAN_TARGET
    mean_bias: float = 0.0
    mean_bias_N: float = 0.0
    # the other stages whose window mean the fitted transients move beyond MEAN_TARGET: (stage, N, relative)
    other_means: tuple[tuple[int, float, float], ...] = ()
    # every fitted stage's transient left in the window, settled or not (gearcli.simulate.leftover)
    leftover: tuple[leftover_mod.Leftover, ...] = ()


def candidate_modes(eigenvalues: np.ndarray, window_s: tuple[float, float],
                    dt_s: float = 0.0) -> list[tuple[float, float]]:
    """(sigma, omega_d) of the oscillating modes the window can see (more than half a period in it, and told
    apart by its samples ``dt_s`` apart: :func:`gearcli.simulate.ringing.fittable`) and that can still carry the
    start (not decayed by e^-DECAYED since t = 0), slowest decay first, at most MAX_MODES."""
    length = window_s[1] - window_s[0]
    lam = np.asarray(eigenvalues, dtype=complex)
    out = [(decay_rate(z), float(z.imag)) for z in lam if z.imag > 0.0 and z.imag * length > math.pi]
    # a mode that has decayed by e^-DECAYED since the run began cannot carry its start-up into the window
    out = [(s, w) for s, w in out if s * window_s[0] < DECAYED]
    return ringing.fittable(out, length, dt_s)[:MAX_MODES]  # the modes the window's samples can tell apart


def check(t: np.ndarray, mask: np.ndarray, forces_N: list[np.ndarray], static_N: list[float],
          eigenvalues: np.ndarray, window_s: tuple[float, float],
          motor_start_s: float | None = None, motor_reaches: bool = True,
          floors_N: list[float] | None = None, forced: tuple[float, ...] = (),
          speed_rad_s: np.ndarray | None = None) -> Settling:
    """The settle test of the window ``mask`` of the samples ``t`` (module text). ``motor_start_s``: when the
    motor reached 98 % of its operating speed (None with ``motor_reaches``: never within the run). ``floors_N``: per
    stage the least force an unloaded stage's transient is measured against (:func:`estimate.force_floors_N`).
    ``speed_rad_s``: the input shaft's speed, where it is free (:func:`_speed_approach`)."""
    if motor_reaches and motor_start_s is None:
        return Settling(False, math.inf, cause="the motor start does not reach its operating speed within the run")
    tw = t[mask]
    modes = candidate_modes(eigenvalues, window_s, (tw[-1] - tw[0]) / (tw.size - 1) if tw.size > 1 else 0.0)
    worst = Settling(True, 0.0)
    floors = floors_N or [0.0] * len(static_N)
    refs = [abs(float(ref)) or max(float(np.mean(np.abs(ft[mask]))), floor)
            for ft, ref, floor in zip(forces_N, static_N, floors, strict=True)]
    fitted = [k for k, ref in enumerate(refs) if ref > 0.0] if modes else []
    # every stage's fit at once (independent per stage: the same numbers as one fit per stage, one batched solve)
    terms, sigs, omegas = ringing.fit_transient_terms(tw, np.column_stack([forces_N[k][mask] for k in fitted]), modes,
                                                      forced=forced) if fitted else \
        (np.empty((0, 0)), np.empty((0, 0)), np.array([m[1] for m in modes]))
    modes = [(m[0], float(w)) for m, w in zip(modes, omegas, strict=True)]  # the frequencies the record rings at
    length = window_s[1] - window_s[0]
    biases: dict[int, tuple[float, float]] = {}  # stage (1-based): the fitted transients' share of its mean, its ref
    left = []
    for i, k in enumerate(fitted):
        ref = refs[k]
        amplitudes, sigmas = [float(abs(a)) for a in terms[i]], [float(x) for x in sigs[i]]
        bias = sum(ringing.window_mean(complex(c), sg, m[1], length) for c, sg, m in zip(terms[i], sigmas, modes,
                                                                                         strict=True))
        left.append(leftover_mod.of_fit(k + 1, tw, terms[i], sigmas, [m[1] for m in modes], ref, mean_N=bias))
        biases[k + 1] = (bias, ref)
        for j, a0 in enumerate(amplitudes):
            fraction = a0 / ref
            if fraction <= worst.transient_fraction:
                continue
            sigma, omega = sigmas[j], modes[j][1]
            settle = window_s[0] + math.log(fraction / SETTLED_FRACTION) / sigma \
                if sigma > 0 and fraction > SETTLED_FRACTION else None
            worst = Settling(fraction < SETTLED_FRACTION, fraction, k + 1, omega / (2 * math.pi), settle,
                             "" if fraction < SETTLED_FRACTION else
                             f"the {omega / (2 * math.pi):.3g} Hz mode rings from the start with ±{a0:.4g} N in stage "
                             f"{k + 1}'s F_t at the window's start ({100 * fraction:.2g} % of "
                             f"{ringing.reference_words(ref, float(static_N[k]) != 0.0)})")
    worst = _envelope(tw, [np.abs(ft[mask]) for ft in forces_N], static_N, worst, floors)
    # a growth is tested after an unsettled fit too: the fit's modes only decay, so an oscillation that grows
    # exponentially (a parametric instability) reads to it as a huge transient with a settle time; one that grows
    # by the factor within the window's last half alone is no decaying transient, and the growth is the verdict
    grown = _growth([ft[mask] for ft in forces_N], refs, static_N, worst, late=not worst.settled)
    worst = grown if grown.growing else worst
    if worst.settled:
        worst = _unseen_drift(tw, [ft[mask] for ft in forces_N], refs, static_N, eigenvalues, window_s, worst)
    if worst.settled and speed_rad_s is not None:
        worst = _speed_approach(tw, speed_rad_s[mask], eigenvalues, window_s, worst)
    if motor_start_s is not None and motor_start_s > window_s[0]:
        settle = max(motor_start_s, worst.settle_time_s or 0.0)
        worst = Settling(False, worst.transient_fraction, worst.stage, worst.frequency_Hz, settle,
                         f"the motor reaches 98 % of its operating speed at {motor_start_s:.4g} s, after the window "
                         f"starts ({window_s[0]:.4g} s)")
    return replace(_with_means(worst, biases), leftover=tuple(left))


def _with_means(settling: Settling, biases: dict[int, tuple[float, float]]) -> Settling:
    """An unsettled window's ``settling`` with the fitted transients' share of its stage's window mean and the other
    stages' shares beyond MEAN_TARGET (``biases``: stage -> (share in N, reference force))."""
    if settling.settled:
        return settling
    own, ref = biases.get(settling.stage or 0, (0.0, 0.0))
    others = tuple((k, b, b / r) for k, (b, r) in biases.items() if k != settling.stage and abs(b) > MEAN_TARGET * r)
    return replace(settling, mean_bias=own / ref if ref > 0.0 else 0.0, mean_bias_N=own, other_means=others)


def _unseen_drift(t: np.ndarray, forces: list[np.ndarray], refs: list[float], static_N: list[float],
                  eigenvalues: np.ndarray, window_s: tuple[float, float], worst: Settling) -> Settling:
    """A window shorter than half a period of an oscillating mode that has not decayed since t = 0 cannot show that
    mode's transient as ringing (the fit leaves such a mode out): it shows it as a drift. Unsettled when a stage's
    F_t drifts across the window (its least-squares line changes) by more than SETTLED_FRACTION of its reference
    force: no settle time is estimated (the window must first hold half a period of the mode)."""
    length = window_s[1] - window_s[0]
    lam = np.asarray(eigenvalues, dtype=complex)
    unseen = [(decay_rate(z), float(z.imag)) for z in lam
              if z.imag > 0.0 and z.imag * length <= math.pi and decay_rate(z) * window_s[0] < DECAYED]
    if not unseen or t.size < 2 or length <= 0.0:
        return worst
    sigma, omega = min(unseen, key=lambda m: m[1])  # the slowest: the one the window sees least of
    for k, (f, ref, static) in enumerate(zip(forces, refs, static_N, strict=True)):
        if ref <= 0.0:
            continue
        drift = abs(float(np.polyfit(t - t[0], f, 1)[0])) * length
        if drift / ref > max(SETTLED_FRACTION, worst.transient_fraction):
            period = 2 * math.pi / omega
            worst = Settling(False, drift / ref, k + 1, omega / (2 * math.pi), None,
                             f"the window ({length:.3g} s) is shorter than half a period ({period / 2:.3g} s) of the "
                             f"{omega / (2 * math.pi):.3g} Hz mode, which has not decayed since the start, and stage "
                             f"{k + 1}'s F_t drifts across it by {drift:.4g} N ({100 * drift / ref:.2g} % of "
                             f"{ringing.reference_words(ref, float(static) != 0.0)}): it cannot be told from that mode's start-up "
                             f"transient; lengthen simulation.duration_s (the window needs ≥ {period / 2:.3g} s, "
                             "and the mode time to decay)")
    return worst


def _speed_approach(t: np.ndarray, w: np.ndarray, eigenvalues: np.ndarray, window_s: tuple[float, float],
                    worst: Settling) -> Settling:
    """The free train's approach to its operating speed: a real eigenvalue -sigma of the linearised chain (the
    rigid-body mode a speed-dependent load or a motor's slip damps, tau = J_eff / (dT/dw)) carries no force the
    mesh tests see (a torque drive's mesh carries its torque whatever the speed), but every speed of the window
    creeps towards the operating point. For the slowest such mode not decayed since t = 0 that decays by at least
    :data:`SEEN_DECAY` within the window, the input speed is fitted by least squares with a constant plus its free
    decay, ``w_op + b e^(-sigma (t - t0))``: unsettled when |b| exceeds SETTLED_FRACTION of w_op, settled from
    ``t0 + ln(|b| / (f w_op)) / sigma``. A slower one cannot be told from the operating point within the window:
    unsettled only when the speed drifts across the window (its least-squares line) by more than that fraction of its
    mean, with no settle time. So is a neutral mode, an eigenvalue at the eigensolver's noise (:data:`NEUTRAL`: a
    balanced torque drive's speed, a free train's angle), which has no time constant to state and no decay to fit:
    taken for one, a numerical -4e-10 was printed as a 2.4e9 s mode, and it hid the 0.45 s mode the fit explains."""
    length = window_s[1] - window_s[0]
    lam = np.asarray(eigenvalues, dtype=complex)
    real = sorted(-float(z.real) for z in lam if z.imag == 0.0 and z.real < 0.0 and -z.real * window_s[0] < DECAYED)
    if not real or t.size < 4 or length <= 0.0:
        return worst
    noise = NEUTRAL * float(np.max(np.abs(lam)))
    physical = [x for x in real if x > noise]
    neutral = len(physical) < len(real)
    seen = [x for x in physical if x * length >= SEEN_DECAY]
    if len(seen) < len(physical) or not seen:  # a slower mode (or only neutral ones): the drift across the window
        slow = f"time constant {1.0 / physical[0]:.3g} s, longer than the window" if len(seen) < len(physical) \
            else "neutral: no torque restores its speed"
        drifting = _drift(t, w, length, slow)
        if drifting is not None:
            return drifting
        if not seen:
            return worst
    sigma = seen[0]
    (w_op, b), *_ = np.linalg.lstsq(np.column_stack([np.ones_like(t), np.exp(-sigma * (t - t[0]))]), w, rcond=None)
    fraction = abs(float(b)) / abs(float(w_op)) if w_op != 0.0 else 0.0
    if fraction <= SETTLED_FRACTION:
        drifting = _drift(t, w, length, "neutral: no torque restores its speed") if neutral else None
        return worst if drifting is None else drifting
    rpm = 30.0 / math.pi
    return Settling(False, fraction, None, None, float(t[0]) + math.log(fraction / SETTLED_FRACTION) / sigma,
                    f"the input speed still approaches its operating point, about {float(w_op) * rpm:.4g} rpm: the "
                    f"train's rigid-body mode (time constant {1.0 / sigma:.3g} s, from the load's and drive's dT/dw) "
                    f"carries {float(b) * rpm:+.4g} rpm at the window's start ({100 * fraction:.2g} % of it), so the "
                    "window's speeds and their means are not the operating point's")


#: an eigenvalue within this share of the largest |eigenvalue| is the eigensolver's zero (a neutral mode): its
#: absolute error is ~1e-16 of the largest, and a physical rigid mode this slow (tau > 1e10 / max|lambda|, days for a
#: drivetrain) cannot be told from a neutral one within any window
NEUTRAL = 1e-10


def _drift(t: np.ndarray, w: np.ndarray, length: float, mode: str) -> Settling | None:
    """Unsettled when the speed drifts across the window (its least-squares line) by more than SETTLED_FRACTION of its
    mean, the slow or neutral rigid-body ``mode`` named; else None."""
    mean, rpm = float(np.mean(w)), 30.0 / math.pi
    drift = abs(float(np.polyfit(t - t[0], w, 1)[0])) * length
    if mean == 0.0 or drift / abs(mean) <= SETTLED_FRACTION:
        return None
    return Settling(False, drift / abs(mean), None, None, None,
                    f"the input speed drifts across the window by {drift * rpm:.4g} rpm ({100 * drift / abs(mean):.2g} "
                    f"% of its mean): the train's rigid-body mode ({mode}) has not brought it to its operating point; "
                    "lengthen simulation.duration_s")


def _growth(forces: list[np.ndarray], refs: list[float], static_N: list[float], worst: Settling,
            late: bool = False) -> Settling:
    """The growing half of the model-free test: a stage's F_t oscillation (peak to peak in each of
    :data:`GROWTH_SEGMENTS` equal parts of the window, each holding at least two cycles about its own mean) that grows
    from part to part, by more than :data:`GROWTH_FACTOR` over the window and to more than SETTLED_FRACTION of the
    reference force, is no steady state: a build-up still under way, or an instability (a parametric resonance of
    the stiffness harmonics: the response grows without bound on a linear mesh). No settle time is estimated.
    ``late``: the growth must also reach the factor within the window's last half alone (where the transient fit
    has found the window unsettled: a build-up it fits as a decaying transient slows down there, an exponential
    growth does not)."""
    for k, (f, ref, static) in enumerate(zip(forces, refs, static_N, strict=True)):
        if ref <= 0.0 or f.size < 8 * GROWTH_SEGMENTS:
            continue
        parts = np.array_split(f, GROWTH_SEGMENTS)
        if any(np.count_nonzero(np.diff(np.sign(p - np.mean(p)))) < 4 for p in parts):
            continue  # not an oscillation the parts resolve (a slow swing, a drift: _unseen_drift's)
        ptp = np.array([float(np.ptp(p)) for p in parts])
        if not (np.all(np.diff(ptp) > 0.0) and ptp[-1] > GROWTH_FACTOR * ptp[0] and ptp[-1] > SETTLED_FRACTION * ref):
            continue
        if late and not ptp[-1] > GROWTH_FACTOR * ptp[GROWTH_SEGMENTS // 2]:
            continue
        return Settling(False, float(ptp[-1] / ref), k + 1, worst.frequency_Hz, None, growing=True, cause=
                        f"stage {k + 1}'s F_t oscillation grows through the window, from ±{ptp[0] / 2:.4g} N in its "
                        f"first {GROWTH_SEGMENTS}th to ±{ptp[-1] / 2:.4g} N in its last ({ptp[-1] / ptp[0]:.3g}x, "
                        f"{100 * ptp[-1] / ref:.3g} % of {ringing.reference_words(ref, float(static) != 0.0)}): a build-up still under "
                        "way or an instability (a parametric resonance of the mesh stiffness harmonics grows without "
                        "bound on a linear mesh), no steady state")
    return worst


def _envelope(t: np.ndarray, forces: list[np.ndarray], static_N: list[float], worst: Settling,
              floors_N: list[float]) -> Settling:
    """The model-free half of the test: a transient that decays through the window raises its first quarter's
    max |F_t| above its last half's (the steady part, which holds every steady peak the first quarter holds); by
    more than SETTLED_FRACTION of the static force, the window is settled from the sample after the last one above
    that level (the fit's settle time where it gives a later one)."""
    if t.size < 8:
        return worst
    quarter, half = t <= t[0] + 0.25 * (t[-1] - t[0]), t >= t[0] + 0.5 * (t[-1] - t[0])
    for k, (f, static, floor) in enumerate(zip(forces, static_N, floors_N, strict=True)):
        ref = abs(float(static)) or max(float(np.mean(f)), floor)
        if ref <= 0.0:
            continue
        steady_max = float(np.max(f[half]))
        excess = (float(np.max(f[quarter])) - steady_max) / ref
        if excess <= SETTLED_FRACTION or excess <= worst.transient_fraction and not worst.settled:
            continue
        above = np.nonzero(f > steady_max + SETTLED_FRACTION * ref)[0]
        # settled from the sample after the last one above the level: a window starting at that sample itself
        # would still hold it, and the test would name the same start again
        settle = float(t[min(above[-1] + 1, t.size - 1)]) if above.size else None
        if worst.settle_time_s is not None and (settle is None or worst.settle_time_s > settle):
            settle = worst.settle_time_s
        worst = Settling(False, max(excess, worst.transient_fraction), k + 1, worst.frequency_Hz, settle,
                         f"stage {k + 1}'s max |F_t| in the window's first quarter exceeds its last half's by "
                         f"{100 * excess:.2g} % of {ringing.reference_words(ref, float(static) != 0.0)}: a start-up "
                         "transient decays through it")
    return worst


def next_window(settling: Settling, window_s: tuple[float, float], first_duration_s: float) -> tuple[float, float] | None:
    """(window start, duration) of the next run: the window from the settle time on, its length kept; None when
    there is no estimate or the run would exceed the budget."""
    if settling.settled:
        return None
    length = window_s[1] - window_s[0]
    if settling.settle_time_s is None and math.isinf(settling.transient_fraction):
        # a motor start that has not reached its operating speed within the run (:func:`check`): it is not
        # settled before the run's end, so the next window starts there (no estimate of how much later)
        settle = window_s[1]
    elif settling.settle_time_s is None or not math.isfinite(settling.settle_time_s):
        return None
    else:
        settle = settling.settle_time_s
    start = max(settle, window_s[0] + 0.25 * length)  # progress, however small the estimate
    duration = start + length
    if duration > min(MAX_DURATION_S, MAX_DURATION_FACTOR * first_duration_s):
        return None
    return start, duration


def message(settling: Settling, window_s: tuple[float, float], runs: int) -> str:
    """The ``window_not_settled`` warning."""
    tried = f" after {runs} longer run{'s' if runs > 1 else ''}" if runs else ""
    when = (f"; it would be settled from about {rounded_up(settling.settle_time_s, 4):g} s (simulation.window_start_s, "
            "simulation.duration_s beyond it)" if settling.settle_time_s is not None
            and math.isfinite(settling.settle_time_s) else "")
    if settling.growing:
        return (f"the statistics window {window_s[0]:.4g}–{window_s[1]:.4g} s is not settled{tried}: {settling.cause}; "
                "its statistics, dynamic factor and load peaks grow with the window (more mesh damping, or stiffness "
                "harmonics below the parametric-resonance threshold, bound it)")
    mean = (f"mean (the fitted transients move it by {settling.mean_bias_N:+.4g} N, {settling.mean_bias:+.2g} of the "
            f"reference, beyond the mean's target {MEAN_TARGET:g}), " if abs(settling.mean_bias) > MEAN_TARGET else "")
    others = (" (and the window mean " + " and ".join(f"of stage {k} by {b:+.4g} N ({rel:+.2g})"
                                                      for k, b, rel in settling.other_means) + ")"
              if settling.other_means else "")
    return (f"the statistics window {window_s[0]:.4g}–{window_s[1]:.4g} s is not settled{tried}: {settling.cause}"
            f"{when}; its {mean}max |F_t|, dynamic factor and load peaks{others} include the start-up transient "
            "(or [simulation] steady = \"periodic\")")


def settled_steady(model: TorsionalModel, choice: Choice, t: np.ndarray, mask: np.ndarray, window, per_stage,
                   stages, steady: SteadyState, motor_summary, diags: list[Diagnostic],
                   floors_N: list[float] | None = None, speeds_rad_s: np.ndarray | None = None,
                   ) -> tuple[SteadyState, tuple]:
    """``steady`` with the settle test of the window (:mod:`gearcli.simulate.settle`; a periodic state: settled
    when it converged); an unsettled fixed window adds the ``window_not_settled`` warning to ``diags`` unless the
    ringing or the motor's start, stall or runaway warning already says so. ``speeds_rad_s``: the input shaft's
    speed at the samples (a free one's approach to its operating point is tested too). With it, ``stages`` whose
    error estimates add the transient the fit leaves in a settled window (:mod:`gearcli.simulate.leftover`; as they
    were for a periodic state and an unsettled window, whose warning says its statistics carry the transient); where
    it exceeds the statistics' target, its ``statistics_unresolved`` warnings are added to ``diags``."""
    if steady.mode == "periodic":
        attracting = reached(steady)
        if steady.converged and not attracting:
            diags.append(not_attracting(steady))
        return replace(steady, settled=attracting), tuple(stages)
    motor_start, reaches = None, False
    if motor_summary is not None and model.layout.motor_drive:
        motor_start = motor_summary.get("start_time_s")
        reaches = not any(d.code == dg.MOTOR_STALLS for d in diags)
    # the eigenvalues with every damping the run integrates (a motor's slip damping, the load law's dT/dw), as the
    # ringing fit and `modes` take them: the connectors' damping alone leaves a motor-damped mode undamped
    free = None if model.layout.speed_drive else speeds_rad_s
    found = check(t, mask, [p[0] for p in per_stage],
                         [st.simulated_static_tangential_N or 0.0 for st in stages],
                         choice.run_eigenvalues, window, motor_start, reaches, floors_N,
                         ringing.forced_rad_s(model.layout), free)
    # a stalled or runaway motor's warning says the run is no operating point: no later window would settle it
    said = (dg.WINDOW_RINGING, dg.START_NOT_SETTLED, dg.MOTOR_STALLS, dg.MOTOR_RUNS_AWAY)
    if found.settled:  # an unsettled window's warning says its statistics carry the transient
        diags += leftover_mod.warnings(found.leftover, stages, window)
    if not found.settled and not any(d.code in said for d in diags):
        diags.append(dg.warning(dg.WINDOW_NOT_SETTLED, message(found, window, steady.settle_runs),
                                transient_fraction=found.transient_fraction if math.isfinite(found.transient_fraction)
                                else None, stage=found.stage, mode_frequency_Hz=found.frequency_Hz,
                                settle_time_s=found.settle_time_s, mean_bias_N=found.mean_bias_N,
                                other_stages_mean_bias_N=[{"stage": k, "mean_bias_N": b} for k, b, _ in found.other_means]))
    fraction = found.transient_fraction if math.isfinite(found.transient_fraction) else None
    return replace(steady, settled=found.settled, transient_fraction=fraction,
                   settle_time_s=found.settle_time_s), \
        leftover_mod.with_errors(stages, found.leftover if found.settled else ())  # unsettled: its warning says so


def reached(steady: SteadyState | None) -> TypeGuard[SteadyState]:
    """Whether a periodic steady state is one the motion settles into: converged, and (found by Newton: the
    shooting, the equilibrium) contracting, its spectral radius below 1 - :data:`NEUTRAL` per period. An orbit or
    equilibrium whose multipliers lie on the unit circle (an undamped mode: configs/extreme/zero_damping.toml) is
    a fixed point of the map that the start-up's vibration circles for ever, not the motion's steady state."""
    if steady is None or not steady.converged:
        return False
    return steady.spectral_radius is None or steady.spectral_radius <= 1.0 - NEUTRAL


def not_attracting(steady: SteadyState) -> Diagnostic:
    """The warning of a converged periodic state (an orbit, an equilibrium) that does not contract (:func:`reached`):
    its statistics are the state's, never those of the motion from rest."""
    what = "equilibrium" if steady.method == "equilibrium" else "periodic orbit"
    rho = steady.spectral_radius if steady.spectral_radius is not None else math.nan
    why = ("a mode without damping: its start-up vibration never decays" if rho <= 1.0 + NEUTRAL
           else "a growing mode: the motion leaves the state")
    return dg.warning(dg.PERIODIC_NOT_ATTRACTING,
                      f'steady = "periodic": the {what} found is not one the motion settles into: a Floquet '
                      f"multiplier of modulus {rho:.9g} per period ({why}), so the statistics and K_v are the "
                      f"{what}'s, not those of the motion from rest ([simulation] steady = \"window\" shows that; "
                      "mesh damping, contact.damping_Ns_mm or contact.damping_ratio, makes the state a steady one)",
                      spectral_radius=steady.spectral_radius)


def longest_run_s(duration_s: float) -> float:
    """The settle test's budget: the longest run, in simulated seconds, for a first run of ``duration_s``."""
    return min(MAX_DURATION_S, MAX_DURATION_FACTOR * duration_s)


def periodic_state(run: Callable[..., SimulationResult], duration_s: float, steps: int, settle_runs: int,
                   window_start_s: float | None = None, **kwargs) -> SimulationResult | None:
    """The periodic steady state (``run(..., steady="periodic")``: the equilibrium, shooting, or period by period)
    within the budget's duration (:func:`longest_run_s`), marked settled after ``settle_runs`` runs; None where
    the search cannot run the scene, does not converge, or the motion does not settle into it (:func:`reached`).
    A search that would start at or past the budget's end (a first run longer than :data:`MAX_DURATION_S`) cannot
    run: None, and the caller keeps its window."""
    longest = longest_run_s(duration_s)
    if window_start_s is not None and window_start_s >= longest:
        return None
    try:
        found = run(longest, steps, window_start_s, steady="periodic", **kwargs)
    except GearcliError:  # the periodic search cannot run this scene
        return None
    if not reached(found.steady):
        return None
    if found.steady.settled is True and found.steady.settle_runs == settle_runs:  # marked so already: as it is
        return found
    return replace(found, steady=replace(found.steady, settled=True, settle_runs=settle_runs))


def settled_run(result: SimulationResult, run: Callable[..., SimulationResult],
                duration_s: float, steps: int, periodic: bool = True,
                finish: Callable[[SimulationResult], SimulationResult] = lambda r: r) -> SimulationResult:
    """``result`` or, while its fixed window is not settled, the run repeated by ``run(duration, steps, window
    start)`` with the window from the settle time on (:func:`next_window`: its length kept, the output samples
    scaled with the duration, within the budget). Where the budget cannot settle it, the periodic steady state
    (:func:`periodic_state`; not with ``periodic = False``: a caller that needs the run from rest sampled, the
    life route's starts); else the last window, whose warning says so. ``finish``: the whole result of a run whose
    unsettled window left its ringing fit for later (``run_simulation``'s ``unfinished``: only the window kept pays
    it). A periodic result keeps the first run's start-up peaks (:func:`with_start`), which the search's run-up, to
    the end of the ramps only, may not reach."""
    first = result
    result, runs, longest = _moved_window(result, run, duration_s, steps)
    if periodic and result.steady is not None and result.steady.mode == "window" and result.steady.settled is False:
        before = runs if runs else result.steady.settle_runs
        orbit = periodic_state(run, duration_s, steps, before + 1)
        if orbit is not None:
            return with_start(orbit, first)
    return _after_runs(finish(result), runs, longest)


def with_start(orbit: SimulationResult, first: SimulationResult) -> SimulationResult:
    """``orbit`` (a periodic steady state) with the start-up figures of ``first``, the run from rest whose window
    it replaces, where that run saw the larger peak: each stage's whole-run peak |F_t|, its time and the run-up
    factor, and ``summary.start`` with its ``peak_over_rigid`` warnings (the periodic search's own run-up ends
    with the ramps; the start's overshoot may come after them)."""
    if len(first.stages) != len(orbit.stages):
        return orbit
    stages = tuple(replace(o, peak_tangential_N=f.peak_tangential_N, peak_time_s=f.peak_time_s,
                           runup_factor=f.runup_factor) if f.peak_tangential_N > o.peak_tangential_N else o
                   for o, f in zip(orbit.stages, first.stages, strict=True))
    if all(a is b for a, b in zip(stages, orbit.stages, strict=True)):
        return orbit
    extra = SimulationExtra(**(orbit.extra or {}))
    if first.extra and "start" in first.extra:
        extra["start"] = first.extra["start"]
    diags = tuple(d for d in orbit.diagnostics if d.code != dg.PEAK_OVER_RIGID) \
        + tuple(d for d in first.diagnostics if d.code == dg.PEAK_OVER_RIGID)
    return replace(orbit, stages=stages, extra=extra, diagnostics=diags, warnings=dg.messages(list(diags)))


def _moved_window(result: SimulationResult, run: Callable[..., SimulationResult], duration_s: float,
                  steps: int) -> tuple[SimulationResult, int, tuple[float, int]]:
    """The window moved later while it is not settled (:func:`settled_run`), the longer runs made, and the (duration,
    steps) of the last run."""
    runs, last = 0, (duration_s, steps)
    while result.steady is not None and result.steady.mode == "window" and result.steady.settled is False \
            and runs < MAX_RUNS:
        st = result.steady
        found = Settling(False, st.transient_fraction or math.inf, settle_time_s=st.settle_time_s)
        nxt = next_window(found, result.window_s, duration_s)
        if nxt is None:
            break
        start, duration = nxt
        samples = max(steps, math.ceil(steps * duration / duration_s))
        try:
            longer = run(duration, samples, start)
        except GearcliError:  # the longer run exceeds its own budget (or fails): the window's warning stands
            break
        runs += 1
        result, last = longer, (duration, samples)
    return result, runs, last


def _after_runs(result: SimulationResult, runs: int, last: tuple[float, int]) -> SimulationResult:
    """The kept window's ``settle_runs``, its warning's note of the longer runs, and the last run's duration and
    steps (``last``) in a suggestion that starts the window at a time of that run
    (:func:`gearcli.simulate.sampling.with_run_duration`)."""
    if runs and result.steady is not None:
        steady = replace(result.steady, settle_runs=runs)
        diags = tuple(sampling.with_run_duration(d, *last) for d in result.diagnostics)
        result = replace(result, steady=steady, diagnostics=diags, warnings=dg.messages(list(diags)))
        if steady.settled is False:
            note = f" (after {runs} longer run{'s' if runs > 1 else ''} within the budget)"
            diags = tuple(replace(d, message=d.message + note) if d.code == dg.WINDOW_NOT_SETTLED else d
                          for d in result.diagnostics)
            result = replace(result, diagnostics=diags, warnings=dg.messages(list(diags)))
    return result
