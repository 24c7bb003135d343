"""The sampling estimate of a kinked extreme (gearcli/simulate/kink_bound.py): a peak made of two straight arms of
very different slope, as a viscous backlash mesh's force where the teeth leave contact (the spring's K q' on one
side, the damper's c q' on the other), sampled at several phases. The true peak is the arms' crossing (closed
form); the estimate must cover the samples' miss and stay near it, where the parabola through three samples
straddling the kink overshot it by up to 60x (module doc). On smooth peaks (a parabola, a sinusoid sampled 16
times a period) the estimate stays SAFETY x the parabola's excess, as before."""

from __future__ import annotations

import math

import numpy as np
import pytest

from gearcli.simulate.sampling import SAFETY, max_excess

STEEP, SHALLOW = 2.0e7, 1.3e6  # N/s: the contact side's slope, the gap side's (the spur oscillator of the module)
H = 25e-6  # s


def _v(t: np.ndarray, t0: float) -> np.ndarray:
    """Two straight arms meeting at t0 with the value 0 there (the peak)."""
    return np.minimum(STEEP * (t - t0), -SHALLOW * (t - t0))


@pytest.mark.parametrize("phase", [0.05, 0.2, 0.35, 0.5, 0.65, 0.8, 0.95])
def test_kinked_peak_estimate_covers_the_miss_and_stays_near_it(phase: float) -> None:
    t = np.arange(0.0, 40 * H, H)
    x = _v(t, (20 + phase) * H)
    miss = 0.0 - float(x.max())  # the closed-form peak is 0
    estimate = SAFETY * max_excess(t, x)
    # the secants of straight arms meet at the peak itself: the estimate is the miss (to rounding)
    assert estimate == pytest.approx(miss, rel=1e-9, abs=1e-9)


def test_worst_phase_parabola_overshoot_is_gone() -> None:
    """The top sample 0.05 h past the kink on the shallow arm, its left neighbour far down the steep one: the
    parabola through the three (its vertex by hand here) lies ~1/8 of the steep step beyond the samples, 60x the
    samples' true miss; the estimate is now the miss itself."""
    t = np.arange(0.0, 40 * H, H)
    x = _v(t, 19.95 * H)
    i = int(np.argmax(x))
    miss = -float(x[i])  # 0.05 h on the shallow arm: 1.625 N
    u, v = x[i] - x[i - 1], x[i] - x[i + 1]  # the steps to the neighbours (both >= 0), even spacing h
    parabola = (u - v) ** 2 / (8.0 * (u + v))  # the vertex's excess over the centre sample
    assert SAFETY * parabola > 50.0 * miss
    estimate = SAFETY * max_excess(t, x)
    assert estimate == pytest.approx(miss, rel=1e-9)


def test_smooth_peaks_keep_the_parabola_estimate() -> None:
    """A sinusoid sampled 16 times a period at an awkward phase: the estimate is SAFETY x the parabola's excess,
    which the secants' bound does not lower (it is at least twice the excess on a parabola)."""
    t = np.arange(0.0, 5.0, 1.0 / 16)
    x = np.sin(2 * math.pi * t + 0.37)
    true_miss = 1.0 - float(x.max())
    est = SAFETY * max_excess(t, x)
    # the parabola's vertex on a sinusoid at 16 samples a period: within 3 % of the miss, doubled
    assert 1.9 * true_miss <= est <= 2.1 * true_miss
