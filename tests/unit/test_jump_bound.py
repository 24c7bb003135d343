"""The sampling estimate of a max beside a step (gearcli/simulate/kink_bound.py, "Jumps"): a spur mesh whose contact
lines vary (`time_varying`) doubles its stiffness as the second tooth pair enters, and its force steps up with it
(tr28a: 36 N to 72 N in an instant on a 12-tooth servo pinion at 10,000 rpm), then relaxes along a smooth arm. The
three samples about the top straddle the step, and the parabola through them put its vertex ~1/8 of the step beyond
the samples, an error that no sampling resolves (the step does not shrink with h): 7.9 N of "miss" at 200,000 steps
where the samples miss at most the arm's change over one step (0.36 N).

Independent reference, the closed form: the force below is B before the step at t_j and B + A e^(-(t - t_j)/tau)
after it, so its supremum is B + A (the step's upper limit), and a sample s after the step misses A (1 - e^(-s/tau)),
at most A h / tau for a sample within one step h of it.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from gearcli.simulate.sampling import SAFETY, max_excess

A, B, TAU = 36.0, 36.0, 50e-6  # N, N, s: the step, the level before it, the upper arm's relaxation
H = 0.5e-6  # s: the sample spacing


def _force(t: np.ndarray, t_jump: float) -> np.ndarray:
    """B up to the step, B + A e^(-(t - t_jump)/TAU) from it; a slow ripple on both arms keeps them smooth."""
    ripple = 0.05 * np.sin(2 * math.pi * 300.0 * t)
    return np.where(t >= t_jump, B + A * np.exp(-(t - t_jump) / TAU), B) + ripple


@pytest.mark.parametrize("phase", [0.02, 0.25, 0.5, 0.75, 0.98])
@pytest.mark.parametrize("where", [40, 1])  # inside the window, and between its first two samples
def test_a_step_up_is_bounded_by_its_arm(phase: float, where: int) -> None:
    t = np.arange(0.0, 200 * H, H)
    t_jump = (where - 1 + phase) * H  # between samples where-1 and where
    x = _force(t, t_jump)
    sup = B + A + 0.05 * math.sin(2 * math.pi * 300.0 * t_jump)  # the closed form's upper limit at the step
    miss = sup - float(x.max())
    estimate = SAFETY * max_excess(t, x)
    arm = A * H / TAU  # the arm's change over one step: the most a sample after the step can miss
    assert miss <= estimate  # the estimate covers the miss ...
    assert estimate <= 2.5 * arm  # ... and stays near the arm's change, not the step's eighth
    assert A / 8.0 > 10.0 * arm  # (the parabola's overshoot: far larger)


def test_a_step_down_out_of_the_top_sample_is_bounded_by_its_arm() -> None:
    """The mirror image: a rising arm whose top is cut by a step down (the second pair leaving): the supremum is the
    arm's limit at the step, the last sample before it misses at most the arm's rise over one step."""
    t = np.arange(0.0, 200 * H, H)
    t_jump = 120.4 * H
    x = np.where(t < t_jump, B + A * np.exp((t - t_jump) / TAU), B)
    miss = (B + A) - float(x.max())
    estimate = SAFETY * max_excess(t, x)
    assert miss <= estimate <= 2.5 * A * H / TAU
