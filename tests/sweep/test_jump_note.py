"""A continued point is marked as a jump only where the branch really ends, not on a steep but smooth flank.

The row's mark compares neighbours: a 30 % change of the DTE rms between two continued points of a coarse speed
grid sends the refinement (``jump_note``) following the branch towards the point. A linear resonance swept in
20 rpm steps changes that much on its flanks without any jump; the branch must then be followed to the point
(no mark). A discontinuous response (an amplitude that drops at 490 rpm) must still be marked, and the end located
to 1/32 of the step. The toy results stand for SimulationResults: only what ``on_branch`` reads.
"""

from __future__ import annotations

from types import SimpleNamespace

from gearcli.sweep.continuation import jump_note, on_branch

N_RES, ZETA = 467.0, 0.02  # the two-stage scene's coupling mode met by the stage-1 mesh order (163.4 Hz x 60 / 21)


def _result(rms: float, mode: str = "periodic", method: str | None = "shooting", settled: bool | None = None):
    stage = SimpleNamespace(dte_um=SimpleNamespace(rms=rms, mean=6.0), tangential_N=SimpleNamespace(std=rms, mean=2e3))
    steady = SimpleNamespace(mode=mode, method=method, attempts=1, settled=settled, multipliers=None)
    return SimpleNamespace(steady=steady, stages=(stage,))


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


def test_a_real_jump_is_marked_and_located_to_a_32nd_of_the_step():
    def rms(rpm: float) -> float:
        return 10.0 if rpm < 490.0 else 2.0

    prev, row = _result(rms(480)), _result(rms(500))
    note = jump_note("input.speed_rpm", 480.0, 500.0, prev, row, lambda v, last: _result(rms(v)))
    # halving from 480: 490 off, 485 on, 490 off, 487.5 on, ..., 489.375 on, then a 0.625 step (20/32) still off
    assert note.startswith("jump: the branch of the previous point (input.speed_rpm = 480) ends between 489.375 and 490")


def test_a_failed_refinement_point_is_off_the_branch():
    prev, row = _result(10.0), _result(2.0)
    note = jump_note("input.speed_rpm", 480.0, 500.0, prev, row, lambda v, last: None)
    assert note.startswith("jump: the branch of the previous point (input.speed_rpm = 480) ends between 480 and 480.625")
