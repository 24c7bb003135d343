"""Pydantic validation errors in an engineer's words: one ``(key path, message)`` per wrong key.

``Input should be greater than or equal to 5`` becomes ``must be ≥ 5, got 3``; a union's
per-member errors (``stiffness`` is ``"hertz"``, ``"iso6336"`` or a number) become one message.
"""

from __future__ import annotations

import datetime
import json
import math
import re
from typing import Any

from pydantic import ValidationError

from gearcli.config.keys import Resolved, Segment, resolve, suggest, unknown_key_hint
from gearcli.core.text import shorten
from gearcli.stages import kinds

_BOUNDS = {"greater_than": ("gt", ">"), "greater_than_equal": ("ge", "≥"),
           "less_than": ("lt", "<"), "less_than_equal": ("le", "≤")}
_EXPECTED = {"int_type": "a whole number", "float_type": "a number", "string_type": "a string",
             "bool_type": "true or false", "model_type": "a table", "dict_type": "a table",
             "list_type": "an array"}
_MISSING_TABLE = {("stage",): "add one [[stage]] table per gear pair", ("input",): "add an [input] table",
                  ("load",): "add a [load] table"}


def bound(value: Any) -> str:
    """A limit of the schema as an engineer writes it: ``45`` not ``45.0``, ``1e-13``."""
    if isinstance(value, float) and value.is_integer() and abs(value) < 1e15:
        return str(int(value))
    return number(value)


def number(value: Any) -> str:
    """A value from the file in TOML spelling: ``21.5``, ``21.0``, ``nan``, ``-inf``, ``true``."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        if value.bit_length() < 100:
            return str(value)
        return f"a {int(value.bit_length() * math.log10(2)) + 1}-digit integer"
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    return str(value)


def got(value: Any) -> str:
    """What the file holds, in TOML terms: ``21.5``, ``"21"``, ``nan``, ``a table``."""
    if isinstance(value, (bool, int, float)):
        return number(value)
    if isinstance(value, str):
        return json.dumps(value[:40], ensure_ascii=False) + ("…" if len(value) > 40 else "")
    if isinstance(value, dict):
        return "a table"
    if isinstance(value, list):
        return "an array"
    if isinstance(value, (datetime.date, datetime.time)):
        return f"a date/time ({value.isoformat()})"
    return type(value).__name__


def _literal_options(err: dict) -> list[str]:
    return re.findall(r"'([^']*)'", (err.get("ctx") or {}).get("expected", ""))


def _literal(err: dict) -> str:
    inp = err.get("input")
    text = f"must be {err['ctx']['expected']}, got {got(inp)}"
    if isinstance(inp, str):
        best = suggest(inp, _literal_options(err))
        if best:
            text += f" (did you mean '{best}'?)"
    return text


def _type(err: dict, path: tuple[Segment, ...]) -> str:
    t, inp = err["type"], err.get("input")
    if t == "int_type" and isinstance(inp, float) and math.isfinite(inp):
        fix = f" (write {int(inp)})" if inp.is_integer() else ""
        return f"must be a whole number, got {number(inp)}{fix}"
    if t == "float_type" and isinstance(inp, int) and not isinstance(inp, bool):
        return f"is too large to be a number, got {number(inp)}"
    if t == "list_type" and path == ("stage",) and isinstance(inp, dict):
        return "must be an array of tables: write [[stage]] (one per gear pair), not [stage]"
    unquote = " (remove the quotes)" if isinstance(inp, str) and _quoted_value(t, inp) else ""
    return f"must be {_EXPECTED[t]}, got {got(inp)}{unquote}"


def _quoted_value(t: str, text: str) -> bool:
    """Whether ``text`` is a number or boolean written in quotes (``"12"`` for ``12``)."""
    if t == "bool_type":
        return text in ("true", "false")
    try:
        (int if t == "int_type" else float)(text)
    except ValueError:
        return False
    return t in ("int_type", "float_type")


def message(err: dict, where: Resolved) -> str:
    """One pydantic error as a short sentence (without the key path)."""
    t, ctx, inp = err["type"], err.get("ctx") or {}, err.get("input")
    if t == "extra_forbidden":
        hint = unknown_key_hint(str(where.path[-1]), where.parent) if where.parent else ""
        return f"unknown key '{shorten(str(where.path[-1]))}'{hint}"
    if t == "missing":
        table_hint = _MISSING_TABLE.get((str(where.path[0]),)) if len(where.path) == 1 else None
        return f"missing required key ({table_hint})" if table_hint else "missing required key"
    if t in _BOUNDS:
        name, sign = _BOUNDS[t]
        return f"must be {sign} {bound(ctx[name])}, got {number(inp)}"
    if t == "finite_number":
        return f"must be a finite number, got {number(inp)}"
    if t == "literal_error":
        return _literal(err)
    if t in _EXPECTED:
        return _type(err, where.path)
    if t in ("too_short", "too_long"):
        n = ctx.get("min_length") if t == "too_short" else ctx.get("max_length")
        what = "at least" if t == "too_short" else "at most"
        actual = ctx.get("actual_length")
        if actual is None and isinstance(inp, (dict, list, tuple, str)):  # pydantic leaves it out for a table
            actual = len(inp)
        return f"needs {what} {n} entr{'y' if n == 1 else 'ies'}, got {actual if actual is not None else 'more'}"
    if t in ("string_too_short", "string_too_long"):
        n = ctx.get("min_length") if t == "string_too_short" else ctx.get("max_length")
        if t == "string_too_short" and n == 1:
            return "must not be empty"
        what = "at least" if t == "string_too_short" else "at most"
        return f"must be {what} {n} character{'' if n == 1 else 's'} long, got {len(str(inp))}"
    if t == "value_error":
        return str(err["msg"]).removeprefix("Value error, ")
    if t == "union_tag_invalid":  # a stage's type
        known = " or ".join(f'"{k}"' for k in kinds.kinds("table"))
        return f"type must be {known}, got {shorten(str(ctx.get('tag')))!r}"
    text = str(err.get("msg", t))
    return text.replace("Input should be", "must be")


def _mismatch(err: dict) -> bool:
    """True when a union member failed only because the value is of another type."""
    t, inp = err["type"], err.get("input")
    return t in _EXPECTED or (t == "literal_error" and not isinstance(inp, str))


def _union(errs: list[dict], where: Resolved) -> str:
    """One message for the member errors of a union field (e.g. ``stiffness``)."""
    specific = [e for e in errs if not _mismatch(e)]
    if len(specific) == 1:
        return message(specific[0], where)
    options: list[str] = []
    alternatives: list[str] = []
    for e in errs:
        if e["type"] == "literal_error":
            options += _literal_options(e)
            alternatives += [f"'{o}'" for o in _literal_options(e)]
        else:
            alternatives.append(_EXPECTED.get(e["type"], e["type"].replace("_", " ")))
    inp = errs[0].get("input")
    listed = ", ".join(alternatives[:-1]) + " or " + alternatives[-1] if len(alternatives) > 1 else alternatives[0]
    best = suggest(inp, options) if isinstance(inp, str) else None
    return f"must be {listed}, got {got(inp)}" + (f" (did you mean '{best}'?)" if best else "")


def _superseded(groups: dict) -> set:
    """Paths of "missing" keys that an unknown key's did-you-mean already names (``teath`` ->
    ``teeth``): one message says it all."""
    out = set()
    for path, (where, errs) in groups.items():
        if errs[0]["type"] == "extra_forbidden" and where.parent is not None:
            best = suggest(str(path[-1]), list(where.parent.model_fields))
            if best:
                out.add(path[:-1] + (best,))
    return out


def translate(exc: ValidationError) -> list[tuple[tuple[Segment, ...], str]]:
    """Every error of ``exc`` as ``(key path, message)``, in file order, one per key."""
    groups: dict[tuple[Segment, ...], tuple[Resolved, list[Any]]] = {}
    for err in exc.errors(include_url=False):
        where = resolve(err["loc"])
        if err["type"] == "union_tag_invalid":  # a stage's type: name the key
            where = Resolved(where.path + ("type",), where.parent)
        keyed = getattr((err.get("ctx") or {}).get("error"), "key", None) if err["type"] == "value_error" else None
        if isinstance(keyed, str):  # a cross-key rule naming the key it refuses (schema_rules.KeyedValueError)
            where = Resolved(where.path + tuple(keyed.split(".")), None)
        groups.setdefault(where.path, (where, []))[1].append(err)
    skip = _superseded(groups)
    out = []
    for path, (where, errs) in groups.items():
        if path in skip and errs[0]["type"] == "missing":
            continue
        text = message(errs[0], where) if len(errs) == 1 else _union(errs, where)
        out.append((path, text))
    return out
