"""Key paths through the design-file schema: walking the pydantic models, printing paths, hints.

A key path is a tuple of segments: table and key names (``str``) and 0-based array indices
(``int``). It prints as ``stage[0].pinion.teeth`` or ``materials.steel.poisson_ratio``; the same
path is written ``stage.0.pinion.teeth`` on the command line (``--set``).
"""

from __future__ import annotations

import json
import re
import types
from collections.abc import Sequence
from typing import Annotated, Any, Union, get_args, get_origin

from pydantic import BaseModel

from gearcli.config.schema import DesignFile
from gearcli.core.records import record
from gearcli.stages import kinds

Segment = str | int
_BARE_KEY = re.compile(r"^[A-Za-z0-9_-]+$")


def format_path(segments: Sequence[Segment]) -> str:
    """``("stage", 0, "pinion", "teeth")`` -> ``stage[0].pinion.teeth`` (odd names TOML-quoted)."""
    out = ""
    for seg in segments:
        if isinstance(seg, int):
            out += f"[{seg}]"
        else:
            name = seg if _BARE_KEY.match(seg) else json.dumps(seg, ensure_ascii=False)
            out += f".{name}" if out else name
    return out


def unwrap(tp: Any) -> Any:
    """The core of an annotation: ``Annotated`` and ``Optional`` stripped; a real union is kept."""
    while True:
        origin = get_origin(tp)
        if origin is Annotated:
            tp = get_args(tp)[0]
        elif origin in (Union, types.UnionType):
            args = [a for a in get_args(tp) if a is not type(None)]
            if len(args) != 1:
                return tp
            tp = args[0]
        else:
            return tp


def is_model(tp: Any) -> bool:
    return isinstance(tp, type) and issubclass(tp, BaseModel)


def container(tp: Any) -> str | None:
    """``"list"`` or ``"dict"`` for ``list[...]`` / ``dict[str, ...]``, else None."""
    origin = get_origin(tp)
    return {list: "list", dict: "dict"}.get(origin)


def item_type(tp: Any) -> Any:
    """The element type of ``list[X]`` or the value type of ``dict[str, X]``."""
    return unwrap(get_args(tp)[-1])


def suggestions(word: str, options: Sequence[str]) -> list[str]:
    """Options close to a mistyped ``word``: a case-insensitive match, else the options that
    contain it (``density`` -> ``density_kg_m3``; ``speed`` -> all three speeds), else the nearest
    spelling (difflib: ``teath`` -> ``teeth``)."""
    lower = {o.lower(): o for o in options}
    w = word.lower()
    if w in lower:
        return [lower[w]]
    containing = [o for o in options if len(w) >= 3 and w in o.lower()]
    if containing:
        return containing[:3]
    import difflib  # lazy: only a misspelt key needs it, start-up time of every command

    close = difflib.get_close_matches(w, list(lower), n=1, cutoff=0.6)
    return [lower[close[0]]] if close else []


def suggest(word: str, options: Sequence[str]) -> str | None:
    """The one option a mistyped ``word`` most likely means, or None."""
    found = suggestions(word, options)
    return found[0] if len(found) == 1 else None


def _quoted(names: Sequence[str]) -> str:
    names = [f"'{n}'" for n in names]
    return names[0] if len(names) == 1 else ", ".join(names[:-1]) + " or " + names[-1]


def unknown_key_hint(word: str, model: type[BaseModel]) -> str:
    """`` (did you mean 'teeth'?)`` for a key ``model`` does not have; also finds a key that belongs
    one table down (``teeth`` in a stage -> ``pinion.teeth``). Empty when nothing is close."""
    fields = list(model.model_fields)
    found = suggestions(word, fields)
    if not found:
        for name, info in model.model_fields.items():
            sub = unwrap(info.annotation)
            if is_model(sub) and word in sub.model_fields:
                found.append(f"{name}.{word}")
    if found:
        return f" (did you mean {_quoted(found)}?)"
    return f" (allowed: {', '.join(fields)})" if len(fields) <= 8 else ""


@record
class Resolved:
    """Where a pydantic error location lands in the schema.

    ``path``: the key path (union-member tags that pydantic appends are dropped); ``parent``: the
    model that owns the last key (for unknown-key hints), or None."""

    path: tuple[Segment, ...]
    parent: type[BaseModel] | None


def tagged(tp: Any, tag: str) -> Any:
    """The member of a tagged union of models whose ``type`` is ``tag`` (the stage union: any registered stage
    kind's table, :mod:`gearcli.stages.kinds`), or None."""
    if get_origin(tp) not in (Union, types.UnionType):
        return None
    if tag in kinds.kinds("table") and any(is_model(unwrap(a)) and "type" in unwrap(a).model_fields
                                           for a in get_args(tp)):
        return kinds.facet(tag, "table")
    for arg in get_args(tp):
        model = unwrap(arg)
        if is_model(model) and "type" in model.model_fields and tag in get_args(model.model_fields["type"].annotation):
            return model
    return None


def resolve(loc: Sequence[Segment], root: type[BaseModel] = DesignFile) -> Resolved:
    """Walk a pydantic error ``loc`` through the schema from ``root``."""
    tp: Any = root
    path: list[Segment] = []
    parent: type[BaseModel] | None = None
    for seg in loc:
        kind = container(tp)
        if is_model(tp) and isinstance(seg, str):
            parent = tp
            path.append(seg)
            info = tp.model_fields.get(seg)
            if info is None:  # an unknown key
                break
            tp = unwrap(info.annotation)
        elif kind == "list" and isinstance(seg, int):
            path.append(seg)
            tp = item_type(tp)
        elif kind == "dict" and isinstance(seg, str):
            path.append(seg)
            tp = item_type(tp)
        elif isinstance(seg, str) and tagged(tp, seg) is not None:  # a stage's type tag: not a key
            tp = tagged(tp, seg)
        else:  # a leaf: what follows is a union-member tag
            break
    return Resolved(tuple(path), parent)
