"""A stability-limited explicit run carries its stiff mode's noise through the run-up at the size of the force, not
of its tolerance: the check pass must start where that noise has decayed below the target, not where an error of
the tolerance's size has (gearcli/simulate/estimate.py, "Stability-limited runs").

Scene: configs/extreme/ratio_1_and_12.toml (a ratio-1 helical stage before a ratio-12 one, default ISO-calibrated
meshes, 1500 rpm and 2400 N m ramped over 0.1 s) at DOP853 rtol 1e-3 (988 steps, stability-limited). The
reference is the same scene at rtol 1e-7, which agrees with rtol 1e-9 to 4e-5 N in min and max, 10x finer than the
errors checked here. Measured before the fix: the check pass started 1 % of the slowest decay before the window
(t = 0.094 s, inside the run-up) and estimated stage 1's min 6.8e-6 N off where the truth is 0.039 N off.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.simulate import run_simulation

SCENE = Path(__file__).resolve().parents[2] / "configs" / "extreme" / "ratio_1_and_12.toml"
SETS = ["simulation.method=DOP853", "simulation.rtol=1e-3", "simulation.engine=python"]


def _run(**kw):
    cfg = load_design(str(SCENE), SETS).design
    return run_simulation(cfg, compute_design(cfg), want_series=False, **kw)


#: the rigid train's tooth forces, by hand: stage 2 carries the load torque on its gear's pitch radius
#: (204 x 4 mm / cos 10 deg / 2 = 414.294 mm), stage 1 a twelfth of it on 30 x 6 mm / cos 15 deg / 2 = 93.17 mm
RIGID_FT_N = (2400e3 / 12 / 93.1749, 2400e3 / 414.294)
#: the reference's own error (rtol 1e-7 against 1e-9) in the window's min and max: <= 4e-5 N
REFERENCE_ERROR_N = 4e-5


def test_stability_limited_runup_errors_are_inside_the_estimate():
    sim = _run()
    truth = _run(rtol=1e-7, error_estimate=False)
    for s, r, rigid in zip(sim.stages, truth.stages, RIGID_FT_N, strict=True):
        assert s.tangential_N.mean == pytest.approx(rigid, rel=1e-4)  # the rigid limit of the mean
        for q in ("min", "max"):
            true = abs(getattr(s.tangential_N, q) - getattr(r.tangential_N, q))
            est = getattr(s.error_estimate.tangential_N, q)
            # the run's noise is chaotic (its size depends on the BLAS's round-off: 4.6e-4 or 0.039 N in stage 1's
            # min, measured), always well above the reference's own error
            assert true > 10 * REFERENCE_ERROR_N  # the premise
            # before the fix: 6.6e-5 N estimated for 4.6e-4 N (and 6.8e-6 for 0.039 N)
            assert true <= est < 5.0 * true, (s.index, q, true, est)
