"""One ``gearcli life`` run: the base file as a sweep scene, and its duty points (from the file or a series).

The facade (:func:`gearcli.api.prepare_life`) loads and designs the base file; this module makes the points.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace
from typing import BinaryIO

from gearcli.config import LoadedDesign
from gearcli.config.load import STDIN, input_digest, load_variant, read_input_file, read_stdin
from gearcli.core.records import record
from gearcli.diagnostics import Diagnostic
from gearcli.errors import ConfigError
from gearcli.life.duty import (
    DEFAULT_CLASSES,
    DutyPoint,
    held_notes,
    held_points,
    points_from_config,
    points_from_series,
    read_series,
    reversal_notes,
    series_notes,
    with_drive,
    with_load_table,
)
from gearcli.life.starts import label
from gearcli.results import DesignResult
from gearcli.sweep.worker import Scene

MAX_SERIES_BYTES = 64 * 1024 * 1024
STDOUT_OR_STDIN = "-"


@record
class Session:
    scene: Scene
    loaded: LoadedDesign  # the base file
    design: DesignResult  # its design
    points: tuple[DutyPoint, ...]
    warnings: tuple[str | Diagnostic, ...] = ()  # about the duty itself: reverse rows of a series, load reversals
    held: tuple[DutyPoint, ...] = ()  # a history's torques held at standstill: the bearings' s_0 alone


def _series_text(path: str, stdin: BinaryIO | None = None) -> str:
    """The history's text: a file read like the design file (a FIFO without a writer refused, never a hang),
    or ``-``: standard input."""
    if path == STDOUT_OR_STDIN:
        raw = read_stdin(MAX_SERIES_BYTES, stdin)
        path = STDIN
    else:
        raw = read_input_file(path, MAX_SERIES_BYTES, what="a CSV file")
    if len(raw) > MAX_SERIES_BYTES:
        raise ConfigError(f"larger than {MAX_SERIES_BYTES // (1024 * 1024)} MiB", source=path)
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError:
        raise ConfigError("not UTF-8 text", source=path) from None


def _check_names(points: Sequence[DutyPoint], source: str) -> None:
    """Every [[duty]] name names one point in the spectra (bins' ``point``), and no point's name is another's start
    classes' (``"<name> (start)"``): a repeated name merged two points' start damage in ``points[i].start``."""
    seen: dict[str, str] = {}
    for p in points:
        for name in (p.name, label(p.name)) if p.starts else (p.name,):
            if name in seen:
                raise ConfigError(f"{name!r} is already {seen[name]}: each duty point needs a name of its own (the "
                                  "spectra's classes and the start records are keyed by it)",
                                  source=source, key=f"{p.key}.name")
        seen[p.name] = f"the name of {p.key}"
        if p.starts:
            seen[label(p.name)] = f"the name of {p.key}'s start classes"


def _without_empty_points(points: Sequence[DutyPoint], source: str) -> tuple[list[DutyPoint], list[str]]:
    """The points that run: a ``hours = 0`` point is an empty bin of a load spectrum (ISO 6336-6's own Table 4 has
    them), no load cycle and no revolution, so it is left out with a note; its starts would need hours to run in
    (exit 2), and a duty whose every point is empty has nothing to rate (exit 2)."""
    empty = [p for p in points if p.hours == 0.0]
    for p in empty:
        if p.starts:
            raise ConfigError(f"0 hours with starts = {p.starts}: the starts are counted over the point's hours (each "
                              "from rest to its settled running); give the hours it runs", source=source,
                              key=f"{p.key}.hours")
    if empty and len(empty) == len(points):
        raise ConfigError("every [[duty]] point has hours = 0: no load cycle, nothing to rate; give the points "
                          "their hours", source=source, key="duty")
    if not empty:
        return list(points), []
    names = ", ".join(f"{p.name} ({p.key})" for p in empty)
    return [p for p in points if p.hours > 0.0], [
        f"{len(empty)} duty point(s) with hours = 0 left out (no load cycles, no revolutions): {names}"]


def prepare(raw: bytes, loaded: LoadedDesign, design: DesignResult, sets: Sequence[str], *,
            series: str | None = None, classes: int | None = None) -> Session:
    """The duty points of the base file ``raw`` (``loaded`` and ``design`` with the ``sets`` applied): its
    ``[[duty]]`` tables, or the history ``series`` classed into ``classes`` torque classes (exit 2 on bad
    input, before any point runs)."""
    classes = DEFAULT_CLASSES if classes is None else classes
    if series is not None:
        source = STDIN if series == STDOUT_OR_STDIN else series
        text = _series_text(series)
        cols = read_series(text, source)
        # the history is an input of the run: input_sha256 covers it (a run on another history is another run)
        loaded = replace(loaded, sha256=input_digest(raw, sets, text.encode("utf-8")))
        points = points_from_series(*cols, source=source, classes=classes)
        notes: list[str | Diagnostic] = [*series_notes(*cols, source=source)]
        held = held_points(*cols, source=source)
        notes += held_notes(held)
        starts = sum(d.starts for d in loaded.design.duty)
        if starts:  # the tables the history replaces carried start-ups: say that they are not counted
            notes.append(f"the history {source} replaces the file's [[duty]] tables, and with them their {starts} "
                         "starts ([[duty]] starts): a history's rows count no start-ups from rest, so no start is "
                         "counted; rate the starts with the [[duty]] tables")
    else:
        points, held = points_from_config(loaded.design), []
        _check_names(points, loaded.source)
        points, empty = _without_empty_points(points, loaded.source)
        notes = [*empty]
    notes += reversal_notes(points)  # a duty point's warnings: their data name the point

    def variant(point_sets: Sequence[str]):  # the file as a point with its own set runs (its efficiencies)
        return load_variant(raw, loaded.source, (*sets, *point_sets))

    points = with_load_table(loaded.design, with_drive(loaded.design, points, variant))
    if loaded.design.rating is None:
        only = " (this file's [rating] sets only the bearings' min_static_safety_bearing)" \
            if loaded.design.min_static_safety_bearing is not None else ""
        raise ConfigError("gearcli life rates every member by ISO 6336-2/-3: add a [rating] table (with the "
                          "materials' treatment and fatigue limits, accuracy grades, roughness and [lubricant])"
                          + only, source=loaded.source, key="rating")
    return Session(Scene(raw, loaded.source, tuple(sets), len(design.stages)), loaded, design, tuple(points),
                   tuple(notes), tuple(with_drive(loaded.design, held)))
