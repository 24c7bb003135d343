"""The report's "orders within ±10 % of the mode at the nominal speed" and the `resonance` warning use one measure,
|f_e − f_m| / f_m at the nominal input speed (gearcli.model.modes.RESONANCE_BAND), checked on a hand-built scene.

A spur pair 20/40, m_n 3 mm, α_n 20°, linear mesh k = 2e5 N/mm, speed drive (the input is held by the drive, so the
clamped chain is one body): r_b2 = 40 · 3/2 · cos 20° = 56.382 mm and f_m = (1/2π) √(k r_b2² / J_2) = 567.5 Hz for
J_2 = 0.05 kg m². At 772 rpm the mesh's 2x order is 2 · 20 · 772/60 = 514.7 Hz, 9.3 % below the mode: the
warning names it; its crossing speed 772 · 567.5/514.7 = 851 rpm lies 10.3 % above the nominal speed, which the
report's column, measured in speed, used to leave out ("none" beside a warning that says "within 9.3 %").
"""

from __future__ import annotations

import math
from pathlib import Path

from click.testing import CliRunner

from gearcli.cli import cli
from gearcli.model.modes import near_nominal

PINION = '{ teeth = 20, face_width_mm = 30, material = "steel", inertia_kg_m2 = 0.002 }'
GEAR = '{ teeth = 40, face_width_mm = 30, material = "steel", inertia_kg_m2 = 0.05 }'
SCENE = f"""
title = "spur pair near its 2x mesh resonance"
materials.steel = {{ density_kg_m3 = 7850, youngs_modulus_MPa = 2.06e5, poisson_ratio = 0.3 }}
contact = {{ stiffness = 2e5, exponent = 1, damping_ratio = 0.05 }}
input = {{ speed_rpm = 772, ramp_s = 0.02 }}
load = {{ torque_Nm = 100, ramp_s = 0.02 }}
simulation = {{ duration_s = 0.1, steps = 2000 }}
stage = [{{ normal_module_mm = 3, normal_pressure_angle_deg = 20, pinion = {PINION}, gear = {GEAR} }}]
"""

def _hand() -> tuple[float, float]:
    r_b2 = 40 * 3.0 / 2.0 * math.cos(math.radians(20.0)) / 1000.0
    f_m = math.sqrt(2e8 * r_b2**2 / 0.05) / (2.0 * math.pi)
    f_e = 2 * 20 * 772 / 60.0
    return f_m, f_e


def test_the_hand_figures_straddle_the_two_measures():
    f_m, f_e = _hand()
    assert abs(f_m - 567.5) < 0.1
    assert abs(f_e - f_m) / f_m < 0.10 < abs(772 * f_m / f_e / 772 - 1.0)  # 9.3 % in frequency, 10.3 % in speed
    assert near_nominal(772 * f_m / f_e, 772)
    assert not near_nominal(772 * 1.12, 772) and not near_nominal(0.0, 772)


def test_report_lists_the_order_the_warning_names(tmp_path: Path):
    path = tmp_path / "near.toml"
    path.write_text(SCENE, encoding="utf-8")
    res = CliRunner().invoke(cli, ["report", str(path), "--quick", "--format", "markdown"])
    assert res.exit_code == 0, res.output
    f_m, f_e = _hand()
    modes = res.stdout.split("## Modes and resonances", 1)[1].split("## ", 1)[0]
    row = next(line for line in modes.splitlines() if line.startswith("| 1 |"))
    assert f"{f_m:.4g}"[:4] in row  # mode 1 is the hand's 567.5 Hz
    assert "stage 1 mesh 2x at" in row, row
    warned = res.stdout.split("## Warnings", 1)[1]
    assert "stage 1 mesh 2x order" in warned and f"within {100 * (f_m - f_e) / f_m:.2g} %" in warned
