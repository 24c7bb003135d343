"""A run-up peak the output samples alias: an impact pulse far shorter than the sample spacing.

Scene (built here): one helical stage (m_n 4, z 20/60, b 40, beta 15 deg) on a linear mesh 1e4x ISO's stiffness
(7e9 N/mm) with 0.1 mm backlash, 30 N m load, 1500 rpm: the backlash closes during the ramp and the teeth strike
with the 139 kHz mesh mode, a pulse of ~4 us. Sampled every 100 us (the run's 300 samples over 30 ms) the largest
sample is 3117 N while the same run sampled every 0.1 us gives 54,782 N (and Radau at rtol 1e-11 the same to 1e-6):
the parabola through the samples estimated only 78 N more (2.5 %), so the old warning understated the miss 660-fold.
The reference here is the same solution sampled 1000x finer: it is independent of the samples' estimator."""

from __future__ import annotations

import math

import numpy as np
import pytest

from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.simulate import run_simulation, sampling

SCENE = """
title = "aliased impact peak"
[materials.steel]
density_kg_m3 = 7800
youngs_modulus_MPa = 2.07e5
poisson_ratio = 0.29
[[stage]]
normal_module_mm = 4
normal_pressure_angle_deg = 20
helix_angle_deg = 15
pinion = { teeth = 20, face_width_mm = 40, hand = "left" }
gear   = { teeth = 60, face_width_mm = 40, hand = "right" }
backlash_mm = 0.1
[input]
speed_rpm = 1500
ramp_s = 0.05
[load]
torque_Nm = 30
ramp_s = 0.05
[simulation]
duration_s = 0.03
steps = 300
method = "Radau"
engine = "python"
[contact]
stiffness = 7.0e9
exponent = 1
damping_ratio = 0.01
"""


def _run(tmp_path, steps: int):
    f = tmp_path / "impact.toml"
    f.write_text(SCENE)
    cfg = load_design(str(f), [f"simulation.steps={steps}"]).design
    return run_simulation(cfg, compute_design(cfg), want_series=False, error_estimate=False)


@pytest.mark.slow
def test_an_aliased_impact_peak_is_warned_as_unbounded_and_its_suggestion_samples_it(tmp_path):
    coarse = _run(tmp_path, 300)
    fine = _run(tmp_path, 300_000)  # the same solution (Radau's steps do not depend on the samples), 0.1 us apart
    true_peak = fine.stages[0].peak_tangential_N
    assert true_peak > 5e4  # the strike: 54.8 kN
    assert coarse.stages[0].peak_tangential_N < 0.3 * true_peak  # 3.1 kN or 12.5 kN: where the samples fall
    (w,) = [d for d in coarse.diagnostics if d.code == "peak_undersampled"]
    assert w.data["aliased"] is True and "no estimate from them bounds the error" in w.message
    # what the samples' parabola would have claimed falls far short of the true miss: no bound
    assert w.data["estimated_error_N"] < 0.05 * (true_peak - coarse.stages[0].peak_tangential_N)
    # the suggestion samples the 139 kHz mode 16 times a period over the 30 ms run: 0.03 x 1.39e5 x 16 = 66,700
    assert w.data["steps"] == 67_000
    suggested = _run(tmp_path, w.data["steps"])
    np.testing.assert_allclose(suggested.stages[0].peak_tangential_N, true_peak, rtol=0.02)  # 0.85 % low


@pytest.mark.parametrize("per_period", [6, 8, 16, 64])
def test_a_sampled_sinusoid_does_not_chatter(per_period):
    # 1000 + 300 cos(2 pi t) with a sample on its peak: second difference 2 A (1 - cos(2 pi / N)) = 300 at N = 6,
    # 176 at N = 8; against the peak 1300 N: 0.23 and 0.14, below ALIAS_CURVATURE = 1
    t = np.arange(5 * per_period + 1) / per_period
    x = 1000.0 + 300.0 * np.cos(2 * math.pi * t)
    i = int(np.argmax(x[1:-1])) + 1
    hand = 2 * 300.0 * (1 - math.cos(2 * math.pi / per_period)) / 1300.0
    assert hand < sampling.ALIAS_CURVATURE and not sampling._aliased_peak(x, i)
    assert not any(w.data.get("aliased") for w in sampling.peak_warnings(t, [x], t.size - 1, 1.0))


def test_an_isolated_spike_chatters_and_names_the_steps_for_the_fastest_mode():
    # a 3000 N sample between 100 N neighbours: second difference 5800 N, 1.93 of the peak; 1 s sampled 1000
    # times; the fastest mode 20 kHz: 16 samples a period over 1 s is 320,000 steps
    t = np.linspace(0.0, 1.0, 1001)
    x = np.full(t.size, 100.0)
    x[500] = 3000.0
    assert sampling._aliased_peak(x, 500)
    (w,) = sampling.peak_warnings(t, [x], 1000, 20e3)
    assert w.data["aliased"] is True and w.data["steps"] == 320_000
    assert "simulation.steps=320000" in w.message
    # beyond the schema's cap (2,000,000 steps): no suggestion, the message says so
    (w,) = sampling.peak_warnings(t, [x], 1000, 200e3)
    assert w.data["steps"] is None and "cannot sample" in w.message
