"""The library facade: load -> design -> simulate / modes / sweep / report, without the command line.

Each function composes the layers below it (ARCHITECTURE.md) and returns the layer's frozen result; none
prints or writes a file except :func:`run_sweep`, whose sink is injected (:mod:`gearcli.io.sweep_file`
gives the file and stdout sinks, a caller may pass its own). The CLI's commands call these, so a script
gets exactly the numbers ``gearcli`` prints::

    from gearcli import api

    loaded, design = api.load_and_design("configs/concrete_mixer.toml")
    result = api.simulate(loaded.design, design)
    print(result.stages[0].tangential_N.mean)

The imports of the simulation, modes, sweep and report layers are local to the functions that need them, on
purpose: ``gearcli design`` (which imports this module) never loads scipy, so it starts fast. They hide
no cycle: every one points down the layers (``lint-imports`` checks it).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, BinaryIO

import gearcli.design as design_layer
from gearcli.config import DesignFile, LoadedDesign, load_design
from gearcli.errors import DesignError
from gearcli.io.sweep_file import open_sink, read_identity
from gearcli.model.spec import ElementSpec, ModelSpec
from gearcli.results import DesignResult
from gearcli.scene import spec_from_design

if TYPE_CHECKING:
    from gearcli.model.modes import ModalAnalysis
    from gearcli.report import LadderSpec, Report
    from gearcli.report.accuracy import ProgressFn
    from gearcli.results import SimulationResult
    from gearcli.sweep.session import Session, SinkFactory

__all__ = ["DesignFile", "ElementSpec", "LoadedDesign", "ModelSpec", "design", "load", "load_and_design", "model_spec",
           "modes", "prepare_sweep", "report", "run_sweep", "simulate", "simulate_spec"]


def load(path: str, overrides: Sequence[str] = (), *, stdin: BinaryIO | None = None) -> LoadedDesign:
    """The validated design file (``-`` reads ``stdin``, else the process's standard input), with ``--set``
    overrides applied. Bad input raises :class:`~gearcli.errors.ConfigError` naming the file and key."""
    return load_design(path, overrides, stdin=stdin)


def design(loaded: LoadedDesign) -> DesignResult:
    """The design calculations of a loaded file; an infeasible design raises
    :class:`~gearcli.errors.DesignError` naming the file."""
    try:
        return design_layer.compute_design(loaded.design)
    except DesignError as exc:
        raise DesignError(exc.message, key=exc.key, source=loaded.source) from exc


def load_and_design(path: str, overrides: Sequence[str] = (), *,
                    stdin: BinaryIO | None = None) -> tuple[LoadedDesign, DesignResult]:
    """:func:`load`, then :func:`design`."""
    loaded = load(path, overrides, stdin=stdin)
    return loaded, design(loaded)


def model_spec(cfg: DesignFile, design_result: DesignResult) -> ModelSpec:
    """The torsional model's SI parameters of a design (the design -> model adapter, :mod:`gearcli.scene`)."""
    return spec_from_design(cfg, design_result)


def simulate(cfg: DesignFile, design_result: DesignResult, *, method: str | None = None, rtol: float | None = None,
             want_series: bool = True) -> SimulationResult:
    """One run of the scene with its ``[simulation]`` settings (``method``/``rtol`` override them)."""
    from gearcli.simulate import run_simulation

    return run_simulation(cfg, design_result, method=method, rtol=rtol, want_series=want_series)


def simulate_spec(spec: ModelSpec, *, duration_s: float, steps: int, method: str = "auto", rtol: float = 1e-6,
                  engine: str = "auto", error_estimate: bool = False) -> SimulationResult:
    """One run of a model given by its SI parameters (a scene changed or extended in code: further elements
    in ``spec.elements``, :class:`ElementSpec`)."""
    from gearcli.model import TorsionalModel
    from gearcli.simulate import simulate_model

    return simulate_model(TorsionalModel(spec), duration_s=duration_s, steps=steps, method=method, rtol=rtol,
                          engine=engine, error_estimate=error_estimate)


def modes(cfg: DesignFile, design_result: DesignResult) -> list[ModalAnalysis]:
    """The linearised drivetrain's modes at each boundary condition (clamped input, free)."""
    from gearcli.model.assembly import Layout
    from gearcli.model.modes import BOUNDARIES, modal_analysis

    lay = Layout.of(spec_from_design(cfg, design_result))
    return [modal_analysis(lay, b, duration_s=cfg.simulation.duration_s) for b in BOUNDARIES]


def report(cfg: DesignFile, design_result: DesignResult, *, accuracy: float = 1e-4, quick: bool = False,
           spec: LadderSpec | None = None, progress: ProgressFn | None = None) -> Report:
    """The report: theory against simulation and, unless ``quick``, the work-precision study."""
    from gearcli.report import build_report

    return build_report(cfg, design_result, accuracy=accuracy, quick=quick, spec=spec, progress=progress)


def prepare_sweep(file: str, sets: Sequence[str], *, vary: Sequence[str] = (), randoms: Sequence[str] = (),
                  samples: int | None = None, sampling: str = "lhs", seed: int | None = None,
                  direction: str | None = None, jobs: int | None = None, scheduler: str | None = None,
                  output: str | None = None, fmt: str = "csv") -> Session:
    """A checked sweep (every usage error raised before any point runs); ``output``, when it exists, is
    read for a resume."""
    from gearcli.sweep.session import prepare

    return prepare(file, sets, vary=vary, randoms=randoms, samples=samples, sampling=sampling, seed=seed,
                   direction=direction, jobs=jobs, scheduler=scheduler, output=output, fmt=fmt,
                   read_previous=read_identity)


def run_sweep(session: Session, on_row: Callable[[bool], None] = lambda failed: None, *,
              sink: SinkFactory | None = None) -> list[dict]:
    """Run a prepared sweep; rows go to ``sink`` (default: the session's ``-o`` file or stdout) as they
    finish. Returns every row in point order."""
    from gearcli.sweep.session import run

    return run(session, sink or open_sink, on_row)
