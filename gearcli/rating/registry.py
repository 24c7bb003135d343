"""The registry of rating standards, keyed by ``[rating] standard`` (scipy's ``METHODS``, sqlite-utils' hooks).

A name no loaded code registered loads the installed plug-ins (the entry-point group ``gearcli.plugins``,
:mod:`gearcli.core.plugins`) once and is looked up again; a plug-in's standard is kept behind
:class:`gearcli.rating.guard.Guarded` (docs/plugins.md)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from gearcli.core import plugins
from gearcli.errors import ConfigError, PluginConflict

if TYPE_CHECKING:
    from gearcli.rating.standard import RatedMesh, RatingStandard

DEFAULT = "iso6336"
BUILT_IN = (DEFAULT,)  # gearcli's own standards' names: no plug-in registers them (ISO 6336 registers lazily)
SEAM = "rating standard"
_STANDARDS: dict[str, RatingStandard] = {}


def register(std: RatingStandard) -> RatingStandard:
    """Register ``std`` under its ``name``; returns it. The same registrant's later registration replaces its own;
    a name another registrant holds, or a built-in name registered from outside gearcli, is a
    :class:`~gearcli.errors.PluginConflict` naming both (:func:`gearcli.core.plugins.claim`)."""
    refused = plugins.claim(SEAM, std.name, std, built_in=BUILT_IN)
    if refused:
        raise PluginConflict(refused)
    if plugins.origin(std).split(".")[0] == "gearcli":  # gearcli's own standards are kept as they are
        _STANDARDS[std.name] = std
    else:
        from gearcli.rating.guard import Guarded  # lazy: only a plug-in's standard is wrapped (start-up without one)

        _STANDARDS[std.name] = Guarded(std)
    return std


def withdraw(name: str) -> None:
    """Remove the standard registered as ``name`` (a plug-in unloaded, a test's standard after the test)."""
    _STANDARDS.pop(name, None)
    plugins.release(SEAM, name)


def names() -> tuple[str, ...]:
    """The registered standards' names, sorted (ISO 6336 registers when a rated design first asks for its
    standard, ``gearcli.design.standards.standard_of``, or on importing ``gearcli.design.iso6336``)."""
    return tuple(sorted(_STANDARDS))


def standard(name: str, *, source: str | None = None) -> RatingStandard:
    """The standard registered as ``name`` (the installed plug-ins loaded first when none is); an unknown name is a
    ``ConfigError`` (exit 2) naming the key ``rating.standard``, the registered names and any plug-in that failed
    to load."""
    found = _STANDARDS.get(name)
    failures: tuple[str, ...] = ()
    if found is None:
        failures = plugins.load()
        found = _STANDARDS.get(name)
    if found is None:
        known = ", ".join(f'"{n}"' for n in names()) or "none"
        raise ConfigError(f'unknown rating standard "{name}"; registered: {known}{plugins.failures_text(failures)}',
                          source=source, key="rating.standard")
    return found


def for_rating(rating: RatedMesh) -> RatingStandard:
    """The standard that rated ``rating`` (by its ``standard`` title)."""
    for std in _STANDARDS.values():
        if std.title == rating.standard:
            return std
    raise LookupError(f"no registered rating standard is titled {rating.standard!r}")
