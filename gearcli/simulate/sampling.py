"""The sampling error of the window's min and max: what the output samples miss of the extremes between them (and,
through :mod:`gearcli.simulate.sampled_moments`, of the mean and the std).

The window statistics are taken over the output samples (``simulation.steps``). The solver's check pass
(:mod:`gearcli.simulate.estimate`) compares two integrations on the same samples, so it sees the solver's
error only; a peak that falls between two samples is missed by the sampled max whatever the tolerance.
This module estimates that miss from the samples alone (no integration, a few vector operations per stage).

Estimator. At every sample that is a local extreme (not below either neighbour, for the max), the parabola
through it and its two neighbours (their own, possibly uneven, spacing) has its vertex at the interpolated
extreme; the largest vertex over the window is the interpolated max, and its excess over the sampled max is
the estimate. For a smooth peak the vertex misses the true peak by O(h^3) where the sample misses it by
O(h^2), so the estimate is the sampling error itself to leading order (any phase of the samples against the
peak; a pure sinusoid with N samples per period: within a few % from N = 16, tests/unit/test_sampling.py).
Every peak of the window counts, not only the sampled max's: a neighbouring period's peak sampled at a worse
phase may be the higher one.

Bound. A concave peak exceeds the sample by at most its step to the other neighbour, and the parabola's excess is
cut to the larger step; it overshoots where three points straddle a kink (an impact, a viscous backlash mesh's
contact), where five concave samples bound the peak by their secants (:mod:`gearcli.simulate.kink_bound`): the
estimate is that bound at a kink, else the smaller of it and SAFETY x the excess (beside a step: the upper arm
continued over the step's interval). Zero is a floor for a clamped contact force: a sampled min of 0 is exact, and no interpolated extreme crosses zero (configs/backlash_oscillator.toml: 2.4e-3).
A window edge's peak is the parabola's through its first three samples, its vertex between them; a constant has none.

Periodic windows (``steady = "periodic"``: whole periods, uniformly sampled without their closing sample) wrap
around: the first sample's left neighbour is the last one, a period earlier.

Safety. The estimate is :data:`SAFETY` x the interpolated excess. On a smooth peak the excess is the error
(a sinusoid: 0.97-1.0x from 16 samples per period), so the estimate is twice it; peaks that are not smooth on the
sample grid are underestimated by the parabola: the kinked top of a time-varying mesh's force (its contact length
is piecewise linear in the mesh phase) 1.2-4.5x on configs/mixer_time_varying_backlash.toml and
configs/concrete_mixer_te.toml (benchmarks/bench_sampling.py, against the same run sampled 16x finer).
Not seen at all: vibration faster than the samples resolve (a few samples per period or fewer: it aliases to
a slower, smooth-looking signal). configs/conveyor.toml's stage 2 carries a ~1.6 kHz vibration sampled at 2 kHz:
its min is 5.2e-3 off, estimated 5e-5. ``gearcli report`` warns (``sampling``) where a natural frequency lies
above the samples' Nyquist frequency; there a mode or excitation line that carries force in the window is found and
the estimate not taken for a bound (:mod:`gearcli.simulate.aliasing`: ``sampling_error.aliased``).

Aliased excitation. The estimate needs the peaks to be sampled at all: an excitation (a mesh's transmission
error or stiffness cycle, a torque ripple, a load fluctuation: :func:`gearcli.simulate.periodic.excitation_periods`,
their fundamentals) with fewer than :data:`MIN_PER_PERIOD` window samples a period is aliased (below 2 a period) or
nearly so, and its response looks smooth to the samples. Such a run is warned ``excitation_undersampled``, naming
the excitation, its frequency, the samples a period and the ``simulation.steps`` that gives :data:`GOOD_PER_PERIOD`
(configs/conveyor_motor.toml: the stage 1 mesh at 2.1 a period). A periodic window has 64 samples a period.

The run's peak. ``peak_tangential_N``, its time and the ``runup_factor`` are the largest |F_t| of the whole run's
samples: a start's peak between two samples is missed the same way. :func:`peak_warnings` estimates it with the
same parabola over the run's |F_t| (SAFETY x the excess) and warns ``peak_undersampled`` where that is more than
:data:`TARGET` of the peak, with the ``simulation.steps`` that resolves it (configs/motor_direct_start.toml: stage
2's DOL peak sampled at 10527 N against 11445 N at 40000 steps, 8 %, estimated 3.8 %: a step response's sharp top
is underestimated as a kinked one is, but seen; there the mesh mode rings above the samples' Nyquist frequency, and
:mod:`gearcli.simulate.start_rings` warns that the samples bound nothing instead). A peak the samples alias (a mode
rung faster than a sample or two a period) is not seen by the parabola, but the samples around it show it: they
chatter, the peak sample's second difference exceeding :data:`ALIAS_CURVATURE` of it (a sinusoid sampled fewer than
6 times a period). Such a peak is warned as not bounded by the samples, with the ``simulation.steps`` that samples
the scene's fastest natural frequency :data:`GOOD_PER_PERIOD` times a period (a 1e4x-ISO mesh closing its 0.1 mm
backlash under 30 N m: a 139 kHz impact pulse sampled every 100 us showed 3117 N, estimated 78 N short, where
sampling it finely gives 54,782 N).

The mean. The window mean is the trapezoid rule over the samples (the channel's integral over the window). It
misses what the samples miss of the integral: little for a smooth force (the rule's error is O(h^2) at the window's
ends, spectrally small inside), but a force with steps (a time-varying mesh's stiffness cycle, impacts) or harmonics
the samples alias puts O(h) or an alias into it (a spur pair with a varying contact line sampled 6 times a mesh
period: 7933 N against 7491 N, 5.9 %; 599 steps instead of 600: 7216 N). The estimate is Richardson's for the rule,
|T_h - T_2h| / 3 (T_2h the rule with every other sample left out): the error of T_h where it is O(h^2) (a smooth
force). A force with steps at random phases to the samples (impacts, a stiffness cycle not locked to them) has an
O(h) error of random sign that T_h - T_2h overstates (measured 2-5x on configs/backlash_oscillator.toml at 700 steps:
4.7e-5 true), so /3 keeps it about right there too; a coherent O(h) error (steps or harmonics locked to the samples,
as above) is understated (3-4x on the spur pair: 107 N estimated, 352 N against 8x the steps), but such runs are
far beyond the target (1.4e-2 there). It is
judged against the mean's own target (``MEAN_TARGET``, with the solver's estimate) and warned
``statistics_undersampled`` (statistic ``mean``); its suggestion assumes the O(h) rate. A periodic window (whole periods, 64 samples a period of its fastest excitation) is
the exact rule of a band-limited signal and is not estimated.

The mean: a partial period. The window mean is the mean over the window, and the steady state's mean is the mean
over whole periods of its excitations: a window that holds n = f T periods of a response component of amplitude A
at frequency f, not a whole number, adds A sin(pi n) cos(2 pi f t_mid + phase) / (pi n) to the mean (t_mid its
middle), at most A |sin(pi n)| / (pi n) and 0 for whole periods. :func:`window_period_warnings` bounds it from the
window itself: for every excitation's fundamental and first :data:`PARTIAL_HARMONICS` harmonics below the samples'
Nyquist frequency (one per frequency resolution 1 / T, the lower harmonic kept), A from the trapezoid-rule
projection of F_t about its mean (accurate to ~1 / (2 pi n) of A: the negative-frequency image leaks in), under one
period the window's half range; the bounds summed over the frequencies. Where the sum exceeds the mean's target
(``MEAN_TARGET`` of the reference force), the run warns ``window_partial_period`` naming the largest contributor and,
where the excitations' common period fits in the window, the ``simulation.window_start_s`` of its last whole periods
(configs/backlash_oscillator.toml: 28.56 periods of its 51 Hz mesh, bound 9.1 N or 3.1e-3 of the mean; its last 28
periods move the mean by 6.0 N and carry no warning). Vibration that is no excitation's (a mode ringing from the
run-up) is ``window_ringing``'s and ``window_not_settled``'s, not counted here. A periodic window holds whole
periods and is not judged.

Verdict and suggestion. Where a check pass ran, the estimate is added to the solver's for min and max
(:func:`merged`); the samples leave a statistic unresolved when the sum exceeds :data:`TARGET` and the sampling is
a cause of it (:func:`_undersampled`). The error of a smooth peak falls as h^2, so ``suggested_steps`` scales the
samples by the square root of the error over half of what the solver leaves of the target, with a 1.25 margin,
rounded up to two significant figures and capped by the schema's ``simulation.steps`` maximum (None beyond it).
A kinked top converges more slowly (h^1.1 measured on configs/backlash_oscillator.toml): the run at the
suggestion may suggest once more.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from gearcli import diagnostics as dg
from gearcli.config.schema import MAX_STEPS
from gearcli.diagnostics import Diagnostic
from gearcli.simulate.estimate import (
    MEAN_TARGET,
    TARGET,  # of the stage's mean force: the solver's and the samples' together
    force_reference,
    reference_words,
    solver_first,
)
from gearcli.simulate.estimate import target as target_of  # MEAN_TARGET for the mean, TARGET else
from gearcli.simulate.kink_bound import peak_excess
from gearcli.simulate.periodic import common_period, excitation_periods
from gearcli.simulate.results import SamplingError, StatisticsError
from gearcli.simulate.sampled_moments import mean_error, std_error

MARGIN = 1.25  # suggested_steps: the h^2 extrapolation's samples x this
SAFETY = 2.0  # the estimate is this x the interpolated excess (module doc, "Safety")
EXTREMES = ("min", "max")
STATISTICS = ("mean", "min", "max", "std")  # the statistics the samples can leave unresolved
# fewer window samples than this and no estimate can be made (the mean's Richardson step needs 5, the parabola through
# a peak 3): a fixed window of 1 or 2 samples (simulation.steps = 1 .. 3) reported its one sample as mean = min = max
# and std 0, "resolved", where a lightly damped reducer's window swings by +-9.5 % of the mean
MIN_WINDOW_SAMPLES = 5
TOO_FEW = ("mean", "min", "max", "std")  # what a window of too few samples leaves unknown
UNBOUNDED = ("min", "max", "std")  # what force above the samples' Nyquist frequency leaves unknown (aliasing.py)
MIN_PER_PERIOD = 4.0  # output samples a period of an excitation, at least (module doc, "Aliased excitation")
GOOD_PER_PERIOD = 16.0  # what the suggestion aims at (a sinusoid's sampled peak then misses by 2 %)
PARTIAL_HARMONICS = 4  # harmonics of each excitation whose partial period the mean's bias bound counts
ALIAS_CURVATURE = 1.0  # |second difference| / peak sample beyond which the samples alias it (module doc)


def _vertex_excess(xl: np.ndarray, xc: np.ndarray, xr: np.ndarray, sl: np.ndarray, sr: np.ndarray) -> np.ndarray:
    """Excess of the parabola's vertex over the centre sample, through (-sl, xl), (0, xc), (sr, xr) (sl, sr > 0,
    xc not below xl nor xr), cut to the larger difference to a neighbour (module doc, "Bound")."""
    u = xc - xl  # >= 0
    v = xc - xr  # >= 0
    with np.errstate(divide="ignore", invalid="ignore"):
        a = -(u / sl + v / sr) / (sl + sr)  # curvature/2 (<= 0)
        b = u / sl + a * sl  # slope at the centre
        excess = np.where(a < 0, -b * b / (4.0 * a), 0.0)
    excess = np.where(np.isfinite(excess), excess, 0.0)
    return np.minimum(excess, np.maximum(u, v))


def _edge_excess(t: np.ndarray, x: np.ndarray, at_end: bool) -> float:
    """A peak between the edge sample and its neighbour: the parabola through the three edge samples, counted
    where its vertex lies between the edge and its neighbour."""
    if at_end:
        t, x = -t[::-1], x[::-1]
    s1, s2 = t[1] - t[0], t[2] - t[0]
    if s1 <= 0 or s2 <= s1:
        return 0.0
    d1, d2 = x[1] - x[0], x[2] - x[0]
    a = (d2 / s2 - d1 / s1) / (s2 - s1)
    b = d1 / s1 - a * s1
    if a >= 0:
        return 0.0
    s_star = -b / (2.0 * a)
    if not 0.0 < s_star < s1:
        return 0.0
    value = x[0] + b * s_star + a * s_star**2
    return float(min(max(0.0, value - max(x[0], x[1])), abs(d1)))


def max_excess(t: np.ndarray, x: np.ndarray, *, periodic: bool = False, zero_floor: bool = False,
               dt: np.ndarray | None = None, extremes: tuple[float, float] | None = None) -> float:
    """How far the interpolated max of ``x`` over the window ``t`` lies above its sampled max (>= 0; module doc);
    ``zero_floor``: not past zero from a sampled max at or below it (a force that the contact law clamps there);
    ``dt``: ``np.diff(t)`` when the caller has it; ``extremes``: ``x``'s (min, max) when the caller has them."""
    n = x.size
    if n < 3:
        return 0.0
    bottom, top = (float(x.min()), float(x.max())) if extremes is None else extremes
    if top == bottom:
        return 0.0
    dt = np.diff(t) if dt is None else dt
    d = np.diff(x)
    if periodic:  # uniform samples: the last sample is a step before the next period's first
        h_wrap = (t[-1] - t[0]) / (n - 1)
        wrap = x[0] - x[-1]
        rise, fall = np.concatenate(([wrap], d)), np.concatenate((d, [wrap]))  # into and out of each sample
        sl, sr, xc = np.concatenate(([h_wrap], dt)), np.concatenate((dt, [h_wrap])), x
        outer = tuple(np.roll(a, k) for a, k in ((rise, 1), (fall, -1), (sl, 1), (sr, -1)))
    else:
        rise, fall, sl, sr, xc = d[:-1], d[1:], dt[:-1], dt[1:], x[1:-1]
        nan = [np.nan]  # an edge's neighbour has no outer neighbour: no secant bound there
        outer = tuple(np.concatenate(p) for p in ((nan, d[:-2]), (d[2:], nan), (nan, dt[:-2]), (dt[2:], nan)))
    # a local max that could beat the sampled max: its excess is at most the larger step to a neighbour
    peak = np.flatnonzero((rise >= 0) & (fall <= 0) & (xc + np.maximum(rise, -fall) > top))
    best = top
    if peak.size:
        xp = xc[peak]
        excess = _vertex_excess(xp - rise[peak], xp, xp + fall[peak], sl[peak], sr[peak])  # or the secants':
        best = max(best, float(np.max(xp + peak_excess(excess, SAFETY, xp, rise[peak], fall[peak], sl[peak], sr[peak],
                                                       *(o[peak] for o in outer)))))
    if not periodic:
        for at_end in (False, True):
            j = n - 1 if at_end else 0
            if x[j] >= x[j - 1 if at_end else 1]:
                edge = _edge_excess(t[-3:] if at_end else t[:3], x[-3:] if at_end else x[:3], at_end)
                best = max(best, float(x[j]) + edge)
    if zero_floor and top <= 0.0:
        best = min(best, 0.0)
    return max(0.0, best - top)


def extremes_error(t: np.ndarray, x: np.ndarray, *, periodic: bool = False, dt: np.ndarray | None = None,
                   extremes: tuple[float, float] | None = None) -> tuple[float, float]:
    """(min, max) sampling errors of the force ``x`` over the window ``t`` (N when ``x`` is in N; module doc): neither
    interpolated extreme crosses zero, where the contact law clamps the force (module doc, "Bound"). ``dt``:
    ``np.diff(t)`` when the caller has it (every stage's window shares it); ``extremes``: ``x``'s (min, max) when
    the caller has them (-x's are their negatives, exactly)."""
    dt = np.diff(t) if dt is None else dt
    if extremes is not None and x.size >= 3 and extremes[0] == extremes[1]:  # a constant window: nothing between
        return 0.0, 0.0
    flipped = None if extremes is None else (-extremes[1], -extremes[0])
    return (max_excess(t, -x, periodic=periodic, zero_floor=True, dt=dt, extremes=flipped),
            max_excess(t, x, periodic=periodic, zero_floor=True, dt=dt, extremes=extremes))


def suggested_steps_linear(steps: int, relative_error: float, goal: float, cap: int = MAX_STEPS) -> int | None:
    """``simulation.steps`` that brings a mean's sampling error of ``relative_error`` at ``steps`` below ``goal``
    (error ∝ h, times :data:`MARGIN`; module doc, "The mean"), as :func:`suggested_steps` rounds it."""
    if relative_error <= goal:
        return steps
    n = up_to_two_figures(steps * relative_error / goal * MARGIN)
    return n if n <= cap else None


def suggested_steps(steps: int, relative_error: float, goal: float, cap: int = MAX_STEPS) -> int | None:
    """``simulation.steps`` that brings a sampling error of ``relative_error`` at ``steps`` below ``goal``
    (error ∝ h^2, times :data:`MARGIN`), rounded up to two significant figures; None when ``cap`` cannot."""
    if relative_error <= goal:
        return steps
    n = up_to_two_figures(steps * math.sqrt(relative_error / goal) * MARGIN)
    return n if n <= cap else None


def up_to_two_figures(wanted: float, slack: float = 0.0) -> int:
    """``wanted`` samples rounded up to two significant figures (``slack``: a relative round-off not rounded up)."""
    digits = 10.0 ** max(0, math.floor(math.log10(wanted)) - 1)
    return int(math.ceil(wanted / digits * (1.0 - slack)) * digits)


def stage_sampling(t: np.ndarray, ft: np.ndarray, static_N: float, steps: int, *, periodic: bool = False,
                   solver: StatisticsError | None = None, window_share: float = 1.0,
                   floor_N: float = 0.0, dt: np.ndarray | None = None,
                   reduced: tuple[float, float, float, float] | None = None) -> SamplingError:
    """The sampling error of a stage's window min and max of F_t (``t``, ``ft``: the window's samples), judged
    with the solver's estimate ``solver`` where a check pass ran (their sum against :data:`TARGET`).
    ``steps``: the ``simulation.steps`` that sampled the window (the window's h is proportional to 1/steps);
    ``window_share``: the window's length over the run's (what a window of too few samples needs more steps for);
    ``floor_N``: the least force an unloaded stage's targets refer to (:func:`estimate.force_floors_N`); ``dt``:
    ``np.diff(t)`` when the caller has it; ``reduced``: ``ft``'s (plain mean, std, min, max) when the caller has
    them (:func:`gearcli.simulate.stats.window_reductions`)."""
    if not periodic and t.size < MIN_WINDOW_SAMPLES:
        return _too_few(t, ft, static_N, steps, solver, window_share, floor_N)
    lo, hi = extremes_error(t, ft, periodic=periodic, dt=dt, extremes=None if reduced is None else reduced[2:])
    if solver is not None:
        ref = solver.reference_N
    else:
        mean, std = (float(ft.mean()), float(ft.std())) if reduced is None else reduced[:2]
        ref = force_reference(mean, std, static_N, floor_N)
    err = {"min": SAFETY * lo, "max": SAFETY * hi, "mean": 0.0 if periodic else mean_error(t, ft),
           "std": 0.0 if periodic else std_error(ft, None if reduced is None else reduced[1])}
    rel = {q: (v / ref if ref > 0 else (0.0 if v == 0 else math.inf)) for q, v in err.items()}
    bad = [q for q in STATISTICS if _undersampled(rel[q], solver.relative[q] if solver is not None else 0.0, q)]
    suggestion = None
    if bad and all(math.isfinite(rel[q]) for q in bad):
        wanted = []
        for q in bad:
            target = target_of(q)
            goal = 0.5 * (target - solver.relative[q] if solver is not None and solver.relative[q] < target
                          else target)
            wanted.append((suggested_steps_linear if q == "mean" else suggested_steps)(steps, rel[q], goal))
        suggestion = None if any(w is None for w in wanted) else max(w for w in wanted if w is not None)
    return SamplingError(min_N=err["min"], max_N=err["max"], relative=rel, reference_N=ref, target_relative=TARGET,
                         samples=int(t.size), resolved=not bad, suggested_steps=suggestion, steps_cap=MAX_STEPS,
                         mean_N=err["mean"], std_N=err["std"])


def too_few(s: SamplingError) -> bool:
    """A fixed window with fewer samples than any estimate needs (:data:`MIN_WINDOW_SAMPLES`): nothing resolved."""
    return not s.resolved and s.samples < MIN_WINDOW_SAMPLES


def _too_few(t: np.ndarray, ft: np.ndarray, static_N: float, steps: int, solver: StatisticsError | None,
             window_share: float, floor_N: float = 0.0) -> SamplingError:
    """A window of too few samples: no error estimated (0), not resolved, and the ``simulation.steps`` that gives it
    :data:`MIN_WINDOW_SAMPLES` (the least an estimate needs; that run's estimate then says what resolves it)."""
    mean = float(ft.mean()) if ft.size else 0.0
    ref = solver.reference_N if solver is not None else force_reference(mean, float(ft.std()) if ft.size else 0.0,
                                                                        static_N, floor_N)
    wanted = max(steps + 1, math.ceil(MIN_WINDOW_SAMPLES / max(window_share, 1e-12)))
    return SamplingError(min_N=0.0, max_N=0.0, relative={q: 0.0 for q in STATISTICS}, reference_N=ref,
                         target_relative=TARGET, samples=int(t.size), resolved=False,
                         suggested_steps=wanted if wanted <= MAX_STEPS else None, steps_cap=MAX_STEPS)


def _undersampled(sampling: float, solver: float, statistic: str = "max") -> bool:
    """The samples leave the statistic unresolved: the sum beyond its target (:data:`MEAN_TARGET` for the mean,
    :data:`TARGET` else), and the sampling a cause of it (the solver's part within the target, or the sampling's own
    beyond it)."""
    target = target_of(statistic)
    return sampling > 0 and sampling + solver > target and (solver <= target or sampling > target)


def merged(e: StatisticsError, s: SamplingError) -> StatisticsError:
    """The solver's estimate with the sampling's share of min and max added (new keys; ``unresolved`` and
    ``resolved`` then cover both; the solver's own keys keep their meaning)."""
    total = {q: e.relative[q] + s.relative[q] for q in STATISTICS}
    over = {q for q in STATISTICS if total[q] > target_of(q)} | (set(TOO_FEW) if too_few(s) else set()) \
        | (set(UNBOUNDED) if s.aliased else set())
    unresolved = tuple(q for q in ("mean", "min", "max", "std", "spectrum") if q in e.unresolved or q in over)
    return replace(e, sampling_N={"min": s.min_N, "max": s.max_N, "mean": s.mean_N, "std": s.std_N},
                   sampling_relative=dict(s.relative),
                   total_relative=total, suggested_steps=s.suggested_steps if not s.resolved else None,
                   unresolved=unresolved, resolved=not unresolved)


def warnings(stages: list[tuple[int, SamplingError]], solver: dict[int, StatisticsError],
             unloaded: frozenset[int] = frozenset()) -> list[Diagnostic]:
    """``statistics_undersampled``, one per stage (1-based index, its sampling error) whose window min or max
    the output samples leave unresolved; ``unloaded``: the stages that carry no static force."""
    out = []
    for stage, s in stages:
        if s.resolved:
            continue
        if too_few(s) or s.aliased:  # force above the Nyquist frequency: aliasing.warnings'
            out += [_too_few_warning(stage, s)] if too_few(s) else []
            continue
        e = solver.get(stage)
        bad = [q for q in STATISTICS if _undersampled(s.relative[q], e.relative[q] if e is not None else 0.0, q)]
        worst = max(bad, key=lambda q: s.relative[q] / target_of(q))
        absolute = {"min": s.min_N, "max": s.max_N, "mean": s.mean_N, "std": s.std_N}[worst]
        with_solver = "" if e is None else f", the solver's estimate {e.relative[worst]:.2g} besides"
        if e is not None and e.relative[worst] > max(target_of(worst), s.relative[worst]):
            fix = solver_first(s.suggested_steps, MAX_STEPS)
        elif s.suggested_steps is not None:
            fix = f"--set simulation.steps={s.suggested_steps} would resolve it"
        else:
            fix = (f"the schema's maximum simulation.steps = {s.steps_cap} cannot resolve it: sample a shorter run "
                   "(simulation.duration_s) or fewer periods")
        what = _what(worst, s.samples, absolute)
        out.append(dg.warning(
            dg.STATISTICS_UNDERSAMPLED,
            f"stage {stage}: F_t {' and '.join(bad)} not resolved by the output samples: {what} "
            f"({s.relative[worst]:.2g} of {reference_words(s.reference_N, stage in unloaded)}{with_solver}, target "
            f"{target_of(worst):g}); {fix}",
            stage=stage, statistics=bad, estimated_error_N=float(absolute), relative_error=float(s.relative[worst]),
            steps=s.suggested_steps, steps_cap=s.steps_cap))
    return out


def _what(worst: str, samples: int, absolute: float) -> str:
    """What the samples miss of the statistic ``worst``, in words (:func:`warnings`)."""
    if worst == "mean":
        return (f"the window's mean (the integral over its {samples} samples) is estimated {absolute:.3g} N off "
                "(a third of its change when every other sample is left out, or half the force's change a step where "
                "the samples lock to an excitation's period): the force has steps or vibration the samples alias")
    if worst == "std":
        return (f"the window's std over its {samples} samples changes by {absolute:.3g} N when every other sample is "
                "left out: the samples see the force at few phases of its period (locked to it) or alias its harmonics")
    return f"the peaks between the {samples} window samples are estimated up to {absolute:.3g} N beyond them"


def _too_few_warning(stage: int, s: SamplingError) -> Diagnostic:
    fix = (f"--set simulation.steps={s.suggested_steps} gives it {MIN_WINDOW_SAMPLES} or more, and an estimate"
           if s.suggested_steps is not None else "a longer window (simulation.window_start_s) gives it more")
    return dg.warning(
        dg.STATISTICS_UNDERSAMPLED,
        f"stage {stage}: F_t {', '.join(TOO_FEW)} not resolved by the output samples: the window holds "
        f"{s.samples} sample{'s' if s.samples != 1 else ''}, fewer than the {MIN_WINDOW_SAMPLES} an error estimate "
        f"needs, so its statistics are those samples' and say nothing of the force between them; {fix}",
        stage=stage, statistics=list(TOO_FEW), estimated_error_N=None, relative_error=None,
        steps=s.suggested_steps, steps_cap=s.steps_cap)


def excitation_warnings(layout, t: np.ndarray, steps: int) -> list[Diagnostic]:
    """``excitation_undersampled``, one per excitation of the scene whose period holds fewer than
    :data:`MIN_PER_PERIOD` of the window's samples ``t`` (module doc, "Aliased excitation"); ``steps``: the file's
    ``simulation.steps`` that sampled them (the suggestion scales it)."""
    if t.size < 2:
        return []
    h = float(t[-1] - t[0]) / (t.size - 1)  # the window's samples are uniform
    if not h > 0.0:
        return []
    out = []
    for ex in excitation_periods(layout):
        per = ex.period_s / h
        if not (ex.period_s > 0.0 and per < MIN_PER_PERIOD):
            continue
        n = up_to_two_figures(steps * GOOD_PER_PERIOD / per, slack=1e-9)  # not rounded up past round-off
        fix = (f"--set simulation.steps={n} samples it {GOOD_PER_PERIOD:g} times a period" if n <= MAX_STEPS else
               f"the schema's maximum simulation.steps = {MAX_STEPS} cannot sample it: a shorter run "
               "(simulation.duration_s)")
        aliased = "; below 2 it is aliased" if per < 2.0 else ""
        out.append(dg.warning(
            dg.EXCITATION_UNDERSAMPLED,
            f"the {ex.label} excitation ({1.0 / ex.period_s:.4g} Hz) has {per:.2g} output samples a period (fewer "
            f"than {MIN_PER_PERIOD:g}{aliased}): the series show its response as a slower, smooth signal, and the "
            "window's min, max, std and spectrum miss what lies between the samples, which the sampling estimate "
            f"cannot see; {fix}",
            excitation=ex.label, frequency_Hz=1.0 / ex.period_s, samples_per_period=per,
            steps=n if n <= MAX_STEPS else None))
    return out


def partial_period_bias(t: np.ndarray, x: np.ndarray, frequency_Hz: float,
                        phasor: np.ndarray | None = None, centred: np.ndarray | None = None) -> tuple[float, float]:
    """(amplitude, bias bound) of ``x``'s component at ``frequency_Hz`` over the window ``t`` (module doc, "The mean:
    a partial period"): the amplitude A from the trapezoid-rule projection ``2 |∫ (x - mean) e^(-i w t) dt| / T``,
    the bound ``A |sin(pi f T)| / (pi f T)`` on what its partial period puts into the window mean (a sinusoid's mean
    over n periods is ``A sin(pi n) cos(phase) / (pi n)``). Under one period the projection cannot tell the component
    from the mean: A is then the window's half range. ``phasor``: ``e^(-i w (t - t0))``, ``centred``: ``x`` less its
    trapezoid-rule mean, when the caller has them (one per window and frequency, one per window and stage)."""
    span = float(t[-1] - t[0])
    n = frequency_Hz * span
    if n < 1.0:
        amplitude = 0.5 * float(np.ptp(x))
    else:
        if phasor is None:
            phasor = np.exp(-2j * math.pi * frequency_Hz * (t - t[0]))
        if centred is None:
            centred = x - float(np.trapezoid(x, t)) / span
        amplitude = 2.0 * abs(complex(np.trapezoid(centred * phasor, t))) / span
    return amplitude, amplitude * abs(math.sin(math.pi * n)) / (math.pi * n)


def _lines(periods, span: float, nyquist: float) -> list[tuple[float, str]]:
    """The excitations' frequencies and their harmonics below ``nyquist``, slowest first, each at least one frequency
    resolution ``1 / span`` from the others (a projection over the window cannot tell closer ones apart): of two
    closer ones the lower harmonic is kept (a mesh's fundamental, not another mesh's harmonic at its frequency)."""
    found = sorted((j, j / ex.period_s, ex.label if j == 1 else f"{ex.label} (harmonic {j})")
                   for ex in periods for j in range(1, PARTIAL_HARMONICS + 1) if j / ex.period_s < nyquist)
    kept: list[tuple[float, str]] = []
    for _, f, label in found:
        if all(abs(f - g) >= 1.0 / span for g, _ in kept):
            kept.append((f, label))
    return sorted(kept)


def window_period_warnings(layout, t: np.ndarray, forces_N: list[np.ndarray], references_N: list[float | None],
                           unloaded: frozenset[int] = frozenset()) -> list[Diagnostic]:
    """``window_partial_period``, one per stage whose window mean F_t the partial periods of the scene's excitations
    (their fundamentals and first :data:`PARTIAL_HARMONICS` harmonics below the samples' Nyquist frequency) may bias
    beyond the mean's target (module doc, "The mean: a partial period"). ``forces_N``: the window's F_t per stage;
    ``references_N``: the force each stage's targets refer to (None: not judged); ``unloaded``: the stages (1-based)
    that carry no static force, whose reference is the rms of their F_t, not their mean."""
    periods = [ex for ex in excitation_periods(layout) if ex.period_s > 0.0]
    judged = [k for k, ref in enumerate(references_N) if ref is not None and ref > 0.0]
    if not periods or not judged or t.size < MIN_WINDOW_SAMPLES or not float(t[-1] - t[0]) > 0.0:
        return []
    span = float(t[-1] - t[0])
    lines = _lines(periods, span, 0.5 * (t.size - 1) / span)
    found: dict[int, list] = {k: [] for k in judged}
    centred = {k: forces_N[k] - float(np.trapezoid(forces_N[k], t)) / span for k in judged}  # shared by the lines
    for f, label in lines:
        phasor = np.exp(-2j * math.pi * f * (t - t[0])) if f * span >= 1.0 else None  # shared by the stages
        for k in judged:
            found[k].append((partial_period_bias(t, forces_N[k], f, phasor, centred[k]), f, label))
    common = common_period(periods)
    out = []
    for k in judged:
        ref = float(references_N[k] or 0.0)
        bound = sum(b for (_, b), _, _ in found[k])
        if not bound > MEAN_TARGET * ref:
            continue
        (amplitude, worst), f, label = max(found[k], key=lambda item: item[0][1])
        if common is not None and common.exact and common.period_s <= span:
            whole = int(math.floor(span / common.period_s))
            start = float(t[-1]) - whole * common.period_s
            fix = (f"a window of whole periods of the excitations' common period {common.period_s:.4g} s (--set "
                   f"{_start_setting(start)}: its last {whole}) or ")
        elif common is not None and common.exact:  # longer than the window: one period from its start, sampled alike
            start, end = None, float(t[0]) + common.period_s
            fix = (f"a window of whole periods of the excitations' common period {common.period_s:.4g} s (--set "
                   f"{_start_setting(float(t[0]), (end, math.ceil(end * (t.size - 1) / span)))}: one period) or ")
        else:
            start, fix = None, "a longer window (the bias falls as 1 / its length) or "
        out.append(dg.warning(
            dg.WINDOW_PARTIAL_PERIOD,
            f"stage {k + 1}: the steady window ({span:.4g} s) holds {f * span:.4g} periods of the {label} excitation "
            f"({f:.4g} Hz), not a whole number: its response there ({amplitude:.3g} N amplitude) may bias the window "
            f"mean F_t by up to {worst:.3g} N, and the excitations together by {bound:.3g} N ({bound / ref:.2g} of "
            f"{reference_words(ref, True) if k + 1 in unloaded else 'the mean'}), beyond the mean's target "
            f"{MEAN_TARGET:g}; {fix}steady = \"periodic\" (whole periods) "
            "removes it",
            stage=k + 1, statistic="mean", excitation=label, frequency_Hz=f, periods=f * span, amplitude_N=amplitude,
            estimated_bias_N=bound, relative_bias=bound / ref, window_start_s=start))
    return out


def _start_setting(start_s: float, run: tuple[float, int] | None = None) -> str:
    """The ``--set`` keys of a window of whole periods from ``start_s``; ``run``: the (duration, steps) of the run
    that warned where it was not the file's own (a sweep row's or duty point's run repeated longer to settle)."""
    before = "" if run is None else f"simulation.duration_s={run[0]:.9g} --set simulation.steps={run[1]} --set "
    return f"{before}simulation.window_start_s={start_s:.9g}"


def with_run_duration(diag: Diagnostic, duration_s: float, steps: int) -> Diagnostic:
    """``diag`` as the run of ``duration_s`` sampled ``steps`` times says it, where that run is longer than the
    design file's (the settle test's repeat, :func:`gearcli.simulate.settle.settled_run`): a
    ``window_partial_period`` warning's whole periods then end at that run's end and start at one of its samples,
    so its suggestion names its duration and steps too (the window start alone would hold a partial period of the
    file's shorter run). Any other diagnostic is returned as it is."""
    start = diag.data.get("window_start_s") if diag.code == dg.WINDOW_PARTIAL_PERIOD else None
    if not isinstance(start, float) or _start_setting(start) not in diag.message:
        return diag
    alone = _start_setting(start)
    return replace(diag, message=diag.message.replace(alone, _start_setting(start, (duration_s, steps))),
                   data={**diag.data, "duration_s": duration_s, "steps": steps})


def peak_warnings(t: np.ndarray, forces_N: list[np.ndarray], steps: int, fastest_Hz: float = 0.0,
                  said: list[Diagnostic] | tuple[Diagnostic, ...] = ()) -> list[Diagnostic]:
    """``peak_undersampled``, one per stage (its F_t over the whole run in ``forces_N``, stage order) whose run peak
    |F_t| the output samples at the times ``t`` miss by more than :data:`TARGET` of it, or alias (module doc, "The
    run's peak"); ``steps``: the file's ``simulation.steps`` (the suggestion scales it); ``fastest_Hz``: the scene's
    highest natural frequency (what an aliased peak's suggestion samples); ``said``: the run's warnings (its rtol first)."""
    if t.size < 3:
        return []
    dt = np.diff(t)
    out = []
    unresolved = {d.data.get("stage"): d.data.get("relative_error") for d in said if d.code == dg.PEAK_UNRESOLVED}
    for k, ft in enumerate(forces_N):
        a = np.abs(np.asarray(ft, dtype=float))
        peak = float(a.max()) if a.size else 0.0
        if not peak > 0.0:
            continue
        i = int(np.argmax(a))
        error = SAFETY * max_excess(t, a, dt=dt)
        rel = error / peak
        aliased = _aliased_peak(a, i)
        if rel <= TARGET and not aliased:
            continue
        at = float(t[i])
        if aliased:
            n = _aliased_steps(t, steps, fastest_Hz)
            out.append(_aliased_peak_warning(k, peak, at, a, i, n, error))
            continue
        n = suggested_steps(steps, rel, 0.5 * TARGET)
        fix = (solver_first(n, MAX_STEPS, dg.PEAK_UNRESOLVED) if isinstance(e := unresolved.get(k + 1), float) and e > rel
               else f"--set simulation.steps={n} would resolve it" if n is not None else
               f"the schema's maximum simulation.steps = {MAX_STEPS} cannot resolve it: sample a shorter run "
               "(simulation.duration_s)")
        out.append(dg.warning(
            dg.PEAK_UNDERSAMPLED,
            f"stage {k + 1}: the run's peak |F_t| {peak:.5g} N (at {at:.3g} s) and its run-up factor are not resolved "
            f"by the output samples: the peak between them is estimated up to {error:.3g} N higher ({rel:.2g} of it, "
            f"target {TARGET:g}); {fix}",
            stage=k + 1, peak_N=peak, estimated_error_N=float(error), relative_error=float(rel), steps=n,
            steps_cap=MAX_STEPS, aliased=False))
    return out


def _aliased_peak(a: np.ndarray, i: int) -> bool:
    """Whether the samples chatter at the peak sample ``a[i]`` (an interior one): its second difference exceeds
    :data:`ALIAS_CURVATURE` of it, as a sinusoid's does with fewer than 6 samples a period (module doc)."""
    if not 0 < i < a.size - 1:
        return False
    return abs(a[i - 1] - 2.0 * a[i] + a[i + 1]) > ALIAS_CURVATURE * a[i]


def _aliased_steps(t: np.ndarray, steps: int, fastest_Hz: float) -> int | None:
    """``simulation.steps`` that samples ``fastest_Hz`` :data:`GOOD_PER_PERIOD` times a period over the run ``t``
    (at least twice ``steps``), or None beyond the schema's maximum or without a frequency."""
    span = float(t[-1] - t[0])
    if not (fastest_Hz > 0.0 and span > 0.0):
        return None
    n = up_to_two_figures(max(2.0 * steps, span * fastest_Hz * GOOD_PER_PERIOD))
    return n if n <= MAX_STEPS else None


def _aliased_peak_warning(k: int, peak: float, at: float, a: np.ndarray, i: int, n: int | None,
                          error: float) -> Diagnostic:
    jump = max(abs(a[i] - a[i - 1]), abs(a[i] - a[i + 1])) / a[i]
    fix = (f"--set simulation.steps={n} samples the scene's fastest natural frequency {GOOD_PER_PERIOD:g} times a "
           "period" if n is not None else
           f"the schema's maximum simulation.steps = {MAX_STEPS} cannot sample the scene's fastest natural frequency: "
           "sample a shorter run (simulation.duration_s)")
    return dg.warning(
        dg.PEAK_UNDERSAMPLED,
        f"stage {k + 1}: the run's peak |F_t| {peak:.5g} N (at {at:.3g} s) and its run-up factor are not resolved by "
        f"the output samples, and no estimate from them bounds the error: |F_t| changes by {jump:.2g} of the peak "
        "from one sample to the next around it (an impact or a vibration faster than the samples, which they alias; "
        f"the true peak may be many times higher); {fix}",
        stage=k + 1, peak_N=peak, estimated_error_N=float(error), relative_error=None, steps=n,
        steps_cap=MAX_STEPS, aliased=True)
