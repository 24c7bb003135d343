"""Mesh excitation in the generated equations: the analytic Jacobian against central differences with
every excitation feature on (transmission error, stiffness harmonics on top of time-varying contact lines,
viscous damping ratio, input torque ripple, load fluctuation), the force law against the Kahraman-Singh
law written out by hand, and the viscous coefficient c = 2 zeta sqrt(k m_e) from the chain's inertias."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose
from test_model_equations import fd_jacobian, mesh

from gearcli.model import (
    CoupledInertia,
    DriveSpec,
    FlexibleShaft,
    LoadSpec,
    ModelSpec,
    SpringSpec,
    TorsionalModel,
)
from gearcli.model.elements import mesh as mesh_el
from gearcli.model.outputs import sample

TE = dict(transmission_error_m=(8e-6, 3e-6, 1e-6), transmission_error_phase_rad=(0.3, -1.1))
KS = dict(stiffness_harmonics=(0.15, 0.05), stiffness_harmonics_phase_rad=(0.7,))
SCENES = {
    "TE + harmonics + time-varying, IMPACT, torque drive with ripple, load fluctuation": ModelSpec(
        (mesh(time_varying=True, backlash_m=2e-5, **TE, **KS),
         mesh(pinion_teeth=17, base_radius_pinion_m=0.08, **TE)), (0.5, 8.0, 40.0),
        DriveSpec("torque", 60.0, 0.1, 150.0, ripple=((0.1, 2.0), (0.03, 6.0))),
        LoadSpec(500.0, 0.05, fluctuation=((0.2, 3.0),))),
    "TE + harmonics, viscous, speed drive, load fluctuation": ModelSpec(
        (mesh(damping_ratio=0.07, backlash_m=3e-5, exponent=1.0, stiffness_N_m_e=4e8, **TE, **KS),
         mesh(damping_ratio=0.05, pinion_teeth=17, base_radius_pinion_m=0.08, **TE)), (0.5, 8.0, 40.0),
        DriveSpec("speed", 60.0, 0.1), LoadSpec(500.0, 0.05, fluctuation=((0.2, 3.0), (0.05, 40.0)))),
    "drivetrain: motor, flexible shaft, drum; TE on both meshes, speed drive": ModelSpec(
        (mesh(damping_ratio=0.05, exponent=1.0, stiffness_N_m_e=4e8, **TE),
         mesh(pinion_teeth=17, base_radius_pinion_m=0.08, **TE, **KS)), (0.5, 8.0, 40.0),
        DriveSpec("speed", 60.0, 0.1), LoadSpec(500.0, 0.05),
        motor=CoupledInertia(0.2, SpringSpec(3e4, 5.0)), drum=CoupledInertia(300.0, SpringSpec(2e6, 50.0)),
        shafts=(FlexibleShaft(SpringSpec(5e5, 10.0), 4.0),)),
    "TE only, viscous, torque drive, ripple": ModelSpec(
        (mesh(damping_ratio=0.1, **TE),), (0.5, 8.0),
        DriveSpec("torque", 60.0, 0.0, 200.0, ripple=((0.2, 1.0),)), LoadSpec(400.0)),
}


def state(model: TorsionalModel, rng: np.random.Generator, flank: int, gap: bool = False) -> np.ndarray:
    """Every mesh on the given flank (or inside its gap), p clear of the damping ramp's ends, speeds near
    nominal, the input angle arbitrary."""
    lay = model.layout
    y = model.initial_state()
    for i in lay.free_bodies:
        y[lay.i_omega(i)] = (1.0 + 0.05 * rng.standard_normal()) * lay.bodies[i].ratio * 60.0
    for c, m in zip(lay.stage_conn, model.spec.meshes, strict=True):
        p = 0.0 if gap else rng.uniform(0.1, 0.9) * m.full_damping_m
        y[c] = flank * (p + 0.5 * m.backlash_m) / m.cos_beta_b  # about delta; the TE moves q around it
    for c, x in enumerate(lay.connectors):
        if x.kind == 0:  # a spring: some twist
            y[c] = rng.uniform(-1, 1) * 1e-3
    if lay.i_theta is not None:
        y[lay.i_theta] = rng.uniform(0, 50.0)
    y[lay.i_quad:] = rng.uniform(-10, 10, lay.n_quad)
    return y


@pytest.mark.parametrize("name", SCENES)
def test_jacobian_with_excitation_matches_central_differences(name):
    model = TorsionalModel(SCENES[name])
    rng = np.random.default_rng(5)
    checked = 0
    for flank, gap in ((1, False), (-1, False), (1, True)):
        for t in (0.013, 0.07, 0.3):
            y = state(model, rng, flank, gap)
            Ja, Jf = model.jac(t, y), fd_jacobian(model, t, y, rel_step=1e-5)
            # central differences with h = 1e-5 x the state scale: ~1e-10 truncation on smooth pieces and
            # ~1e-11 rounding of the row scale on the dynamic rows, 1e-6 leaving room for the curvature of
            # p^e; the energy rows' integrands (c q'^2, F e' phi') are large products whose differences lose
            # ~5 more digits (measured: the FD value of d(c q'^2)/d delta drifts by 2e-5 between h = 1e-8 and
            # 1e-9 m while it agrees with the analytic one to 1e-8 at h = 1e-7 m), hence 1e-5 there.
            # A sample whose +-h straddles a contact edge has no derivative: skipped.
            scale = np.abs(Jf).max(axis=1, keepdims=True) + 1e-300
            tol = np.where(np.arange(y.size)[:, None] < model.layout.i_quad, 1e-6, 1e-5)
            if np.any(np.abs(Ja - Jf) / scale > tol) and _near_edge(model, t, y):
                continue
            bad = np.abs(Ja - Jf) / scale > tol
            assert not bad.any(), f"{name}, flank {flank}, gap {gap}, t {t}: {np.argwhere(bad)}, {Ja[bad]} vs {Jf[bad]}"
            checked += 1
    assert checked >= 6


def _near_edge(model, t, y) -> bool:
    """A mesh whose approach lies within the FD step of a gap edge, or a spur contact-line step."""
    s = sample(model.layout, np.array([t]), y[:, None])
    for x, cs in zip(model.layout.connectors, s.connectors, strict=True):
        if x.kind != 1:
            continue
        h = abs(x.params[mesh_el.I_CB] * cs.dte_m[0])
        if abs(h - x.params[mesh_el.I_HALF]) < 1e-8:
            return True
    return False


def test_the_rhs_follows_the_kahraman_singh_law_by_hand():
    # one viscous mesh, speed drive: F = cos(b) K (cos(b) q - j/2) + c q', q = delta - e(phi), with
    # e = sum e_j cos(j z theta + psi_j) and K (1 - sum s_j cos(j z theta + chi_j)), all written out here
    m = mesh(damping_ratio=0.07, backlash_m=3e-5, exponent=1.0, stiffness_N_m_e=4e8, **TE, **KS)
    model = TorsionalModel(ModelSpec((m,), (0.5, 8.0), DriveSpec("speed", 60.0, 0.0), LoadSpec(500.0)))
    lay = model.layout
    c = lay.connectors[0].params[mesh_el.I_CV]
    rng = np.random.default_rng(2)
    for _ in range(20):
        t = rng.uniform(0.0, 1.0)
        y = model.initial_state()
        y[0] = rng.uniform(-1, 1) * 6e-5
        y[1] = 60.0 * 0.06 / 0.15 * (1 + 0.01 * rng.standard_normal())
        th = 60.0 * t  # no ramp
        x = 21 * th
        e = 8e-6 * math.cos(x + 0.3) + 3e-6 * math.cos(2 * x - 1.1) + 1e-6 * math.cos(3 * x)
        de = -21 * 60.0 * (8e-6 * math.sin(x + 0.3) + 2 * 3e-6 * math.sin(2 * x - 1.1) + 3e-6 * math.sin(3 * x))
        K = 4e8 * (1 - 0.15 * math.cos(x + 0.7) - 0.05 * math.cos(2 * x))
        q = y[0] - e
        qd = 0.06 * 60.0 - 0.15 * y[1] - de
        cb = math.cos(math.radians(11.0))
        h = cb * q
        fe = cb * K * (h - 1.5e-5) if h > 1.5e-5 else (-cb * K * (-h - 1.5e-5) if h < -1.5e-5 else 0.0)
        F = fe + c * qd
        f = model.rhs(t, y)
        assert_allclose(f[1] * 8.0, 0.15 * F - 500.0, rtol=1e-9, atol=1e-9 * abs(F))


def test_viscous_coefficient_from_the_chain():
    # c = 2 zeta sqrt(k_lin m_e): k_lin = K (e = 1: the contract's 'K itself'); m_e = 1/(r_p^2/J_p + r_g^2/J_g) for a torque
    # drive, J_g / r_g^2 when the pinion's speed is prescribed
    for drive, m_e in (("torque", 1.0 / (0.06**2 / 0.5 + 0.15**2 / 8.0)), ("speed", 8.0 / 0.15**2)):
        m = mesh(damping_ratio=0.05, exponent=1.0, stiffness_N_m_e=4e8)
        model = TorsionalModel(ModelSpec((m,), (0.5, 8.0), DriveSpec(drive, 60.0, 0.0, 1.0), LoadSpec(500.0)))
        P = model.layout.connectors[0].params
        k = 4e8
        assert_allclose([P[mesh_el.I_KLIN], P[mesh_el.I_ME]], [k, m_e], rtol=1e-14)
        assert_allclose(P[mesh_el.I_CV], 2 * 0.05 * math.sqrt(k * m_e), rtol=1e-14)
    # Hertzian: k_lin = dF_n/dh = 1.5 K p0^0.5 at p0 = (F / cos(b) / K)^(2/3), F = T_L / r_g
    m = mesh(damping_ratio=0.05)
    model = TorsionalModel(ModelSpec((m,), (0.5, 8.0), DriveSpec("speed", 60.0), LoadSpec(500.0)))
    cb = math.cos(math.radians(11.0))
    p0 = (500.0 / 0.15 / cb / 4e10) ** (2 / 3)
    assert_allclose(model.layout.connectors[0].params[mesh_el.I_KLIN], 1.5 * 4e10 * p0**0.5, rtol=1e-12)


@pytest.mark.parametrize("name", SCENES)
def test_energy_balance_with_every_excitation(name):
    # W_in (drive + the TE's work) - W_load - E_damp - dKE - dU + parametric work = 0: the quadratures
    # integrate the actual (rippled, fluctuating) torques and the TE's power -F e' phi'. At rtol 1e-9 the
    # residual must be a small fraction of the damping loss, the smallest term of the balance (in the
    # viscous scenes the TE supplies most of it)
    from gearcli.simulate.solver import integrate

    model = TorsionalModel(SCENES[name])
    t = np.linspace(0.0, 0.25, 2001)
    it = integrate(model, t, "DOP853", 1e-9)
    assert it.status == 0, it.message
    en = model.energy(sample(model.layout, t, it.y), it.y)
    assert en.damping_loss_J > 1e-3 * max(abs(en.input_work_J), abs(en.load_work_J))
    assert abs(en.residual_J) < 1e-5 * en.damping_loss_J, en


def test_schema_harmonics_cap_is_the_model_row_width():
    from gearcli.config.schema import MAX_HARMONICS
    from gearcli.model.elements import N_HARM

    assert MAX_HARMONICS == N_HARM

