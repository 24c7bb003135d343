"""Evaluating points: one branch (a task) at a time, in any process (local pool or a Dask worker).

A :class:`Task` is plain picklable data: the design file's bytes (so a remote worker needs no access
to the file), the base ``--set`` overrides, and the points. Each process parses a design file once
(:func:`_base`, cached per process by its hash); points only apply their overrides, validate, compute the
design, build one model (its generated code compiled once per model structure and process,
:func:`gearcli.model.codegen.compile_functions`) and simulate. A point that fails (a value the schema rejects, an infeasible design, a solver
failure) becomes a ``failed`` row with its message and the branch goes on, starting cold again.
"""

from __future__ import annotations

import copy
import time
from collections.abc import Iterator
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any

from gearcli import engine
from gearcli.config.load import _parse, _validate
from gearcli.config.overrides import apply_all
from gearcli.design import compute_design
from gearcli.errors import GearcliError
from gearcli.model import TorsionalModel
from gearcli.scene import spec_from_design
from gearcli.simulate.run import run_simulation
from gearcli.sweep.columns import failed_row, ok_row, one_line
from gearcli.sweep.continuation import NO_RAMPS, Carried, carry_phases, continue_state
from gearcli.sweep.spec import Point


@dataclass(frozen=True)
class Scene:
    """The base scene of a sweep: the design file's bytes, its name for messages, and ``--set``."""

    raw: bytes
    source: str
    sets: tuple[str, ...] = ()
    n_stages: int = 1


@dataclass(frozen=True)
class Task:
    scene: Scene
    points: tuple[Point, ...]
    continuation: bool
    skip: frozenset[int] = field(default_factory=frozenset)  # indices already written: computed, not returned
    runs_hint: int = 0  # about how many points the worker running this task will do (engine = "auto")


@lru_cache(maxsize=8)
def _base(raw: bytes, source: str) -> dict:
    """The parsed TOML of a design file, once per process (points deep-copy it)."""
    return _parse(raw, source)


def load_point(scene: Scene, overrides: tuple[str, ...]):
    """The validated ``DesignFile`` of a point: the base data, the base ``--set``s, then the point's."""
    data = copy.deepcopy(_base(scene.raw, scene.source))
    paths = apply_all(data, (*scene.sets, *overrides))
    return _validate(data, scene.source, paths)


def _evaluate(scene: Scene, point: Point, prev: Carried | None) -> tuple[Any, Carried | None]:
    """Simulate one point (continued from the previous point's ``prev`` when given); the result and
    what it hands on to the next point."""
    cfg = load_point(scene, tuple(point.overrides()) + (NO_RAMPS if prev else ()))
    design = compute_design(cfg)
    spec = spec_from_design(cfg, design)
    y0 = None
    if prev is not None:
        model = model_of(carry_phases(spec, prev))
        y0 = continue_state(prev.state, prev.model, model, prev.time_s)
    if y0 is None:  # a cold start (the first point, or the chain changed), with the file's ramps
        if prev is not None:
            cfg = load_point(scene, tuple(point.overrides()))
            design = compute_design(cfg)
            spec = spec_from_design(cfg, design)
        model = model_of(spec)
    # no check pass per point (it would double a sweep's cost; README "Honest statistics"): a point's statistics
    # are checked by `gearcli simulate` on that point
    result = run_simulation(cfg, design, want_series=False, y0=y0, model=model, error_estimate=False)
    if result.final_state is None or result.final_time_s is None:
        return result, None
    return result, Carried(model, result.final_state, result.final_time_s)


def model_of(spec):
    """The compiled model of a ModelSpec."""
    return TorsionalModel(spec)


def iter_task(task: Task) -> Iterator[dict]:
    """The rows of a task's points as each finishes (those in ``task.skip`` are computed, not yielded)."""
    with engine.batch(max(len(task.points), task.runs_hint)):  # auto: the kernel's load is shared by the points
        prev = None
        for point in task.points:
            t0 = time.perf_counter()
            try:
                result, carried = _evaluate(task.scene, point, prev if task.continuation else None)
            except GearcliError as exc:
                prev = None
                row = failed_row(point.values, point.direction, _message(exc, task.scene), time.perf_counter() - t0)
            except (ArithmeticError, ValueError, RuntimeError, OverflowError) as exc:  # a bug or a numerical failure
                prev = None
                row = failed_row(point.values, point.direction, f"{type(exc).__name__}: {exc}", time.perf_counter() - t0)
            else:
                prev = carried
                row = ok_row(point.values, point.direction, result, time.perf_counter() - t0, task.scene.n_stages,
                             message=one_line("\n".join(result.warnings)))
            if point.index not in task.skip:
                yield {"_index": point.index, **row}


def run_task(task: Task) -> list[dict]:
    """A whole task in one call (what a pool or Dask worker runs)."""
    return list(iter_task(task))


def _message(exc: GearcliError, scene: Scene) -> str:
    text = str(exc)
    return text.replace("<stdin>", scene.source) if scene.source != "<stdin>" else text



def check_keys(scene: Scene, point: Point) -> None:
    """Raise ConfigError (exit 2) when a varied key is not a key ``--set`` accepts; values are checked per point."""
    apply_all(copy.deepcopy(_base(scene.raw, scene.source)), (*scene.sets, *point.overrides()))
