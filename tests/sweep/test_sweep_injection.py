"""The sweep's workers evaluate points only through the function their task carries (gearcli.api injects
``evaluate_point``): they neither parse the design file nor design nor simulate themselves."""

from __future__ import annotations

from gearcli.errors import SimulationError
from gearcli.sweep.spec import Point
from gearcli.sweep.worker import Scene, Task, run_task


def test_the_worker_calls_the_injected_evaluator_and_nothing_else():
    calls = []

    def fake(scene, overrides, start=None, /, *, series=False, check=False):
        calls.append((scene.source, tuple(overrides), start))
        raise SimulationError(f"fake failure at {overrides[0]}")

    scene = Scene(b"this is not a design file", "plant.toml")  # parsing it would fail with a ConfigError
    points = tuple(Point(i, (("input.speed_rpm", v),), "none") for i, v in enumerate((100, 200)))
    rows = run_task(Task(scene, points, False, fake))
    assert [r["status"] for r in rows] == ["failed", "failed"]
    assert [r["message"] for r in rows] == ["fake failure at input.speed_rpm=100",
                                            "fake failure at input.speed_rpm=200"]
    # independent points: each a cold start (no previous state handed on)
    assert calls == [("plant.toml", ("input.speed_rpm=100",), None), ("plant.toml", ("input.speed_rpm=200",), None)]
