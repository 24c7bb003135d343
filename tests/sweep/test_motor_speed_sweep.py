"""A motor drive and a speed sweep (issue 30 item 6): a frequency converter follows each row's speed (constant
V/f: the motor's slip speed at a load does not depend on the supply), any other start refuses a speed sweep up
front (exit 2 naming the key), and --set input.drive=speed works on a motor file (its starting keys ignored with a
note)."""

from __future__ import annotations

import json
from pathlib import Path

from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]
DOL = str(ROOT / "configs" / "motor_direct_start.toml")
VFD = str(ROOT / "configs" / "motor_vfd.toml")


def test_a_speed_sweep_on_a_dol_motor_is_refused_up_front():
    res = CliRunner().invoke(cli, ["sweep", DOL, "--vary", "input.speed_rpm=1000,1460"])
    assert res.exit_code == 2
    assert "input.speed_rpm" in res.stderr and "motor_direct_start.toml" in res.stderr
    assert '"vfd"' in res.stderr and 'input.drive=' in res.stderr  # what to vary instead
    assert "Traceback" not in res.output


def test_a_vfd_speed_sweep_runs_each_row_at_its_design_speed():
    res = CliRunner().invoke(cli, ["sweep", VFD, "--vary", "input.speed_rpm=1000,1460", "--format", "json",
                                   "--set", "simulation.duration_s=1.5", "--jobs", "1"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    rows = doc["rows"] if isinstance(doc, dict) else doc
    assert [r["status"] for r in rows] == ["ok", "ok"]
    ratio = 75 / 19 * 68 / 19
    # constant V/f: at the same load torque the motor slips by the same speed at either supply, so each row runs
    # at its own speed plus the same small slip offset (the load is a little below the rated torque)
    offsets = [r["output_speed_rpm"] * ratio - r["input.speed_rpm"] for r in rows]
    assert_allclose(offsets[0], offsets[1], atol=1e-3)  # rpm (they agree to ~1e-7 rpm)
    assert abs(offsets[1]) < 0.01 * 1460  # the row runs at its design speed within 1 %


def test_drive_speed_override_on_a_motor_file_works_with_a_note():
    res = CliRunner().invoke(cli, ["design", DOL, "--set", 'input.drive="speed"', "--format", "json"])
    assert res.exit_code == 0, res.output
    warnings = [w["message"] if isinstance(w, dict) else w for w in json.loads(res.stdout)["warnings"]]
    assert any("starting" in w and "ignores" in w for w in warnings)


def test_drive_torque_override_on_a_motor_file_ignores_the_motor_with_a_note():
    res = CliRunner().invoke(cli, ["design", DOL, "--set", 'input.drive="torque"', "--set", "input.torque_Nm=95",
                                   "--format", "json"])
    assert res.exit_code == 0, res.output
    warnings = [w["message"] if isinstance(w, dict) else w for w in json.loads(res.stdout)["warnings"]]
    assert any("motor, starting" in w and 'drive = "torque" ignores them' in w for w in warnings)


def test_a_speed_sweep_on_a_vfd_with_a_table_motor_is_refused_up_front():
    # tr11a: a table has no rated point to set the converter's supply by, so its motor runs at the table's own
    # synchronous speed whatever speed_rpm says, and every row of the sweep ran at that one speed
    table = "input.motor={torque_speed=[[0,700],[1400,700],[1500,0]]}"
    res = CliRunner().invoke(cli, ["sweep", VFD, "--set", table, "--vary", "input.speed_rpm=1000,1460"])
    assert res.exit_code == 2, res.output
    assert "input.speed_rpm" in res.stderr and "torque_speed table" in res.stderr
    assert "Traceback" not in res.output
