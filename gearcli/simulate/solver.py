"""One wrapper around scipy's ODE solvers: tolerances, output samples, counters, failures.

The loop is the one ``scipy.integrate.solve_ivp`` runs (``OdeSolver.step`` until the end, dense output
evaluated at the requested samples inside each step), written out here so that it can also count
accepted steps, stop a run that exceeds its function-evaluation budget (an explicit method on a
stiff scene would otherwise grind for minutes), stop at the first non-finite state (checked once per
accepted step, not on every evaluation; an overflow inside the right-hand side is caught at the step)
and stop a run whose energy grows without input (:mod:`gearcli.simulate.guards`). Success is decided from the solver's
``status`` only, never from its message text; failures raise :class:`~gearcli.errors.SimulationError`
with the likely cause and the fix.

The run is integrated in segments between the times where the forcing is not smooth: the ends of the
STEP ramps of the drive and the load, where the input acceleration (speed drive) or the torque rate has a
kink. A step that straddles such a kink violates the smoothness the error estimate assumes; scipy's
implicit methods filter their error estimate through ``(I - h gamma J)^-1``, which hides the resulting
error in lightly damped stiff mesh modes. Radau at rtol 1e-6 on a very stiff undamped mesh
(configs/extreme/stiff_linear_10000x.toml) then misses the mesh force after the ramp by ~100 %, and at
rtol 1e-7 leaves a spurious ringing of 60 % of the load; restarting the solver at the kink brings both
back to the resolution of the tolerance (tests/extreme/test_guards.py).
"""

from __future__ import annotations

import math
import os
import threading
import time
from bisect import bisect_right
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.integrate import OdeSolver

from gearcli import engine
from gearcli.core import cost, signals
from gearcli.core.cost import BUDGET_CHECK_EVERY
from gearcli.core.cost import CAP as MAX_NFEV
from gearcli.core.methods import METHODS, scipy_solver
from gearcli.core.records import record
from gearcli.engine import status as st
from gearcli.errors import SimulationError
from gearcli.model import TorsionalModel
from gearcli.simulate.choice import contact_step, stability_step
from gearcli.simulate.guards import ENERGY_MARGIN, EnergyReport, EnergyWatch, energy_watch, over_budget, priced_work_s

# how a run ended (gearcli.engine.status: one set of codes for both engines)
STATUS_FINISHED, STATUS_FAILED, STATUS_BUDGET = st.FINISHED, st.FAILED, st.BUDGET
STATUS_NONFINITE, STATUS_ENERGY, STATUS_PROJECTED = st.NONFINITE, st.ENERGY, st.PROJECTED
STATUS_SWITCH = st.SWITCH
FINISHED_MESSAGE = "reached the end of the run"


@record
class Integration:
    """One integration's samples, tolerances, counters, wall time and status."""

    t: np.ndarray  # the requested samples
    y: np.ndarray  # (n_states, len(t))
    method: str
    rtol: float
    atol: np.ndarray
    nfev: int
    njev: int
    nlu: int
    steps: int  # accepted steps
    wall_s: float
    status: int  # 0 reached the end; < 0 failed (see STATUS_*)
    message: str
    t_fail: float  # where it stopped
    engine: str = "python"  # "python" (scipy) or "compiled" (gearcli.engine)
    compile_s: float = 0.0  # compiled engine: numba import and kernel load/compilation, not in wall_s
    y_end: np.ndarray | None = None  # the state at t_fail where a course change stopped a Python run


def _solver(model: TorsionalModel, method: str, t0: float, y0: np.ndarray, t_end: float, rtol: float,
            atol: np.ndarray, max_step: float = np.inf) -> OdeSolver:
    if method not in METHODS:
        raise SimulationError(f"unknown integration method {method!r}; use one of {', '.join(METHODS)}")
    extra = {"jac": model.jac} if METHODS[method].takes_jacobian else {}
    return scipy_solver(method)(model.rhs, t0, y0, t_end, rtol=rtol, atol=atol, max_step=max_step, **extra)


def step_ceiling(model: TorsionalModel, method: str) -> float:
    """The largest step ``method`` may take on ``model`` (scipy's ``max_step``): an explicit method's stability
    limit on the scene's stiffest mode (:func:`gearcli.simulate.choice.stability_step`); an implicit one's
    :func:`gearcli.simulate.choice.contact_step` (inf without a time-varying contact length); none (inf) for an unknown method (refused by
    :func:`_solver`)."""
    if method not in METHODS:
        return np.inf
    if METHODS[method].implicit:
        return contact_step(model.layout)
    return stability_step(model.spec, model.layout, method)


def breakpoints(model: TorsionalModel, t_end: float, t0: float = 0.0) -> list[float]:
    """Segment ends: the ramp ends of the drive and the load inside ``(t0, t_end)``, then ``t_end``."""
    spec = model.spec
    drive_value = spec.drive.speed_rad_s if spec.drive.kind == "speed" else spec.drive.torque_Nm
    kinks = {r for r, v in ((spec.drive.ramp_s, drive_value), (spec.load.ramp_s, spec.load.torque_Nm))
             if v != 0.0 and t0 < r < t_end}
    return sorted(kinks) + [t_end]


def tolerances(model: TorsionalModel, rtol: float, watch: EnergyWatch | None) -> np.ndarray:
    """The model's absolute tolerances, with the energy quadratures brought under error control.

    The model leaves the work quadratures (W_in, W_load, E_damp, W_el) out of the step control
    (atol 1e20). An implicit method that steps over unresolved stiff mesh modes then integrates them
    from inaccurate stage values: on configs/extreme/stiff_linear_10000x.toml Radau's 29 steps put the
    energy balance 0.8 % off (a false "tighten rtol" warning) while the states were right to 1e-6.
    ``rtol`` times the scene's energy scale (:class:`~gearcli.simulate.guards.EnergyWatch`) fixes that
    for ~170 more evaluations there and leaves the cost of the other scenes unchanged.
    """
    atol = model.atol(rtol)
    if watch is not None:
        atol[model.layout.state.quadratures] = rtol * watch.scale
    return atol


@dataclass
class CourseLimit:
    """An ``auto`` run's limit (:mod:`gearcli.simulate.course`): past these evaluations or this time the Python
    engine asks ``decide(t, y, nfev)`` at the state reached; a reason stops the run there (``STATUS_SWITCH``,
    ``Integration.y_end`` the state) for ``auto`` to go on otherwise, None lets it run on undisturbed (no more
    checks)."""
    nfev: float
    wall_s: float
    decide: Callable[[float, np.ndarray, int], str | None] | None = None
    spent: bool = False


@dataclass
class _Counters:
    """A run's evaluation, Jacobian and LU counts as they accumulate."""

    nfev: int = 0
    njev: int = 0
    nlu: int = 0
    steps: int = 0

    def add(self, solver: OdeSolver) -> None:
        self.nfev += int(solver.nfev)
        self.njev += int(getattr(solver, "njev", 0))
        self.nlu += int(getattr(solver, "nlu", 0))


def integrate(model: TorsionalModel, t_eval: np.ndarray, method: str, rtol: float, *,
              y0: np.ndarray | None = None, max_nfev: int = MAX_NFEV, watch_energy: bool = True,
              t0: float = 0.0, atol: np.ndarray | None = None, engine: str = "python",
              pace_limit_s: float | None = None, progress: Callable[[float], None] | None = None,
              course: CourseLimit | None = None, ceiling: float = 1.0) -> Integration:
    """Integrate from ``t0`` (default 0, the start of the run) to ``t_eval[-1]`` and sample at ``t_eval``
    (ascending, starting at ``t0``). A continuation (``t0 > 0``) needs ``y0``, the state at ``t0``: the
    drive's and the load's profiles are functions of the absolute time. ``atol`` overrides the per-state
    absolute tolerances of :func:`tolerances` (an array of the state's size, or a scalar); ``rtol`` is a
    scalar for every method.

    An explicit method's steps are capped at ``ceiling`` times its stability limit on the scene's stiffest mode
    (:func:`step_ceiling`, on both engines; a check pass halves it).

    Never raises on a solver failure: the returned ``status`` says what happened and ``y`` holds
    the samples reached (the rest NaN); :func:`check` turns a failure into an error. ``engine``
    "compiled" runs :mod:`gearcli.engine` (DOP853, RK45, Radau; from ``t0`` too; the caller checks
    :func:`gearcli.engine.unsupported` first), "python" scipy's solvers.

    ``pace_limit_s`` (Python engine): once the run has used ``cost.PACE_SWITCH_AFTER_S`` of priced work
    (:func:`gearcli.core.cost.priced_work_s`), a pace that projects the whole run over this many priced
    seconds stops it with ``STATUS_SWITCH`` (the caller goes on on
    the compiled engine). ``course`` (Python engine): the evaluations and wall time past which an ``auto`` run
    stops with ``STATUS_SWITCH`` to re-decide (:mod:`gearcli.simulate.course`). ``progress``: called with the fraction of the run done, every few hundred steps (a
    terminal's progress bar; never printed here); a compiled run reports it every :data:`PROGRESS_EVERY_S`
    (:func:`_kernel_with_progress`).
    """
    if t0 != 0.0 and y0 is None:
        raise ValueError("a run that starts at t0 > 0 needs the state y0 there")
    y = model.initial_state() if y0 is None else np.asarray(y0, dtype=float)
    watch = energy_watch(model, y, t0) if watch_energy else None
    if atol is None:
        atol = tolerances(model, rtol, watch)
    atol = np.broadcast_to(np.asarray(atol, dtype=float), y.shape).copy()
    max_step = ceiling * step_ceiling(model, method)
    if engine == "compiled" and t_eval[-1] > t0:  # (an empty run is scipy's: nothing to integrate)
        return _integrate_compiled(model, t_eval, method, rtol, y, atol, max_nfev, watch, float(t0), progress,
                                   max_step)
    out = np.full((y.size, t_eval.size), np.nan)
    out[:, t_eval <= t0] = y[:, None]
    done = int(np.searchsorted(t_eval, t0, side="right"))
    count = _Counters()
    start, t, status, message = time.perf_counter(), float(t0), STATUS_FINISHED, FINISHED_MESSAGE
    cpu_start = time.thread_time()
    for t_end in breakpoints(model, float(t_eval[-1]), t):
        solver = _solver(model, method, t, y, t_end, rtol, atol, max_step)
        status, message, done = _segment(solver, t_eval, out, done, count, max_nfev, watch,
                                         (0.0, float(t_eval[-1])), METHODS[method].implicit,
                                         _Pace(float(t0), float(t_eval[-1]), pace_limit_s, progress, course, cpu_start))
        count.add(solver)
        t, y = float(solver.t), solver.y
        if status != STATUS_FINISHED:
            break
    wall = time.perf_counter() - start
    return Integration(t_eval, out, method, rtol, atol, count.nfev, count.njev, count.nlu, count.steps, wall, status,
                       message, t, y_end=np.array(y, dtype=float) if status == STATUS_SWITCH else None)


@record
class _Pace:
    """The run's pace limit (priced work) and its progress callback."""
    t0: float
    t_end: float
    limit_s: float | None
    progress: Callable[[float], None] | None
    course: CourseLimit | None = None
    started: float = 0.0  # time.thread_time() at the run's start

    def check(self, t: float, work_s: float, nfev: int = 0, y: np.ndarray | None = None) -> tuple[int, str] | None:
        """Report progress; stop for ``auto`` to re-decide when the run has spent its course limit (evaluations
        or wall time), or for the switch when the priced work ``work_s`` projects the run over the limit."""
        done = (t - self.t0) / (self.t_end - self.t0) if self.t_end > self.t0 else 1.0
        if self.progress is not None:
            self.progress(done)
        if self.course is not None and not self.course.spent:
            # the run's own time: the CPU time of this thread, which other jobs on a shared machine do not inflate
            # (the wall clock would let the machine's load decide the course)
            spent = time.thread_time() - self.started
            if nfev > self.course.nfev or spent > self.course.wall_s:
                self.course.spent = True
                why = self.course.decide(t, y, nfev) if self.course.decide is not None and y is not None else "limit"
                if why is not None:
                    return STATUS_SWITCH, why
        if self.limit_s is None:
            return None
        if work_s > cost.PACE_SWITCH_AFTER_S and done > 0 and work_s / done > self.limit_s:
            return STATUS_SWITCH, (f"at its pace on scipy ({100 * done:.2g} % after ~{work_s:.2g} s of priced work) "
                                   f"the run would take ~{work_s / done:.2g} s, over {self.limit_s:.2g} s")
        return None


def _segment(solver: OdeSolver, t_eval: np.ndarray, out: np.ndarray, done: int, count: _Counters, max_nfev: int,
             watch, span: tuple[float, float] = (0.0, 0.0), implicit: bool = False,
             pace: _Pace | None = None) -> tuple[int, str, int]:
    """Step ``solver`` to its end, filling ``out`` at the samples passed; (status, message, samples done)."""
    n = out.shape[0]
    times = t_eval.tolist()  # the samples passed by each step: bisected as floats (numpy's per-call cost, ~1 us a step)
    while solver.status == "running":
        try:
            with np.errstate(over="ignore", invalid="ignore", divide="ignore"):  # judged below, not printed
                msg = solver.step()
        except (OverflowError, ZeroDivisionError) as exc:  # Python float arithmetic of the right-hand side
            return STATUS_NONFINITE, f"the right-hand side overflowed near t = {solver.t:.6g} s ({exc})", done
        except (ValueError, np.linalg.LinAlgError) as exc:  # an implicit method's LU met inf/NaN of its own
            return STATUS_NONFINITE, f"the solver's linear algebra failed ({type(exc).__name__}: {exc})", done
        if solver.status == "failed":
            return STATUS_FAILED, str(msg), done
        count.steps += 1
        if not math.isfinite(solver.y.sum()):  # once per accepted step: inf and NaN propagate into the sum
            return STATUS_NONFINITE, f"the state became non-finite at t = {solver.t:.6g} s", done
        upto = bisect_right(times, solver.t)
        if upto > done:
            out[:, done:upto] = solver.dense_output()(t_eval[done:upto]).reshape(n, -1)
            done = upto
        nfev = count.nfev + solver.nfev
        if nfev > max_nfev:
            return STATUS_BUDGET, f"more than {max_nfev} right-hand-side evaluations", done
        if count.steps % BUDGET_CHECK_EVERY == 0:
            njev, nlu = count.njev + getattr(solver, "njev", 0), count.nlu + getattr(solver, "nlu", 0)
            stop = _budget_stop(nfev, njev, nlu, count.steps, implicit, float(solver.t), span)
            if stop is None and pace is not None:
                stop = pace.check(float(solver.t), priced_work_s(nfev, njev, nlu, count.steps, implicit), nfev,
                                  solver.y)
            if stop is not None:
                return (*stop, done)
        if watch is not None and (count.steps % watch.every == 0 or solver.status != "running"):
            report = watch.check(solver.t, solver.y)
            if report.diverging:
                return STATUS_ENERGY, watch.message(report), done
    return STATUS_FINISHED, FINISHED_MESSAGE, done


def _budget_stop(nfev: int, njev: int, nlu: int, steps: int, implicit: bool, t: float,
                 span: tuple[float, float], speedup: float = 1.0) -> tuple[int, str] | None:
    """(status, message) when the priced work budget stops the run here (:func:`gearcli.simulate.guards.over_budget`;
    ``speedup``: a compiled run's), else None (the kernel checks the same limits at the same steps)."""
    work = priced_work_s(nfev, njev, nlu, steps, implicit)
    verdict = over_budget(work, t, *span, speedup=speedup)
    if verdict is None:
        return None
    kind, why = verdict
    return (STATUS_PROJECTED if kind == "projected" else STATUS_BUDGET), (
        f"{why} ({nfev} right-hand sides, {steps} steps, {nlu} LU decompositions, {njev} Jacobians)")


PROGRESS_EVERY_S = 0.1  # how often a compiled run's progress is reported


def _kernel_with_progress(kernel: Callable[..., tuple], args: tuple, wpar: np.ndarray, span: tuple[float, float],
                          progress: Callable[[float], None] | None) -> tuple:
    """``kernel(*args)`` in a worker thread (the kernel releases the GIL) while this thread waits with SIGINT,
    SIGTERM and SIGHUP held back (:func:`gearcli.core.signals.deferred`): a signal raises the kernel's stop flag
    (``wpar[status.WP_STOP]``), the kernel returns at its next step, and the signal is acted on here once it has
    (KeyboardInterrupt or ``Terminated``), never while machine code runs under an unwinding interpreter. With
    ``progress``, the time the kernel has reached (``wpar[status.WP_PROGRESS]``, written at every budget check) is
    reported as the fraction of ``span`` every :data:`PROGRESS_EVERY_S`. One call either way, so the numbers are
    those of a run without progress; the thread is one a process (:class:`_KernelThread`). ``wpar`` must have both
    entries. Without ``progress`` and with no Python signal handler to hold back (:func:`gearcli.core.signals.handled`: a sweep's
    pool or Dask worker) the kernel is called here, directly: the same call without the thread."""
    if progress is None and not signals.handled():
        return kernel(*args)
    box: dict[str, Any] = {}

    def work() -> None:
        try:
            box["out"] = kernel(*args)
        except BaseException as exc:  # handed to the calling thread below
            box["exc"] = exc

    length = span[1] - span[0]

    def report() -> None:
        if progress is not None and length > 0:
            progress(min(1.0, max(0.0, (float(wpar[st.WP_PROGRESS]) - span[0]) / length)))

    with signals.deferred(wpar, st.WP_STOP):
        done = _KERNEL_THREAD.run(work)
        while not done.acquire(timeout=PROGRESS_EVERY_S):
            report()
        report()  # where the kernel stopped (its last budget check), also when it finished before the first poll
    if "exc" in box:
        raise box["exc"]
    return box["out"]


class _KernelThread:
    """The worker thread that runs :func:`_kernel_with_progress`'s kernels, one at a time: started on first use and
    kept for the process's later runs (a sweep's thousands of points each handed it their integration; a thread
    started and joined per run cost ~0.2 ms a point). A forked child, where the thread does not exist, starts its
    own. A daemon thread: one idle at exit waits on its queue and is not joined."""

    def __init__(self) -> None:
        self._thread: threading.Thread | None = None
        self._pid = 0

    def run(self, work: Callable[[], None]) -> Any:
        """Hand ``work`` (which must not raise) to the thread; returns a lock released when it has returned."""
        if self._thread is None or self._pid != os.getpid() or not self._thread.is_alive():
            import queue  # lazy: a run on scipy alone never hands a kernel over

            self._jobs: Any = queue.SimpleQueue()
            self._thread = threading.Thread(target=self._serve, args=(self._jobs,), name="gearcli-kernel",
                                            daemon=True)
            self._thread.start()
            self._pid = os.getpid()
        done = threading.Lock()
        done.acquire()
        self._jobs.put((work, done))
        return done

    @staticmethod
    def _serve(jobs: Any) -> None:  # a queue.SimpleQueue
        while True:
            work, done = jobs.get()
            try:
                work()
            finally:
                done.release()


_KERNEL_THREAD = _KernelThread()


def _integrate_compiled(model: TorsionalModel, t_eval: np.ndarray, method: str, rtol, y: np.ndarray,
                        atol: np.ndarray, max_nfev: int, watch: EnergyWatch | None, t0: float = 0.0,
                        progress: Callable[[float], None] | None = None, max_step: float = np.inf) -> Integration:
    """The same run on the compiled kernel: same start, segments, tolerances (vectors), step ceiling, guards and
    statuses; ``progress`` as in :func:`integrate`."""

    if method not in engine.COMPILED_METHODS:
        raise SimulationError(f"the compiled engine integrates {', '.join(engine.COMPILED_METHODS)} only, "
                              f"not {method}")
    loaded = engine.load()
    kernel, entry_s = engine.entry(method)
    compile_s = (loaded.load_s if not _COMPILED_USED else 0.0) + entry_s
    _COMPILED_USED[:] = [True]  # (one entry: a sweep's thousands of runs do not grow it)
    n = y.size
    rtol_v = np.array(np.broadcast_to(np.asarray(rtol, dtype=float), (n,)))  # writable: one kernel signature
    atol_v = np.array(np.broadcast_to(np.asarray(atol, dtype=float), (n,)))
    breaks = np.array(breakpoints(model, float(t_eval[-1]), t0), dtype=float)

    implicit = METHODS[method].implicit
    watch_par = [watch.e0, watch.w0, watch.scale, ENERGY_MARGIN] if watch is not None else [0.0, 0.0, 0.0, 0.0]
    p = cost.PRICE_S["python"]  # the work budget (gearcli.simulate.guards.over_budget with the compiled speed-up)
    speedup = cost.compiled_speedup(method)
    wpar = np.array([*watch_par, t0, cost.WORK_CAP_S * speedup, cost.PROJECTION_AFTER_S,
                     cost.PROJECTION_LIMIT,
                     float(BUDGET_CHECK_EVERY), p["eval"], p["jac"], p["lu"],
                     p["step_implicit" if implicit else "step_explicit"], 0.0, float(t_eval[-1])]
                    + [t0, 0.0]  # the kernel writes the time reached there; a signal raises the stop flag
                    + [max_step])
    every = np.int64(watch.every if watch is not None else 0)
    start = time.perf_counter()
    args = (_packed(model), np.ascontiguousarray(y, dtype=float), np.ascontiguousarray(t_eval, dtype=float),
            breaks, rtol_v, atol_v, np.int64(max_nfev), every, wpar, np.empty(0))
    out, counters, floats, _ = _kernel_with_progress(kernel, args, wpar, (t0, float(t_eval[-1])), progress)
    wall = time.perf_counter() - start
    nfev, steps, status = (int(v) for v in counters[:3])
    njev, nlu = (int(v) for v in counters[4:6]) if counters.size > 4 else (0, 0)
    t_end, created, scale = (float(v) for v in floats)
    messages = {STATUS_FINISHED: FINISHED_MESSAGE,
                STATUS_FAILED: "Required step size is less than spacing between numbers.",
                STATUS_NONFINITE: f"the state became non-finite at t = {t_end:.6g} s"}
    if status == STATUS_ENERGY and watch is not None:

        message = watch.message(EnergyReport(created, scale))
    elif status == STATUS_BUDGET and nfev > max_nfev:
        message = f"more than {max_nfev} right-hand-side evaluations"
    elif status in (STATUS_BUDGET, STATUS_PROJECTED):
        stop = _budget_stop(nfev, njev, nlu, steps, implicit, t_end, (0.0, float(t_eval[-1])), speedup)
        message = stop[1] if stop is not None else f"more than {max_nfev} right-hand-side evaluations"
    else:
        message = messages.get(status, f"status {status}")
    return Integration(t_eval, out, method, float(np.max(rtol_v)) if np.ndim(rtol) else float(rtol), atol, nfev, njev,
                       nlu, steps, wall, status, message, t_end, engine="compiled", compile_s=compile_s)


def _packed(model: TorsionalModel):
    """The kernel's model of ``model.arrays`` (:func:`gearcli.engine.pack`), packed once per model: every
    integration of a run (its settle runs, the periodic search's shots, the check pass) hands the kernel the same
    arrays, which it only reads."""
    arrays = model.arrays
    kept = model.__dict__.get("_packed")
    if kept is None or kept[0] is not arrays:
        kept = (arrays, engine.pack(arrays))
        model.__dict__["_packed"] = kept
    return kept[1]


_COMPILED_USED: list[bool] = []  # the kernel's load time is reported by the first compiled run of a process
