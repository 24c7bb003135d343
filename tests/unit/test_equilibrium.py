"""An unexcited scene's steady state found directly as its equilibrium (gearcli.simulate.equilibrium): the seed's
static tooth forces by hand, the start-up of the window run kept, the multipliers of a finite-difference
linearisation, and the state the motion itself reaches when it is integrated long enough (scipy, independently)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.integrate import solve_ivp

from gearcli import api
from gearcli.model import TorsionalModel
from gearcli.scene import spec_from_design
from gearcli.simulate import equilibrium, run_simulation

ROOT = Path(__file__).resolve().parents[2]
SEED = str(ROOT / "configs" / "concrete_mixer.toml")


def _seed(*sets: str):
    loaded = api.load(SEED, list(sets))
    return loaded.design, api.design(loaded)


def _pitch_radius_m(z: int, m_n_mm: float, beta_deg: float) -> float:
    return z * m_n_mm / math.cos(math.radians(beta_deg)) / 2.0 / 1000.0


@pytest.fixture(scope="module")
def seed_settled():
    cfg, design = _seed("simulation.engine=python")
    return cfg, design, run_simulation(cfg, design, settle=True, want_series=True)


def test_the_seed_settles_at_its_equilibrium_with_the_static_tooth_forces_by_hand(seed_settled):
    """The seed reducer (no excitation, 600 rpm prescribed): the settled steady state is the equilibrium, whose
    window holds each stage's static tangential force, constant. By hand, from the drum's 5.31e6 N mm through
    the pitch radii d = z m_n / cos(beta) (lossless meshes): stage 3 F_t = T / r_6, stage 2 F_t = F_t3 r_5 / r_4,
    stage 1 F_t = F_t2 r_3 / r_2; the output speed 600 rpm x (21/51)(17/50)(17/53)."""
    _, _, r = seed_settled
    st = r.steady
    assert st.mode == "periodic" and st.method == "equilibrium" and st.converged and st.settled and st.stable
    assert st.residual is not None and st.residual <= 1.0
    f3 = 5.31e3 / _pitch_radius_m(53, 25, 9)
    f2 = f3 * _pitch_radius_m(17, 25, 9) / _pitch_radius_m(50, 18, 11)
    f1 = f2 * _pitch_radius_m(17, 18, 11) / _pitch_radius_m(51, 12, 12)
    for stage, by_hand in zip(r.stages, (f1, f2, f3), strict=True):
        # the state solves the equations to 1e-3 of the tolerance (rtol 1e-6): the force to well within 1e-6
        assert_allclose(stage.tangential_N.mean, by_hand, rtol=1e-6)
        assert_allclose([stage.tangential_N.min, stage.tangential_N.max], by_hand, rtol=1e-6)
        assert stage.dynamic_factor == pytest.approx(1.0, abs=1e-6)
    assert_allclose(r.output_speed_deg_s / 6.0, 600 * (21 / 51) * (17 / 50) * (17 / 53), rtol=1e-9)
    # the energy balance of the exact period: the input's work is the drum's (lossless, nothing stored)
    assert r.energy.residual_relative < 1e-9


def test_the_start_up_is_the_window_runs_own(seed_settled):
    """The run from rest to simulation.duration_s is sampled as the window run samples it: the start-up peaks,
    their times and the run-up factors are that run's, sample for sample."""
    cfg, design, settled = seed_settled
    plain = run_simulation(cfg, design, settle=False)
    for a, b in zip(settled.stages, plain.stages, strict=True):
        assert a.peak_tangential_N == b.peak_tangential_N and a.peak_time_s == b.peak_time_s
        assert a.runup_factor == b.runup_factor
    # summary.start: the rigid-body start is integrated to each result's last sample (the window run's end, the
    # equilibrium's period after it) at its own tolerance: the same peaks to its accuracy
    for key in ("peak_over_rigid", "rigid_peak_N"):
        assert_allclose(settled.extra["start"][key], plain.extra["start"][key], rtol=1e-5)


def test_the_multipliers_are_those_of_a_finite_difference_linearisation(seed_settled):
    """exp(lambda T) of the eigenvalues of a central-difference Jacobian of the equations at the window's state
    (not the analytic Jacobian Newton used)."""
    cfg, design, r = seed_settled
    model = TorsionalModel(spec_from_design(cfg, design))
    d = model.layout.state.n_mechanical
    y = np.array(r.final_state, dtype=float)
    t = r.final_time_s
    J = np.empty((d, d))
    for k in range(d):
        h = 1e-6 * max(abs(y[k]), 1e-6)
        yp, ym = y.copy(), y.copy()
        yp[k] += h
        ym[k] -= h
        J[:, k] = (model.rhs(t, yp)[:d] - model.rhs(t, ym)[:d]) / (2 * h)
    mu = np.exp(np.linalg.eigvals(J) * r.steady.period_s)
    mu = mu[np.argsort(-np.abs(mu))]
    got = np.array([complex(a, b) for a, b in r.steady.multipliers])
    assert_allclose(np.abs(got), np.abs(mu), rtol=1e-4)
    assert r.steady.spectral_radius < 1.0


def test_the_motion_goes_there():
    """The seed with its mesh damping raised (its slowest mode then decays within the run): scipy's Radau from
    rest, independently, at a tight tolerance, to 3 s; its final deflections and speeds are the equilibrium's."""
    cfg, design = _seed("contact.damping_Ns_mm=20000", "simulation.engine=python")
    r = run_simulation(cfg, design, settle=True)
    assert r.steady.method == "equilibrium"
    model = TorsionalModel(spec_from_design(cfg, design))
    d = model.layout.state.n_mechanical
    sol = solve_ivp(model.rhs, (0.0, 3.0), model.initial_state(), method="Radau", jac=model.jac, rtol=1e-10,
                    atol=1e-14)
    assert sol.success
    # the slowest decay rate is above 10/s here: e^-28 of the start is left at 3 s
    assert_allclose(sol.y[:d, -1], r.final_state[:d], rtol=1e-6, atol=1e-12)


def test_an_excited_scene_is_not_taken_for_an_equilibrium():
    loaded = api.load(str(ROOT / "configs" / "concrete_mixer_te.toml"), [])
    model = TorsionalModel(spec_from_design(loaded.design, api.design(loaded)))
    assert not equilibrium.applies(model)
    cfg, design = _seed()
    assert equilibrium.applies(TorsionalModel(spec_from_design(cfg, design)))


def test_a_periodic_result_keeps_the_start_of_the_run_it_replaces():
    """configs/conveyor.toml (a transmission error excites it): its settled result is the periodic orbit the
    shooting finds after an unsettled window; the start-up it reports is at least the window run's, which ran
    from rest over the whole simulation.duration_s (the orbit's own run-up ends with the ramps)."""
    loaded = api.load(str(ROOT / "configs" / "conveyor.toml"), [])
    design = api.design(loaded)
    plain = run_simulation(loaded.design, design, settle=False)
    settled = run_simulation(loaded.design, design, settle=True)
    assert settled.steady.mode == "periodic" and settled.steady.method != "equilibrium"
    for a, b in zip(settled.stages, plain.stages, strict=True):
        assert a.peak_tangential_N >= b.peak_tangential_N
        assert a.runup_factor == pytest.approx(a.peak_tangential_N / a.simulated_static_tangential_N, rel=1e-12)


def test_an_undamped_scene_has_no_steady_state_to_settle_into():
    """configs/extreme/zero_damping.toml (no mesh damping): its equilibrium has every multiplier on the unit circle,
    a fixed point the start-up vibration circles for ever; the settled run keeps its window and says it is not
    settled (its ringing warning gives the decay time), rather than reporting the equilibrium's K_v = 1."""
    loaded = api.load(str(ROOT / "configs" / "extreme" / "zero_damping.toml"), [])
    r = run_simulation(loaded.design, api.design(loaded), settle=True)
    assert r.steady.mode == "window" and r.steady.settled is False
    assert any(d.code in ("window_ringing", "window_not_settled") for d in r.diagnostics)
    assert max(st.dynamic_factor for st in r.stages) > 1.1  # the start-up's vibration, undamped


def test_a_periodic_state_is_reached_only_when_it_contracts():
    from gearcli.simulate.results import SteadyState
    from gearcli.simulate.settle import NEUTRAL, reached

    def state(converged, radius):
        return SteadyState("periodic", 0.1, 3, "period-1", converged, 0.5, spectral_radius=radius)

    assert reached(state(True, 0.989))  # the conveyor's drum mode: 1.1 % per period
    assert not reached(state(True, 1.0 - NEUTRAL / 10))  # an undamped mode (rounding below 1)
    assert not reached(state(False, 0.5))
    assert reached(state(True, None))  # brute force: the motion itself repeated


def test_newton_reaches_the_equilibrium_of_shafts_ten_decades_apart():
    """configs/extreme/unequal_inertias.toml (a 1e-6 kg m^2 intermediate shaft, a 1e4 kg m^2 output): a full Newton
    step leaves a force error of ~0.1 % that the light shaft turns into a drift far above the start's, so a step
    judged by the drift was halved every time until Newton gave up (the search then fell to brute force,
    unconverged). Judged by the distance to the root it converges in a few steps; the window holds the static
    tangential forces by hand: stage 2 F_t = 1e4 N m / r_4, stage 1 F_t = F_t2 r_3 / r_2 (lossless meshes)."""
    loaded = api.load(str(ROOT / "configs" / "extreme" / "unequal_inertias.toml"),
                      ['simulation.steady="periodic"', "simulation.engine=python"])
    r = run_simulation(loaded.design, api.design(loaded))
    st = r.steady
    assert st.method == "equilibrium" and st.converged and st.iterations is not None and st.iterations <= 10
    f2 = 1e4 / _pitch_radius_m(50, 18, 11)
    f1 = f2 * _pitch_radius_m(17, 18, 11) / _pitch_radius_m(51, 12, 12)
    for stage, by_hand in zip(r.stages, (f1, f2), strict=True):
        assert_allclose([stage.tangential_N.mean, stage.tangential_N.min, stage.tangential_N.max], by_hand,
                        rtol=1e-6)


def test_an_undamped_periodic_state_is_found_but_not_called_settled():
    """steady = "periodic" on configs/extreme/zero_damping.toml: without damping the linearised motion about the
    equilibrium is a set of undamped oscillators, lambda = +-i omega, so every multiplier exp(lambda T) has modulus
    1. The equilibrium is a periodic state (K_v 1), but not the one the motion from rest reaches: not settled, and
    the warning says so; the damped seed's is settled without it."""
    loaded = api.load(str(ROOT / "configs" / "extreme" / "zero_damping.toml"),
                      ['simulation.steady="periodic"', "simulation.engine=python"])
    r = run_simulation(loaded.design, api.design(loaded))
    assert r.steady.method == "equilibrium" and r.steady.converged
    assert r.steady.spectral_radius == pytest.approx(1.0, abs=1e-9)
    assert r.steady.settled is False
    assert [d.code for d in r.diagnostics].count("periodic_not_attracting") == 1
    cfg, design = _seed('simulation.steady="periodic"', "simulation.engine=python")
    damped = run_simulation(cfg, design)
    assert damped.steady.settled is True and damped.steady.spectral_radius < 1.0 - 1e-6
    assert "periodic_not_attracting" not in [d.code for d in damped.diagnostics]
