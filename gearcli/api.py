"""The library facade: load -> design -> simulate / modes / sweep / report, without the command line.

Each function composes the layers below it (ARCHITECTURE.md) and returns the layer's frozen result; none
prints or writes a file except :func:`run_sweep`, whose sink is injected (:mod:`gearcli.io.sweep_file`
gives the file and stdout sinks, a caller may pass its own). The CLI's commands call these, so a script
gets the numbers ``gearcli`` prints, exactly where its BLAS runs on one thread as the console script's does
(``OMP_NUM_THREADS=1`` and ``OPENBLAS_NUM_THREADS=1`` set before numpy is imported; with more threads an implicit
method's LU solves may round differently: 390 against 399 Radau steps on a lossy reducer, agreeing to its
tolerance). A script that runs a sweep with ``jobs > 1`` starts a process pool: its main code goes under
``if __name__ == "__main__":``, as for any multiprocessing script::

    from gearcli import api

    loaded, design = api.load_and_design("configs/concrete_mixer.toml")
    result = api.simulate(loaded.design, design)
    print(result.stages[0].tangential_N.mean)

The sweep and the life calculation evaluate their points with the functions of this module, injected
(the layers below cannot import the facade): :func:`evaluate_point` loads, designs and simulates one
variant of a file, :func:`design_case` loads and designs one. Both are top-level functions, so a process
pool or a Dask worker receives them by reference.

The imports of the simulation, modes, sweep, life and report layers are local to the functions that need
them, on purpose: ``gearcli design`` (which imports this module) never loads scipy, so it starts fast. They
hide no cycle: every one points down the layers (``lint-imports`` checks it).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, BinaryIO

import gearcli.design as design_layer
from gearcli.config import DesignFile, LoadedDesign, json_schema, load_design, load_variant, starter_toml
from gearcli.config.bounds import check_run_budget, memory_limit_bytes
from gearcli.config.load import read_bytes
from gearcli.config.overrides import SOURCE, blames_key
from gearcli.core import plugins
from gearcli.core.jsontypes import JsonObject
from gearcli.design.standards import with_simulated_rating
from gearcli.errors import ConfigError, DesignError, RunTooLong, SimulationError
from gearcli.io.units import key_units
from gearcli.model import TorsionalModel
from gearcli.model.assembly import Layout
from gearcli.model.modes import BOUNDARIES, campbell_data, modal_analysis
from gearcli.model.spec import ElementSpec, ModelSpec
from gearcli.results import DesignResult
from gearcli.scene import build_model, motor_spec, motor_start_warnings, resonance_diagnostics, spec_from_design

if TYPE_CHECKING:
    from gearcli.diagnostics import Diagnostic
    from gearcli.engine import Built
    from gearcli.life.result import LifeResult
    from gearcli.life.session import Session as LifeSession
    from gearcli.model.campbell import CampbellData
    from gearcli.model.modes import ModalAnalysis
    from gearcli.report import LadderSpec, Report
    from gearcli.report.accuracy import ProgressFn
    from gearcli.simulate.results import SimulationResult
    from gearcli.sweep.columns import Row
    from gearcli.sweep.continuation import Carried
    from gearcli.sweep.modes import SweepCampbell
    from gearcli.sweep.session import Session, SinkFactory
    from gearcli.sweep.worker import Case, Evaluation, Scene

__all__ = ["DesignFile", "ElementSpec", "LoadedDesign", "ModelSpec", "campbell", "check_budget", "design", "design_case",
           "engine_build", "engine_cache_refusal", "evaluate_point", "evaluate_sweep_point", "life", "load", "load_and_design", "model_source", "model_spec", "modes", "prepare_life",
           "prepare_sweep", "report", "report_file", "run_sweep", "simulate", "simulate_file", "simulate_spec",
           "sweep_campbell", "with_motor_start", "with_resonances", "design_file_schema", "plugin_failures", "starter_toml"]


def check_environment() -> None:
    """The environment every command reads, checked the same way for each: a set ``GEARCLI_MEMORY_LIMIT_MB``
    must be a number of MiB (:class:`~gearcli.errors.ConfigError`, exit 2, otherwise)."""
    memory_limit_bytes()


def engine_build(*, force: bool = False, quiet: bool = False) -> Built:
    """Compile the compiled engine's kernel into its cache (``force``: discard it first) and load it as a run would
    (:func:`gearcli.engine.build`); a first build is reported through the installed reporter
    (:mod:`gearcli.core.announce`)."""
    from gearcli import engine  # lazy: numpy and the engine, start-up time of gearcli design

    return engine.build(force=force, quiet=quiet)


def engine_cache_refusal() -> str:
    """Why the compiled engine's cache is not where ``$XDG_CACHE_HOME`` (or the home directory) asks ('' when it
    is): :func:`gearcli.engine.location.cache_choice`."""
    from gearcli.engine.location import cache_choice  # lazy: the engine's modules, start-up time of gearcli design

    return cache_choice()[1]


def design_file_schema() -> JsonObject:
    """The JSON Schema of the design file (``gearcli schema``), with the stage tables of the installed plug-ins
    (their entry points loaded first: a file may name their types; docs/plugins.md)."""
    plugins.load()
    return json_schema()


def plugin_failures() -> tuple[str, ...]:
    """The installed plug-ins that failed to load, one line each (``'name' (value) failed to load: Error: text``);
    the entry points are loaded first if no file has asked for them yet (docs/plugins.md)."""
    return plugins.load()


def load(path: str, overrides: Sequence[str] = (), *, stdin: BinaryIO | None = None) -> LoadedDesign:
    """The validated design file (``-`` reads ``stdin``, else the process's standard input), with ``--set``
    overrides applied. Bad input raises :class:`~gearcli.errors.ConfigError` naming the file and key."""
    return load_design(path, overrides, stdin=stdin)


def design(loaded: LoadedDesign, overrides: Sequence[str] = ()) -> DesignResult:
    """The design calculations of a loaded file; an infeasible design raises
    :class:`~gearcli.errors.DesignError` naming the file, or the ``--set`` whose value it is about."""
    try:  # written in the units of the file's keys (docs/output.md, "Units")
        result = dataclasses.replace(design_layer.compute_design(loaded.design), units=key_units(loaded.design))
    except DesignError as exc:
        source = SOURCE if blames_key(exc.key, overrides) else loaded.source
        raise DesignError(exc.message, key=exc.key, source=source) from exc
    try:  # a nameplate no Kloss curve passes through: named now, with its file, not by the model's first build
        motor_spec(loaded.design.input)
    except ConfigError as exc:
        raise _located(exc, loaded, overrides) from None
    return result


def load_and_design(path: str, overrides: Sequence[str] = (), *,
                    stdin: BinaryIO | None = None) -> tuple[LoadedDesign, DesignResult]:
    """:func:`load`, then :func:`design`."""
    loaded = load(path, overrides, stdin=stdin)
    return loaded, design(loaded, overrides)


def with_resonances(cfg: DesignFile, design_result: DesignResult) -> DesignResult:
    """The design with the drivetrain's resonance warnings added (``gearcli design``: a mesh order near a natural
    frequency of the linearised chain, the same messages ``simulate`` gives)."""
    return _with(design_result, resonance_diagnostics(cfg, design_result))


def with_motor_start(cfg: DesignFile, design_result: DesignResult) -> DesignResult:
    """The design with a motor drive's start judged from its curves (``gearcli design``): the warning that the
    motor cannot start its load (check ``motor_cannot_start``, or a soft start's ``soft_start_rolls_back``), the
    physics ``simulate`` warns of as ``motor_stalls`` and ``motor_rolls_back`` after its run."""
    return _with(design_result, motor_start_warnings(cfg, design_result))


def _with(design_result: DesignResult, found: tuple[Diagnostic, ...]) -> DesignResult:
    return dataclasses.replace(design_result, warnings=design_result.warnings + tuple(d.message for d in found),
                               diagnostics=design_result.diagnostics + found)


def model_spec(cfg: DesignFile, design_result: DesignResult) -> ModelSpec:
    """The torsional model's SI parameters of a design (the design -> model adapter, :mod:`gearcli.scene`)."""
    return spec_from_design(cfg, design_result)


def model_source(cfg: DesignFile, design_result: DesignResult) -> str:
    """The scene's generated equations (Python source), as ``gearcli simulate --dump-model`` prints them."""
    return build_model(cfg, design_result).source


def simulate(cfg: DesignFile, design_result: DesignResult, *, method: str | None = None, rtol: float | None = None,
             want_series: bool = True, progress: Callable[[float], None] | None = None) -> SimulationResult:
    """One run of the scene with its ``[simulation]`` settings (``method``/``rtol`` override them); ``progress``
    is called with the fraction of the run done (a terminal's progress bar). With ``[rating] dynamic_factor =
    "simulated"`` the facade rates the run's stages by the file's standard at their simulated K_v (simulate itself
    knows no standard). With ``[[bearing]]`` tables (and the series kept) the result carries the bearing reactions
    as channels and their window statistics; its ``units`` are those of the file's keys: what ``gearcli simulate``
    prints."""
    from gearcli.simulate import run_simulation  # lazy: scipy, start-up time of gearcli design

    result = run_simulation(cfg, design_result, method=method, rtol=rtol, want_series=want_series, progress=progress)
    result = with_simulated_rating(cfg, design_result, result)
    if cfg.bearing and want_series:  # bearing reactions: channels and window statistics (docs/life.md)
        from gearcli.simulate.bearings import with_bearings  # lazy: the shaft statics, start-up time without bearings

        result = with_bearings(cfg, design_result, result)
    return dataclasses.replace(result, units=key_units(cfg))  # written in the units of the file's keys


def check_budget(loaded: LoadedDesign, design_result: DesignResult, *, output_format: str = "json",
                 series: bool = False) -> None:
    """The file's run checked for memory (its output in ``output_format``, with the ``series`` in JSON) and
    cost before anything is integrated (before scipy is even imported): a
    :class:`~gearcli.errors.ResourceError` naming the file and the key to change. ``gearcli simulate`` and
    ``gearcli report`` call it before :func:`simulate_file` and :func:`report_file`."""
    check_run_budget(loaded.design, design_result, fmt=output_format, series=series, source=loaded.source)


def simulate_file(loaded: LoadedDesign, design_result: DesignResult, *,
                  progress: Callable[[float], None] | None = None, overrides: Sequence[str] = ()) -> SimulationResult:
    """``gearcli simulate``: one run with the series (:func:`check_budget` first for a guarded run); errors name
    the file (or the ``--set`` of ``overrides`` they are about); with ``[[bearing]]`` tables, the bearing reactions
    as channels and window statistics (:func:`simulate`)."""
    try:
        result = simulate(loaded.design, design_result, want_series=True, progress=progress)  # statistics need them
    except RunTooLong as exc:
        raise RunTooLong(f"{loaded.source}: {exc}") from None
    except SimulationError as exc:  # the run failed (exit 1): named with its file, as every error is
        raise SimulationError(f"{loaded.source}: {exc}") from None
    except DesignError as exc:  # what the model cannot integrate (a planetary's phase-dependent excitation)
        raise DesignError(exc.message, key=exc.key, source=loaded.source) from None
    except ConfigError as exc:  # a cross-key rule only the model can check (a periodic run's duration)
        raise _located(exc, loaded, overrides) from None
    return result


def _located(exc: ConfigError, loaded: LoadedDesign, overrides: Sequence[str]) -> ConfigError:
    """``exc`` naming where its key was written: the ``--set`` that gave it, else the design file."""
    if exc.source is not None:
        return exc
    source = SOURCE if blames_key(exc.key, overrides) else loaded.source
    return ConfigError(exc.message, source=source, key=exc.key)


def simulate_spec(spec: ModelSpec, *, duration_s: float, steps: int, method: str = "auto", rtol: float = 1e-6,
                  engine: str = "auto", error_estimate: bool = False) -> SimulationResult:
    """One run of a model given by its SI parameters (a scene changed or extended in code: further elements
    in ``spec.elements``, :class:`ElementSpec`)."""
    from gearcli.simulate import simulate_model  # lazy: the solver layers (scipy), start-up time of gearcli design

    return simulate_model(TorsionalModel(spec), duration_s=duration_s, steps=steps, method=method, rtol=rtol,
                          engine=engine, error_estimate=error_estimate)


def modes(cfg: DesignFile, design_result: DesignResult) -> list[ModalAnalysis]:
    """The linearised drivetrain's modes at each boundary condition (clamped input, free)."""
    lay = Layout.of(spec_from_design(cfg, design_result))
    return [modal_analysis(lay, b, duration_s=cfg.simulation.duration_s) for b in BOUNDARIES]


def campbell(cfg: DesignFile, design_result: DesignResult) -> CampbellData:
    """The Campbell data (natural frequencies and excitation orders over speed) at the drive's boundary."""
    lay = Layout.of(spec_from_design(cfg, design_result))
    return campbell_data(lay, "clamped_input" if lay.speed_drive else "free", duration_s=cfg.simulation.duration_s)


def report(cfg: DesignFile, design_result: DesignResult, *, accuracy: float = 1e-4, quick: bool = False,
           spec: LadderSpec | None = None, progress: ProgressFn | None = None) -> Report:
    """The report: theory against simulation and, unless ``quick``, the work-precision study."""
    from gearcli.report import build_report  # lazy: the solver layers (scipy), start-up time of gearcli design

    rep = build_report(cfg, design_result, accuracy=accuracy, quick=quick, spec=spec, progress=progress)
    return dataclasses.replace(rep, simulation=dataclasses.replace(rep.simulation, units=key_units(cfg)))


def report_file(loaded: LoadedDesign, design_result: DesignResult, *, accuracy: float = 1e-4, quick: bool = False,
                rtols: Sequence[float] | None = None, progress: ProgressFn | None = None,
                overrides: Sequence[str] = ()) -> Report:
    """``gearcli report`` (:func:`check_budget` first for a guarded run): :func:`report` with the accuracy
    ladder's tolerances ``rtols`` (default: the ladder's own); a run too long names the file."""
    from gearcli.report import LadderSpec  # lazy: the solver layers (scipy), start-up time of gearcli design

    spec = LadderSpec(rtols=tuple(rtols)) if rtols else LadderSpec()
    try:
        return report(loaded.design, design_result, accuracy=accuracy, quick=quick, spec=spec, progress=progress)
    except RunTooLong as exc:
        raise RunTooLong(f"{loaded.source}: {exc}") from None
    except SimulationError as exc:  # the report's own run failed (exit 1): named with its file
        raise SimulationError(f"{loaded.source}: {exc}") from None
    except ConfigError as exc:  # a file the report cannot compare (a stage kind without a gear mesh): named
        raise _located(exc, loaded, overrides) from None


def prepare_sweep(file: str, sets: Sequence[str], *, vary: Sequence[str] = (), randoms: Sequence[str] = (),
                  samples: int | None = None, sampling: str = "lhs", seed: int | None = None,
                  direction: str | None = None, jobs: int | None = None, scheduler: str | None = None,
                  output: str | None = None, fmt: str = "csv") -> Session:
    """A checked sweep (every usage error raised before any point runs); ``output``, when it exists, is
    read for a resume."""
    from gearcli.io.sweep_file import read_identity  # lazy: the sweep's file, start-up time of simulate
    from gearcli.sweep.session import prepare  # lazy: the sweep and life layers, start-up time of gearcli design

    raw = read_bytes(file)
    loaded = load_design(file, sets, raw=raw)  # the bytes read once: a FIFO's (`<(cat f.toml)`) are gone after
    return prepare(raw, loaded, design(loaded, sets), sets, vary=vary, randoms=randoms, samples=samples,
                   sampling=sampling, seed=seed, direction=direction, jobs=jobs, scheduler=scheduler, output=output,
                   fmt=fmt, evaluate=evaluate_sweep_point, read_previous=read_identity)


def run_sweep(session: Session, on_row: Callable[[bool], None] = lambda failed: None, *,
              sink: SinkFactory | None = None) -> list[Row]:
    """Run a prepared sweep; rows go to ``sink`` (default: the session's ``-o`` file or stdout) as they
    finish. Returns every row in point order."""
    from gearcli.io.sweep_file import open_sink  # lazy: the sweep's file, start-up time of simulate
    from gearcli.sweep.session import run  # lazy: the sweep and life layers, start-up time of gearcli design

    return run(session, sink or open_sink, on_row)


def sweep_campbell(session: Session) -> SweepCampbell | None:
    """The Campbell diagram of a sweep over the input speed (``gearcli sweep --plots``): the modes and order
    lines at the file's own speed over the swept range, the swept speeds marked; None when no input speed is
    swept."""
    # lazy: the sweep and life layers, start-up time of gearcli design
    from gearcli.sweep.modes import sweep_campbell as diagram

    return diagram(session.spec, session.scene, design_case, key_units)


def prepare_life(file: str, overrides: Sequence[str] = (), *, series: str | None = None,
                 classes: int | None = None) -> LifeSession:
    """A checked ``gearcli life`` run: the base file read, validated and designed (bad input raises before any
    point runs), and its duty points (the file's ``[[duty]]`` tables, or the history ``series`` classed into
    ``classes`` torque classes)."""
    from gearcli.life.session import prepare  # lazy: the sweep and life layers, start-up time of gearcli design

    if file == "-" and series == "-":
        raise ConfigError("'-' (standard input) already carries the design file; give the history as a "
                          "file", source="--series")
    raw = read_bytes(file)
    loaded = load_design(file, overrides, raw=raw)  # the bytes read once (as prepare_sweep's)
    try:
        return prepare(raw, loaded, design(loaded, overrides), overrides, series=series, classes=classes)
    except ConfigError as exc:  # a duty rule a --set broke (every point's hours 0, a repeated name) names the --set
        if exc.source != loaded.source or not blames_key(exc.key, overrides):
            raise
        raise ConfigError(exc.message, source=SOURCE, key=exc.key) from None


def life(session: LifeSession, *, static: bool = False, variant: str = "iso",
         progress: Callable[[str, int, int], None] | None = None) -> LifeResult:
    """The life of every member and bearing over the session's duty points: each point simulated (its
    mesh-cycle load spectrum) or, ``static``, rated at its static forces with the rating's K_v; Miner damage by
    ``variant`` (``iso``, ``elementary``, ``modified``)."""
    from gearcli.life.run import compute_life  # lazy: the sweep and life layers, start-up time of gearcli design
    from gearcli.rating.sn import VARIANTS  # lazy: the rating layer's S-N curves, start-up time of gearcli design

    if variant not in VARIANTS:  # the CLI's --miner choice; a script's typo was a bare KeyError deep in life
        raise ValueError(f"variant: must be one of {', '.join(VARIANTS)}, got {variant!r}")
    result = compute_life(session.scene, session.points, route="static" if static else "dynamic", variant=variant,
                          progress=progress, design_case=design_case, evaluate=evaluate_point, notes=session.warnings,
                          base_warnings=session.design.warnings, held=session.held)
    return dataclasses.replace(result, units=key_units(session.loaded.design))  # tables in the file's units


# ----------------------------------------------------------------- points (injected into sweep and life)
def design_case(scene: Scene, overrides: Sequence[str], /) -> Case:
    """One variant of the scene's file (``overrides`` after the scene's ``--set``), validated and designed."""
    from gearcli.sweep.worker import Case  # lazy: the sweep and life layers, start-up time of gearcli design

    cfg = load_variant(scene.raw, scene.source, (*scene.sets, *overrides))
    return Case(cfg, design_layer.compute_design(cfg))


def evaluate_point(scene: Scene, overrides: Sequence[str], start: Carried | None = None, /, *,
                   series: bool = False, check: bool | None = False, settle: bool | str = True,
                   bearing_peaks: bool = False) -> Evaluation:
    """One variant of the scene's file loaded, designed and simulated (the sweep's and the life calculation's
    point, :class:`~gearcli.sweep.worker.PointEvaluator`). Continued from ``start`` (the previous point's final
    state, :mod:`gearcli.sweep.continuation`) when given: without the start-up ramps, from that state, the
    phases carried on; a point whose chain differs starts cold with the file's ramps. ``series`` keeps the time
    series; ``check`` runs the check pass (None: the file's ``simulation.error_estimate``); ``settle`` the window
    shown settled (:func:`gearcli.simulate.settle.settled_run`; ``"window"``: never the periodic state). The
    result has the start's warnings but no ``summary.start`` (``extra["start"]``), which neither reads.
    ``bearing_peaks`` (a sweep's row): bearings with a C_0 are checked at the window's peak as ``gearcli simulate``
    checks them (ISO 76, :func:`gearcli.simulate.bearings.with_bearings`: its warning), from the series the run keeps
    for it (dropped again unless ``series``); the life calculation checks them over the whole duty instead."""
    from gearcli.simulate import run_simulation  # lazy: the solver layers (scipy), start-up time of gearcli design

    # lazy: the sweep and life layers, start-up time of gearcli design
    from gearcli.sweep.continuation import NO_RAMPS, Carried, carry_phases, continue_state
    from gearcli.sweep.worker import Evaluation  # lazy: the sweep and life layers, start-up time of gearcli design

    case = design_case(scene, (*overrides, *(NO_RAMPS if start else ())))
    # the point's run, held in memory and refused up front where its cost estimate is absurd, as simulate refuses
    # it (a ResourceError: a sweep's failed row with simulate's message, a duty point's error)
    check_run_budget(case.cfg, case.design, fmt="json", series=False, source=scene.source)
    spec = spec_from_design(*case)
    y0 = None
    if start is not None:
        model = TorsionalModel(carry_phases(spec, start))
        y0 = continue_state(start.state, start.model, model, start.time_s)
    if y0 is None:  # a cold start (the first point, or the chain changed), with the file's ramps
        if start is not None:
            case = design_case(scene, overrides)
            spec = spec_from_design(*case)
        model = TorsionalModel(spec)
    # a sweep row and a duty point are dynamic verdicts: from a window shown settled (gearcli.simulate.settle)
    peaks = bearing_peaks and any(b.static_load_rating_kN is not None for b in case.cfg.bearing)
    result = run_simulation(case.cfg, case.design, want_series=series or peaks, y0=y0, model=model,
                            error_estimate=check, settle=settle, summary_start=False)  # no summary.start read
    result = with_simulated_rating(case.cfg, case.design, result)
    if peaks:
        from gearcli.simulate.bearings import with_bearings  # lazy: the shaft statics, start-up time without bearings

        result = with_bearings(case.cfg, case.design, result)
        if not series:  # the reactions' series served the check: a row keeps none
            result = dataclasses.replace(result, time_s=result.time_s[:0], series={})
    if result.final_state is None or result.final_time_s is None:
        return Evaluation(case, result, None)
    return Evaluation(case, result, Carried(model, result.final_state, result.final_time_s))


def evaluate_sweep_point(scene: Scene, overrides: Sequence[str], start: Carried | None = None, /, *,
                         series: bool = False, check: bool | None = False, settle: bool | str = True) -> Evaluation:
    """A sweep's point (the :class:`~gearcli.sweep.worker.PointEvaluator` ``gearcli sweep`` injects): :func:`evaluate_point`
    with the bearings checked at the window's peak, so that a row's message holds the warnings ``gearcli simulate``
    gives for the same point (docs/sweeps.md)."""
    return evaluate_point(scene, overrides, start, series=series, check=check, settle=settle, bearing_peaks=True)
