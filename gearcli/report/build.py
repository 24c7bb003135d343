"""Assemble a :class:`Report`: the file's own simulation, theory against it, and the accuracy study."""

from __future__ import annotations

from collections.abc import Callable
from functools import partial
from typing import TYPE_CHECKING

from gearcli import diagnostics as dg
from gearcli import engine
from gearcli.core.cost import WORK_CAP_S, accuracy_factor, compiled_speedup, duration_text, priced_work_s
from gearcli.core.methods import EXPLICIT_METHOD, METHODS
from gearcli.core.records import record
from gearcli.core.text import rounded_down
from gearcli.design.standards import with_simulated_rating
from gearcli.errors import ConfigError, SimulationError, StudyTooLong
from gearcli.model import TorsionalModel
from gearcli.model.damping import operating_load_factor, settling_speed_rad_s
from gearcli.model.modes import campbell_data, modal_analysis
from gearcli.report.accuracy import LadderSpec, ProgressFn, accuracy_study, same_rtol
from gearcli.report.checks import accuracy_checks, energy_check, sampling_checks
from gearcli.report.compare import comparison_rows, rating_comparison, stage_reports, window_speed_factor
from gearcli.report.result import AccuracyStudy, Report, TheoryPoint
from gearcli.results import DesignResult
from gearcli.scene import spec_from_design
from gearcli.simulate.results import SimulationResult
from gearcli.simulate.run import run_simulation
from gearcli.stages.design import design_kind

if TYPE_CHECKING:
    from gearcli.config.schema import DesignFile

SimulateFn = Callable[..., SimulationResult]  # gearcli.simulate.run_simulation's signature


def _require_gear_meshes(design: DesignResult) -> None:
    """The report compares each stage's gear mesh (its mesh frequency, spectrum, K_v) with its theory: a stage of
    a kind without one (a belt) is exit 2 naming it, before any run."""
    other = [st for st in design.stages if not design_kind(st).gear_pair]
    if other:
        st = other[0]
        raise ConfigError(f"gearcli report compares every stage's gear mesh with its theory, and stage {st.index} is "
                          f'of type "{getattr(st, "type", "?")}", which has none: run gearcli simulate on this file',
                          key=f"stage[{st.index - 1}].type")


def build_report(
    cfg: DesignFile,
    design: DesignResult,
    *,
    accuracy: float = 1e-4,
    quick: bool = False,
    spec: LadderSpec | None = None,
    progress: ProgressFn | None = None,
    simulate: SimulateFn | None = None,
) -> Report:
    """Run the design file's scene with its own ``[simulation]`` settings and compare it with the
    design's static values; unless ``quick``, add the work-precision study (see ``report.accuracy``).

    ``cfg`` is the validated ``DesignFile``; ``simulate`` defaults to ``gearcli.simulate.run_simulation``
    (tests pass a stand-in); ``progress(label, done, total)`` is called before each run.
    """
    _require_gear_meshes(design)
    spec = spec or LadderSpec()
    modes, model = None, None
    if simulate is None:
        # every run of the report is the same scene (only method and rtol change): one model, generated once
        model = TorsionalModel(spec_from_design(cfg, design))
        simulate = partial(run_simulation, model=model)
        modes = _modes(model.layout, cfg.simulation.duration_s)
    tick = progress or (lambda label, done, total: None)
    sim_cfg = cfg.simulation
    planned = 1 if quick else 1 + 2 + len(spec.rtols) * len(spec.methods)
    if not quick and sim_cfg.engine == "auto":  # the ladder (~25 runs, a reference at rtol 1e-12) always
        # repays loading the compiled engine: load it once, for every DOP853 rung

        engine.expect_runs(planned)
        if engine.available():
            try:
                engine.load()
            except Exception:  # numba cannot compile or cache here: every run stays on scipy  # noqa: BLE001
                pass
    tick(f"simulation ({sim_cfg.method}, rtol {sim_cfg.rtol:g})", 0, planned)
    # the comparison is a dynamic verdict: from a window shown settled (gearcli.simulate.settle), moved later within
    # the budget; the window stays a window (its spectrum and statistics sections), an unsettled one says so
    own = simulate(cfg, design, want_series=True, settle="window") if model is not None else simulate(
        cfg, design, want_series=True)
    sim = with_simulated_rating(cfg, design, own)  # the rating at the run's K_v (simulate knows no standard)
    prescribed = model is None or model.layout.speed_drive  # a stand-in simulate: the design's speeds
    stages = stage_reports(design, sim, window_speed_factor(design, sim, prescribed))
    study, failure = None, None
    if not quick:
        try:
            study = _study(Ladder(cfg, design, own, sim, model, simulate), spec, accuracy, tick)
        except SimulationError as exc:  # the reference failed or diverged, or the study's budget ran out
            failure = str(exc)  # (StudyTooLong): the engineering sections stand; the study's section says why
    checks = (*(dg.warning(dg.ENERGY_RESIDUAL, w, residual=sim.solver.energy_residual) for w in energy_check(sim)),
              *sampling_checks(stages, sim.natural_frequencies_Hz, sim_cfg.steps),
              *accuracy_checks(study, sim_cfg.method, sim_cfg.rtol),
              *([dg.warning(dg.ACCURACY, study_failed_text(failure), failed=True)] if failure else []))
    warnings = _merge(design.warnings, sim.warnings, dg.messages(checks))
    diagnostics = (*getattr(design, "diagnostics", ()), *sim.diagnostics, *checks)
    point = theory_point(model.layout, design) if model is not None else None
    return Report(title=design.title, design=design, simulation=sim, comparison=comparison_rows(design, sim, point),
                  stages=stages, accuracy=study, warnings=warnings, diagnostics=diagnostics,
                  rating=rating_comparison(design, sim),
                  modes=modes[0] if modes else None, campbell=modes[1] if modes else None,
                  accuracy_failure=failure, theory_point=point)


def theory_point(lay, design: DesignResult) -> TheoryPoint | None:
    """The operating point the comparison's theory is taken at where the drive does not prescribe the speed (a
    motor, a torque drive) and the train settles away from the design's nominal speed or load (where it runs: a
    motor's first crossing from rest, a stall below its breakdown speed too); None where it settles there (a speed
    drive, a torque drive against a constant load it balances). Where it settles nowhere (a motor that cannot
    start or runs away, a torque drive nothing balances) the point is the nominal one with ``reached`` False."""
    if lay.speed_drive or lay.drive.speed_rad_s <= 0.0:
        return None
    drive = "motor" if lay.motor_drive else "torque"
    settles = settling_speed_rad_s(lay)
    if settles is None:
        return TheoryPoint(drive=drive, input_speed_deg_s=design.input_speed_deg_s,
                           nominal_input_speed_deg_s=design.input_speed_deg_s, load_factor=1.0, reached=False)
    factor = settles / lay.drive.speed_rad_s
    load = operating_load_factor(lay)
    if factor == 1.0 and load == 1.0:
        return None
    return TheoryPoint(drive=drive, input_speed_deg_s=factor * design.input_speed_deg_s,
                       nominal_input_speed_deg_s=design.input_speed_deg_s, load_factor=load)


def study_failed_text(failure: str) -> str:
    """The warning of a report whose accuracy study failed (``Report.accuracy_failure`` is ``failure``)."""
    return (f"the accuracy study failed, so the file's solver settings are not checked against a reference: {failure}; "
            "the theory-against-simulation sections are the file's own run, complete")


@record
class Ladder:
    """What the accuracy study runs on: the file, its design, its own run (``own``, the rating at the run's K_v:
    ``sim``), the model every run shares (None with a stand-in ``simulate``) and the simulate function."""

    cfg: DesignFile
    design: DesignResult
    own: SimulationResult
    sim: SimulationResult
    model: TorsionalModel | None
    simulate: SimulateFn


def _study(lad: Ladder, spec: LadderSpec, accuracy: float, tick: ProgressFn) -> AccuracyStudy:
    """The work-precision study (``report.accuracy``) within the report's budget; raises SimulationError when the
    reference or its check fails, StudyTooLong when the budget cannot hold it."""
    sim_cfg, sim, own, model = lad.cfg.simulation, lad.sim, lad.own, lad.model
    budget = ReportBudget(_work(sim), sim_cfg.duration_s)
    budget.check_projection(sim.solver.rtol, spec)  # the run's own rtol (auto may have tightened it)
    shared = own if same_as_rung(own, sim_cfg) else None
    compiled = _ladder_compiled(model, sim_cfg.engine)

    def run(method: str, rtol: float) -> SimulationResult:
        if shared is not None and method == sim_cfg.method and same_rtol(rtol, sim_cfg.rtol):
            return shared  # the file's settings' rung is the file's own run (its work is counted already)
        # a rung's error is measured against the study's reference, so its own check pass (issue 10's
        # estimate, which doubles a run) would be computed and never read
        # nor its ringing fit, settle test and resonance check: the study reads its statistics and counters only
        out = lad.simulate(lad.cfg, lad.design, method=method, rtol=rtol, want_series=False, error_estimate=False,
                           **({"diagnose": False} if model is not None else {}))
        budget.spend(_work(out))
        return out

    with engine.batch(0):  # the ladder: auto may run Radau compiled too (labelled)
        return accuracy_study(
            run, file_method=sim_cfg.method, file_rtol=sim_cfg.rtol, accuracy=accuracy, spec=spec,
            auto_choice=sim.solver.method if sim_cfg.method == "auto" else None,
            stiffness_indicator=(sim.extra or {}).get("stiffness_indicator"),
            explicit_speedup=compiled_speedup(EXPLICIT_METHOD) if compiled else 1.0,
            engine_methods=engine.COMPILED_METHODS if compiled else None,
            progress=lambda label, done, total: tick(label, done + 1, total + 1),
        )


def same_as_rung(sim: SimulationResult, sim_cfg) -> bool:
    """Whether the file's own run is the run its rung of the ladder would make, step for step, so that the rung
    reuses it: the same method and rtol (auto did not tighten it), the fixed window kept (no settle re-run), no
    course change, and the engine the rung takes (a rung runs in the ladder's batch, where ``auto`` takes the
    loaded compiled engine for every method it has; the file's run, outside it, may keep a short Radau run on
    scipy). What the file's run does beyond the rung (its check pass, series, ringing fit, settle test) reads the
    run and leaves it as it is; the method choice weighs the check pass against the engine's load only, which is
    paid before the file's run (gearcli.simulate.choice.predicted_costs)."""
    sv, steady = sim.solver, sim.steady
    return (sv.requested_method == sim_cfg.method and same_rtol(sv.rtol, sim_cfg.rtol) and not sv.course_changes
            and (sv.engine == "compiled" or sim_cfg.engine != "auto") and sv.status == 0
            and (steady is None or not steady.settle_runs))


def _ladder_compiled(model: TorsionalModel | None, requested: str) -> bool:
    """Whether the ladder runs on the compiled engine (loaded, the scene supported): its explicit reference is
    then priced at the compiled engine's speed-up and no rung swaps to a sibling it cannot run (report.accuracy)."""
    if model is None or requested == "python" or engine.loaded_kernel() is None:
        return False
    replaced = () if getattr(model, "generated", True) else ("a right-hand side replaced in Python",)
    return "compiled" in engine.options(requested, model.arrays, (EXPLICIT_METHOD,), replaced)[EXPLICIT_METHOD]


def _modes(lay, duration_s: float):
    """The modal analysis at the drive's boundary and the Campbell data, for the report's engineering part."""
    boundary = "clamped_input" if lay.speed_drive else "free"
    return (modal_analysis(lay, boundary, duration_s=duration_s),
            campbell_data(lay, boundary, duration_s=duration_s))


#: priced seconds (gearcli.simulate.guards.priced_work_s) a whole report may use: the file's run, the reference
#: pair and the ladder together; each run is also bounded on its own by the run budget (guards.WORK_CAP_S)
REPORT_WORK_CAP_S = 2 * WORK_CAP_S


def _work(result: SimulationResult) -> float:
    """A run's priced work from its counters (deterministic, unlike its wall clock), a compiled run's at the compiled
    engine's prices (as the run budget allows it: gearcli.simulate.guards.over_budget's speed-up)."""
    sv = result.solver
    work = priced_work_s(sv.nfev, sv.njev, sv.nlu, sv.steps, bool(getattr(METHODS.get(sv.method), "implicit", False)))
    return work / compiled_speedup(sv.method) if sv.engine == "compiled" else work


class ReportBudget:
    """The report's run-time bound, the run budget's machinery applied to the whole study: before the ladder, its
    cost is projected from the file's own run (each rung costs that run's work times the accuracy factor of its
    rtol over the file's); a projection over :data:`REPORT_WORK_CAP_S` is refused at once, and the priced work
    spent is checked after every run. Both raise :class:`RunTooLong` (exit 2) with the settings that would fit."""

    def __init__(self, first_work_s: float, duration_s: float) -> None:
        self.spent = first_work_s
        self.duration_s = duration_s
        self.first = max(first_work_s, 1e-9)

    def _fit(self, total: float) -> str:
        """The advice of a refusal: a duration whose work fits the budget, rounded down (rounded to nearest, 1.98e3 s
        for 1977.8 would be refused again, as the run budget's advice was: core.text.rounded_down)."""
        fit = self.duration_s * REPORT_WORK_CAP_S / total if total > 0 else self.duration_s
        return f"use --quick (one run), or set simulation.duration_s ≤ {rounded_down(fit):g} s"

    def check_projection(self, file_rtol: float, spec) -> None:
        base = accuracy_factor(file_rtol)
        (_, ref_rtol), (_, check_rtol) = spec.reference_pair()
        rungs = sum(accuracy_factor(r) for r in spec.rtols) * len(spec.methods)
        projected = self.first * (rungs + accuracy_factor(ref_rtol) + accuracy_factor(check_rtol)) / base
        if self.spent + projected > REPORT_WORK_CAP_S:
            raise StudyTooLong(f"the accuracy study would need about {duration_text(self.spent + projected)} of computing "
                             f"({len(spec.rtols) * len(spec.methods) + 2} runs at the pace of the file's own run), over "
                             f"the report's budget of ~{REPORT_WORK_CAP_S:g} s; {self._fit(self.spent + projected)}")

    def spend(self, work_s: float) -> None:
        self.spent += work_s
        if self.spent > REPORT_WORK_CAP_S:
            raise StudyTooLong(f"the accuracy study used its computing budget of ~{REPORT_WORK_CAP_S:g} s before it "
                             f"finished; {self._fit(self.spent)}")


def _merge(*groups) -> tuple[str, ...]:
    out: list[str] = []
    for group in groups:
        out += [w for w in group if w not in out]
    return tuple(out)
