"""Shooting on the new user's conveyor (configs/conveyor_periodic.toml: two helical TE-excited meshes with a
common period of 0.079 s, a 900 kg m^2 drum on a coupling whose ~4.9 Hz mode decays by only ~1 % per period).

References, all independent of the shooting: (1) over a periodic orbit the mean angular acceleration of every
body is zero, so the mean line force of the last mesh carries the drum torque exactly, mean F_t2 = T_L / (r_2 eta)
(r_2 the output gear's pitch radius: F_t = F_bt cos alpha_t and r_b = r cos alpha_t), and the first mesh
carries it scaled by the second pinion's pitch radius over the first gear's and one more 1/eta (each stage's
efficiency acts in the dynamics); (2) the meshes are linear with a
constant stiffness, so apart from the micrometre TE terms the equations are time invariant: the Floquet
multipliers equal exp(lambda T) of the eigenvalues of the Jacobian (numpy's, of the frozen equations);
(3) the energy balance of the period. The brute-force search needed more than 126 periods and did not converge.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from numpy.testing import assert_allclose

from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.model import TorsionalModel
from gearcli.scene import spec_from_design
from gearcli.simulate import run_simulation

SCENE = Path(__file__).resolve().parents[2] / "configs" / "conveyor_periodic.toml"
T_L = 6860.0  # N m, the drum torque


def _engine() -> str:
    import importlib.util

    return "compiled" if importlib.util.find_spec("numba") else "python"


def test_conveyor_orbit_by_shooting():
    cfg = load_design(str(SCENE), [f"simulation.engine={_engine()}"]).design
    design = compute_design(cfg)
    sim = run_simulation(cfg, design, want_series=False)
    st = sim.steady
    assert st.method == "shooting" and st.converged and st.periodicity == "period-1" and st.stable
    ramp_periods = 1.0 / st.period_s
    assert_allclose(st.period_s, 37 * 60 / (19 * 1480), rtol=1e-12)  # 37 stage-1 mesh periods
    assert st.periods_to_converge + ramp_periods <= 30
    r_g1 = 4e-3 * 74 / math.cos(math.radians(12)) / 2
    r_p2, r_g2 = (7e-3 * z / math.cos(math.radians(10)) / 2 for z in (18, 92))
    # each stage passes on eta = 0.985 of its power (its losses act in the dynamics): the pinion-side force of
    # stage 2 is T_L / (r_2 eta), stage 1's carries that torque on pinion 3 divided by eta once more
    eta = 0.985
    assert_allclose(sim.stages[1].tangential_N.mean, T_L / r_g2 / eta, rtol=1e-7)
    assert_allclose(sim.stages[0].tangential_N.mean, T_L / r_g2 / eta * r_p2 / r_g1 / eta, rtol=1e-7)
    assert sim.energy.residual_relative < 1e-8
    model = TorsionalModel(spec_from_design(cfg, design))
    d = model.layout.n_conn + len(model.layout.free_bodies)
    lam = np.linalg.eigvals(np.asarray(model.jac(sim.final_time_s, sim.final_state))[:d, :d])
    frozen = np.exp(lam * st.period_s)
    frozen = frozen[np.argsort(-np.abs(frozen))]
    got = np.array([complex(*m) for m in st.multipliers])
    for a, b in zip(sorted(got[:4], key=lambda m: (round(abs(m), 3), m.imag)),
                    sorted(frozen[:4], key=lambda m: (round(abs(m), 3), m.imag)), strict=True):
        assert abs(a - b) < 1e-3
    assert 0.98 < st.spectral_radius < 1.0  # the drum mode: lightly damped, no bifurcation
    assert st.bifurcation == "none"
