"""CLI tests for `gearcli simulate`: every format, the output contract of docs/output.md, exit codes.

The seed scene is shortened (0.25 s, 500 steps) where only the format is under test; reference
numbers are the corrected static theory of the seed paper (hand calculations beside them).
"""

from __future__ import annotations

import csv
import io
import json
from pathlib import Path

import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]
SEED = str(ROOT / "configs" / "concrete_mixer.toml")
SHORT = ("--set", "simulation.duration_s=0.25", "--set", "simulation.steps=500")


def run(*args, input=None):
    return CliRunner().invoke(cli, ["simulate", *args], input=input, catch_exceptions=False)


@pytest.fixture(scope="module")
def seed_json() -> dict:
    res = run(SEED, "--format", "json")
    assert res.exit_code == 0, res.stderr
    return json.loads(res.stdout)


def test_seed_json_summary_meets_issue_acceptance(seed_json):
    s = seed_json["summary"]
    # i = 51/21 * 50/17 * 53/17 = 22.2689; dynamic ratio within 0.05 %
    assert_allclose(s["ratio"], 51 / 21 * 50 / 17 * 53 / 17, rtol=5e-4)
    # static F_t of stage 1: T_in / r_1 = (5.31e6 / 22.2689) / (12 * 21 / (2 cos 12 deg)) = 1851.1 N;
    # F_r = F_t tan(alpha_t) = 688.8 N, F_a = F_t tan 12 deg = 393.5 N; means within 0.5 %
    stage1 = s["stages"][0]
    assert_allclose(stage1["tangential_N"]["mean"], 1851.1, rtol=5e-3)
    assert_allclose(stage1["radial_N"]["mean"], 688.8, rtol=5e-3)
    assert_allclose(stage1["axial_N"]["mean"], 393.5, rtol=5e-3)
    assert s["window_s"][1] == pytest.approx(0.5)
    for stage in s["stages"]:
        for ch in ("tangential_N", "radial_N", "axial_N"):
            assert set(stage[ch]) == {"mean", "min", "max", "std"}
            assert stage[ch]["min"] <= stage[ch]["mean"] <= stage[ch]["max"]


def test_seed_json_solver_block_states_its_numerics(seed_json):
    sv = seed_json["solver"]
    assert {"method", "rtol", "atol", "nfev", "njev", "steps", "wall_s", "energy_residual"} <= set(sv)
    assert sv["rtol"] == 1e-6 and sv["nfev"] > 0 and sv["steps"] > 0
    assert abs(sv["energy_residual"]) < 1e-4
    assert seed_json["gearcli_version"] and len(seed_json["input_sha256"]) == 64
    assert "series" not in seed_json  # only with --series


def test_series_only_with_flag():
    doc = json.loads(run(SEED, *SHORT, "--format", "json", "--series").stdout)
    series = doc["series"]
    assert len(series["time_s"]) == 501  # steps + 1
    assert series["time_s"][0] == 0.0 and series["time_s"][-1] == pytest.approx(0.25)
    assert len(series["stage3_axial_N"]) == 501


def test_csv_is_default_in_a_pipe_with_contract_columns():
    res = run(SEED, *SHORT)
    assert res.exit_code == 0
    rows = list(csv.reader(io.StringIO(res.stdout)))
    header = rows[0]
    expected = ["time_s", *[f"shaft{i}_speed_deg_s" for i in range(1, 5)], "input_torque_Nmm"]
    for k in range(1, 4):
        expected += [f"stage{k}_{q}" for q in ("tangential_N", "radial_N", "axial_N", "penetration_mm", "dte_um")]
    assert header == expected
    assert len(rows) == 1 + 501
    # at t = 0.25 s the input runs at the full 3600 deg/s (ramp over at 0.18 s): analytic STEP profile
    assert_allclose(float(rows[-1][1]), 3600.0, rtol=1e-9)
    # the output shaft turns at 3600 / 22.2689 = 161.66 deg/s within the ringing (a few per mille)
    assert_allclose(float(rows[-1][4]), 161.66, rtol=2e-2)


def test_table_format_and_warning_on_stderr():
    res = run(SEED, *SHORT, "--format", "table")
    assert res.exit_code == 0
    assert "dynamic ratio" in res.stdout and "energy residual" in res.stdout
    assert "warning:" in res.stderr  # the seed misses its 23 rpm target


def test_output_file_is_atomic_and_complete(tmp_path):
    out = tmp_path / "run.csv"
    res = run(SEED, *SHORT, "-o", str(out))
    assert res.exit_code == 0 and res.stdout == ""
    assert out.read_text().count("\n") == 502
    assert [p.name for p in tmp_path.iterdir()] == ["run.csv"]


def test_solver_failure_is_exit_1_with_cause_and_fix(tmp_path):
    # RK45 on the stiff scene made another 10^4 x stiffer (top mode ~1.1 MHz: stability alone would take
    # ~1e7 right-hand-side evaluations, ten times the 1e6 an explicit method is allowed): a clean exit-1 error that names an
    # implicit method as the fix, no traceback, and no output file -- even one that existed is left as it was
    out = tmp_path / "x.csv"
    out.write_text("previous\n")
    res = CliRunner().invoke(cli, ["simulate", str(ROOT / "configs" / "stiff_linear_mesh.toml"),
                                   "--set", "simulation.method=RK45", "--set", "stage.0.mesh.stiffness=1.4392e12",
                                   "-o", str(out)])
    assert res.exit_code == 1, res.stderr
    assert "Radau" in res.stderr and "Traceback" not in res.stderr
    assert out.read_text() == "previous\n"


# ------------------------------------------------------------------------------ drivetrain, modes
def test_drivetrain_scene_has_its_channels_and_a_labelled_boundary():
    scene = str(Path(__file__).resolve().parents[2] / "configs" / "concrete_mixer_drivetrain.toml")
    res = CliRunner().invoke(cli, ["simulate", scene, "--format", "json", "--series",
                                   "--set", "simulation.duration_s=0.3", "--set", "simulation.steps=300"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    assert doc["summary"]["natural_frequencies_boundary"] == "clamped_input"
    # issue 21: torques in the unit of the load's key (this file: torque_Nmm), so the couplings' too
    for name in ("shaft2_twist_deg", "shaft3_twist_deg", "motor_speed_deg_s", "drum_speed_deg_s",
                 "input_coupling_torque_Nmm", "load_coupling_torque_Nmm", "shaft4_speed_deg_s"):
        assert name in doc["series"], name
    assert "shaft5_speed_deg_s" not in doc["series"]  # shaft channels stay the reducer's


def test_modes_command_json_and_dump_model():
    scene = str(Path(__file__).resolve().parents[2] / "configs" / "concrete_mixer_drivetrain.toml")
    res = CliRunner().invoke(cli, ["modes", scene, "--format", "json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    free = doc["boundaries"]["free"]
    assert free[0]["rigid"] and free[0]["frequency_Hz"] == 0.0
    for mode in doc["boundaries"]["clamped_input"]:
        assert abs(sum(mode["energy_share"].values()) - 1.0) < 1e-12
    res = CliRunner().invoke(cli, ["simulate", scene, "--dump-model"])
    assert res.exit_code == 0 and "def rhs(t, y):" in res.stdout and "def jac(t, y):" in res.stdout
    csv_res = CliRunner().invoke(cli, ["modes", scene, "--format", "csv"])
    assert csv_res.exit_code == 0 and csv_res.stdout.startswith("boundary,mode,frequency_Hz")


def test_generated_code_shows_in_tracebacks():
    import linecache
    import traceback

    from gearcli.model import DriveSpec, LoadSpec, ModelSpec, TorsionalModel
    from gearcli.model.spec import MeshSpec

    mesh = MeshSpec(0.06, 0.15, 0.17, 0.36, 0.19, 4e10, 1.5, 5e4, 1e-4)
    model = TorsionalModel(ModelSpec((mesh,), (0.5, 8.0), DriveSpec("speed", 60.0), LoadSpec(100.0)))
    try:
        model.rhs(0.0, None)  # y.tolist() fails on the first generated line
    except AttributeError as exc:
        frames = traceback.extract_tb(exc.__traceback__)
    assert frames[-1].filename.startswith("gearcli/model/_generated_")
    assert "y.tolist()" in frames[-1].line and linecache.getline(frames[-1].filename, frames[-1].lineno)
