"""Loading a design file: bytes -> TOML -> ``--set`` overrides -> validated :class:`DesignFile`.

Every failure is a :class:`~gearcli.errors.ConfigError` naming the file (``source``) and the key
path (``key``), e.g. ``configs/x.toml: stage[1].pinion.teeth: must be ≥ 5, got 3``. Several
validation errors raise :class:`ConfigErrors`, whose text has one such line per error.
"""

from __future__ import annotations

import copy
import hashlib
import os
import re
import stat
import sys
import tomllib
import types
from collections.abc import Sequence
from functools import lru_cache
from pathlib import Path
from typing import BinaryIO, Union, get_args, get_origin

from pydantic import BaseModel, ValidationError

from gearcli.config import overrides as _overrides
from gearcli.config.keys import format_path
from gearcli.config.messages import translate
from gearcli.config.prescan import MAX_BYTES, check_bytes, check_text
from gearcli.config.schema import DesignFile, validate_design
from gearcli.config.starter import json_schema, starter_toml
from gearcli.core import plugins
from gearcli.core.records import record
from gearcli.errors import ConfigError
from gearcli.stages import kinds

__all__ = ["ConfigErrors", "LoadedDesign", "load_design", "json_schema", "starter_toml", "MAX_BYTES", "STDIN",
           "read_input_file"]

MAX_LINES_REPORTED = 20
STDIN = "<stdin>"
_INIT_HINT = "`gearcli init FILE` writes a starter design file"


class ConfigErrors(ConfigError):
    """Several errors in one design file: ``str()`` is one ``file: key: message`` line each.
    ``source``, ``key`` and ``message`` are the first error's; ``errors`` holds them all."""

    def __init__(self, errors: Sequence[ConfigError]):
        self.errors = tuple(errors)
        first = self.errors[0]
        super().__init__(first.message, source=first.source, key=first.key)

    def format(self) -> str:
        lines = [e.format() for e in self.errors[:MAX_LINES_REPORTED]]
        extra = len(self.errors) - MAX_LINES_REPORTED
        if extra > 0:
            lines.append(f"{self.errors[0].source}: ... and {extra} more error{'s' if extra > 1 else ''}")
        return "\n".join(lines)


@record
class LoadedDesign:
    """A validated design file.

    ``source``: the path as given, or ``"<stdin>"``. ``sha256``: hex digest of the raw bytes read;
    with ``--set`` overrides, of the raw bytes followed by ``b"\\0--set " + override`` (UTF-8) for
    each override in order, so runs with different overrides differ while a run without any has
    the plain ``sha256sum`` of the file (NUL never occurs in a valid TOML file, so this is
    unambiguous). ``raw``: the TOML data after the overrides, as validated."""

    design: DesignFile
    source: str
    sha256: str
    raw: dict


def load_design(path: str, overrides: Sequence[str] = (), *, stdin: BinaryIO | None = None,
                raw: bytes | None = None) -> LoadedDesign:
    """Read, parse, override and validate a design file; ``path == "-"`` reads ``stdin`` (default
    ``sys.stdin.buffer``); ``raw``: the bytes :func:`read_bytes` has already read from ``path``, which is not read
    again (a FIFO, ``<(cat f.toml)``, holds them once; a file rewritten meanwhile would parse other bytes than
    those hashed). Raises :class:`ConfigError` (or :class:`ConfigErrors`) on any problem."""
    source = STDIN if path == "-" else path
    raw = read_bytes(path, stdin) if raw is None else raw
    data = _parse(raw, source)
    paths = _overrides.apply_all(data, overrides)
    design = _validate(data, source, paths)
    _check_duty_sets(data, design, source, paths)
    return LoadedDesign(design=design, source=source, sha256=_digest(raw, overrides), raw=data)


def _check_duty_sets(data: dict, design: DesignFile, source: str, paths: Sequence[tuple] = ()) -> None:
    """Each ``[[duty]]`` point's ``set`` applied to the file and validated, by every command that loads it, as every
    other key of the file is (``gearcli life`` designs each point with it; ``design`` or ``simulate`` passed a typo
    there). A bad key or value is named ``duty[i].set.KEY`` as ``life`` names it; a value valid alone that breaks
    another key names the point and that key; ``--set`` is the source where one wrote the point's set (``paths``:
    the written paths) or, for a rule between keys, the key named."""
    rest = {k: v for k, v in data.items() if k != "duty"}  # a set never writes the duty (Duty refuses duty.…)
    for i, duty in enumerate(design.duty):
        if not duty.set:
            continue
        variant = _copied(rest)  # without the other points: one point's check does not grow with their number
        set_source = _overrides.SOURCE if _overrides.blamed(("duty", i, "set"), paths) else source
        written = {}  # each key the point sets, by its path
        for key, value in duty.set.items():
            ov = _overrides.parse(f"{key}=0")
            written[ov.path] = ov.key
            try:
                _overrides.apply(variant, _overrides.Override(f"{key}={value}", ov.key, ov.path, value))
            except ConfigError as exc:
                raise ConfigError(exc.message, source=set_source, key=f"duty[{i}].set.{exc.key}") from None
        try:
            validate_design(variant)
        except ValidationError as exc:
            path, text = translate(exc)[0]
            key = format_path(path)
            own = written.get(tuple(path))
            blame = set_source if own or set_source != source else \
                (_overrides.SOURCE if _overrides.blamed(path, paths) else source)
            raise ConfigError(text if own else f"duty[{i}] ({duty.name}): {text}", source=blame,
                              key=f"duty[{i}].set.{own}" if own else key or None) from None


@lru_cache(maxsize=8)
def _parsed(raw: bytes, source: str) -> dict:
    """The parsed TOML of a design file's bytes, once per process (variants deep-copy it)."""
    return _parse(raw, source)


def load_variant(raw: bytes, source: str, overrides: Sequence[str]) -> DesignFile:
    """The validated ``DesignFile`` of a variant of the design file ``raw`` (named ``source`` in messages): its
    data with the ``--set`` ``overrides`` applied in order. The file is parsed once per process (a sweep's or a
    duty's points differ only in their overrides)."""
    data = _copied(_parsed(raw, source))
    paths = _overrides.apply_all(data, overrides)
    return _validate(data, source, paths)


def _copied(data):
    """A deep copy of parsed TOML data: its tables and arrays copied, its leaves (str, int, float, bool, dates and
    times: immutable) shared; what ``copy.deepcopy`` gives for a tree the parser built (no object in two places),
    at a fraction of its cost (a sweep point copies the file's data once)."""
    if type(data) is dict:
        return {k: _copied(v) for k, v in data.items()}
    if type(data) is list:
        return [_copied(v) for v in data]
    return data


def check_override_keys(raw: bytes, source: str, overrides: Sequence[str]) -> None:
    """Raise ConfigError when an override names a key ``--set`` does not accept (values are not validated)."""
    _overrides.apply_all(copy.deepcopy(_parsed(raw, source)), overrides)


def integer_keys(raw: bytes, source: str, sets: Sequence[str], keys: Sequence[str]) -> list[str]:
    """Those of ``keys`` (``--set`` key paths) that take no real number (a tooth or planet count, a choice among
    whole numbers such as ``speed_exponent``, a flag), in the file ``raw`` with ``sets`` applied."""
    return [k for k, tp in _leaf_types(raw, source, sets, keys) if not _takes_real(tp)]


def list_keys(raw: bytes, source: str, sets: Sequence[str], keys: Sequence[str]) -> list[str]:
    """Those of ``keys`` (``--set`` key paths) that name a whole list (``transmission_error_um``, a list of
    harmonics), whose entries ``KEY.0``, ``KEY.1`` ... are the numbers."""
    return [k for k, tp in _leaf_types(raw, source, sets, keys) if _is_list(tp)]


def table_keys(raw: bytes, source: str, sets: Sequence[str], keys: Sequence[str]) -> list[str]:
    """Those of ``keys`` (``--set`` key paths) that name a whole table (``stage.0.mesh``, ``contact``,
    ``materials``), whose keys ``KEY.NAME`` are the numbers."""
    return [k for k, tp in _leaf_types(raw, source, sets, keys) if _is_table(tp)]


def _leaf_types(raw: bytes, source: str, sets: Sequence[str], keys: Sequence[str]) -> list[tuple[str, object]]:
    """Each of ``keys`` with its schema type in the file ``raw`` with ``sets`` applied."""
    data = copy.deepcopy(_parsed(raw, source))
    _overrides.apply_all(data, sets)
    return [(k, _overrides.leaf_type(data, k)) for k in keys]


def _is_table(tp: object) -> bool:
    if get_origin(tp) in (Union, types.UnionType):
        return any(_is_table(a) for a in get_args(tp) if a is not type(None))
    return get_origin(tp) is dict or tp is dict or (isinstance(tp, type) and issubclass(tp, BaseModel))


def _is_list(tp: object) -> bool:
    if get_origin(tp) in (Union, types.UnionType):
        return any(_is_list(a) for a in get_args(tp) if a is not type(None))
    return get_origin(tp) in (list, tuple) or tp in (list, tuple)


def _takes_real(tp: object) -> bool:
    if tp is float:
        return True
    if get_origin(tp) in (Union, types.UnionType):
        return any(_takes_real(a) for a in get_args(tp))
    return tp is object or str(tp) == "typing.Any"


def _digest(raw: bytes, overrides: Sequence[str]) -> str:
    return input_digest(raw, overrides)


def input_digest(raw: bytes, overrides: Sequence[str], history: bytes | None = None) -> str:
    """The JSON's ``input_sha256``: of the design file's bytes, then ``b"\\0--set " + override`` per override
    (:class:`LoadedDesign`), then, for ``gearcli life --series``, ``b"\\0--series "`` and the history's bytes
    (its UTF-8 text, without a BOM): every input of the run, so that two runs on different histories never share it."""
    h = hashlib.sha256(raw)
    for text in overrides:
        h.update(b"\0--set " + text.encode("utf-8", "surrogateescape"))
    if history is not None:
        h.update(b"\0--series " + history)
    return h.hexdigest()


def read_bytes(path: str, stdin: BinaryIO | None = None) -> bytes:
    """The raw bytes of the file (or stdin), at most :data:`MAX_BYTES`."""
    if path == "-":
        source = STDIN
        raw = read_stdin(MAX_BYTES, stdin)
    else:
        source = path
        raw = _read_file(path)
    check_bytes(raw, source)
    return raw


def read_stdin(limit: int, stdin: BinaryIO | None = None) -> bytes:
    """At most ``limit`` + 1 bytes of standard input (``stdin``, else ``sys.stdin.buffer``). A closed standard input
    (``<&-``: Python's ``sys.stdin`` is None) or one that cannot be read is a :class:`ConfigError` naming it."""
    stream = stdin if stdin is not None else getattr(sys.stdin, "buffer", None)
    if stream is None:
        raise ConfigError("standard input is closed ('-' reads it): pipe the file in, or give its path", source=STDIN)
    try:
        return stream.read(limit + 1)
    except OSError as exc:
        raise ConfigError(f"cannot read standard input: {exc.strerror or exc}", source=STDIN) from None


def _read_bounded(path: str, limit: int = MAX_BYTES) -> bytes:
    """At most ``limit`` + 1 bytes. A FIFO is opened without blocking (no writer: empty, never a hang);
    /dev/zero and the like stop at the size limit."""
    fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    try:
        if hasattr(os, "O_NONBLOCK"):
            import fcntl  # lazy: POSIX only (no fcntl on Windows)

            fcntl.fcntl(fd, fcntl.F_SETFL, fcntl.fcntl(fd, fcntl.F_GETFL) & ~os.O_NONBLOCK)
        chunks, size = [], 0
        while size <= limit:
            chunk = os.read(fd, limit + 1 - size)
            if not chunk:
                break
            chunks.append(chunk)
            size += len(chunk)
        raw = b"".join(chunks)
        if not raw and stat.S_ISFIFO(os.fstat(fd).st_mode):
            raise ConfigError("is a FIFO with nothing written to it (no writer); pipe the file into '-' instead",
                              source=path)
        return raw
    finally:
        os.close(fd)


def _read_file(path: str) -> bytes:
    if not path:
        raise ConfigError("no design file given (" + _INIT_HINT + ")")
    return read_input_file(path, MAX_BYTES, what="a design file", hint=_INIT_HINT)


def read_input_file(path: str, limit: int, *, what: str, hint: str = "") -> bytes:
    """At most ``limit`` + 1 bytes of an input file a command reads (the design file, ``life --series``), the
    same way for every one: a directory, a missing or unreadable file, a FIFO without a writer (never a hang)
    are :class:`ConfigError` naming the path."""
    try:
        if Path(path).is_dir():
            raise ConfigError(f"is a directory, not {what}", source=path)
        return _read_bounded(path, limit)
    except FileNotFoundError:
        raise ConfigError("no such file" + (f" ({hint})" if hint else ""), source=path) from None
    except PermissionError:
        raise ConfigError("permission denied", source=path) from None
    except IsADirectoryError:
        raise ConfigError(f"is a directory, not {what}", source=path) from None
    except OSError as exc:
        raise ConfigError(f"cannot read: {exc.strerror or exc}", source=path) from None
    except ValueError:  # e.g. an embedded NUL byte
        raise ConfigError("not a valid file name", source=repr(path)) from None


def _parse(raw: bytes, source: str) -> dict:
    """Bytes -> TOML data, with clear messages for empty, binary, non-UTF-8 and malformed input."""
    if not raw.strip():
        raise ConfigError(f"file is empty ({_INIT_HINT})", source=source)
    try:
        text = raw.decode("utf-8").removeprefix("\ufeff")
    except UnicodeDecodeError as exc:
        line = raw.count(b"\n", 0, exc.start) + 1
        column = exc.start - (raw.rfind(b"\n", 0, exc.start) + 1) + 1
        raise ConfigError(f"not UTF-8 text: byte 0x{raw[exc.start]:02x} at line {line}, column {column} "
                          "(save the file as UTF-8)", source=source) from None
    check_text(text, source)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ConfigError(_syntax_message(str(exc), text), source=source) from None
    except ValueError:  # an integer longer than sys.get_int_max_str_digits()
        limit = sys.get_int_max_str_digits()
        raise ConfigError(f"TOML syntax error: an integer with more than {limit} digits", source=source) from None
    except RecursionError:
        raise ConfigError("TOML syntax error: arrays or inline tables nested too deeply", source=source) from None
    if not data:
        raise ConfigError(f"file is empty: no keys, only comments ({_INIT_HINT})", source=source)
    _unknown_kinds(data)  # a plug-in's kind is registered before --set walks into its table
    return data


_AT = re.compile(r"^(?P<what>.*?) \(at (?:line (?P<line>\d+), column (?P<col>\d+)|end of document)\)$", re.S)
_TWICE = re.compile(r"Cannot declare \((?P<key>.*?),?\) twice")


def _syntax_message(error: str, text: str) -> str:
    """tomllib's ``Invalid value (at line 3, column 5)`` -> ``TOML syntax error at line 3, column 5:
    invalid value (...)  | the line |``."""
    m = _AT.match(error)
    what = m.group("what") if m else error
    line = int(m.group("line")) if m and m.group("line") else None
    col = int(m.group("col")) if m and m.group("col") else None
    lines = text.splitlines()
    if what == "Cannot overwrite a value":
        if line is None:
            line = _duplicate_line(text)
        header = line is not None and 0 < line <= len(lines) and lines[line - 1].lstrip().startswith("[")
        what = ("this table clashes with an earlier key or table of the same name (every stage is [[stage]])"
                if header else "a key is given twice (or a key and a table share a name)")
    elif (t := _TWICE.match(what)) is not None:
        name = ".".join(part.strip().strip("'\"") for part in t.group("key").split(","))
        what = f"table [{name}] is declared twice"
    elif what == "Invalid value":
        word = re.match(r"[A-Za-z_][\w-]*", lines[line - 1][col - 1:]) if line and col and line <= len(lines) else None
        what = f'invalid value (text needs quotes: "{word.group()}")' if word else "invalid value"
    else:
        what = what[:1].lower() + what[1:]
    where = f"line {line}" + (f", column {col}" if col else "") if line else "the end of the file"
    snippet = ""
    if line and 0 < line <= len(lines) and lines[line - 1].strip():
        shown = lines[line - 1].strip()
        snippet = f": {shown[:60]}{'…' if len(shown) > 60 else ''}"
    return f"TOML syntax error at {where}: {what}{snippet}"


def _duplicate_line(text: str) -> int | None:
    """The line that redefines a key, when tomllib only says "at end of document": the shortest
    prefix of the file that fails the same way (binary search; best effort)."""
    lines = text.splitlines(keepends=True)

    def fails(n: int) -> bool:
        try:
            tomllib.loads("".join(lines[:n]))
        except tomllib.TOMLDecodeError as exc:
            return str(exc).startswith("Cannot overwrite a value")
        except (ValueError, RecursionError):
            return False
        return False

    lo, hi = 1, len(lines)
    if not fails(hi):
        return None
    while lo < hi:
        mid = (lo + hi) // 2
        lo, hi = (lo, mid) if fails(mid) else (mid + 1, hi)
    return lo


def _check_window(design: DesignFile, source: str, paths: Sequence[tuple]) -> None:
    """simulation.window_start_s must fall inside the run (a cross-key check the models cannot state)."""
    sim = design.simulation
    if sim.window_start_s is not None and sim.window_start_s >= sim.duration_s:
        blamed = any(_overrides.blamed(("simulation", k), paths) for k in ("window_start_s", "duration_s"))
        raise ConfigError(f"must be below simulation.duration_s = {sim.duration_s:g} s, got {sim.window_start_s:g}",
                          key="simulation.window_start_s", source=_overrides.SOURCE if blamed else source)


def _unknown_kinds(data: dict) -> tuple[int | None, str | None, tuple[str, ...]]:
    """The first stage whose ``type`` no loaded code registered, after loading the installed plug-ins (once per
    process, and only when a stage names such a type): its index, its type and the plug-ins that failed to load."""
    stages = data.get("stage")
    named = [(i, s["type"]) for i, s in enumerate(stages) if isinstance(s, dict) and isinstance(s.get("type"), str)
             ] if isinstance(stages, list) else []
    if all(t in kinds.kinds("table") for _, t in named):
        return None, None, ()
    failures = plugins.load()
    i, t = next(((i, t) for i, t in named if t not in kinds.kinds("table")), (None, None))
    return i, t, failures


def _plug_in_kinds(data: dict, source: str, paths: Sequence[tuple]) -> None:
    """A stage ``type`` no loaded code registered loads the installed plug-ins (:mod:`gearcli.core.plugins`) before
    the file is validated; still unknown with a plug-in that failed to load, a ConfigError saying so."""
    i, t, failures = _unknown_kinds(data)
    if i is not None and failures:  # else validation names the registered kinds
        known = ", ".join(f'"{k}"' for k in kinds.kinds("table"))
        path = ("stage", i, "type")
        raise ConfigError(f'unknown stage type "{t}"; registered: {known}{plugins.failures_text(failures)}',
                          key=format_path(path), source=_overrides.SOURCE if _overrides.blamed(path, paths) else source)


def _validate(data: dict, source: str, paths: Sequence[tuple]) -> DesignFile:
    """The validated model, or ConfigError(s) naming each wrong key (``--set`` as the source of
    errors at or below an overridden key)."""
    _plug_in_kinds(data, source, paths)
    try:
        design = validate_design(data)
        _check_window(design, source, paths)
        return design
    except ValidationError as exc:
        errors = [
            ConfigError(text, key=format_path(path) or None,
                        source=_overrides.SOURCE if _overrides.blamed(path, paths) else source)
            for path, text in translate(exc)
        ]
    except RecursionError:
        raise ConfigError("nested too deeply to validate", source=source) from None
    if len(errors) == 1:
        raise errors[0]
    raise ConfigErrors(errors)
