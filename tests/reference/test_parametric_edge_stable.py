"""``summary.steady.stable`` past a period-doubling edge: a multiplier outside the unit circle is not stable.

Scene: one spur stage 25/25 (m = 3 mm, base radii 35.24 mm), the pinion at a prescribed speed, the gear
(0.0063 kg m^2) free against 70.5 N m, a linear mesh (2e5 N/mm, zeta = 0.05 on the DTE) with a 30 % first stiffness
harmonic K (1 - 0.3 cos phi) and 0.1 mm backlash. Near twice the mesh mode (999 Hz) the in-contact mesh is
parametrically unstable between about 4516 and 5052 rpm. At 4517.3 rpm the period-1 orbit (in contact all along)
has a multiplier -1.0008: the motion leaves it (the run's own warning says so), but ``stable`` came out true, the
shooting's slack for the monodromy's error (1e-3) taken for the contract's "all inside the unit circle".

Reference: the monodromy of m_e q'' + c q' + k (1 - 0.3 cos(Omega t)) q = 0, m_e = J_g / r_b^2, c = 2 zeta
sqrt(k m_e), Omega = 2 pi 25 n / 60, integrated over one mesh period with scipy's DOP853 (rtol 1e-12) from the
unit vectors; its eigenvalues are the orbit's multipliers (the orbit stays in contact, where the mesh is linear).
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner
from scipy.integrate import solve_ivp

from gearcli.cli import cli

SCENE = """title = "spur mesh with a stiffness harmonic near its parametric resonance"
[[stage]]
pinion = { teeth = 25, face_width_mm = 20, hand = "spur" }
gear   = { teeth = 25, face_width_mm = 20, hand = "spur", inertia_kg_m2 = 0.0063 }
backlash_mm = 0.1
normal_module_mm = 3
normal_pressure_angle_deg = 20
[contact]
stiffness_harmonics = [0.3]
damping_ratio = 0.05
stiffness = 2e5
exponent = 1
[input]
speed_rpm = %s
ramp_s = 0.02
[load]
torque_Nm = 70.5
ramp_s = 0.02
[simulation]
duration_s = 0.3
steps = 4000
steady = "periodic"
"""
K, ZETA, S, J = 2e8, 0.05, 0.3, 0.0063


def _multipliers(rpm: float) -> np.ndarray:
    rb = 3e-3 * 25 * math.cos(math.radians(20.0)) / 2
    m_e = J / rb ** 2
    c = 2 * ZETA * math.sqrt(K * m_e)
    w = 2 * math.pi * 25 * rpm / 60

    def rhs(t, y):
        return [y[1], -(c * y[1] + K * (1 - S * math.cos(w * t)) * y[0]) / m_e]

    cols = [solve_ivp(rhs, (0.0, 2 * math.pi / w), y0, method="DOP853", rtol=1e-12, atol=1e-15).y[:, -1]
            for y0 in ([1.0, 0.0], [0.0, 1.0])]
    return np.linalg.eigvals(np.column_stack(cols))


def _steady(tmp_path, rpm: float) -> dict:
    path = tmp_path / "scene.toml"
    path.write_text(SCENE % rpm)
    out = CliRunner().invoke(cli, ["simulate", str(path), "--format", "json"])
    assert out.exit_code == 0, out.output
    summary = json.loads(out.stdout)["summary"]
    assert summary["stages"][0]["contact_loss_fraction"] == 0.0  # in contact: the linear reference applies
    return summary["steady"]


@pytest.mark.parametrize("rpm", [4500.0, 4517.3])
def test_stable_says_whether_every_multiplier_is_inside_the_unit_circle(tmp_path, rpm):
    mu = _multipliers(rpm)
    steady = _steady(tmp_path, rpm)
    assert steady["periodicity"] == "period-1" and steady["method"] == "shooting"
    got = sorted(complex(re, im).real for re, im in steady["multipliers"])
    assert got == pytest.approx(sorted(mu.real), abs=1e-4)
    inside = bool(np.max(np.abs(mu)) < 1.0)
    assert inside == (rpm == 4500.0)  # the reference: 0.98652 at 4500 rpm, 1.00082 at 4517.3 rpm
    assert steady["stable"] is inside
