"""A new two-body element needs one module (``torsional_damper.py``, beside this file) and its registration.

The test uses the element API (:mod:`gearcli.model.elements`) and, to run scenes, the library facade
(:mod:`gearcli.api`); nothing in gearcli was edited for the damper. References: finite differences of the
damper's own law; dampers in parallel add (``c_1 delta' + c_2 delta' = (c_1 + c_2) delta'``); a damper that
only sees vibration (levers in the bodies' speed ratio) leaves the steady mean forces at the design's statics;
energy conservation.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest
import torsional_damper
from numpy.testing import assert_allclose

from gearcli import api
from gearcli.model import elements

CONFIGS = Path(__file__).resolve().parents[2] / "configs"


@pytest.fixture(scope="module")
def damper() -> elements.ElementType:
    return elements.register(torsional_damper)


def test_registration_gives_a_kind_and_checks_the_protocol(damper):
    assert elements.law_of(damper.kind) is torsional_damper
    assert elements.kind_of("test_torsional_damper") == damper.kind and damper.n_bodies == 2
    assert elements.register(torsional_damper) is damper  # idempotent
    assert not damper.compiled  # not compiled into the kernel: it runs on the Python engine
    incomplete = type(torsional_damper)("incomplete")
    incomplete.NAME = "incomplete"
    with pytest.raises(TypeError, match="lacks"):
        elements.register(incomplete)


def test_the_law_s_partials_and_power_by_finite_differences(damper):
    law = elements.law_of(damper.kind)
    P = law.pack(37.0)
    rng = np.random.default_rng(3)
    h = 1e-6
    for d, dd in rng.normal(size=(20, 2)):
        f, kd, kv, _, _, p_damp, _, _ = law.force(P, d, dd, 0.0, 0.0)
        assert_allclose(kd, (law.force(P, d + h, dd, 0, 0)[0] - law.force(P, d - h, dd, 0, 0)[0]) / (2 * h), atol=1e-6)
        assert_allclose(kv, (law.force(P, d, dd + h, 0, 0)[0] - law.force(P, d, dd - h, 0, 0)[0]) / (2 * h), rtol=1e-8)
        assert_allclose(p_damp, f * dd, rtol=1e-14)  # all its work is dissipated
        grad = law.power_gradient(P, d, dd, 0.0, 0.0)
        dp = (law.force(P, d, dd + h, 0, 0)[5] - law.force(P, d, dd - h, 0, 0)[5]) / (2 * h)
        assert_allclose(grad[1], dp, rtol=1e-7)
        assert law.potential(P, d, 0.0) == 0.0


def _drivetrain() -> tuple[api.ModelSpec, float]:
    loaded, design = api.load_and_design(str(CONFIGS / "concrete_mixer_drivetrain.toml"))
    sim = loaded.design.simulation
    return api.model_spec(loaded.design, design), sim.duration_s


def _run(spec: api.ModelSpec, duration_s: float):
    return api.simulate_spec(spec, duration_s=duration_s, steps=3000, method="DOP853", rtol=1e-8, engine="python")


@pytest.fixture(scope="module")
def drivetrain() -> tuple[api.ModelSpec, float, object]:
    """The drivetrain's spec, duration and its run without elements: the base every element test compares with
    (run once for the module; specs are frozen, each test replaces what it changes)."""
    spec, duration = _drivetrain()
    return spec, duration, _run(spec, duration)


def test_a_damper_beside_the_input_coupling_adds_its_damping(damper, drivetrain):
    spec, duration, a = drivetrain
    motor = spec.motor
    assert motor is not None and motor.coupling.damping_Nms_rad > 0
    c = motor.coupling.damping_Nms_rad
    undamped = dataclasses.replace(motor, coupling=dataclasses.replace(motor.coupling, damping_Nms_rad=0.0))
    split = dataclasses.replace(spec, motor=undamped,
                                elements=(api.ElementSpec(damper.name, (0, 1), (1.0, 1.0), c, "parallel damper"),))
    b = _run(split, duration)
    for sa, sb in zip(a.stages, b.stages, strict=True):
        scale = abs(sa.static_tangential_N)
        for stat in ("mean", "min", "max"):
            assert_allclose(getattr(sb.tangential_N, stat), getattr(sa.tangential_N, stat), atol=1e-5 * scale)
    assert_allclose(b.energy.damping_loss_J, a.energy.damping_loss_J, rtol=1e-5)


def test_a_damper_across_the_whole_train_conserves_energy(damper, drivetrain):
    """Shaft 1 to the drum, past every mesh: no chain joins these bodies. A force scattered to the wrong body or
    with the wrong lever would do work the damper's own dissipation does not account for: the balance (input =
    load + damping + kinetic + potential, each its own quadrature or state) would not close."""
    spec, duration, base = drivetrain
    ratio = spec.speed_ratios[-1]  # the last shaft's (and the drum's) nominal speed over shaft 1's
    # bodies: the motor 0, shaft 1 is body 1, a flexible shaft two bodies, the drum last
    drum = 1 + len(spec.meshes) + sum(s is not None for s in spec.shafts) + 1
    across = dataclasses.replace(spec, elements=(  # levers in the speed ratio: it sees the train's vibration only
        api.ElementSpec(damper.name, (1, drum), (1.0, 1.0 / ratio), 2000.0, "shaft 1 to drum damper"),))
    run = _run(across, duration)
    assert abs(run.energy.residual_relative) < 1e-9
    assert run.energy.damping_loss_J > 10 * base.energy.damping_loss_J  # it dissipates, much more than the rest
    assert_allclose(run.output_speed_deg_s / run.input_speed_deg_s, base.output_speed_deg_s / base.input_speed_deg_s,
                    rtol=1e-3)  # and leaves the kinematics alone


def test_a_three_body_element_scatters_to_its_three_bodies(drivetrain):
    """Motor, shaft 1 and the drum with levers that cancel on the rigid motion (r_a w_0 - r_b w_1 + r_c w_N = 0):
    it damps the train's vibration through three bodies at once, and the energy balance closes only if its
    force reaches each of them with its own lever."""
    import three_body_damper

    et = elements.register(three_body_damper)
    assert et.n_bodies == 3
    spec, duration, base = drivetrain
    ratio = spec.speed_ratios[-1]
    drum = 1 + len(spec.meshes) + sum(s is not None for s in spec.shafts) + 1
    # rigid: w_0 = w_1 = w, w_N = ratio w  ->  1.0 w - 2.0 w + (1 / ratio) ratio w = 0
    three = dataclasses.replace(spec, elements=(
        api.ElementSpec(et.name, (0, 1, drum), (1.0, 2.0, 1.0 / ratio), 500.0, "three-body damper"),))
    run = _run(three, duration)
    assert abs(run.energy.residual_relative) < 1e-9
    assert run.energy.damping_loss_J > base.energy.damping_loss_J
    assert_allclose(run.output_speed_deg_s / run.input_speed_deg_s, base.output_speed_deg_s / base.input_speed_deg_s,
                    rtol=1e-3)
