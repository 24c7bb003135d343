"""Writing a sweep's rows as they arrive: a resumable ``-o FILE`` (CSV or JSON), or stdout.

CSV file: the first line is a comment that identifies the sweep, then the header row, then one row per
point, appended (and flushed) as each arrives::

    # gearcli sweep: {"gearcli_version": "0.1.0", "input_sha256": "...", "sweep": {...}}
    input.speed_rpm,direction,status,message,stage1_tangential_N_mean,...

Read it with ``pandas.read_csv(path, skiprows=1)`` (or ``comment="#"``; messages never contain '#'),
or skip the first line with any CSV reader. Empty cells are values the run does not provide.

JSON file: one document ``{"gearcli_version", "input_sha256", "sweep", "columns", "rows": [{...}]}``.
A JSON document cannot be appended to and stay valid, so it is rewritten atomically (temporary file,
rename) at most once a second while rows arrive and once at the end, Ctrl-C included: the file on disk
is always a complete document; a hard kill loses at most the last second of rows.

Resume: an existing file whose identity (input hash and sweep arguments) equals this run's lends its
rows; the run computes only the missing points. A different identity is an error (exit 2), never a
mix. At the end the file is rewritten in the sweep's point order, so a resumed sweep leaves the same
file as an uninterrupted one (except ``wall_s``). All whole-file writes go through :func:`_replace`.
"""

from __future__ import annotations

import csv
import io
import json
import math
import os
import re
import sys
import time
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, TextIO

from gearcli.core.jsontypes import JsonObject, JsonScalar
from gearcli.core.text import shorten, sweep_text_cell
from gearcli.errors import ConfigError, OutputError
from gearcli.io.atomic import write_atomic
from gearcli.io.output import write_stream

if TYPE_CHECKING:  # `gearcli design` imports the facade, which imports this module: not the sweep (numpy)
    from gearcli.sweep.columns import Row

MARK = "# gearcli sweep: "
_INT = re.compile(r"-?[0-9]+")
JSON_EVERY_S = 1.0


def _unwritable(path: Path, exc: OSError) -> OutputError:
    """A sweep file the system refuses (a full disk, a file-size limit, a vanished directory): exit 2 naming it, as
    every ``-o`` (the rows already on disk stay; a row a full disk cut short is dropped when the sweep resumes)."""
    return OutputError(f"cannot write: {exc.strerror or exc}", path=shorten(str(path)))


def _replace(path: Path, text: str) -> None:
    """The one place a whole sweep file is written (atomically, flushed to the disk: a checkpoint a machine crash
    must not empty); swap for the shared -o helper."""
    try:
        write_atomic(path, text, durable=True)
    except OSError as exc:
        raise _unwritable(path, exc) from None


def _cell(v: JsonScalar) -> str:
    if v is None:
        return ""
    if isinstance(v, float):
        return repr(v) if math.isfinite(v) else ""
    if isinstance(v, str):  # text: controls escaped, no spreadsheet formula (as every gearcli CSV), no '#'
        return sweep_text_cell(v)
    return str(v)


def _json_value(v: JsonScalar) -> JsonScalar:
    return None if isinstance(v, float) and not math.isfinite(v) else v


def _csv_line(values: Sequence[JsonScalar]) -> str:
    buf = io.StringIO()
    csv.writer(buf, lineterminator="\n").writerow([_cell(v) for v in values])
    return buf.getvalue()


class SweepFileError(ConfigError):
    """The -o file belongs to another sweep or is not a sweep file (exit 2)."""


class RowSink:
    """Where rows go: ``add`` each as it arrives, ``finish`` with all rows in point order."""

    def __init__(self, columns: Sequence[str], identity: JsonObject):
        self.columns = list(columns)
        self.identity = identity
        self.rows: list[Row] = []

    def add(self, row: Row) -> None:
        self.rows.append(row)

    def finish(self, ordered: Sequence[Row]) -> None:
        self.rows = list(ordered)

    def close(self) -> None:
        """On interruption: leave what is done."""


def read_identity(path: str) -> tuple[JsonObject | None, list[Row]]:
    """The identity and the rows of an existing sweep file; (None, []) when there is none (or it is empty)."""
    p = Path(path)
    if not p.exists() or p.stat().st_size == 0:
        return None, []
    if p.is_dir():
        raise SweepFileError("is a directory", source=path)
    text = p.read_text(encoding="utf-8", errors="replace")
    if p.suffix.lower() == ".json":
        return _read_json(text, path)
    return _read_csv(text, path)


def _not_ours(path: str) -> SweepFileError:
    return SweepFileError("exists and is not a gearcli sweep file; choose another -o FILE or remove it", source=path)


def _read_csv(text: str, path: str) -> tuple[JsonObject, list[Row]]:
    first, _, rest = text.partition("\n")
    if not first.startswith(MARK):
        raise _not_ours(path)
    try:
        identity = json.loads(first[len(MARK):])
    except (ValueError, RecursionError):  # not JSON, or nested past the parser's recursion limit
        raise _not_ours(path) from None
    if not _is_identity(identity):
        raise _not_ours(path)
    lines = _csv_lines(rest, path)
    if not lines:
        return identity, []
    header, body = lines[0], lines[1:]
    if not text.endswith("\n") and body:  # a row cut short by a hard kill
        body = body[:-1]
    rows: list[Row] = [dict(zip(header, map(_typed, r), strict=True)) for r in body if len(r) == len(header)]
    return identity, rows


def _csv_lines(text: str, path: str) -> list[list[str]]:
    """The CSV records of ``text``. A cell is read back whatever its length (a point's long message: the csv module's
    default limit, 128 KiB a field, would refuse the file this module wrote); text that is no CSV is no sweep file."""
    limit = csv.field_size_limit()
    csv.field_size_limit(max(limit, len(text)))
    try:
        return list(csv.reader(io.StringIO(text)))
    except csv.Error:
        raise _not_ours(path) from None
    finally:
        csv.field_size_limit(limit)


def _typed(cell: str) -> JsonScalar:
    """A cell read back as the value :func:`_cell` wrote: an empty cell None, a number the number it was
    written from (floats by ``repr``, which round-trips exactly; integers by ``str``), else the text as
    written. So a resumed row is the fresh row again, and writing it again gives the same bytes (a text cell
    never gets the formula escape twice, a negative number never gets it at all)."""
    if cell == "":
        return None
    if _INT.fullmatch(cell):
        return int(cell)
    try:
        value = float(cell)
    except ValueError:
        return cell
    return value if math.isfinite(value) and repr(value) == cell else cell


def _read_json(text: str, path: str) -> tuple[JsonObject, list[Row]]:
    try:
        doc = json.loads(text)
    except (ValueError, RecursionError):  # not JSON, or nested past the parser's recursion limit
        raise _not_ours(path) from None
    if not _is_identity(doc) or "sweep" not in doc or not isinstance(doc.get("rows"), list):
        raise _not_ours(path)
    identity = {k: doc.get(k) for k in ("gearcli_version", "input_sha256", "sweep")}
    return identity, [r for r in doc["rows"] if isinstance(r, dict)]  # anything else is no row: computed again


def _is_identity(doc: object) -> bool:
    """Whether ``doc`` has the shape of a sweep file's identity: an object whose ``sweep`` (the arguments), when
    present, is an object too. Valid JSON of another shape (a list, ``"sweep": 3``) is no sweep file of ours."""
    return isinstance(doc, dict) and isinstance(doc.get("sweep", {}), dict)


class CsvFile(RowSink):
    def __init__(self, path: str, columns: Sequence[str], identity: JsonObject, previous: Sequence[Row]):
        super().__init__(columns, identity)
        self.path = Path(path)
        self.rows = list(previous)
        _replace(self.path, self._text(self.rows))  # also drops a row a hard kill cut short
        try:
            self.fh: TextIO | None = self.path.open("a", encoding="utf-8", newline="")
        except OSError as exc:
            raise _unwritable(self.path, exc) from None

    def _text(self, rows: Sequence[Row]) -> str:
        return (MARK + json.dumps(self.identity, separators=(", ", ": ")) + "\n" + _csv_line(self.columns)
                + "".join(_csv_line([r.get(c) for c in self.columns]) for r in rows))

    def add(self, row: Row) -> None:
        super().add(row)
        assert self.fh is not None
        whole = os.fstat(self.fh.fileno()).st_size  # the file's whole lines (every row before was flushed)
        try:
            self.fh.write(_csv_line([row.get(c) for c in self.columns]))  # one write per row: whole lines only
            self.fh.flush()
        except OSError as exc:
            self._abandon(whole)
            raise _unwritable(self.path, exc) from None

    def _abandon(self, whole: int) -> None:
        """After a failed write: drop the handle (its buffer cannot be written either: closing it fails again, and
        at exit Python would print that failure), then cut the part of the row the disk took, so the file keeps
        whole rows only."""
        fh, self.fh = self.fh, None
        if fh is not None:
            try:
                fh.close()
            except OSError:
                pass
        try:
            os.truncate(self.path, whole)
        except OSError:
            pass  # the resume drops a cut row too

    def close(self) -> None:
        if self.fh is not None:
            self.fh.close()
            self.fh = None

    def finish(self, ordered: Sequence[Row]) -> None:
        self.close()
        super().finish(ordered)
        _replace(self.path, self._text(self.rows))


class JsonFile(RowSink):
    def __init__(self, path: str, columns: Sequence[str], identity: JsonObject, previous: Sequence[Row]):
        super().__init__(columns, identity)
        self.path = Path(path)
        self.rows = list(previous)
        self.written = 0.0
        self._write()

    def _write(self) -> None:
        rows = [{c: _json_value(r.get(c)) for c in self.columns} for r in self.rows]
        doc = {**self.identity, "columns": self.columns, "rows": rows}
        _replace(self.path, json.dumps(doc, indent=1, allow_nan=False) + "\n")
        self.written = time.monotonic()

    def add(self, row: Row) -> None:
        super().add(row)
        if time.monotonic() - self.written >= JSON_EVERY_S:
            self._write()

    def close(self) -> None:
        self._write()

    def finish(self, ordered: Sequence[Row]) -> None:
        super().finish(ordered)
        self._write()


class CsvStdout(RowSink):
    """CSV to stdout: the header, then the rows in point order as they arrive (no identity line: nothing to
    resume). Workers finish points out of order; a row waits for the points before it (``_index``, 0, 1, ...: a
    sweep to stdout runs every point), so a pipe reads the same rows in the same order as ``-o FILE`` holds them.
    An interruption writes the rows done, in point order."""

    def __init__(self, columns: Sequence[str], identity: JsonObject, stream: TextIO | None = None):
        super().__init__(columns, identity)
        self.stream = stream or sys.stdout
        self._next = 0
        self._held: dict[int, Row] = {}
        write_stream(self.stream, _csv_line(self.columns))

    def _write_row(self, row: Row) -> None:
        write_stream(self.stream, _csv_line([row.get(c) for c in self.columns]))

    def add(self, row: Row) -> None:
        super().add(row)
        index = row.get("_index")
        if not isinstance(index, int):
            self._write_row(row)
            return
        self._held[index] = row
        while self._next in self._held:
            self._write_row(self._held.pop(self._next))
            self._next += 1

    def _flush(self) -> None:
        for index in sorted(self._held):
            self._write_row(self._held.pop(index))

    def close(self) -> None:
        self._flush()

    def finish(self, ordered: Sequence[Row]) -> None:
        super().finish(ordered)
        self._flush()


class JsonStdout(RowSink):
    """JSON to stdout, once, at the end (or at an interruption, with the rows done)."""

    def __init__(self, columns: Sequence[str], identity: JsonObject, stream: TextIO | None = None):
        super().__init__(columns, identity)
        self.stream = stream or sys.stdout

    def _write(self) -> None:
        rows = [{c: _json_value(r.get(c)) for c in self.columns} for r in self.rows]
        write_stream(self.stream, json.dumps({**self.identity, "columns": self.columns, "rows": rows}, indent=1) + "\n")

    def close(self) -> None:
        self._write()

    def finish(self, ordered: Sequence[Row]) -> None:
        super().finish(ordered)
        self._write()


def open_sink(output: str | None, fmt: str, columns: Sequence[str], identity: JsonObject,
              previous: Sequence[Row]) -> RowSink:
    if output:
        return (JsonFile if fmt == "json" else CsvFile)(output, columns, identity, previous)
    return JsonStdout(columns, identity) if fmt == "json" else CsvStdout(columns, identity)
