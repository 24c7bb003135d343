"""``steady = "periodic"`` without a prescribed speed: the period is the motion's, from its own mean input speed.

Scene: one spur stage 25/25 (m = 3 mm, base radii 35.24 mm), pinion and gear of 0.0063 kg m^2 each, a linear mesh
(2e5 N/mm, zeta = 0.05 on the DTE) with a 2 um transmission error, driven by a torque drive of 70.5 N m with a 10 %
ripple of order 2 against a fan load 70.5 N m (n / 1500 rpm)^2. The rigid balance is 1500 rpm, which gave the search
its period (one input revolution, 0.04 s); the ripple and the mesh losses keep the train at 1499.86 rpm, 9.2e-5
slower, so the state compared 0.04 s apart never repeated (the mesh phase drifts) and the run said "not periodic
(chaotic or quasi-periodic)" after 81 periods. Every excitation is a function of the input angle, so the motion
repeats over one input revolution: the search now times its period from the motion's mean input speed.

Reference: the two-degree-of-freedom model written from the contract's mesh law (docs/physics.md; angles and speeds of both wheels, q = r_b
(theta_p - theta_g) - e(25 theta_p), F = k q + c q', c = 2 zeta sqrt(k m_e), m_e = J_p J_g / (J_p r_b^2 + J_g r_b^2))
integrated with scipy's DOP853 for 2 s; the period is the time one input revolution takes there, the statistics
those of F_t = F cos(alpha) over it.
"""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest
from click.testing import CliRunner
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from gearcli.cli import cli

SCENE = """title = "torque drive, ripple, fan load, transmission error"
[[stage]]
normal_module_mm = 3
normal_pressure_angle_deg = 20
pinion = { teeth = 25, face_width_mm = 20, hand = "spur", inertia_kg_m2 = 0.0063 }
gear   = { teeth = 25, face_width_mm = 20, hand = "spur", inertia_kg_m2 = 0.0063 }
[contact]
stiffness = 2e5
exponent = 1
damping_ratio = 0.05
transmission_error_um = [2.0]
[input]
drive = "torque"
speed_rpm = 1500
torque_Nm = 70.5
ramp_s = 0.05
torque_ripple = [{amplitude_percent = 10, order = 2}]
[load]
torque_Nm = 70.5
speed_exponent = 2
ramp_s = 0.05
[simulation]
duration_s = 3
steps = 4000
steady = "periodic"
"""
ALPHA, Z, J, K, ZETA, T0, TE, RIPPLE = math.radians(20.0), 25, 0.0063, 2e8, 0.05, 70.5, 2e-6, 0.10
W0 = 1500 * 2 * math.pi / 60


@pytest.fixture(scope="module")
def ref() -> dict:
    rb = 3e-3 * Z * math.cos(ALPHA) / 2
    m_e = J * J / (2 * J * rb ** 2)
    c = 2 * ZETA * math.sqrt(K * m_e)

    def force(y):
        thp, wp, thg, wg = y
        q = rb * (thp - thg) - TE * np.cos(Z * thp)
        return K * q + c * (rb * (wp - wg) + TE * Z * wp * np.sin(Z * thp))

    def rhs(_t, y):
        f = force(y)
        return [y[1], (T0 * (1 + RIPPLE * math.cos(2 * y[0])) - f * rb) / J, y[3], (f * rb - T0 * (y[3] / W0) ** 2) / J]

    sol = solve_ivp(rhs, (0.0, 2.0), [0.0, W0, -T0 / rb / K / rb, W0], method="DOP853", rtol=1e-10,
                    atol=[1e-12, 1e-8, 1e-12, 1e-8], dense_output=True)
    t0 = 1.9
    th0 = sol.sol(t0)[0]
    t1 = brentq(lambda t: sol.sol(t)[0] - th0 - 2 * math.pi, t0 + 0.039, t0 + 0.041, xtol=1e-14)
    tt = np.linspace(t0, t1, 40001)
    ft = force(sol.sol(tt)) * math.cos(ALPHA)
    w = np.full(tt.size, 1.0)
    w[[0, -1]] = 0.5
    w /= w.sum()
    mean = float(np.sum(w * ft))
    return {"period_s": t1 - t0, "mean": mean, "std": float(np.sqrt(np.sum(w * (ft - mean) ** 2))),
            "min": float(ft.min()), "max": float(ft.max())}


@pytest.fixture(scope="module")
def run(tmp_path_factory) -> dict:
    path = tmp_path_factory.mktemp("torque_drive") / "scene.toml"
    path.write_text(SCENE)
    out = CliRunner().invoke(cli, ["simulate", str(path), "--format", "json"])
    assert out.exit_code == 0, out.output
    return json.loads(out.stdout)


def test_the_period_is_one_input_revolution_at_the_motion_s_mean_speed(run, ref):
    steady = run["summary"]["steady"]
    assert steady["converged"] and steady["periodicity"] == "period-1"
    assert not any(w["code"] == "not_periodic" for w in run["warnings"])
    assert steady["period_s"] == pytest.approx(ref["period_s"], rel=1e-7)  # 9.2e-5 off the rigid balance's
    assert 60 / steady["period_s"] == pytest.approx(run["summary"]["input_speed_rpm"], rel=1e-7)
    # the source gives the mean speed's difference from the rigid balance: 0.04 s / T - 1 = -9.22e-5
    said = re.search(r"at the motion's mean input speed \(([-+0-9.e]+) relative", steady["period_source"])
    assert float(said.group(1)) == pytest.approx(0.04 / ref["period_s"] - 1.0, rel=1e-2)
    assert steady["note"].startswith("a torque drive: ")


def test_the_statistics_over_that_period_are_the_motion_s(run, ref):
    ft = run["summary"]["stages"][0]["tangential_N"]
    assert ft["mean"] == pytest.approx(ref["mean"], rel=1e-6)
    assert ft["std"] == pytest.approx(ref["std"], rel=1e-4)
    for key in ("min", "max"):
        assert ft[key] == pytest.approx(ref[key], abs=1e-4 * ref["mean"])
