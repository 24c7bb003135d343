"""Shooting on the Kahraman-Singh spur oscillator (configs/spur_oscillator_te.toml with a 10 um transmission
error) against an independent integration of its one-degree-of-freedom equation, written here.

The pinion turns at a prescribed speed, so the gear's motion is one degree of freedom, the dynamic
transmission error q = delta - e along the line of action (spur: normal = transverse):

    m_e q'' + c q' + F(q) = F_s + m_e Omega^2 E cos(Omega t)

with m_e = J_g / r_bg^2, c = 2 zeta sqrt(k m_e), F(q) = k (q - b/2) for q > b/2, k (q + b/2) for q < -b/2, 0
in the gap (b the backlash, 0.1 mm), F_s = T_L / r_bg. The reference integrates it with scipy's DOP853 at
rtol 1e-11 over 80 mesh periods (the transient decays by exp(-zeta omega_n T) = 0.68 per period at
Omega/omega_n = 0.8) and takes the rms of q over the last 10, sampled 2000 times each. Both points lose
contact every cycle (single-sided impacts); the rms is quoted in units of the backlash b.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_allclose

from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.simulate import run_simulation

SCENE = Path(__file__).resolve().parents[2] / "configs" / "spur_oscillator_te.toml"
TE = "contact.transmission_error_um=[10.0]"
K, ZETA, B, E, J_G, T_L, Z = 2e8, 0.05, 1e-4, 10e-6, 0.0063, 70.5, 25
R_B = 3e-3 * 25 / 2 * math.cos(math.radians(20.0))  # base radius of both 25-tooth wheels, m
M_E = J_G / R_B**2
W_N = math.sqrt(K / M_E)


def rpm_at(r: float) -> float:
    return r * W_N * 60.0 / (2 * math.pi * Z)


def reference_rms(r: float) -> float:
    """rms of q over the steady state, by brute-force integration of the equation above (scipy only)."""
    from scipy.integrate import solve_ivp

    w = r * W_N
    c = 2 * ZETA * math.sqrt(K * M_E)
    f_s = T_L / R_B

    def rhs(t, y):
        q, v = y
        f = K * (q - B / 2) if q > B / 2 else (K * (q + B / 2) if q < -B / 2 else 0.0)
        return [v, (f_s - c * v - f + M_E * w * w * E * math.cos(w * t)) / M_E]

    T = 2 * math.pi / w
    n, tail = 80, 10
    t = np.linspace((n - tail) * T, n * T, tail * 2000 + 1)
    sol = solve_ivp(rhs, (0.0, n * T), [B / 2 + f_s / K, 0.0], method="DOP853", rtol=1e-11, atol=1e-14, t_eval=t)
    q = sol.y[0, :-1]
    return float(np.sqrt(np.mean((q - q.mean()) ** 2)))


def periodic(r: float, *sets: str):
    cfg = load_design(str(SCENE), [TE, "simulation.steady=periodic", f"input.speed_rpm={rpm_at(r)!r}", *sets]).design
    return run_simulation(cfg, compute_design(cfg), want_series=False)


@pytest.mark.parametrize(("r", "quoted"), [(0.80, 0.2480), (1.00, 0.1774)])
def test_periodic_dte_rms_by_shooting_equals_the_independent_integration(r, quoted):
    ref = reference_rms(r) / B
    assert abs(ref - quoted) <= 1e-3  # the figures, reproduced by the reference
    sim = periodic(r)
    st = sim.steady
    assert st.method == "shooting" and st.converged and st.periodicity == "period-1" and st.stable
    assert st.periods_to_converge <= 30
    assert abs(sim.stages[0].dte_um.rms * 1e-6 / B - ref) <= 1e-3
    assert sim.stages[0].contact_loss_fraction > 0.3  # impacting


def test_sweep_up_and_down_through_the_coexistence_band_shows_both_branches_and_marks_the_fold():
    # r = 0.57 .. 0.75 in steps of 0.02 (pinion speeds by the formula above): below the band only the quiet
    # (linear, always in contact) response exists, above it only the impacting one; between them both coexist,
    # so the up sweep stays quiet and the down sweep stays impacting until each branch ends and the row that
    # leaves it is marked as a jump. The impacting branch ends at a fold: a real multiplier heading to +1.
    from click.testing import CliRunner

    from gearcli.cli import cli

    rs = np.round(np.arange(0.57, 0.7501, 0.02), 4)
    values = ",".join(repr(rpm_at(float(r))) for r in rs)
    res = CliRunner().invoke(cli, ["sweep", str(SCENE), "--set", TE, "--set", "simulation.steady=periodic",
                                    "--vary", f"input.speed_rpm={values}", "--direction", "both", "--jobs", "1",
                                    "--format", "csv"])
    assert res.exit_code == 0, res.output
    import csv
    import io

    rows = list(csv.DictReader(line for line in io.StringIO(res.stdout) if not line.startswith("#")))
    assert len(rows) == 2 * rs.size and all(row["status"] == "ok" for row in rows)
    linear = {}  # the quiet branch: the linear base-excitation response, rms = X / sqrt(2)
    for r in rs:
        linear[round(float(r), 4)] = E * r * r / math.sqrt((1 - r * r) ** 2 + (2 * ZETA * r) ** 2) / math.sqrt(2)
    up = {round(float(r), 4): row for r, row in zip(rs, rows[:rs.size], strict=True)}
    down = {round(float(r), 4): row for r, row in zip(rs[::-1], rows[rs.size:], strict=True)}
    band = [r for r in linear if 0.61 <= r <= 0.69]
    for r in band:  # both branches at the same speed
        q_up, q_down = float(up[r]["stage1_dte_um_rms"]) * 1e-6, float(down[r]["stage1_dte_um_rms"]) * 1e-6
        assert_allclose(q_up, linear[r], rtol=1e-3)
        assert float(up[r]["stage1_contact_loss_fraction"]) == 0.0
        assert q_down > 3 * q_up and float(down[r]["stage1_contact_loss_fraction"]) > 0.3
    jumps_up = [r for r, row in up.items() if row["message"].startswith("jump")]
    jumps_down = [r for r, row in down.items() if row["message"].startswith("jump")]
    assert len(jumps_up) == 1 and jumps_up[0] > 0.69 and len(jumps_down) == 1 and jumps_down[0] < 0.61
    assert "heads to +1: a fold" in down[jumps_down[0]]["message"]
    assert "extrapolated" in down[jumps_down[0]]["message"]  # where the real multiplier reaches +1
