"""CLI tests for `[simulation] steady` and the mesh-response outputs: JSON keys, CSV column, table lines,
exit codes (the contract of docs/output.md)."""

from __future__ import annotations

import csv
import io
import json
from pathlib import Path

from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]
OSCILLATOR = str(ROOT / "configs" / "backlash_oscillator.toml")
LINEAR = ("--set", "stage.0.backlash_mm=0", "--set", "contact.exponent=1", "--set", "contact.stiffness=1e6",
          "--set", "contact.full_damping_penetration_mm=0.001", "--set", "simulation.duration_s=2")
PERIODIC = ("--set", "simulation.steady=periodic")
STEADY_KEYS = {"mode", "period_s", "periods_to_converge", "periodicity", "converged", "residual"}


def run(*args):
    return CliRunner().invoke(cli, ["simulate", *args], catch_exceptions=False)


def test_periodic_json_has_steady_summary_and_stage_response():
    res = run(OSCILLATOR, *LINEAR, *PERIODIC, "--format", "json")
    assert res.exit_code == 0, res.stderr
    summary = json.loads(res.stdout)["summary"]
    steady = summary["steady"]
    assert STEADY_KEYS <= set(steady)
    assert steady["mode"] == "periodic" and steady["periodicity"] == "period-1" and steady["converged"] is True
    assert_allclose(steady["period_s"], 60 / (17 * 180), rtol=1e-12)  # one mesh period: 17 teeth at 180 rpm
    assert steady["residual"] <= 1.0
    stage = summary["stages"][0]
    assert set(stage["dte_um"]) == {"mean", "rms", "min", "max"}
    assert stage["dte_um"]["min"] <= stage["dte_um"]["mean"] <= stage["dte_um"]["max"]
    assert stage["contact_loss_fraction"] == 0.0 and stage["back_flank_fraction"] == 0.0
    assert stage["regime"] == "no impact"


def test_window_json_carries_the_mode_and_the_excitation_period():
    res = run(OSCILLATOR, "--format", "json", "--set", "simulation.duration_s=0.5")
    assert res.exit_code == 0, res.stderr
    steady = json.loads(res.stdout)["summary"]["steady"]
    assert steady["mode"] == "window" and steady["converged"] is None and steady["periodicity"] is None
    assert_allclose(steady["period_s"], 60 / (17 * 180), rtol=1e-12)


def test_csv_has_the_dte_column_after_each_stage_penetration():
    res = run(OSCILLATOR, *LINEAR, *PERIODIC, "--format", "csv")
    assert res.exit_code == 0
    header = next(csv.reader(io.StringIO(res.stdout)))
    assert header[header.index("stage1_penetration_mm") + 1] == "stage1_dte_um"


def test_table_shows_regime_and_the_steady_line():
    res = run(OSCILLATOR, *LINEAR, *PERIODIC, "--format", "table")
    assert res.exit_code == 0
    assert "regime" in res.stdout and "no impact" in res.stdout
    folded = " ".join(res.stdout.split())  # the console's width may fold the steady line
    assert "steady periodic: period" in folded and "period-1, converged" in folded
    assert "\\n" not in res.stdout  # each summary line is its own line, no escaped newline


def test_not_periodic_is_a_warning_on_stderr_not_a_failure():
    # 5 mesh periods after the ramps of a 0.4 s run: too few for shooting (or brute force) to settle
    res = run(OSCILLATOR, *PERIODIC, "--format", "json", "--set", "simulation.duration_s=0.4")
    assert res.exit_code == 0
    assert "did not repeat" in res.stderr
    assert json.loads(res.stdout)["summary"]["steady"]["periodicity"] == "none"


def test_bad_steady_value_is_exit_2_naming_the_key():
    res = run(OSCILLATOR, "--set", "simulation.steady=forever")
    assert res.exit_code == 2
    assert "simulation.steady" in res.stderr and "Traceback" not in res.stderr
