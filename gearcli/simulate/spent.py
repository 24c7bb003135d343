"""What a result cost: every run behind it, not only the one whose numbers it reports (docs/output.md, ``solver``).

A result's ``solver.nfev``, ``steps`` and ``wall_s`` are the run that produced its numbers. Getting there may have
taken more: the settle test's longer runs with their windows moved later and the periodic search
(:mod:`gearcli.simulate.settle`), ``auto``'s repeat at a tighter rtol (:func:`gearcli.simulate.run.simulate_model`),
each of the replaced runs with its own check pass. ``solver.total_nfev`` and ``solver.total_wall_s`` add them all up
but the kept run's check pass, which ``solver.check_pass`` reports; ``solver.runs`` counts the runs. A course change
is within one run (its ``nfev`` already the pieces' sum). A run that raised (a longer run beyond its budget, a
periodic search that cannot run the scene) left no result and is not counted.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import replace

from gearcli.simulate.results import SimulationResult


def check_cost(result: SimulationResult) -> tuple[int, float]:
    """(evaluations, integration seconds) of the result's own check pass (0 without one)."""
    cp = result.solver.check_pass or {}
    nfev, wall = cp.get("nfev", 0), cp.get("wall_s", 0.0)
    return (int(nfev) if isinstance(nfev, (int, float)) else 0), (float(wall) if isinstance(wall, (int, float)) else 0.0)


def whole(result: SimulationResult) -> tuple[int, float, int]:
    """(evaluations, integration seconds, runs) of everything the result took, its check pass included."""
    sv, (nfev, wall) = result.solver, check_cost(result)
    return sv.total_nfev + nfev, sv.total_wall_s + wall, sv.runs


def added(result: SimulationResult, nfev: int, wall_s: float, runs: int = 1) -> SimulationResult:
    """``result`` with ``runs`` replaced runs that cost ``nfev`` evaluations and ``wall_s`` seconds added to its
    totals."""
    sv = result.solver
    return replace(result, solver=replace(sv, total_nfev=sv.total_nfev + int(nfev),
                                          total_wall_s=sv.total_wall_s + float(wall_s), runs=sv.runs + runs))


def totalled(kept: SimulationResult, made: Iterable[SimulationResult]) -> SimulationResult:
    """``kept`` (one of ``made``, or its finished or marked copy: the same solver figures) with the totals of all
    the runs ``made`` on the way to it, its own check pass aside."""
    made = list(made)
    if len(made) < 2:
        return kept
    costs = [whole(r) for r in made]
    own = check_cost(kept)
    return replace(kept, solver=replace(kept.solver, total_nfev=sum(c[0] for c in costs) - own[0],
                                        total_wall_s=sum(c[1] for c in costs) - own[1],
                                        runs=sum(c[2] for c in costs)))
