"""At the schema's rtol floor (1e-13) no tighter rtol exists: a warning never advises an rtol that is not tighter
than the run's, and ``auto`` does not repeat a run at its own rtol.

Found on a rattling helical mesh (backlash 0.1 mm, 10 µm of transmission error near the mesh mode, 0.5 N·m of load)
run at ``simulation.rtol = 1e-13``: the mean of F_t was estimated 1.1e-4 off (target 1e-4), ``auto`` repeated the whole
run at the same rtol (the same numbers again, twice the cost) and warned "ran at rtol 1e-13 instead of 1e-13",
and the statistics warning advised "--set simulation.rtol=1e-13 would resolve it", the rtol it had run at.

The reference for ``suggested_rtol`` is the estimate's own model stated independently: the error falls in
proportion to rtol, so an error ``e`` at ``rtol`` becomes e x 1e-13 / rtol at the floor; the floor is worth
suggesting only where that meets the target.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from gearcli import diagnostics as dg
from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.simulate import run_simulation
from gearcli.simulate.estimate import (
    MEAN_TARGET,
    MIN_RTOL,
    TARGET,
    CheckPass,
    means_rtol,
    stage_error,
    suggested_rtol,
    warnings,
)
from gearcli.simulate.solver import STATUS_FINISHED

ROOT = Path(__file__).resolve().parents[2]
# the Kahraman-Singh oscillator at 2300 rpm (mesh 958 Hz, near its ~1 kHz mode) with 20 um of transmission error and
# 5 N m of load: the flanks part and meet at random (rattle), its statistics differ between any two passes
RATTLE = ("configs/spur_oscillator_te.toml", ["simulation.rtol=1e-13", "input.speed_rpm=2300", "load.torque_Nm=5",
                                              "contact.transmission_error_um=[20]", "simulation.steps=2000"])


@pytest.mark.parametrize(("rtol", "error", "goal"), [(1e-13, 2e-3, TARGET), (1e-12, 1e3, TARGET),
                                                     (1e-11, 0.5, TARGET), (1e-13, 1.1e-4, MEAN_TARGET)])
def test_no_suggestion_where_the_floor_leaves_the_error_above_the_target(rtol, error, goal):
    assert error * MIN_RTOL / rtol > goal  # the floor, by the model, would not resolve it
    assert suggested_rtol(rtol, error, goal) is None


@pytest.mark.parametrize(("rtol", "error"), [(1e-12, 5e-3), (1e-11, 2e-2), (1e-6, 2e-3)])
def test_a_suggestion_is_tighter_than_the_run_and_resolves_by_the_model(rtol, error):
    got = suggested_rtol(rtol, error)
    assert got is not None and MIN_RTOL <= got < rtol
    assert error * got / rtol <= TARGET


def _check_at_the_floor() -> CheckPass:
    """A check pass (at the floor, as the run) whose window differs from the run's by 1 % of the mean force."""
    t = np.linspace(0.0, 0.1, 801)
    run = 100.0 + 10.0 * np.sin(2 * np.pi * 200 * t)
    check = run * 1.01
    e = stage_error(0, t, run, check, 100.0, MIN_RTOL)
    assert not e.resolved and "mean" in e.unresolved
    return CheckPass(rtol=MIN_RTOL, from_s=0.0, scale=1.0, nfev=1, njev=0, steps=1, wall_s=0.0,
                     status=STATUS_FINISHED, message="", errors=(e,))


def test_at_the_floor_the_warning_names_no_rtol_and_auto_does_not_repeat():
    ref = _check_at_the_floor()
    assert ref.errors[0].suggested_rtol is None
    assert means_rtol(ref) is None
    (w,) = warnings(ref, "DOP853")
    assert w.data["rtol"] is None and "--set simulation.rtol" not in w.message
    assert f"floor {MIN_RTOL:g}" in w.message


def test_a_rattling_run_at_the_floor_is_not_repeated_nor_advised_its_own_rtol():
    rel, sets = RATTLE
    cfg = load_design(str(ROOT / rel), sets).design
    sim = run_simulation(cfg, compute_design(cfg), want_series=False)
    assert sim.solver.rtol == MIN_RTOL
    assert not [d for d in sim.diagnostics if d.code == dg.RTOL_TIGHTENED]
    assert [d for d in sim.diagnostics if d.code == dg.STATISTICS_UNRESOLVED]  # the rattle stays unresolved
    for d in sim.diagnostics:
        advised = d.data.get("rtol") if d.code in (dg.STATISTICS_UNRESOLVED, dg.PEAK_UNRESOLVED) else None
        assert advised is None, d.message  # nothing is tighter than the floor
        assert f"simulation.rtol={MIN_RTOL:g}" not in d.message, d.message
