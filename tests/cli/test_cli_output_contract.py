"""The output contract across commands on scenes of their own (DESIGN §5, §7, §12): JSON ``warnings`` are
objects {code, message, ...data} in every command that computes them, in the order stderr says them."""

from __future__ import annotations

import json
import math
import re
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli
from gearcli.diagnostics import WARNING_SCHEMA

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from jsonschema_subset import valid  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
LIST_SCHEMA = {"type": "array", "items": WARNING_SCHEMA}

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


def test_life_json_warnings_are_objects_in_stderr_order(tmp_path):
    # they were plain strings: the only JSON whose warnings were not {code, message, ...} (DESIGN §12)
    path = tmp_path / "rated.toml"
    path.write_text(RATED_RPM)
    res = CliRunner().invoke(cli, ["life", str(path), "--static", "--format", "json"])
    assert res.exit_code == 0, res.output
    warnings = json.loads(res.stdout)["warnings"]
    assert warnings and valid(warnings, LIST_SCHEMA, LIST_SCHEMA), warnings
    assert [w["message"] for w in warnings] == _stderr_warnings(res)  # the same list in every format (§7)
    # the heavy point's own design warning keeps the rating's code and data, and names the point
    heavy = [w for w in warnings if w.get("point") == "heavy"]
    assert heavy and {w["code"] for w in heavy} <= {"bending_safety_low", "pitting_safety_low"}, heavy
    assert all(w["message"].startswith("duty point heavy: ") and w["stage"] == 1 for w in heavy)
    assert any(w["code"] == "bending_safety_low" and w["S"] < w["S_min"] == 1.4 for w in heavy), heavy
    # --static cannot count the duty's starts: said with its own code
    assert [w["code"] for w in warnings if "dynamic route only" in w["message"]] == ["starts_not_counted"]


@pytest.mark.parametrize("command", ["design", "modes", "life"])
def test_planetary_warnings_fit_the_warning_schema(command, tmp_path):
    # the NREL 5 MW stage 1 rates its ring below S_Hmin = 1.25 (S_H 0.86): these warnings name member "ring", which
    # the schema's member enum (pinion, gear) refused
    args = [command, str(ROOT / "configs" / "planetary_stage.toml"), "--format", "json"]
    if command == "life":
        args += ["--static", "--set", 'duty=[{name="rated", hours=1000, torque_Nm=999650.9, speed_rpm=12.127}]']
    res = CliRunner().invoke(cli, args)
    assert res.exit_code == 0, res.output
    warnings = json.loads(res.stdout)["warnings"]
    assert {"ring"} <= {w.get("member") for w in warnings}, warnings
    assert valid(warnings, LIST_SCHEMA, LIST_SCHEMA), [w for w in warnings if not valid([w], LIST_SCHEMA, LIST_SCHEMA)]
    assert [w["message"] for w in warnings] == _stderr_warnings(res)


# two helical stages in the seed's units (°/s, N·mm), each losing power (η 0.97, 0.98), the load reversed so that
# the power flows from the output back to the input
LOSSY_REVERSED = """
title = "two lossy helical stages, load reversed"
[materials.steel]
density_kg_m3 = 7850
youngs_modulus_MPa = 2.1e5
poisson_ratio = 0.3
[[stage]]
normal_module_mm = 5
normal_pressure_angle_deg = 20
helix_angle_deg = 15
efficiency = 0.97
pinion = { teeth = 23, face_width_mm = 60, hand = "left", material = "steel" }
gear   = { teeth = 67, face_width_mm = 55, hand = "right", material = "steel" }
[[stage]]
normal_module_mm = 8
normal_pressure_angle_deg = 20
helix_angle_deg = 10
efficiency = 0.98
pinion = { teeth = 19, face_width_mm = 90, hand = "right", material = "steel" }
gear   = { teeth = 71, face_width_mm = 85, hand = "left", material = "steel" }
[input]
speed_deg_s = 6000
ramp_s = 0.1
[load]
torque_Nmm = -2.0e6
ramp_s = 0.1
[simulation]
duration_s = 1.0
steps = 4000
"""


def test_dynamic_factor_of_a_reversed_load_through_lossy_meshes(tmp_path):
    """A reversed load drives the train from its output: each mesh's driving side is its gear, which gets the whole
    law force f (docs/physics.md, sigma = -1), and the pinion η f. By hand, on the pitch circles (r = z m_n / (2 cos β)):
    stage 2 carries F_t2 = T / r_g2; its pinion passes η2 F_t2 r_p2 on to the gear of stage 1: F_t1 = η2 F_t2 r_p2 / r_g1.
    The steady window's mean equals these, and K_v = max |F_t| / that is 1 within the window's ripple (it was 1/η1,
    1/η2 high: the reference took the pinion side's η f)."""
    r = lambda z, m, beta: z * m / (2 * math.cos(math.radians(beta)))  # noqa: E731  pitch radius, mm
    f2 = 2.0e6 / r(71, 8, 10)  # N·mm / mm
    f1 = 0.98 * f2 * r(19, 8, 10) / r(67, 5, 15)
    path = tmp_path / "reversed.toml"
    path.write_text(LOSSY_REVERSED)
    res = CliRunner().invoke(cli, ["simulate", str(path), "--format", "json", "-q"])
    assert res.exit_code == 0, res.output
    stages = json.loads(res.stdout)["summary"]["stages"]
    for st, hand in zip(stages, (f1, f2), strict=True):
        assert_allclose(st["simulated_static_tangential_N"], -hand, rtol=1e-9)  # statics: rounding only
        # a settled, unexcited window's mean: to a few times the run's rtol (1e-6), whichever method auto takes
        assert_allclose(st["tangential_N"]["mean"], -hand, rtol=2e-5)
        ripple = (st["tangential_N"]["max"] - st["tangential_N"]["min"]) / hand
        assert 1.0 <= st["dynamic_factor"] <= 1.0 + ripple + 1e-9, (st["dynamic_factor"], ripple)
        assert ripple < 1e-3  # the window is steady: K_v ≈ 1, far from 1/η (1.02, 1.03)


# one helical stage in rad/s and N·m (the fourth speed/torque combination: neither the seed's °/s nor rpm)
RAD_S_NM = """
title = "one helical stage, rad/s and N*m"
[[stage]]
normal_module_mm = 4
normal_pressure_angle_deg = 20
helix_angle_deg = 12
pinion = { teeth = 19, face_width_mm = 75, hand = "left" }
gear   = { teeth = 74, face_width_mm = 70, hand = "right" }
[input]
speed_rad_s = 150.0
[load]
torque_Nm = 700
"""


def test_design_writes_a_rad_s_and_n_m_file_in_its_units(tmp_path):
    """DESIGN §12: speeds in the unit of the input's speed key, torques in the load's (N·m everywhere). The design
    JSON kept only °/s and rpm (no rad/s anywhere) and N·mm at the top; the contract's fixed keys stay beside."""
    path = tmp_path / "rad.toml"
    path.write_text(RAD_S_NM)
    res = CliRunner().invoke(cli, ["design", str(path), "--format", "json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    ratio = 74 / 19
    assert doc["units"] == {"speed": "rad_s", "torque": "Nm"}
    assert_allclose(doc["input_speed_rad_s"], 150.0, rtol=1e-12)
    assert_allclose(doc["output_speed_rad_s"], 150.0 / ratio, rtol=1e-12)
    assert_allclose(doc["output_speed_rpm"], 150.0 / ratio * 30 / math.pi, rtol=1e-12)  # the fixed keys stay
    assert_allclose(doc["output_torque_Nm"], 700.0, rtol=1e-12)
    assert_allclose(doc["input_torque_Nm"], 700.0 / ratio, rtol=1e-12)  # lossless
    assert_allclose(doc["input_torque_Nmm"], 700e3 / ratio, rtol=1e-12)
    stage = doc["stages"][0]
    assert_allclose(stage["pinion"]["speed_rad_s"], 150.0, rtol=1e-12)
    assert_allclose(stage["gear"]["speed_rad_s"], 150.0 / ratio, rtol=1e-12)
    assert_allclose([sh["speed_rad_s"] for sh in doc["shafts"]], [150.0, 150.0 / ratio], rtol=1e-12)
    csv = CliRunner().invoke(cli, ["design", str(path), "--format", "csv"])
    assert {"pinion_speed_rad_s", "gear_speed_rad_s"} <= set(csv.stdout.splitlines()[0].split(","))
    table = CliRunner().invoke(cli, ["design", str(path), "--format", "table"], env={"COLUMNS": "120"})
    assert "speed [rad/s]" in table.stdout and f"output {150.0 / ratio:.5g} rad/s" in table.stdout
    assert "°/s" not in table.stdout and "N·mm" not in table.stdout  # the file's units in the table too


def test_a_seed_unit_file_states_its_units_and_adds_no_other_speed_key(tmp_path):
    path = tmp_path / "a.toml"
    path.write_text(LOSSY_REVERSED)
    doc = json.loads(CliRunner().invoke(cli, ["design", str(path), "--format", "json"]).stdout)
    assert doc["units"] == {"speed": "deg_s", "torque": "Nmm"}
    assert not [k for k in doc if k.endswith(("_rad_s", "_torque_Nm"))]
    assert "speed_rad_s" not in doc["stages"][0]["pinion"]


@pytest.mark.parametrize(("option", "args"), [("--vary", ["--vary", "stage.0.pinion.teath=20,21"]),
                                               ("--random", ["--samples", "2", "--random", "nosuch=normal(1,0.1)"])])
def test_sweep_names_the_option_of_a_bad_key(option, args, tmp_path):
    # the message named --set for a key the user gave to --vary or --random
    path = tmp_path / "rad.toml"
    path.write_text(RAD_S_NM)
    res = CliRunner().invoke(cli, ["sweep", str(path), *args, "--jobs", "1"])
    assert res.exit_code == 2 and res.stdout == ""
    assert res.stderr.startswith(f"gearcli: {option}: ") and "Traceback" not in res.stderr, res.stderr
    res = CliRunner().invoke(cli, ["sweep", str(path), "--vary", "input.speed_rad_s=100,150", "--set", "nosuch=1"])
    assert res.exit_code == 2 and res.stderr.startswith("gearcli: --set: nosuch: ")


def test_report_design_section_in_the_files_units(tmp_path):
    path = tmp_path / "rad.toml"
    path.write_text(RAD_S_NM + "[simulation]\nduration_s = 0.2\nsteps = 400\n")
    res = CliRunner().invoke(cli, ["report", str(path), "--quick", "--format", "json", "-q"])
    assert res.exit_code == 0, res.output
    d = json.loads(res.stdout)["design"]
    ratio = 74 / 19
    assert d["units"] == {"speed": "rad_s", "torque": "Nm"}
    assert_allclose(d["shaft_speeds_rad_s"], [150.0, 150.0 / ratio], rtol=1e-12)
    assert_allclose([d["input_torque_Nm"], d["output_torque_Nm"]], [700.0 / ratio, 700.0], rtol=1e-12)
    assert_allclose(d["shaft_speeds_deg_s"][0], 150.0 * 180 / math.pi, rtol=1e-12)  # the fixed key stays


def test_sweep_legend_says_no_direction_for_independent_points():
    from gearcli.io.sweep_plots import _label  # the legend of the response curves (gearcli sweep --plots)

    assert _label(("none",), []) == ""  # was "none" (the legend read "none mean", "none min", "none max")
    assert _label(("up",), []) == "up"
    assert _label(("none", "20"), ["stage.0.pinion.teeth"]) == "(stage.0.pinion.teeth=20)"
    assert _label(("down", "20"), ["stage.0.pinion.teeth"]) == "down (stage.0.pinion.teeth=20)"


def test_modes_table_gives_crossing_speeds_in_the_files_unit(tmp_path):
    """The modes table said "input rpm" whatever the file's speed key (DESIGN §12: tables in its unit). The crossing
    of the mesh's 1x order with a mode at f: z1 n = f, so n = f / 19 rev/s = 2π f / 19 rad/s."""
    path = tmp_path / "rad.toml"
    path.write_text(RAD_S_NM)
    drum = ["--set", "load.inertia_kg_m2=20", "--set", "load.coupling_stiffness_Nm_rad=2e5"]  # a low mode
    doc = json.loads(CliRunner().invoke(cli, ["modes", str(path), *drum, "--format", "json"]).stdout)
    crossing = next(c | {"f": m["frequency_Hz"]} for modes in doc["boundaries"].values() for m in modes
                    for c in m["crossings"] if c["excitation"] == "stage 1 mesh 1x")
    assert_allclose(crossing["input_speed_rpm"], 60 * crossing["f"] / 19, rtol=1e-9)
    table = CliRunner().invoke(cli, ["modes", str(path), *drum, "--format", "table", "-q"],
                               env={"COLUMNS": "400"}).stdout
    assert "[input rad/s]" in table and "input rpm" not in table
    assert f"stage 1 mesh 1x @ {2 * math.pi * crossing['f'] / 19:.4g} " in table
    assert f"crossings for input 0 .. {1.2 * 150.0:.5g} rad/s" in table  # 0 … 1.2 × nominal


@pytest.mark.parametrize(("speed", "unit"), [("input.speed_rpm=1432.4", "rpm"), ("input.speed_rad_s=150", "rad/s")])
def test_report_footer_speed_in_the_files_unit(tmp_path, speed, unit):
    """The report's footer printed °/s first whatever the file's key (`simulate`'s footer already followed it).
    Lossless and steady: output = input / (74/19)."""
    path = tmp_path / "rad.toml"
    path.write_text(RAD_S_NM + "[simulation]\nduration_s = 0.2\nsteps = 400\n")
    res = CliRunner().invoke(cli, ["report", str(path), "--quick", "--format", "markdown", "-q", "--set", speed])
    assert res.exit_code == 0, res.output
    footer = next(line for line in res.stdout.splitlines() if "dynamic ratio" in line)
    value = float(speed.split("=")[1]) / (74 / 19)
    assert "°/s" not in footer and re.search(rf"output ([\d.]+) {re.escape(unit)}", footer), footer
    assert_allclose(float(re.search(rf"output ([\d.]+) {re.escape(unit)}", footer).group(1)), value, rtol=1e-4)


def test_life_duty_table_in_the_load_keys_torque_unit(tmp_path):
    """The duty table printed N·m whatever the file's torque key (DESIGN §12: torque_Nmm -> N·mm everywhere); the
    JSON keeps the contract's `torque_Nm`. 600 N·m as `torque_Nmm = 6e5` on the load and the duty."""
    text = RATED_RPM.replace("torque_Nm = 600\nramp_s", "torque_Nmm = 6e5\nramp_s", 1)
    assert "torque_Nmm = 6e5" in text
    path = tmp_path / "nmm.toml"
    path.write_text(text)
    table = CliRunner().invoke(cli, ["life", str(path), "--static", "--format", "table", "-q"], env={"COLUMNS": "200"})
    assert table.exit_code == 0, table.output
    assert "output torque [N·mm]" in table.stdout and "output torque [N·m]" not in table.stdout
    row = next(line for line in table.stdout.splitlines() if "│ nominal" in line)
    assert "6e+05" in row, row  # 600 N·m in N·mm
    doc = json.loads(CliRunner().invoke(cli, ["life", str(path), "--static", "--format", "json", "-q"]).stdout)
    assert [p["torque_Nm"] for p in doc["life"]["points"]] == [600.0, 4000.0]  # the JSON's fixed key, N·m
    rpm = CliRunner().invoke(cli, ["life", str(tmp_path / "nmm.toml"), "--static", "-q", "--format", "table",
                                   "--set", "load.torque_Nm=600"], env={"COLUMNS": "200"})
    assert "output torque [N·m]" in rpm.stdout
