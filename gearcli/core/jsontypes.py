"""The JSON value types, defined once: what a JSON document, a sweep row or a result's ``extra`` holds.

``JsonValue`` is recursive (lists and objects of JSON values); ``JsonScalar`` is one cell of a CSV row or a
JSON leaf. Layers type their boundaries with these instead of ``Any``.
"""

from __future__ import annotations

from typing import TypeAlias

JsonScalar: TypeAlias = str | int | float | bool | None
JsonValue: TypeAlias = JsonScalar | list["JsonValue"] | tuple["JsonValue", ...] | dict[str, "JsonValue"]
JsonObject: TypeAlias = dict[str, JsonValue]

__all__ = ["JsonObject", "JsonScalar", "JsonValue"]
