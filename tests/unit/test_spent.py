"""What a result cost (gearcli.simulate.spent): solver.total_nfev and total_wall_s add up every run behind the
result, counted here independently by wrapping the integrator every run goes through."""

from __future__ import annotations

from pathlib import Path

import pytest
from numpy.testing import assert_allclose

from gearcli import api
from gearcli.simulate import course, estimate, periodic, shooting, solver
from gearcli.sweep.columns import ok_row

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture
def counted(monkeypatch):
    """Every integration's (nfev, wall_s), by the module that ran it (the check pass: estimate's)."""
    calls: list[tuple[str, int, float]] = []

    def wrap(module):
        real = solver.integrate

        def integrate(*args, **kwargs):
            out = real(*args, **kwargs)
            calls.append((module.__name__, int(out.nfev), float(out.wall_s)))
            return out

        monkeypatch.setattr(module, "integrate", integrate)

    for module in (course, estimate, periodic, shooting):
        wrap(module)
    return calls


def _duty_point():
    """configs/motor_duty_starts.toml's full-load point: its window after the DOL start is unsettled, and the
    settle test repeats the run with a later window (tests/unit/test_settle.py)."""
    loaded = api.load(str(ROOT / "configs" / "motor_duty_starts.toml"), [])
    return loaded.design, api.design(loaded)


def test_the_total_is_every_run_of_a_settled_window(counted):
    from gearcli.simulate import run_simulation

    cfg, design = _duty_point()
    result = run_simulation(cfg, design, settle=True, error_estimate=False, want_series=False)
    sv = result.solver
    assert result.steady.settle_runs >= 1  # the scene needs a re-run
    assert sv.runs == result.steady.settle_runs + 1
    assert sv.total_nfev == sum(n for _, n, _ in counted)  # exact: integer counts
    assert_allclose(sv.total_wall_s, sum(w for _, _, w in counted), rtol=1e-12)  # the same floats summed
    assert sv.nfev < sv.total_nfev  # the kept run's own figures stay its own
    row = ok_row((), "up", result, 1.0, len(result.stages))
    assert row["nfev"] == sv.total_nfev  # no check pass: the point's evaluations are the runs'


def test_the_kept_check_pass_stays_apart(counted):
    from gearcli.simulate import run_simulation

    cfg, design = _duty_point()
    result = run_simulation(cfg, design, settle=True, error_estimate=True, want_series=False)
    sv = result.solver
    assert sv.check_pass is not None and sv.runs >= 2
    checks = sum(n for m, n, _ in counted if m == estimate.__name__)
    runs = sum(n for m, n, _ in counted if m != estimate.__name__)
    # every integration but the kept run's check pass; with it, all of them (the replaced runs' checks included)
    assert sv.total_nfev + sv.check_pass["nfev"] == runs + checks
    assert sv.total_nfev >= runs
    row = ok_row((), "up", result, 1.0, len(result.stages))
    assert row["nfev"] == runs + checks


def test_a_single_run_costs_its_own(counted):
    from gearcli.simulate import run_simulation

    cfg, design = _duty_point()
    result = run_simulation(cfg, design, settle=False, error_estimate=False, want_series=False)
    sv = result.solver
    assert sv.runs == 1 and sv.total_nfev == sv.nfev == sum(n for _, n, _ in counted)
    assert_allclose(sv.total_wall_s, sv.wall_s, rtol=1e-12)  # the same run's figure
