"""``method = "auto"`` changes course: a run that has spent far more than its prediction re-decides from the state
it has reached (docs/performance.md, "Runs that change course").

An ``auto`` run (a fixed-window run whose method and engine ``auto`` chose) is held to a limit: ``COURSE_FACTOR``
times its predicted evaluations or its predicted wall time (:data:`gearcli.core.cost.COURSE_FACTOR`; the wall
time from the price per evaluation of the model's size, :func:`gearcli.core.cost.price_us_per_eval`, at least
``COURSE_MIN_S``). The Python engine checks both every ``BUDGET_CHECK_EVERY`` accepted steps, the time as the CPU
time of the thread that integrates (the run's own time: the wall clock of a machine shared with other jobs would
let their load decide the course, and a sweep in a process pool and on a Dask cluster would then differ); the
compiled kernel checks the evaluations (its ``max_nfev``), its time being its evaluations' price.

Past the limit ``auto`` decides again for the rest of the run, from what it has measured, not from the prediction
that failed (on the Python engine at the very step that spent the limit, from the solver's own state; the
compiled kernel stops at its evaluation limit and decides from its last output sample):

- the current method and engine: the evaluations per simulated second measured so far, over the remaining span;
- the same method on the other engine (the compiled one where it is installed and supports the scene): the same
  evaluations at that engine's price, plus what loading it still costs;
- the other method (DOP853 or Radau) on its best engine: its prediction for the remaining share of the run;
  for DOP853 at least its stability need at the state reached, ``EXPLICIT_PER_UNIT`` x max|lambda| of the
  Jacobian there x the remaining span (the stiffness the run has met, even where the linearised scene hid it).

Each is priced at the cost model's price per evaluation for the model's size, not at this run's clock, so that the
same state reached takes the same decision on a busy machine and a quiet one. The cheapest is taken when it saves
at least ``COURSE_MARGIN`` against going on; the run then continues from the state reached (``t0``, ``y0``: the
drive and load profiles are functions of the absolute time, the energy quadratures are states and carry on), at
the same tolerance, so its numbers are those of a run at the requested tolerance. A Python run that keeps its
course is not disturbed: it runs on with no further limit. A method once left is not taken up again, and a run changes course at most
``MAX_COURSE_CHANGES`` times; after its last change it runs to the end unlimited. Each change is recorded in
``solver.course_changes`` = [{``at_s``, ``from``, ``to``, ``why``}] (``from``/``to``: "DOP853 (python)").
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace

import numpy as np

from gearcli import diagnostics as dg
from gearcli import engine as eng_mod
from gearcli.core import cost
from gearcli.core.jsontypes import JsonObject
from gearcli.core.methods import AUTO, EXPLICIT_METHOD, IMPLICIT_METHOD
from gearcli.core.methods import method as method_info
from gearcli.core.records import record
from gearcli.diagnostics import Diagnostic
from gearcli.model import TorsionalModel
from gearcli.simulate.choice import Choice
from gearcli.simulate.solver import (
    FINISHED_MESSAGE,
    STATUS_BUDGET,
    STATUS_FINISHED,
    STATUS_SWITCH,
    CourseLimit,
    Integration,
    integrate,
)

MAX_COURSE_CHANGES = 2


@record
class CourseChange:
    """A mid-run change of method or engine: when, from what, to what and why."""

    at_s: float
    from_: str
    to: str
    why: str

    def as_json(self) -> JsonObject:
        return {"at_s": self.at_s, "from": self.from_, "to": self.to, "why": self.why}


def predicted_nfev(choice: Choice, method: str) -> float:
    """The cost model's evaluations for ``method`` (an explicit one: DOP853's; an implicit one: Radau's)."""
    return choice.predicted_evals[1 if method_info(method).implicit else 0]


def limit(choice: Choice, method: str, engine: str, share: float = 1.0) -> CourseLimit:
    """The evaluations and wall time after which a run of ``method`` on ``engine`` over ``share`` of the run
    stops to re-decide (module text)."""
    n = max(predicted_nfev(choice, method) * share, cost.COURSE_MIN_NFEV)
    price = cost.seconds_per_eval(engine, method, choice.size)
    return CourseLimit(cost.COURSE_FACTOR * n, cost.COURSE_FACTOR * max(n * price, cost.COURSE_MIN_S))


def _label(method: str, engine: str) -> str:
    return f"{method} ({engine})"


def _stiffness_now(model: TorsionalModel, t: float, y: np.ndarray) -> float:
    """max|lambda| of the model's Jacobian at the state reached (the dynamic states; 0 where it fails)."""
    try:
        jac = np.asarray(model.jac(t, y), dtype=float)
        dyn = model.layout.state.dynamic
        lam = np.linalg.eigvals(jac[dyn, dyn])
    except (ValueError, np.linalg.LinAlgError, ArithmeticError):
        return 0.0
    return float(np.max(np.abs(lam))) if lam.size and np.all(np.isfinite(lam)) else 0.0


def _engines_for(model: TorsionalModel, method: str, requested_engine: str) -> list[str]:
    """The engines ``auto`` may move ``method`` to (the compiled one only where it loads and supports the scene)."""
    out = ["python"] if requested_engine != "compiled" else []
    if requested_engine != "python" and eng_mod.available() and getattr(model, "generated", True) \
            and not eng_mod.unsupported(model.arrays, method) and eng_mod.load_share_s() < cost.COMPILE_S:
        out.append("compiled")
    return out or ["python"]


@record
class Spent:
    """What a run of ``method`` on ``engine`` from ``t_from`` had spent when it reached ``t_at`` (state ``y_at``)."""

    method: str
    engine: str
    nfev: int
    t_from: float
    t_at: float
    y_at: np.ndarray


def decide(model: TorsionalModel, choice: Choice, run: Spent, t_end: float, left: set[str],
           requested_engine: str, nfev_left: float = math.inf) -> tuple[str, str, str] | None:
    """(method, engine, why) to go on with from ``run.t_at`` (state ``run.y_at``), or None to go on as before
    (module text). ``left``: the methods already abandoned; ``nfev_left``: the evaluations the run's budget still
    allows. A run that has advanced (its pace measured) is not moved to an option predicted to need more: that would
    only end it in the budget's failure, where going on may finish (an implicit method's pace through a start
    transient overstates its rest). A run stopped before it advanced has no pace to weigh and moves as before."""
    rest = max(t_end - run.t_at, 0.0)
    nfev = max(run.nfev, 1)
    pace = nfev / max(run.t_at - run.t_from, 1e-300)  # evaluations per simulated second so far
    if not run.t_at > run.t_from:
        nfev_left = math.inf  # no pace measured: the budget decides nothing (module text)
    here = _label(run.method, run.engine)
    # every option at the cost model's prices for this model's size (not the clock of this run: the same state
    # reached takes the same decision on a busy machine and a quiet one, in a pool worker and a Dask thread)
    going_on = pace * rest * cost.seconds_per_eval(run.engine, run.method, choice.size)
    options: list[tuple[float, str, str, str]] = []
    for e in _engines_for(model, run.method, requested_engine):
        if e != run.engine:
            s = pace * rest * cost.seconds_per_eval(e, run.method, choice.size) + eng_mod.load_share_s() * (e == "compiled")
            if pace * rest <= nfev_left:
                options.append((s, run.method, e, f"~{pace * rest:.2g} more evaluations at its measured pace"))
    other = IMPLICIT_METHOD if run.method == EXPLICIT_METHOD else EXPLICIT_METHOD
    if other not in left:
        share = rest / t_end if t_end > 0 else 0.0
        n = predicted_nfev(choice, other) * share
        lam = 0.0
        if other == EXPLICIT_METHOD:
            lam = _stiffness_now(model, run.t_at, run.y_at)
            n = max(n, cost.EXPLICIT_PER_UNIT * lam * rest)
        for e in _engines_for(model, other, requested_engine) if n <= nfev_left else ():
            s = n * cost.seconds_per_eval(e, other, choice.size) + eng_mod.load_share_s() * (e == "compiled")
            stiff = f", max|λ| {lam:.3g} 1/s at the state reached" if lam else ""
            options.append((s, other, e, f"~{n:.2g} evaluations predicted for the rest{stiff}"))
    if not options:
        return None
    s, m, e, what = min(options)
    if cost.COURSE_MARGIN * s >= going_on:
        return None
    why = (f"{here} had spent {run.nfev} evaluations over {run.t_at - run.t_from:.4g} s of the run, over "
           f"{cost.COURSE_FACTOR:g}x its prediction; going on: ~{going_on:.2g} s for the remaining {rest:.4g} s; "
           f"{_label(m, e)}: ~{s:.2g} s ({what})")
    return m, e, why


def _last_sample(run: Integration, start: int) -> int:
    """Index (into ``run.t``) of the last output sample the stopped piece filled (``start``: its first)."""
    ok = np.all(np.isfinite(run.y), axis=0)
    ok[:start] = False
    filled = np.flatnonzero(ok & (run.t <= run.t_fail + 1e-12 * max(1.0, abs(run.t_fail))))
    return int(filled[-1]) if filled.size else start


def integrate_auto(model: TorsionalModel, t_eval: np.ndarray, choice: Choice, rtol: float, engine: str, *,
                   requested_engine: str, y0: np.ndarray | None, max_nfev: int,
                   progress: Callable[[float], None] | None = None,
                   enabled: bool = True) -> tuple[Integration, list[CourseChange]]:
    """The run of ``choice.method`` on ``engine`` over ``t_eval``, changing course where it overruns (module text).
    ``enabled`` False: one plain run (a requested method, an explicit engine).

    On the Python engine the decision is taken inside the run at the step that spends the limit (the solver's
    own state): a run that goes on as it was is not disturbed (its steps are those of a run without the limit),
    one that changes course goes on from exactly that state. The compiled kernel stops at its evaluation limit;
    it goes on from its last output sample, also when it keeps its course."""
    method = choice.method
    changes: list[CourseChange] = []
    left: set[str] = {EXPLICIT_METHOD} if choice.explicit_barred else set()  # abandoned, or never offered
    pieces: list[tuple[int, Integration]] = []
    k, y, used, t0 = 0, y0, 0, 0.0
    t_end = float(t_eval[-1])
    while True:
        free = not enabled or len(changes) >= MAX_COURSE_CHANGES
        lim = None if free else limit(choice, method, engine, (t_end - t0) / t_end if t_end > 0 else 1.0)
        verdict: list[tuple[str, str, str] | None] = []
        if lim is not None and engine != "compiled":
            def ask(t: float, y_now: np.ndarray, nfev: int, m=method, e=engine, start=t0,
                    box=verdict, spent=used) -> str | None:
                box.append(decide(model, choice, Spent(m, e, nfev, start, t, y_now), t_end, left, requested_engine,
                                  max_nfev - spent - nfev))
                return None if box[-1] is None else box[-1][2]
            lim.decide = ask
        budget = max_nfev - used
        nfev_cap = budget if lim is None or engine != "compiled" else min(budget, int(math.ceil(lim.nfev)))
        t_piece = t_eval[k:] if t0 == float(t_eval[k]) else np.concatenate(([t0], t_eval[k:]))
        run = integrate(model, t_piece, method, rtol, y0=y, t0=t0, max_nfev=nfev_cap, engine=engine,
                        course=lim if engine != "compiled" else None,
                        progress=None if progress is None else _shifted(progress, t0, t_end))
        used += run.nfev
        offset = t_piece.size - (t_eval.size - k)  # 1 where the piece starts between two samples
        pieces.append((k, _samples(run, offset)))
        if run.status == STATUS_SWITCH and run.y_end is not None and verdict and verdict[-1] is not None:
            m, e, why = verdict[-1]
            t_at, y_at = float(run.t_fail), run.y_end
        elif lim is not None and engine == "compiled" and run.status == STATUS_BUDGET and nfev_cap < budget \
                and run.nfev > nfev_cap:
            j = k + _last_sample(pieces[-1][1], 0)
            y_at = pieces[-1][1].y[:, j - k]
            got = decide(model, choice, Spent(method, engine, run.nfev, t0, float(t_eval[j]), y_at), t_end, left,
                         requested_engine, max_nfev - used)
            m, e, why = got if got is not None else (method, engine, "")
            t_at = float(t_eval[j])
            if got is None:
                enabled = False  # keeps its course: on from the last sample, unlimited
        else:
            break
        j = int(np.searchsorted(t_eval, t_at, side="right"))  # the first sample after the state reached
        if j >= t_eval.size:  # the piece filled the last sample before its limit stopped it: the run is complete
            pieces[-1] = (pieces[-1][0], replace(pieces[-1][1], status=STATUS_FINISHED, message=FINISHED_MESSAGE,
                                                 t_fail=t_end, y_end=None))
            break
        if why:
            changes.append(CourseChange(t_at, _label(method, engine), _label(m, e), why))
            if m != method:
                left.add(method)
        method, engine = m, e
        pieces[-1] = (pieces[-1][0], _cut(pieces[-1][1], j - pieces[-1][0] - 1))
        k, y, t0 = j, np.array(y_at, dtype=float), t_at
        if float(t_eval[j - 1]) == t_at:  # stopped on a sample: the next piece starts there
            k, t0 = j - 1, t_at
    merged = _merge(t_eval, pieces)
    if len(pieces) > 1 and merged.status == STATUS_BUDGET and used > max_nfev:  # the run's budget, not the piece's rest
        merged = replace(merged, message=f"more than {max_nfev} right-hand-side evaluations")
    return merged, changes


def _samples(run: Integration, offset: int) -> Integration:
    """The piece's output samples only (``offset`` 1: its first column is its start between two samples)."""
    return run if offset == 0 else replace(run, t=run.t[offset:], y=run.y[:, offset:])


def _shifted(progress: Callable[[float], None], t0: float, t_end: float) -> Callable[[float], None]:
    """A piece's progress (its own fraction from ``t0``) as the whole run's."""
    def report(f: float) -> None:
        progress((t0 + f * (t_end - t0)) / t_end if t_end > 0 else 1.0)
    return report


def _cut(run: Integration, upto: int) -> Integration:
    """The piece up to its sample ``upto`` (the next piece starts there)."""
    return replace(run, t=run.t[:upto + 1], y=run.y[:, :upto + 1])


def _merge(t_eval: np.ndarray, pieces: list[tuple[int, Integration]]) -> Integration:
    """One Integration of the pieces: samples in order (a piece's first sample is the previous one's last),
    counters and wall times added, the last piece's method, engine and status."""
    if len(pieces) == 1:
        return pieces[0][1]
    y = np.full((pieces[-1][1].y.shape[0], t_eval.size), np.nan)
    for k, run in pieces:
        y[:, k:k + run.y.shape[1]] = run.y
    last = pieces[-1][1]
    total = {f: sum(getattr(r, f) for _, r in pieces) for f in ("nfev", "njev", "nlu", "steps", "wall_s", "compile_s")}
    return replace(last, t=t_eval, y=y, **total)


def prediction(choice: Choice, engine: str, nfev: float) -> JsonObject:
    """``solver.prediction``: what ``auto``'s cost model predicted for the run's own integration (the chosen
    method on the engine first chosen; the check pass aside): evaluations, the price per evaluation of this
    model's size on that engine (:func:`gearcli.core.cost.price_us_per_eval`) and their product plus the engine's
    fixed cost per run."""
    price = cost.price_us_per_eval(engine, choice.method, choice.size)
    return {"nfev": float(nfev), "price_us_per_eval": price,
            "wall_s": cost.RUN_FIXED_S.get(engine, 0.0) + nfev * price * 1e-6}


def pace_warnings(run: Integration, choice: Choice) -> list[Diagnostic]:
    """A run whose evaluations far exceed what the cost model predicted for its method says so, with both figures
    (counters, not the wall clock: the same warning on a busy machine and a quiet one). Every method is judged: the
    cost model predicts DOP853 and Radau, and prices RK45 as DOP853, BDF and LSODA as Radau (a requested BDF run
    on a stiff scene took 180x Radau's prediction, 27 s, unwarned when only the two were judged)."""
    n = predicted_nfev(choice, choice.method)
    took = cost.predicted_wall_s(run.engine, run.method, run.nfev, size=choice.size)
    if took < cost.PACE_MIN_S or run.nfev < cost.PACE_WARN_FACTOR * n:
        return []
    family = IMPLICIT_METHOD if method_info(run.method).implicit else EXPLICIT_METHOD
    what = "the cost model predicted" if family == run.method else f"the cost model predicted for {family}"
    if choice.requested == AUTO:
        tail = 'method = "auto" may have chosen the slower method here'
    else:
        explicit, implicit = choice.predicted_evals
        tail = (f'method = "{choice.requested}" was requested (the cost model predicts {explicit:.2g} evaluations '
                f'for {EXPLICIT_METHOD}, {implicit:.2g} for {IMPLICIT_METHOD}; method = "auto" chooses between them)')
    # a prediction of none (nothing to resolve where the cost model looks: an unloaded Hertzian mesh continued
    # without ramps has no stiffness at its static load) is no ratio
    over = f"{run.nfev / n:.2g}x the {n:.2g}" if n > 0 else "where"
    return [dg.warning(dg.SLOW_PACE, f"{run.method} ({run.engine} engine) took {run.nfev} evaluations, "
                       f"{over} {what} {'none ' if n <= 0 else ''}(~{took:.2g} s against "
                       f"~{cost.predicted_wall_s(run.engine, run.method, n, size=choice.size):.2g} s); {tail} "
                       '(docs/numerics.md, "Choosing the method: auto")',
                       nfev=run.nfev, predicted_nfev=n)]
