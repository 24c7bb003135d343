"""The periodic steady state of the transmission-error backlash oscillator against a long fixed-window run.

configs/spur_oscillator_te.toml (one spur mesh, 0.1 mm backlash, 5 um first-harmonic TE, zeta 0.05,
f_n = 1.00 kHz). The reference is the same scene integrated over a long fixed window (0.3 to 0.5 s: about
190 mesh periods at 2300 rpm) with no period search. Over a window that is not a whole number of periods,
the mean and rms carry an end error of the order of (amplitude / number of periods), so they are compared
to 1e-3; the extremes of a period-1 response are the same in both runs up to the sampling grids (the
periodic run samples its last period densely, the window run every 5 us), compared to 1e-3 of the
amplitude. At 1500 rpm the teeth never separate; at 2300 rpm (r = 0.96) and 2600 rpm (r = 1.08) the
response separates the teeth every mesh cycle (single-sided impacts).
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from numpy.testing import assert_allclose

from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.simulate import run_simulation
from gearcli.simulate.results import REGIME_NO_IMPACT, REGIME_SINGLE_SIDED

SCENE = Path(__file__).resolve().parents[2] / "configs" / "spur_oscillator_te.toml"
COMMON = ("simulation.rtol=1e-8", "simulation.duration_s=0.5")


def _run(*sets: str):
    cfg = load_design(str(SCENE), [*COMMON, *sets]).design
    return run_simulation(cfg, compute_design(cfg), want_series=False)


@pytest.mark.parametrize(("rpm", "regime"), [(1500, REGIME_NO_IMPACT), (2300, REGIME_SINGLE_SIDED),
                                             (2600, REGIME_SINGLE_SIDED)])
def test_periodic_statistics_equal_a_long_window_run(rpm, regime):
    per = _run(f"input.speed_rpm={rpm}", "simulation.steady=periodic")
    win = _run(f"input.speed_rpm={rpm}", "simulation.window_start_s=0.3", "simulation.steps=40000")
    assert per.steady.converged and per.steady.periodicity == "period-1"
    assert_allclose(per.steady.period_s, 60.0 / (25 * rpm), rtol=1e-12)
    p, w = per.stages[0], win.stages[0]
    assert p.regime == w.regime == regime
    amplitude = w.dte_um.max - w.dte_um.min
    assert_allclose(p.dte_um.mean, w.dte_um.mean, rtol=1e-3)
    assert_allclose(p.dte_um.rms, w.dte_um.rms, rtol=1e-3)
    assert_allclose([p.dte_um.min, p.dte_um.max], [w.dte_um.min, w.dte_um.max], atol=1e-3 * amplitude)
    assert abs(p.contact_loss_fraction - w.contact_loss_fraction) <= 5e-3
    if regime == REGIME_NO_IMPACT:  # mean DTE = static deflection F/k + half the backlash (0.05 mm), by hand
        r_b = 3.0 * 25 / 2 * math.cos(math.radians(20.0)) * 1e-3  # base radius of the 25-tooth gear, m
        force = 70.5 / r_b  # N, the load torque over the gear's base radius
        assert_allclose(p.dte_um.mean, force / 2e5 * 1e3 + 50.0, rtol=1e-5)
