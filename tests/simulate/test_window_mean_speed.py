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

The motor summary's window means likewise (tests/simulate/data/motor_table_fluctuating_load.toml: the same stage on a
motor whose table is linear between 1400 and 1500 rpm, T_m = c0 - c1 w with c0 = 4500 N m, c1 = 90/pi N m s/rad,
under 600 N m (1 + 0.5 sin(2 pi 5.3 Hz t))). Hand reference, the rigid train with J = J_p + J_g / i^2: the linear
ODE J w' = c0 - c1 w - (T_L/i)(1 + 0.5 sin W t) settles (J / c1 = 1.4 ms) to w_op + a sin W t + c cos W t,
w_op = (c0 - T_L/i) / c1, a = -B c1 / (c1^2 + J^2 W^2), c = B J W / (c1^2 + J^2 W^2), B = 0.5 T_L / i; its
window mean 1433.742 rpm and the motor's mean torque c0 - c1 mean(w) = 198.775 N m. The plain means read
1433.663 rpm (5.5e-5 low) and 199.011 N m (1.2e-3 high).
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.simulate import run_simulation

SCENE = Path(__file__).resolve().parent / "data" / "torque_drive_fluctuating_speed.toml"
MOTOR_SCENE = Path(__file__).resolve().parent / "data" / "motor_table_fluctuating_load.toml"


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


def test_motor_summary_window_means_are_the_integral():
    cfg = load_design(str(MOTOR_SCENE), []).design
    sim = run_simulation(cfg, compute_design(cfg), want_series=False)
    t0, t1 = sim.window_s
    i = 71 / 23
    inertia = 0.004 + 0.35 / (i * i)
    c0, c1 = 4500.0, 90.0 / math.pi
    load_in, omega = 600.0 / i, 2 * math.pi * 5.3
    b = 0.5 * load_in
    den = c1 * c1 + (inertia * omega) ** 2
    a, c = -b * c1 / den, b * inertia * omega / den
    span = omega * (t1 - t0)
    mean_sin = (math.cos(omega * t0) - math.cos(omega * t1)) / span
    mean_cos = (math.sin(omega * t1) - math.sin(omega * t0)) / span
    w_mean = (c0 - load_in) / c1 + a * mean_sin + c * mean_cos
    motor = sim.extra["motor"]
    assert motor["operating_speed_rpm"] == pytest.approx(w_mean * 30 / math.pi, rel=1e-5)
    assert motor["mean_torque_Nm"] == pytest.approx(c0 - c1 * w_mean, rel=1e-4)
