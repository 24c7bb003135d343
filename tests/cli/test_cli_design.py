"""CLI tests for `gearcli design`, `init` and `schema`: every format and exit code.

Reference numbers are the seed paper's corrected values (docs/physics.md, "Design calculations" errata), each with its
hand calculation beside it.
"""

from __future__ import annotations

import csv
import io
import json
import math
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]
SEED = str(ROOT / "configs" / "concrete_mixer.toml")


@pytest.fixture
def runner() -> CliRunner:
    return CliRunner()


def run(runner, *args, input=None):
    return runner.invoke(cli, list(args), input=input, catch_exceptions=False)


def test_design_json_seed_acceptance_numbers(runner):
    res = run(runner, "design", SEED, "--format", "json")
    assert res.exit_code == 0, res.stderr
    doc = json.loads(res.stdout)
    # i = 51/21 * 50/17 * 53/17 = 135150/6069 = 22.26890...
    assert_allclose(doc["total_ratio"], 51 / 21 * 50 / 17 * 53 / 17, rtol=1e-12)
    assert_allclose(doc["total_ratio"], 22.2689, rtol=5e-6)
    # gear 2 turns at 3600 * 21/51 = 1482.35 deg/s (the paper's table says 1492: erratum)
    assert_allclose(doc["stages"][0]["gear"]["speed_deg_s"], 1482.35, rtol=5e-6)
    # output 3600 / 22.2689 = 161.66 deg/s = 26.94 rpm
    assert_allclose(doc["output_speed_deg_s"], 161.66, rtol=5e-5)
    assert_allclose(doc["output_speed_rpm"], 161.66 / 6, rtol=5e-5)
    # T_in = 5.31e6 / 22.2689 = 2.3845e5 N mm; F_t = T_in / (12*21/(2 cos 12deg)) = 1851.1 N
    assert_allclose(doc["input_torque_Nmm"], 5.31e6 / 22.26890, rtol=1e-5)
    forces = doc["stages"][0]["static_force_N"]
    assert_allclose(forces["tangential"], 1851.1, rtol=1e-4)
    assert_allclose(forces["radial"], 688.8, rtol=2e-4)  # F_t tan20/cos12
    assert_allclose(forces["axial"], 393.5, rtol=2e-4)  # F_t tan12
    # 1/E* = 2 (1 - 0.29^2) / 2.07e5 = 8.849e-6 /MPa (the paper's 8.743e-6 is an erratum)
    assert_allclose(doc["stages"][0]["effective_modulus_MPa"], 1.130e5, rtol=5e-4)
    # K = 4/3 sqrt(91.24 mm) 1.130e5 MPa = 1.439e6 N/mm^1.5 (the paper's 2.87e6 is an erratum)
    assert_allclose(doc["stages"][0]["hertz_stiffness_N_mm1_5"], 1.439e6, rtol=5e-4)
    assert any("23" in w["message"] and "rpm" in w["message"] for w in doc["warnings"]), doc["warnings"]
    assert doc["gearcli_version"]
    assert len(doc["input_sha256"]) == 64


def test_design_json_has_contract_keys(runner):
    doc = json.loads(run(runner, "design", SEED, "--format", "json").stdout)
    for key in ("total_ratio", "output_speed_deg_s", "output_speed_rpm", "input_torque_Nmm", "warnings", "stages"):
        assert key in doc
    stage_keys = ("ratio", "contact_ratio_transverse", "overlap_ratio", "contact_ratio_total", "center_distance_mm",
                  "equivalent_radius_mm", "effective_modulus_MPa", "hertz_stiffness_N_mm1_5", "mesh_frequency_Hz",
                  "static_force_N", "iso6336_single_pair_stiffness_N_mm_um", "iso6336_mesh_stiffness_N_mm_um",
                  "pinion", "gear")
    gear_keys = ("teeth", "pitch_diameter_mm", "base_diameter_mm", "tip_diameter_mm", "root_diameter_mm",
                 "speed_deg_s", "speed_rpm", "torque_Nmm", "inertia_kg_m2")
    for stage in doc["stages"]:
        assert set(stage_keys) <= set(stage)
        assert set(stage["static_force_N"]) >= {"tangential", "radial", "axial", "normal"}
        for part in ("pinion", "gear"):
            assert set(gear_keys) <= set(stage[part])


def test_design_csv_is_default_in_a_pipe_and_has_one_row_per_stage(runner):
    res = run(runner, "design", SEED)  # CliRunner's stdout is not a terminal
    assert res.exit_code == 0
    rows = list(csv.DictReader(io.StringIO(res.stdout)))
    assert len(rows) == 3
    assert [int(r["pinion_teeth"]) for r in rows] == [21, 17, 17]
    # stage 2 ratio 50/17
    assert_allclose(float(rows[1]["ratio"]), 50 / 17, rtol=1e-9)
    assert "warning:" in res.stderr and "warning" not in res.stdout


def test_design_table_format(runner):
    res = run(runner, "design", SEED, "--format", "table")
    assert res.exit_code == 0
    assert "total ratio 22.2689" in res.stdout
    assert "stage 3" in res.stdout


def test_output_file_format_from_suffix_and_atomic(runner, tmp_path):
    out = tmp_path / "d.json"
    res = run(runner, "design", SEED, "-o", str(out))
    assert res.exit_code == 0 and res.stdout == ""
    assert json.loads(out.read_text())["stages"][2]["gear"]["teeth"] == 53
    assert [p.name for p in tmp_path.iterdir()] == ["d.json"]  # no temporary file left behind


def test_failed_run_leaves_existing_output_untouched(runner, tmp_path):
    out = tmp_path / "d.json"
    out.write_text("previous\n")
    bad = tmp_path / "bad.toml"
    bad.write_text(Path(SEED).read_text().replace("teeth = 21", "teeth = 0"))
    res = run(runner, "design", str(bad), "-o", str(out))
    assert res.exit_code == 2
    assert out.read_text() == "previous\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.toml", "d.json"]


def test_stdin_input_matches_file(runner):
    text = Path(SEED).read_text()
    a = json.loads(run(runner, "design", SEED, "--format", "json").stdout)
    b = json.loads(run(runner, "design", "-", "--format", "json", input=text).stdout)
    assert a == b


def test_set_override_changes_the_design(runner):
    # 22 pinion teeth: i1 = 51/22, total = 51/22 * 50/17 * 53/17
    res = run(runner, "design", SEED, "--format", "json", "--set", "stage.0.pinion.teeth=22")
    doc = json.loads(res.stdout)
    assert_allclose(doc["total_ratio"], 51 / 22 * 50 / 17 * 53 / 17, rtol=1e-12)


def test_bad_value_exit_2_names_file_and_key_without_traceback(runner, tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(Path(SEED).read_text().replace("teeth = 21", "teeth = 3"))
    res = run(runner, "design", str(bad))
    assert res.exit_code == 2
    assert "bad.toml" in res.stderr and "stage[0].pinion.teeth" in res.stderr
    assert "Traceback" not in res.stderr and res.stdout == ""


def test_unknown_key_hint(runner, tmp_path):
    bad = tmp_path / "typo.toml"
    bad.write_text(Path(SEED).read_text().replace("helix_angle_deg = 12", "helix_angel_deg = 12"))
    res = run(runner, "design", str(bad))
    assert res.exit_code == 2
    assert "helix_angel_deg" in res.stderr and "helix_angle_deg" in res.stderr


def test_same_hand_external_pair_is_exit_2_with_file_and_key(runner, tmp_path):
    bad = tmp_path / "hands.toml"
    bad.write_text(Path(SEED).read_text().replace('teeth = 51, face_width_mm = 180, hand = "right"',
                                                  'teeth = 51, face_width_mm = 180, hand = "left"'))
    res = run(runner, "design", str(bad))
    assert res.exit_code == 2
    assert "hands.toml" in res.stderr and "stage[0]" in res.stderr


def test_missing_file_and_usage_errors_exit_2(runner, tmp_path):
    assert run(runner, "design", str(tmp_path / "nope.toml")).exit_code == 2
    assert runner.invoke(cli, ["design"]).exit_code == 2  # missing argument: click usage error
    assert runner.invoke(cli, ["design", SEED, "--format", "xml"]).exit_code == 2


def test_init_writes_a_starter_that_designs_like_the_seed(runner, tmp_path):
    path = tmp_path / "starter.toml"
    assert run(runner, "init", str(path)).exit_code == 0
    text = path.read_text()
    assert text.lstrip().startswith("#")  # commented
    a = json.loads(run(runner, "design", str(path), "--format", "json").stdout)
    b = json.loads(run(runner, "design", SEED, "--format", "json").stdout)
    assert_allclose(a["total_ratio"], b["total_ratio"], rtol=1e-12)
    # refuses to overwrite without --force
    assert run(runner, "init", str(path)).exit_code == 2
    assert run(runner, "init", str(path), "--force").exit_code == 0


def test_init_to_stdout(runner):
    res = run(runner, "init")
    assert res.exit_code == 0 and "[[stage]]" in res.stdout


def test_schema_is_json_schema_of_the_design_file(runner):
    doc = json.loads(run(runner, "schema").stdout)
    assert {"stage", "input", "load"} <= set(doc["properties"])
    assert set(doc.get("required", [])) >= {"stage", "input", "load"}


def test_version(runner):
    res = run(runner, "--version")
    assert res.exit_code == 0 and "gearcli" in res.stdout


def test_design_never_imports_scipy():
    code = (
        "import sys\n"
        "from gearcli.cli import cli\n"
        "try:\n"
        f"    cli(['design', {SEED!r}, '--format', 'json'], prog_name='gearcli')\n"
        "except SystemExit as e:\n"
        "    assert e.code in (0, None), e.code\n"
        "assert 'scipy' not in sys.modules, 'gearcli design imported scipy'\n"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr


def test_python_dash_m_entry_point():
    proc = subprocess.run([sys.executable, "-m", "gearcli", "design", SEED, "--format", "json"],
                          capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    assert math.isclose(json.loads(proc.stdout)["total_ratio"], 22.2689, rel_tol=1e-5)
