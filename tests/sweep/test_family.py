"""Issue 33 item 3: a sweep's check pass is shared by a family of neighbouring points (gearcli.sweep.family)."""

from __future__ import annotations

import functools
from pathlib import Path
from types import SimpleNamespace

from gearcli.api import evaluate_point
from gearcli.sweep import family
from gearcli.sweep.family import CHECK_EVERY, Family
from gearcli.sweep.worker import Scene, Task, iter_task

ROOT = Path(__file__).resolve().parents[2]


def _result(nfev: int, method="DOP853", engine="python", rtol=1e-6, unresolved=("stage 1: F_t max not resolved",)):
    diags = tuple(SimpleNamespace(code="statistics_unresolved", message=m) for m in unresolved)
    return SimpleNamespace(diagnostics=diags, final_time_s=0.5,
                           solver=SimpleNamespace(method=method, engine=engine, rtol=rtol, nfev=nfev))


def test_which_points_check_does_not_depend_on_the_tasks():
    assert [i for i in range(40) if Family.needs_check(i)] == [0, CHECK_EVERY, 2 * CHECK_EVERY]


def test_an_unresolved_verdict_carries_only_to_alike_neighbours():
    f = Family()
    assert f.carried(_result(1000)) == ()  # no checked point yet in this task: nothing carried
    assert f.checked("speed 300", _result(1000)) == ()  # its own warnings are in its result
    (msg,) = f.carried(_result(1400))  # 1.4x the pace: alike (PACE_RATIO 1.5)
    assert msg.startswith("stage 1: F_t max not resolved") and "checked point speed 300" in msg
    assert f.carried(_result(1600)) == ()  # 1.6x: not alike
    assert f.carried(_result(1000, engine="compiled")) == ()
    assert f.carried(_result(1000, method="Radau")) == ()
    assert f.carried(_result(1000, rtol=1e-7)) == ()  # a checked point auto re-ran tighter carries nothing
    f.checked("speed 400", _result(1000, unresolved=()))
    assert f.carried(_result(1000)) == ()  # a resolved verdict carries silently


def test_a_loose_sweep_carries_the_checked_points_warning_into_its_neighbours_rows(monkeypatch):
    """configs/concrete_mixer_loose_rtol.toml (rtol 1e-3) is unresolved at every speed near 600 rpm: the checked
    point's row has its own warning, its alike neighbours the family's."""
    monkeypatch.setattr(family, "CHECK_EVERY", 3)
    path = ROOT / "configs" / "concrete_mixer_loose_rtol.toml"
    scene = Scene(path.read_bytes(), str(path), ("simulation.engine=python",), 3)
    from gearcli.sweep.spec import Point

    points = tuple(Point(i, (("input.speed_rpm", 600.0 + 5 * i),), "none") for i in range(3))
    # the window from rest (settle=False): its run-up ringing is what rtol 1e-3 cannot resolve; a settled window of
    # this scene is resolved even at 1e-3, and would leave the family nothing to carry
    carrier = family.Carrier()  # independent points take their family's verdict in the sweep's own process
    rows = [r for got in iter_task(Task(scene, points, False, functools.partial(evaluate_point, settle=False)))
            for r in carrier.add(got)]
    assert "not resolved" in rows[0]["message"] and "family's checked point" not in rows[0]["message"]
    for r in rows[1:]:
        # named as the user writes the point (`--set` form), not as a Python tuple
        assert "family's checked point input.speed_rpm=600.0)" in r["message"] and "((" not in r["message"]


def test_a_transient_left_in_the_checked_window_is_not_carried():
    """A settled window's start-up transient (gearcli.simulate.leftover: ``transient_N`` in its data) is the checked
    point's own, not the solver's verdict on its neighbours."""
    f = Family()
    own = SimpleNamespace(code="statistics_unresolved", message="stage 1: F_t min, max not resolved by the window",
                          data={"transient_N": 123.0})
    solver = SimpleNamespace(code="statistics_unresolved", message="stage 1: F_t max not resolved", data={})
    checked = _result(1000)
    f.checked("speed 300", SimpleNamespace(**{**vars(checked), "diagnostics": (own, solver)}))
    (msg,) = f.carried(_result(1000))
    assert msg.startswith("stage 1: F_t max not resolved")
