"""Mesh losses are an element hook (:data:`gearcli.model.elements.LOSS_HOOK`): a test-only coupling that passes on
``eta`` of its torque (``lossy_coupling.py``, beside this file) loses power through the assembly, the generated
Python and the energy quadratures with nothing in gearcli edited for it.

References: the loss law written out by hand below (the module text of ``lossy_coupling``), the scatter of
an element's force to its bodies (``-s_j r_j F`` on body j, here the side forces), the loss power
``v_a (f_a - f) - v_b (f_b - f)``; central finite differences of the generated right-hand side for its
Jacobian; the energy balance of a run (input = load + damping + kinetic + potential, each its own quadrature).
"""

from __future__ import annotations

import dataclasses
import math
import types
from pathlib import Path

import lossy_coupling
import numpy as np
import pytest
from numpy.testing import assert_allclose

from gearcli import api
from gearcli.model import TorsionalModel, elements

CONFIGS = Path(__file__).resolve().parents[2] / "configs"
K, C = 2.0e5, 5.0  # N m/rad, N m s/rad: a coupling in parallel with the drivetrain's own input coupling


@pytest.fixture(scope="module")
def coupling() -> elements.ElementType:
    return elements.register(lossy_coupling)


def test_an_element_with_part_of_the_hook_is_refused():
    partial = types.ModuleType("half_lossy")
    for name in elements.PROTOCOL:
        setattr(partial, name, getattr(lossy_coupling, name))
    partial.NAME, partial.lossy = "half_lossy", lossy_coupling.lossy
    with pytest.raises(TypeError, match="part of the loss hook"):
        elements.register(partial)


def _spec(eta: float, coupling: elements.ElementType) -> api.ModelSpec:
    loaded, design = api.load_and_design(str(CONFIGS / "concrete_mixer_drivetrain.toml"))
    spec = api.model_spec(loaded.design, design)
    assert spec.motor is not None  # body 0 the motor, body 1 shaft 1: both free
    return dataclasses.replace(spec, elements=(api.ElementSpec(coupling.name, (0, 1), (1.0, 1.0), (K, C, eta),
                                                               "lossy coupling"),))


def test_the_side_forces_and_the_loss_power_by_hand(coupling):
    eta = 0.9
    lossy, lossless = TorsionalModel(_spec(eta, coupling)), TorsionalModel(_spec(1.0, coupling))
    lay = lossy.layout
    c = next(i for i, x in enumerate(lay.connectors) if x.label == "lossy coupling")
    x = lay.connectors[c]
    assert x.lossy and not lossless.layout.connectors[c].lossy
    # the assembly's power scale: LOSS_WIDTH x the static torque at body 1 x the motor's nominal speed
    spec = lay.spec
    W = 1e-3 * abs(spec.load.torque_Nm * lay.bodies[-1].ratio / lay.bodies[1].ratio) * abs(
        lay.bodies[0].ratio * spec.drive.speed_rad_s)
    assert_allclose(x.params[lossy_coupling.I_LW], W, rtol=1e-12)
    st = lay.state
    t = max(spec.drive.ramp_s, spec.load.ramp_s) + 0.1  # past the ramps: a speed-driven body 0 turns at its speed
    rng = np.random.default_rng(5)
    for _ in range(5):
        y = lossy.initial_state()
        y[st.deflections] += rng.normal(scale=1e-4, size=st.n_conn)
        for b in lay.free_bodies:  # about the nominal speeds (the initial state starts from rest)
            y[st.omega(b)] = lay.bodies[b].ratio * spec.drive.speed_rad_s * (1.0 + 0.01 * rng.normal())
        w0 = spec.drive.speed_rad_s if st.omega(0) is None else y[st.omega(0)]
        w1 = y[st.omega(1)]
        d, dd = y[st.delta(c)], w0 - w1
        f = K * d + C * dd
        s = math.tanh(f * 0.5 * (w0 + w1) / W)
        fa, fb = f * (1 - 0.5 * (1 - eta) * (1 - s)), f * (1 - 0.5 * (1 - eta) * (1 + s))
        diff = np.asarray(lossy.rhs(t, y)) - np.asarray(lossless.rhs(t, y))
        expected = np.zeros(st.n_states)
        if st.omega(0) is None:  # the drive supplies body 0's reaction: f_a instead of f, at w0
            expected[st.quadrature("input_work_J")] = (fa - f) * w0
        else:  # body 0 takes -f_a
            expected[st.omega(0)] = -(fa - f) / lay.inertias[0]
        expected[st.omega(1)] = (fb - f) / lay.inertias[1]  # body 1 takes +f_b
        expected[st.quadrature("damping_loss_J")] = w0 * (fa - f) - w1 * (fb - f)
        scale = np.abs(np.asarray(lossless.rhs(t, y))).max()
        assert_allclose(diff, expected, rtol=1e-7, atol=1e-12 * scale)  # differences of sums of ~1e3 terms
        assert expected[st.quadrature("damping_loss_J")] > 0.0  # a loss never feeds power in


def test_the_generated_jacobian_of_the_lossy_element_by_finite_differences(coupling):
    model = TorsionalModel(_spec(0.85, coupling))
    st = model.layout.state
    y = model.initial_state()
    y[st.deflections] += 1e-4
    for b in model.layout.free_bodies:
        y[st.omega(b)] = model.layout.bodies[b].ratio * model.spec.drive.speed_rad_s * 1.01
    t = max(model.spec.drive.ramp_s, model.spec.load.ramp_s) + 0.1
    J = np.asarray(model.jac(t, y))
    for col in range(st.i_quad):
        h = 1e-7 * max(abs(y[col]), 1e-3)
        yp, ym = y.copy(), y.copy()
        yp[col] += h
        ym[col] -= h
        fd = (np.asarray(model.rhs(t, yp)) - np.asarray(model.rhs(t, ym))) / (2 * h)
        assert_allclose(J[:, col], fd, rtol=1e-5, atol=1e-6 * (np.abs(fd).max() + 1.0))  # central differences


def test_a_run_with_the_lossy_coupling_closes_its_energy_balance(coupling):
    loaded, _ = api.load_and_design(str(CONFIGS / "concrete_mixer_drivetrain.toml"))
    duration = loaded.design.simulation.duration_s
    runs = [api.simulate_spec(_spec(eta, coupling), duration_s=duration, steps=3000, method="DOP853", rtol=1e-8,
                              engine="python") for eta in (1.0, 0.8)]
    lossless, lossy = runs
    assert abs(lossy.energy.residual_relative) < 1e-9  # the side forces' work is all in the quadratures
    assert lossy.energy.damping_loss_J > lossless.energy.damping_loss_J  # and the loss is counted as dissipation
