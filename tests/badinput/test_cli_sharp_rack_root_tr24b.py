"""A parallel stage's member cut by a sharp basic rack (``basic_rack.root_radius = 0``) at x = h_fP* (trial tr24b).

ISO 6336-3 (method B): G = ρ_fP/m_n − h_fP/m_n + x = 0 puts the tool's corner on the reference line, which rolls
without slip on the reference circle, so it cuts no trochoid and the fillet radius ρ_F = ρ_fP + 2 G² m_n /
(cos θ (z_n cos² θ − 2 G)) is 0: the notch parameter q_s = s_Fn / (2 ρ_F) divided by zero and `gearcli design`
stopped with "internal error: ZeroDivisionError" (exit 1). It is now exit 2 naming the key, as the planetary ring's
sharp root already was (tests/badinput/test_cli_contract_tr17d.py). A shift a little off that point (G ≠ 0) leaves a
fillet, ρ_F > 0 by the same formula, and rates with a finite Y_S.
"""

from __future__ import annotations

import json
import math

import pytest
from click.testing import CliRunner

from gearcli.cli import cli

SCENE = """title = "spur pair cut by a sharp rack, the wheel shifted by its dedendum"
[materials.c]
density_kg_m3 = 7850
youngs_modulus_MPa = 206000
poisson_ratio = 0.3
treatment = "case_carburized"
contact_fatigue_limit_MPa = 1500
bending_fatigue_limit_MPa = 450
[[stage]]
normal_module_mm = 3
accuracy_grade = 6
basic_rack = {{ addendum = 1.0, dedendum = 1.25, root_radius = 0 }}
pinion = {{ teeth = 20, face_width_mm = 30, material = "c", profile_shift = -0.25, flank_roughness_Rz_um = 3, root_roughness_Rz_um = 10 }}
gear = {{ teeth = 61, face_width_mm = 30, material = "c", profile_shift = {x}, flank_roughness_Rz_um = 3, root_roughness_Rz_um = 10 }}
[input]
speed_rpm = 1500
[load]
torque_Nm = 600
[lubricant]
viscosity_40C_mm2_s = 220
[rating]
required_life_h = 20000
"""
DUTY = '\n[[duty]]\nname = "run"\nhours = 1000\ntorque_Nm = 600\nspeed_rpm = 1500\n'


@pytest.mark.parametrize("command", [["design"], ["life", "--static"]])
def test_a_sharp_rack_root_at_x_equal_to_the_dedendum_is_refused_naming_the_key(command, tmp_path):
    design = tmp_path / "sharp.toml"
    design.write_text(SCENE.format(x=1.25) + (DUTY if command[0] == "life" else ""))  # G = 0 − 1.25 + 1.25 = 0
    out = tmp_path / "out.json"
    res = CliRunner().invoke(cli, [*command, str(design), "-o", str(out)])
    assert res.exit_code == 2, (res.exit_code, res.stderr)
    assert f"gearcli: {design}: stage[0].basic_rack.root_radius: " in res.stderr, res.stderr
    assert "ρ_F = 0" in res.stderr and "61-tooth" in res.stderr
    assert "Traceback" not in res.stderr and "internal error" not in res.stderr, res.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["sharp.toml"]  # no output, no temporary file


def test_off_that_shift_the_trochoid_rounds_the_root(tmp_path):
    """x = 1.2: G = −0.05, θ from ISO's iteration by hand, ρ_F = 2 G² m_n / (cos θ (z_n cos² θ − 2G)) > 0, the
    rating's finite Y_S, and the q_s warning (far above 8)."""
    design = tmp_path / "near.toml"
    design.write_text(SCENE.format(x=1.2))
    res = CliRunner().invoke(cli, ["design", str(design), "--format", "json", "-q"])
    assert res.exit_code == 0, res.stderr
    doc = json.loads(res.stdout)
    gear = doc["stages"][0]["rating"]["gear"]
    m, z, an, g = 3.0, 61, math.radians(20.0), -0.05
    e = math.pi / 4 * m - 1.25 * m * math.tan(an)  # ρ_fP = 0
    h = 2 / z * (math.pi / 2 - e / m) - math.pi / 3
    theta = math.pi / 6
    for _ in range(200):
        theta = 2 * g / z * math.tan(theta) - h
    rho_f = 2 * g * g * m / (math.cos(theta) * (z * math.cos(theta) ** 2 - 2 * g))
    s_fn = m * (z * math.sin(math.pi / 3 - theta) + math.sqrt(3) * g / math.cos(theta))
    assert 0.0 < rho_f < 0.01 and s_fn / (2 * rho_f) > 8
    assert math.isfinite(gear["Y_S"]) and gear["Y_S"] > 1 and gear["S_F"] > 0
    assert any(w.get("quantity") == "q_s" and w.get("member") == "gear"
               and math.isclose(w["value"], s_fn / (2 * rho_f), rel_tol=1e-6) for w in doc["warnings"])
