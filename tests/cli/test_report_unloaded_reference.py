"""`gearcli report` names the force an unloaded stage's sampling error refers to: the rms of its F_t over the window
(gearcli.simulate.estimate.force_reference), not its mean, which is round-off or rattle and near zero. Before, the
report's line said "… of the mean" of that rms (a rattling unloaded stage: 6.5e-06 "of the mean" with the mean
0.68 N, the error 0.00024 N: 6.5e-06 of the 36.7 N rms)."""

from __future__ import annotations

import json
import math
import re

from click.testing import CliRunner

from gearcli.cli import cli

#: one spur stage, 0.05 mm backlash, no load, an 8 um transmission error: the gear floats and rattles in the gap
SCENE = (
    'title = "unloaded rattle"\n'
    "stage = [{ normal_module_mm = 3, normal_pressure_angle_deg = 20, backlash_mm = 0.05, "
    "pinion = { teeth = 21, face_width_mm = 30 }, gear = { teeth = 40, face_width_mm = 30 }, "
    "mesh = { transmission_error_um = [8.0] } }]\n"
    "input = { speed_rpm = 1200, ramp_s = 0.01 }\nload = { torque_Nm = 0 }\n"
    "simulation = { duration_s = 0.05, steps = 2000 }\n")


def test_an_unloaded_stage_s_sampling_error_is_named_against_the_rms_of_its_force(tmp_path):
    path = tmp_path / "unloaded.toml"
    path.write_text(SCENE)
    run = CliRunner()
    doc = run.invoke(cli, ["report", str(path), "--quick", "--format", "json", "-q"])
    assert doc.exit_code == 0, doc.output
    (stage,) = json.loads(doc.stdout)["simulation"]["summary"]["stages"]
    assert stage["static_tangential_N"] == 0.0
    ft, error = stage["tangential_N"], stage["sampling_error"]
    rms = math.hypot(ft["mean"], ft["std"])  # the window rms of F_t from its mean and standard deviation
    assert abs(error["reference_N"] - rms) <= 1e-9 * rms
    md = run.invoke(cli, ["report", str(path), "--quick", "--format", "markdown", "-q"])
    assert md.exit_code == 0, md.output
    (line,) = [x for x in md.stdout.splitlines() if "sampling error of the window min / max" in x]
    found = re.search(r"\(([0-9.e+-]+) / ([0-9.e+-]+) of the rms ([0-9.e+-]+) N of the unloaded stage's F_t,", line)
    assert found, line
    assert abs(float(found.group(3)) - rms) <= 1e-3 * rms  # printed to 4 figures
    assert abs(float(found.group(1)) - error["min_N"] / rms) <= 0.06 * float(found.group(1)) + 1e-300
