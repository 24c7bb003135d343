"""The simulation against closed-form answers: a linear mesh's free vibration, the rigid-body limit,
energy that damping never creates, backlash rattle with its momentum invariant, and the mesh frequency
of a time-varying stiffness. Scenes are plain parameters (gearcli.model.ModelSpec); every expected
value is derived here, none is copied from the code's output."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose

from gearcli.io.channels import named
from gearcli.model import DriveSpec, LoadSpec, MeshSpec, ModelSpec, TorsionalModel
from gearcli.simulate import simulate_model

DEG = math.pi / 180.0
R_P, R_G = 0.06, 0.15  # base radii, m
BETA_B = 10.0 * DEG
CB = math.cos(BETA_B)


def mesh(**kw) -> MeshSpec:
    base = dict(base_radius_pinion_m=R_P, base_radius_gear_m=R_G, base_helix_angle_rad=BETA_B,
                transverse_pressure_angle_rad=20.3 * DEG, helix_angle_rad=10.6 * DEG, stiffness_N_m_e=2e8,
                exponent=1.0, damping_Ns_m=0.0, full_damping_m=1e-4, contact_ratio=1.6, overlap_ratio=0.0,
                pinion_teeth=20)
    base.update(kw)
    return MeshSpec(**base)


def speeds_rad_s(sim, n):
    return np.array([named(sim)[f"shaft{i + 1}_speed_deg_s"] for i in range(n)]) * DEG


# ----------------------------------------------------------------------- linear free vibration
def test_linear_mesh_oscillates_at_the_analytic_natural_frequency():
    # Pinion held at a constant speed (speed drive, no ramp), constant load T on the gear, linear
    # undamped mesh k_n: delta'' = -(r_bg / J_g)(k_t r_bg delta - T), k_t = k_n cos^2(beta_b), so
    # delta(t) = delta_s + (delta_0 - delta_s) cos(w_n t), w_n^2 = k_t r_bg^2 / J_g, delta_s = T / (r_bg k_t).
    k_n, J_g, T = 2e8, 2.5, 300.0
    k_t = k_n * CB**2
    w_n = math.sqrt(k_t * R_G**2 / J_g)
    delta_s = T / (R_G * k_t)
    spec = ModelSpec((mesh(stiffness_N_m_e=k_n),), (0.3, J_g), DriveSpec("speed", 50.0), LoadSpec(T))
    model = TorsionalModel(spec)
    y0 = model.initial_state()
    y0[0] = 0.5 * delta_s  # starts at half the static deflection: never leaves the drive flank
    periods = 20
    duration = periods * 2 * math.pi / w_n
    sim = simulate_model(model, duration_s=duration, steps=periods * 100, method="DOP853", rtol=1e-10, y0=y0)
    t = sim.time_s
    delta = named(sim)["stage1_penetration_mm"] * 1e-3 / CB
    exact = delta_s - 0.5 * delta_s * np.cos(w_n * t)
    # DOP853 at rtol 1e-10: global error over 20 periods ~1e-8 of the amplitude; 1e-6 is a margin of 100
    assert_allclose(delta, exact, rtol=0, atol=1e-6 * 0.5 * delta_s)
    # the period from zero crossings of delta - delta_s (linear interpolation: the crossings are at the
    # points of no curvature, so the interpolation error is O((w dt)^3) ~ 2.5e-4 of a sample, ~1e-6 of the
    # period); 2 crossings per period
    x = delta - delta_s
    i = np.nonzero(np.sign(x[1:]) != np.sign(x[:-1]))[0]
    tc = t[i] - x[i] * (t[i + 1] - t[i]) / (x[i + 1] - x[i])
    period = 2 * (tc[-1] - tc[0]) / (tc.size - 1)
    assert_allclose(2 * math.pi / period, w_n, rtol=2e-6)
    assert_allclose(sim.natural_frequencies_Hz, [w_n / (2 * math.pi)], rtol=1e-12)  # linearised = exact here
    # the mean force over whole periods balances the load: F_t = F_bt cos(alpha_t), F_bt = T / r_bg
    assert_allclose(sim.stages[0].tangential_N.mean, T / R_G * math.cos(20.3 * DEG), rtol=2e-3)


# ----------------------------------------------------------------------------- rigid-body limit
def test_very_stiff_meshes_give_the_rigid_body_input_torque():
    # Two stages with linear meshes 1e11 N/m (w_n ~ 1e4 rad/s, w_n T ~ 2e3 over the 0.2 s ramp), fully
    # damped from contact on: the train follows the STEP speed rigidly, and the input torque is
    # T_in = J_eff alpha_1(t) + rho_n T_L(t),  J_eff = sum J_i rho_i^2,  rho = (1, r_p1/r_g1, r_p1 r_p2/(r_g1 r_g2)).
    J = (0.2, 3.0, 30.0)
    r2p, r2g = 0.08, 0.2
    meshes = (mesh(stiffness_N_m_e=1e11, damping_Ns_m=2e5, full_damping_m=1e-9),
              mesh(base_radius_pinion_m=r2p, base_radius_gear_m=r2g, stiffness_N_m_e=1e11, damping_Ns_m=2e5,
                   full_damping_m=1e-9))
    v, Tr, TL = 60.0, 0.2, 400.0
    spec = ModelSpec(meshes, J, DriveSpec("speed", v, Tr), LoadSpec(TL, Tr))
    sim = simulate_model(TorsionalModel(spec), duration_s=0.3, steps=600, method="auto", rtol=1e-8)
    t = sim.time_s
    rho = np.array([1.0, R_P / R_G, R_P / R_G * r2p / r2g])
    J_eff = float(np.dot(J, rho**2))
    s = np.clip(t / Tr, 0, 1)
    alpha1 = 6 * v * s * (1 - s) / Tr  # d/dt of v (3 s^2 - 2 s^3)
    T_load = TL * s * s * (3 - 2 * s)
    rigid = J_eff * alpha1 + rho[2] * T_load
    # quasi-static lag of the compliant meshes: relative size ~ 2 zeta / (w_n T) + 1/(w_n T)^2 ~ 1e-3 of the
    # peak torque; tolerance 3e-3 of the peak
    assert_allclose(named(sim)["input_torque_Nmm"] * 1e-3, rigid, rtol=0, atol=3e-3 * rigid.max())
    # stage 2 carries the output shaft's inertia and the load: F_bt2 r_g2 = J_3 alpha_3 + T_L
    f_bt2 = (J[2] * rho[2] * alpha1 + T_load) / r2g
    ft2 = named(sim)["stage2_tangential_N"]
    assert_allclose(ft2, f_bt2 * math.cos(20.3 * DEG), rtol=0, atol=3e-3 * f_bt2.max())


# ---------------------------------------------------------------- damping never creates energy
@given(c=st.one_of(st.just(0.0), st.floats(1e2, 1e5)), k_mm=st.floats(1e5, 1e7), e=st.floats(1.0, 2.0),
       jp=st.floats(0.05, 5.0), jg=st.floats(0.5, 50.0), p0=st.floats(1e-6, 5e-5))
@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])
def test_free_vibration_never_gains_energy(c, k_mm, e, jp, jg, p0):
    # Free train: torque drive with zero torque, zero load; the mesh starts compressed by p0 with both
    # shafts at the nominal speed. With j = 0 both flanks touch at h = 0, so it vibrates through h = 0.
    # E = 0.5 (J_p w_p^2 + J_g w_g^2) + K |p|^(e+1)/(e+1) never grows (damping and the clamp only remove
    # energy), is conserved without damping; J_p w_p / r_bp + J_g w_g / r_bg is conserved (the mesh force
    # acts on both shafts along one line: J_p w_p' = -r_bp F, J_g w_g' = r_bg F).
    K = k_mm * 1e3**e  # K in N/mm^e (1e5 ... 1e7, the range of steel meshes) -> N/m^e
    spec = ModelSpec((mesh(stiffness_N_m_e=K, exponent=e, damping_Ns_m=c, full_damping_m=2e-5),), (jp, jg),
                     DriveSpec("torque", 60.0, 0.0, 0.0), LoadSpec(0.0))
    model = TorsionalModel(spec)
    y0 = model.initial_state()
    y0[0] = p0 / CB
    kn = e * K * p0 ** (e - 1)  # linearised at p0: sets the run length (~8 periods)
    w = math.sqrt(kn * CB**2 * (R_P**2 / jp + R_G**2 / jg))
    sim = simulate_model(model, duration_s=8 * 2 * math.pi / w, steps=800, method="DOP853", rtol=1e-10, y0=y0)
    wp, wg = speeds_rad_s(sim, 2)
    p = np.abs(named(sim)["stage1_penetration_mm"]) * 1e-3
    energy = 0.5 * (jp * wp**2 + jg * wg**2) + K * p ** (e + 1) / (e + 1)
    # E is ~0.5 J w^2 ~ 1e3-1e4 J of rigid rotation plus the vibration; the global error of an rtol-controlled
    # run grows with its step count (hypothesis found 1.4e-8 E at rtol 1e-9), so rtol 1e-10 keeps drift < 1e-8 E
    assert np.all(np.diff(energy) <= 1e-8 * energy[0])
    if c == 0.0:
        assert_allclose(energy, energy[0], rtol=1e-8)
    assert_allclose(jp * wp / R_P + jg * wg / R_G, jp * wp[0] / R_P + jg * wg[0] / R_G, rtol=1e-9)
    assert sim.energy.residual_relative < 1e-7
    assert sim.energy.damping_loss_J >= -1e-9 * energy[0]


# --------------------------------------------------------------------------------- backlash rattle
def test_backlash_rattle_touches_both_flanks():
    # Zero load, zero input torque, free train, backlash j = 0.1 mm; the mesh starts centred in the gap
    # with the pinion closing at v = 0.05 m/s along the line of action. Free flight until the normal
    # approach reaches j/2: t1 = (j/2) / (v cos(beta_b)); the drive flank is hit first, the damped
    # impact throws the gear ahead, it crosses the gap and hits the back flank, and so on.
    j, v = 1e-4, 0.05
    spec = ModelSpec((mesh(stiffness_N_m_e=2e10, exponent=1.5, damping_Ns_m=2e3, full_damping_m=5e-6, backlash_m=j),),
                     (0.3, 2.5), DriveSpec("torque", 60.0, 0.0, 0.0), LoadSpec(0.0))
    model = TorsionalModel(spec)
    y0 = model.initial_state()
    y0[2] = (R_P * 60.0 - v) / R_G  # the gear lags: delta' = r_bp w_p - r_bg w_g = v
    sim = simulate_model(model, duration_s=0.02, steps=4000, method="DOP853", rtol=1e-9, y0=y0)
    t, pen = sim.time_s, named(sim)["stage1_penetration_mm"]
    ft = named(sim)["stage1_tangential_N"]
    t1 = (j / 2) / (v * CB)
    first = t[np.nonzero(pen)[0][0]]
    assert t1 <= first <= t1 + (t[1] - t[0]) + 1e-12  # first contact in the sample after t1
    assert pen[np.nonzero(pen)[0][0]] > 0  # ... on the drive flank
    assert np.any(pen > 0) and np.any(pen < 0)  # both flanks
    assert np.all(ft[pen == 0] == 0) and np.all(ft * pen >= 0)  # no force in the gap, never tensile
    wp, wg = speeds_rad_s(sim, 2)
    assert_allclose(0.3 * wp / R_P + 2.5 * wg / R_G, 0.3 * 60 / R_P + 2.5 * y0[2] / R_G, rtol=1e-10)
    # the impacts are damped: kinetic + elastic energy never grows and ends below its start
    p = np.abs(pen) * 1e-3
    energy = 0.5 * (0.3 * wp**2 + 2.5 * wg**2) + 2e10 * p**2.5 / 2.5
    assert np.all(np.diff(energy) <= 1e-9 * energy[0]) and energy[-1] < energy[0]
    assert sim.energy.damping_loss_J > 0


# ------------------------------------------------------------------- time-varying mesh stiffness
@pytest.mark.parametrize("overlap", [0.0, 0.45])
def test_time_varying_stiffness_excites_the_mesh_frequency(overlap):
    # Pinion at 5 rev/s with z_p = 20: f_z = 100 Hz, well above the mesh mode (w_n / 2 pi ~ 23 Hz, 20 %
    # damped): the heavy gear turns almost uniformly, so the deflection stays near its mean and the force
    # follows the stiffness, F ~ k(t) delta_mean. The stiffness follows the contact-line length (spur: a
    # 1-2 pair rectangular wave, lines at f_z / n; helical eps_beta 0.45: a trapezoid): the force spectrum
    # peaks at f_z. (Below resonance the force would instead follow delta'' and favour high harmonics.)
    zp, n_p = 20, 5.0
    f_z = zp * n_p
    k_n, J_g, T = 2e8, 200.0, 300.0
    k_t = k_n * CB**2
    w_n = math.sqrt(k_t * R_G**2 / J_g)
    c = 2 * 0.2 * math.sqrt(k_t * J_g / R_G**2) / CB**2
    spec = ModelSpec((mesh(stiffness_N_m_e=k_n, damping_Ns_m=c, full_damping_m=1e-9, time_varying=True,
                           overlap_ratio=overlap, pinion_teeth=zp),), (0.3, J_g),
                     DriveSpec("speed", 2 * math.pi * n_p), LoadSpec(T))
    model = TorsionalModel(spec)
    y0 = model.initial_state()
    y0[0] = T / (R_G * k_t)  # start at the mean static deflection
    sim = simulate_model(model, duration_s=1.0, steps=4000, method="auto", rtol=1e-7, y0=y0)
    lo, hi = sim.window_s
    assert_allclose([lo, hi], [0.2, 1.0], rtol=1e-12)  # no ramps: 20 % of the run settles
    mask = sim.time_s >= lo - 1e-12
    f = named(sim)["stage1_tangential_N"][mask]
    dt = sim.time_s[1] - sim.time_s[0]
    spectrum = np.abs(np.fft.rfft((f - f.mean()) * np.hanning(f.size)))
    freqs = np.fft.rfftfreq(f.size, dt)
    peak = freqs[1 + np.argmax(spectrum[1:])]
    assert abs(peak - f_z) <= freqs[1]  # within one frequency bin (1.25 Hz)
    assert sim.stages[0].tangential_N.std > 1e-3 * sim.stages[0].tangential_N.mean  # a real fluctuation
    assert_allclose(sim.stages[0].tangential_N.mean, T / R_G * math.cos(20.3 * DEG), rtol=5e-3)
    assert sim.energy.residual_relative < 1e-6  # parametric work accounted for
    assert f_z > 3 * w_n / (2 * math.pi)  # (the scene stays above resonance, as designed)
