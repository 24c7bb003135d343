"""Duty cycles: the ``[[duty]]`` operating points of a design file, or a measured torque–speed history
(``--series FILE.csv`` with ``time_s,torque_Nm,speed_rpm``) classed into points (docs/life.md, "Duty").

A point becomes a design file through ``--set`` overrides of the base file (as a sweep point does): its
input speed, its output torque, K_A = 1 (the spectrum is the load, ISO 6336-6) and the point's own ``set``.
"""

from __future__ import annotations

import csv
import io
import math
from collections.abc import Callable, Sequence
from dataclasses import replace
from typing import Any

from gearcli.config.duty import MAX_DUTY_HOURS
from gearcli.config.machine import table_value
from gearcli.config.schema_rules import MAX_SPEED_RPM, MAX_TORQUE_NMM
from gearcli.core.records import record
from gearcli.design.kinematics import stage_torques_Nmm
from gearcli.diagnostics import DUTY, Diagnostic, warning
from gearcli.errors import ConfigError
from gearcli.stages import kinds
from gearcli.stages.design import design_kind

MAX_SERIES_ROWS = 2_000_000
#: the shortest time step of a history (a 1 GHz logger's): 5e-324 s steps made a class's hours 0 (an internal
#: error dividing by them) or subnormal
MIN_SERIES_STEP_S = 1e-9
#: a history's torque and speed cells within what the design file's load.torque_Nm and input.speed_rpm allow (in
#: magnitude: a history may reverse), so the classing's sums stay finite (1e308 in a cell made a class's width or
#: mean speed overflow: an internal error, or "got inf" for a value the file never held)
SERIES_LIMITS = {"torque_Nm": (MAX_TORQUE_NMM / 1e3, "N m", "load.torque_Nm"),
                 "speed_rpm": (MAX_SPEED_RPM, "rpm", "input.speed_rpm")}
DEFAULT_CLASSES = 10


@record
class DutyPoint:
    """One operating point: hours at an output torque and input speed, and the other keys it sets."""

    name: str
    hours: float
    torque_Nm: float  # output torque
    speed_rpm: float  # input speed
    sets: tuple[str, ...] = ()  # further --set texts (the [[duty]] table's ``set``)
    key: str = ""  # where it came from, for messages: "duty[1]" or the series file
    starts: int = 0  # start-ups from rest over the point's hours (the [[duty]] table's ``starts``)

    def overrides(self) -> tuple[str, ...]:
        """The ``--set`` texts that turn the base design file into this point."""
        return (f"input.speed_rpm={self.speed_rpm!r}", f"load.torque_Nm={self.torque_Nm!r}",
                "load.application_factor=1.0", *self.sets)


def with_drive(cfg, points: Sequence[DutyPoint],
               variant: Callable[[Sequence[str]], Any] | None = None) -> list[DutyPoint]:
    """A torque-driven input (``drive = "torque"``) gets each point's input torque too: the output torque
    carried back through the stages as the design carries it (kinematics' stage torques with the stage
    efficiencies, and a planetary stage's own efficiency where the load reverses), so that the point runs at its
    speed instead of drifting from the file's input torque. A speed drive needs nothing. ``variant``: the design
    file with a point's own ``set`` applied (a point may run under other stage efficiencies: an oil's, a worn
    stage's); without it the base file's.

    (Until 2026-11-30 a reversed point on a lossy planetary took the forward η, 0.28 % off the balance on a ring-held
    stage of η 0.9, and a point's ``set`` of a stage's efficiency was not seen: 0.93 for 0.98 left 5 % of the input
    torque unbalanced, the train stopped and the point failed with "no whole mesh cycle";
    tests/life/test_tr24a_torque_drive_reversed.py.)"""
    if cfg.input.drive != "torque":
        return list(points)

    out = []
    for p in points:
        own = variant(p.sets) if variant is not None and p.sets else cfg
        ratios = tuple(stage_ratio(s) for s in own.stage)
        efficiencies = tuple(float(s.efficiency) for s in own.stage)
        reverse = tuple(design_kind(s).reverse_efficiency(s, k) for k, s in enumerate(own.stage))
        torque = stage_torques_Nmm(p.torque_Nm * 1000.0, ratios, efficiencies, reverse)[0][0]
        out.append(replace(p, sets=(f"input.torque_Nm={torque / 1000.0!r}", *p.sets)))
    return out


def with_load_table(cfg, points: Sequence[DutyPoint]) -> list[DutyPoint]:
    """A table load (``[load] torque_speed``: the driven machine's torque against its speed) keeps its shape at
    every point, scaled to the point's torque at the point's nominal output speed, as a speed law (``speed_exponent``)
    keeps its exponent with the point's torque at that speed: the point's ``load.torque_Nm`` alone replaces the
    table (one torque key) by a constant torque, which the start from rest and a motor's operating point would meet
    instead of the machine's characteristic. A point of zero torque (idling), or where the table gives 0, keeps it."""
    table = cfg.load.torque_speed
    if table is None:
        return list(points)
    ratio = math.prod(stage_ratio(s) for s in cfg.stage)
    out = []
    for p in points:
        ref = table_value(table, abs(p.speed_rpm) / ratio)  # as the design and the model read it at its speed
        if p.torque_Nm == 0.0 or ref == 0.0:
            out.append(p)
            continue
        scaled = [[float(n), float(t) * (p.torque_Nm / ref)] for n, t in table]
        out.append(replace(p, sets=(f"load.torque_speed={toml_value(scaled)}", *p.sets)))
    return out


def toml_value(value: Any) -> str:
    """A Python value of a TOML document written back as an inline TOML value (for ``--set``)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return repr(value)
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f'"{k}" = {toml_value(v)}' for k, v in value.items()) + "}"
    raise ConfigError(f"cannot use a {type(value).__name__} value in a duty point's set table")


def stage_ratio(stage) -> float:
    """|input speed / output speed| of a stage (its table's: z_gear / z_pinion, a planetary stage's Willis ratio)."""
    return float(kinds.table_figure(stage, "speed_ratio"))


def points_from_config(cfg) -> list[DutyPoint]:
    """The ``[[duty]]`` tables as points (power_kW at the output speed of the point's input speed)."""
    ratio = math.prod(stage_ratio(s) for s in cfg.stage)
    return [DutyPoint(d.name, d.hours, d.output_torque_Nm(ratio), d.speed_rpm,
                      tuple(f"{k}={toml_value(v)}" for k, v in d.set.items()), f"duty[{i}]", d.starts)
            for i, d in enumerate(cfg.duty)]


def read_series(text: str, source: str) -> tuple[list[float], list[float], list[float]]:
    """time_s, torque_Nm, speed_rpm columns of a CSV text (ConfigError naming the file, the row and the column
    on bad data; rows are numbered as a spreadsheet numbers them, the header being row 1)."""
    reader = csv.reader(io.StringIO(text))
    try:
        return _read_series(reader, source)
    except csv.Error as exc:  # a cell over the csv module's 128 KiB field limit, ...: no history of numbers
        raise ConfigError(f"row {reader.line_num}: not CSV ({exc})", source=source) from None


def _read_series(reader, source: str) -> tuple[list[float], list[float], list[float]]:
    header = [h.strip() for h in next(reader, [])]
    need = ("time_s", "torque_Nm", "speed_rpm")
    missing = [c for c in need if c not in header]
    if missing:
        raise ConfigError(f"needs the columns {', '.join(need)} (missing {', '.join(missing)}; the header row "
                          f"has {', '.join(repr(h) for h in header) or 'nothing'})", source=source)
    twice = [c for c in need if header.count(c) > 1]
    if twice:
        raise ConfigError(f"the header row names the column {twice[0]} {header.count(twice[0])} times: "
                          "which one is the history is ambiguous", source=source)
    idx = [header.index(c) for c in need]
    cols: tuple[list[float], list[float], list[float]] = ([], [], [])
    rows: list[int] = []  # the file's row number of each data row (for messages)
    for row_no, row in enumerate(reader, start=2):
        if not row or all(not c.strip() for c in row):
            continue
        if row_no > MAX_SERIES_ROWS:
            raise ConfigError(f"more than {MAX_SERIES_ROWS} rows", source=source)
        if any(c.strip() for c in row[len(header):]):
            raise ConfigError(f"row {row_no}: {len(row)} cells, more than the header's {len(header)} (a decimal comma, "
                              "or a cell without a column: which cell is which column is ambiguous)", source=source)
        for col, name, i in zip(cols, need, idx, strict=True):
            col.append(_cell(row, i, name, row_no, source))
        rows.append(row_no)
    t = cols[0]
    if len(t) < 2:
        raise ConfigError("needs at least two rows (each level holds from its time to the next row's)", source=source)
    for k in range(1, len(t)):
        if t[k] <= t[k - 1]:
            raise ConfigError(f"row {rows[k]}, column time_s: {t[k]!r} s does not follow row {rows[k - 1]}'s "
                              f"{t[k - 1]!r} s (time_s must increase from row to row: sort the history and "
                              "drop repeated time stamps)", source=source)
        if not t[k] - t[k - 1] >= MIN_SERIES_STEP_S:
            raise ConfigError(f"row {rows[k]}, column time_s: {t[k]!r} s follows row {rows[k - 1]}'s {t[k - 1]!r} s "
                              f"by {t[k] - t[k - 1]:.3g} s, less than the {MIN_SERIES_STEP_S:g} s a history's step "
                              "may be (time_s is in seconds)", source=source)
    span = t[-1] - t[0]  # inf when it overflows (time stamps of either sign near 1e308)
    if not span <= MAX_DUTY_HOURS * 3600.0:
        raise ConfigError(f"row {rows[-1]}, column time_s: the history spans {span:.4g} s from row {rows[0]} "
                          f"({span / 3600.0:.4g} h), more than a duty point may hold ({MAX_DUTY_HOURS:.4g} h): "
                          "time_s is in seconds", source=source)
    return cols


def _cell(row: Sequence[str], i: int, name: str, row_no: int, source: str) -> float:
    """The finite number in column ``name`` (index ``i``) of the file's row ``row_no``."""
    if i >= len(row):
        raise ConfigError(f"row {row_no}, column {name}: missing (the row has {len(row)} of the header's cells)",
                          source=source)
    text = row[i].strip()
    if not text:
        raise ConfigError(f"row {row_no}, column {name}: empty cell", source=source)
    try:
        value = float(text)
    except ValueError:
        raise ConfigError(f"row {row_no}, column {name}: expected a number, got {text!r}", source=source) from None
    if not math.isfinite(value):
        raise ConfigError(f"row {row_no}, column {name}: not a finite number ({text!r})", source=source)
    if name in SERIES_LIMITS and abs(value) > SERIES_LIMITS[name][0]:
        limit, unit, key = SERIES_LIMITS[name]
        raise ConfigError(f"row {row_no}, column {name}: {value:g} {unit} is beyond the ±{limit:g} {unit} a design "
                          f"file's {key} allows (check the column's unit)", source=source)
    return value


def points_from_series(time_s: Sequence[float], torque_Nm: Sequence[float], speed_rpm: Sequence[float],
                       source: str, classes: int = DEFAULT_CLASSES) -> list[DutyPoint]:
    """Time at level -> points: each row's torque and speed hold until the next row; the levels are put into
    ``classes`` torque classes of equal width. A class's point carries the largest torque of the class (the
    spectrum is not made milder by classing), its total time, and the speed that keeps its revolutions
    (time-weighted mean), so each revolution at a level is a load cycle for the teeth. A class that holds
    torques of both signs is two points, ``class c (negative torque)`` and ``class c``: the sign chooses the
    flank and the bearings' reaction directions, which one signed torque cannot stand for."""
    dt = [b - a for a, b in zip(time_s, time_s[1:], strict=False)]
    # a reverse row's revolutions are load cycles too (|speed|); the torque's sign says which flank they load
    levels = [(torque_Nm[i], abs(speed_rpm[i]), dt[i]) for i in range(len(dt)) if speed_rpm[i] != 0.0]
    if not levels:
        raise ConfigError("no row with a nonzero speed: nothing turns, nothing wears", source=source)
    lo, hi = min(q for q, _, _ in levels), max(q for q, _, _ in levels)
    width = (hi - lo) / classes if hi > lo else 1.0
    groups: dict[tuple[int, bool], list[tuple[float, float, float]]] = {}
    for q, n, d in levels:  # by class, then by the torque's sign (negative first)
        groups.setdefault((min(classes - 1, int((q - lo) / width)), q >= 0.0), []).append((q, n, d))
    points = []
    for c, positive in sorted(groups):
        g = groups[(c, positive)]
        seconds = sum(d for _, _, d in g)
        speed = sum(n * d for _, n, d in g) / seconds
        torque = max(g, key=lambda x: abs(x[0]))[0]
        split = not positive and (c, True) in groups
        name = f"class {c + 1} (negative torque)" if split else f"class {c + 1}"
        points.append(DutyPoint(name, seconds / 3600.0, torque, speed, (), source))
    return points


HELD_LABEL = "held at standstill"


def held_points(time_s: Sequence[float], torque_Nm: Sequence[float], speed_rpm: Sequence[float],
                source: str) -> list[DutyPoint]:
    """A history's rows at zero speed that carry a torque (a brake or a stalled drive holding the load): no
    revolutions, so no load cycles and no damage, but a load the bearings' ISO 76 static safety must see. One
    point per sign of torque, at its largest magnitude, holding those rows' hours; its speed, which a held load
    does not have, is the turning rows' time-weighted mean (the design's statics do not depend on it)."""
    rows = range(len(time_s) - 1)
    turning = [(abs(speed_rpm[i]), time_s[i + 1] - time_s[i]) for i in rows if speed_rpm[i] != 0.0]
    seconds = sum(d for _, d in turning)
    speed = sum(n * d for n, d in turning) / seconds if seconds > 0.0 else 0.0
    out = []
    for negative in (True, False):
        held = [i for i in rows if speed_rpm[i] == 0.0 and torque_Nm[i] != 0.0 and (torque_Nm[i] < 0.0) == negative]
        if held and speed > 0.0:
            torque = max((torque_Nm[i] for i in held), key=abs)
            hours = sum(time_s[i + 1] - time_s[i] for i in held) / 3600.0
            name = f"{HELD_LABEL} (negative torque)" if negative else HELD_LABEL
            out.append(DutyPoint(name, hours, torque, speed, (), source))
    return out


def held_notes(points: Sequence[DutyPoint]) -> list[str]:
    """What a history's held rows became (docs/life.md, "A measured history")."""
    return [f"{p.key}: rows at zero speed hold a torque ({p.name}: {p.hours:.4g} h, the largest {p.torque_Nm:.6g} N·m): no "
            "revolutions, so no load cycles and no damage; the held torque loads the bearings' static safety s_0 "
            "(ISO 76), not the teeth's static strength, which counts load cycles only" for p in points]


def reversal_notes(points: Sequence[DutyPoint]) -> list[Diagnostic]:
    """The warning docs/life.md promises for a load reversal: a point with a negative torque loads the back
    flanks, and is counted by magnitude on the S-N curves of the drive flanks. A duty point's warning: its data
    carries the ``point`` (docs/output.md, "Warnings"), its ``key`` and ``torque_Nm``."""
    return [warning(DUTY, f"duty point {p.name} ({p.key}): negative torque {p.torque_Nm:.6g} N·m, a load reversal: the "
                    "back flanks carry it; it is counted by magnitude on the drive flanks' S-N curves (mean stress and "
                    "the back flanks' own damage are not modelled, docs/life.md \"Limits\")",
                    point=p.name, key=p.key, torque_Nm=p.torque_Nm)
            for p in points if p.torque_Nm < 0.0]


def series_notes(time_s: Sequence[float], torque_Nm: Sequence[float], speed_rpm: Sequence[float],
                 source: str) -> list[str]:
    """What a history's rows with a negative speed became: counted by |speed|, each on the flank its torque's
    sign loads (the sense of rotation does not choose the flank: the torque does)."""
    rows = [i for i in range(len(time_s) - 1) if speed_rpm[i] < 0.0]
    if not rows:
        return []
    hours = sum(time_s[i + 1] - time_s[i] for i in rows) / 3600.0
    back = sum(torque_Nm[i] < 0.0 for i in rows)
    return [f"{source}: {len(rows)} row(s) turn in reverse (negative speed_rpm, {hours:.4g} h, the first in data row "
            f"{rows[0] + 1}): their revolutions are counted by |speed|; {len(rows) - back} of them with a positive "
            f"torque load the drive flanks, {back} with a negative torque the back flanks (counted by magnitude)"]
