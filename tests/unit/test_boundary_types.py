"""The layer boundaries are typed without ``Any`` (ARCHITECTURE.md, CONTRIBUTING.md): the facade's public
functions, the result dataclasses, the design -> model adapter and the model's parameters, the simulation's
entry points, the sweep's and the life calculation's entry points, and io's public functions.

A parameter or return without an annotation, an explicit ``Any``, or a bare container (``dict``, ``list``,
``tuple``, ``set``, ``Callable`` without parameters: an implicit ``Any``) fails. Arrays are ``np.ndarray``
(their dtype is float64 by the house rule, not written in each annotation). Annotations are resolved with
``typing.get_type_hints``, names imported under ``TYPE_CHECKING`` included.
"""

from __future__ import annotations

import ast
import collections.abc
import dataclasses
import importlib
import inspect
import pkgutil
import types
import typing

import pytest

import gearcli.io
from gearcli.core import jsontypes

BARE = {dict, list, tuple, set, frozenset, type, collections.abc.Callable, collections.abc.Mapping,
        collections.abc.Sequence, collections.abc.Iterable, collections.abc.Iterator}

#: module -> the names that form its boundary (None: every public function and dataclass it defines)
BOUNDARIES: dict[str, tuple[str, ...] | None] = {
    "gearcli.api": None,
    "gearcli.results": None,
    "gearcli.simulate.results": None,
    "gearcli.simulate.bearings": ("with_bearings", "reaction_series"),
    "gearcli.core.channels": None,
    "gearcli.diagnostics": ("Diagnostic", "warning", "warning_objects"),
    "gearcli.scene": None,
    "gearcli.model.spec": None,
    "gearcli.simulate.run": ("run_simulation", "simulate_model"),
    "gearcli.sweep.session": ("prepare", "run", "Session"),
    "gearcli.sweep.execute": ("execute", "plan"),
    "gearcli.sweep.worker": ("Scene", "Task", "Case", "Evaluation", "PointEvaluator", "CaseDesigner", "iter_task",
                             "run_task"),
    "gearcli.sweep.continuation": ("Carried", "carry_phases", "continue_state"),
    "gearcli.sweep.columns": ("ok_row", "failed_row", "columns"),
    "gearcli.sweep.spec": ("Axis", "Point", "SweepSpec", "spec_from_options"),
    "gearcli.sweep.modes": ("SweepCampbell", "sweep_campbell"),
    "gearcli.life.run": ("compute_life",),
    "gearcli.life.session": ("prepare", "Session"),
    "gearcli.life.result": None,
    **{f"gearcli.io.{m.name}": None for m in pkgutil.iter_modules(gearcli.io.__path__)},
}


def _namespace(module: types.ModuleType) -> dict[str, object]:
    """The module's globals plus what it imports under ``if TYPE_CHECKING:`` (names its annotations use), and
    the JSON aliases (recursive: their forward references name each other)."""
    ns = {**vars(jsontypes), **vars(module)}
    for node in ast.parse(inspect.getsource(module)).body:
        if isinstance(node, ast.If) and isinstance(node.test, ast.Name) and node.test.id == "TYPE_CHECKING":
            exec(compile(ast.Module(node.body, type_ignores=[]), module.__file__ or "", "exec"), ns)  # noqa: S102
    return ns


def _untyped(tp: object) -> str | None:
    """Why ``tp`` is not a precise type (None: it is)."""
    if tp is typing.Any:
        return "Any"
    if tp is inspect.Parameter.empty:
        return "no annotation"
    if tp in BARE:
        return f"bare {getattr(tp, '__name__', tp)}"
    for arg in typing.get_args(tp):
        for a in arg if isinstance(arg, list) else [arg]:  # Callable[[args], ret]
            why = None if a is Ellipsis else _untyped(a)
            if why:
                return why
    return None


def _members(name: str, only: tuple[str, ...] | None) -> list[tuple[str, object]]:
    module = importlib.import_module(name)
    out = []
    for attr, obj in vars(module).items():
        if attr.startswith("_") or getattr(obj, "__module__", None) != name:
            continue
        if (only is None and (inspect.isfunction(obj) or inspect.isclass(obj))) or attr in (only or ()):
            out.append((attr, obj))
    return out


def _function_findings(where: str, fn: object, ns: dict[str, object]) -> list[str]:
    hints = typing.get_type_hints(fn, globalns=ns)
    found = []
    for p in inspect.signature(fn).parameters.values():  # type: ignore[arg-type]
        if p.name in ("self", "cls"):
            continue
        why = _untyped(hints.get(p.name, inspect.Parameter.empty))
        if why:
            found.append(f"{where}({p.name}): {why}")
    why = _untyped(hints.get("return", inspect.Parameter.empty))
    return found + ([f"{where} -> {why}"] if why else [])


def _findings(name: str, only: tuple[str, ...] | None) -> list[str]:
    module = importlib.import_module(name)
    ns = _namespace(module)
    found = []
    for attr, obj in _members(name, only):
        where = f"{name}.{attr}"
        if inspect.isfunction(obj):
            found += _function_findings(where, obj, ns)
            continue
        hints = typing.get_type_hints(obj, globalns=ns)
        if dataclasses.is_dataclass(obj):
            found += [f"{where}.{f.name}: {why}" for f in dataclasses.fields(obj) if (why := _untyped(hints[f.name]))]
        else:  # a NamedTuple, a Protocol, a class: its annotated attributes
            found += [f"{where}.{k}: {why}" for k, v in hints.items() if (why := _untyped(v))]
        for method, fn in vars(obj).items():  # and its public methods
            if inspect.isfunction(fn) and (not method.startswith("_") or method == "__call__"):
                found += _function_findings(f"{where}.{method}", fn, ns)
    return found


def test_the_checker_sees_any_bare_containers_and_missing_annotations():
    def untyped(a, b: dict, c: typing.Any) -> list:  # type: ignore[no-untyped-def]
        return []

    hints = typing.get_type_hints(untyped)
    assert [_untyped(hints.get(p, inspect.Parameter.empty)) for p in ("a", "b", "c", "return")] == \
        ["no annotation", "bare dict", "Any", "bare list"]
    assert _untyped(dict[str, typing.Any]) == "Any" and _untyped(collections.abc.Callable[[int], None]) is None
    assert _untyped(int | None) is None and _untyped(tuple[float, ...]) is None


@pytest.mark.parametrize("module", sorted(BOUNDARIES))
def test_boundary_has_no_any(module):
    assert _members(module, BOUNDARIES[module]), f"{module}: no boundary members found"
    assert _findings(module, BOUNDARIES[module]) == []
