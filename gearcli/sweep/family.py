"""A sweep's error estimate, shared by a family of neighbouring points (docs/numerics.md, "Honest statistics"; docs/performance.md).

A point's check pass (:mod:`gearcli.simulate.estimate`) integrates the scene a second time; paid at every point
it doubles a sweep. Every ``CHECK_EVERY``-th point of the sweep (its index a multiple of it: which points are
checked does not depend on how the sweep is split into tasks or resumed, so a resumed file equals the
uninterrupted one) runs the check pass, and its verdict is carried to the points of its family while they stay
alike. In a continuation branch (one task, run in order) the family is the branch's points after the checked one;
among independent points (a grid, random samples) it is the points of the same ``index // CHECK_EVERY``, whichever
task ran them: their rows are completed in the parent process by :class:`Carrier` (a row waits for its family's
checked row), so the rows, warnings included, do not depend on ``--jobs``, ``--scheduler`` or a resume (a resume
whose family's checked point is already written with an unresolved verdict runs it again, unwritten, for the
verdict; a row still waiting for its checked row when the sweep is stopped is not written: it runs again). Alike
means each point

- ran the same method on the same engine at the same rtol as the checked point (a checked point that ``auto``
  re-ran at a tighter rtol for its means carries nothing to points at the file's rtol), and
- needed evaluations at a pace (evaluations per simulated second) within ``PACE_RATIO`` of the checked
  point's (a run that needs many more steps resolves its vibration differently).

A resolved verdict carries silently (the family's numbers meet the targets); an unresolved one carries its
warnings into each alike row's message, named as the family's ("estimated at the checked point ..."). A point
that is not alike, or whose family's checked point failed (or, in a branch, that has no checked point before it),
carries no verdict: its row has the
warnings of its own run only (``simulation.error_estimate`` of a one-shot ``gearcli simulate`` checks one
point alone).
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from typing import TYPE_CHECKING

from gearcli.core.records import record
from gearcli.simulate.results import SimulationResult
from gearcli.sweep.columns import OK, Row, one_line

if TYPE_CHECKING:
    from gearcli.sweep.worker import Task

CHECK_EVERY = 16  # every CHECK_EVERY-th point of a sweep runs its check pass
PACE_RATIO = 1.5  # a point whose evaluations per simulated second differ more from the checked one's: re-check


def family_of(index: int) -> int:
    """The family of an independent point (its index's block of ``CHECK_EVERY``; its checked point the first)."""
    return index // CHECK_EVERY


@record
class Verdict:
    """The checked point's run and what its check pass said."""

    values: str  # the checked point's values, for the carried message
    method: str
    engine: str
    rtol: float
    pace: float  # evaluations per simulated second
    warnings: tuple[str, ...]  # its statistics_unresolved warnings (empty: resolved)


def solvers_unresolved(result: SimulationResult) -> tuple[str, ...]:
    """The messages of the solver's ``statistics_unresolved`` warnings: a neighbour's verdict (a start-up transient
    left in the window, ``transient_N``: gearcli.simulate.leftover, is the point's own and no neighbour's)."""
    return tuple(d.message for d in result.diagnostics
                 if d.code == "statistics_unresolved" and "transient_N" not in getattr(d, "data", {}))


def _pace(result: SimulationResult) -> float:
    span = result.final_time_s or 0.0
    return result.solver.nfev / span if span > 0 else float(result.solver.nfev)


class Family:
    """The verdict of the task's last checked point."""

    def __init__(self) -> None:
        self.verdict: Verdict | None = None

    @staticmethod
    def needs_check(index: int) -> bool:
        return index % CHECK_EVERY == 0

    def checked(self, values: str, result: SimulationResult) -> tuple[str, ...]:
        """A point that ran its check pass: its verdict is the family's from here (its own warnings are in its
        result: nothing to add)."""
        unresolved = solvers_unresolved(result)
        sv = result.solver
        self.verdict = Verdict(values, sv.method, sv.engine, sv.rtol, _pace(result), unresolved)
        return ()

    def carried(self, result: SimulationResult) -> tuple[str, ...]:
        """A point without its own check pass: the family's unresolved warnings to add to its row (none when the
        verdict is resolved, or when the point is not alike)."""
        sv = result.solver
        return _carried(self.verdict, sv.method, sv.engine, sv.rtol, _pace(result))


def _carried(v: Verdict | None, method: str, engine: str, rtol: float, pace: float) -> tuple[str, ...]:
    if v is None:
        return ()
    alike = (method, engine, rtol) == (v.method, v.engine, v.rtol) and v.pace > 0 \
        and 1.0 / PACE_RATIO <= pace / v.pace <= PACE_RATIO
    if not alike:
        return ()
    return tuple(f"{w} (estimated at the family's checked point {v.values})" for w in v.warnings)


UNRESOLVED_MARK = "at the run's rtol"  # in statistics_unresolved's message (gearcli.simulate.estimate), peak_unresolved's too


def unresolved_row(row: Row) -> bool:
    """Whether a written row may be a checked point's unresolved verdict (its own statistics_unresolved warning; a
    peak_unresolved one reads alike, and only costs a rerun): a resume runs such a point again for its family."""
    return row.get("status") == OK and UNRESOLVED_MARK in str(row.get("message") or "")


SEPARATOR = "\x1e"  # between the warnings of a checked row's hidden verdict (a warning may hold a newline)
#: the hidden fields of an independent point's row that :class:`Carrier` reads (and removes)
HIDDEN = ("_method", "_engine", "_rtol", "_pace", "_checked", "_checked_at", "_unresolved", "_verdict_only")


def marks(result: SimulationResult | None, checked: str | None) -> Row:
    """The hidden fields of an independent point's row: how its run went (``result``; None: the point failed) and,
    for a checked point (``checked``: its values), its verdict."""
    out: Row = {}
    if result is not None:
        sv = result.solver
        out.update(_method=sv.method, _engine=sv.engine, _rtol=sv.rtol, _pace=_pace(result))
    if checked is not None:
        out["_checked"] = True
        if result is not None:
            out["_checked_at"] = checked
            out["_unresolved"] = SEPARATOR.join(solvers_unresolved(result))
    return out


class Carrier:
    """The parent's side of the independent points' families: each row waits for its family's checked row, then
    takes its verdict; a checked point that failed carries nothing. Rows come out without the hidden fields."""

    def __init__(self, tasks: Iterable[Task] = ()) -> None:
        """``tasks``: the sweep's; a family whose checked point none of them runs (written before a resume with a
        resolved verdict, which carries nothing) has no verdict to wait for: its rows are written as they come."""
        running = {p.index for t in tasks if not t.continuation for p in t.points}
        self.verdicts: dict[int, Verdict | None] = {family_of(i): None for i in running
                                                    if family_of(i) * CHECK_EVERY not in running}
        self.waiting: dict[int, list[Row]] = {}

    def add(self, row: Row) -> Iterator[Row]:
        """The rows ready to write after ``row`` arrives (none while its family's checked row has not)."""
        if not any(k in row for k in HIDDEN):  # a branch's row (carried in its task) or a lost task's
            yield row
            return
        family = family_of(int(row["_index"]))  # type: ignore[arg-type]  # set by the worker
        if row.get("_checked"):
            self.verdicts[family] = _verdict(row)
            if not row.get("_verdict_only"):
                yield self._done(row, family)
            for waiting in self.waiting.pop(family, []):
                yield self._done(waiting, family)
        elif row.get("status") == OK and family not in self.verdicts:
            self.waiting.setdefault(family, []).append(row)
        else:
            yield self._done(row, family)

    def rest(self) -> Iterator[Row]:
        """The rows whose checked row never came (its task lost): without a verdict."""
        for family in sorted(self.waiting):
            for row in self.waiting.pop(family):
                yield self._done(row, None)

    def _done(self, row: Row, family: int | None) -> Row:
        v = self.verdicts.get(family) if family is not None else None
        shared = () if row.get("_checked") or "_pace" not in row else _carried(
            v, str(row["_method"]), str(row["_engine"]), float(row["_rtol"]),  # type: ignore[arg-type]
            float(row["_pace"]))  # type: ignore[arg-type]
        out = {k: v for k, v in row.items() if k not in HIDDEN}
        if shared:
            out["message"] = one_line("\n".join((str(out.get("message") or ""), *shared)))
        return out


def _verdict(row: Row) -> Verdict | None:
    if "_checked_at" not in row:  # the checked point failed
        return None
    text = str(row.get("_unresolved") or "")
    return Verdict(str(row["_checked_at"]), str(row["_method"]), str(row["_engine"]), float(row["_rtol"]),  # type: ignore[arg-type]
                   float(row["_pace"]), tuple(text.split(SEPARATOR)) if text else ())  # type: ignore[arg-type]
