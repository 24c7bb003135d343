"""Continuation: the start state of a continued point (docs/sweeps.md, the continuation rule)."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_allclose

from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.scene import build_model
from gearcli.sweep.continuation import NO_RAMPS, continue_state

SEED = Path(__file__).resolve().parents[2] / "configs" / "concrete_mixer.toml"


def _model(*sets: str):
    cfg = load_design(str(SEED), list((*NO_RAMPS, *sets))).design
    return build_model(cfg, compute_design(cfg))


def _rates(model, y: np.ndarray, w_in: float) -> list[float]:
    """delta_c' = r_a w_a - r_b w_b, by hand from the speeds in y (the input body prescribed or free)."""
    lay = model.layout
    w = [w_in if lay.i_omega(i) is None else y[lay.i_omega(i)] for i in range(lay.n_bodies)]
    return [x.ra * w[x.a] - x.rb * w[x.b] for x in lay.connectors]


def test_speed_drive_keeps_deflections_and_their_rates_and_moves_the_speeds():
    old, new = _model("input.speed_rpm=600"), _model("input.speed_rpm=900")
    lay = old.layout
    y = old.initial_state()  # at rest on the rigid motion of 600 rpm (no ramps)
    y[:lay.n_conn] = [3e-5, -1e-6, 2e-6]
    deviation = 0.7
    y[lay.i_omega(1)] += deviation  # a vibration about the rigid speed
    y[lay.i_quad:] = 5.0
    y0 = continue_state(y, old, new)
    assert y0 is not None
    assert_allclose(y0[:lay.n_conn], y[:lay.n_conn], rtol=0, atol=0)
    w_old, w_new = 600 * 2 * np.pi / 60, 900 * 2 * np.pi / 60
    assert_allclose(_rates(new, y0, w_new), _rates(old, y, w_old), rtol=0, atol=1e-9)  # vibration carried over
    rigid_new = w_new * 21 / 51  # shaft 2's rigid speed at 900 rpm, by hand from the tooth counts
    assert_allclose(y0[lay.i_omega(1)], rigid_new + deviation, rtol=1e-9)
    assert_allclose(y0[lay.i_quad:], 0.0, atol=0)  # energy quadratures restart


def test_another_chain_starts_cold():
    old = _model()
    new = _model("stage.0.shaft.stiffness_Nm_rad=1e6")  # a flexible shaft: one more body and connector
    assert continue_state(old.initial_state(), old, new) is None


TE_SCENE = Path(__file__).resolve().parents[2] / "configs" / "spur_oscillator_te.toml"


def _te_run(sets: tuple[str, ...], duration_s: float, prev=None):
    """A run of the transmission-error oscillator (continued from ``prev`` when given), rtol 1e-10."""
    from gearcli.model import TorsionalModel
    from gearcli.scene import spec_from_design
    from gearcli.simulate.run import simulate_model
    from gearcli.sweep.continuation import Carried, carry_phases

    cfg = load_design(str(TE_SCENE), list(sets + (NO_RAMPS if prev else ()))).design
    spec = spec_from_design(cfg, compute_design(cfg))
    model = TorsionalModel(carry_phases(spec, prev) if prev else spec)
    y0 = continue_state(prev.state, prev.model, model, prev.time_s) if prev else None
    res = simulate_model(model, duration_s=duration_s, steps=int(duration_s * 40000), rtol=1e-10, y0=y0,
                         want_series=False)
    return res, Carried(model, res.final_state, res.final_time_s)


def test_continuing_at_the_same_speed_is_not_stopping():
    # the mesh phase z_p theta_p goes on from where the previous run ended: a run of 0.06 s continued for
    # 0.03 s ends where one run of 0.09 s ends (the transmission error would otherwise restart at phase 0
    # under a vibration that does not, and the end states would differ by the order of e = 5 um)
    _, first = _te_run((), 0.06)
    assert first.model.input_angle(first.time_s) > 0
    whole, _ = _te_run((), 0.09)
    _, second = _te_run((), 0.03, prev=first)
    assert_allclose(second.model.spec.drive.angle_rad, 1500 * 2 * np.pi / 60 * (0.06 - 0.02 / 2), rtol=1e-12)
    dyn = whole.final_state[:2]  # the mesh deflection (m) and the gear speed (rad/s)
    assert_allclose(second.state[0], dyn[0], rtol=0, atol=1e-11)  # 1e-6 of the 10 um static deflection
    assert_allclose(second.state[1], dyn[1], rtol=1e-10)


def test_a_continued_ramped_run_moves_the_speeds_from_its_end_not_its_start():
    # the first point of a branch starts at rest on its ramps: the rigid speed at its end is the nominal one
    old, new = _model("input.ramp_s=0.5", "input.speed_rpm=600"), _model("input.speed_rpm=900")
    lay = old.layout
    y = new.initial_state()
    y[lay.i_omega(1)] = 600 * 2 * np.pi / 60 * 21 / 51 + 0.3  # at the end of the old run: nominal + vibration
    y0 = continue_state(y, old, new, t_prev=2.0)
    assert_allclose(y0[lay.i_omega(1)], 900 * 2 * np.pi / 60 * 21 / 51 + 0.3, rtol=1e-12)


def _no_ramps(spec):
    import dataclasses

    return dataclasses.replace(spec, drive=dataclasses.replace(spec.drive, ramp_s=0.0),
                               load=dataclasses.replace(spec.load, ramp_s=0.0))


def _scipy_run(m, y0, t_end):
    """The end state of ``m`` from ``y0`` over [0, t_end], integrated by scipy's Radau directly."""
    from scipy.integrate import solve_ivp

    n = m.layout.state.i_quad  # the dynamic states (StateLayout.dynamic), the quadratures after them
    sol = solve_ivp(m.rhs, (0.0, t_end), y0, method="Radau", jac=m.jac, rtol=1e-9,
                    atol=np.r_[m.atol(1e-9)[:n], np.full(m.n_states - n, 1e20)])
    assert sol.success, sol.message
    return sol.y[:, -1]


@pytest.mark.parametrize("name", ["TE + harmonics + time-varying, IMPACT, torque drive with ripple, load fluctuation",
                                  "TE + harmonics, viscous, speed drive, load fluctuation"])
def test_continuing_keeps_the_ripple_and_the_load_fluctuation_in_phase(name):
    # model level: a torque drive with an input torque ripple (its angle is a state) and a load fluctuation
    # (a clock), and a speed drive with TE and fluctuation (an analytic angle); past the ramps, 0 -> T1 then
    # a continued model (no ramps, as a sweep point) over T1 -> T ends where 0 -> T does
    from gearcli.model import TorsionalModel
    from gearcli.sweep.continuation import Carried, carry_phases

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "unit"))
    from test_model_excitation import SCENES

    spec = SCENES[name]
    model = TorsionalModel(spec)
    lay = model.layout
    t1, t2 = 0.105, 0.01
    whole = _scipy_run(model, model.initial_state(), t1 + t2)
    first = _scipy_run(model, model.initial_state(), t1)
    nxt = TorsionalModel(carry_phases(_no_ramps(spec), Carried(model, first, t1)))
    y0 = continue_state(first, model, nxt, t1)
    assert y0 is not None
    second = _scipy_run(nxt, y0, t2)
    n = lay.state.i_quad  # the dynamic states (StateLayout.dynamic)
    scale = np.r_[model.deflection_scales(), model.speed_scales_rad_s(), [1.0] * (n - lay.n_conn - len(lay.free_bodies))]
    assert_allclose(second[:n] / scale, whole[:n] / scale, rtol=0, atol=1e-5)
