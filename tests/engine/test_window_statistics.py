"""The compiled window statistics (gearcli.engine.window) against closed forms and against independent numpy
computations (np.mean, np.trapezoid, np.std, math.fsum), and bit for bit against the numpy path that runs where
numba is absent (gearcli.simulate.stats): a sweep row and simulate's JSON are the same numbers either way."""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("numba")

from gearcli import engine  # noqa: E402
from gearcli.engine import window  # noqa: E402
from gearcli.simulate import stats  # noqa: E402

LENGTHS = [1, 2, 7, 8, 9, 127, 128, 129, 136, 257, 1000, 2001, 4097]


def _stats(W, whole, t, periodic, loaded):
    return window.window_statistics(np.ascontiguousarray(W, dtype=float), np.ascontiguousarray(whole, dtype=float),
                                    np.ascontiguousarray(t, dtype=float), periodic, np.asarray(loaded, dtype=float))


def _stage(ft, fr, fa, pen, dte):
    return np.stack([ft, fr, fa, pen, dte])


@pytest.mark.parametrize("n", LENGTHS)
def test_pairwise_sum_is_numpys_sum_and_close_to_the_exact_sum(n):
    x = np.random.default_rng(n).standard_normal(n + 5) * 1e3
    span, left = np.empty((window.DEPTH, 3), dtype=np.int64), np.empty(window.DEPTH)
    got = 0.0 + window.pairwise_sum(x, 5, n, span, left)
    assert got == np.sum(x[5:])  # numpy's pairwise summation, the same additions
    assert got == pytest.approx(math.fsum(x[5:].tolist()), rel=1e-12, abs=1e-9)


def test_sine_over_whole_periods_has_zero_mean_and_rms_amplitude_over_root_two():
    A, periods, n = 3.7, 5, 640  # uniform samples of whole periods, without the closing sample
    t = np.arange(n) / n
    x = A * np.sin(2 * np.pi * periods * t)
    W = _stage(x, 2 * x, -x, x, x + 1.0)
    S, _, _, _ = _stats(W, x[None, :], t, True, [1.0])
    mean, lo, hi, std, plain = S[0]
    assert plain == pytest.approx(0.0, abs=1e-12 * A)
    assert mean == pytest.approx(0.0, abs=1e-12 * A)
    assert std == pytest.approx(A / math.sqrt(2.0), rel=1e-12)  # about the mean 0: the rms
    assert (lo, hi) == pytest.approx((-A, A), rel=1e-12)  # n / periods divisible by 4: the crests are samples
    assert S[1, 3] == pytest.approx(2 * A / math.sqrt(2.0), rel=1e-12)
    assert S[4, 0] == pytest.approx(1.0, rel=1e-12) and S[4, 3] == pytest.approx(A / math.sqrt(2.0), rel=1e-12)


def test_trapezoid_mean_of_a_ramp_on_an_uneven_grid_is_its_midpoint_value():
    t = np.sort(np.random.default_rng(1).uniform(2.0, 5.0, 301))
    x = 4.0 + 1.5 * t  # linear: the trapezoid rule is exact
    W = _stage(x, x, x, x, x)
    S, _, _, _ = _stats(W, x[None, :], t, False, [1.0])
    assert S[0, 0] == pytest.approx(4.0 + 1.5 * (t[0] + t[-1]) / 2, rel=1e-13)
    assert S[0, 1] == 4.0 + 1.5 * t[0] and S[0, 2] == 4.0 + 1.5 * t[-1]
    assert S[0, 3] == pytest.approx(np.sqrt(np.mean((x - x.mean()) ** 2)), rel=1e-12)  # std about the plain mean
    assert S[0, 4] == pytest.approx(4.0 + 1.5 * np.mean(t), rel=1e-13)  # the plain mean: the samples' own


def test_run_up_peak_is_the_first_largest_magnitude():
    whole = np.array([[1.0, -9.0, 3.0, 9.0, -9.0], [0.0, 2.0, 5.0, 5.0, 1.0]])
    W = np.ones((10, 2))
    _, peak_at, _, _ = _stats(W, whole, np.array([0.0, 1.0]), True, [1.0, 1.0])
    assert peak_at.tolist() == [1, 2]  # |-9| first, before the later 9 and -9; the first 5


def test_contact_fractions_count_the_samples_without_contact_and_on_the_back_flank():
    n = 100
    ft = np.full(n, 50.0)
    pen = np.full(n, 0.01)
    ft[10:15] = 0.0  # 5 samples without force
    pen[40:47] = 0.0  # 7 without penetration
    pen[80:83] = -0.002  # 3 on the back flank of a positively loaded mesh
    W = _stage(ft, ft, ft, pen, pen)
    t = np.arange(n) / n
    _, _, frac, flags = _stats(W, ft[None, :], t, True, [1.0])
    assert frac[0].tolist() == [12 / n, 3 / n] and flags[0].tolist() == [1.0, 1.0]
    _, _, frac, flags = _stats(W, ft[None, :], t, True, [-1.0])  # loaded on the other flank: the rest is back
    assert frac[0, 1] == pytest.approx((n - 7 - 3) / n) and flags[0, 1] == 1.0
    W = _stage(np.full(n, 50.0), ft, ft, np.full(n, 0.01), pen)
    _, _, frac, flags = _stats(W, ft[None, :], t, True, [1.0])
    assert frac[0].tolist() == [0.0, 0.0] and flags[0].tolist() == [0.0, 0.0]


@pytest.mark.parametrize("periodic", [False, True])
@pytest.mark.parametrize("n", LENGTHS)
def test_random_rows_against_independent_numpy_reductions(n, periodic):
    rng = np.random.default_rng(100 + n)
    t = np.sort(rng.uniform(0.0, 2.0, n))
    W = rng.standard_normal((10, n)) * rng.uniform(0.1, 1e4, (10, 1)) + rng.uniform(-1e3, 1e3, (10, 1))
    whole = rng.standard_normal((2, n + 50))
    S, peak_at, _, _ = _stats(W, whole, t, periodic, [1.0, -1.0])
    plain = n < 2 or periodic
    mean = W.mean(axis=1) if plain else np.trapezoid(W, t, axis=1) / (t[-1] - t[0])
    np.testing.assert_allclose(S[:, 0], mean, rtol=1e-11, atol=1e-11 * np.abs(W).max())
    np.testing.assert_array_equal(S[:, 1], W.min(axis=1))
    np.testing.assert_array_equal(S[:, 2], W.max(axis=1))
    np.testing.assert_allclose(S[:, 3], np.sqrt(((W - W.mean(axis=1, keepdims=True)) ** 2).mean(axis=1)),
                               rtol=1e-10, atol=1e-12 * np.abs(W).max())
    np.testing.assert_allclose(S[:, 4], np.array([math.fsum(r) / n for r in W.tolist()]), rtol=1e-12,
                               atol=1e-12 * np.abs(W).max())
    np.testing.assert_array_equal(peak_at, np.argmax(np.abs(whole), axis=1))


@pytest.mark.parametrize("periodic", [False, True])
@pytest.mark.parametrize("n", [9, 129, 2001])
def test_stages_dynamics_compiled_and_numpy_are_the_same_numbers(n, periodic, monkeypatch):
    """gearcli.simulate.stats.stages_dynamics with the compiled pass and with numpy's reductions (the engine not
    loaded): equal results, every float bit for bit."""
    rng = np.random.default_rng(n)
    t = np.sort(rng.uniform(0.0, 1.0, n))
    mask = t >= t[n // 3]
    per_stage = []
    for _ in range(3):
        ft = rng.standard_normal(n) * 100 + 500
        ft[rng.uniform(size=n) < 0.05] = 0.0
        pen = rng.standard_normal(n) * 0.01 + 0.005
        per_stage.append((ft, 0.3 * ft, 0.1 * ft, pen, rng.standard_normal(n)))
    static = [480.0, -300.0, 0.0]

    def run():
        return stats.stages_dynamics(t, mask, per_stage, static, periodic=periodic, simulated_static_N=[470.0, None,
                                                                                                         None])

    from gearcli.engine import kernel as compiled  # the kernel module, imported directly (bound to the cache)

    monkeypatch.setattr(engine, "loaded_kernel", lambda: compiled)
    with_kernel = run()
    monkeypatch.setattr(engine, "loaded_kernel", lambda: None)
    with_numpy = run()
    assert with_kernel == with_numpy
    assert repr(with_kernel) == repr(with_numpy)  # every float's repr: bit for bit, the NaN-free records


@pytest.mark.parametrize("periodic", [False, True])
@pytest.mark.parametrize("kind", ["random", "constant", "sine"])
def test_sampling_estimate_from_the_reductions_is_the_one_from_the_samples(kind, periodic):
    """gearcli.simulate.sampling.stage_sampling given the window's reductions (the sweep's path) and computing them
    itself: the same estimate."""
    from gearcli.simulate import sampling

    n = 400
    t = np.linspace(0.0, 0.1, n, endpoint=not periodic)
    ft = {"random": np.random.default_rng(7).standard_normal(n) * 30 + 900, "constant": np.full(n, 812.5),
          "sine": 900 + 40 * np.sin(2 * np.pi * 7 * t / 0.1)}[kind]
    W = _stage(ft, ft, ft, ft, ft)
    S, _, _, _ = _stats(W, ft[None, :], t, periodic, [1.0])
    given = sampling.stage_sampling(t, ft, 880.0, n, periodic=periodic, reduced=(S[0, 4], S[0, 3], S[0, 1], S[0, 2]))
    assert given == sampling.stage_sampling(t, ft, 880.0, n, periodic=periodic)
    if kind == "constant":  # nothing between equal samples: no sampling error
        assert (given.min_N, given.max_N) == (0.0, 0.0)


CONSTANTS = [812.5, -3.3e-7, 1e300, 5e-324, 0.0, -0.0, 0.1, -1234.5678]


@pytest.mark.parametrize("n", LENGTHS)
def test_a_constant_sum_is_the_pairwise_sum_of_its_copies(n):
    span, left = np.empty((window.DEPTH, 3), dtype=np.int64), np.empty(window.DEPTH)
    for c in CONSTANTS + list(np.random.default_rng(n).standard_normal(5) * 1e4):
        copies = np.full(n, c)
        got = window.constant_sum(c, n)
        want = window.pairwise_sum(copies, 0, n, span, left)
        assert math.copysign(1.0, got) == math.copysign(1.0, want) and (got == want or math.isnan(want))
        assert 0.0 + got == np.sum(copies)  # numpy's own sum of the copies
        nudged = np.concatenate([copies[:-1], [np.nextafter(c, np.inf)]])
        assert window.constant(copies) and (n < 2 or not window.constant(nudged))


def test_a_row_is_constant_bit_for_bit():
    assert not window.constant(np.array([0.0, -0.0])) and not window.constant(np.array([-0.0, 0.0, -0.0]))
    assert not window.constant(np.array([np.nan, np.nan])) and not window.constant(np.array([1.0, np.nan]))
    assert window.constant(np.array([-0.0, -0.0])) and window.constant(np.array([np.inf, np.inf]))


@pytest.mark.parametrize("periodic", [False, True])
@pytest.mark.parametrize("n", LENGTHS)
def test_constant_rows_are_the_general_passs_numbers(n, periodic):
    """Constant rows (an equilibrium's window: sums of copies, min = max = the value) against the same rows each with
    its last sample nudged and back (the general pass on rows that differ by one sample: then equal again), and
    against numpy's reductions of the copies; the contact flags of constant rows too."""
    rng = np.random.default_rng(7 + n)
    t = np.sort(rng.uniform(0.0, 2.0, n))
    values = (CONSTANTS * 2)[:10]
    W = np.array([np.full(n, c) for c in values])
    whole = rng.standard_normal((2, n + 50))
    S, peak_at, frac, flags = _stats(W, whole, t, periodic, [1.0, -1.0])
    np.testing.assert_array_equal(S[:, 1], W.min(axis=1))
    np.testing.assert_array_equal(S[:, 2], W.max(axis=1))
    with np.errstate(over="ignore", invalid="ignore"):  # 1e300's copies overflow their sum: inf, NaN both ways
        np.testing.assert_array_equal(S[:, 4], W.mean(axis=1))  # numpy's mean: its pairwise sum over n
        np.testing.assert_array_equal(S[:, 3], W.std(axis=1))
    if periodic or n < 2:
        np.testing.assert_array_equal(S[:, 0], S[:, 4])
    # the general pass on the same values (a row made non-constant in a copy of the scratch only: each row's
    # statistics depend on its own samples alone), row by row
    for r in range(W.shape[0]):
        if n < 2:
            break
        varied = W.copy()
        varied[r, -1] = np.nextafter(varied[r, -1], np.inf) if varied[r, -1] != 0.0 else 1.0
        S2, _, _, _ = _stats(varied, whole, t, periodic, [1.0, -1.0])
        others = [i for i in range(W.shape[0]) if i != r]
        np.testing.assert_array_equal(S2[others], S[others])
    span, left = np.empty((window.DEPTH, 3), dtype=np.int64), np.empty(window.DEPTH)
    for k, loaded in enumerate((1.0, -1.0)):
        f, p = W[5 * k], W[5 * k + 3]
        lost = ((f == 0.0) | (p == 0.0)).astype(float)
        back = (loaded * p < 0.0).astype(float)
        for c, flag in enumerate((lost, back)):
            plain = (0.0 + window.pairwise_sum(flag, 0, n, span, left)) / n
            if periodic or n < 2:
                assert frac[k, c] == plain
            assert flags[k, c] == (1.0 if plain > 0.0 else 0.0)
    np.testing.assert_array_equal(peak_at, np.argmax(np.abs(whole), axis=1))


@pytest.mark.parametrize("periodic", [False, True])
def test_stages_dynamics_of_an_equilibriums_window_compiled_and_numpy_are_the_same_numbers(periodic, monkeypatch):
    """A window constant in every channel (an equilibrium's), a run-up before it: stages_dynamics with the compiled
    pass and with numpy's reductions, bit for bit."""
    rng = np.random.default_rng(11)
    n = 4001
    t = np.linspace(0.0, 3.0, n)
    mask = t >= 1.5
    per_stage = []
    for scale in (1851.1, 3715.4, -7916.4):
        rows = []
        for factor in (1.0, 0.36, 0.18, 1e-3, 1e-2):
            x = scale * factor * (1.0 + 0.3 * rng.standard_normal(n))
            x[mask] = x[np.argmax(mask)]  # the window: one sample repeated
            rows.append(x)
        per_stage.append(tuple(rows))
    static = [1851.1, 3715.4, -7916.4]
    from gearcli.engine import kernel as compiled

    monkeypatch.setattr(engine, "loaded_kernel", lambda: compiled)
    with_kernel = stats.stages_dynamics(t, mask, per_stage, static, periodic=periodic)
    monkeypatch.setattr(engine, "loaded_kernel", lambda: None)
    with_numpy = stats.stages_dynamics(t, mask, per_stage, static, periodic=periodic)
    assert repr(with_kernel) == repr(with_numpy)
