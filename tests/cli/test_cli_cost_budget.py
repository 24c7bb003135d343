"""Issue 11, resource bounds: a valid scene that would run for minutes is refused a few seconds in (exit 2).

The integration budget is priced per counter and per method (gearcli.simulate.guards.PRICE_S): an implicit
step costs far more than an explicit one, so a cap on evaluations alone let Radau grind for many minutes on
a 1e-9 kg m² load behind a 1e9 N m/rad coupling with instant ramps (5e6 evaluations reached t = 1e-4 s of
0.5 s). Now the run's pace is projected to its end after a few priced seconds and the run is stopped then.
"""

from __future__ import annotations

import math
import re
import subprocess
import sys
from pathlib import Path

from gearcli.simulate import guards

ROOT = Path(__file__).resolve().parents[2]
SCENE = ROOT / "configs" / "extreme" / "instant_ramps.toml"
TINY_LOAD = ["--set", "load.inertia_kg_m2=1e-9", "--set", "load.coupling_stiffness_Nm_rad=1e9",
             "--set", "simulation.method=Radau"]


def test_priced_work_adds_the_counters_at_their_prices():
    p = guards.PRICE_S
    # by hand: 1000 evaluations, 10 Jacobians, 20 LU, 100 implicit steps
    expected = 1000 * p["eval"] + 10 * p["jac"] + 20 * p["lu"] + 100 * p["step_implicit"]
    assert math.isclose(guards.priced_work_s(1000, 10, 20, 100, implicit=True), expected)
    assert guards.priced_work_s(0, 0, 0, 100, implicit=True) > guards.priced_work_s(0, 0, 0, 100, implicit=False)


def test_the_budget_stops_a_spent_run_and_a_hopeless_pace_but_not_a_fair_one():
    cap, after, limit = guards.WORK_CAP_S, guards.PROJECTION_AFTER_S, guards.PROJECTION_LIMIT
    assert guards.over_budget(cap * 1.01, 0.99, 0.0, 1.0) is not None  # spent, however close to the end
    assert guards.over_budget(after * 0.99, 1e-9, 0.0, 1.0) is None  # too early to project
    # after `after` s, 1 % done: projected 100 * after; stopped only when that is over limit * cap
    projected = after * 1.01 / 0.01
    verdict = guards.over_budget(after * 1.01, 0.01, 0.0, 1.0)
    assert (verdict is not None) == (projected > limit * cap)
    if verdict is not None:  # the duration that fits: 1 % of the run per after * 1.01 s, so cap / that
        assert verdict[0] == "projected" and f"≤ {0.01 * cap / (after * 1.01):.3g} s would fit" in verdict[1]
    assert guards.over_budget(cap * 1.01, 0.99, 0.0, 1.0)[0] == "spent"
    assert guards.over_budget(after * 1.01, 0.5, 0.0, 1.0) is None  # half done: projected ~2 * after


def test_a_tiny_load_inertia_on_a_stiff_coupling_is_stopped_early_with_the_fix():
    res = subprocess.run([sys.executable, "-m", "gearcli", "simulate", str(SCENE), *TINY_LOAD, "--format", "json"],
                         capture_output=True, text=True, timeout=120, env={"PYTHONPATH": str(ROOT), "PATH": ""})
    assert res.returncode == 2, res.stderr  # refused like a resource estimate, the file named
    # (on a machine without the compiled engine's cache a line announcing its compilation may come first)
    msg = next((line for line in res.stderr.splitlines() if line.startswith(f"gearcli: {SCENE}: ")), "")
    assert msg.startswith(f"gearcli: {SCENE}: Radau stopped at t = "), res.stderr
    assert "Traceback" not in res.stderr and "internal error" not in res.stderr
    assert "would need about" in msg and "simulation.duration_s ≤" in msg and "tiny inertia" in msg, msg
    # stopped by the projection, i.e. a few priced seconds in: the counters in the message say so
    steps = int(re.search(r"(\d+) steps", msg).group(1))
    nfev = int(re.search(r"(\d+) right-hand sides", msg).group(1))
    work = guards.priced_work_s(nfev, 0, 0, steps, implicit=True)
    assert work < guards.PROJECTION_AFTER_S * 2, msg
    # the coupling mode sqrt(k / J) / 2 pi = sqrt(1e9 / 1e-9) / 2 pi = 1.59e8 Hz is named
    assert "1.59e+08 Hz" in msg, msg
