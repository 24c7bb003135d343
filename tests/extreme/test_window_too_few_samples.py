"""A fixed window with fewer output samples than any error estimate needs (simulation.steps of 1 to 5 over a 0.2 s run
whose window is its last 0.12 s) reported its one or two samples as the window's mean, min, max and std, "resolved",
with no warning; the lightly damped reducer below swings by +-9.5 % of its mean F_t through that window. Now the run
warns ``statistics_undersampled`` for mean, min, max and std (docs/numerics.md, "The output sampling") and suggests
the ``simulation.steps`` that gives the window 5 samples.

The truth is the same scene at DOP853 rtol 1e-10 sampled 4000 times (docs/numerics.md measures its sampled extremes
within 1e-3 of the mean: the parabola estimate of its own run is below that).
"""

from __future__ import annotations

import math

import pytest

from gearcli import diagnostics as dg
from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.simulate import run_simulation
from tests.extreme.light_mesh_scene import SCENE

SETS = ["contact.damping_ratio=1e-4", "simulation.method=auto", "simulation.rtol=1e-6"]


@pytest.fixture(scope="module")
def scene(tmp_path_factory):
    path = tmp_path_factory.mktemp("few") / "light_mesh_damping.toml"
    path.write_text(SCENE, encoding="utf-8")
    return path


def _run(path, sets, **kw):
    cfg = load_design(str(path), SETS + list(sets)).design
    return run_simulation(cfg, compute_design(cfg), want_series=False, **kw)


@pytest.fixture(scope="module")
def truth(scene):
    return _run(scene, ["simulation.steps=4000"], method="DOP853", rtol=1e-10, error_estimate=False,
                max_nfev=5_000_000)


def _window_samples(steps: int, start: float = 0.08, duration: float = 0.2) -> int:
    """Samples k * duration / steps, k = 0 .. steps, at or after the window start (counted by hand)."""
    return sum(1 for k in range(steps + 1) if k * duration / steps >= start - 1e-12)


@pytest.mark.parametrize("steps", [1, 2, 3, 5])
def test_too_few_window_samples_warn(scene, truth, steps):
    sim = _run(scene, [f"simulation.steps={steps}"])
    n = _window_samples(steps)
    assert n < 5
    s1, r1 = sim.stages[0].tangential_N, truth.stages[0].tangential_N
    # the premise: what the samples show is far from the window's truth (std 161 N, min/max +-283 N about 2980 N)
    assert abs(s1.std - r1.std) > 1e-3 * abs(r1.mean) or abs(s1.max - r1.max) > 1e-3 * abs(r1.mean)
    for s in sim.stages:
        assert s.sampling_error is not None and s.sampling_error.samples == n and not s.sampling_error.resolved
        assert s.error_estimate is not None and not s.error_estimate.resolved
        assert {"mean", "min", "max", "std"} <= set(s.error_estimate.unresolved)
    warned = [d for d in sim.diagnostics if d.code == dg.STATISTICS_UNDERSAMPLED]
    assert sorted(d.data["stage"] for d in warned) == [1, 2]
    # the suggestion gives the window 5 samples: ceil(5 / (0.12 s / 0.2 s)) = 9 steps, 6 window samples
    assert {d.data["steps"] for d in warned} == {max(steps + 1, math.ceil(5 / 0.6))}
    assert _window_samples(9) == 6


def test_five_window_samples_are_estimated(scene):
    sim = _run(scene, ["simulation.steps=9"])
    # 6 window samples: the estimators run (the parabola needs 3, Richardson's mean 5); whatever they then find is
    # an estimate, not the too-few verdict
    assert sim.stages[0].sampling_error.samples == 6
    assert not any("fewer than the 5" in d.message for d in sim.diagnostics)
