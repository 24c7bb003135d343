"""``--set KEY=VALUE``: command-line overrides of design-file keys, applied before validation.

KEY is dotted; numeric segments index arrays (``stage.0.pinion.teeth``; ``stage[0].pinion.teeth``,
the form error messages print, is accepted too), and name a key under a table (``materials.4140``); a quoted
segment (``materials."S355.J2"``) is a name as TOML's quoted keys are. KEY must name a key of the schema, present in
the file or not: a missing key or table is created. VALUE is read as a TOML value
(``22`` int, ``1e-8`` float, ``true`` bool, ``"x"`` string, ``{ ... }`` inline table), and as
a bare string when it is not one (``hand=left``); a number given to a key that holds a string is its text
(``material=4140``).

Setting one key of a group where the schema wants exactly one (``input.speed_rpm`` when the file
has ``speed_deg_s``) removes the others of the group: the user means to change the speed, not to
give it twice. Setting ``input.starting`` removes the parameters of the other starting methods (a star-delta
file's ``switch_speed_rpm`` under ``starting = "direct"``), which the command line could not unset otherwise.
"""

from __future__ import annotations

import copy
import re
import tomllib
import types
from collections.abc import Sequence
from typing import Any, Union, get_args, get_origin

from pydantic import BaseModel

from gearcli.config.drive import START_PARAMETERS
from gearcli.config.duty import DUTY_TORQUE_KEYS, Duty
from gearcli.config.keys import (
    Segment,
    container,
    format_path,
    is_model,
    item_type,
    tagged,
    unknown_key_hint,
    unwrap,
)
from gearcli.config.machine import NAMEPLATE, Motor
from gearcli.config.messages import got
from gearcli.config.schema import DesignFile, Input, Load, Lubricant, Rating, Target
from gearcli.core import plugins
from gearcli.core.records import record
from gearcli.core.text import shorten
from gearcli.errors import ConfigError
from gearcli.stages import kinds

SOURCE = "--set"

#: Keys of which a table holds exactly one (or at most one): setting one replaces its siblings, so a --set can
#: override the file's choice (a duty point's power for its torque, K_gamma for the file's load_sharing_factor).
EXCLUSIVE: dict[type[BaseModel], tuple[tuple[str, ...], ...]] = {
    Input: (("speed_deg_s", "speed_rpm", "speed_rad_s"), ("torque_Nm", "torque_Nmm", "power_kW")),
    Load: (("torque_Nmm", "torque_Nm", "power_kW", "torque_speed"),),  # a torque-speed table is the torque too
    Target: (("output_speed_rpm", "output_speed_deg_s"),),
    Duty: (DUTY_TORQUE_KEYS,),
    Lubricant: (("contamination", "e_C"),),  # a cleanliness level, or its factor
    Rating: (("load_sharing_factor", "K_gamma"),),  # one K_gamma under two names
}


@record
class Override:
    """One parsed ``--set``: the key as typed, its path, and the value."""

    text: str
    key: str
    path: tuple[Segment, ...]
    value: Any


def parse_value(text: str) -> Any:
    """A TOML value (``22``, ``1e-8``, ``true``, ``"x"``, ``[1, 2]``), else the text as a string."""
    try:
        parsed = tomllib.loads("v = " + text)
    except (ValueError, RecursionError):  # TOMLDecodeError is a ValueError
        return text
    return parsed["v"] if list(parsed) == ["v"] else text


def toml_error(text: str) -> str | None:
    """Why ``text`` is no TOML value (tomllib's reason, its place counted in ``text``), or None if it is one."""
    try:
        tomllib.loads("v = " + text)
    except (ValueError, RecursionError) as exc:
        where = lambda m: f"at character {int(m.group(1)) - 4} of the value"  # noqa: E731 - "v = " comes first
        return re.sub(r"at line 1, column (\d+)", where, str(exc)).replace("end of document", "the end of the value")
    return None


def split_key(key: str) -> list[tuple[str, bool]]:
    """The key's segments, each with whether it was quoted: ``materials."4140".density_kg_m3`` (TOML's quoted
    key) names the material 4140, never an index, and may hold dots."""
    key = re.sub(r"\[(\d+)\]", r".\1", key.strip())
    segments: list[tuple[str, bool]] = []
    rest = key
    while True:
        m = re.match(r'"([^"]*)"(?=\.|$)|\'([^\']*)\'(?=\.|$)', rest)
        if m:
            segments.append((m.group(1) if m.group(1) is not None else m.group(2), True))
            rest = rest[m.end():]
        else:
            head = rest.partition(".")[0]
            segments.append((head, False))
            rest = rest[len(head):]
        if not rest:
            return segments
        rest = rest[1:]  # the dot
        if not rest:
            segments.append(("", False))
            return segments


def parse(text: str) -> Override:
    """``"stage.0.pinion.teeth=22"`` -> an :class:`Override` (the path is checked by :func:`apply`)."""
    done = _PARSED.get(text)
    if done is not None:
        return done
    ov = _parse(text)
    if type(ov.value) in _IMMUTABLE:  # an array or a table, which the data would share and may change, never kept
        if len(_PARSED) >= _PARSED_MAX:
            _PARSED.clear()
        _PARSED[text] = ov
    return ov


#: :func:`parse`'s overrides of one process, keyed by the text (a str: all that determines one), at most
#: _PARSED_MAX of them; those whose value is immutable only (an Override is frozen): a sweep's or a duty's points
#: apply the same --set and ramp overrides at every point
_PARSED: dict[str, Override] = {}
_PARSED_MAX = 256
_IMMUTABLE = frozenset({int, float, bool, str})


def _parse(text: str) -> Override:
    key, sep, value = text.partition("=")
    key = key.strip()
    if not sep or not key:
        raise ConfigError(f"expected KEY=VALUE, got {shorten(repr(text))} (e.g. --set input.speed_rpm=1450)",
                          source=SOURCE)
    segments = split_key(key)
    if any(s == "" and not quoted for s, quoted in segments):
        raise ConfigError("empty key segment (keys look like stage.0.pinion.teeth)", source=SOURCE, key=key)
    path = tuple(int(s) if not quoted and s.isascii() and s.isdigit() else s for s, quoted in segments)
    return Override(text, key, path, parse_value(value.strip()))


def _as_key(tp: Any, seg: Segment) -> Segment:
    """A segment under a table (a model, or a name-keyed table such as ``[materials]``) is a key, a string: the
    material ``4140`` of ``materials.4140``, not an index."""
    return str(seg) if isinstance(seg, int) and (is_model(tp) or container(tp) == "dict") else seg


def _as_text(leaf_tp: Any, ov: Override) -> Any:
    """The value as typed where the key holds a string and TOML read a number (``material=4140``, ``title=2024``):
    the text, as a bare word is."""
    if leaf_tp is str and isinstance(ov.value, int | float) and not isinstance(ov.value, bool):
        return ov.text.partition("=")[2].strip()
    return ov.value


def _fail(ov: Override, message: str) -> ConfigError:
    return ConfigError(message, source=SOURCE, key=ov.key)


def _descend(ov: Override, child: Any, child_tp: Any, depth: int) -> Any:
    """Check that the data under ``ov.path[:depth + 1]`` can hold keys; return it."""
    here = format_path(ov.path[: depth + 1])
    want = list if container(child_tp) == "list" else dict
    if not (is_model(child_tp) or container(child_tp)):
        raise _fail(ov, f"{here} is a value, not a table")
    if not isinstance(child, want):
        what = "an array of tables" if want is list else "a table"
        raise _fail(ov, f"{here} is {got(child)} in the file, not {what}")
    return child


def _entry_keys(tp: Any) -> dict[str, Any]:
    """The keys an entry of the array ``tp`` may have and their types (of every member of a union of tables, and
    of every registered stage kind where the entry is a stage table)."""
    entry = item_type(tp)
    members = [unwrap(a) for a in get_args(entry)] if get_origin(entry) in (Union, types.UnionType) else [entry]
    members = [m for m in members if is_model(m)]
    if any("type" in m.model_fields for m in members):
        members += [kinds.facet(k, "table") for k in kinds.kinds("table")]
    return {k: unwrap(f.annotation) for m in members if is_model(m) for k, f in m.model_fields.items()}


def _holds_keys(tp: Any) -> bool:
    return is_model(tp) or container(tp) is not None or get_origin(tp) in (Union, types.UnionType)


def _where(ov: Override, depth: int) -> str:
    """The table ``ov.path[:depth]`` as a message names it (only a failed step's message reads it)."""
    return format_path(ov.path[:depth]) or "the design file"


def _step(ov: Override, node: Any, tp: Any, seg: Segment, depth: int) -> tuple[Any, Any]:
    """The schema type and the data one segment down from ``node``, created when absent.
    For the last segment only the schema is checked and the data is None."""
    last = depth == len(ov.path) - 1
    if container(tp) == "list":
        if not isinstance(seg, int):
            signed = isinstance(seg, str) and seg[:1] in "+-" and seg[1:].isdigit()
            # a signed index, or a word no entry has as a key (``stage.x.pinion``: meant as the index), is replaced
            # by the index; an entry's key (``stage.pinion``: the index left out) is kept after it
            keys = _entry_keys(tp)
            kept = str(seg) in keys and (last or _holds_keys(keys[str(seg)]))
            rest = ov.path[depth:] if kept else ov.path[depth + 1:]
            example = ".".join(map(str, ov.path[:depth] + (0,) + rest))
            if signed:
                n = len(node) if isinstance(node, list) else 0
                span = f" (0–{n - 1} here)" if n else ""
                raise _fail(ov, f"{_where(ov, depth)} is an array: an index is a whole number from 0{span}, without a "
                                f"sign (no counting from the end), e.g. {example}")
            raise _fail(ov, f"{_where(ov, depth)} is an array: give an index, e.g. {example}")
        if seg >= len(node):
            n = len(node)
            have = f"{n} {_where(ov, depth)} entr{'y' if n == 1 else 'ies'}" + (f" (0–{n - 1})" if n else "")
            raise _fail(ov, f"index {seg} is out of range: the file has {have}")
        child_tp = item_type(tp)
        if isinstance(node[seg], dict):  # a stage: the member of the stage union its ``type`` names
            tag = str(node[seg].get("type", "parallel"))
            member = tagged(child_tp, tag)
            if member is None and ov.path[:1] == ("stage",) and not last:
                known = ", ".join(f'"{k}"' for k in kinds.kinds("table"))
                raise _fail(ov, f'{format_path(ov.path[: depth + 1])} is of type "{shorten(tag)}", which no stage kind '
                                f"registered (registered: {known}; an installed plug-in's, docs/plugins.md)"
                                f"{plugins.failures_text(plugins.load())}")  # why a plug-in that would have did not
            child_tp = member or child_tp
        return (child_tp, None) if last else (child_tp, _descend(ov, node[seg], child_tp, depth))
    if is_model(tp):
        if not isinstance(seg, str) or seg not in tp.model_fields:
            raise _fail(ov, f"unknown key '{shorten(str(seg))}' in {shorten(_where(ov, depth))}"
                            f"{unknown_key_hint(str(seg), tp)}")
        child_tp = unwrap(tp.model_fields[seg].annotation)
    elif container(tp) == "dict":
        child_tp = item_type(tp)
    else:
        raise _fail(ov, f"{_where(ov, depth)} is a value, not a table")
    if last:
        return child_tp, None
    if container(tp) == "dict" and not (is_model(child_tp) or container(child_tp)):  # a [[duty]] set: dotted keys
        key = ".".join(map(str, ov.path[depth:]))
        raise _fail(ov, f"{_where(ov, depth)} takes a key of the design file as --set writes it, {key} here: quote it "
                        f"as one key, --set '{'.'.join(map(str, ov.path[:depth]))}.\"{key}\"=VALUE'")
    if not (is_model(child_tp) or container(child_tp)):
        raise _fail(ov, f"{format_path(ov.path[: depth + 1])} is a value, not a table")
    if seg not in node:
        node[seg] = _new_table(tp, seg, child_tp)
    return child_tp, _descend(ov, node[seg], child_tp, depth)


def _new_table(tp: Any, seg: Segment, child_tp: Any) -> Any:
    """An empty table (or array) for a key the file lacks; a table of named entries starts from
    the schema's default, so ``materials.alu.*`` adds aluminium without losing the default steel."""
    if container(child_tp) == "list":
        return []
    if is_model(tp) and container(child_tp) == "dict":
        default = tp.model_fields[seg].get_default(call_default_factory=True)
        if isinstance(default, dict):
            return {k: v.model_dump() if isinstance(v, BaseModel) else v for k, v in default.items()}
    return {}


def apply(data: dict, ov: Override) -> tuple[Segment, ...]:
    """Set ``ov`` in the TOML data in place, after checking its key against the schema. Returns
    the path of what it wrote: the key, or the outermost table it had to create for it."""
    tp: Any = DesignFile
    node: Any = data
    path: list[Segment] = []
    created: int | None = None
    for depth, seg in enumerate(ov.path[:-1]):
        seg = _as_key(tp, seg)
        path.append(seg)
        if created is None and isinstance(node, dict) and seg not in node:
            created = depth + 1
        tp, node = _step(ov, node, tp, seg, depth)
    last = _as_key(tp, ov.path[-1])
    path.append(last)
    leaf_tp = _step(ov, node, tp, last, len(ov.path) - 1)[0]  # checks the last key exists in the schema
    _no_broken_array_or_table(ov, leaf_tp)
    if isinstance(node, dict):
        for group in EXCLUSIVE.get(tp, ()):
            if last in group:
                for sibling in group:
                    node.pop(sibling, None)
        if tp is Input and last == "starting":
            _drop_other_starting_parameters(node, ov.value)
        if tp is Motor:  # a motor is its nameplate or its torque-speed table: the one set replaces the other
            for key in NAMEPLATE if last == "torque_speed" else ("torque_speed",) if last in NAMEPLATE else ():
                node.pop(key, None)
    node[last] = _as_text(leaf_tp, ov)
    return tuple(path[:created]) if created is not None else tuple(path)


def _no_broken_array_or_table(ov: Override, leaf_tp: Any) -> None:
    """A value written as an array or an inline table (``[`` or ``{`` first) that TOML cannot read, on a key that
    holds one: TOML's reason, not the schema's "must be an array, got \"[-0.1 -0.2]\"" of the text taken as a word
    (a bare word stays a string where the key takes one: ``--set title=[draft]``)."""
    text = ov.value if isinstance(ov.value, str) else ""
    if text[:1] not in ("[", "{") or not (is_model(leaf_tp) or container(leaf_tp)):
        return
    reason = toml_error(text)
    if reason is not None:
        what, form = (("an array", "[a, b, ...]") if text[0] == "[" else
                      ("an inline table", "{ key = value, ... }, each key once"))
        raise _fail(ov, f"{shorten(repr(text))} is not {what} TOML can read: {reason}; TOML writes {what} "
                        f"{form}, with commas (quote the whole --set for the shell)")


def _drop_other_starting_parameters(node: dict, method: Any) -> None:
    """Make the input's starting parameters ``method``'s: another method's would be a stray key (exit 2) that a
    ``--set`` cannot remove, so comparing starts (``--set input.starting=direct`` on a star-delta file, a sweep over
    ``input.starting``) would need an edited file. A motor drive's ``ramp_s`` is the VFD's alone."""
    for key, owner in START_PARAMETERS.items():
        if owner != method:
            node.pop(key, None)
    if method != "vfd" and node.get("drive") == "motor":
        node.pop("ramp_s", None)


def leaf_type(data: dict, key: str) -> Any:
    """The schema type of ``key`` (a ``--set`` key path) in the TOML data, unwrapped (``int``, ``float``, a
    model ...); the key is checked as :func:`apply` checks it, the data left as it was."""
    ov = parse(f"{key}=0")
    tp: Any = DesignFile
    node: Any = copy.deepcopy(data)
    for depth, seg in enumerate(ov.path[:-1]):
        tp, node = _step(ov, node, tp, _as_key(tp, seg), depth)
    return _step(ov, node, tp, _as_key(tp, ov.path[-1]), len(ov.path) - 1)[0]


def apply_all(data: dict, texts: Sequence[str]) -> list[tuple[Segment, ...]]:
    """Apply every ``--set`` in order (a later one wins); the paths written, see :func:`blamed`."""
    return [apply(data, parse(text)) for text in texts]


def blames_key(key: str | None, overrides: Sequence[str]) -> bool:
    """Whether a design error at ``key`` (``stage[0].gear.hand``) comes from a ``--set``: written at or around
    it, or at its sibling member of the same stage (``--set stage.0.pinion.hand=right`` breaks the pair's
    hands, reported at the gear)."""
    if not key or not overrides:
        return False
    try:
        path = parse(f"{key}=0").path
        written = [parse(o).path for o in overrides]
    except ConfigError:
        return False
    stage = path[:2] if len(path) >= 4 and path[0] == "stage" else None
    return blamed(path, written) or (stage is not None and any(w[:2] == stage and len(w) > 2 for w in written))


def blamed(path: Sequence[Segment], written: Sequence[tuple[Segment, ...]]) -> bool:
    """Whether an error at ``path`` comes from a ``--set``: it lies at or below a written path
    (a wrong value, a key missing from a table the override created), or above one (a table-level
    rule such as "exactly one speed" broken by the override)."""
    path = tuple(path)
    return any(path[: len(w)] == w or w[: len(path)] == path for w in written)
