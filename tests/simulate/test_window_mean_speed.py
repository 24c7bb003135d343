"""The window-mean speeds (summary ``output_speed_deg_s``, ``ratio``) are the integral of the speed channel over the
window, as every mean of simulate (DESIGN section 7), not the plain mean of the samples (trial tr25a).

Scene (tests/simulate/data/torque_drive_fluctuating_speed.toml): one helical stage 23/71, pinion 0.004 kg m^2, gear
0.35 kg m^2, torque drive T_in = T_L / i at 1200 rpm, load T_L = 600 N m (1 + 0.1 sin(2 pi 5.3 Hz t)), no ramps,
1 s in 300 steps. Hand reference, the rigid train (the mesh's compliance moves the speed by ~1e-6): the output
inertia J = J_g + J_p i^2 sees the net torque -0.1 T_L sin(2 pi f t), so
w_out(t) = w_0 - A (1 - cos(2 pi f t)), A = 0.1 T_L / (J 2 pi f) = 4.64 rad/s (12 % of w_0 = 40.7 rad/s), and its
mean over the window [t0, t1] is w_0 - A (1 - (sin(2 pi f t1) - sin(2 pi f t0)) / (2 pi f (t1 - t0))).
Over the 0.2-1 s window that is 345.371 rpm; the samples' plain mean (both ends counted in full) read 345.424 rpm,
1.5e-4 high, beyond the mean's 1e-4 target (the forces' means were already the trapezoid rule's).
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.simulate import run_simulation

SCENE = Path(__file__).resolve().parent / "data" / "torque_drive_fluctuating_speed.toml"


def _rigid_window_mean_rad_s(t0: float, t1: float) -> float:
    i = 71 / 23
    w0 = 1200 * 2 * math.pi / 60 / i
    inertia = 0.35 + 0.004 * i * i
    omega = 2 * math.pi * 5.3
    amplitude = 0.1 * 600.0 / (inertia * omega)
    cos_mean = (math.sin(omega * t1) - math.sin(omega * t0)) / (omega * (t1 - t0))
    return w0 - amplitude * (1.0 - cos_mean)


def test_window_mean_output_speed_is_the_integral():
    cfg = load_design(str(SCENE), []).design
    sim = run_simulation(cfg, compute_design(cfg), want_series=False)
    t0, t1 = sim.window_s
    expected_deg_s = math.degrees(_rigid_window_mean_rad_s(t0, t1))
    assert sim.output_speed_deg_s == pytest.approx(expected_deg_s, rel=2e-5)
    # the reducer's ratio of the window means: the rigid train's z2/z1 (both shafts swing alike)
    assert sim.ratio == pytest.approx(71 / 23, rel=2e-5)
