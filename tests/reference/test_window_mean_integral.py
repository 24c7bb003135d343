"""The window mean is the channel's integral over the window (DESIGN section 7), checked on an impact oscillator
whose every number is derived here: a spur stage with backlash and an undamped linear mesh, the pinion at a
prescribed speed from t = 0, the free gear loaded by a step. Its motion is written out below and integrated by
scipy with the force integral as a quadrature state (no sampling), independent of gearcli's model code."""

from __future__ import annotations

import math

import numpy as np
from numpy.testing import assert_allclose
from scipy.integrate import solve_ivp

from gearcli import api
from gearcli.io.channels import named
from gearcli.io.units import input_torque_window_means

SCENE = """
title = "spur stage with backlash, undamped linear mesh, load step: an impact oscillator"
[materials.steel]
density_kg_m3 = 7800
youngs_modulus_MPa = 2.07e5
poisson_ratio = 0.3
[[stage]]
normal_module_mm = 4
normal_pressure_angle_deg = 20
backlash_mm = 0.1
pinion = { teeth = 20, face_width_mm = 30, material = "steel", inertia_kg_m2 = 0.01 }
gear   = { teeth = 40, face_width_mm = 30, material = "steel", inertia_kg_m2 = 0.05 }
[contact]
stiffness = 3e5
exponent = 1
damping_Ns_mm = 0
[input]
speed_rpm = 600
ramp_s = 0.0
[load]
torque_Nm = 200
ramp_s = 0.0
[simulation]
duration_s = 0.1
steps = 2000
rtol = 1e-9
"""
ALPHA = math.radians(20.0)  # spur: alpha_t = alpha_n, beta_b = 0
R_BP, R_BG = 0.5 * 20 * 4e-3 * math.cos(ALPHA), 0.5 * 40 * 4e-3 * math.cos(ALPHA)
J_G, K, T_L, HALF = 0.05, 3e8, 200.0, 0.5e-4  # kg m^2, N/m, N m, half the normal backlash (m)
OMEGA = 600 * 2 * math.pi / 60


def _line_force(d: float) -> float:
    """The undamped linear mesh on the deflection beyond half the backlash, either flank."""
    if d > HALF:
        return K * (d - HALF)
    if d < -HALF:
        return K * (d + HALF)
    return 0.0


def _reference(window: tuple[float, float]) -> float:
    """The window mean of F_t = F_bt cos(alpha) from the integral of the force, carried as a state."""
    def rhs(t, y):
        d, w_g, _ = y
        f = _line_force(d)
        return [R_BP * OMEGA - R_BG * w_g, (R_BG * f - T_L) / J_G, f * math.cos(ALPHA)]

    def touch(t, y):  # stop at every contact boundary: the force's kink is never stepped over
        return (y[0] - HALF) * (y[0] + HALF)

    sol = solve_ivp(rhs, (0.0, window[1]), [0.0, OMEGA * R_BP / R_BG, 0.0], method="DOP853", rtol=1e-12,
                    atol=[1e-16, 1e-12, 1e-12], dense_output=True, events=touch, max_step=5e-5)
    assert sol.status == 0
    q0, q1 = sol.sol(window[0])[2], sol.sol(window[1])[2]
    return float((q1 - q0) / (window[1] - window[0]))


def _impact_closed_form() -> tuple[float, float]:
    """The rattle by hand: the gear starts at the rigid speed in the middle of the backlash, the load decelerates it
    across j/2 to the drive flank (impact speed v, v^2 = 2 (F_s/m_e) j/2), the undamped spring throws it back to the
    middle, and so on. Peak force F_s (1 + sqrt(1 + k j / F_s)); the fraction of each cycle without contact is the
    flight 2 v / a over the flight plus the contact (pi + 2 asin(F_s / (k A))) / w, A = sqrt((F_s/k)^2 + (v/w)^2)."""
    m_e = J_G / R_BG**2
    f_s = T_L / R_BG
    a = f_s / m_e
    v = math.sqrt(2 * a * HALF)
    w = math.sqrt(K / m_e)
    amp = math.hypot(f_s / K, v / w)
    flight = 2 * v / a
    contact = (math.pi + 2 * math.asin(f_s / (K * amp))) / w
    peak = f_s * (1 + math.sqrt(1 + K * 2 * HALF / f_s))
    return peak * math.cos(ALPHA), flight / (flight + contact)


def test_a_rattling_mesh_has_the_window_mean_of_its_integral(tmp_path):
    path = tmp_path / "rattle.toml"
    path.write_text(SCENE)
    loaded = api.load(str(path), [])
    result = api.simulate(loaded.design, api.design(loaded))
    st = result.stages[0]
    peak, lost = _impact_closed_form()
    assert_allclose(st.peak_tangential_N, peak, rtol=1e-5)  # every impact the same: the scene is conservative
    # 44.6 impact cycles in the 0.08 s window: the window's partial cycle moves the fraction by up to 1/44.6 of a cycle
    assert abs(st.contact_loss_fraction - lost) < 1.0 / 44.6
    # F_t runs from 0 to 4.5x its mean; the plain mean of the 1601 window samples counts both ends in full and was
    # 1.55 N (6e-4) off, six times the mean's 1e-4 target, while the run called the mean resolved
    ref = _reference(result.window_s)
    assert_allclose(st.tangential_N.mean, ref, rtol=1e-4)
    if st.error_estimate is not None:  # what the run says of its mean holds
        assert abs(st.tangential_N.mean - ref) <= max(10 * st.error_estimate.tangential_N.mean, 1e-4 * ref)
    # the footer's input torque is the same integral's: T_in = r_bp F_bt for the speed-driven, rigid pinion shaft
    t = np.asarray(result.time_s)
    ch = named(result)
    w = (t >= result.window_s[0] - 1e-12)
    f_bt = np.asarray(ch["stage1_tangential_N"]) / math.cos(ALPHA)
    torque = np.asarray(ch["input_torque_Nm"]) if "input_torque_Nm" in ch else np.asarray(ch["input_torque_Nmm"]) / 1e3
    assert_allclose(torque[w], R_BP * f_bt[w], rtol=1e-9, atol=1e-9)
    means = input_torque_window_means(result)
    assert means is not None
    assert_allclose(means[0], R_BP * ref / math.cos(ALPHA), rtol=1e-4)
