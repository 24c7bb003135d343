"""The stage-kind registry: one entry per design-file stage ``type``, one implementation per facet.

The bottom layer (it imports nothing of gearcli but ``errors``): the facets themselves are typed by the
protocols of the layer that calls them (``gearcli.stages.design.DesignKind``, ``gearcli.stages.model.ModelKind``,
``gearcli.stages.io.IoKind``), which look their implementation up here. A kind registered from outside
gearcli (a plug-in, or a test: ``tests/stages/belt.py``) calls :func:`provide` once per facet.
"""

from __future__ import annotations

PARALLEL = "parallel"  # the kind of a stage table without ``type``

_FACETS: dict[tuple[str, str], object] = {}


def provide(kind: str, facet: str, implementation: object) -> None:
    """Register ``implementation`` as the ``facet`` ("design", "model", "io", …) of stage ``type = kind``."""
    _FACETS[(kind, facet)] = implementation


def withdraw(kind: str, facet: str) -> None:
    """Remove the ``facet`` of stage kind ``kind`` (a plug-in unloaded, a test's kind after the test)."""
    _FACETS.pop((kind, facet), None)


def facet(kind: str, facet: str) -> object:
    """The ``facet`` of stage kind ``kind``; a ``KeyError`` naming the kinds that have it when none is registered."""
    try:
        return _FACETS[(kind, facet)]
    except KeyError:
        known = sorted(k for k, f in _FACETS if f == facet)
        raise KeyError(f"stage type {kind!r} has no {facet} registered (known: {', '.join(known)})") from None


def kinds(facet: str) -> tuple[str, ...]:
    """The stage kinds with a ``facet`` registered, in registration order."""
    return tuple(k for k, f in _FACETS if f == facet)


def kind_of(stage: object) -> str:
    """The kind of a stage table or a stage result: its ``type``, "parallel" when it has none."""
    return str(getattr(stage, "type", None) or PARALLEL)
