"""Two output conventions (DESIGN §5, docs/output.md "Warnings"):

- a usage error that click finds (an unknown option or command, a missing argument, a bad choice) ends, as every
  other gearcli error, with a ``gearcli: `` line, exit 2 (it printed click's ``Error: ...``);
- every JSON warning carries ``stage``, null for one about the train (``target_speed`` had no ``stage`` key).
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]
TWO_STAGE = ROOT / "configs" / "industrial_two_stage.toml"


@pytest.mark.parametrize(("args", "message"), [
    (["design", "--bogus", "x.toml"], "No such option '--bogus'."),
    (["nocmd"], "No such command 'nocmd'."),
    (["simulate"], "Missing argument 'FILE'."),
    (["engine", "nosuch"], "No such command 'nosuch'."),
    (["design", str(TWO_STAGE), "--format", "xml"], "Invalid value for '--format': 'xml' is not one of"),
])
def test_click_usage_errors_carry_the_gearcli_prefix(args, message):
    res = CliRunner().invoke(cli, args, prog_name="gearcli")
    assert res.exit_code == 2, res.output
    last = res.stderr.strip().splitlines()[-1]
    assert last.startswith(f"gearcli: {message}"), res.stderr
    assert "Error:" not in res.stderr and "Traceback" not in res.stderr
    assert res.stderr.startswith("Usage: gearcli"), res.stderr  # the usage and the hint as click gives them


def test_a_train_warning_has_stage_null(tmp_path):
    # 1450 rpm through 75/19 and 68/19: 1450 * 19 * 19 / (75 * 68) = 102.637 rpm, 6.7 % under a 110 rpm target
    f = tmp_path / "target.toml"
    text = TWO_STAGE.read_text()
    assert "output_speed_rpm = 103.6" in text
    f.write_text(text.replace("output_speed_rpm = 103.6", "output_speed_rpm = 110"))
    res = CliRunner().invoke(cli, ["design", str(f), "--format", "json"])
    assert res.exit_code == 0, res.stderr
    warnings = json.loads(res.stdout)["warnings"]
    target = [w for w in warnings if w.get("check") == "target_speed"]
    assert len(target) == 1 and "stage" in target[0] and target[0]["stage"] is None
    assert target[0]["output_speed_rpm"] == pytest.approx(1450 * 19 * 19 / (75 * 68), rel=1e-12)
    assert all("stage" in w for w in warnings)
    assert [w["stage"] for w in warnings if w["code"] == "resonance"] == [1]  # a stage's warning keeps its stage
