"""Issue 21, field test: outputs follow the design file's units (speed_rpm -> rpm columns, torque_Nm -> N·m
everywhere; the seed's speed_deg_s and torque_Nmm keep their names), and the simulate footer prints window
means, not a single end sample."""

from __future__ import annotations

import csv
import io
import json
import math
import re
from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]
SEED = str(ROOT / "configs" / "concrete_mixer.toml")
DRIVETRAIN = str(ROOT / "configs" / "concrete_mixer_drivetrain.toml")
RPM_NM = ("--set", "input.speed_rpm=600", "--set", "load.torque_Nm=5310")  # the same scene, other keys
I_TOTAL = (51 / 21) * (50 / 17) * (53 / 17)  # seed ratio, Table 1
SEED_HEADER = ("time_s,shaft1_speed_deg_s,shaft2_speed_deg_s,shaft3_speed_deg_s,shaft4_speed_deg_s,input_torque_Nmm,"
               + ",".join(f"stage{k}_{c}" for k in (1, 2, 3)
                          for c in ("tangential_N", "radial_N", "axial_N", "penetration_mm", "dte_um")))


def _run(path: str, fmt: str, *extra: str) -> str:
    res = CliRunner().invoke(cli, ["simulate", path, "--format", fmt, *extra])
    assert res.exit_code == 0, res.output
    return res.stdout


def test_seed_csv_header_is_unchanged():
    assert _run(SEED, "csv").partition("\n")[0] == SEED_HEADER


def test_rpm_and_newton_metre_file_writes_rpm_and_newton_metre_everywhere():
    args = ("--set", "simulation.duration_s=0.6", "--set", "simulation.steps=600", *RPM_NM)
    text = _run(DRIVETRAIN, "csv", *args)
    header = text.partition("\n")[0].split(",")
    assert {"shaft1_speed_rpm", "shaft4_speed_rpm", "motor_speed_rpm", "drum_speed_rpm", "input_torque_Nm",
            "input_coupling_torque_Nm", "load_coupling_torque_Nm"} <= set(header)
    assert not [h for h in header if h.endswith(("_deg_s", "_Nmm"))]  # no mixed units
    rows = list(csv.DictReader(io.StringIO(text)))
    # the motor follows the prescribed STEP to 600 rpm over the 1.5 s ramp: at 0.6 s, s = 0.4 and the speed is
    # 600 s^2 (3 - 2 s) = 211.2 rpm (by hand)
    (row,) = [r for r in rows if float(r["time_s"]) == pytest.approx(0.6)]
    assert float(row["motor_speed_rpm"]) == pytest.approx(600 * 0.4**2 * (3 - 2 * 0.4), rel=1e-9)
    # the output follows through the ratio within the drivetrain's ringing
    assert float(row["shaft4_speed_rpm"]) == pytest.approx(211.2 / I_TOTAL, rel=0.2)
    doc = json.loads(_run(DRIVETRAIN, "json", "--series", *args))
    summary = doc["summary"]
    assert summary["units"] == {"speed": "rpm", "torque": "Nm"}
    assert summary["output_speed_rpm"] == pytest.approx(summary["output_speed_deg_s"] / 6.0)
    assert "shaft1_speed_rpm" in doc["series"] and "input_torque_Nm" in doc["series"]
    table = _run(DRIVETRAIN, "table", *args)
    assert "°/s" not in table.split("dynamic ratio", 1)[1] and "N·mm" not in table


def test_a_newton_millimetre_file_writes_its_coupling_torques_in_newton_millimetres():
    args = ("--set", "simulation.duration_s=0.3", "--set", "simulation.steps=300")
    header = _run(DRIVETRAIN, "csv", *args).partition("\n")[0].split(",")
    assert "input_coupling_torque_Nmm" in header and "load_coupling_torque_Nmm" in header
    assert "input_torque_Nmm" in header and not [h for h in header if h.endswith("_Nm")]


def test_footer_prints_window_means_of_torque_and_power():
    """The seed at steady state needs T_L / i = 5310 / 22.27 = 238.4 N·m at 600 rpm = 14.98 kW (by hand); the
    window mean is within the ringing's averaging error (1 %); the old footer printed the end sample, 308 N·m."""
    table = " ".join(_run(SEED, "table").split())  # a terminal's width may fold the footer line
    m = re.search(r"input torque ([\d.e+]+) N·mm = ([\d.e+]+) N·m, power ([\d.e+]+) kW \(means over the steady "
                  r"window", table)
    assert m, table
    t_nm = 5310.0 / I_TOTAL
    assert float(m.group(2)) == pytest.approx(t_nm, rel=0.01)
    assert float(m.group(1)) == pytest.approx(1000 * float(m.group(2)), rel=1e-4)
    assert float(m.group(3)) == pytest.approx(t_nm * 600 * 2 * math.pi / 60 / 1000, rel=0.01)
    doc = json.loads(_run(SEED, "json"))
    assert doc["summary"]["input_torque_Nmm"] == pytest.approx(1000 * t_nm, rel=0.01)
