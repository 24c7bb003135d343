"""Evaluating points: one branch (a task) at a time, in any process (local pool or a Dask worker).

A :class:`Task` is plain picklable data: the design file's bytes (so a remote worker needs no access
to the file), the base ``--set`` overrides, the points, and the function that evaluates one point. The
sweep never loads, designs or simulates a point itself: the evaluator is injected (the library facade's
:func:`gearcli.api.evaluate_point`, a top-level function, so that it pickles by reference to a pool or a
Dask worker). It validates a point's overrides on the file parsed once per process, computes the design,
builds one model (its generated code compiled once per model structure and process,
:func:`gearcli.model.codegen.compile_function`) and simulates. A point that fails (a value the schema
rejects, an infeasible design, a run refused up front for its memory or its cost as ``simulate``
refuses it, a solver failure) becomes a ``failed`` row with its message and the branch
goes on, starting cold again.
"""

from __future__ import annotations

import re
import time
from collections.abc import Iterator, Sequence
from dataclasses import field
from typing import NamedTuple, Protocol, cast

from gearcli import engine
from gearcli.config import DesignFile, check_override_keys
from gearcli.config.overrides import SOURCE
from gearcli.core.records import record
from gearcli.errors import ConfigError, GearcliError, located
from gearcli.results import DesignResult
from gearcli.simulate import spent
from gearcli.simulate.results import SimulationResult
from gearcli.sweep.columns import Row, failed_row, ok_row, one_line
from gearcli.sweep.continuation import Carried, has_branch, jump_note, on_branch
from gearcli.sweep.family import Family, marks
from gearcli.sweep.load_law import LoadLaw, law_overrides
from gearcli.sweep.spec import Point, canonical_key

#: what a point's run may raise besides a GearcliError (a bug or a numerical failure): the point's row is failed
NUMERICAL = (ArithmeticError, ValueError, RuntimeError, OverflowError)


@record
class Scene:
    """The base scene of a sweep: the design file's bytes, its name for messages, and ``--set``."""

    raw: bytes
    source: str
    sets: tuple[str, ...] = ()
    n_stages: int = 1
    load_law: LoadLaw | None = None  # a speed-dependent load: each point's torque on it (gearcli.sweep.load_law)


class Case(NamedTuple):
    """One operating point, loaded and designed: its validated design file and its design."""

    cfg: DesignFile
    design: DesignResult


class Evaluation(NamedTuple):
    """One simulated point: its case, its result, and what it hands on to the next point of its branch
    (None: the next point starts cold)."""

    case: Case
    result: SimulationResult
    carried: Carried | None


class CaseDesigner(Protocol):
    """Loads and designs one variant of a scene (``overrides`` after the scene's ``--set``)."""

    def __call__(self, scene: Scene, overrides: Sequence[str], /) -> Case: ...


class PointEvaluator(Protocol):
    """Loads, designs and simulates one variant of a scene, continued from ``start`` (a previous point's final
    state) when given. ``series``: keep the time series; ``check``: run the check pass (None: the file's
    ``simulation.error_estimate``). A sweep point keeps no series; its check pass is shared by its task's
    points (:mod:`gearcli.sweep.family`: paid at every point it would double a sweep's cost)."""

    def __call__(self, scene: Scene, overrides: Sequence[str], start: Carried | None = None, /, *,
                 series: bool = False, check: bool | None = False, settle: bool | str = True) -> Evaluation: ...


@record
class Task:
    scene: Scene
    points: tuple[Point, ...]
    continuation: bool
    evaluate: PointEvaluator
    skip: frozenset[int] = field(default_factory=frozenset)  # indices already written: computed, not returned
    runs_hint: int = 0  # about how many points the worker running this task will do (engine = "auto")
    # engine = "auto": each point's price of loading the kernel (gearcli.engine.sweep_load_share_s; None: the
    # process's own expected load, which depends on what it ran before and on the machine's load)
    load_share_s: float | None = None


def _evaluate(evaluate: PointEvaluator, scene: Scene, point: Point, prev: Carried | None,
              check: bool = False) -> Evaluation:
    """Simulate one point (continued from the previous point's ``prev`` when given) with the injected
    evaluator; ``check``: with its check pass (:mod:`gearcli.sweep.family`)."""
    overrides = [*point.overrides(), *law_overrides(scene.load_law, point.values)]
    return evaluate(scene, overrides, prev, check=check) if check else evaluate(scene, overrides, prev)


def iter_task(task: Task) -> Iterator[Row]:
    """The rows of a task's points as each finishes (those in ``task.skip`` are computed, not yielded). The task's
    points are one family whose error estimate is shared (:mod:`gearcli.sweep.family`)."""
    family = Family()
    with engine.batch(max(len(task.points), task.runs_hint), task.load_share_s):  # auto: the kernel's load is shared by the points
        prev = None
        before: _Before | None = None  # the previous ok point of the branch
        for point in task.points:
            t0 = time.perf_counter()
            check = family.needs_check(point.index)
            got: SimulationResult | None = None
            try:
                _, result, carried = _evaluate(task.evaluate, task.scene, point, prev if task.continuation else None,
                                               check)
                got = result
                shared: tuple[str, ...] = ()
                if task.continuation:  # a branch carries its verdict along itself; independent points: the Carrier
                    shared = family.checked(one_line(point.shown()), result) if check else family.carried(result)
                jump, refined = _jump(task, before, point, result) if task.continuation else ("", 0)
            except GearcliError as exc:
                prev = before = None
                row = failed_row(point.cells(), point.direction, _message(exc, task.scene, point),
                                 time.perf_counter() - t0)
            except NUMERICAL as exc:  # a bug or a numerical failure
                prev = before = None
                row = failed_row(point.cells(), point.direction, f"{type(exc).__name__}: {exc}", time.perf_counter() - t0)
            else:
                prev, before = carried, _Before(point, result, carried)
                row = ok_row(point.cells(), point.direction, result, time.perf_counter() - t0, task.scene.n_stages,
                             message=one_line("\n".join(((jump,) if jump else ()) + tuple(result.warnings) + shared)),
                             extra_nfev=refined)
            hidden = {} if task.continuation else marks(got, one_line(point.shown()) if check else None)
            if point.index not in task.skip:
                yield {"_index": point.index, **row, **hidden}
            elif check and not task.continuation:  # run again for its family's verdict alone (a resume)
                yield {"_index": point.index, **hidden, "_verdict_only": True}


class _Before(NamedTuple):
    point: Point
    result: SimulationResult
    carried: Carried | None


def _jump(task: Task, before: _Before | None, point: Point, result: SimulationResult) -> tuple[str, int]:
    """A periodic point continued from ``before`` that left its branch: the row's jump mark, with the branch's
    end closed in on by bisection of the one varied value (:func:`gearcli.sweep.continuation.jump_note`), and the
    evaluations its refinement runs took (the row's ``nfev`` counts them, as its ``wall_s`` does)."""
    if before is None or result.steady is None or result.steady.mode != "periodic":
        return "", 0
    p0, r0, c0 = before
    if not has_branch(r0) or on_branch(r0, result):  # (no orbit before: no branch to follow, nothing to mark)
        return "", 0
    changed = [(i, a, b) for i, ((_, a), (_, b)) in enumerate(zip(p0.values, point.values, strict=True)) if a != b]
    if len(changed) != 1 or not all(isinstance(v, (int, float)) for v in changed[0][1:]):
        return f"jump: left the branch of the previous point ({one_line(p0.shown())})", 0
    at, v0, v1 = changed[0]
    carried = {id(r0): c0}
    spent_nfev = [0]

    def refine(value: float, last: SimulationResult) -> SimulationResult | None:
        mid = Point(-1, tuple((k, value if i == at else v) for i, (k, v) in enumerate(point.values)), point.direction,
                    point.columns)
        try:
            _, got, c = _evaluate(task.evaluate, task.scene, mid, carried[id(last)])
        except (GearcliError, *NUMERICAL):  # a refinement point that fails is off the branch; the row stands
            return None
        carried[id(got)] = c
        spent_nfev[0] += spent.whole(got)[0]
        return got

    note = jump_note(point.cells()[at][0], float(cast(float, v0)), float(cast(float, v1)), r0, result, refine)  # numbers (above)
    return note, spent_nfev[0]


def run_task(task: Task) -> list[Row]:
    """A whole task in one call (what a pool or Dask worker runs)."""
    return list(iter_task(task))


def _message(exc: GearcliError, scene: Scene, point: Point) -> str:
    """A failed point's message. A value of the point's own (a ``--vary`` or ``--random`` value the schema
    rejects) is named by its key alone, as the row's design errors are: the point's overrides are checked as
    ``--set`` overrides, but the user gave no ``--set`` for it."""
    if isinstance(exc, ConfigError) and exc.source == SOURCE:
        law = law_overrides(scene.load_law, point.values)  # the point's load on the file's speed law (load_law)
        if exc.key and law and law[0].startswith(f"{exc.key}=") and not _varied(exc.key, point):
            return located(f"{exc.message} (the file's load scaled to this point's speed on its speed law, "
                           f"(n / n0)^p: {law[0]})", None, exc.key)
        named = exc.key or _leading_key(exc.message)  # a table-level check names its table in the message
        if named and _varied(named, point):
            return located(exc.message, None, exc.key)
    text = str(exc)
    return text.replace("<stdin>", scene.source) if scene.source != "<stdin>" else text


def _leading_key(message: str) -> str | None:
    """``stage[0].shaft`` of ``"stage[0].shaft: the last stage's gear ..."``."""
    m = re.match(r"([A-Za-z_][\w.\[\]-]*): ", message)
    return m[1] if m else None


def _varied(key: str, point: Point) -> bool:
    """Whether the error's key is a varied key, or a table holding one (``load`` for ``load.inertia_kg_m2``), or a
    key inside a varied table."""
    try:
        named = canonical_key(key)
    except ConfigError:
        return False
    return any(named == k or k.startswith(named + ".") or named.startswith(k + ".") for k, _ in point.values)


def check_keys(scene: Scene, point: Point) -> None:
    """Raise ConfigError (exit 2) when a varied key is not a key ``--set`` accepts; values are checked per point."""
    check_override_keys(scene.raw, scene.source, (*scene.sets, *point.overrides()))
