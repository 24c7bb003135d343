"""The stage-kind registry: one entry per design-file stage ``type``, one implementation per facet.

The bottom layer (it imports nothing of gearcli but ``errors``): the facets themselves are typed by the
protocols of the layer that calls them (``gearcli.stages.design.DesignKind``, ``gearcli.stages.model.ModelKind``,
``gearcli.stages.io.IoKind``), which look their implementation up here. A kind registered from outside
gearcli (a plug-in, or a test: ``tests/stages/belt.py``) calls :func:`provide` once per facet.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from typing import Any

from gearcli.core import plugins
from gearcli.core.text import shorten
from gearcli.errors import PLUGIN_FAULTS, GearcliError, PluginConflict, PluginError

PARALLEL = "parallel"  # the kind of a stage table without ``type``
BUILT_IN = (PARALLEL, "planetary")  # gearcli's own kinds: no plug-in provides a facet of theirs
SEAM = "stage type"

_FACETS: dict[tuple[str, str], object] = {}


def provide(kind: str, facet: str, implementation: object) -> None:
    """Register ``implementation`` as the ``facet`` ("design", "model", "io", …) of stage ``type = kind``. A
    plug-in's (an implementation from outside gearcli, not a class) is kept behind :class:`Guarded`. The same
    registrant's later implementation replaces its own; a facet another registrant provides, or a facet of a built-in
    kind provided from outside gearcli, is a :class:`~gearcli.errors.PluginConflict` naming both
    (:func:`gearcli.core.plugins.claim`)."""
    refused = plugins.claim(SEAM, kind, implementation, built_in=BUILT_IN, part=facet)
    if refused:
        raise PluginConflict(refused)
    # gearcli's own, and a schema table (a class): kept as they are
    kept = plugins.origin(implementation).split(".")[0] == "gearcli" or facet == "table"
    _FACETS[(kind, facet)] = implementation if kept else Guarded(kind, facet, implementation)


def withdraw(kind: str, facet: str) -> None:
    """Remove the ``facet`` of stage kind ``kind`` (a plug-in unloaded, a test's kind after the test)."""
    _FACETS.pop((kind, facet), None)
    plugins.release(SEAM, kind, facet)


def _withdraw_failed(claims: list[tuple[str, str, str]]) -> None:
    for what, kind, part in claims:
        if what == SEAM:
            withdraw(kind, part)


plugins.on_failure(_withdraw_failed)


def facet(kind: str, facet: str) -> object:
    """The ``facet`` of stage kind ``kind``; a ``KeyError`` naming the kinds that have it when none is registered."""
    try:
        return _FACETS[(kind, facet)]
    except KeyError:
        known = ", ".join(f'"{k}"' for k in sorted(k for k, f in _FACETS if f == facet)) or "none"
        raise MissingFacet(f'stage type "{kind}" has no {facet} facet registered (the stage types with one: '
                           f"{known}; docs/plugins.md)") from None


def kinds(facet: str) -> tuple[str, ...]:
    """The stage kinds with a ``facet`` registered, in registration order."""
    return tuple(k for k, f in _FACETS if f == facet)


def kind_of(stage: object) -> str:
    """The kind of a stage table or a stage result: its ``type``, "parallel" when it has none."""
    return str(getattr(stage, "type", None) or PARALLEL)


def table_figure(table: object, name: str) -> Any:
    """A stage table's property ``name`` (``speed_ratio``, ``efficiency``: a plug-in table's are its code, read by the
    validation, the kinematics and life): what it raises is a :class:`~gearcli.errors.PluginError` naming the kind and
    the property, never an internal error of the layer that read it."""
    try:
        return getattr(table, name)
    except GearcliError:
        raise
    except PLUGIN_FAULTS as exc:  # third-party code: named, with what it raised
        raise PluginError(f'stage type "{kind_of(table)}" ({type(table).__module__}): its table\'s {name} raised '
                          f"{type(exc).__name__}: {shorten(' '.join(str(exc).split()), 300)} (docs/plugins.md, "
                          '"A stage kind")') from exc


class MissingFacet(PluginError, KeyError):
    """A stage kind without the facet a command needs (a plug-in kind without a ``"life"`` facet run by
    ``gearcli life``): a plain message, exit 1."""

    def __str__(self) -> str:  # KeyError's own quotes its message
        return str(self.args[0])


class FacetError(PluginError, AttributeError):
    """A plug-in facet lacks an attribute its protocol has (an AttributeError still, for ``getattr`` defaults)."""


class Guarded:
    """A plug-in kind's facet: its attributes as they are; a call that raises (other than gearcli's own errors,
    which keep their message and exit code) is a :class:`~gearcli.errors.PluginError` naming the stage type, the
    facet and the method, never an internal error far from its cause."""

    def __init__(self, kind: str, facet: str, implementation: object):
        self._where = f'stage type "{kind}" ({plugins.origin(implementation)}): its {facet} facet\'s'
        self._impl = implementation
        self._facet = facet
        self._provided = f'kinds.provide("{kind}", "{facet}", {getattr(implementation, "__name__", "")}())'

    @property
    def origin(self) -> str:
        """The module of the plug-in's implementation."""
        return plugins.origin(self._impl)

    def __getattr__(self, attr: str) -> Any:
        if attr.startswith("__") or attr in ("_impl", "_where", "_provided", "_facet"):  # copy and pickle ask before __init__
            raise AttributeError(attr)
        if isinstance(self._impl, type):  # the class given where its instance belongs: every call would fail
            raise FacetError(f"{self._where} {attr} cannot be asked: the facet provided is the class "
                             f"{self._impl.__name__}, not an instance of it ({self._provided}; docs/plugins.md)")
        try:
            value = getattr(self._impl, attr)
        except AttributeError:
            raise FacetError(f"{self._where} {attr} is missing (docs/plugins.md, the facet's protocol)") from None
        if not callable(value) or isinstance(value, type):
            return value

        @functools.wraps(value)
        def call(*args: Any, **kwargs: Any) -> Any:
            try:
                out = value(*args, **kwargs)
            except GearcliError:
                raise
            except PLUGIN_FAULTS as exc:  # third-party code: named, with what it raised
                raise PluginError(f"{self._where} {attr} raised {type(exc).__name__}: "
                                  f"{shorten(' '.join(str(exc).split()), 300)}") from exc
            wanted = _RETURNS.get((self._facet, attr))
            if wanted is not None and not wanted[0](out):
                raise PluginError(f"{self._where} {attr} returned {shorten(repr(out), 120)}, not {wanted[1]} "
                                  "(docs/plugins.md, the facet's protocol)")
            return out
        return call


def _number(x: object) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x) and x >= 0


def _sequence(x: object) -> bool:
    return isinstance(x, (list, tuple))


#: what a facet's call must return where a wrong value would fail far from its cause (an output's type error)
_RETURNS: dict[tuple[str, str], tuple[Callable[[object], bool], str]] = {
    ("design", "inertia"): (_number, "an inertia (kg·m², a finite number ≥ 0)"),
    ("design", "fastest_rad_s"): (_number, "an angular frequency (rad/s, a finite number ≥ 0)"),
    ("design", "diagnostics"): (_sequence, "a list of gearcli.diagnostics.Diagnostic"),
    ("io", "design_tables"): (_sequence, "a list of rich renderables"),
    ("io", "simulation_tables"): (_sequence, "a list of rich renderables"),
    ("io", "json_stage"): (lambda x: _led_by(x, ("index", "type")),
                           "a dict led by index and type (the stage's JSON object, as every stage's)"),
    ("io", "json_simulated_stage"): (lambda x: _led_by(x, ("index",)),
                                     "a dict led by index (the simulated stage's JSON object, as every stage's)"),
}


def _led_by(x: object, keys: tuple[str, ...]) -> bool:
    """A stage's JSON object: a dict whose first keys are ``keys`` (the output contract's ``index`` and the kind's
    ``type``; without them the CSV of a mixed train lost its ``index`` and ``type`` columns)."""
    return isinstance(x, dict) and tuple(x)[:len(keys)] == keys
