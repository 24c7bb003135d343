"""Every cost constant of a simulation in one place: what a run costs, what it may cost, and what ``auto``
predicts (no imports beyond the standard library, so the design-file bounds, the engine and the method
choice all read it without pulling in scipy or numba).

Prices. One price per counter and engine, in seconds, measured on the 2-core reference machine by
``benchmarks/bench_cost.py`` (a least-squares fit of the integration wall time against the counters over every
scene of configs/ and configs/extreme/, the excitation scenes and the conveyor, both methods, both engines):
one right-hand-side evaluation, one Jacobian, one LU decomposition (Radau factors a real and a complex matrix,
two counts), and the work of an accepted step beyond its evaluations (error norm, dense output at the
samples, the per-step checks; for an implicit method also its Newton back-substitutions).

Two uses of the prices:

- the run's **work budget** (:func:`priced_work_s`, :mod:`gearcli.simulate.guards`): a run's counters priced at
  scipy's rates, so that whether a run is within its budget (and where a hopeless one is stopped) is
  deterministic and does not depend on the machine's load. The budget a compiled run may spend is the same ~60 s
  of its own, i.e. :func:`compiled_speedup` times as much priced work (the report's Radau reference at rtol 1e-10
  on the conveyor, 1.7e6 evaluations, ~2 s compiled, would be called off at scipy's rates), and a hopeless pace is
  judged against that budget on either engine (a projection over PROJECTION_LIMIT times it: a run the compiled
  engine finishes in seconds is not refused for what it would cost on scipy);
- ``auto``'s **wall-time prediction** (:func:`predicted_wall_s`): predicted evaluations times the engine's price
  per evaluation of that method (:func:`seconds_per_eval`: the evaluation's price plus its share of the typical
  steps, LU decompositions and Jacobians per evaluation, :data:`COUNTERS_PER_EVAL`), plus what loading the
  compiled engine still costs the process.

Evaluations (``auto``, :mod:`gearcli.simulate.choice`): DOP853 needs ``EXPLICIT_PER_UNIT`` evaluations per unit of
the stiffness indicator ``max|lambda| T`` for stability, ``EXPLICIT_PER_RAD`` per radian of free vibration it
must resolve and ``EXPLICIT_PER_EXCITED_RAD`` per radian of the highest excitation harmonic (transmission error,
stiffness harmonics, contact-line stiffness, torque ripple, load fluctuation) swept over the run; Radau
``IMPLICIT_FIXED`` plus ``IMPLICIT_PER_RAD`` and ``IMPLICIT_PER_EXCITED_RAD`` per radian of each. A forced
response must be resolved at the run's tolerance for its whole length whatever the method, which is why the
excitation's radians cost both methods alike (the conveyor, configs/conveyor.toml: 8,800 radians of the
second transmission-error harmonic, ~40 DOP853 and ~25 Radau evaluations each; the spur oscillator of
benchmarks/bench_excitation.py, 15-37 and 25-40; the old model, which counted free vibration only, predicted
5.9e3 evaluation-equivalents for Radau on the conveyor where it took 217,000 evaluations).

Measured on the 2-core machine shared with other jobs (benchmarks/bench_cost.py, 2026-11): compiled 0.67 µs per
evaluation, 1.8 µs per explicit and 2.3 µs per implicit step (LU and Jacobians of these small systems vanish in
the fit); scipy ~10 µs per DOP853 evaluation all included, ~3.3x that per Radau evaluation. The cost model
predicts the evaluations of the scenes to within 0.25-4x (most within 0.7-1.6x) for both methods alike, which
is what a choice between them needs.
"""

from __future__ import annotations

import math

from gearcli.core.records import record

# ----------------------------------------------------------------------------------------------- prices
#: seconds per counter, per engine (benchmarks/bench_cost.py)
PRICE_S: dict[str, dict[str, float]] = {
    "python": {"eval": 8e-6, "jac": 10e-6, "lu": 8e-6, "step_explicit": 30e-6, "step_implicit": 200e-6},
    "compiled": {"eval": 0.67e-6, "jac": 1e-6, "lu": 0.5e-6, "step_explicit": 1.8e-6, "step_implicit": 2.3e-6},
}
#: the typical counters per evaluation of each method (steps, LU decompositions, Jacobians), to price a run
#: predicted in evaluations (DOP853: 12 evaluations a step; RK45: 6; Radau, measured over all the scenes:
#: 0.127 steps, 0.096 LU decompositions, 0.0008 Jacobians per evaluation)
COUNTERS_PER_EVAL: dict[str, dict[str, float]] = {
    "DOP853": {"steps": 1 / 12},
    "RK45": {"steps": 1 / 6},
    "Radau": {"steps": 0.127, "lu": 0.096, "jac": 0.001},
}
IMPLICIT = ("Radau", "BDF", "LSODA")


@record
class ModelSize:
    """What a right-hand side's price depends on (:data:`PRICE_US`): the state's size, the mesh connectors
    (a planetary stage's planet meshes each count, and count again as planet meshes: their load sharing and
    phases), the meshes whose stiffness varies with the mesh phase (contact lines: the dearest element), the
    meshes with transmission-error or stiffness harmonics, and a motor's torque curve."""

    states: int = 0
    meshes: int = 0
    planet_meshes: int = 0
    time_varying: int = 0
    harmonics: int = 0
    motor: bool = False

    def features(self) -> tuple[float, ...]:
        return (1.0, float(self.states), float(self.meshes), float(self.planet_meshes), float(self.time_varying),
                float(self.harmonics), float(self.motor))


FEATURES = ("fixed", "per_state", "per_mesh", "per_planet_mesh", "per_time_varying_mesh", "per_harmonic_mesh",
            "motor")
#: microseconds per right-hand-side evaluation, all the run's work included (steps, error norms, dense output,
#: LU decompositions and Jacobians), per engine and method: the coefficients of ModelSize.features(), a
#: non-negative least-squares fit of the integration's CPU time over the fitting set of benchmarks/bench_cost.py
#: (python: 2026-11-28, 2-core machine: within 1.03x (median) and 1.31x (worst) of the measured time at the
#: measured evaluations on the fitting set, 1.11x and 1.36x on the held-out set it never saw; compiled: refitted
#: 2026-11-28 after the kernel lost numba's reference counting, on the median CPU time of three runs: 1.07x and
#: 2.43x on the fitting set, 1.15x and 3.67x on the held-out set, the worst a run of a few ms; the old compiled
#: prices were 5.6x (median) too high; docs/performance.md)
PRICE_US: dict[str, dict[str, tuple[float, ...]]] = {
    "python": {"DOP853": (5.0, 0.682, 0.0, 1.26, 2.11, 1.3, 0.468), "Radau": (25.1, 0.0, 2.1, 1.61, 5.73, 5.76, 9.3)},
    "compiled": {"DOP853": (0.0924, 0.0173, 0.00529, 0.0146, 0.0, 0.0623, 0.0),
                 "Radau": (0.0, 0.0376, 0.0121, 0.06, 0.0, 0.0658, 0.0994)},
}

#: seconds every integration costs whatever its length (setting up the solver or the kernel's call, the segments'
#: restarts, the compiled kernel's worker thread), per engine: the constant of the same fit (compiled: the mean
#: of DOP853's 0.885 ms and Radau's 0.797 ms, 2026-11-28)
RUN_FIXED_S: dict[str, float] = {"python": 4.4e-3, "compiled": 0.84e-3}


def price_us_per_eval(engine: str, method: str, size: ModelSize | None = None) -> float:
    """Predicted microseconds per evaluation of ``method`` on ``engine`` for a model of ``size`` (without a size:
    the scene-independent price of :func:`seconds_per_eval`). RK45 is priced as DOP853, BDF and LSODA as Radau."""
    if size is None:
        return 1e6 * seconds_per_eval(engine, method)
    table = PRICE_US.get(engine, PRICE_US["python"])
    coef = table.get(method, table["Radau" if method in IMPLICIT else "DOP853"])
    return float(sum(c * f for c, f in zip(coef, size.features(), strict=True)))


def seconds_per_eval(engine: str, method: str, size: ModelSize | None = None) -> float:
    """Predicted wall seconds per right-hand-side evaluation of ``method`` on ``engine``, all work included
    (``size``: the model's, :func:`price_us_per_eval`). A method the compiled engine lacks is priced as on Python."""
    if size is not None:
        return 1e-6 * price_us_per_eval(engine, method, size)
    p = PRICE_S.get(engine, PRICE_S["python"])
    per = COUNTERS_PER_EVAL.get(method, COUNTERS_PER_EVAL["Radau" if method in IMPLICIT else "DOP853"])
    step = p["step_implicit" if method in IMPLICIT else "step_explicit"]
    return p["eval"] + per["steps"] * step + per.get("lu", 0.0) * p["lu"] + per.get("jac", 0.0) * p["jac"]


def compiled_speedup(method: str) -> float:
    """How much less a compiled run of ``method`` costs than scipy's for the same counters (~13x DOP853)."""
    return seconds_per_eval("python", method) / seconds_per_eval("compiled", method)


def predicted_wall_s(engine: str, method: str, nfev: float, fixed_s: float = 0.0,
                     size: ModelSize | None = None) -> float:
    """Predicted wall time of a run of ``nfev`` evaluations (``fixed_s``: what loading the engine still costs;
    ``size``: the model's, for its price per evaluation)."""
    return fixed_s + nfev * seconds_per_eval(engine, method, size)


def priced_work_s(nfev: int, njev: int, nlu: int, steps: int, implicit: bool) -> float:
    """The run's work in seconds from its counters at scipy's prices (deterministic, unlike a wall clock;
    module text)."""
    p = PRICE_S["python"]
    step = p["step_implicit" if implicit else "step_explicit"]
    return nfev * p["eval"] + njev * p["jac"] + nlu * p["lu"] + steps * step


# ------------------------------------------------------------------------------------ auto's prediction
EXPLICIT_PER_UNIT = 2.6  # DOP853 evaluations per unit of max|lambda| T (stability radius, rejected steps)
EXPLICIT_PER_RAD = 6.0  # DOP853 evaluations per radian of resolved free vibration (the seed: 5407 for 578)
EXPLICIT_PER_EXCITED_RAD = 35.0  # DOP853 evaluations per radian of the highest excitation harmonic
IMPLICIT_FIXED = 1000.0  # Radau evaluations with nothing to resolve (run-up, restarts at the ramp ends)
IMPLICIT_PER_RAD = 17.0  # Radau evaluations per radian of resolved free vibration (measured 15-50, median 26)
IMPLICIT_PER_EXCITED_RAD = 30.0  # Radau evaluations per radian of the highest excitation harmonic
#: Radau only when its predicted wall time is this much lower (its cost per evaluation varies by scene)
IMPLICIT_MARGIN = 1.3
STIFFNESS_LIMIT = 1.0e4  # max|lambda| T above which a scene counts as stiff for an explicit method (warnings)


def accuracy_factor(rtol: float) -> float:
    """How much more a run at ``rtol`` costs than at 1e-6 (order-5 error control; >= 1)."""
    return max(1.0, (1e-6 / rtol) ** 0.2)


def predicted_evaluations(indicator: float, vibration_rad: float, excited_rad: float,
                          rtol: float = 1e-6) -> tuple[float, float]:
    """(DOP853, Radau) predicted right-hand-side evaluations (module text)."""
    f = accuracy_factor(rtol)
    explicit = max(EXPLICIT_PER_UNIT * indicator,
                   f * (EXPLICIT_PER_RAD * vibration_rad + EXPLICIT_PER_EXCITED_RAD * excited_rad))
    implicit = IMPLICIT_FIXED + f * (IMPLICIT_PER_RAD * vibration_rad + IMPLICIT_PER_EXCITED_RAD * excited_rad)
    return explicit, implicit


# ---------------------------------------------------------------------------------------------- engine
COMPILE_S = 60.0  # s: compiling the kernel when nothing is cached (measured 45-70 s on the 2-core machine)
DEFAULT_LOAD_S = 0.6  # s: numba import + cache load on the 2-core reference machine, before any measurement
MIN_LOAD_S = 0.15  # s: numba's import alone
#: a run with its error estimate integrates the scene again (the check pass of gearcli.simulate.estimate): the
#: whole run's work over the run's own (the seed: 1.82x the evaluations), what the engine's load is weighed against
CHECK_PASS_WORK = 1.8
#: a one-shot run of a method the compiled engine reproduces to the tolerance but not step for step (Radau)
#: stays on scipy, the reference implementation, unless the compiled engine is predicted to save at least this
#: (the conveyor's Radau: ~9 s; the example scenes' Radau runs: 0.03-0.2 s, whose recorded numbers then stay)
REFERENCE_KEEP_S = 1.0

# -------------------------------------------------------------------------------------- the run's pace
#: a run whose evaluations exceed the prediction this many times (and whose priced time exceeds PACE_MIN_S) says
#: so (counters, not the wall clock, so that the warning does not depend on the machine's load)
PACE_WARN_FACTOR = 5.0
PACE_MIN_S = 1.0
#: an auto DOP853/RK45 run on scipy goes on on the compiled engine (the same steps) when, after
#: PACE_SWITCH_AFTER_S of priced work, its pace projects the run to over PACE_SWITCH_FACTOR times its prediction
PACE_SWITCH_FACTOR = 4.0
PACE_SWITCH_AFTER_S = 2.0

# ------------------------------------------------------------------------------------- changing course
#: an auto run that has spent this many times its predicted evaluations or wall time re-decides from the state
#: it has reached (gearcli.simulate.course) ...
COURSE_FACTOR = 3.0
COURSE_MIN_NFEV = 2000.0  # ... its prediction taken as at least this many evaluations (a tiny run: noise) ...
COURSE_MIN_S = 0.3  # ... and this much wall time (the clock of a shared machine)
COURSE_MARGIN = 1.5  # another method or engine is taken when it is predicted to cost this much less than going on

# -------------------------------------------------------------------------------------------- budgets
COST_PER_UNIT = 30.0  # evaluations per unit of max|lambda| T at rtol 1e-6, any method (worst measured: 26)
HEADROOM = 10.0
FLOOR = 200_000  # ~1 s of right-hand sides: never stop a short soft run early
CAP = 5_000_000  # evaluations; then the run is called off
EXPLICIT_CAP = 1_000_000  # stability-only evaluations beyond which an explicit method is refused
WORK_CAP_S = 60.0  # priced seconds one run may use; then it is called off
PROJECTION_AFTER_S = 5.0  # priced seconds after which the pace is projected to the end of the run
PROJECTION_LIMIT = 4.0  # a projected total over this many times the run's budget stops it at once
BUDGET_CHECK_EVERY = 64  # accepted steps between checks of the priced budget
#: design-time refusal (gearcli.config.bounds): estimates beyond this are a unit mistake, not a scene. The
#: estimate is an upper bound for explicit methods; implicit ones step over fast modes that are not excited
#: (configs/extreme/unequal_inertias.toml: estimate 2.8e8, run within the budget), hence 100x the cap
ABSURD_EVALUATIONS = 100 * CAP


def nfev_budget(indicator: float, rtol: float, predicted: float = 0.0) -> int:
    """Right-hand-side evaluations a run of stiffness indicator ``max|lambda| T`` may use: ``HEADROOM`` times the
    larger of what its stiffness costs at worst and ``predicted`` (the cost model's evaluations for its method,
    :func:`predicted_evaluations`: an excitation to follow, which the stiffness does not count), within
    ``FLOOR`` .. ``CAP``: a run is not stopped before ten times its own prediction (a 100 kHz load fluctuation
    over 0.3 s, 1.9e5 rad of excitation, took ~7e5 evaluations where the scene's stiffness alone, max|lambda| T =
    2.0e3, budgeted 6.1e5)."""
    estimate = max(COST_PER_UNIT * max(indicator, 1.0) * accuracy_factor(rtol), predicted)
    return int(min(CAP, max(FLOOR, HEADROOM * estimate)))


def duration_text(seconds: float) -> str:
    if not math.isfinite(seconds):
        return "forever"
    for unit, size in (("days", 86400.0), ("hours", 3600.0), ("minutes", 60.0)):
        if seconds >= 2 * size:
            return f"{seconds / size:.3g} {unit}"
    return f"{seconds:.3g} s"
