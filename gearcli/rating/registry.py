"""The registry of rating standards, keyed by ``[rating] standard`` (scipy's ``METHODS``, sqlite-utils' hooks)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from gearcli.errors import ConfigError

if TYPE_CHECKING:
    from gearcli.rating.standard import RatedMesh, RatingStandard

DEFAULT = "iso6336"
_STANDARDS: dict[str, RatingStandard] = {}


def register(std: RatingStandard) -> RatingStandard:
    """Register ``std`` under its ``name`` (a later registration of the same name replaces it); returns it."""
    _STANDARDS[std.name] = std
    return std


def names() -> tuple[str, ...]:
    """The registered standards' names, sorted (ISO 6336 registers when a rated design first asks for its
    standard, ``gearcli.design.standards.standard_of``, or on importing ``gearcli.design.iso6336``)."""
    return tuple(sorted(_STANDARDS))


def standard(name: str, *, source: str | None = None) -> RatingStandard:
    """The standard registered as ``name``; an unknown name is a ``ConfigError`` (exit 2) naming the key
    ``rating.standard`` and the registered names."""
    found = _STANDARDS.get(name)
    if found is None:
        known = ", ".join(f'"{n}"' for n in names()) or "none"
        raise ConfigError(f'unknown rating standard "{name}"; registered: {known}', source=source,
                          key="rating.standard")
    return found


def for_rating(rating: RatedMesh) -> RatingStandard:
    """The standard that rated ``rating`` (by its ``standard`` title)."""
    for std in _STANDARDS.values():
        if std.title == rating.standard:
            return std
    raise LookupError(f"no registered rating standard is titled {rating.standard!r}")
