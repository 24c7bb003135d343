"""Every sweep point has its own estimate of the output sampling's error of the window min and max (no check pass
needed: gearcli.simulate.sampling), and its row says when the samples leave them unresolved."""

from __future__ import annotations

import functools
from pathlib import Path

from gearcli.api import evaluate_point
from gearcli.sweep.family import CHECK_EVERY
from gearcli.sweep.spec import Point
from gearcli.sweep.worker import Scene, Task, iter_task

ROOT = Path(__file__).resolve().parents[2]


def test_unchecked_points_warn_undersampled_in_their_rows() -> None:
    # configs/backlash_oscillator.toml at 700 steps: its window max is 6e-3 of the mean off between the samples
    # (tests/unit/test_sampling.py: 19.8 N true against the same run sampled 16x finer); point 1 and 2 run no check
    # pass (only every CHECK_EVERY-th does), yet their rows name the steps that resolve it
    assert CHECK_EVERY > 2
    path = ROOT / "configs" / "backlash_oscillator.toml"
    scene = Scene(path.read_bytes(), str(path), ("simulation.steps=700", "simulation.method=DOP853"), 3)
    points = tuple(Point(i, (("input.speed_rpm", 200.0 + 2 * i),), "none") for i in range(3))
    rows = list(iter_task(Task(scene, points, False, functools.partial(evaluate_point, settle=False))))
    for r in rows:
        assert "not resolved by the output samples" in r["message"] and "--set simulation.steps=" in r["message"]
