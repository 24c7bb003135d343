"""One compiled model per model structure and process, not per point (issue 14): the points of a speed
sweep differ only in the constants of the generated code, which are bound to the code compiled once."""

from __future__ import annotations

import functools
from pathlib import Path

from gearcli.api import evaluate_point
from gearcli.model import codegen
from gearcli.sweep.spec import Point
from gearcli.sweep.worker import Scene, Task, run_task

TE_SCENE = Path(__file__).resolve().parents[2] / "configs" / "spur_oscillator_te.toml"
# on scipy: the generated code is what integrates (a run on the compiled engine never builds it)
SHORT = ("simulation.duration_s=0.03", "simulation.steps=600", "simulation.engine=python")


def _points(direction: str, speeds) -> tuple[Point, ...]:
    return tuple(Point(i, (("input.speed_rpm", n),), direction) for i, n in enumerate(speeds))


def _spy(monkeypatch) -> list[tuple[str, str]]:
    """Each compilation (a miss of codegen's cache) as (template, function): ``rhs`` and, for a method that asks
    for it, ``jac`` are compiled apart (each its own template), each once per model structure."""
    made: list[tuple[str, str]] = []
    plain = codegen._compiled.__wrapped__

    @functools.cache
    def spy(template: str, n_constants: int, name: str):
        made.append((template, name))
        return plain(template, n_constants, name)

    monkeypatch.setattr(codegen, "_compiled", spy)
    return made


def test_a_sweep_compiles_each_model_structure_once(monkeypatch):
    scene = Scene(TE_SCENE.read_bytes(), TE_SCENE.name, SHORT)
    made = _spy(monkeypatch)
    rows = run_task(Task(scene, _points("none", (1500, 1600, 1700, 1800)), continuation=False, evaluate=evaluate_point))
    assert [r["status"] for r in rows] == ["ok"] * 4
    names = [n for _, n in made]
    assert names.count("rhs") == 1 and names.count("jac") <= 1  # four cold starts: one structure
    made = _spy(monkeypatch)
    rows = run_task(Task(scene, _points("up", (1500, 1600, 1700, 1800)), continuation=True, evaluate=evaluate_point))
    assert [r["status"] for r in rows] == ["ok"] * 4
    # the first point starts cold on its ramps, the continued ones without ramps from a start angle: two
    names = [n for _, n in made]
    assert names.count("rhs") == 2 and names.count("jac") <= 2


def test_bound_constants_give_the_literal_source_values():
    # the code that runs is the template bound to the constants: the same numbers as the printed source
    import numpy as np

    from gearcli.config import load_design
    from gearcli.design import compute_design
    from gearcli.scene import build_model

    cfg = load_design(str(TE_SCENE), []).design
    model = build_model(cfg, compute_design(cfg))
    namespace = dict(model.rhs.__globals__)
    exec(compile(model.source, "<literal>", "exec"), namespace)  # noqa: S102 - the printed source, as is
    y = model.initial_state()
    y[0], y[1] = 5.5e-5, 150.0
    for t in (0.0, 0.011, 0.05):
        np.testing.assert_array_equal(model.rhs(t, y), namespace["rhs"](t, y))
        np.testing.assert_array_equal(model.jac(t, y), namespace["jac"](t, y))
