"""The error estimate of the window statistics: a check pass over the window (docs/numerics.md "Honest statistics").

``mean`` is the integral of a channel and converges with the solution; ``min``, ``max``, ``std`` and the spectrum depend
on how finely the solver resolves the oscillation. The run estimates their error from a second pass on the same output
samples and the difference of every statistic between the two passes. Each stage's statistics either meet their target
or the run carries a ``statistics_unresolved`` warning naming the statistic, the stage, the estimated error and the
``--set simulation.rtol=...`` that would resolve them all (not promised where a mesh leaves its flank in the window:
:data:`NONSMOOTH`).

Targets. ``MEAN_TARGET`` (1e-4 of the stage's mean |F_t|, or of its static force when the mean is ~0) for the mean,
``TARGET`` (1e-3) for min, max, std and the spectrum. The mean is the number a rating reads (it is the static force plus
what the window's speed change stores), an integral of the solution that converges with it at the rate of the tolerance,
so the check pass estimates it well (0.6-1.2x the true error on every scene of benchmarks/bench_auto.py whose mean is
off by more than 1e-5, measured against DOP853 at rtol 1e-10; the exception, Radau stepping over an undamped mode, has
its own warning: :func:`gearcli.simulate.stepped_over.unresolved_mode`) and resolving it to 1e-4 costs one decade of
rtol where it is needed (a resonant, impacting mesh whose window mean DOP853 at rtol 1e-6 left 1.7e-4 off with its
amplitudes within 2.4e-4: docs/numerics.md, "Means to 1e-4").

Span. The check pass starts from the run's own state at the window start when the scene forgets what happened before it;
where errors made before the window survive into it (a lightly damped scene keeps its run-up vibration), it starts
earlier: at the window start minus ``DECAY_SPANS`` / sigma, sigma the slowest decay rate of the oscillating modes of the
linearised scene, and never before t = 0 (the seed, with damping ratios below 1 %, is checked from the start). Started
at the window on such a scene, the check misses the error entirely (configs/extreme/load_reversal.toml: 1e-7 estimated,
5e-3 true). A mesh that leaves its flank in the window (rattle) is checked from t = 0 whatever its damping: where
responses coexist the run-up picks one (docs/numerics.md; tests/extreme/test_rattle_span.py).

Tolerance. Where the span costs little (``TIGHT_FACTOR`` ** (1/8) x its share of the run, DOP853's order, at most
``TIGHT_COST``), the check runs at rtol / ``TIGHT_FACTOR`` and the difference is (1 - 10^-q) of the run's error, q the
statistic's convergence order in rtol; the estimate is :func:`tight_scale` x the difference, 1.33x for the slowest
measured q = ``SLOW_ORDER`` (0.6), so that it is never below the error where q >= 0.6. Measured against DOP853 at rtol
1e-9 (an undamped ISO mesh, tests/extreme/test_tight_estimate.py): RK45, BDF and LSODA converge at q ~ 0.7-0.8 and their
bare difference was 0.80-0.84x the true error, so a min 1.15e-3 of the mean off (RK45, rtol 7e-7) was estimated 0.97e-3
and reported resolved. Where the span is most of the run, a tighter pass would cost 2.3x the run on the seed, so the
check runs at ``LOOSE_FACTOR`` x rtol instead (0.92x the cost) and the estimate is ``LOOSE_SAFETY`` x the difference:
with an error that falls as rtol^p, the difference is (2^p - 1) times the run's error, which is 0.5x for the slowest
convergence measured (p = 0.6, configs/extreme/load_reversal.toml) and 1x at p = 1; faster-converging statistics are
overestimated, never under. When that loose estimate flags a statistic, a tight pass (rtol / 10, same span) confirms it
and its scaled difference is the estimate: a resolved run pays for one cheap pass, a flagged one for both, and a loose
pass that rattles or spikes where the run did not does not turn into a false warning.

Stability-limited runs. An explicit run whose steps are set by stability rather than by its tolerance (fewer than
``STABILITY_LIMITED`` x max|lambda| T / R steps, R the method's stability radius) carries its stiff mode as noise that
the step-size control sustains, and a loose pass of the same method carries noise of the same size: their statistics
agree by chance. Such a run gets the tight pass whatever its span. Measured (a two-stage reducer under 90x its rated
load, DOP853 at rtol 1e-5): the loose pass estimated the window's min and max 4e-5 and 7e-5 of the mean where the truth
is 1.1e-3 and 1.4e-3; the tight pass 1.0e-3 and 1.4e-3 (tests/extreme/test_stability_limited.py). Its run-up carries
the noise at the force's size: the pass starts ``FORGOTTEN`` / sigma before the window, not ``DECAY_SPANS`` / sigma
(tests/extreme/test_stability_runup.py). Radial and axial forces are the tangential one times constants of the stage,
so they share its relative error. A planetary stage is checked over every planet's sun and ring meshes."""

from __future__ import annotations

import math
import time

import numpy as np

from gearcli import diagnostics as dg
from gearcli.core.methods import method as method_info
from gearcli.core.records import record
from gearcli.diagnostics import Diagnostic
from gearcli.model import TorsionalModel
from gearcli.model.outputs import (
    Sampled,
    connector_line_forces,
    mesh_line_forces,
    planet_sun_connectors,
    tangential_force_N,
    tooth_forces,
)
from gearcli.simulate.choice import Choice
from gearcli.simulate.results import ChannelStats, StatisticsError
from gearcli.simulate.solver import STATUS_FINISHED, Integration, integrate
from gearcli.simulate.stats import gapless_meshes, leaves_flank, window_means

TARGET = 1e-3  # of the stage's mean force: min, max, std, the spectrum
MEAN_TARGET = 1e-4  # of the stage's mean force: the mean (module doc, "Targets")
TIGHT_FACTOR = 10.0  # a short check pass runs at rtol / TIGHT_FACTOR
TIGHT_COST = 0.95  # ... when it costs at most this share of the run
LOOSE_FACTOR = 2.0  # a long one at LOOSE_FACTOR x rtol
LOOSE_SAFETY = 2.0  # its difference x this is the estimate
SLOW_ORDER = 0.6  # the slowest convergence of a statistic in rtol, error ~ rtol^SLOW_ORDER (module doc, "Tolerance")
DECAY_SPANS = math.log(100.0)  # an error made this many 1/sigma before the window is 1 % of itself in it
STATISTICS = ("mean", "min", "max", "std", "spectrum")
AMPLITUDE = ("min", "max", "std", "spectrum")  # set by the vibration the solver resolves
LIGHT_DAMPING = 0.05  # damping ratio below which a mode's vibration outlasts the run-up
FORGOTTEN = math.log(100.0 / TARGET)  # e-folds after which a run-up vibration of 100x the mean is below TARGET
STABILITY_LIMITED = 1.25  # an explicit run with fewer steps than this x stability's alone is stability-limited
MIN_RTOL = 1e-13  # the schema's floor of simulation.rtol
MAX_RTOL = 1e-2  # the loosest check pass (the schema's ceiling of simulation.rtol)


@record
class PeakError:
    """The solver's error of a stage's run peak |F_t| (``peak_tangential_N``, ``runup_factor``), estimated as the
    window statistics are: the check pass's peak over the same samples of its span against the run's."""

    stage: int  # 1-based
    peak_N: float  # the run's peak |F_t|
    at_s: float
    error_N: float  # scale x |run peak - check peak|
    relative: float  # error_N / peak_N


@record
class CheckPass:
    """The check pass and the per-stage error estimates (empty where it did not finish)."""

    rtol: float
    from_s: float
    scale: float  # estimate = scale x |check - run|
    nfev: int
    njev: int
    steps: int
    wall_s: float
    status: int
    message: str
    errors: tuple[StatisticsError, ...]
    passes: int = 1  # 2 when a loose check's warning was confirmed by a tight one
    peaks: tuple[PeakError, ...] = ()  # the run's peak |F_t| per stage, where the check pass spans it
    def summary(self) -> dict:
        return {"rtol": self.rtol, "from_s": self.from_s, "estimate_factor": self.scale, "nfev": self.nfev, "njev": self.njev, "steps": self.steps,
                "wall_s": self.wall_s, "finished": self.status == STATUS_FINISHED, "passes": self.passes}


def spectrum(t: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(frequencies Hz, amplitudes) of the detrended, Hann-windowed series (as ``gearcli report`` draws it)."""
    n = t.size
    if n < 4 or t[-1] <= t[0]:
        return np.zeros(0), np.zeros(0)
    dt = (t[-1] - t[0]) / (n - 1)
    s = t - t[0]
    detrended = x - np.polyval(np.polyfit(s, x, 1), s)
    w = np.hanning(n)
    return np.fft.rfftfreq(n, dt), np.abs(np.fft.rfft(detrended * w)) * 2.0 / w.sum()


def _dominant(freqs: np.ndarray, amp: np.ndarray) -> float:
    return float(freqs[1 + int(np.argmax(amp[1:]))]) if amp.size > 1 else 0.0


def _stats(t: np.ndarray, x: np.ndarray) -> ChannelStats:
    """The window statistics of ``x`` at the times ``t``, the mean the integral's as the run reports it."""
    return ChannelStats(float(window_means(t, x, False)[0]), float(x.min()), float(x.max()), float(x.std()))


def target(statistic: str) -> float:
    """The relative target of a window statistic: :data:`MEAN_TARGET` for the mean, :data:`TARGET` else."""
    return MEAN_TARGET if statistic == "mean" else TARGET


def force_reference(mean: float, std: float, static_N: float, floor_N: float = 0.0) -> float:
    """The force a stage's targets refer to: |mean F_t| (the static |F_t| when the mean is 0). A mesh that
    carries no static force (an unloaded train rattling, a mesh whose load is zero) has a window mean that is
    zero but for the run's own noise (1e-4 N on a ±75 N swing), 1e-3 of which no rtol and no number of samples
    reaches: its targets refer to the channel's rms about zero, sqrt(mean² + std²), the size of what it carries,
    but never to less than ``floor_N`` (:func:`force_floors_N`: a stage at rest carries only round-off)."""
    if static_N == 0.0:
        return max(math.hypot(mean, std), floor_N)
    return abs(mean) or abs(static_N)


def force_floors_N(model: TorsionalModel, rtol: float) -> list[float]:
    """Per stage, the least F_t its relative targets refer to: the force the run resolves, the mesh's tangent
    stiffness at its deflection scale h (the atol's: the static deflection, the backlash's half gap, at least 1 um)
    times the absolute tolerance rtol h on its deflection, e K h^e rtol along the line of action. An unloaded stage
    whose F_t stays below it is at rest to the run's accuracy (a zero-load duty step: F_t of 1e-11 N, round-off)
    and has nothing to resolve or to settle; a rattling train lies above it (±75 N; the held-out rattle with the
    ISO law: ±5 N against a floor of 0.74 N, whose min is 2e-3 of its rms off and warned so: the floor taken 1/TARGET
    times larger, 744 N, called it resolved)."""
    scales = model.deflection_scales_m()
    out = []
    for k, (m, h) in enumerate(zip(model.spec.meshes, scales, strict=True)):
        line = m.exponent * m.stiffness_N_m_e * float(h) ** m.exponent * rtol
        out.append(abs(tangential_force_N(model.layout, k, line)))
    return out


def reference_words(reference_N: float, unloaded: bool) -> str:
    """How a warning names the force its relative error refers to (:func:`force_reference`; ``unloaded``: the
    stage carries no static force)."""
    if unloaded:
        return f"the rms {reference_N:.4g} N of the unloaded stage's F_t"
    return f"the mean {reference_N:.4g} N"


def suggested_rtol(rtol: float, relative_error: float, goal: float = TARGET) -> float | None:
    """The rtol that brings an error of ``relative_error`` at ``rtol`` below half the target ``goal``, assuming
    the error falls in proportion to rtol (the slowest order of these statistics, measured), rounded down to
    a power of ten and at least the schema's floor ``MIN_RTOL``; None where even the floor is predicted to leave
    the error above ``goal`` (a run at the floor has no tighter rtol to suggest)."""
    wanted = rtol * 0.5 * goal / max(relative_error, 1e-300)
    if 2.0 * wanted < MIN_RTOL:
        return None
    return max(MIN_RTOL, 10.0 ** math.floor(math.log10(wanted)))


NO_RTOL_RESOLVES = (f"no simulation.rtol down to the schema's floor {MIN_RTOL:g} is predicted to resolve it: take the "
                    "statistic as uncertain by the estimated error")  # where suggested_rtol has none
NONSMOOTH = ("a mesh leaves its flank in the window, where responses can coexist and a tighter rtol (this one predicts "
             "{rtol:g}) may land on another rather than converge: take the statistic as uncertain by the estimated error")


def solver_first(steps: int | None, cap: int, code: str = dg.STATISTICS_UNRESOLVED) -> str:
    """The fix of a sampling warning (``statistics_undersampled``, ``peak_undersampled``) whose statistic the solver
    leaves unresolved too (``code``) by more than the samples' estimate: the solver's noise between the samples reads
    as undersampling, so the steps the samples ask for are the unresolved solution's (a DOP853 run at rtol 1e-3 asked for 310,000 where its samples at
    the rtol named, 1e-7, were resolved at its 20,000: tests/simulate/test_sampling_solver_first.py)."""
    these = f"simulation.steps={steps}" if steps is not None else f"more than the maximum {cap} steps"
    return (f"the solver leaves it unresolved too ({code}) and these samples carry its error: take that warning's "
            f"simulation.rtol first, whose run says what its samples need (these ask for {these})")


def start_time(choice: Choice, window: tuple[float, float], spans: float = DECAY_SPANS) -> float:
    """Where the check pass starts: the window start, earlier in a lightly damped scene, ``spans`` e-folds (module doc)."""
    ev = np.concatenate([choice.at_full_load.eigenvalues, choice.at_operating_point.eigenvalues])
    osc = ev[np.abs(ev.imag) > 1e-9 * np.maximum(np.abs(ev), 1.0)]
    if osc.size == 0:
        return window[0]
    sigma = float(np.min(-osc.real))
    if sigma <= 0:
        return 0.0
    return max(0.0, window[0] - spans / sigma)


def stage_error(k: int, t: np.ndarray, ft_run: np.ndarray, ft_check: np.ndarray, static_N: float,
                rtol: float, scale: float = 1.0, floor_N: float = 0.0) -> StatisticsError:
    """The error estimate of stage ``k`` (0-based) of the run from its F_t and the check pass's over the
    window samples: ``scale`` x the difference of each statistic."""
    a, b = _stats(t, ft_run), _stats(t, ft_check)
    fa, aa = spectrum(t, ft_run)
    fb, ab = spectrum(t, ft_check)
    d = scale
    err = {"mean": abs(a.mean - b.mean) * d, "min": abs(a.min - b.min) * d, "max": abs(a.max - b.max) * d,
           "std": abs(a.std - b.std) * d, "spectrum": float(np.max(np.abs(aa - ab))) * d if aa.size else 0.0}
    # a mesh that carries nothing in the run's window (no load, teeth apart: F_t = 0 throughout) is measured
    # against the check pass's force, so an error is a finite fraction of what the tighter pass sees (1 when
    # only it sees contact) and never inf, which no JSON can hold; both passes at zero: no error at all
    reference = force_reference(a.mean, a.std, static_N, floor_N) or math.hypot(b.mean, b.std)
    return _statistics_error(k, err, reference, rtol, _dominant(fa, aa), _dominant(fb, ab))


def _statistics_error(k: int, err: dict[str, float], reference: float, rtol: float, dominant_Hz: float,
                      check_dominant_Hz: float) -> StatisticsError:
    """Stage ``k``'s (0-based) estimate from its statistics' errors ``err`` (N) over the force ``reference``."""
    rel = {q: (v / reference if reference > 0 else 0.0) for q, v in err.items()}
    unresolved = tuple(q for q in STATISTICS if rel[q] > target(q))
    if any(q in AMPLITUDE for q in unresolved):  # one vibration error moves them all: name them together
        unresolved = tuple(q for q in STATISTICS if q in unresolved or q in AMPLITUDE)
    suggestion = None
    if unresolved and all(math.isfinite(rel[q]) for q in STATISTICS):  # the rtol that resolves every statistic
        each = [suggested_rtol(rtol, rel[q], target(q)) for q in STATISTICS]
        suggestion = None if None in each else min(r for r in each if r is not None)
    return StatisticsError(
        stage=k + 1, reference_N=reference, target_relative=TARGET, mean_target_relative=MEAN_TARGET,
        tangential_N=ChannelStats(err["mean"], err["min"], err["max"], err["std"]), spectrum_N=err["spectrum"],
        relative={q: rel[q] for q in STATISTICS}, dominant_frequency_Hz=dominant_Hz,
        check_dominant_frequency_Hz=check_dominant_Hz, unresolved=unresolved, suggested_rtol=suggestion,
        resolved=not unresolved)


def planet_suns(model: TorsionalModel, t: np.ndarray, Y: np.ndarray, gear: str = "sun") -> dict[int, list]:
    """Stage (0-based) -> its planets' sun-mesh F_t (N) at ``t``, planet 1 first; {} without planetary stages. A
    planetary stage's dynamic and run-up factors are its most loaded planet's (:mod:`gearcli.simulate.planet_stats`),
    its channels planet 1's: the check compares every planet, so the factors it prints are covered too (``gear``
    "ring": their ring meshes')."""
    lay = model.layout
    return {k: [tooth_forces(lay, k, f)[0] for f in connector_line_forces(lay, t, Y, conns)]
            for k, conns in planet_sun_connectors(lay, gear).items()}


def worst_planet(stage: StatisticsError, planets: list[StatisticsError], rtol: float, rings: tuple = ()) -> StatisticsError:
    """A planetary stage's estimate over its planets' sun meshes (and ``rings``, their ring meshes): each statistic's
    largest error (N) over them (planet 1's, the stage's channels, among them), over the mean of the planets' sun-mesh
    reference forces (a loaded stage's: the static force per planet, which its dynamic and run-up factors refer to)."""
    every = [stage, *planets, *rings]
    err = {q: max(float(getattr(e.tangential_N, q)) for e in every) for q in ("mean", "min", "max", "std")}
    err["spectrum"] = max(e.spectrum_N for e in every)
    reference = float(np.mean([e.reference_N for e in planets])) if planets else stage.reference_N
    return _statistics_error(stage.stage - 1, err, reference, rtol, stage.dominant_frequency_Hz,
                             stage.check_dominant_frequency_Hz)


def over_planets(model: TorsionalModel, errors: tuple[StatisticsError, ...], suns: dict[int, list[np.ndarray]],
                  fine_suns: dict[int, list[np.ndarray]], tw: np.ndarray, n_check: int, rtol: float,
                  scale: float, floors: list[float], rings: tuple = ({}, {})) -> tuple[StatisticsError, ...]:
    """``errors`` with each planetary stage's replaced by :func:`worst_planet` over its planets' sun meshes: the
    run's F_t ``suns`` (every sample of the run) against the check's ``fine_suns`` (its ``n_check`` samples, the
    window's ``tw`` last), each referred to no less than the stage's ``floors`` (:func:`force_floors_N`: an
    unloaded stage's planets at rest carry round-off, 1e-10 N, which no rtol resolves to 1e-3); ``rings``: the run's
    and the check's ring-mesh F_t alike (printed too: tests/extreme/test_planet_ring_estimate.py)."""
    n_w = tw.size
    out = []
    for e in errors:
        k = e.stage - 1
        if k not in suns:
            out.append(e)
            continue
        static = model.spec.meshes[k].static_tangential_N
        n_run = suns[k][0].size
        each = [stage_error(k, tw, a[n_run - n_w:], b[n_check - n_w:], static, rtol, scale, floors[k])
                for a, b in zip(suns[k], fine_suns[k], strict=True)]
        ring = tuple(stage_error(k, tw, a[n_run - n_w:], b[n_check - n_w:], static, rtol, scale, floors[k])
                     for a, b in zip(rings[0].get(k, ()), rings[1].get(k, ()), strict=True))
        out.append(worst_planet(e, each, rtol, ring))
    return tuple(out)


def peak_error(k: int, t: np.ndarray, ft_run: np.ndarray, ft_check: np.ndarray, i_from: int,
               scale: float = 1.0) -> PeakError | None:
    """Stage ``k``'s (0-based) run peak |F_t| (over the run's samples ``ft_run`` at ``t``) and its error from the check
    pass's F_t ``ft_check`` at the samples ``i_from``, ``i_from`` + 1, ...: ``scale`` x the difference between the run's
    peak and the check's over those samples; None where the run's peak lies outside them. (The check's peak, not its
    value at the run's peak sample: a stability-limited run's peak can be a noise spike where the true peak lies
    elsewhere; wind_turbine_gearbox stage 3, 1.09e-3 off, read 9.7e-3 at the spike's sample.)"""
    a = np.abs(ft_run)
    if a.size == 0 or not float(a.max()) > 0.0 or ft_check.size == 0:
        return None
    i = int(np.argmax(a))
    if not i_from <= i < i_from + ft_check.size:
        return None
    peak = float(a[i])
    error = scale * abs(peak - float(np.max(np.abs(ft_check))))
    return PeakError(k + 1, peak, float(t[i]), error, error / peak)


def peak_warnings(ref: CheckPass, run_rtol: float, method: str) -> list[Diagnostic]:
    """``peak_unresolved``, one per stage whose run peak |F_t| the check pass finds off by more than
    :data:`TARGET` of it (the run's ``peak_tangential_N`` and ``runup_factor``)."""
    out = []
    for p in ref.peaks:
        if p.relative <= TARGET:
            continue
        rtol = suggested_rtol(run_rtol, p.relative)
        fix = f"--set simulation.rtol={rtol:g} would resolve it" if rtol is not None else NO_RTOL_RESOLVES
        out.append(dg.warning(
            dg.PEAK_UNRESOLVED,
            f"stage {p.stage}: the run's peak |F_t| {p.peak_N:.5g} N (at {p.at_s:.4g} s) and its run-up factor are not "
            f"resolved by {method} at the run's rtol: estimated error up to {p.error_N:.3g} N ({p.relative:.2g} of "
            f"it, target {TARGET:g}); {fix}",
            stage=p.stage, peak_N=p.peak_N, at_s=p.at_s, estimated_error_N=p.error_N, relative_error=p.relative,
            rtol=rtol))
    return out


@record
class Plan:
    """The span and tolerance of the check pass (module doc), fixed by the samples, the run's rtol, the
    method choice and the window, so known before the run."""

    i_w: int  # first window sample
    i_s: int  # the sample the check pass starts from
    rtol: float
    scale: float


def stability_limited(choice: Choice, method: str, steps: int) -> bool:
    """An explicit run whose accepted steps are within :data:`STABILITY_LIMITED` of what stability alone takes
    (max|lambda| T over the method's stability radius): its step size is set by stability, not by its tolerance, and
    the stiff mode it steps over lives on as noise that a loose check pass of the same method repeats by chance
    (module doc, "Stability-limited runs")."""
    m = method_info(method)
    if m.implicit or steps <= 0 or not choice.indicator > 0:
        return False
    return steps < STABILITY_LIMITED * choice.indicator / m.stability_radius


def tight_rtol(rtol: float, mixed: bool = False) -> float:
    """The tight check pass's rtol: the run's / :data:`TIGHT_FACTOR`, not below the schema's floor; a run of several
    methods (``mixed``: ``auto`` changed course, :mod:`gearcli.simulate.course`) one factor tighter again. The check
    integrates with the run's last method, whose error at the run's rtol may be many times another segment's (a
    lightly damped scene: DOP853's window max 8.5 N off at rtol 1e-5 where Radau's at 1e-4 is 6.5 N off): at
    rtol / 10 the check then carries an error as large as the run's and their difference says little (1.6 N
    estimated); at rtol / 100 (0.06 N off) the difference is the run's error again."""
    return max(rtol / (TIGHT_FACTOR * (TIGHT_FACTOR if mixed else 1.0)), MIN_RTOL)


def tight_scale(rtol: float, check_rtol: float) -> float:
    """The factor on a tighter check pass's difference that makes it the run's error, not less: with an error that
    falls as rtol^q, the difference is (1 - (check_rtol/rtol)^q) of the run's error; q = :data:`SLOW_ORDER`, the
    slowest measured, gives 1.33 at rtol / 10 and 1.07 at rtol / 100 (module doc, "Tolerance"). A check at the run's
    own rtol (the schema's floor) estimates nothing more: 1."""
    ratio = check_rtol / rtol
    return 1.0 / (1.0 - ratio ** SLOW_ORDER) if ratio < 1.0 else 1.0


def plan(t_eval: np.ndarray, rtol: float, choice: Choice, window: tuple[float, float],
         stability_bound: bool = False, mixed: bool = False, impacting: bool = False) -> Plan:
    """Where the check pass starts and at which tolerance (module doc); ``stability_bound``: the run is
    :func:`stability_limited` (then always the tight pass); ``mixed``: the run changed course (then always the tight
    pass, at :func:`tight_rtol`'s mixed tolerance: a loose pass of the last method says nothing of the first's);
    ``impacting``: a mesh leaves its flank in the window (:func:`~gearcli.simulate.stats.leaves_flank`): from t = 0."""
    mask = (t_eval >= window[0] - 1e-9 * max(1.0, window[1]))
    i_w = int(np.argmax(mask))
    t_start = 0.0 if impacting else start_time(choice, window, FORGOTTEN if stability_bound else DECAY_SPANS)
    i_s = min(i_w, int(np.searchsorted(t_eval, t_start, side="right")) - 1)
    i_s = max(i_s, 0)
    share = (t_eval[-1] - t_eval[i_s]) / max(t_eval[-1] - t_eval[0], 1e-300)
    if mixed:
        return Plan(i_w, i_s, (r := tight_rtol(rtol, mixed=True)), tight_scale(rtol, r))
    if TIGHT_FACTOR ** 0.125 * share <= TIGHT_COST or rtol * LOOSE_FACTOR > MAX_RTOL or stability_bound:
        return Plan(i_w, i_s, (r := tight_rtol(rtol)), tight_scale(rtol, r))
    return Plan(i_w, i_s, rtol * LOOSE_FACTOR, LOOSE_SAFETY)


#: the check pass's step ceiling, as a share of the run's (:func:`gearcli.simulate.solver.step_ceiling`): where the
#: ceiling sets a run's steps (a stability-limited run whose stiff mode is at rest), a tighter rtol alone takes the
#: same steps and its difference shows nothing (a run-up peak 1.5e-3 off, estimated resolved: tests/extreme/
#: test_peak_unresolved.py); half the ceiling refines those steps too. Elsewhere the error control keeps the steps
#: below it and the pass is the one its rtol gives.
CHECK_CEILING = 0.5


def one_pass(model: TorsionalModel, t_eval: np.ndarray, y_start: np.ndarray, idx: np.ndarray, method: str,
             rtol: float, max_nfev: int, engine: str) -> tuple[Integration, list[np.ndarray] | None, float]:
    """One check pass from sample ``idx[0]`` (state ``y_start``) to sample ``idx[-1]``, sampled at ``t_eval[idx]``
    (dense output costs DOP853 three evaluations a step where it samples): the integration, the meshes' line forces
    at those samples (None when it did not finish) and the wall time."""
    t0 = time.perf_counter()
    t_check = t_eval[idx]
    fine = integrate(model, t_check, method, rtol, y0=y_start, t0=float(t_check[0]), max_nfev=max_nfev,
                     watch_energy=False,  # the run itself was watched
                     engine=engine,  # the run's engine: scipy's steps either way
                     ceiling=CHECK_CEILING)
    forces = None
    if fine.status == STATUS_FINISHED:
        forces = mesh_line_forces(model.layout, t_check, fine.y)
    return fine, forces, time.perf_counter() - t0


def check_pass(model: TorsionalModel, run: Integration, choice: Choice, window: tuple[float, float], *,
               max_nfev: int, sampled: Sampled | None = None, mixed: bool = False) -> CheckPass:
    """The check pass and its per-stage error estimates (module doc). ``sampled``: the run's own samples at
    ``run.t`` when the caller has them (their window part is the run's side of the comparison; the channels
    are sample by sample, so the slice equals sampling the window again); ``mixed``: the run changed course
    (:func:`tight_rtol`)."""
    lay = model.layout
    t_eval = run.t
    p = plan(t_eval, run.rtol, choice, window, stability_limited(choice, run.method, run.steps), mixed,
             sampled is not None and leaves_flank(sampled, window, gapless_meshes(model.spec)))
    i_w, i_s, rtol, scale = p.i_w, p.i_s, p.rtol, p.scale
    t0 = time.perf_counter()
    tw = t_eval[i_w:]
    if sampled is None:
        run_all = mesh_line_forces(lay, t_eval, run.y)
    else:
        run_all = [m.line_force_N for m in sampled.meshes]
    run_forces = [f[i_w:] for f in run_all]
    ft_all = [tooth_forces(lay, k, f)[0] for k, f in enumerate(run_all)]
    suns = planet_suns(model, t_eval, run.y)  # a planetary stage's peak is its most loaded planet's
    worst = {k: int(np.argmax([np.max(np.abs(f)) if f.size else 0.0 for f in fs])) for k, fs in suns.items()}
    for k, j in worst.items():
        ft_all[k] = suns[k][j]
    # every sample of the span: the window's, and where a run's peak lies before the window, the run-up's too (its
    # dense output costs DOP853 three evaluations a step: +420 on the seed's 4426, so only when a peak is there)
    in_runup = any(i_s <= int(np.argmax(np.abs(f))) < i_w for f in ft_all if f.size)
    idx = np.arange(i_s if in_runup else i_w, t_eval.size)
    if idx[0] != i_s:
        idx = np.concatenate(([i_s], idx))
    nfev = njev = steps = 0
    passes = 0
    floors = force_floors_N(model, run.rtol)
    while True:
        passes += 1
        fine, fine_forces, _ = one_pass(model, t_eval, run.y[:, i_s], idx, run.method, rtol, max_nfev, run.engine)
        nfev, njev, steps = nfev + fine.nfev, njev + fine.njev, steps + fine.steps
        status, message = fine.status, fine.message
        errors: tuple[StatisticsError, ...] = ()
        peaks: tuple[PeakError, ...] = ()
        if status != STATUS_FINISHED or fine_forces is None:
            break
        errors = tuple(stage_error(k, tw, tooth_forces(lay, k, run_forces[k])[0],
                                   tooth_forces(lay, k, fine_forces[k][idx.size - tw.size:])[0],
                                   m.static_tangential_N, run.rtol, scale, floors[k])
                       for k, m in enumerate(model.spec.meshes))
        fine_ft = [tooth_forces(lay, k, f)[0] for k, f in enumerate(fine_forces)]
        if suns:
            fine_suns = planet_suns(model, t_eval[idx], fine.y)
            rings = (planet_suns(model, t_eval, run.y, "ring"), planet_suns(model, t_eval[idx], fine.y, "ring"))
            errors = over_planets(model, errors, suns, fine_suns, tw, idx.size, run.rtol, scale, floors, rings)
            for k, j in worst.items():
                fine_ft[k] = fine_suns[k][j]
        lead = 1 if idx.size > 1 and idx[1] != idx[0] + 1 else 0  # the span's first sample alone, then contiguous
        peaks = tuple(e for k in range(len(model.spec.meshes))
                      if (e := peak_error(k, t_eval, ft_all[k], fine_ft[k][lead:], int(idx[lead]), scale)) is not None)
        if rtol <= run.rtol or all(e.resolved for e in errors):  # a tight pass, or a loose one that flags nothing
            break
        # the loose check flags a statistic: confirm it with a tight pass over the same span, whose difference
        # is the run's error to first order (a loose pass that rattles differently overstates it 1e5-fold:
        # configs/concrete_mixer_drivetrain.toml, stage 1 max estimated 4.3 of the mean, true 3e-5)
        rtol = tight_rtol(run.rtol)
        scale = tight_scale(run.rtol, rtol)
    if status == STATUS_FINISHED:  # the peaks before the span: a short tight pass of their own
        before, cost = runup_peaks(model, run, choice, ft_all, i_s, max_nfev, mixed, worst)
        peaks = tuple(sorted(peaks + before, key=lambda x: x.stage))
        nfev, njev, steps = nfev + cost[0], njev + cost[1], steps + cost[2]
    wall = time.perf_counter() - t0
    return CheckPass(rtol, float(t_eval[i_s]), scale, nfev, njev, steps, wall, status, message, errors, passes,
                     peaks if status == STATUS_FINISHED else ())


def runup_peaks(model: TorsionalModel, run: Integration, choice: Choice, ft_run: list[np.ndarray], i_s: int,
                max_nfev: int, mixed: bool = False, planet: dict[int, int] | None = None
                ) -> tuple[tuple[PeakError, ...], tuple[int, int, int]]:
    """The error of the run peaks |F_t| (stage F_t over the run's samples ``ft_run``) that lie before the check pass's
    span (sample ``i_s``): one pass at rtol / ``TIGHT_FACTOR`` from where the errors made earlier have decayed to 1 %
    of themselves (``DECAY_SPANS`` / sigma before the earliest such peak, as the window's check starts; t = 0 in a
    lightly damped scene) to just past the last one; its difference is the run's error to first order. Returns the
    estimates and the pass's (nfev, njev, steps)."""
    t = run.t
    early = [(k, int(np.argmax(np.abs(f)))) for k, f in enumerate(ft_run) if f.size and np.abs(f).max() > 0.0]
    early = [(k, i) for k, i in early if i < i_s]
    if not early:
        return (), (0, 0, 0)
    first, last = min(i for _, i in early), max(i for _, i in early)
    start = start_time(choice, (float(t[first]), float(t[-1])))
    i_0 = max(0, min(first, int(np.searchsorted(t, start, side="right")) - 1))
    idx = np.arange(i_0, min(t.size, last + 2))  # to just past the last peak
    if idx.size < 2:
        return (), (0, 0, 0)
    rtol = tight_rtol(run.rtol, mixed)
    fine, forces, _ = one_pass(model, t, run.y[:, i_0], idx, run.method, rtol, max_nfev, run.engine)
    cost = (fine.nfev, fine.njev, fine.steps)
    if fine.status != STATUS_FINISHED or forces is None:
        return (), cost
    lay = model.layout
    fine_ft = [tooth_forces(lay, k, f)[0] for k, f in enumerate(forces)]
    if planet:  # ``planet``: stage -> the planet whose sun mesh ``ft_run`` holds (its most loaded)
        fine_suns = planet_suns(model, t[idx], fine.y)
        for k, j in planet.items():
            fine_ft[k] = fine_suns[k][j]
    out = (peak_error(k, t, ft_run[k], fine_ft[k], i_0, tight_scale(run.rtol, rtol)) for k, _ in early)
    return tuple(p for p in out if p is not None), cost


def means_rtol(ref: CheckPass) -> float | None:
    """The tighter rtol at which an ``auto`` run is repeated, or None (docs/numerics.md "Choosing the method: auto").

    When the check pass finds every amplitude statistic of every stage resolved and only means beyond
    :data:`MEAN_TARGET`, ``auto`` repeats the run at the rtol that resolves them (:func:`suggested_rtol`, one
    decade for an error up to 5x the target): the repeat costs about 1.3x the run per decade and returns a run
    resolved in every statistic. Where amplitude statistics are unresolved too, the run stands with its
    ``statistics_unresolved`` warning, whose suggested rtol resolves the means as well: a repeat for the means
    alone would still be warned, and one for everything can cost many times the run
    (configs/extreme/stiff_hertz_10000x.toml suggests rtol 1e-9)."""
    if ref.status != STATUS_FINISHED or not ref.errors:
        return None
    if not any("mean" in e.unresolved for e in ref.errors) or any(set(e.unresolved) - {"mean"} for e in ref.errors):
        return None
    wanted = [e.suggested_rtol for e in ref.errors if e.suggested_rtol is not None]
    return min(wanted) if wanted else None


def tightened_warning(run: Integration, ref: CheckPass, finer: float) -> Diagnostic:
    """What an ``auto`` run repeated at ``finer`` says about the run it replaced (``run``, checked by ``ref``)."""
    rtol, method = run.rtol, run.method
    worst = max(ref.errors, key=lambda e: e.relative["mean"])
    return dg.warning(
        dg.RTOL_TIGHTENED,
        f"method = \"auto\" ran at rtol {finer:g} instead of {rtol:g}: at rtol {rtol:g} {method}'s window mean of "
        f"F_t on stage {worst.stage} was estimated {worst.tangential_N.mean:.3g} N off ({worst.relative['mean']:.2g} "
        f"of the mean, target {MEAN_TARGET:g}), every other statistic resolved ({run.nfev + ref.nfev} evaluations "
        "of that run and its check pass spent before the repeat)",
        stage=worst.stage, rtol=rtol, tightened_rtol=finer, relative_error=float(worst.relative["mean"]),
        discarded_nfev=run.nfev + ref.nfev)


_NAMES = {"mean": "mean", "min": "min", "max": "max", "std": "std", "spectrum": "spectrum peaks"}


def warnings(ref: CheckPass, method: str, unloaded: frozenset[int] = frozenset(),
             nonsmooth: bool = False) -> list[Diagnostic]:
    """``statistics_unresolved``, one per stage with a statistic beyond the target (none when resolved); ``unloaded``:
    the stages (1-based) without static force (:func:`force_reference`); ``nonsmooth``: :data:`NONSMOOTH`'s case."""
    if ref.status != STATUS_FINISHED:
        return [dg.warning(dg.STATISTICS_UNRESOLVED, f"the error of the window statistics could not be estimated: "
                           f"the check pass at rtol {ref.rtol:g} stopped ({ref.message}); min, max, std and "
                           "the spectrum are unverified", stage=None, statistics=list(STATISTICS))]
    out = []
    for e in ref.errors:
        if not e.unresolved:
            continue
        names = ", ".join(_NAMES[q] for q in e.unresolved)
        worst = max(e.unresolved, key=lambda q: e.relative[q] / target(q))
        absolute = e.spectrum_N if worst == "spectrum" else getattr(e.tangential_N, worst)
        fix = (NONSMOOTH.format(rtol=e.suggested_rtol) if nonsmooth and e.suggested_rtol else
               f"--set simulation.rtol={e.suggested_rtol:g} would resolve it" if e.suggested_rtol else NO_RTOL_RESOLVES)
        moved = ""
        if "spectrum" in e.unresolved and abs(e.dominant_frequency_Hz - e.check_dominant_frequency_Hz) > 0:
            moved = (f"; the dominant frequency {e.dominant_frequency_Hz:.4g} Hz is "
                     f"{e.check_dominant_frequency_Hz:.4g} Hz at rtol {ref.rtol:g}")
        out.append(dg.warning(
            dg.STATISTICS_UNRESOLVED,
            f"stage {e.stage}: F_t {names} not resolved by {method} at the run's rtol: estimated error up to "
            f"{absolute:.3g} N ({e.relative[worst]:.2g} of {reference_words(e.reference_N, e.stage in unloaded)}, "
            f"target {target(worst):g}){moved}; {fix}",
            stage=e.stage, statistics=list(e.unresolved), estimated_error_N=float(absolute),
            relative_error=float(e.relative[worst]), rtol=e.suggested_rtol))
    return out

