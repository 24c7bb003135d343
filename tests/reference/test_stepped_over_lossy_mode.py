"""The stepped-over-mode warning (``statistics_unresolved`` of gearcli/simulate/stepped_over.py) names the mode at
the frequency and damping the lossy chain rings with, as ``modes`` does.

One spur stage (z 21/64, m_n 3 mm, 20 deg) behind a speed drive, efficiency 0.95, a linear mesh law K = 5e5 N/mm
with a viscous damping ratio of 1e-4, the gear's 0.9 kg m^2 alone on the output: Radau at rtol 1e-3 steps over the
mesh mode the ramps ring. Hand model (DESIGN sections 4, 6, 9): the pinion's angle is prescribed, the forward mesh
passes eta of its force f = k delta + c delta' to the gear, c = 2 zeta sqrt(k m_e) with m_e = J_g / r_bg^2 (a speed
driven side counts as infinitely heavy), so J_g lambda^2 + eta c r_bg^2 lambda + eta k r_bg^2 = 0: 329.840 Hz,
damping ratio 9.747e-5. The warning named the lossless chain's 338.41 Hz (1 / sqrt(eta) higher) and ratio 1e-4.
"""

from __future__ import annotations

import json
import math

import numpy as np
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

SCENE = """
title = "one lossy spur stage behind a speed drive, light linear mesh"
[[stage]]
normal_module_mm = 3
helix_angle_deg = 0
efficiency = 0.95
pinion = { teeth = 21, face_width_mm = 40, hand = "spur", inertia_kg_m2 = 0.02 }
gear   = { teeth = 64, face_width_mm = 38, hand = "spur", inertia_kg_m2 = 0.9 }
[contact]
stiffness = 5.0e5
exponent = 1.0
damping_ratio = 1e-4
[input]
speed_rpm = 1480
ramp_s = 0.05
[load]
torque_Nm = 1000
ramp_s = 0.05
[simulation]
duration_s = 0.2
method = "Radau"
rtol = 1e-3
"""


def test_stepped_over_mode_is_the_lossy_chains(tmp_path):
    path = tmp_path / "lossy_light.toml"
    path.write_text(SCENE, encoding="utf-8")
    res = CliRunner().invoke(cli, ["simulate", str(path), "--format", "json", "-q"])
    assert res.exit_code == 0, res.output
    warned = [w for w in json.loads(res.stdout)["warnings"] if w["code"] == "statistics_unresolved"]
    rg, J, k, eta, zeta = 64 * 3 / 2 * math.cos(math.radians(20)) / 1000, 0.9, 5e8, 0.95, 1e-4
    c = 2 * zeta * math.sqrt(k * J / rg**2)
    lam = max(np.roots([J, eta * c * rg**2, eta * k * rg**2]), key=lambda z: z.imag)
    assert_allclose(lam.imag / (2 * math.pi), 329.840, atol=1e-3)
    assert warned, "Radau at rtol 1e-3 steps over the mode"
    for w in warned:
        assert_allclose(w["mode_Hz"], lam.imag / (2 * math.pi), rtol=1e-9)
        assert f"the {lam.imag / (2 * math.pi):.4g} Hz mode (damping ratio {-lam.real / abs(lam):.2g})" in w["message"]
