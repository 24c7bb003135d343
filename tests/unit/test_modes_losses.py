"""A lossy mesh in the linearised chain (DESIGN §9, §13: modes linearise what simulate integrates). Found by the
audit: `modes` and simulate's `natural_frequencies_Hz` gave the lossless chain's frequencies, while the
simulation rings at the lossy chain's, and a `damping_ratio` mesh's c was sized at the lossless static force.

A mesh with efficiency eta puts its line force f on the driving pinion and eta f on the driven gear. Behind a
speed drive (pinion clamped), a linear mesh k_n (transverse k_t = k_n cos^2 beta_b) on a gear J_g:
J_g theta_g'' = eta k_t r_bg (r_bp theta_p - r_bg theta_g) - T, so w^2 = eta k_t r_bg^2 / J_g.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.testing import assert_allclose

from gearcli.io.channels import named
from gearcli.model import DriveSpec, LoadSpec, MeshSpec, ModelSpec, TorsionalModel
from gearcli.model.assembly import Layout
from gearcli.model.modes import modal_analysis
from gearcli.simulate import simulate_model

DEG = math.pi / 180.0
R_P, R_G, BETA_B = 0.06, 0.15, 10.0 * DEG
K_N, J_P, J_G, T = 2e8, 0.3, 2.5, 300.0
K_T = K_N * math.cos(BETA_B) ** 2


def spec(eta: float, **kw) -> ModelSpec:
    mesh = MeshSpec(base_radius_pinion_m=R_P, base_radius_gear_m=R_G, base_helix_angle_rad=BETA_B,
                    transverse_pressure_angle_rad=20.3 * DEG, helix_angle_rad=10.6 * DEG,
                    full_damping_m=1e-4, contact_ratio=1.6, overlap_ratio=0.0, pinion_teeth=20, efficiency=eta,
                    **{"stiffness_N_m_e": K_N, "exponent": 1.0, "damping_Ns_m": 0.0, **kw})
    return ModelSpec((mesh,), (J_P, J_G), DriveSpec("speed", 50.0), LoadSpec(T))


def test_a_lossy_mesh_rings_at_sqrt_eta_times_the_lossless_frequency():
    eta = 0.9
    w_lossy = math.sqrt(eta * K_T * R_G**2 / J_G)  # 1253.46 rad/s; lossless 1321.26
    modes = modal_analysis(Layout.of(spec(eta)), "clamped_input").modes
    assert_allclose([m.frequency_Hz for m in modes], [w_lossy / (2 * math.pi)], rtol=1e-12)
    # the simulation rings there too: released from half the static deflection delta_s = T / (eta k_t r_bg)
    model = TorsionalModel(spec(eta))
    y0 = model.initial_state()
    y0[0] = 0.5 * T / (eta * K_T * R_G)
    sim = simulate_model(model, duration_s=20 * 2 * math.pi / w_lossy, steps=4000, method="DOP853", rtol=1e-10,
                         y0=y0)
    assert_allclose(sim.natural_frequencies_Hz, [w_lossy / (2 * math.pi)], rtol=1e-12)
    t, x = sim.time_s, named(sim)["stage1_penetration_mm"]
    x = x - 0.5 * (x.max() + x.min())
    i = np.nonzero(np.sign(x[1:]) != np.sign(x[:-1]))[0]
    tc = t[i] - x[i] * (t[i + 1] - t[i]) / (x[i + 1] - x[i])
    # zero crossings by linear interpolation at 200 samples per period: ~1e-6 of the period (the crossings sit at
    # the points of no curvature); 5 % apart from the lossless 1321 rad/s
    assert_allclose(2 * math.pi * (tc.size - 1) / (2 * (tc[-1] - tc[0])), w_lossy, rtol=1e-5)


def test_a_lossy_viscous_mesh_is_damped_at_the_force_it_carries():
    # Hertzian law (e = 1.5): the mesh carries f = T / (eta r_bg), its tangent there is k = e K p0^(e - 1),
    # p0 = (f / (K cos beta_b))^(1/e) along the normal... c = 2 zeta sqrt(k_lin m_e), k_lin = dF_n/dh at that
    # force, m_e = J_g / r_bg^2 (speed-driven pinion). One DOF: J_g theta'' + eta c' r_bg^2 theta' + eta k_t' r_bg^2
    # theta = 0 with k_t' = k_lin cos^2 beta_b and c' = c along the transverse line: zeta_modal =
    # eta c r_bg^2 / (2 sqrt(eta k_lin cos^2 beta_b r_bg^2 J_g)) = zeta sqrt(eta) / cos(beta_b).
    eta, zeta, e, K = 0.9, 0.05, 1.5, 3e13  # K in N/m^1.5
    s = spec(eta, stiffness_N_m_e=K, exponent=e, damping_ratio=zeta)
    f_n = T / (eta * R_G) / math.cos(BETA_B)  # normal line force of the gear-side torque balance
    k_lin = e * K * (f_n / K) ** ((e - 1) / e)
    w = math.sqrt(eta * k_lin * math.cos(BETA_B) ** 2 * R_G**2 / J_G)
    (mode,) = modal_analysis(Layout.of(s), "clamped_input").modes
    assert_allclose(mode.frequency_Hz, w / (2 * math.pi), rtol=1e-9)
    assert_allclose(mode.damping_ratio, zeta * math.sqrt(eta) / math.cos(BETA_B), rtol=1e-9)
