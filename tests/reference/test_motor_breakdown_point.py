"""The breakdown point the motor warnings report is the curve's own: the extended Kloss curve's largest torque is
at s = s_b (docs/physics.md), a torque_speed table's at one of its points. design's `motor_cannot_start`
(`breakdown_speed_rpm`) and simulate's `ramp_over_breakdown` of a VFD (`breakdown_slip_speed_rpm`) took the argmax
of a 4000-cell speed grid: 993.375 rpm and 506.625 rpm for a 15 kW 1500 rpm motor whose s_b = 0.337821 puts them at
993.269 and 506.731 rpm (tr27e's trial), and a table's 1200 rpm peak off by up to half a cell.

Reference: s_b fitted here from the nameplate by the docs' conditions alone (T(s_r) = T_N, T(1) = k_l T_N with the
maximum k_b T_N at s_b), with scipy's brentq; nothing of gearcli's."""

from __future__ import annotations

import json
import math
from pathlib import Path

from click.testing import CliRunner
from numpy.testing import assert_allclose
from scipy.optimize import brentq

from gearcli.cli import cli

CONFIG = Path(__file__).resolve().parents[2] / "configs" / "motor_direct_start.toml"
N_S, N_R, K_B, K_L = 1500.0, 1460.0, 2.8, 2.3  # the file's nameplate (15 kW)
T_RATED = 15e3 / (N_R * math.pi / 30)
TRAIN = 75 / 19 * 68 / 19 * 0.98**2  # output torque per N m at the motor, losses included


def _kloss_sb() -> float:
    def a_of(sb: float) -> float:  # T(1) = k_l T_N is linear in a
        return (K_L * (1 + sb * sb) - 2 * K_B * sb) / (2 * sb * sb * (K_B - K_L))

    def ratio(s: float, sb: float) -> float:  # T / T_N
        a = a_of(sb)
        return 2 * K_B * (1 + a * sb) * s * sb / (s * s + sb * sb + 2 * a * sb * sb * abs(s))

    s_r = 1 - N_R / N_S
    return brentq(lambda sb: ratio(s_r, sb) - 1.0, s_r * (1 + 1e-9), 1 - 1e-9, xtol=1e-15)


def _invoke(command: str, *sets: str) -> list[dict]:
    res = CliRunner().invoke(cli, [command, str(CONFIG), "--format", "json", "-q",
                                   *[a for s in sets for a in ("--set", s)]])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)["warnings"]


def test_design_reports_the_kloss_curve_s_breakdown_speed():
    # a fan load of 8 T_N at the motor at 1460 rpm meets the curve below its breakdown speed (it stalls there)
    (w,) = [w for w in _invoke("design", "load.speed_exponent=2", f"load.torque_Nm={8 * T_RATED * TRAIN!r}")
            if w.get("check") == "motor_cannot_start"]
    assert_allclose(w["breakdown_speed_rpm"], N_S * (1 - _kloss_sb()), rtol=1e-7)
    assert w["stall_speed_rpm"] < w["breakdown_speed_rpm"]


def test_design_reports_a_tables_peak_at_its_point():
    # the table's largest torque is its point (1200 rpm, 260 N m); a fan of 450 N m at the motor at 1460 rpm
    # meets its rising part first, where 200 + 0.05 n = 450 (n / 1460)^2: below the peak, a stall
    table = "input.motor={torque_speed=[[0,200],[1200,260],[1400,150],[1490,0],[1550,-120]]}"
    (w,) = [w for w in _invoke("design", table, "load.speed_exponent=2", f"load.torque_Nm={450 * TRAIN!r}")
            if w.get("check") == "motor_cannot_start"]
    assert_allclose(w["breakdown_speed_rpm"], 1200.0, rtol=1e-9)
    a, b, c = 450 / 1460**2, -0.05, -200.0
    assert_allclose(w["stall_speed_rpm"], (-b + math.sqrt(b * b - 4 * a * c)) / (2 * a), rtol=1e-6)


def test_a_vfd_ramp_outrunning_its_motor_reports_the_breakdown_slip_speed():
    # a 0.15 s ramp against a 200 kg m2 machine: the supply runs far ahead of the rotor
    sets = ['input.starting="vfd"', "input.ramp_s=0.15", "load.inertia_kg_m2=200",
            "load.coupling_stiffness_Nm_rad=2e6", "load.coupling_damping_Nms_rad=2000",
            "simulation.duration_s=0.3", "simulation.window_start_s=0.2", "simulation.steps=600"]
    (w,) = [w for w in _invoke("simulate", *sets) if w["code"] == "ramp_over_breakdown"]
    assert_allclose(w["breakdown_slip_speed_rpm"], N_S * _kloss_sb(), rtol=1e-7)
    assert w["slip_speed_rpm"] > w["breakdown_slip_speed_rpm"]
