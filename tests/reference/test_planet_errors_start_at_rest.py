"""A run with planet position errors starts at rest, unloaded, in equilibrium (trial tr24c).

Five planets (40/20/80, ring held, sun speed-driven) on a linear mesh law without backlash carry position errors e
along their sun meshes. A planet's two meshes are in series and its own angle cancels from their sum,
delta_sp,j + delta_rp,j = S + e_j (S the central members' common angle); without a gap both flanks are in contact,
so at rest and unloaded the planets preload each other: f_j = k_eq (S + e_j), k_eq = k / 2, and the carrier's balance
sum f_j = 0 gives S = -mean(e): f_j = k_eq (e_j - mean(e)). The run started with every body at 0 instead (S = 0, each
planet's whole e_j on its sun mesh): the planets with the largest errors pressed their meshes, the carrier was
kicked backwards at t = 0, and the run's peak force and run-up factor were that kick's (2819 N at 0 s against a
settled worst planet of 2738 N, here 1.69 x static). Reference: the same equations written from docs/physics.md and
integrated by scipy's solve_ivp from the hand equilibrium (the mesh damping c = 2 zeta sqrt(k m_e), m_e over the
planet and the carrier, the speed-driven sun and the held ring infinitely heavy)."""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest
import tomli_w
from click.testing import CliRunner
from scipy.integrate import solve_ivp

from gearcli.cli import cli

K, ZETA, J_P, M_P, J_C, N = 6e8, 0.05, 0.00038, 0.84, 0.02, 5  # N/m, -, kg m^2, kg, kg m^2
ERRORS_UM = [5.0, 0.0, -2.0, 0.0, 3.0]
M, ZS, ZP, ZR = 3e-3, 40, 20, 80
SPEED_RPM, LOAD_NM, RAMP_S, END_S = 1500.0, 1500.0, 0.05, 0.1
COS = math.cos(math.radians(20))
RBS, RBP, RBR = ZS * M / 2 * COS, ZP * M / 2 * COS, ZR * M / 2 * COS


def _scene() -> str:
    stage = {"type": "planetary", "normal_module_mm": M * 1e3, "normal_pressure_angle_deg": 20, "fixed": "ring",
             "input": "sun", "sun": {"teeth": ZS, "face_width_mm": 40},
             "planet": {"teeth": ZP, "face_width_mm": 38, "count": N, "inertia_kg_m2": J_P, "mass_kg": M_P,
                        "position_error_um": ERRORS_UM},
             "ring": {"teeth": ZR, "face_width_mm": 38}, "carrier": {"inertia_kg_m2": J_C}}
    return tomli_w.dumps({"stage": [stage], "contact": {"stiffness": K / 1000, "exponent": 1, "damping_ratio": ZETA},
                          "input": {"speed_rpm": SPEED_RPM, "ramp_s": RAMP_S},
                          "load": {"torque_Nm": LOAD_NM, "ramp_s": RAMP_S},
                          "simulation": {"duration_s": END_S, "steps": 1000, "rtol": 1e-9}})


def _step(t: float) -> float:
    s = min(max(t / RAMP_S, 0.0), 1.0)
    return s * s * (3.0 - 2.0 * s)


def _step_integral(t: float) -> float:
    if t >= RAMP_S:
        return RAMP_S / 2.0 + (t - RAMP_S)
    s = t / RAMP_S
    return RAMP_S * (s**3 - s**4 / 2.0)


def _hand_run(times: np.ndarray) -> np.ndarray:
    """Planet j's sun-mesh tangential force (rows) at ``times`` (columns), from the hand rest equilibrium."""
    e = np.array(ERRORS_UM) * 1e-6
    j_c = J_C + N * M_P * ((ZS + ZP) * M / 2) ** 2
    m_e = 1.0 / (RBP**2 / J_P + (RBS + RBP) ** 2 / j_c)  # zero shifts: r_c cos a_w = r_bs + r_bp = r_br - r_bp
    c = 2.0 * ZETA * math.sqrt(K * m_e)
    w_s = SPEED_RPM * math.pi / 30.0
    # rest: S = -mean(e) by the carrier's angle (r_bs + r_br) theta_c = mean(e); each planet's own angle splits
    # S + e_j equally between its two meshes (equal k): delta_sp = (S + e_j) / 2, so
    # r_bp theta_p = (S + e_j) / 2 - e_j + (r_bs + r_bp) theta_c
    th_c = float(np.mean(e)) / (RBS + RBR)
    th_p = (-(e + np.mean(e)) / 2.0 + (RBS + RBP) * th_c) / RBP
    y0 = np.concatenate([th_p, [th_c], np.zeros(N + 1)])

    def meshes(t, y):
        th, w = y[:N + 1], y[N + 1:]
        d_sp = RBS * w_s * _step_integral(t) + RBP * th[:N] - (RBS + RBP) * th[N] + e
        v_sp = RBS * w_s * _step(t) + RBP * w[:N] - (RBS + RBP) * w[N]
        d_rp = -RBP * th[:N] - (RBR - RBP) * th[N]
        v_rp = -RBP * w[:N] - (RBR - RBP) * w[N]
        return K * d_sp + c * v_sp, K * d_rp + c * v_rp

    def rhs(t, y):
        f_sp, f_rp = meshes(t, y)
        a_p = RBP * (f_rp - f_sp) / J_P
        a_c = (np.sum(f_sp) * (RBS + RBP) + np.sum(f_rp) * (RBR - RBP) - LOAD_NM * _step(t)) / j_c
        return np.concatenate([y[N + 1:], a_p, [a_c]])

    jac = np.array([(rhs(0.0, np.eye(2 * N + 2)[i]) - rhs(0.0, np.zeros(2 * N + 2))) for i in range(2 * N + 2)]).T
    sol = solve_ivp(rhs, (0.0, END_S), y0, method="Radau", t_eval=times, rtol=1e-10, atol=1e-14, jac=jac)
    assert sol.status == 0
    return np.array([meshes(t, sol.y[:, i])[0] for i, t in enumerate(times)]).T * COS


def test_planet_errors_start_from_the_unloaded_equilibrium(tmp_path):
    path = tmp_path / "errors.toml"
    path.write_text(_scene())
    out = tmp_path / "run.csv"
    res = CliRunner().invoke(cli, ["-q", "simulate", str(path), "-o", str(out)])
    assert res.exit_code == 0, res.output
    rows = list(csv.DictReader(line for line in out.read_text().splitlines() if not line.startswith("#")))
    t = np.array([float(r["time_s"]) for r in rows])
    run = np.array([[float(r[f"stage1_planet{j + 1}_sun_tangential_N"]) for r in rows] for j in range(N)])
    e = np.array(ERRORS_UM) * 1e-6
    preload = K / 2.0 * (e - e.mean()) * COS  # 1071 N on planet 1, -902 N on planet 3: summing to 0
    assert t[0] == 0.0
    assert run[:, 0] == pytest.approx(preload, rel=1e-6, abs=1e-6)  # was 2819, 0, -1128, 0, 1691 N
    hand = _hand_run(t)
    static = LOAD_NM / 3.0 / (N * ZS * M / 2)  # the equal share, 1666.7 N
    assert np.max(np.abs(run - hand)) < 1e-4 * static
    worst = static + K / 2.0 * (e.max() - e.mean()) * COS  # the settled worst planet, 2737.9 N
    res = CliRunner().invoke(cli, ["-q", "simulate", str(path), "--format", "json"])
    import json

    stage = json.loads(res.stdout)["summary"]["stages"][0]
    assert stage["peak_tangential_N"] == pytest.approx(float(np.max(np.abs(hand))), rel=1e-5)  # 2744 N at 0.048 s
    assert stage["peak_time_s"] > 0.0
    assert stage["peak_tangential_N"] < 1.01 * worst  # the ramp's overshoot, not a kick (2819 N before)
