"""``run_simulation``: the design file's scene, integrated and summarised into a SimulationResult."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace
from typing import TYPE_CHECKING

import numpy as np

from gearcli import diagnostics as dg
from gearcli import engine
from gearcli.core import cost
from gearcli.core.channels import Channel
from gearcli.core.jsontypes import JsonObject
from gearcli.core.methods import AUTO, EXPLICIT, EXPLICIT_METHOD, IMPLICIT_METHOD
from gearcli.diagnostics import Diagnostic
from gearcli.engine import EngineChoice
from gearcli.engine import choose as choose_engine
from gearcli.engine import options as engine_options
from gearcli.engine import reproducible as reproducible_batch
from gearcli.errors import ConfigError, SimulationError
from gearcli.model import TorsionalModel
from gearcli.model.damping import operating_load_factor
from gearcli.model.linear import damped_modes, operating_line_forces_N
from gearcli.model.modes import resonances
from gearcli.model.outputs import Sampled, sample, stage_rows, tangential_force_N
from gearcli.results import DesignResult, MeshStiffness
from gearcli.scene import spec_from_design
from gearcli.simulate import aliasing, estimate, orbit_check, rigid_start, sampling, spent, stats, stepped_over
from gearcli.simulate import settle as settle_mod
from gearcli.simulate.choice import STIFFNESS_LIMIT, Choice, choose_method
from gearcli.simulate.course import CourseChange, integrate_auto, pace_warnings, predicted_nfev, prediction
from gearcli.simulate.failures import check
from gearcli.simulate.guards import force_noise_warnings, nfev_budget, require_feasible
from gearcli.simulate.periodic import MAX_PERIODS, MAX_SUBHARMONIC, CommonPeriod, run_up_end, scene_period
from gearcli.simulate.planet_stats import peak_series, planet_contact_warnings, planet_series, planets_of, with_planets
from gearcli.simulate.results import EnergyBalance, SimulationResult, SolverStats, SteadyState
from gearcli.simulate.ringing import ringing_warnings
from gearcli.simulate.solver import Integration
from gearcli.simulate.start_rings import peak_warnings as start_peak_warnings

if TYPE_CHECKING:
    from gearcli.config.schema import DesignFile
    from gearcli.model.spec import MeshSpec

RAD_TO_DEG = 180.0 / math.pi
StageSeries = tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]  # F_t, F_r, F_a (N), pen. (mm), DTE (um)


def run_simulation(cfg: DesignFile, design: DesignResult, *, method: str | None = None, rtol: float | None = None,
                   want_series: bool = True, max_nfev: int | None = None,
                   y0: np.ndarray | None = None, model: TorsionalModel | None = None,
                   error_estimate: bool | None = None, settle: bool | str | None = None,
                   progress: Callable[[float], None] | None = None, diagnose: bool = True,
                   summary_start: bool = True) -> SimulationResult:
    """Simulate a validated ``DesignFile`` with its ``DesignResult`` (``method``/``rtol`` default to
    ``cfg.simulation``). ``want_series=False`` leaves ``time_s`` and ``series`` empty (the statistics
    are still computed from the full samples). ``max_nfev`` defaults to the scene's budget
    (:func:`gearcli.simulate.guards.nfev_budget`); ``y0`` overrides the initial state (continuation:
    :meth:`gearcli.model.TorsionalModel.continue_state`); ``model``: the scene's model when the caller has
    already built it (a sweep point), else built here; ``error_estimate`` (default
    ``simulation.error_estimate``) runs the check pass of :mod:`gearcli.simulate.estimate`; ``settle`` (default: when
    ``[rating] dynamic_factor = "simulated"``; ``"window"``: without the periodic fallback) repeats a run whose fixed
    window is not settled with a later window
    (:func:`gearcli.simulate.settle.settled_run`: the dynamic verdicts of life, sweep and report ask for it).
    ``diagnose=False``: the statistics without the window's ringing fit, settle test, resonance check, start-up
    summary and motor summary (a run only its statistics and counters are read from: the report's accuracy
    ladder). ``summary_start=False``: the start's warnings without ``summary.start`` (``extra["start"]``; a caller
    that reads no summary: a sweep row, a duty point; :func:`gearcli.simulate.rigid_start.start_summary`) nor
    ``extra["damped_modes"]`` (the report's spectrum reads them). The
    design's own warnings come first in the result's. Raises SimulationError on failure, never returns NaN."""
    sim = cfg.simulation
    if sim.window_start_s is not None and sim.window_start_s >= sim.duration_s:
        raise ConfigError(f"must be below simulation.duration_s = {sim.duration_s:g} s, got {sim.window_start_s:g}",
                          key="simulation.window_start_s")
    if model is None:
        model = TorsionalModel(spec_from_design(cfg, design))
    check = sim.error_estimate if error_estimate is None else error_estimate
    design_diags = _design_diagnostics(design)
    if settle is None:
        settle = cfg.rating is not None and cfg.rating.dynamic_factor == "simulated"
    pending: list[tuple[SimulationResult, Callable[[], SimulationResult]]] = []  # this call's unfinished runs
    made: list[SimulationResult] = []  # every run this call made: what the result cost (gearcli.simulate.spent)

    def run(duration_s: float, steps: int, window_start_s: float | None, steady: str = sim.steady,
            run_up_samples: int | None = None) -> SimulationResult:
        # a run the settle test may replace leaves its ringing fit for later (finish) where its window is unsettled
        unfinished: list[Callable[[], SimulationResult]] | None = [] if settle else None
        result = simulate_model(model, duration_s=duration_s, steps=steps, method=method or sim.method,
                                rtol=rtol or sim.rtol, window_start_s=window_start_s, want_series=want_series,
                                max_nfev=max_nfev, y0=y0, steady=steady, error_estimate=check,
                                prior_diagnostics=design_diags, engine=sim.engine, progress=progress,
                                unfinished=unfinished, diagnose=diagnose, run_up_samples=run_up_samples,
                                file_steps=max(1, round(steps * sim.duration_s / duration_s)),
                                summary_start=summary_start)
        if unfinished:
            pending.append((result, unfinished[0]))
        made.append(result)
        return result

    def finish(result: SimulationResult) -> SimulationResult:
        return next((whole() for r, whole in pending if r is result), result)

    periodic = settle != "window"
    if settle and periodic and sim.steady == "window" and _at_rest(model):
        # an unexcited scene's steady state is its equilibrium: the run from rest to simulation.duration_s, sampled
        # as the window run would be (its start-up peaks the same), then the periodic search from its end
        found = settle_mod.periodic_state(run, sim.duration_s, sim.steps, 0, sim.duration_s, run_up_samples=sim.steps)
        if found is not None:
            return spent.totalled(found, made)
        periodic = False  # the periodic search was tried: the later windows are what is left
    result = run(sim.duration_s, sim.steps, run_up_end(model, sim, from_rest=y0 is None))  # a window's: its start
    if settle:
        result = settle_mod.settled_run(result, run, sim.duration_s, sim.steps, periodic=periodic, finish=finish)
    return spent.totalled(result, made)


def _at_rest(model: TorsionalModel) -> bool:
    """The scene's steady state is its equilibrium (:func:`gearcli.simulate.equilibrium.applies`)."""
    from gearcli.simulate import equilibrium  # lazy: a settled or periodic run only (start-up time of a one-shot run)

    return equilibrium.applies(model)


def _design_diagnostics(design) -> list[Diagnostic]:
    """The design's warnings as diagnostics (code ``design``, with the check's data where the design has it)."""
    known = {d.message: d for d in getattr(design, "diagnostics", ())}
    return [known.get(w) or dg.warning(dg.DESIGN, w) for w in getattr(design, "warnings", ())]


def simulate_model(model: TorsionalModel, *, duration_s: float, steps: int, method: str = "auto",
                   rtol: float = 1e-6, window_start_s: float | None = None, want_series: bool = True,
                   y0: np.ndarray | None = None, max_nfev: int | None = None,
                   steady: str = "window", error_estimate: bool = True,
                   prior_diagnostics: list[Diagnostic] | None = None, engine: str = "auto",
                   progress: Callable[[float], None] | None = None,
                   tightened: Diagnostic | None = None,
                   unfinished: list[Callable[[], SimulationResult]] | None = None,
                   diagnose: bool = True, run_up_samples: int | None = None,
                   file_steps: int | None = None, summary_start: bool = True) -> SimulationResult:
    """The engine of :func:`run_simulation` on an assembled model (also used by tests with plain
    parameters); ``y0`` overrides the initial state (layout: :mod:`gearcli.model.assembly`);
    ``error_estimate`` runs the check pass over the fixed window (:mod:`gearcli.simulate.estimate`; a periodic orbit
    found by shooting is found again at rtol / 10: :mod:`gearcli.simulate.orbit_check`); ``prior_diagnostics`` (the
    design's warnings) lead the result's warnings; ``engine`` "auto", "python" or "compiled"
    (:func:`gearcli.engine.choose`); ``progress`` is called with the fraction of the run done (a terminal's
    progress bar, :mod:`gearcli.io.progress`; both engines).

    ``steady = "window"``: one run to ``duration_s``, statistics over the fixed window. ``"periodic"``: past
    the ramps (or ``window_start_s``) the run goes on period by period until the response repeats, at most
    until ``duration_s`` (:mod:`gearcli.simulate.periodic`), and the statistics are taken over whole periods.

    ``method = "auto"`` with the error estimate: when the check pass finds only window means unresolved, the
    run is repeated once at the rtol that resolves them (:func:`gearcli.simulate.estimate.means_rtol`);
    ``tightened`` is the repeat's ``rtol_tightened`` warning.

    ``unfinished`` (a list; a run the settle test may replace, :func:`gearcli.simulate.settle.settled_run`): a
    fixed window that the settle test finds unsettled skips its ringing fit, and the function that returns the
    whole result (ringing warnings included, the result without ``unfinished``) is appended to the list.
    ``diagnose=False``: no ringing fit, settle test, resonance check, start-up nor motor summary
    (:func:`run_simulation`). ``run_up_samples``: ``steady = "periodic"``'s run-up sampled with this many samples
    (default: as a window run over ``duration_s`` would sample it). ``file_steps``: the design file's
    ``simulation.steps`` that samples as densely as this run (a settled run's longer one keeps the density), which
    the sampling estimate's suggestion scales (default ``steps``). ``summary_start``: :func:`run_simulation`'s."""
    spec = model.spec
    window, diags = stats.steady_window(spec, duration_s, window_start_s)
    prior = list(prior_diagnostics or [])
    replaced = () if getattr(model, "generated", True) else ("a right-hand side replaced in Python",)
    candidates = engine_options(engine, model.arrays, (EXPLICIT_METHOD, IMPLICIT_METHOD), replaced)
    # the check pass integrates again; a sweep's checked point is priced as its family's (their method and engine)
    work = cost.CHECK_PASS_WORK if error_estimate and steady == "window" and not reproducible_batch() else 1.0
    choice = choose_method(spec, duration_s, method, rtol, candidates, work, layout=model.layout)
    given_nfev = max_nfev
    if max_nfev is None:  # the scene's own budget; an explicit method that cannot meet it is refused now
        max_nfev = nfev_budget(choice.indicator, rtol, predicted_nfev(choice, choice.method))
        require_feasible(choice, max_nfev)
    nfev_estimate = work * predicted_nfev(choice, choice.method)
    if steady == "periodic":  # auto prices the shooting's own span, the variational periods at their cost
        from gearcli.simulate.shooting import priced_nfev  # lazy: start-up time of a fixed window's one-shot run

        nfev_estimate = priced_nfev(nfev_estimate, model.layout, duration_s, window_start_s,
                                    at_rest=_at_rest(model))
    eng = choose_engine(engine, model.arrays, choice.method, nfev_estimate, replaced, choice.size)
    eng = _loadable(eng)
    first_engine = eng.engine  # what the prediction is priced on (a course change may move the run)
    fallback = [dg.warning(dg.ENGINE_FALLBACK, f'engine = "compiled": this scene runs on the Python engine: '
                           f"{eng.reason}", unsupported=list(eng.unsupported))] \
        if eng.unsupported and engine == "compiled" else []
    mask_window, steady_state, energy_from = window, None, 0
    changes: list[CourseChange] = []
    if steady == "periodic":
        diags = []  # the fixed window's warning does not apply: the window is found, not set
        from gearcli.simulate.shooting import integrate_shooting  # lazy: start-up time of a fixed window's run

        found = integrate_shooting(model, choice.method, rtol, steps=steps, duration_s=duration_s,
                                   window_start_s=window_start_s, y0=y0, max_nfev=max_nfev,
                                   fastest_rad_s=_fastest_rad_s(choice), engine=eng.engine,
                                   continued=y0 is not None, run_up_samples=run_up_samples)
        if isinstance(found, Integration):
            check(found, choice, duration_s, model)
            raise SimulationError("the periodic search stopped without a result; this is a bug, please report it")
        run, window, mask_window, steady_state = found.run, found.window_s, found.mask_window_s, found.steady
        energy_from = found.energy_from
        diags += steady_warnings(steady_state, found.period)
    else:
        t_eval = np.linspace(0.0, duration_s, steps + 1)
        run, changes = integrate_auto(model, t_eval, choice, rtol, eng.engine, requested_engine=eng.requested,
                                      y0=y0, max_nfev=max_nfev, progress=progress,
                                      enabled=choice.requested == AUTO and getattr(model, "generated", True))
        if changes:
            eng = replace(eng, engine=run.engine, reason=f"{eng.reason}; then {changes[-1].to} from "
                          f"t = {changes[-1].at_s:.4g} s (solver.course_changes)")
        steady_state = window_steady(model)
    check(run, choice, duration_s, model)
    error_estimate = error_estimate and (steady != "periodic" or orbit_check.applies(steady_state))
    # the drive's and the load's torques are read by the series' channels and a motor's summary alone (a sweep point
    # without a motor samples neither)
    torques = want_series or model.layout.drive.motor is not None
    if getattr(steady_state, "method", None) == "equilibrium":
        from gearcli.simulate import equilibrium  # lazy: a settled run's equilibrium only

        s = equilibrium.sampled(model.layout, run.t, run.y, energy_from, torques=torques, arrays=model.arrays)
    else:  # (the model's arrays, built for the engine's choice above: the compiled call's connector rows)
        s = sample(model.layout, run.t, run.y, torques=torques, arrays=model.arrays)
    energy = model.energy(s, run.y, start=energy_from)
    diags = prior + diags + fallback + (pace_warnings(run, choice) if not changes else []) \
        + stats.model_warnings(spec) \
        + _choice_warnings(choice)
    if not (error_estimate and choice.requested == AUTO):  # auto's own choice: the error estimate measures the noise
        diags += force_noise_warnings(choice, rtol)
    diags += resonance_warnings(model, choice) if diagnose else []
    ref = (orbit_check.check_pass(model, run, window, found.period.period_s, _fastest_rad_s(choice), max_nfev)
           if steady == "periodic" else estimate.check_pass(model, run, choice, window, max_nfev=max_nfev, sampled=s,
                                                            mixed=bool(changes))) if error_estimate else None
    mode = (stepped_over.unresolved_mode(choice, run, duration_s, window[0], s)
            or stepped_over.damped_ringing(choice, run.method, run.steps, s, duration_s, window)) \
        if ref is not None and ref.errors and steady != "periodic" else None
    nonsmooth = ref is not None and any(e.unresolved for e in ref.errors) and stats.leaves_flank(s, window, stats.gapless_meshes(spec))
    stat_diags = estimate.warnings(ref, run.method, _unloaded(spec), nonsmooth) if ref is not None else []
    if ref is not None and mode is not None:  # the check pass cannot see that mode: its warnings replace the estimate's
        ref, stat_diags = stepped_over.mode_unresolved(ref, mode, run, duration_s)
    if ref is not None:  # the run's peak |F_t| (docs/numerics.md, "The run's peak")
        stat_diags += estimate.peak_warnings(ref, run.rtol, run.method)
    finer = estimate.means_rtol(ref) if ref is not None and mode is None and tightened is None \
        and choice.requested == AUTO else None
    if ref is not None and finer is not None:  # auto resolves the means at a tighter rtol (docs/numerics.md "... auto")
        again = simulate_model(model, duration_s=duration_s, steps=steps, method=method, rtol=finer,
                               window_start_s=window_start_s, want_series=want_series, y0=y0, max_nfev=given_nfev,
                               steady=steady, error_estimate=True, prior_diagnostics=prior_diagnostics,
                               engine=engine, progress=progress,
                               tightened=estimate.tightened_warning(run, ref, finer), unfinished=unfinished,
                               diagnose=diagnose, run_up_samples=run_up_samples, file_steps=file_steps,
                               summary_start=summary_start)
        return spent.added(again, run.nfev + ref.nfev, run.wall_s + ref.wall_s)  # this run and its check replaced
    if tightened is not None:
        diags.append(tightened)

    def summary(deferred: list[bool] | None) -> SimulationResult:
        out = _summarise(model, s, run, choice, (window, mask_window), energy, list(diags), want_series, steady_state,
                         ref, stat_diags, eng.reason, deferred, diagnose, steps=file_steps or steps,
                         from_rest=y0 is None, prediction=prediction(choice, first_engine, nfev_estimate / work),
                         course_changes=tuple(c.as_json() for c in changes), summary_start=summary_start)
        _require_finite(out)
        return out

    deferred: list[bool] | None = [] if unfinished is not None else None
    result = summary(deferred)
    if deferred and unfinished is not None:
        unfinished.append(lambda: summary(None))
    return result


def _loadable(eng: EngineChoice) -> EngineChoice:
    """``auto``'s compiled choice, or Python with the reason when the kernel cannot be loaded or compiled here
    (an explicit ``compiled`` lets the error through)."""
    if eng.engine != "compiled" or eng.requested != "auto":
        return eng
    try:
        engine.load()
    except Exception as exc:  # numba cannot compile or cache here: scipy runs it
        return EngineChoice("python", eng.requested, f"the compiled engine could not be loaded ({type(exc).__name__}: "
                            f"{exc})")
    return eng


def mesh_stiffness(model: TorsionalModel, choice: Choice) -> tuple[MeshStiffness, ...]:
    """The contact law each mesh used, in the design file's units: K (N/mm^e), and its slope along the normal
    at the static approach h0 of the linearisation at full load, e K h0^(e-1) (N/mm; the design's
    ``linearised_stiffness_N_mm``; K itself for e = 1), with h0 (mm), the law's name and ISO 6336-1's k_n (N/mm)."""
    return tuple(_law(m, h) for m, h in zip(model.spec.meshes, choice.at_full_load.penetration_m.tolist(), strict=True))


def planet_ring_stiffness(model: TorsionalModel, choice: Choice) -> dict[int, MeshStiffness]:
    """Per planetary stage (0-based), its planet–ring mesh's law as :func:`mesh_stiffness` gives the sun–planet
    mesh's (planet 1's meshes stand for the stage; DESIGN section 13: every mesh's ``mesh_stiffness``)."""
    out, models = {}, model.spec.stage_models
    for c, x in enumerate(model.layout.connectors):
        ring = (getattr(models[x.index], "ring_mesh", None)  # planet 1's ring mesh alone
                if x.gear == "ring" and x.planet == 0 and 0 <= x.index < len(models) else None)
        if ring is not None:
            out[x.index] = _law(ring, float(choice.at_full_load.deflection[c]))
    return out


def _law(m: MeshSpec, h0_m: float) -> MeshStiffness:
    K = m.stiffness_N_m_e / 1000.0**m.exponent
    h0 = h0_m * 1000.0
    slope = m.exponent * K * h0 ** (m.exponent - 1.0) if h0 > 0 or m.exponent == 1.0 else 0.0
    return MeshStiffness(law_N_mm_e=K, exponent=m.exponent, linearised_N_mm=slope, static_approach_mm=h0,
                         law=m.law, K=K, iso_N_mm=m.iso_normal_stiffness_N_m / 1000.0)


def _residual_text(residual: float | None) -> str:
    return " (no period fits before simulation.duration_s)" if residual is None \
        else f" (residual {residual:.3g} x the tolerance)"


def _fastest_rad_s(choice: Choice) -> float:
    freqs = choice.at_operating_point.natural_frequencies_Hz  # an array (the method: np.max's reduction, without
    return 2.0 * math.pi * float(freqs.max()) if freqs.size else 0.0  # its dispatch)


def window_steady(model: TorsionalModel) -> SteadyState:
    """``steady = "window"``: the fixed window; the excitation period for information."""
    period = scene_period(model.layout)
    return SteadyState(mode="window", period_s=period.period_s, periods_to_converge=None, periodicity=None,
                       converged=None, residual=None, period_source=period.source)


def steady_warnings(steady: SteadyState, period: CommonPeriod) -> list[Diagnostic]:
    """A response that did not repeat, or repeats only after k periods; a period that is not common."""
    from gearcli.simulate.shooting import fell_back  # lazy: start-up time of a fixed window's one-shot run

    out = []
    if not period.exact:
        out.append(dg.warning(dg.PERIOD_NOT_COMMON, f"steady = \"periodic\": the excitations have no usable common "
                              f"period; the period used is {period.source}", period_s=period.period_s))
    if not steady.converged:
        out.append(dg.warning(dg.NOT_PERIODIC, f"steady = \"periodic\": the response did not repeat over "
                              f"{steady.periods_to_converge} excitation periods of {steady.period_s:.4g} s, nor after "
                              f"2 .. {MAX_SUBHARMONIC} of them{_residual_text(steady.residual)}: "
                              "not periodic (chaotic or quasi-periodic) or still settling — lengthen "
                              f"simulation.duration_s to search longer (cap {MAX_PERIODS} periods); the statistics "
                              f"are over the last {steady.window_periods} periods", periods=steady.periods_to_converge,
                              residual=steady.residual))
    if fell_back(steady):
        out.append(dg.warning(dg.SHOOTING_FALLBACK, f"steady = \"periodic\": {steady.note}", note=steady.note))
    if steady.bifurcation in ("fold", "period doubling") and steady.multipliers:
        mu = max(steady.multipliers, key=lambda m: -abs(complex(*m) - (1.0 if steady.bifurcation == "fold" else -1.0)))
        what = "a fold: the branch turns back nearby, the response may jump to another branch" \
            if steady.bifurcation == "fold" else "a period doubling nearby"
        out.append(dg.warning(dg.NEAR_BIFURCATION, f"steady = \"periodic\": Floquet multiplier {mu[0]:.3g} near "
                              f"{'+1' if steady.bifurcation == 'fold' else '-1'}: {what}",
                              bifurcation=steady.bifurcation, multiplier=mu))
    if steady.converged and steady.periodicity != "period-1":
        out.append(dg.warning(dg.SUBHARMONIC, f"steady = \"periodic\": the response repeats only every "
                              f"{steady.window_periods} excitation periods ({steady.periodicity}, a subharmonic "
                              f"response); the statistics are over those {steady.window_periods} periods",
                              periodicity=steady.periodicity))
    return out


def _series(model: TorsionalModel, s: Sampled, channels: bool = True) -> tuple[dict[Channel, np.ndarray],
                                                                               list[StageSeries], np.ndarray]:
    """The time series in SI, keyed by what they are, in the output's column order (docs/output.md; the names
    and units are :mod:`gearcli.io.channels`'); and per stage (F_t, F_r, F_a in N, penetration in mm, DTE in
    um) for its statistics, the rows of one array (:func:`gearcli.model.outputs.stage_rows`, also returned). Reducer
    shafts first (a flexible shaft reports its gear end), then the drivetrain's own channels. ``channels=False``: the
    stages' series alone (a run that keeps no series)."""
    lay = model.layout
    rows = stage_rows(lay, s.meshes)
    per_stage: list[StageSeries] = list(zip(*[iter(rows)] * 5, strict=True))  # the rows' views, five a stage
    if not channels:
        return {}, per_stage, rows
    ch: dict[Channel, np.ndarray] = {Channel("speed", f"shaft{i + 1}"): s.omega_rad_s[b]
                                     for i, b in enumerate(lay.shaft_body)}
    ch[Channel("torque", "input")] = s.input_torque_Nm
    for k, ms in enumerate(s.meshes):
        ft, fr, fa = per_stage[k][:3]
        stage = f"stage{k + 1}"
        ch.update({Channel("tangential_force", stage): ft, Channel("radial_force", stage): fr,
                   Channel("axial_force", stage): fa, Channel("penetration", stage): ms.penetration_m,
                   Channel("dte", stage): ms.dte_m})
    for (k, j, gear), (ft, dte_m) in planet_series(model, s).items():  # a planetary stage: every planet mesh
        ch[Channel("tangential_force", f"stage{k + 1}_planet{j + 1}_{gear}")] = ft
        ch[Channel("dte", f"stage{k + 1}_planet{j + 1}_{gear}")] = dte_m
    for shaft, c in sorted(lay.shaft_conn.items()):
        ch[Channel("twist", f"shaft{shaft + 1}")] = s.connectors[c].deflection
    if lay.motor_body is not None:
        ch[Channel("speed", "motor")] = s.omega_rad_s[lay.motor_body]
    if lay.drum_body is not None:
        ch[Channel("speed", "drum")] = s.omega_rad_s[lay.drum_body]
    if lay.drive.motor is not None:  # the motor (drive = "motor", or the one a speed ramp is checked against)
        ch[Channel("torque", "drive")] = s.input_torque_Nm
        ch[Channel("speed", "drive")] = s.omega_rad_s[0]
    for owner, label in (("input_coupling", "input coupling"), ("load_coupling", "load coupling")):
        named = lay.conn_named(label)
        if named is not None:
            ch[Channel("torque", owner)] = s.connectors[named].force
    return ch, per_stage, rows


def _summarise(model: TorsionalModel, s: Sampled, run: Integration, choice: Choice, windows, energy,
               diags: list[Diagnostic], want_series: bool, steady: SteadyState,
               ref: estimate.CheckPass | None = None, stat_diags: list[Diagnostic] | None = None,
               engine_reason: str = "as requested", deferred: list[bool] | None = None,
               diagnose: bool = True, steps: int | None = None, from_rest: bool = True,
               prediction: JsonObject | None = None, course_changes: tuple[JsonObject, ...] = (),
               summary_start: bool = True) -> SimulationResult:
    """``windows``: the reported statistics window and the one the sample mask uses (for whole periods,
    the window without its closing sample, which starts the next period). ``steps``: the run's
    ``simulation.steps`` (the sampling estimate's suggestion scales it; whole periods: the window's samples). ``deferred`` (a list): a fixed window
    that the settle test finds unsettled skips the ringing fit and says so (``True`` appended); a settled one has
    its ringing warnings after the settle test's (which adds none then: the same warnings, in the same order).
    ``from_rest``: the run started from rest (not continued from another run's state): only then a start summary.
    ``prediction``, ``course_changes``: the solver's (:class:`SolverStats`). ``summary_start=False``: the start's
    warnings without its summary (:func:`run_simulation`)."""
    spec = model.spec
    window, mask_window = windows
    mask = stats.window_mask(s.time_s, mask_window)
    periodic = steady.mode == "periodic"
    series, per_stage, rows = _series(model, s, want_series)
    stiffness, simulated_static = mesh_stiffness(model, choice), simulated_static_tangential_N(model)
    ks = range(len(spec.meshes))
    solver_errors = [ref.errors[k] if ref is not None and k < len(ref.errors) else None for k in ks]
    run_s = float(s.time_s[-1] - s.time_s[0]) if s.time_s.size > 1 else 0.0
    share = (window[1] - window[0]) / run_s if run_s > 0 else 1.0  # the window's share of the samples
    floors = estimate.force_floors_N(model, run.rtol)  # an unloaded stage's least reference force
    statics, flank = [m.static_tangential_N for m in spec.meshes], stats.loaded_flank(operating_load_factor(model.layout))
    reduced = stats.window_reductions(s.time_s, mask, per_stage[:len(ks)], [flank * f for f in statics], periodic, rows)
    # a periodic window is judged without the modes (its own grid); every planet mesh's series and window, made once
    planets = planet_series(model, s)
    pw = stats.planet_windows(s.time_s, mask, planets, periodic)
    samplings = aliasing.window_sampling(s.time_s, mask, per_stage, spec, solver_errors, steps, periodic, share,
                                         floors, reduced, model.layout, None if periodic else choice.run_eigenvalues,
                                         planets, pw)
    merged = [sampling.merged(e, se) if e is not None and se is not None else e
              for e, se in zip(solver_errors, samplings, strict=True)]
    stages = tuple(stats.stages_dynamics(
        s.time_s, mask, per_stage[:len(ks)], statics, periodic=periodic, reduced=reduced,
        simulated_static_N=simulated_static, gapless=stats.gapless_meshes(spec),
        error_estimate=merged, sampling_error=samplings,
        mesh_stiffness=[stiffness[k] if k < len(stiffness) else None for k in ks],
        type=[spec.stage_types[k] if k < len(spec.stage_types) else "parallel" for k in ks]))
    peaks = [st.peak_tangential_N for st in stages] if len(stages) == len(per_stage) else None  # max |F_t|, each
    stages = tuple(with_planets(st, *planets_of(model, s, mask, k, periodic, planets, pw))
                   for k, st in enumerate(stages))
    rings = planet_ring_stiffness(model, choice)
    stages = tuple(replace(st, planet_ring_mesh_stiffness=rings[k]) if k in rings else st for k, st in enumerate(stages))
    # the reducer's ratio: shaft 1 over the last shaft, not motor over drum (the window's samples read in place)
    shafts = model.layout.shaft_body
    first, last, sel = shafts[0], shafts[-1], stats.window_slice(mask) if reduced is None else reduced.sel
    # the window means as every mean of simulate: the integral over the window (trapezoid rule, DESIGN section 7);
    # the samples' plain mean erred by (mean - (x_0 + x_N)/2) / N (1.5e-4 on a speed swinging 12 % over 240 samples)
    w_in, w_out = (float(w) for w in stats.window_means(s.time_s[sel], s.omega_rad_s[:, sel][[first, last]], periodic))
    ratio, ratio_warnings = stats.ratio_of(w_in, w_out)
    contacts = [ms.penetration_m if model.layout.connectors[c].role == "mesh" else None
                for c, ms in zip(model.layout.stage_conn, s.meshes, strict=True)]
    diags += ratio_warnings + stats.contact_warnings(spec, mask, contacts, choice.at_full_load.penetration_m, reduced,
                                                     planet_contact_warnings(model, s, mask, flank), flank)
    toggled = None
    if model.layout.drive.motor is not None:
        from gearcli.simulate import motor as motor_side  # lazy: a motor drive's run only

        toggled = (motor_side.reswitches(model.layout.drive.motor, s.time_s, s.omega_rad_s[0])
                   if model.layout.motor_drive else None)
    start_doc, start_diags = rigid_start.start_summary(model.layout, choice.boundary, s.time_s,
                                                       [p[0] for p in per_stage], window, stats.WARN_PEAK_OVER_RIGID,
                                                       reswitch_s=None if toggled is None else toggled[2],
                                                       summary=summary_start, peaks_N=peaks) \
        if diagnose and from_rest else (None, [])  # a continued run (a sweep's next point) has no start from rest
    diags += start_diags
    motor_summary = None
    if model.layout.drive.motor is not None and diagnose:
        motor_summary, motor_diags = motor_side.summary(model.layout, s.time_s, s.omega_rad_s[0], s.input_torque_Nm,
                                                        mask, window, periodic, omega=s.omega_rad_s)
        diags += motor_diags
    if (residual := energy.residual_relative) > stats.WARN_ENERGY_RESIDUAL:  # (a property: read once)
        diags.append(dg.warning(dg.ENERGY_RESIDUAL, f"energy balance residual {residual:.2g} exceeds "
                                f"{stats.WARN_ENERGY_RESIDUAL:g}: tighten simulation.rtol",
                                residual=residual))
    diags += stat_diags or []
    diags += sampling.warnings([(k + 1, se) for k, se in enumerate(samplings) if se is not None],
                               {e.stage: e for e in solver_errors if e is not None}, _unloaded(spec)) \
        + aliasing.warnings(samplings)
    if not periodic:  # a periodic window has its own grid: 64 samples a period of its fastest excitation
        sel = stats.window_slice(mask)
        diags += sampling.excitation_warnings(model.layout, s.time_s[sel], steps or s.time_s.size - 1)
        diags += sampling.window_period_warnings(model.layout, s.time_s[sel],  # the mean's partial period
                                                 [np.asarray(p[0])[sel] for p in per_stage[:len(samplings)]],
                                                 [se.reference_N if se is not None else None for se in samplings],
                                                 _unloaded(spec))
        if diagnose and from_rest:  # the start's peak (a continued run has no start)
            peaks_N = peak_series(model, s, [p[0] for p in per_stage])
            n_steps, fastest_Hz = steps or s.time_s.size - 1, max(choice.natural_frequencies_Hz, default=0.0)
            found = aliasing.peak_warnings(sampling.peak_warnings(s.time_s, peaks_N, n_steps, fastest_Hz, diags),
                                           samplings, s.time_s, peaks_N, n_steps, fastest_Hz)
            diags += start_peak_warnings(found, model, choice.boundary, s.time_s, peaks_N, n_steps)

    def ringing_diags() -> list[Diagnostic]:
        return ringing_warnings(model, choice, s.time_s, mask, [p[0] for p in per_stage],
                                [st.simulated_static_tangential_N or 0.0 for st in stages], window, floors)

    if not periodic and deferred is None and diagnose:
        diags += ringing_diags()
    if diagnose:
        steady, stages = settle_mod.settled_steady(model, choice, s.time_s, mask, window, per_stage, stages, steady,
                                                   motor_summary, diags, floors, s.omega_rad_s[first])
    if not periodic and deferred is not None:
        if steady.settled is False:
            deferred.append(True)
        else:
            diags += ringing_diags()
    solver = SolverStats(
        method=run.method, requested_method=choice.requested, choice_reason=choice.reason, rtol=run.rtol,
        atol=_atol_summary(model, run.atol),
        nfev=run.nfev, njev=run.njev, nlu=run.nlu, steps=run.steps, wall_s=run.wall_s,
        energy_residual=residual, status=run.status, message=run.message,
        check_pass=ref.summary() if ref is not None else None, engine=run.engine, engine_reason=engine_reason,
        compile_s=run.compile_s, prediction=prediction, course_changes=course_changes)
    balance = EnergyBalance(energy.input_work_J, energy.load_work_J, energy.damping_loss_J, energy.kinetic_change_J,
                            energy.potential_change_J, residual, energy.parametric_work_J)
    return SimulationResult(
        time_s=s.time_s if want_series else np.empty(0), series=series if want_series else {},
        window_s=(float(window[0]), float(window[1])), ratio=ratio, output_speed_deg_s=w_out * RAD_TO_DEG,
        input_speed_deg_s=w_in * RAD_TO_DEG, stages=stages, solver=solver, energy=balance,
        warnings=dg.messages(diags), diagnostics=tuple(diags),
        natural_frequencies_Hz=choice.natural_frequencies_Hz, natural_frequencies_boundary=choice.boundary,
        final_state=run.y[:, -1].copy(), final_time_s=float(run.t[-1]), steady=steady,
        extra={"parametric_work_J": energy.parametric_work_J,
               "stiffness_indicator": choice.indicator,
               "natural_frequencies_runup_Hz": [float(f) for f in choice.at_operating_point.natural_frequencies_Hz],
               **({"damped_modes": damped_modes(choice.run_eigenvalues)} if summary_start else {}),  # the report's
               **({"motor": motor_summary} if motor_summary is not None else {}),
               **({"start": start_doc} if start_doc else {})},
    )


def _unloaded(spec) -> frozenset[int]:
    """The stages (1-based) that carry no static force: their statistics' targets refer to the channel's rms
    (:func:`gearcli.simulate.estimate.force_reference`)."""
    return frozenset(k + 1 for k, m in enumerate(spec.meshes) if m.static_tangential_N == 0.0)


def simulated_static_tangential_N(model: TorsionalModel) -> list[float]:
    """Per stage, the static F_t of the load the simulation applies, with the losses its dynamics model (the
    model's own steady-state connector forces, the meshes' efficiencies included: on a settled unexcited run the
    window means equal them and the design's static F_t): the reference of the dynamic and run-up factors.

    A speed-dependent load (``load.speed_exponent``, ``load.torque_speed``) is taken at the speed the train runs
    at (:func:`gearcli.model.damping.operating_speed_rad_s`: a motor's operating point, a torque drive's balance),
    not at the nominal speed its ``torque_Nm`` is given for: a torque drive settling at 1.28x the nominal speed of
    a quadratic load carried 1.65x the nominal force, which read as a dynamic factor of 1.65 on a steady run."""
    lay = model.layout
    return [tangential_force_N(lay, k, f) for k, f in
            enumerate(operating_line_forces_N(lay, operating_load_factor(lay)).tolist())]


def _atol_summary(model: TorsionalModel, atol: np.ndarray) -> dict[str, float]:
    """The smallest absolute tolerance of each state group (deflections, speeds)."""
    lay, meshes, each = model.layout, set(model.layout.stage_conn), atol.tolist()  # minima of floats: numpy's
    out = {"deflection_m": min(each[c] for c in lay.stage_conn),
           "speed_rad_s": min(each[lay.state.speeds])}
    springs = [each[c] for c in range(lay.n_conn) if c not in meshes]
    return {**out, "twist_rad": min(springs)} if springs else out


def _choice_warnings(choice: Choice) -> list[Diagnostic]:
    """A requested explicit method on a stiff scene where ``auto`` takes Radau (its own rule: the cost margin)."""
    if choice.requested != AUTO and choice.method in EXPLICIT and choice.indicator > STIFFNESS_LIMIT \
            and choice.auto_method == IMPLICIT_METHOD:
        return [dg.warning(dg.STIFF_FOR_EXPLICIT, f"the scene is stiff for an explicit method (max|λ|·T = "
                           f"{choice.indicator:.2g}, at least {choice.explicit_evaluations(choice.method):.2g} "
                           f'evaluations for stability alone): method = "auto" would use {IMPLICIT_METHOD}',
                           indicator=choice.indicator)]
    return []


def resonance_warnings(model: TorsionalModel, choice: Choice) -> list[Diagnostic]:
    """A mesh order (1x-3x mesh frequency), shaft order (1x), input torque ripple order or load fluctuation at the
    nominal speed within 10 % of a natural frequency that it excites (its meshes' share of the mode's strain energy,
    a torque's body's share of its kinetic energy, over twice the modal damping ratio at least 0.1), naming the mode, its dominant element and how strongly (:mod:`gearcli.model.modes`). The
    model's own: found once per layout and boundary (a sweep point's settle runs ask again)."""
    cache = model.layout.__dict__.setdefault("_resonance_warnings", {})
    if choice.boundary not in cache:
        cache[choice.boundary] = [dg.warning(dg.RESONANCE, r.message, **r.data, boundary=choice.boundary)
                                  for r in resonances(model.layout, boundary=choice.boundary,
                                                      full_load=(choice.at_full_load.stiffness,
                                                                 choice.at_full_load.damping))]
    return list(cache[choice.boundary])


def _require_finite(result: SimulationResult) -> None:
    bad = [str(name) for name, x in result.series.items() if not np.all(np.isfinite(x))]
    scalars = [result.ratio, result.output_speed_deg_s, result.energy.residual_relative]
    if bad or not all(math.isfinite(v) for v in scalars):
        raise SimulationError("the simulation produced non-finite values"
                              + (f" in {', '.join(bad[:4])}" if bad else "") + "; this is a bug, please report it")
