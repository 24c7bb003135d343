"""A lossy plug-in stage's run-up against an independent model: the roller chain of ``plug_chain.py`` (the built-in
mesh element as a linear contact without backlash, efficiency eta; docs/plugins.md "Losses") alone, its driver
speed-driven on a STEP ramp, its driven sprocket loaded by a STEP-ramped torque. The reference is written here from
docs/physics.md ("Torsional model", "Stage efficiency in the dynamics"), never importing gearcli's model: one degree
of freedom theta_2,

    J_2 theta_2'' = r_2 f_b - T_L STEP(t, 0, 0, t_L, 1),   f = k (r_1 theta_1(t) - r_2 theta_2),
    f_b = f (1 - c (1 + s)), c = (1 - eta) / 2, s = tanh(f v / W), v = (r_1 w_1 + r_2 w_2) / 2,
    W = 1e-3 (T_L / r_2) (r_1 w_N)   (the driven side's static force, the driving side's nominal speed),

theta_1 the integral of w_N STEP(t, 0, 0, t_in, 1), integrated by scipy's DOP853 at rtol 1e-11. gearcli's chain
force series must follow it through the run-up (its ringing included: no damping) to 1e-5 of the peak, and the
input torque the speed drive gives, r_1 f_a + J_1 w_1' with f_a = f (1 - c (1 - s)), likewise."""

from __future__ import annotations

import csv
import math

import numpy as np
import plug_chain as pc
import pytest
import tomli_w
from click.testing import CliRunner
from numpy.testing import assert_allclose
from scipy.integrate import solve_ivp

from gearcli.cli import cli

Z1, Z2, PITCH, ETA, K, J1, J2 = 17, 51, 19.05, 0.9, 2.0e7, 0.02, 0.2  # -, -, mm, -, N/m, kg m², kg m²
N_IN, T_IN, T_L, T_LR, DURATION, STEPS = 600.0, 0.2, 600.0, 0.1, 0.3, 3000  # rpm, s, N m, s, s, -


@pytest.fixture
def chain():
    pc.register()
    yield
    pc.withdraw()


def _step(t: float, span: float) -> float:
    d = min(max(t / span, 0.0), 1.0)
    return d * d * (3.0 - 2.0 * d)


def _reference(t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    r1, r2 = Z1 * PITCH * 1e-3 / (2 * math.pi), Z2 * PITCH * 1e-3 / (2 * math.pi)
    w_n = N_IN * math.pi / 30.0
    width = 1e-3 * (T_L / r2) * (r1 * w_n)
    c = 0.5 * (1.0 - ETA)

    def theta_1(x: float) -> float:
        if x < T_IN:
            d = x / T_IN
            return w_n * T_IN * (d**3 - d**4 / 2.0)
        return w_n * (T_IN / 2.0 + x - T_IN)

    def split(x: float, th2: float, w2: float) -> tuple[float, float]:
        f = K * (r1 * theta_1(x) - r2 * th2)
        s = math.tanh(f * 0.5 * (r1 * w_n * _step(x, T_IN) + r2 * w2) / width)
        return f * (1.0 - c * (1.0 - s)), f * (1.0 - c * (1.0 + s))

    def rhs(x, y):
        return [y[1], (r2 * split(x, y[0], y[1])[1] - T_L * _step(x, T_LR)) / J2]

    sol = solve_ivp(rhs, (0.0, DURATION), [0.0, 0.0], t_eval=t, method="DOP853", rtol=1e-11, atol=1e-14)
    force = np.array([K * (r1 * theta_1(x) - r2 * th2) for x, th2 in zip(t, sol.y[0], strict=True)])
    def accel_1(x: float) -> float:  # w_N d/dt STEP(t, 0, 0, t_in, 1)
        d = min(max(x / T_IN, 0.0), 1.0)
        return w_n * 6.0 * d * (1.0 - d) / T_IN

    torque_in = np.array([r1 * split(x, th2, w2)[0] + J1 * accel_1(x) for x, th2, w2 in zip(t, *sol.y, strict=True)])
    return force, torque_in


def test_a_lossy_plug_in_stage_runs_up_as_its_hand_model(chain, tmp_path):
    stage = {"type": pc.KIND, "driver_teeth": Z1, "driven_teeth": Z2, "pitch_mm": PITCH, "chain_efficiency": ETA,
             "stiffness_N_m": K, "damping_Ns_m": 0.0, "driver_inertia_kg_m2": J1, "driven_inertia_kg_m2": J2}
    doc = {"title": "a chain alone, run up", "stage": [stage], "input": {"speed_rpm": N_IN, "ramp_s": T_IN},
           "load": {"torque_Nm": T_L, "ramp_s": T_LR},
           "simulation": {"duration_s": DURATION, "steps": STEPS, "rtol": 1e-9}}
    path = tmp_path / "chain.toml"
    path.write_text(tomli_w.dumps(doc), encoding="utf-8")
    out = tmp_path / "run.csv"
    r = CliRunner().invoke(cli, ["simulate", str(path), "-o", str(out), "-q"])
    assert r.exit_code == 0, r.output
    with out.open(encoding="utf-8") as fh:
        rows = list(csv.DictReader(line for line in fh if not line.startswith("#")))
    t = np.array([float(row["time_s"]) for row in rows])
    force = np.array([float(row["stage1_tangential_N"]) for row in rows])
    torque_in = np.array([float(row["input_torque_Nm"]) for row in rows])
    ref_force, ref_torque = _reference(t)
    peak = np.max(np.abs(ref_force))
    assert peak > 1.03 * T_L / (Z2 * PITCH * 1e-3 / (2 * math.pi)) / ETA  # the run-up overshoots: a dynamic check
    assert_allclose(force, ref_force, rtol=0, atol=1e-5 * peak)
    assert_allclose(torque_in, ref_torque, rtol=0, atol=1e-5 * np.max(np.abs(ref_torque)))
