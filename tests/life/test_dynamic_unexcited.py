"""The dynamic route on a model without excitation: every engagement meets the steady force, so the damage is
the rating's at K_v = 1 and the output says so (``dynamic_unexcited``), naming the points.

Scene (not a shipped config): a through-hardened spur stage (27/61, m 5, b 56, grade 8) near its pitting
endurance limit, two duty points. Hand reference: the pinion's pitting damage from the S-N curve of ISO 6336-2:2006
Table 2 (St/V: 1.6 at 1e5, 1.0 at 5e7, 0.85 at 1e10, the last slope continued) at the stresses ``gearcli design``
prints at each point with K_A = 1 and K_v = 1 (an independent command), cycles = hours x 60 x speed.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

ZNT = ((1e5, 1.6), (5e7, 1.0), (1e10, 0.85))
POINTS = (("high", 2000.0, 1500.0, 960.0), ("rated", 8000.0, 1250.0, 960.0))  # name, hours, torque N m, rpm

SCENE = """
materials = { qt = { density_kg_m3 = 7850, youngs_modulus_MPa = 2.1e5, poisson_ratio = 0.3, treatment = "through_hardened", contact_fatigue_limit_MPa = 720, bending_fatigue_limit_MPa = 300 } }

[[stage]]
normal_module_mm = 5
accuracy_grade = 8
pinion = { teeth = 27, face_width_mm = 60, material = "qt", flank_roughness_Rz_um = 6, root_roughness_Rz_um = 16 }
gear   = { teeth = 61, face_width_mm = 56, material = "qt", flank_roughness_Rz_um = 6, root_roughness_Rz_um = 16 }

[input]
speed_rpm = 960
ramp_s = 0.1

[load]
torque_Nm = 1300
ramp_s = 0.1

[lubricant]
viscosity_40C_mm2_s = 320

[rating]
required_life_h = 10000
face_load_factor = 1.2

[simulation]
duration_s = 0.4
""" + "".join(f"""
[[duty]]
name = "{name}"
hours = {hours}
torque_Nm = {torque}
speed_rpm = {rpm}
""" for name, hours, torque, rpm in POINTS)


def _json(*args: str) -> dict:
    res = CliRunner().invoke(cli, ["-q", *args, "--format", "json"])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def _cycles_to_failure(stress: float, knee_stress: float) -> float:
    (n0, y0), (n1, y1), (n2, y2) = ZNT
    y = stress / knee_stress
    k = math.log(n1 / n0) / math.log(y0 / y1) if y >= y1 else math.log(n2 / n1) / math.log(y1 / y2)
    return n1 * (y1 / y) ** k


def test_an_unexcited_model_is_named_and_rated_at_k_v_one(tmp_path: Path):
    path = tmp_path / "spur.toml"
    path.write_text(SCENE)
    life = _json("life", str(path))
    flagged = [w for w in life["warnings"] if w["code"] == "dynamic_unexcited"]
    assert len(flagged) == 1 and flagged[0]["points"] == [p[0] for p in POINTS]
    damage = 0.0
    for _name, hours, torque, rpm in POINTS:
        rating = _json("design", str(path), "--set", f"load.torque_Nm={torque}", "--set", f"input.speed_rpm={rpm}",
                       "--set", "load.application_factor=1", "--set", "rating.dynamic_factor=1")["stages"][0]["rating"]
        member = rating["pinion"]
        knee = member["sigma_HG_MPa"] / member["Z_NT"]  # sigma_inf: the curve's stress at Z_NT = 1
        damage += hours * 60 * rpm / _cycles_to_failure(member["sigma_H_MPa"], knee)
    pitting = life["life"]["stages"][0]["pinion"]["pitting"]
    assert_allclose(pitting["damage"], damage, rtol=1e-9)
    static = _json("life", str(path), "--static")["life"]["stages"][0]["pinion"]["pitting"]
    assert static["damage"] > 2 * pitting["damage"]  # ISO's K_v 1.15-1.18 on a curve of slope ~13
    assert not [w for w in _json("life", str(path), "--static")["warnings"] if w["code"] == "dynamic_unexcited"]


def test_an_excited_model_is_not_named(tmp_path: Path):
    path = tmp_path / "spur_te.toml"
    path.write_text(SCENE.replace("[input]", "[contact]\ntransmission_error_um = [4.0]\n\n[input]"))
    life = _json("life", str(path))
    assert not [w for w in life["warnings"] if w["code"] == "dynamic_unexcited"]
    assert all(k > 1.01 for p in life["life"]["points"] for k in p["K_v"])
