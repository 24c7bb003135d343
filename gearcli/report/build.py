"""Assemble a :class:`Report`: the file's own simulation, theory against it, and the accuracy study."""

from __future__ import annotations

from collections.abc import Callable
from functools import partial
from typing import TYPE_CHECKING

from gearcli import engine
from gearcli.model import TorsionalModel
from gearcli.report.accuracy import LadderSpec, ProgressFn, accuracy_study
from gearcli.report.checks import accuracy_checks, energy_check, sampling_checks
from gearcli.report.compare import comparison_rows, rating_comparison, stage_reports
from gearcli.report.result import Report
from gearcli.results import DesignResult, SimulationResult
from gearcli.scene import spec_from_design
from gearcli.simulate.run import run_simulation

if TYPE_CHECKING:
    from gearcli.config.schema import DesignFile

SimulateFn = Callable[..., SimulationResult]  # gearcli.simulate.run_simulation's signature


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
    spec = spec or LadderSpec()
    if simulate is None:
        # every run of the report is the same scene (only method and rtol change): one model, generated once
        simulate = partial(run_simulation, model=TorsionalModel(spec_from_design(cfg, design)))
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
    sim = simulate(cfg, design, want_series=True)
    stages = stage_reports(design, sim)
    study = None
    if not quick:
        def run(method: str, rtol: float) -> SimulationResult:
            # a rung's error is measured against the study's reference, so its own check pass (issue 10's
            # estimate, which doubles a run) would be computed and never read
            return simulate(cfg, design, method=method, rtol=rtol, want_series=False, error_estimate=False)

        with engine.batch(0):  # the ladder: auto may run Radau compiled too (labelled)
            study = accuracy_study(
                run, file_method=sim_cfg.method, file_rtol=sim_cfg.rtol, accuracy=accuracy, spec=spec,
                auto_choice=sim.solver.method if sim_cfg.method == "auto" else None,
                stiffness_indicator=(sim.extra or {}).get("stiffness_indicator"),
                progress=lambda label, done, total: tick(label, done + 1, total + 1),
            )
    warnings = _merge(
        design.warnings,
        sim.warnings,
        energy_check(sim),
        sampling_checks(stages, sim.natural_frequencies_Hz),
        accuracy_checks(study, sim_cfg.method, sim_cfg.rtol),
    )
    return Report(title=design.title, design=design, simulation=sim, comparison=comparison_rows(design, sim),
                  stages=stages, accuracy=study, warnings=warnings, rating=rating_comparison(design, sim))


def _merge(*groups) -> tuple[str, ...]:
    out: list[str] = []
    for group in groups:
        out += [w for w in group if w not in out]
    return tuple(out)
