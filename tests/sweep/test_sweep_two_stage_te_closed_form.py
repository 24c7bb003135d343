"""A speed sweep of a two-stage helical chain through its first mode, row by row against the closed-form forced
response (tr19e).

The scene: tests/field/data/coincident_orders.toml (stage 1 20/60, m_n 3; stage 2 20/50, m_n 4; beta 15 deg; inertias
given; linear meshes 4e5 N/mm with viscous damping zeta = 0.05) and a 3 um first-harmonic transmission error on both
meshes. The input's speed is prescribed, so shafts 2 (J = 0.06) and 3 (J = 0.3) are a linear 2-DOF chain: the mesh
acts on q = delta - e along the transverse line of action with stiffness k cos^2 beta_b and damping
c = 2 zeta sqrt(k m_e) (m_e = J2 / r_bg1^2 behind the speed-driven pinion, 1 / (r_bp2^2 / J2 + r_bg2^2 / J3) for stage 2;
docs/physics.md). No backlash: a drive flank that lets go hands the force to the back flank at once, so the chain
stays linear at any amplitude and its steady DTE is the sum of the two mesh lines' complex responses (stage 1 at
z1 n / 60, stage 2 at z3 n / (3 * 60)); the rms of each stage's DTE is sqrt(sum |Q|^2 / 2). Mode 1 (489.2 Hz) is met
by stage 1's mesh order at 60 f / 20 = 1467.5 rpm.
"""

from __future__ import annotations

import csv
import io
import math
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from gearcli.cli import cli

SCENE = Path(__file__).resolve().parents[1] / "field" / "data" / "coincident_orders.toml"
K = 4e8  # N/m, the law's linear stiffness along the normal line of action
ZETA, TE = 0.05, 3e-6
J2, J3 = 0.05 + 0.01, 0.3


def _base_radius(z: int, m_mm: float) -> float:
    beta, alpha_n = math.radians(15.0), math.radians(20.0)
    alpha_t = math.atan(math.tan(alpha_n) / math.cos(beta))
    return z * m_mm * 1e-3 * math.cos(alpha_t) / (2 * math.cos(beta))


def dte_rms_um(n_rpm: float) -> tuple[float, float]:
    """Steady DTE rms (um) of stages 1 and 2 at input speed n by the closed-form frequency response."""
    cos2 = 1.0 - (math.sin(math.radians(15.0)) * math.cos(math.radians(20.0))) ** 2
    k = K * cos2
    g1, p2, g2 = _base_radius(60, 3.0), _base_radius(20, 4.0), _base_radius(50, 4.0)
    c1 = 2 * ZETA * math.sqrt(K * J2 / g1**2)
    c2 = 2 * ZETA * math.sqrt(K / (p2**2 / J2 + g2**2 / J3))
    omega_in = n_rpm * 2 * math.pi / 60
    ms = [0.0, 0.0]
    for source, w in ((1, 20 * omega_in), (2, 20 * omega_in / 3)):
        s = 1j * w
        k1, k2 = k + c1 * s, k + c2 * s
        e1, e2 = (TE, 0.0) if source == 1 else (0.0, TE)
        # J2 th2'' = r_bg1 F1 - r_bp2 F2, J3 th3'' = r_bg2 F2; F1 = k1 (-r_bg1 th2 - e1), F2 = k2 (r_bp2 th2 - r_bg2 th3 - e2)
        a = np.array([[J2 * s * s + k1 * g1**2 + k2 * p2**2, -k2 * p2 * g2], [-k2 * g2 * p2, J3 * s * s + k2 * g2**2]])
        th2, th3 = np.linalg.solve(a, np.array([-g1 * k1 * e1 + p2 * k2 * e2, -g2 * k2 * e2]))
        q1, q2 = -g1 * th2 - e1, p2 * th2 - g2 * th3 - e2
        ms[0] += abs(q1) ** 2 / 2
        ms[1] += abs(q2) ** 2 / 2
    return math.sqrt(ms[0]) * 1e6, math.sqrt(ms[1]) * 1e6


def test_sweep_rows_are_the_closed_form_forced_response(tmp_path):
    assert dte_rms_um(1450.0)[0] == pytest.approx(7.404, abs=1e-3)  # the resonant row's figure, by hand
    out = tmp_path / "sweep.csv"
    res = CliRunner().invoke(cli, ["sweep", str(SCENE), "--vary", "input.speed_rpm=1300,1450,1600", "--jobs", "1",
                                   "--set", "contact.transmission_error_um=[3.0]", "--set", "input.ramp_s=0.02",
                                   "--set", "load.ramp_s=0.02", "--set", "simulation.duration_s=0.15",
                                   "--set", "simulation.steps=3000", "-o", str(out)])
    assert res.exit_code == 0, res.stderr
    rows = list(csv.DictReader(io.StringIO("".join(l for l in out.read_text().splitlines(True) if l[0] != "#"))))
    for row in rows:
        hand = dte_rms_um(float(row["input.speed_rpm"]))
        got = (float(row["stage1_dte_um_rms"]), float(row["stage2_dte_um_rms"]))
        # the window holds partial periods of the two lines: the observed spread is 0.2 %
        assert got == pytest.approx(hand, rel=5e-3), row["input.speed_rpm"]
    peak = max(rows, key=lambda r: float(r["stage1_dte_um_rms"]))
    assert peak["input.speed_rpm"] == "1450"  # nearest to 1467.5 rpm
