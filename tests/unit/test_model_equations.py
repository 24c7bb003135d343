"""The generated equations: analytic Jacobian against finite differences, the generated RHS against
the IMPACT law written out by hand in this test, the STEP drive profile, and forces
that are never tensile. Scenes are built from plain parameters (no design needed)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose

from gearcli.model import DriveSpec, LoadSpec, MeshSpec, ModelSpec, TorsionalModel
from gearcli.model.outputs import sample
from gearcli.model.step import ramp, ramp_motion

ROOT = Path(__file__).resolve().parents[2]


def mesh(**kw) -> MeshSpec:
    base = dict(base_radius_pinion_m=0.06, base_radius_gear_m=0.15, base_helix_angle_rad=math.radians(11.0),
                transverse_pressure_angle_rad=math.radians(20.4), helix_angle_rad=math.radians(11.7),
                stiffness_N_m_e=4.0e10, exponent=1.5, damping_Ns_m=5.0e4, full_damping_m=1.0e-4,
                contact_ratio=1.6, overlap_ratio=0.7, pinion_teeth=21, normal_module_m=0.006)
    base.update(kw)
    return MeshSpec(**base)


def spec(meshes, inertias, drive="speed", ramp_s=0.1, load=500.0, torque=0.0) -> ModelSpec:
    return ModelSpec(tuple(meshes), tuple(inertias), DriveSpec(drive, 60.0, ramp_s, torque), LoadSpec(load, 0.05))


SCENES = {
    "hertz, damped, speed drive": spec([mesh(), mesh(base_radius_pinion_m=0.08, base_radius_gear_m=0.2)],
                                       [0.5, 8.0, 40.0]),
    "linear, undamped, torque drive": spec([mesh(exponent=1.0, stiffness_N_m_e=3e8, damping_Ns_m=0.0)], [0.5, 8.0],
                                           drive="torque", torque=200.0),
    "backlash, e = 2.2": spec([mesh(backlash_m=4e-5, exponent=2.2, stiffness_N_m_e=1e15)], [0.5, 8.0]),
    "time-varying helical, torque drive, backlash": spec(
        [mesh(time_varying=True, backlash_m=2e-5), mesh(time_varying=True, contact_ratio=1.45, overlap_ratio=1.3,
                                                        pinion_teeth=17, base_radius_pinion_m=0.08)],
        [0.5, 8.0, 40.0], drive="torque", torque=150.0),
    "time-varying spur (steps), speed drive": spec([mesh(time_varying=True, overlap_ratio=0.0, base_helix_angle_rad=0.0)],
                                                   [0.5, 8.0], ramp_s=0.0),
}


def contact_state(model: TorsionalModel, rng: np.random.Generator, flanks) -> np.ndarray:
    """A state with every mesh in contact on the given flank, p in (0.1, 0.9) d (clear of the damping
    ramp's ends), speeds near nominal, energies arbitrary."""
    lay = model.layout
    y = model.initial_state()
    for i in lay.free_bodies:
        y[lay.i_omega(i)] = (1.0 + 0.05 * rng.standard_normal()) * model.spec.speed_ratios[i] * 60.0
    for k, m in enumerate(model.spec.meshes):
        p = rng.uniform(0.1, 0.9) * m.full_damping_m
        h = flanks[k] * (p + 0.5 * m.backlash_m)
        y[k] = h / m.cos_beta_b
    if lay.has_theta_state:
        y[lay.i_theta] = rng.uniform(0, 50.0)
    y[lay.i_quad:] = rng.uniform(-10, 10, lay.n_quad)
    return y


def fd_jacobian(model: TorsionalModel, t: float, y: np.ndarray, rel_step: float = 1e-6) -> np.ndarray:
    """Central differences of the right-hand side, each state stepped by ``rel_step`` of its scale (every
    connector's deflection, every free body's speed, 1 for the angle and quadrature states)."""
    lay = model.layout
    scale = np.concatenate([model.deflection_scales(), model.speed_scales_rad_s(),
                            np.ones(model.n_states - lay.n_conn - len(lay.free_bodies))])
    J = np.empty((y.size, y.size))
    for j in range(y.size):
        h = rel_step * scale[j]
        yp, ym = y.copy(), y.copy()
        yp[j] += h
        ym[j] -= h
        J[:, j] = (model.rhs(t, yp) - model.rhs(t, ym)) / (2 * h)
    return J


@pytest.mark.parametrize("name", SCENES)
def test_jacobian_matches_central_differences(name):
    model = TorsionalModel(SCENES[name])
    rng = np.random.default_rng(7)
    flank_sets = [(1,) * model.layout.n_conn, (-1,) * model.layout.n_conn,
                  tuple((-1) ** k for k in range(model.layout.n_conn))]
    for flanks in flank_sets:
        for t in (0.013, 0.07, 0.3):
            y = contact_state(model, rng, flanks)
            Ja, Jf = model.jac(t, y), fd_jacobian(model, t, y)
            # compare column-scaled rows: |Ja - Jf|_ij s_j <= 1e-6 max_j |Jf_ij s_j|. Central differences
            # with h = 1e-6 x the state scale are accurate to ~(h/scale)^2 ~ 1e-12 on smooth pieces plus
            # rounding ~ 1e-16/1e-6 = 1e-10 of the row scale; 1e-6 leaves room for the curvature of p^e.
            scale = np.abs(Jf).max(axis=1, keepdims=True) + 1e-300
            assert_allclose(Ja / scale, Jf / scale, atol=1e-6, err_msg=f"{name}, flanks {flanks}, t {t}")


def test_jacobian_of_a_clamped_mesh():
    # separating fast: the damping pull exceeds the spring (F_n clamped at 0); rows of the force and the
    # damping-loss integrand must follow the clamp
    model = TorsionalModel(SCENES["hertz, damped, speed drive"])
    y = contact_state(model, np.random.default_rng(3), (1, 1))
    y[model.layout.i_omega(1)] *= 1.5  # gear 1 runs away from its pinion: p' << 0
    f = model.rhs(0.3, y)
    Ja, Jf = model.jac(0.3, y), fd_jacobian(model, 0.3, y)
    scale = np.abs(Jf).max(axis=1, keepdims=True) + 1e-300
    assert_allclose(Ja / scale, Jf / scale, atol=1e-6)
    assert f[model.layout.i_quad + 2] > 0  # the clamp removes energy (damping loss grows)


@pytest.mark.parametrize("name", SCENES)
def test_generated_rhs_agrees_with_the_numpy_force_law(name):
    model = TorsionalModel(SCENES[name])
    lay, sp = model.layout, model.spec
    rng = np.random.default_rng(11)
    for flanks in [(1,) * lay.n_conn, (-1,) * lay.n_conn]:
        for t in (0.0, 0.02, 0.5):
            y = contact_state(model, rng, flanks)
            f = model.rhs(t, y)
            s = sample(lay, np.array([t]), y[:, None])
            F = [ms.line_force_N[0] for ms in s.meshes]
            w = s.omega_rad_s[:, 0]
            for k, m in enumerate(sp.meshes):  # kinematics of the deflections
                assert_allclose(f[k], m.base_radius_pinion_m * w[k] - m.base_radius_gear_m * w[k + 1], rtol=1e-12)
            for i in lay.free_bodies:  # J w' = r_bg F_{i-1} - r_bp F_i (+ T_in) (- T_L)
                torque = (sp.meshes[i - 1].base_radius_gear_m * F[i - 1] if i > 0 else s.input_torque_Nm[0]) \
                    - (sp.meshes[i].base_radius_pinion_m * F[i] if i < lay.n_conn else s.load_torque_Nm[0])
                assert_allclose(f[lay.i_omega(i)] * sp.inertias_kg_m2[i], torque, rtol=1e-9, atol=1e-9 * max(map(abs, F)))
            q = lay.i_quad
            assert_allclose(f[q], s.input_torque_Nm[0] * w[0], rtol=1e-9, atol=1e-9)
            assert_allclose(f[q + 1], s.load_torque_Nm[0] * w[-1], rtol=1e-12, atol=1e-12)
            damping_power = 0.0
            for k, m in enumerate(sp.meshes):  # the IMPACT law by hand: F_n = K g p^e + STEP(p, 0, 0, d, C) p'
                sign = flanks[k]
                p = sign * m.cos_beta_b * y[k] - 0.5 * m.backlash_m
                pd = sign * m.cos_beta_b * f[k]
                x = min(p / m.full_damping_m, 1.0)
                c = m.damping_Ns_m * x * x * (3 - 2 * x)
                fe = F[k] / (sign * m.cos_beta_b) - c * pd if F[k] != 0 else None
                if not m.time_varying:  # constant K: the elastic part is known in closed form
                    fe_hand = m.stiffness_N_m_e * p**m.exponent
                    assert_allclose(max(fe_hand + c * pd, 0.0), abs(F[k]) / m.cos_beta_b, rtol=1e-9)
                    fe = fe_hand
                fn = abs(F[k]) / m.cos_beta_b
                damping_power += (fn - fe) * pd
            assert_allclose(f[q + 2], damping_power, rtol=1e-9, atol=1e-9)


@given(t=st.floats(0.0, 0.6), ramp_s=st.sampled_from([0.0, 0.05, 0.18]))
@settings(max_examples=40, deadline=None)
def test_step_profile_angle_is_the_integral_of_the_speed(t, ramp_s):
    # the exact angle of the STEP speed against a fine trapezoid of the speed; and alpha = d(omega)/dt
    angle, omega, alpha = ramp_motion(t, ramp_s, 62.83)
    ts = np.linspace(0.0, t, 20001)
    speed = ramp(ts, ramp_s, 62.83) * np.ones_like(ts)
    trapz = float(np.sum(0.5 * (speed[1:] + speed[:-1]) * np.diff(ts))) if t > 0 else 0.0
    # trapezoid error <= T dt^2 max|omega''| / 12 = 0.6 (3e-5)^2 (6 x 62.83 / 0.05^2) / 12 ~ 7e-6 rad
    assert_allclose(angle, trapz, atol=1e-5)
    assert_allclose(omega, ramp(t, ramp_s, 62.83), rtol=1e-14)
    dt = 1e-7
    if ramp_s > 0 and dt < t < ramp_s - dt:
        slope = (ramp(t + dt, ramp_s, 62.83) - ramp(t - dt, ramp_s, 62.83)) / (2 * dt)
        assert_allclose(alpha, slope, rtol=1e-6, atol=1e-6)
    if ramp_s > 0:  # peak acceleration 1.5 v / T at T/2
        assert_allclose(ramp_motion(ramp_s / 2, ramp_s, 62.83)[2], 1.5 * 62.83 / ramp_s, rtol=1e-14)


@given(d=st.floats(-2e-4, 2e-4), rate=st.floats(-5.0, 5.0), c=st.floats(0.0, 1e6), e=st.floats(1.0, 3.0),
       j=st.sampled_from([0.0, 5e-5]))
@settings(max_examples=150, deadline=None)
def test_forces_are_never_tensile(d, rate, c, e, j):
    # F_n >= 0 always; F_bt has the sign of the flank in contact, and is 0 inside the backlash
    model = TorsionalModel(spec([mesh(damping_Ns_m=c, exponent=e, stiffness_N_m_e=1e6 * 1e3 ** e, backlash_m=j)],
                                [0.5, 8.0], ramp_s=0.0))
    y = model.initial_state()
    y[0] = d
    y[1] += rate / model.spec.meshes[0].base_radius_gear_m  # relative speed: the gear runs faster or slower
    s = sample(model.layout, np.array([0.2]), y[:, None])
    ms = s.meshes[0]
    assert ms.line_force_N[0] * math.copysign(1.0, model.spec.meshes[0].cos_beta_b * d or 1.0) >= 0.0
    assert ms.line_force_N[0] * ms.penetration_m[0] >= 0.0
    h = model.spec.meshes[0].cos_beta_b * d
    if abs(h) <= j / 2:
        assert ms.line_force_N[0] == 0.0
    # and the generated RHS sees the same force: J_g w_g' = r_bg F_bt - T_L
    f = model.rhs(0.2, y)
    torque = f[model.layout.i_omega(1)] * 8.0 + model.spec.load.torque_Nm
    assert_allclose(torque, model.spec.meshes[0].base_radius_gear_m * ms.line_force_N[0], rtol=1e-9, atol=1e-9)


def test_initial_state_is_rigid_body_consistent():
    for drive, ramp_s, w1 in (("speed", 0.1, 0.0), ("speed", 0.0, 60.0), ("torque", 0.1, 60.0)):
        sp = spec([mesh(), mesh(base_radius_pinion_m=0.08, base_radius_gear_m=0.2)], [0.5, 8.0, 40.0],
                  drive=drive, ramp_s=ramp_s, torque=1.0)
        model = TorsionalModel(sp)
        y0 = model.initial_state()
        assert_allclose(y0[:2], 0.0)  # undeflected
        w = sample(model.layout, np.array([0.0]), y0[:, None]).omega_rad_s[:, 0]
        assert_allclose(w, w1 * np.array([1.0, 0.06 / 0.15, 0.06 / 0.15 * 0.08 / 0.2]), rtol=1e-14)
        assert_allclose(model.rhs(0.0, y0)[:2], 0.0, atol=1e-12)  # no relative motion at the start


def test_generated_code_leaves_out_what_the_scene_does_not_use():
    plain = TorsionalModel(spec([mesh(damping_Ns_m=0.0, exponent=1.0)], [0.5, 8.0], ramp_s=0.0, load=0.0)).source
    assert "TL" not in plain and "Tin" not in plain and "th0" not in plain and "_power0" not in plain
    full = TorsionalModel(SCENES["time-varying helical, torque drive, backlash"]).source
    assert "th0" in full and "Tin" in full and "_power1" in full  # phase, input torque, energy-row partials


def test_model_from_the_seed_design_file():
    from gearcli.config import load_design
    from gearcli.design import compute_design
    from gearcli.scene import build_model

    loaded = load_design(str(ROOT / "configs" / "concrete_mixer.toml"), [])
    design = compute_design(loaded.design)
    model = build_model(loaded.design, design)
    m0 = model.spec.meshes[0]
    # K = 1.4392e6 N/mm^1.5 -> x 1000^1.5 N/m^1.5; 50 N s/mm -> 5e4 N s/m; 0.1 mm -> 1e-4 m
    assert_allclose(m0.stiffness_N_m_e, design.stages[0].hertz_stiffness_N_mm1_5 * 1000**1.5, rtol=1e-14)
    assert_allclose([m0.damping_Ns_m, m0.full_damping_m], [5e4, 1e-4], rtol=1e-14)
    assert_allclose(model.spec.inertias_kg_m2, [s.inertia_kg_m2 for s in design.shafts], rtol=1e-14)
    # speed ratio of the train from base radii = 1 / total ratio (base radii are proportional to z)
    assert_allclose(model.spec.speed_ratios[-1], 6069 / 135150, rtol=1e-12)
    # the static deflection scale of stage 1: h0 / cos(beta_b), h0 = 0.012510 mm from the design
    assert_allclose(model.deflection_scales_m()[0], design.stages[0].static_approach_mm * 1e-3 / m0.cos_beta_b,
                    rtol=1e-6)
    Ja, Jf = model.jac(0.09, _loaded_state(model)), fd_jacobian(model, 0.09, _loaded_state(model))
    scale = np.abs(Jf).max(axis=1, keepdims=True) + 1e-300
    assert_allclose(Ja / scale, Jf / scale, atol=1e-6)


def _loaded_state(model):
    y = model.initial_state()
    y[:3] = model.deflection_scales_m() * 1.7
    y[3:6] = np.array(model.spec.speed_ratios[1:]) * 30.0
    return y
