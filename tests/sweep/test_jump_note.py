"""A continued point is marked as a jump only where the branch really ends, not on a steep but smooth flank.

The row's mark compares neighbours: a 30 % change of the DTE rms between two continued points of a coarse speed
grid sends the refinement (``jump_note``) following the branch towards the point. A linear resonance swept in
20 rpm steps changes that much on its flanks without any jump; the branch must then be followed to the point
(no mark). A discontinuous response (an amplitude that drops at 490 rpm) must still be marked, and the end located
to 1/32 of the step. The toy results stand for SimulationResults: only what ``on_branch`` reads.
"""

from __future__ import annotations

import re
from types import SimpleNamespace

import pytest

from gearcli.sweep.continuation import jump_note, on_branch

N_RES, ZETA = 467.0, 0.02  # the two-stage scene's coupling mode met by the stage-1 mesh order (163.4 Hz x 60 / 21)


def _result(rms: float, mode: str = "periodic", method: str | None = "shooting", settled: bool | None = None,
            note: str = "", attempts: int = 1, converged: bool | None = True):
    stage = SimpleNamespace(dte_um=SimpleNamespace(rms=rms, mean=6.0), tangential_N=SimpleNamespace(std=rms, mean=2e3))
    steady = SimpleNamespace(mode=mode, method=method, attempts=attempts, settled=settled, multipliers=None, note=note,
                             converged=converged)
    solver = SimpleNamespace(total_nfev=1000, total_wall_s=0.0, runs=1, check_pass=None)
    return SimpleNamespace(steady=steady, stages=(stage,), solver=solver)


def linear_rms(rpm: float) -> float:
    """Base-excited linear oscillator: |H| = 1 / sqrt((1 - r^2)^2 + (2 zeta r)^2), r = n / n_res."""
    r = rpm / N_RES
    return 1.0 / ((1 - r * r) ** 2 + (2 * ZETA * r) ** 2) ** 0.5


def test_a_steep_linear_flank_is_followed_to_the_point_without_a_jump_mark():
    prev, row = _result(linear_rms(480)), _result(linear_rms(500))
    # by hand: |H|(480) = 14.3, |H|(500) = 6.56, a 54 % change: the neighbours alone look like a jump
    assert not on_branch(prev, row)
    calls = []

    def refine(value, last):
        calls.append(value)
        return _result(linear_rms(value))

    assert jump_note("input.speed_rpm", 480.0, 500.0, prev, row, refine) == ""
    assert calls[-1] == 500.0 and len(calls) <= 20


def test_a_settled_window_continued_from_the_orbit_counts_as_on_the_branch():
    # a refinement point close to the previous one settles in its first window (no shooting needed)
    assert on_branch(_result(1.0), _result(1.05, mode="window", method=None, settled=True))
    assert not on_branch(_result(1.0), _result(1.05, mode="window", method=None, settled=False))


def _ends(note: str) -> tuple[float, float]:
    m = re.match(r"jump: the branch of the previous point \(input.speed_rpm = 480\) ends between (\S+) and (\S+?)(;|$)", note)
    assert m, note
    return float(m[1]), float(m[2])


def test_a_real_jump_is_marked_and_located_to_a_1024th_of_the_step():
    def rms(rpm: float) -> float:
        return 10.0 if rpm < 490.0 else 2.0

    calls = []

    def refine(value, last):
        calls.append(value)
        return _result(rms(value))

    note = jump_note("input.speed_rpm", 480.0, 500.0, _result(rms(480)), _result(rms(500)), refine)
    lo, hi = _ends(note)  # the branch reaches lo (< 490) and a step of at most 20 / 2^10 rpm from it leaves it
    assert lo < 490.0 <= hi and hi - lo <= 20 / 1024 * (1 + 1e-9)
    assert len(calls) <= 60


def test_a_sharp_resonance_over_a_wide_step_is_followed_not_marked():
    # zeta = 0.01 crossed between 400 and 600 rpm: |H| rises from 3.7 to 50 and falls to 1.5, its half-power
    # band 2 zeta = 2 % of the speed (9 rpm) inside a 200 rpm step
    def rms(rpm: float) -> float:
        r = rpm / N_RES
        return 1.0 / ((1 - r * r) ** 2 + (2 * 0.01 * r) ** 2) ** 0.5

    prev, row = _result(rms(400.0)), _result(rms(600.0))
    note = jump_note("input.speed_rpm", 400.0, 600.0, prev, row, lambda v, last: _result(rms(v)))
    assert note == ""


def test_a_failed_refinement_point_is_off_the_branch():
    note = jump_note("input.speed_rpm", 480.0, 500.0, _result(10.0), _result(2.0), lambda v, last: None)
    assert _ends(note) == pytest.approx((480.0, 480.0 + 20 / 1024), abs=1e-5)  # printed to 8 digits


def test_a_refinement_point_that_raises_leaves_the_row_ok(monkeypatch):
    """The row's own point ran; a refinement point between it and its neighbour that fails numerically (a
    ValueError, an ArithmeticError) only ends the branch there: the row stays ``ok`` with its jump mark."""
    from gearcli.sweep import worker
    from gearcli.sweep.spec import Point

    def evaluate(evaluator, scene, point, prev, check=False):
        if point.index < 0:  # a refinement point
            raise ValueError("a numerical failure")
        return SimpleNamespace(case=None, result=_result(10.0 if point.index == 0 else 2.0), carried=object())

    monkeypatch.setattr(worker, "_evaluate", evaluate)
    points = tuple(Point(i, (("input.speed_rpm", v),), "up") for i, v in enumerate((480.0, 500.0)))
    task = worker.Task(worker.Scene(b"", "scene.toml"), points, True, evaluate)
    note, refined = worker._jump(task, worker._Before(points[0], _result(10.0), object()), points[1], _result(2.0))
    assert refined == 0  # no refinement point ran to its end
    assert _ends(note) == pytest.approx((480.0, 480.0 + 20 / 1024), abs=1e-5)


def test_a_brute_force_result_is_judged_by_its_amplitude():
    # the brute-force search integrates the motion on from the previous point's state (a torque drive, or excitations
    # without a common period): on the branch unless the response changed by 30 % (module text)
    assert on_branch(_result(1.0), _result(1.05, method="brute force"))
    assert not on_branch(_result(1.0), _result(1.6, method="brute force"))


def test_a_brute_force_search_the_shooting_fell_back_to_leaves_the_branch():
    # the shooting failed from the continued orbit (FALLBACK_NOTE): near a fold the orbit it followed is gone, so the
    # brute-force state it fell back to is no evidence of the branch, however little the response changed (the
    # Kahraman-Singh fold of tests/reference/test_shooting_kahraman_singh.py is found and named this way)
    from gearcli.simulate.shooting import FALLBACK_NOTE

    fallen = _result(1.05, method="brute force", note=f"{FALLBACK_NOTE} (the Newton steps diverged); brute force")
    assert not on_branch(_result(1.0), fallen)


# A two-stage train at light load (stage 1 helical, 5 um TE, rattling near its coupling mode, 467 Hz): continued
# up in 50 rpm steps, a brute-force integration of the two free bodies (scipy's DOP853, rtol 1e-10, each speed run
# 0.25 s from the previous one's final state and mesh phase) gives stage 1's DTE rms 5.363 um at 1300 rpm and 5.293 um
# at 1350 rpm, both period-2 orbits: the motion goes on smoothly (1.3 %), with no jump between them.
FLIP = "the period-1 orbit is unstable through a multiplier below -1: shooting over 2 periods"


def test_a_period_2_orbit_shot_after_the_period_1_orbits_flip_stays_on_the_branch():
    prev = _result(5.363, note=FLIP, attempts=2)
    row = _result(5.293, note=FLIP, attempts=2)
    assert on_branch(prev, row)  # the second start is the period-2 one, from the same state: no failure, no jump
    assert not on_branch(prev, _result(5.293, note=FLIP, attempts=3))  # a restart after a failed start still counts
    assert not on_branch(prev, _result(5.293, attempts=2))  # ... and so does a plain second start


def test_a_point_after_one_without_a_periodic_orbit_is_not_marked(monkeypatch):
    """A predecessor whose periodic search found no period (chaotic, quasi-periodic or still settling) has no branch:
    the row is not followed by bisection (it cost up to 60 runs) nor marked as the end of one. The same train going
    down: 1050 rpm not periodic (DTE rms 24.2 um over its last period), 1000 rpm the period-2 orbit, 7.72 um (the
    brute-force reference: 7.720 um)."""
    from gearcli.sweep import worker
    from gearcli.sweep.spec import Point

    calls = []

    def evaluate(evaluator, scene, point, prev, check=False):
        calls.append(point.index)
        return None, _result(7.72), object()

    monkeypatch.setattr(worker, "_evaluate", evaluate)
    points = tuple(Point(i, (("input.speed_rpm", v),), "down") for i, v in enumerate((1050.0, 1000.0)))
    task = worker.Task(worker.Scene(b"", "scene.toml"), points, True, evaluate)
    chaotic = _result(24.2, method="brute force", converged=False,
                      note="shooting did not converge (the periods allowed are used up); brute force")
    assert worker._jump(task, worker._Before(points[0], chaotic, object()), points[1], _result(7.72)) == ("", 0)
    assert calls == []
    # a converged predecessor with the same jump is still followed and marked, and the row's nfev counts the
    # refinement runs (each of the toy's costs 1000 evaluations), as its wall_s does
    note, refined = worker._jump(task, worker._Before(points[0], _result(24.2), object()), points[1], _result(7.72))
    assert note.startswith("jump: the branch of the previous point") and calls
    assert refined == 1000 * len(calls)
