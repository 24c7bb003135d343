"""A run that genuinely fails (exit 1) names its design file, as every gearcli error does (docs/output.md, "Exit
codes": messages "name the file (or `--set`) and the key path"). Before, a solver failure printed only its cause:
``gearcli: method = "RK45" cannot integrate this scene: ...`` without the file, so a script running many files
could not tell which one failed.

The scene: one helical stage with a linear mesh of 1e13 N/mm (1e16 N/m) on a 50 kg m^2 gear; the pinion's speed is
prescribed, so the mesh mode is a single-DOF oscillator, by hand: r_bg = m_n z cos(alpha_t) / (2 cos beta) =
12 * 51 * cos(20.41 deg) / (2 cos 12 deg) = 293.2 mm, m_e = J_g / r_bg^2 = 581.6 kg, cos beta_b = 0.9807 (sin beta_b =
sin beta cos alpha_n), k_t = k cos^2 beta_b = 9.62e15 N/m, omega = sqrt(k_t / m_e) = 4.07e6 rad/s (6.5e5 Hz); over
0.3 s max|lambda| T = 1.2e6, a hundred times what an explicit method affords: RK45 is refused up front (fast)."""

from __future__ import annotations

import math
import re

from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

SCENE = """\
title = "one stiff stage"
[[stage]]
normal_module_mm = 12
helix_angle_deg = 12
pinion = { teeth = 21, face_width_mm = 190, hand = "left" }
gear   = { teeth = 51, face_width_mm = 180, hand = "right", inertia_kg_m2 = 50 }
[contact]
stiffness = 1e13
exponent = 1
[input]
speed_rpm = 600
ramp_s = 0.1
[load]
torque_Nm = 580
ramp_s = 0.1
[simulation]
duration_s = 0.3
steps = 600
method = "RK45"
"""


def _scene(tmp_path):
    path = tmp_path / "stiff_one_stage.toml"
    path.write_text(SCENE)
    return path


def test_simulate_failure_names_the_file(tmp_path):
    path = _scene(tmp_path)
    out = tmp_path / "run.json"
    res = CliRunner().invoke(cli, ["simulate", str(path), "-q", "-o", str(out)])
    assert res.exit_code == 1, res.stderr
    first = res.stderr.splitlines()[0]
    assert first.startswith(f"gearcli: {path}: "), first
    assert 'method = "RK45" cannot integrate this scene' in first and "Radau" in first
    assert "Traceback" not in res.stderr and not out.exists()
    hz = float(re.search(r"highest mode ([0-9.e+]+) Hz", first).group(1))
    k_t = 1e16 * (1 - (math.sin(math.radians(12)) * math.cos(math.radians(20))) ** 2)
    alpha_t = math.atan(math.tan(math.radians(20)) / math.cos(math.radians(12)))
    r_bg = 12e-3 * 51 * math.cos(alpha_t) / (2 * math.cos(math.radians(12)))
    assert_allclose(hz, math.sqrt(k_t * r_bg**2 / 50.0) / (2 * math.pi), rtol=0.01)  # printed to 3 figures


def test_report_failure_names_the_file(tmp_path):
    path = _scene(tmp_path)
    res = CliRunner().invoke(cli, ["report", str(path), "-q", "--quick", "--format", "json"])
    assert res.exit_code == 1, res.stderr
    assert res.stderr.startswith(f"gearcli: {path}: "), res.stderr
    assert "Traceback" not in res.stderr
