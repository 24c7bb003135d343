"""A tiny JSON Schema checker for the subset pydantic emits, shared by the tests that compare the schema with
validation (tests/unit/test_docs_and_schema.py checks the checker itself)."""

from __future__ import annotations

import re


def valid(value, schema: dict, root: dict) -> bool:
    """Whether ``value`` satisfies ``schema`` (the subset pydantic emits: $ref, anyOf, oneOf, allOf, not, type,
    enum, const, bounds, min/maxLength, pattern, min/maxItems, items, properties, required,
    additionalProperties)."""
    if "$ref" in schema:
        return valid(value, root["$defs"][schema["$ref"].rsplit("/", 1)[1]], root)
    if "anyOf" in schema and not any(valid(value, s, root) for s in schema["anyOf"]):
        return False
    if "oneOf" in schema and sum(valid(value, s, root) for s in schema["oneOf"]) != 1:
        return False
    if "allOf" in schema and not all(valid(value, s, root) for s in schema["allOf"]):
        return False
    if "not" in schema and valid(value, schema["not"], root):
        return False
    if "enum" in schema and value not in schema["enum"]:
        return False
    if "const" in schema and value != schema["const"]:
        return False
    t = schema.get("type")
    types = {"number": (int, float), "integer": (int,), "string": (str,), "boolean": (bool,), "object": (dict,),
             "array": (list,), "null": (type(None),)}
    if t is not None:
        if not isinstance(value, types[t]) or (t in ("number", "integer") and isinstance(value, bool)):
            return False
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        if value != value or value in (float("inf"), float("-inf")):
            return False
        for key, ok in (("minimum", value >= schema.get("minimum", value)),
                        ("maximum", value <= schema.get("maximum", value))):
            if key in schema and not ok:
                return False
        if "exclusiveMinimum" in schema and not value > schema["exclusiveMinimum"]:
            return False
        if "exclusiveMaximum" in schema and not value < schema["exclusiveMaximum"]:
            return False
    if isinstance(value, str) and not schema.get("minLength", 0) <= len(value) <= schema.get("maxLength", len(value)):
        return False
    if isinstance(value, str) and "pattern" in schema and re.search(schema["pattern"], value) is None:
        return False
    if isinstance(value, list):
        if not schema.get("minItems", 0) <= len(value) <= schema.get("maxItems", len(value)):
            return False
        if "items" in schema and not all(valid(v, schema["items"], root) for v in value):
            return False
    if isinstance(value, dict):
        props = schema.get("properties", {})
        if any(k not in value for k in schema.get("required", [])):
            return False
        extra = schema.get("additionalProperties", True)
        for k, v in value.items():
            if k in props:
                if not valid(v, props[k], root):
                    return False
            elif extra is False:
                return False
            elif isinstance(extra, dict) and not valid(v, extra, root):
                return False
        if "maxProperties" in schema and len(value) > schema["maxProperties"]:
            return False
    return True
