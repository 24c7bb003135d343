"""Work-precision study: numerical error of the simulation against its run time.

The scene runs over a ladder of relative tolerances for several methods. Each run's error is
measured against a reference run at a much tighter tolerance, and the reference is itself checked by
a second tight run with a different method (explicit against implicit): the largest relative
difference between the two is the reference's ``uncertainty``; each quantity's own difference is the
reference's resolution of it. An error below its quantity's resolution cannot be resolved and is flagged
``below_reference_resolution`` (its number is kept, but it is only an upper bound of nothing: the true error
may be anywhere below that resolution).

A run meets a requested accuracy when ``max(error, uncertainty) <= accuracy`` for the three compared
quantities (window-mean output speed, per-stage mean F_t, per-stage run-up peak |F_t|).
The recommended setting is the cheapest run that meets it. Its cost is ``nfev`` times its method's
median wall time per evaluation over the ladder rather than its own wall time: two neighbouring rungs
often differ by a few milliseconds, less than the timing noise of one run, and the pooled rate keeps
the choice repeatable while still weighing an implicit method's dearer evaluations (Jacobians, LU).
"""

from __future__ import annotations

import statistics
from collections.abc import Callable, Iterable, Mapping

from gearcli.core.cost import EXPLICIT_CAP
from gearcli.core.methods import method as method_info
from gearcli.core.records import record
from gearcli.errors import GearcliError, RunTooLong, SimulationError, StudyTooLong
from gearcli.report.result import QUANTITIES, AccuracyRun, AccuracyStudy, ReferenceRun, RunMetrics
from gearcli.simulate.results import SimulationResult

DEFAULT_RTOLS = (1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9)
#: when a method picked by "auto" is also on the ladder, the other method of its family runs instead
SAME_FAMILY = {"DOP853": "RK45", "RK45": "DOP853", "Radau": "BDF", "BDF": "Radau", "LSODA": "BDF"}

RunFn = Callable[[str, float], SimulationResult]  # (method, rtol) -> result (series not needed)
ProgressFn = Callable[[str, int, int], None]  # (label, runs done, runs planned)


@record
class LadderSpec:
    """What the study runs.

    ``reference``/``check``: (method, rtol) of the reference and of its independent check. ``None``
    picks DOP853 at 1e-12 checked by Radau at 1e-10: an explicit high-order method at a tight
    tolerance is the cheapest accurate reference on these scenes, stiff ones included (on
    configs/stiff_linear_mesh.toml it takes 2.5 s against 12 s for Radau at 1e-11, and the two agree to
    6e-11). Only when the scene's stiffness indicator max|λ|·T exceeds ``explicit_reference_limit``
    (stability alone would then cost DOP853 on scipy more than ~2 max|λ|·T = 4e5 evaluations, ~4 s) times
    the explicit reference's speed-up on the engine that runs it (``explicit_speedup``: the compiled
    engine's, :func:`gearcli.core.cost.compiled_speedup`, where the ladder runs DOP853 compiled; the same
    seconds then buy that many times the evaluations) does the pair become Radau at 1e-11 checked by BDF at
    1e-10 (so too where DOP853's stability alone would exceed the explicit budget, ``gearcli.core.cost.EXPLICIT_CAP``
    evaluations, which refuses the run) (BDF runs on scipy only: on configs/stiff_linear_mesh.toml, max|λ|·T = 2.45e5, that check alone
    took 15 s of CPU and agreed with its reference to 1e-7 only, where the compiled DOP853/Radau pair takes
    ~0.3 s). ``max_run_s``: once a run of a method takes longer, its tighter rungs are skipped (a note says
    so), so a stiff scene cannot run for hours.
    """

    rtols: tuple[float, ...] = DEFAULT_RTOLS
    methods: tuple[str, ...] = ("auto", "DOP853", "Radau")
    reference: tuple[str, float] | None = None
    check: tuple[str, float] | None = None
    max_run_s: float = 15.0
    explicit_reference_limit: float = 2e5

    def reference_pair(self, stiffness_indicator: float | None = None, explicit_speedup: float = 1.0
                       ) -> tuple[tuple[str, float], tuple[str, float]]:
        dop = method_info("DOP853")  # beyond its stability budget an explicit run is refused (guards.require_feasible)
        feasible = EXPLICIT_CAP * dop.stability_radius / dop.evals_per_step
        limit = min(self.explicit_reference_limit * max(explicit_speedup, 1.0), feasible)
        stiff = stiffness_indicator is not None and stiffness_indicator > limit
        ref = self.reference or (("Radau", 1e-11) if stiff else ("DOP853", 1e-12))
        check = self.check or (("BDF", 1e-10) if stiff else ("Radau", 1e-10))
        return ref, check


# ------------------------------------------------------------------------------------------ errors
#: a window-mean force below this fraction of its run-up peak is a zero load (an unloaded train's mean F_t is round-off,
#: ~1e-11 N): its error is measured against that fraction of the peak, the force scale the solver's rtol controls
ZERO_MEAN_OF_PEAK = 1e-3


def _rel(value: float, ref: float, scale: float) -> float:
    return abs(value - ref) / (abs(ref) if ref != 0 else max(abs(scale), 1.0))


def _rel_mean(value: float, ref: float, peak: float) -> float:
    """The error of a window-mean force relative to the mean, or to ``ZERO_MEAN_OF_PEAK`` of the run-up peak where
    the mean is smaller (a loaded train's mean is its static force, far above; 1 N where both are 0)."""
    scale = max(abs(ref), ZERO_MEAN_OF_PEAK * abs(peak))
    return abs(value - ref) / (scale if scale > 0 else 1.0)


def relative_errors(m: RunMetrics, ref: RunMetrics) -> dict[str, float]:
    """Relative errors of ``m`` against ``ref``; forces: the largest over the stages."""
    speed = _rel(m.output_speed_deg_s, ref.output_speed_deg_s, 1.0)
    mean = max((_rel_mean(a, b, p) for a, b, p in zip(m.mean_tangential_N, ref.mean_tangential_N,
                                                    ref.peak_tangential_N, strict=True)), default=0.0)
    peak = max((_rel(a, b, 1.0) for a, b in zip(m.peak_tangential_N, ref.peak_tangential_N, strict=True)), default=0.0)
    return {"speed": speed, "mean_force": mean, "peak_force": peak}


def meets(errors: Mapping[str, float | None], uncertainty: float, accuracy: float) -> bool:
    """True when every error, or the reference's uncertainty where larger, is within ``accuracy``."""
    return all(e is not None and max(e, uncertainty) <= accuracy for e in errors.values())


# ------------------------------------------------------------------------------------------- plan
def ladder_method(method: str, auto_choice: str | None, methods: Iterable[str],
                  engine_methods: Iterable[str] | None = None) -> str:
    """A method that "auto" resolves to, when "auto" is also on the ladder, is swapped for its family
    sibling (DOP853 <-> RK45, Radau <-> BDF), so that no setting runs twice; not for a sibling the engine that
    runs the ladder cannot run (``engine_methods``: the compiled engine's DOP853, RK45 and Radau; None: every
    method), which would run on scipy at ~10-40x the price of every other rung (BDF: 37 s of CPU on
    configs/stiff_linear_mesh.toml's three tightest rungs, where the compiled Radau takes 0.1 s for all seven).
    The column then keeps its method and repeats auto's rungs where auto resolved to it."""
    if method != "auto" and method == auto_choice and "auto" in methods:
        sibling = SAME_FAMILY.get(method, method)
        runs_on = None if engine_methods is None else tuple(engine_methods)
        if runs_on is None or sibling in runs_on or method not in runs_on:
            return sibling
    return method


def ladder_methods(methods: Iterable[str], auto_choice: str | None,
                   engine_methods: Iterable[str] | None = None) -> tuple[str, ...]:
    methods = tuple(methods)
    out: list[str] = []
    for m in methods:
        m = ladder_method(m, auto_choice, methods, engine_methods)
        if m not in out:
            out.append(m)
    return tuple(out)


def same_rtol(a: float, b: float) -> bool:
    return abs(a - b) <= 1e-9 * max(abs(a), abs(b))


# ------------------------------------------------------------------------------------------- runs
Outcome = SimulationResult | str  # a result, or why there is none


def reference_run(ref: SimulationResult, check: SimulationResult, ref_rtol: float,
                  check_rtol: float) -> ReferenceRun:
    ref_m = RunMetrics.of(ref)
    differences = relative_errors(RunMetrics.of(check), ref_m)
    return ReferenceRun(
        method=ref.solver.method, rtol=ref_rtol, wall_s=ref.solver.wall_s, nfev=ref.solver.nfev,
        check_method=check.solver.method, check_rtol=check_rtol, check_wall_s=check.solver.wall_s,
        check_nfev=check.solver.nfev, uncertainty=max(differences.values()), differences=differences,
        metrics=ref_m, window_s=(float(ref.window_s[0]), float(ref.window_s[1])),
    )


def measure(sim: SimulationResult, method: str, rtol: float, ref: ReferenceRun, accuracy: float,
            file_settings: bool) -> AccuracyRun:
    errors = relative_errors(RunMetrics.of(sim), ref.metrics)
    return AccuracyRun(
        method=method, method_used=sim.solver.method, rtol=rtol, wall_s=sim.solver.wall_s, nfev=sim.solver.nfev,
        njev=sim.solver.njev, steps=sim.solver.steps, error_speed=errors["speed"],
        error_mean_force=errors["mean_force"], error_peak_force=errors["peak_force"],
        below_reference_resolution={q: errors[q] < ref.resolution(q) for q in QUANTITIES},
        meets_accuracy=meets(errors, ref.uncertainty, accuracy), file_settings=file_settings,
        engine=sim.solver.engine,
    )


def failed(method: str, rtol: float, reason: str, file_settings: bool) -> AccuracyRun:
    return AccuracyRun(method, method, rtol, 0.0, 0, 0, 0, None, None, None,
                       {q: False for q in QUANTITIES}, False, file_settings, reason)


class _Runner:
    """Runs settings one by one, counting them for the progress callback; failures become text."""

    def __init__(self, run: RunFn, progress: ProgressFn | None, total: int):
        self.run, self.tick, self.total, self.done = run, progress or (lambda *a: None), total, 0

    def __call__(self, method: str, rtol: float, role: str = "") -> Outcome:
        self.tick(f"{role + ' ' if role else ''}{method} rtol {rtol:g}", self.done, self.total)
        self.done += 1
        try:
            return self.run(method, rtol)
        except StudyTooLong:  # the study's own budget: it ends the study (exit 2), not just this run
            raise
        except RunTooLong as exc:
            if role:  # the reference or its check out of its run budget: no study without it (exit 2)
                raise StudyTooLong(f"the accuracy study's {role} run ({method}, rtol {rtol:g}) is out of its "
                                   f"computing budget: {exc}; use --quick (one run)") from None
            return str(exc)
        except GearcliError as exc:
            return str(exc)


def accuracy_study(
    run: RunFn,
    *,
    file_method: str,
    file_rtol: float,
    accuracy: float = 1e-4,
    spec: LadderSpec = LadderSpec(),
    auto_choice: str | None = None,
    stiffness_indicator: float | None = None,
    explicit_speedup: float = 1.0,
    engine_methods: tuple[str, ...] | None = None,
    progress: ProgressFn | None = None,
) -> AccuracyStudy:
    """Run the ladder (auto first, to learn what it resolves to), the file's own settings when they
    are not a rung, then the reference and its check; measure every run against the reference.
    ``auto_choice`` (what "auto" resolved to in the file's own run: the sibling swap's fallback when none of
    auto's rungs ran) and ``stiffness_indicator`` (max|λ|·T) come from the file's own run when known;
    ``explicit_speedup``: what the engine that runs the explicit reference saves over scipy
    (:meth:`LadderSpec.reference_pair`); ``engine_methods``: the methods the engine that runs the ladder integrates
    (:func:`ladder_method`; None: every method). Raises SimulationError when the reference or its check fails."""
    rtols = sorted(spec.rtols, reverse=True)
    in_ladder = file_method in spec.methods and any(same_rtol(r, file_rtol) for r in rtols)
    runner = _Runner(run, progress, len(spec.methods) * len(rtols) + 2 + (0 if in_ladder else 1))
    # the reference pair first: the tightest, costliest runs, so a study that cannot afford them ends at once
    # (their run budget refuses them within seconds) instead of after the whole ladder
    ref = _reference(runner, spec.reference_pair(stiffness_indicator, explicit_speedup))
    outcomes, slow = _ladder(runner, spec, rtols, auto_choice, (file_method, file_rtol), engine_methods)
    extra = not any(_is_file(m, r, file_method, file_rtol) for m, r, _ in outcomes)
    if extra:  # e.g. swapped for a sibling, or an rtol off the ladder
        runner.total += 1 if in_ladder else 0
        outcomes.append((file_method, file_rtol, runner(file_method, file_rtol)))
    runner.tick("done", runner.total, runner.total)
    runs = []
    for m, r, o in outcomes:
        is_file = _is_file(m, r, file_method, file_rtol)
        runs.append(measure(o, m, r, ref, accuracy, is_file) if isinstance(o, SimulationResult)
                    else failed(m, r, o, is_file))
    ok = [x for x in runs if x.meets_accuracy]
    cost = _cost(runs)
    best = min(ok, key=lambda x: (cost(x), x.nfev)) if ok else None
    file_run = next(x for x in runs if x.file_settings)
    return AccuracyStudy(accuracy, ref, tuple(runs), best, file_run.meets_accuracy,
                         tuple(_notes(ref, runs, accuracy, slow)), file_run_extra=extra)


def _cost(runs: Iterable[AccuracyRun]) -> Callable[[AccuracyRun], float]:
    """Estimated cost of a run: nfev x its method's median seconds per evaluation over the ladder."""
    rates: dict[str, list[float]] = {}
    for x in runs:
        if x.failure is None and x.nfev:
            rates.setdefault(x.method, []).append(x.wall_s / x.nfev)
    per = {m: statistics.median(r) for m, r in rates.items()}
    return lambda x: x.nfev * per[x.method] if x.method in per else float("inf")


def _ladder(runner: _Runner, spec: LadderSpec, rtols: list[float], auto_choice: str | None,
            file_setting: tuple[str, float], engine_methods: tuple[str, ...] | None = None
            ) -> tuple[list[tuple[str, float, Outcome]], dict[str, float]]:
    """Every method over the rtols, loose to tight; "auto" first so its choice is known before the
    siblings are picked: the method auto resolved to on most of its own rungs (the loosest first on a tie), which
    is what a column of that method would repeat; ``auto_choice`` only where none of them ran. (The file's own
    run may resolve otherwise: its settle test may have lengthened it, and a longer run can tip auto to Radau,
    whose sibling BDF runs on scipy only.) Returns (method, rtol, outcome) triples and the methods that became
    slow."""
    outcomes: list[tuple[str, float, Outcome]] = []
    slow: dict[str, float] = {}
    resolved: list[str] = []  # what auto resolved to, rung by rung
    for m in sorted(spec.methods, key=lambda m: m != "auto"):
        m = ladder_method(m, _most_common(resolved) or auto_choice, spec.methods, engine_methods)
        if any(m == done for done, _, _ in outcomes):
            runner.total -= len(rtols)
            continue
        for r in rtols:
            if m in slow and not _is_file(m, r, *file_setting):
                outcomes.append((m, r, f"skipped: the {m} rung before took {slow[m]:.1f} s"))
                runner.total -= 1
                continue
            outcome = runner(m, r)
            outcomes.append((m, r, outcome))
            if isinstance(outcome, SimulationResult):
                resolved += [outcome.solver.method] if m == "auto" else []
                if outcome.solver.wall_s > spec.max_run_s:
                    slow[m] = outcome.solver.wall_s
    return outcomes, slow


def _most_common(names: list[str]) -> str | None:
    return max(names, key=lambda n: (names.count(n), -names.index(n))) if names else None


def _is_file(method: str, rtol: float, file_method: str, file_rtol: float) -> bool:
    return method == file_method and same_rtol(rtol, file_rtol)


def _reference(runner: _Runner, pair) -> ReferenceRun:
    (ref_method, ref_rtol), (check_method, check_rtol) = pair
    results = []
    for role, (method, rtol) in zip(("reference", "check"), pair, strict=True):
        outcome = runner(method, rtol, role)
        if not isinstance(outcome, SimulationResult):
            raise SimulationError(f"accuracy reference run ({method}, rtol {rtol:g}) failed: {outcome}; "
                                  "use --quick to skip the accuracy study")
        results.append(outcome)
    return reference_run(results[0], results[1], ref_rtol, check_rtol)


def _notes(ref: ReferenceRun, runs: list[AccuracyRun], accuracy: float, slow: dict) -> list[str]:
    notes = []
    flat = not_converging(runs, ref.uncertainty)
    if flat:
        notes.append(f"the error of {' and '.join(NOT_CONVERGING_NAMES[q] for q in flat)} does not fall with rtol on "
                     f"any method (by less than {1 / CONVERGING_DROP:g}x over the ladder, far above the reference's "
                     "uncertainty): it is no solver setting's error but the quantity's own spread, as in an impacting "
                     "(chaotic) response whose trajectories part after a few impacts; no rtol and no tighter "
                     "reference certifies it: judge statistics over a longer window, or conservation laws")
    if ref.uncertainty > accuracy:
        notes.append(f"the reference's own uncertainty {ref.uncertainty:.1e} exceeds the requested accuracy "
                     f"{accuracy:.0e}: no setting can be certified; "
                     + ("a tighter reference may not lower it (the note above)" if flat else
                        "tighten the reference"))
    for method, wall in slow.items():
        notes.append(f"{method}: tighter rungs skipped after a run of {wall:.1f} s")
    for r in runs:
        if r.failure and not r.failure.startswith("skipped"):
            notes.append(f"{r.method} rtol {r.rtol:g} failed: {r.failure}")
    return notes


#: a converging quantity's error falls by more than this factor over the ladder's rtols (>= 2 decades)
CONVERGING_DROP = 0.1
NOT_CONVERGING_NAMES = {"error_speed": "the output speed", "error_mean_force": "the mean F_t",
                        "error_peak_force": "the peak F_t"}


def not_converging(runs: Iterable[AccuracyRun], uncertainty: float) -> list[str]:
    """The error fields (AccuracyRun.error_*) that fall with rtol on no method: on every method with rungs over two
    decades or more, the tightest rung's error is above CONVERGING_DROP times the loosest's and ten times the
    reference's uncertainty (a converging method of order p drops it ~10^p-fold there; an error at the
    uncertainty is the reference's, not the rung's)."""
    by_method: dict[str, list[AccuracyRun]] = {}
    for r in runs:
        if r.failure is None:
            by_method.setdefault(r.method, []).append(r)
    out = []
    for q in NOT_CONVERGING_NAMES:
        verdicts = []
        for rungs in by_method.values():
            rungs = sorted(rungs, key=lambda r: -r.rtol)
            loose, tight = getattr(rungs[0], q), getattr(rungs[-1], q)
            if len(rungs) < 3 or rungs[0].rtol < 100.0 * rungs[-1].rtol or loose is None or tight is None:
                continue
            verdicts.append(tight > CONVERGING_DROP * loose and tight > 10.0 * uncertainty)
        if verdicts and all(verdicts):
            out.append(q)
    return out


def struggling(runs: Iterable[AccuracyRun], ladder: Iterable[AccuracyRun],
               factor: float = 5.0) -> list[tuple[AccuracyRun, float]]:
    """Those of ``runs`` whose nfev is more than ``factor`` times the median nfev of the ``ladder``'s
    runs at the same rtol, each with that median."""
    ladder = [r for r in ladder if r.failure is None]
    out = []
    for r in (r for r in runs if r.failure is None):
        peers = [p.nfev for p in ladder if same_rtol(p.rtol, r.rtol)]
        if len(peers) >= 3 and r.nfev > factor * statistics.median(peers):
            out.append((r, float(statistics.median(peers))))
    return out


def struggling_text(run: AccuracyRun, median_nfev: float) -> str:
    return (f"{run.method} at rtol {run.rtol:g} needed {run.nfev} function evaluations, "
            f"{run.nfev / median_nfev:.0f}x the ladder's median at that rtol: "
            "the solver struggles (stiffness or a discontinuity)")
