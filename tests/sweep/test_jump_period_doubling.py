"""A periodic sweep's branch that ends at a period doubling says so, and where the multiplier crosses -1.

Scene: the spur mesh of tests/reference/test_parametric_edge_stable.py (25/25, m = 3 mm, gear 0.0063 kg m^2 free
against 70.5 N m, linear 2e5 N/mm, zeta = 0.05, a 30 % stiffness harmonic, 0.1 mm backlash), swept up from 4500 to
4700 rpm. The in-contact period-1 orbit loses stability where a real multiplier crosses -1 (the principal parametric
resonance's lower edge); past it the period-2 orbit with the teeth separating takes over (a jump in DTE rms). The
row's mark called this "largest Floquet multiplier -0.716+0i is not near +1: a non-smooth end", quoting the other
multiplier. Reference: the edge from the monodromy of m_e q'' + c q' + k (1 - 0.3 cos(Omega t)) q = 0 (scipy
DOP853, rtol 1e-12) and a root search on its lowest multiplier + 1: 4516.24 rpm.
"""

from __future__ import annotations

import json
import math
import re

import numpy as np
import tomli_w
from click.testing import CliRunner
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from gearcli.cli import cli

SCENE = {
    "title": "parametric spur mesh swept into its instability band",
    "stage": [{"normal_module_mm": 3, "normal_pressure_angle_deg": 20, "backlash_mm": 0.1,
               "pinion": {"teeth": 25, "face_width_mm": 20, "hand": "spur"},
               "gear": {"teeth": 25, "face_width_mm": 20, "hand": "spur", "inertia_kg_m2": 0.0063}}],
    "contact": {"stiffness": 2e5, "exponent": 1, "damping_ratio": 0.05, "stiffness_harmonics": [0.3]},
    "input": {"speed_rpm": 4500, "ramp_s": 0.02}, "load": {"torque_Nm": 70.5, "ramp_s": 0.02},
    "simulation": {"duration_s": 0.3, "steps": 4000, "steady": "periodic"},
}


def _lowest_multiplier(rpm: float) -> float:
    rb = 3e-3 * 25 * math.cos(math.radians(20.0)) / 2
    m_e, k = 0.0063 / rb ** 2, 2e8
    c = 2 * 0.05 * math.sqrt(k * m_e)
    w = 2 * math.pi * 25 * rpm / 60

    def rhs(t, y):
        return [y[1], -(c * y[1] + k * (1 - 0.3 * math.cos(w * t)) * y[0]) / m_e]

    cols = [solve_ivp(rhs, (0.0, 2 * math.pi / w), y0, method="DOP853", rtol=1e-12, atol=1e-15).y[:, -1]
            for y0 in ([1.0, 0.0], [0.0, 1.0])]
    return float(np.min(np.linalg.eigvals(np.column_stack(cols)).real))


def test_the_branch_ends_at_the_period_doubling_where_the_multiplier_crosses_minus_one(tmp_path):
    edge = brentq(lambda n: _lowest_multiplier(n) + 1.0, 4500.0, 4600.0, xtol=1e-3)
    path = tmp_path / "scene.toml"
    path.write_text(tomli_w.dumps(SCENE))
    out = CliRunner().invoke(cli, ["sweep", str(path), "--vary", "input.speed_rpm=4500,4700", "--direction", "up",
                                   "--jobs", "1", "--format", "json"])
    assert out.exit_code == 0, out.output
    row = json.loads(out.stdout)["rows"][1]
    assert row["message"].startswith("jump:")
    assert "a period doubling" in row["message"] and "not near +1" not in row["message"]
    at = float(re.search(r"period doubling \(the orbit of twice the period takes over\), at input\.speed_rpm = "
                         r"([0-9.]+) \(interpolated\)", row["message"]).group(1))
    assert abs(at - edge) < 0.1  # 4516.22 against 4516.24; the branch's end itself is bisected to 0.2 rpm
