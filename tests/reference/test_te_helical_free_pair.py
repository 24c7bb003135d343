"""A helical stage between two free bodies (a balanced torque drive), a linear mesh with viscous damping, excited by
a first-harmonic transmission error: the mesh coordinate is a single degree of freedom whatever the rigid-body
motion, and its steady response is the textbook frequency response, written out here from the geometry (ISO 21771)
and DESIGN sections 4 and 6 (q = delta - e along the transverse line of action, normal approach cos(beta_b) q,
F_bt = cos(beta_b) K cos(beta_b) q + c q', c = 2 zeta sqrt(K m_e), m_e = J_p J_g / (J_p r_bg^2 + J_g r_bp^2))."""

from __future__ import annotations

import math

import pytest
from numpy.testing import assert_allclose

from gearcli import api

SCENE = """
title = "helical stage, torque drive, linear mesh, TE excitation"
[materials.steel]
density_kg_m3 = 7800
youngs_modulus_MPa = 2.07e5
poisson_ratio = 0.3
[[stage]]
normal_module_mm = 3
normal_pressure_angle_deg = 20
helix_angle_deg = 20
pinion = { teeth = 23, face_width_mm = 30, hand = "left", material = "steel", inertia_kg_m2 = 0.003 }
gear   = { teeth = 47, face_width_mm = 30, hand = "right", material = "steel", inertia_kg_m2 = 0.03 }
[contact]
stiffness = 5e5
exponent = 1
damping_ratio = 0.03
transmission_error_um = [3.0]
transmission_error_phase_deg = [30]
[input]
drive = "torque"
torque_Nm = 300
speed_rpm = 1000
ramp_s = 0.01
[load]
torque_Nm = 613.0434782608696
ramp_s = 0.01
[simulation]
duration_s = 0.3
steps = 30000
steady = "periodic"
"""
J_P, J_G, K, ZETA, E1 = 0.003, 0.03, 5e8, 0.03, 3e-6  # kg m^2, N/m (normal), -, m
T_L = 613.0434782608696  # N m = 300 N m x 47/23: the torque drive balances the load


def _geometry():
    a_n, beta = math.radians(20.0), math.radians(20.0)
    a_t = math.atan(math.tan(a_n) / math.cos(beta))
    m_t = 3e-3 / math.cos(beta)
    r_bp, r_bg = 23 * m_t / 2 * math.cos(a_t), 47 * m_t / 2 * math.cos(a_t)
    beta_b = math.atan(math.tan(beta) * math.cos(a_t))
    return a_t, r_bp, r_bg, math.cos(beta_b)


def _closed_form(rpm: float) -> dict:
    a_t, r_bp, r_bg, cb = _geometry()
    m_e = J_P * J_G / (J_P * r_bg**2 + J_G * r_bp**2)
    k_t = cb**2 * K  # the transverse stiffness along delta
    c = 2 * ZETA * math.sqrt(K * m_e)  # k_lin is the normal slope K (DESIGN section 6)
    w = 23 * rpm / 60 * 2 * math.pi  # the mesh frequency, rad/s
    # m_e q'' + c q' + k_t q = F_bt,static - m_e e'': the TE drives q through the inertia term
    amp = m_e * w**2 * E1 / math.hypot(k_t - m_e * w**2, c * w)
    return {"f_n": math.sqrt(k_t / m_e) / (2 * math.pi), "q_rms_um": amp / math.sqrt(2) * 1e6,
            "q_static_um": T_L / r_bg / k_t * 1e6, "ft_std": amp * math.hypot(k_t, c * w) * math.cos(a_t) / math.sqrt(2),
            "ft_static": T_L / r_bg * math.cos(a_t)}


@pytest.mark.parametrize("rpm", [1000.0, 5900.0, 6700.0])
def test_te_response_of_a_free_helical_pair_is_the_closed_form(tmp_path, rpm):
    path = tmp_path / "te.toml"
    path.write_text(SCENE)
    loaded = api.load(str(path), [f"input.speed_rpm={rpm}"])
    result = api.simulate(loaded.design, api.design(loaded))
    want = _closed_form(rpm)
    st = result.stages[0]
    assert_allclose(result.natural_frequencies_Hz[-1], want["f_n"], rtol=1e-9)
    assert_allclose(st.dte_um.mean, want["q_static_um"], rtol=1e-4)
    # the amplitude statistics to their target, 1e-3 of the channel's mean (DESIGN section 7); measured: 1.5e-4 of
    # the amplitude at 6700 rpm, where the mode (2508 Hz) beats with the 2568 Hz excitation as the start dies out
    assert_allclose(st.dte_um.rms, want["q_rms_um"], atol=1e-3 * want["q_static_um"])
    assert_allclose(st.tangential_N.std, want["ft_std"], atol=1e-3 * want["ft_static"])
    assert_allclose(st.tangential_N.mean, want["ft_static"], rtol=1e-4)
    lost = [d for d in result.diagnostics if d.code == "contact_loss"]
    if want["q_rms_um"] * math.sqrt(2) > want["q_static_um"]:  # 6700 rpm: q swings through zero
        # no backlash: the back flank takes the force at once and the response stays linear (the closed form
        # holds above), so the warning must not speak of impacts
        assert st.back_flank_fraction > 0 and len(lost) == 1
        assert "no impact" in lost[0].message and "rattle" not in lost[0].message
    else:
        assert not lost and st.contact_loss_fraction == 0.0
