"""The run's peak |F_t| (``peak_tangential_N``, ``runup_factor``) is printed by every run, so its solver error is
estimated like the window statistics' (DESIGN section 7: every number either resolved or saying it is not): where the
check pass spans the peak, from its own samples; where the peak lies before it (a run-up peak of a well damped scene),
from a short pass at rtol / 10 from DECAY_SPANS / sigma before the peak. Beyond 1e-3 of the peak: ``peak_unresolved``.

Scene: the two-stage reducer of light_mesh_scene.py with the default mesh damping ratio 0.05, DOP853 at rtol 1e-5.
The truth is DOP853 at rtol 1e-10 on the same samples (its peak agrees with rtol 1e-9 to 1e-10). Measured: the run-up
peaks at 0.036 s and 0.042 s are 4030.0 N and 6638.3 N against the truth's 4026.0 N and 6617.8 N (1.0e-3 and 3.1e-3
off; stage 2 estimated 3.1e-3), before the window's check pass (from 0.049 s); before the estimate of run-up peaks no
warning said so. The run's steps sit on the explicit step ceiling there (docs/numerics.md "The step ceiling"): the
check pass halves the ceiling as well as tightening the rtol, or it would take the same steps and see nothing. (Until
the ceiling the scene ran RK45 at rtol 1e-4, 4.8e-3 off; RK45 now keeps to its stability limit there and is 5e-6
off at any rtol from 1e-3.)
"""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_allclose

from gearcli import diagnostics as dg
from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.simulate import run_simulation
from gearcli.simulate.estimate import TARGET, peak_error
from tests.extreme.light_mesh_scene import SCENE

GREY = 1.2  # an error within 20 % of the target may be estimated either side of it
SETS = ["contact.damping_ratio=0.05", "simulation.method=DOP853", "simulation.rtol=1e-5"]


@pytest.fixture(scope="module")
def scene(tmp_path_factory):
    path = tmp_path_factory.mktemp("peak") / "reducer.toml"
    path.write_text(SCENE, encoding="utf-8")
    return path


def _run(path, sets=(), **kw):
    cfg = load_design(str(path), SETS + list(sets)).design
    return run_simulation(cfg, compute_design(cfg), want_series=False, **kw)


@pytest.fixture(scope="module")
def truth(scene):
    return _run(scene, method="DOP853", rtol=1e-10, error_estimate=False, max_nfev=5_000_000)


def _peak_errors(sim, truth):
    return [abs(s.peak_tangential_N - r.peak_tangential_N) / r.peak_tangential_N
            for s, r in zip(sim.stages, truth.stages, strict=True)]


def test_runup_peak_error_is_estimated_and_warned(scene, truth):
    sim = _run(scene)
    true = _peak_errors(sim, truth)
    warned = {d.data["stage"]: d for d in sim.diagnostics if d.code == dg.PEAK_UNRESOLVED}
    for k, e in enumerate(true):
        if e > GREY * TARGET:  # stage 2 (stage 1, 1.0e-3 off, sits on the target: warned or not, both are right)
            assert k + 1 in warned, (k, e)
        if k + 1 in warned:
            # the estimate is the run's error to first order: within 2x of the truth (measured 1.0x)
            assert 0.5 * e < warned[k + 1].data["relative_error"] < 2.0 * e
            assert warned[k + 1].data["at_s"] < sim.window_s[0]  # a run-up peak, before the window
    assert any(e > GREY * TARGET for e in true), "the scene's premise: a run-up peak off by more than the target"
    assert sim.solver.check_pass["finished"]


def test_suggested_rtol_resolves_the_peak(scene, truth):
    sim = _run(scene)
    rtol = min(d.data["rtol"] for d in sim.diagnostics if d.code == dg.PEAK_UNRESOLVED)
    fine = _run(scene, [f"simulation.rtol={rtol:g}"])
    assert max(_peak_errors(fine, truth)) < TARGET
    assert not [d for d in fine.diagnostics if d.code == dg.PEAK_UNRESOLVED]


def test_peak_error_by_hand():
    t = np.linspace(0.0, 1.0, 11)
    run = np.array([0, 1, 5, 9, -12, 3, 2, 2, 2, 2, 2], dtype=float)
    check = run.copy()
    check[4] = -11.7  # the check pass sees the peak 0.3 N lower
    p = peak_error(0, t, run, check[2:], 2, scale=2.0)  # the check sampled 2 .. 10; a loose pass: 2 x the difference
    assert p is not None and p.stage == 1 and p.at_s == pytest.approx(0.4)
    assert_allclose([p.peak_N, p.error_N, p.relative], [12.0, 0.6, 0.05], rtol=1e-12)
    # the check's own peak, wherever it lies: a run whose peak is a spike (sample 4) against a check whose peak is
    # elsewhere (11.9 N at sample 7) is off by 0.1 N, not by the 9 N between the two at sample 4
    spiky = check.copy()
    spiky[4], spiky[7] = 3.0, 11.9
    assert_allclose(peak_error(0, t, run, spiky[2:], 2).error_N, 0.1, rtol=1e-12)
    assert peak_error(0, t, run, check[5:], 5) is None  # the peak (sample 4) lies before the check's samples
