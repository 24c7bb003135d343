"""The JSON value types, defined once: what a JSON document, a sweep row or a result's ``extra`` holds.

``JsonValue`` is recursive (sequences and mappings of JSON values, read-only so that a ``list[float]`` is one); ``JsonScalar`` is one cell of a CSV row or a
JSON leaf. Layers type their boundaries with these instead of ``Any``.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TypeAlias

JsonScalar: TypeAlias = str | int | float | bool | None
#: read-only containers (covariant: a ``list[dict[str, float]]`` is a JSON value)
JsonValue: TypeAlias = JsonScalar | Sequence["JsonValue"] | Mapping[str, "JsonValue"]
JsonObject: TypeAlias = dict[str, JsonValue]

__all__ = ["JsonObject", "JsonScalar", "JsonValue"]
