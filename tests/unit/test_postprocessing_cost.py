"""The post-processing's shortcuts compute the same numbers as the long way (issue 33 item 3): the ringing fit with
stages sharing their decay rates against a fit per stage, the window read in place against its mask, the per-layout
energy scale against a fresh one, and a sampling without torques against the whole one."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_allclose

from gearcli.model import TorsionalModel
from gearcli.simulate import ringing, stats
from gearcli.simulate.guards import EnergyWatch, _nominal_scale

SEED = Path(__file__).resolve().parents[2] / "configs" / "concrete_mixer.toml"


def _record(n: int = 1500, stages: int = 3, seed: int = 3):
    """Three stages' F_t ringing in two modes with stage-specific amplitudes (returned: at the record's start) and
    a little noise (a record whose stages share the modes, the seed's case); each mode decays 1.3 times faster
    than the linearised rate given with it (the refinement's case)."""
    rng = np.random.default_rng(seed)
    t = np.linspace(0.3, 0.8, n)
    modes = [(1.2, 2 * math.pi * 58.0), (4.5, 2 * math.pi * 112.0)]
    X = np.empty((n, stages))
    amplitudes = rng.uniform(50, 500, size=(stages, len(modes)))
    for s in range(stages):
        X[:, s] = 5000.0 * (s + 1) + rng.normal(scale=2.0, size=n)
        for (sigma, omega), a in zip(modes, amplitudes[s], strict=True):
            X[:, s] += a * np.exp(-1.3 * sigma * (t - t[0])) * np.cos(omega * (t - t[0]) + s)
    return t, X, modes, amplitudes


def test_the_batched_ringing_fit_equals_one_fit_per_stage():
    # a fit per stage has nothing to share; the stages' fits are independent, so the batched fit (its stages
    # grouped by their decay rates) must give each stage's alone: the same refined rates, and the amplitudes to
    # rounding (a single column's centring sums in another order)
    t, X, modes, expected = _record()
    amplitudes, sigmas = ringing.fit_transients(t, X, modes)
    for s in range(X.shape[1]):
        a1, s1 = ringing.fit_transients(t, X[:, s:s + 1], modes)
        assert np.array_equal(s1[0], sigmas[s])
        assert_allclose(a1[0], amplitudes[s], rtol=1e-9)
    # and the fit finds the amplitudes put in: within 5 % (the refined decay rate is within half a trial step,
    # 6 %, of the true 1.3x, which moves the fitted amplitude by a few %; the noise is 2 N against 50 .. 500 N)
    assert_allclose(amplitudes, expected, rtol=0.05)


def test_identical_stages_share_their_fit():
    t, X, modes, _ = _record()
    same = np.column_stack([X[:, 0]] * 3)
    amplitudes, sigmas = ringing.fit_transients(t, same, modes)
    assert np.array_equal(amplitudes[0], amplitudes[1]) and np.array_equal(amplitudes[0], amplitudes[2])
    assert np.array_equal(sigmas[0], sigmas[2])


def test_a_window_slice_reads_the_same_samples_as_its_mask():
    t = np.linspace(0.0, 0.5, 2001)
    mask = stats.window_mask(t, (0.244, 0.5))
    sel = stats.window_slice(mask)
    assert isinstance(sel, slice) and np.array_equal(t[sel], t[mask])
    holes = mask.copy()
    holes[1500] = False
    assert stats.window_slice(holes) is holes  # not contiguous: the mask itself


@pytest.mark.parametrize(("true", "expected"), [
    ((2000, 4001), slice(2000, 4001)),  # to the end: a fixed window
    ((1000, 3000), slice(1000, 3000)),  # inside: a window moved earlier
    ((0, 5), slice(0, 5)),  # from the first sample
    ((0, 4001), slice(0, 4001)),  # every sample
    ((4000, 4001), slice(4000, 4001)),  # the last sample alone
])
def test_a_contiguous_boolean_window_is_its_slice(true, expected):
    mask = np.zeros(4001, dtype=bool)
    mask[true[0]:true[1]] = True
    assert stats.window_slice(mask) == expected


@pytest.mark.parametrize("true", [[], [3, 7], [0, 4000], [10, 11, 13]])
def test_an_empty_or_broken_boolean_window_is_its_mask(true):
    mask = np.zeros(4001, dtype=bool)
    mask[true] = True
    assert stats.window_slice(mask) is mask
    empty = np.zeros(0, dtype=bool)
    assert stats.window_slice(empty) is empty


@pytest.fixture(scope="module")
def seed_model():
    from gearcli import api

    loaded, design = api.load_and_design(str(SEED))
    return TorsionalModel(api.model_spec(loaded.design, design))


def test_the_energy_scale_is_kept_per_layout(seed_model):
    y0 = seed_model.initial_state()
    first = EnergyWatch(seed_model, y0)
    assert seed_model.layout.__dict__["_energy_scale"] == [_nominal_scale(seed_model.layout)]
    again = EnergyWatch(seed_model, y0)
    assert again.scale == first.scale and again.e0 == first.e0


def test_a_sampling_without_torques_has_the_same_speeds_forces_and_energies(seed_model):
    from gearcli.model.outputs import sample
    from gearcli.simulate.run import simulate_model

    run = simulate_model(seed_model, duration_s=0.3, steps=600, error_estimate=False)
    y = run.final_state
    assert y is not None
    t = np.linspace(0.0, 0.3, 7)
    Y = np.repeat(y[:, None], t.size, axis=1)
    whole, brief = sample(seed_model.layout, t, Y), sample(seed_model.layout, t, Y, torques=False)
    assert brief.input_torque_Nm.size == 0 and brief.load_torque_Nm.size == 0
    assert np.array_equal(whole.omega_rad_s, brief.omega_rad_s)
    for a, b in zip(whole.connectors, brief.connectors, strict=True):
        assert np.array_equal(a.force, b.force) and np.array_equal(a.potential_J, b.potential_J)
