"""`gearcli modes --format csv` carries what its JSON and table carry: the modal damping ratio per mode.

Reference: a single spur mesh (linear, exponent 1, K = 2e5 N/mm, viscous ζ = 0.05 on the dynamic transmission
error) between a speed-driven pinion and a free gear, both inertias given. By DESIGN §6 the mesh damping is
c = 2 ζ √(k m_e) with m_e = J_g / r_bg² (the speed-driven pinion counts as infinitely heavy), so
- clamped input: the one mode is that very oscillator, ζ_1 = 0.05 exactly, f = √(k / m_e) / 2π;
- free: the mode's mass is m_f = J_p J_g / (J_p r_bg² + J_g r_bp²), the damper the same c, so
  ζ_2 = c / (2 √(k m_f)) = 0.05 √(m_e / m_f) = 0.05 √(1 + J_g r_bp² / (J_p r_bg²)), and the rigid mode 0.
"""

from __future__ import annotations

import csv
import io
import json
import math

from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

SCENE = """
title = "spur mesh, modal damping by hand"
[[stage]]
normal_module_mm = 3
normal_pressure_angle_deg = 20
pinion = { teeth = 25, face_width_mm = 20, hand = "spur", inertia_kg_m2 = 0.002 }
gear   = { teeth = 50, face_width_mm = 20, hand = "spur", inertia_kg_m2 = 0.02 }
[contact]
stiffness = 2e5
exponent = 1
damping_ratio = 0.05
[input]
speed_rpm = 1000
[load]
torque_Nm = 100
"""


def _modes(tmp_path, fmt):
    path = tmp_path / "spur.toml"
    path.write_text(SCENE)
    res = CliRunner().invoke(cli, ["modes", str(path), "--format", fmt, "-o", "-"], catch_exceptions=False)
    assert res.exit_code == 0, res.output
    return res.stdout


def test_modes_csv_has_the_damping_ratio_of_the_json_and_of_the_hand_calculation(tmp_path):
    rows = list(csv.DictReader(io.StringIO(_modes(tmp_path, "csv"))))
    doc = json.loads(_modes(tmp_path, "json"))
    # by hand: r_b = m z cos(20°) / 2
    r_bp = 3e-3 * 25 * math.cos(math.radians(20)) / 2
    r_bg = 3e-3 * 50 * math.cos(math.radians(20)) / 2
    k = 2e8  # N/m
    m_e = 0.02 / r_bg**2
    zeta_free = 0.05 * math.sqrt(1 + 0.02 * r_bp**2 / (0.002 * r_bg**2))  # 0.05 √3.5: J_g/J_p = 10, (r_bp/r_bg)² = 1/4
    expected = {("clamped_input", "1"): (math.sqrt(k / m_e) / (2 * math.pi), 0.05),
                ("free", "1"): (0.0, 0.0),
                ("free", "2"): (None, zeta_free)}
    assert {(r["boundary"], r["mode"]) for r in rows} == set(expected)
    for r in rows:
        f, zeta = expected[(r["boundary"], r["mode"])]
        # the eigenvalue's -Re λ/|λ| of the linearised model: exact but for rounding
        assert_allclose(float(r["damping_ratio"]), zeta, rtol=1e-9, atol=1e-12)
        if f is not None:
            assert_allclose(float(r["frequency_Hz"]), f, rtol=1e-9, atol=1e-9)
        js = doc["boundaries"][r["boundary"]][int(r["mode"]) - 1]
        assert float(r["damping_ratio"]) == js["damping_ratio"]  # the same number in both formats
        assert float(r["frequency_Hz"]) == js["frequency_Hz"]
