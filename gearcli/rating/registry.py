"""The registry of rating standards, keyed by ``[rating] standard`` (scipy's ``METHODS``, sqlite-utils' hooks).

A name no loaded code registered loads the installed plug-ins (the entry-point group ``gearcli.plugins``,
:mod:`gearcli.core.plugins`) once and is looked up again; a plug-in's standard is kept behind
:class:`gearcli.rating.guard.Guarded` (docs/plugins.md)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from gearcli.core import plugins
from gearcli.errors import ConfigError, PluginConflict, PluginError

if TYPE_CHECKING:
    from gearcli.rating.standard import RatedMesh, RatingStandard

DEFAULT = "iso6336"
BUILT_IN = (DEFAULT,)  # gearcli's own standards' names: no plug-in registers them (ISO 6336 registers lazily)
ISO_TITLE = "ISO 6336:2006 method B"  # the title of gearcli's ISO 6336 (gearcli.design.rating.STANDARD)
BUILT_IN_TITLES = {ISO_TITLE: DEFAULT}  # a built-in standard's title -> its name: no other standard takes it
SEAM = "rating standard"
_STANDARDS: dict[str, RatingStandard] = {}


def register(std: RatingStandard) -> RatingStandard:
    """Register ``std`` under its ``name``; returns it. The same registrant's later registration replaces its own;
    a name another registrant holds, or a built-in name registered from outside gearcli, is a
    :class:`~gearcli.errors.PluginConflict` naming both (:func:`gearcli.core.plugins.claim`)."""
    refused = plugins.claim(SEAM, std.name, std, built_in=BUILT_IN)
    if refused:
        raise PluginConflict(refused)
    try:
        _check_title(std)
    except PluginError:
        plugins.release(SEAM, std.name)
        raise
    if plugins.origin(std).split(".")[0] == "gearcli":  # gearcli's own standards are kept as they are
        _STANDARDS[std.name] = std
    else:
        from gearcli.rating.guard import Guarded  # lazy: only a plug-in's standard is wrapped (start-up without one)

        _STANDARDS[std.name] = Guarded(std)
    return std


def _check_title(std: RatingStandard) -> None:
    """A standard's ``title`` is a text no other standard has (a built-in one's included, registered or not): the
    rating tables and ``gearcli life`` find a rating's standard by its title (:func:`for_rating`), so a plug-in
    titled as ISO 6336 had its ratings read by ISO's table rows (an internal error) and its life by the first
    registered. A :class:`~gearcli.errors.PluginError` (no text) or :class:`~gearcli.errors.PluginConflict`."""
    title, where = getattr(std, "title", None), f'rating standard "{std.name}" ({plugins.origin(std)})'
    if not isinstance(title, str) or not title.strip():
        raise PluginError(f"{where}: its title is {title!r}, not a text (the standard its ratings carry, JSON "
                          "rating.standard; docs/plugins.md, \"A rating standard\")")
    holder = next((n for n, other in _STANDARDS.items() if n != std.name and other.title == title),
                  BUILT_IN_TITLES.get(title, std.name))
    if holder != std.name:
        raise PluginConflict(f'{where} is titled {title!r}, the title of rating standard "{holder}": a title names '
                             "one standard (the rating tables and gearcli life find a rating's standard by it); give "
                             "it a title of its own (docs/plugins.md)")


def withdraw(name: str) -> None:
    """Remove the standard registered as ``name`` (a plug-in unloaded, a test's standard after the test)."""
    _STANDARDS.pop(name, None)
    plugins.release(SEAM, name)


def _withdraw_failed(claims: list[tuple[str, str, str]]) -> None:
    for what, name, _ in claims:
        if what == SEAM:
            withdraw(name)


plugins.on_failure(_withdraw_failed)


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
