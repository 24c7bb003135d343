"""The output contract across commands on scenes of their own (DESIGN §5, §7, §12): JSON ``warnings`` are
objects {code, message, ...data} in every command that computes them, in the order stderr says them."""

from __future__ import annotations

import json

from click.testing import CliRunner

from gearcli.cli import cli
from gearcli.diagnostics import WARNING_SCHEMA

# one rated helical stage in rpm and N·m with a two-point duty; the "heavy" point's torque (4000 N·m, 6.7x the
# nominal 600 N·m) takes the root stress over the permissible one (S_F ≈ 1.15 < S_Fmin = 1.4 and S_H ≈ 0.84 <
# S_Hmin = 1.0 by `gearcli design --set load.torque_Nm=4000`; at 600 N·m S_F ≈ 4.5, no warning), so the point's
# design warns, naming the point
RATED_RPM = """
title = "one rated helical stage, rpm and N*m"
[materials.case]
density_kg_m3 = 7830
youngs_modulus_MPa = 206000
poisson_ratio = 0.3
treatment = "case_carburized"
contact_fatigue_limit_MPa = 1500
bending_fatigue_limit_MPa = 430
[[stage]]
normal_module_mm = 3
normal_pressure_angle_deg = 20
helix_angle_deg = 18
accuracy_grade = 6
pinion = { teeth = 21, face_width_mm = 40, hand = "left", material = "case", flank_roughness_Rz_um = 3, root_roughness_Rz_um = 12 }
gear   = { teeth = 83, face_width_mm = 38, hand = "right", material = "case", flank_roughness_Rz_um = 3, root_roughness_Rz_um = 12 }
[lubricant]
viscosity_40C_mm2_s = 150
[input]
speed_rpm = 1450
ramp_s = 0.05
[load]
torque_Nm = 600
ramp_s = 0.05
[rating]
required_life_h = 20000
[simulation]
duration_s = 0.3
steps = 1500
[[duty]]
name = "nominal"
hours = 15000
torque_Nm = 600
speed_rpm = 1450
starts = 10
[[duty]]
name = "heavy"
hours = 50
torque_Nm = 4000
speed_rpm = 1450
"""


def _stderr_warnings(res) -> list[str]:
    return [line[len("warning: "):] for line in res.stderr.splitlines() if line.startswith("warning: ")]


def _is_warning_object(w) -> bool:
    return (isinstance(w, dict) and set(WARNING_SCHEMA["required"]) <= set(w) and isinstance(w["code"], str)
            and isinstance(w["message"], str))


def test_life_json_warnings_are_objects_in_stderr_order(tmp_path):
    # they were plain strings: the only JSON whose warnings were not {code, message, ...} (DESIGN §12)
    path = tmp_path / "rated.toml"
    path.write_text(RATED_RPM)
    res = CliRunner().invoke(cli, ["life", str(path), "--static", "--format", "json"])
    assert res.exit_code == 0, res.output
    warnings = json.loads(res.stdout)["warnings"]
    assert warnings and all(_is_warning_object(w) for w in warnings), warnings
    assert [w["message"] for w in warnings] == _stderr_warnings(res)  # the same list in every format (§7)
    # the heavy point's own design warning keeps the rating's code and data, and names the point
    heavy = [w for w in warnings if w.get("point") == "heavy"]
    assert heavy and {w["code"] for w in heavy} <= {"bending_safety_low", "pitting_safety_low"}, heavy
    assert all(w["message"].startswith("duty point heavy: ") and w["stage"] == 1 for w in heavy)
    assert any(w["code"] == "bending_safety_low" and w["S"] < w["S_min"] == 1.4 for w in heavy), heavy
    # --static cannot count the duty's starts: said with its own code
    assert [w["code"] for w in warnings if "dynamic route only" in w["message"]] == ["starts_not_counted"]
