"""A sweep's error estimate, shared by a family of neighbouring points (docs/numerics.md, "Honest statistics"; docs/performance.md).

A point's check pass (:mod:`gearcli.simulate.estimate`) integrates the scene a second time; paid at every point
it doubles a sweep. Every ``CHECK_EVERY``-th point of the sweep (its index a multiple of it: which points are
checked does not depend on how the sweep is split into tasks or resumed, so a resumed file equals the
uninterrupted one) runs the check pass, and its verdict is carried to the points after it in the same task
(a branch, or a batch of neighbouring values) while they stay alike, i.e. each point

- ran the same method on the same engine at the same rtol as the checked point (a checked point that ``auto``
  re-ran at a tighter rtol for its means carries nothing to points at the file's rtol), and
- needed evaluations at a pace (evaluations per simulated second) within ``PACE_RATIO`` of the checked
  point's (a run that needs many more steps resolves its vibration differently).

A resolved verdict carries silently (the family's numbers meet the targets); an unresolved one carries its
warnings into each alike row's message, named as the family's ("estimated at the checked point ..."). A point
that is not alike, or whose task holds no checked point before it, carries no verdict: its row has the
warnings of its own run only (``simulation.error_estimate`` of a one-shot ``gearcli simulate`` checks one
point alone).
"""

from __future__ import annotations

from gearcli.core.records import record
from gearcli.simulate.results import SimulationResult

CHECK_EVERY = 16  # every CHECK_EVERY-th point of a sweep runs its check pass
PACE_RATIO = 1.5  # a point whose evaluations per simulated second differ more from the checked one's: re-check


@record
class Verdict:
    """The checked point's run and what its check pass said."""

    values: str  # the checked point's values, for the carried message
    method: str
    engine: str
    rtol: float
    pace: float  # evaluations per simulated second
    warnings: tuple[str, ...]  # its statistics_unresolved warnings (empty: resolved)


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
        unresolved = tuple(d.message for d in result.diagnostics if d.code == "statistics_unresolved")
        sv = result.solver
        self.verdict = Verdict(values, sv.method, sv.engine, sv.rtol, _pace(result), unresolved)
        return ()

    def carried(self, result: SimulationResult) -> tuple[str, ...]:
        """A point without its own check pass: the family's unresolved warnings to add to its row (none when the
        verdict is resolved, or when the point is not alike)."""
        v = self.verdict
        if v is None:
            return ()
        sv = result.solver
        pace = _pace(result)
        alike = (sv.method, sv.engine, sv.rtol) == (v.method, v.engine, v.rtol) and v.pace > 0 \
            and 1.0 / PACE_RATIO <= pace / v.pace <= PACE_RATIO
        if not alike:
            return ()
        return tuple(f"{w} (estimated at the family's checked point {v.values})" for w in v.warnings)
