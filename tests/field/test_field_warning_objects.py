"""Issue 21, field test: JSON `warnings` are objects {code, message, the diagnostic's data}, the same list in
every format of every command that gives warnings (stderr and tables print the messages)."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli.cli import cli
from gearcli.diagnostics import WARNING_SCHEMA, Diagnostic, warning_objects

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from jsonschema_subset import valid  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
SEED = str(ROOT / "configs" / "concrete_mixer.toml")
LIST_SCHEMA = {"type": "array", "items": WARNING_SCHEMA}


def _stderr_warnings(stderr: str) -> list[str]:
    return [line[len("warning: "):] for line in stderr.splitlines() if line.startswith("warning: ")]


def test_the_schema_refuses_bare_strings_and_bad_codes():
    assert not valid(["a bare string"], LIST_SCHEMA, LIST_SCHEMA)
    assert not valid([{"code": "Not Snake", "message": "x"}], LIST_SCHEMA, LIST_SCHEMA)
    assert not valid([{"message": "x"}], LIST_SCHEMA, LIST_SCHEMA)
    assert valid([{"code": "window_ringing", "message": "x", "stage": 2}], LIST_SCHEMA, LIST_SCHEMA)


def test_a_list_of_statistics_is_named_under_statistic_too():
    diags = [Diagnostic("statistics_undersampled", "warning", "a", {"stage": 1, "statistics": ["min", "max"]}),
             Diagnostic("window_ringing", "warning", "b", {"stage": 1, "statistic": "mean, std"})]
    assert warning_objects(["a", "b"], diags) == [
        {"code": "statistics_undersampled", "message": "a", "stage": 1, "statistics": ["min", "max"],
         "statistic": "min, max"},
        {"code": "window_ringing", "message": "b", "stage": 1, "statistic": "mean, std"}]


def test_objects_keep_the_order_and_the_data():
    diags = [Diagnostic("resonance", "warning", "b", {"stage": 1, "amplification": float("inf")}),
             Diagnostic("design", "warning", "a", {"check": "target_speed"})]
    assert warning_objects(["a", "b", "c"], diags) == [
        {"code": "design", "message": "a", "stage": None, "check": "target_speed"},  # the train's: stage null
        {"code": "resonance", "message": "b", "stage": 1, "amplification": None},  # strict JSON: no infinity
        {"code": "other", "message": "c", "stage": None}]


@pytest.mark.parametrize("command", [["design"], ["simulate"], ["modes"], ["report", "--quick"]])
def test_every_command_writes_warning_objects_and_prints_their_messages(command):
    res = CliRunner().invoke(cli, [*command, SEED, "--format", "json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    warnings = doc["warnings"]
    assert valid(warnings, LIST_SCHEMA, LIST_SCHEMA), warnings
    # the seed misses its 23 rpm target by +17.1 % (26.94 rpm by hand: 600 x 21/51 x 17/50 x 17/53)
    (target,) = [w for w in warnings if w.get("check") == "target_speed"]
    assert target["code"] == "design" and target["target_rpm"] == 23.0
    assert target["output_speed_rpm"] == pytest.approx(600 * 21 / 51 * 17 / 50 * 17 / 53, rel=1e-12)
    assert [w["message"] for w in warnings] == _stderr_warnings(res.stderr)
    # every warning about statistics names them under the contract's key `statistic` (DESIGN §12), as
    # window_ringing does; statistics_unresolved/_undersampled keep their list `statistics` beside it
    listed = [w for w in warnings if "statistics" in w]
    for w in listed:
        assert w["statistic"] == ", ".join(w["statistics"]), w
    if command == ["simulate"]:  # the seed's 1025 window samples miss stage 1's min and max between them
        assert [(w["code"], w["stage"], w["statistic"]) for w in listed] == [("statistics_undersampled", 1, "min, max")]


def test_design_warning_data_names_stage_and_member():
    res = CliRunner().invoke(cli, ["design", SEED, "--format", "json", "--set", "stage.0.pinion.teeth=12"])
    assert res.exit_code == 0, res.output
    warnings = json.loads(res.stdout)["warnings"]
    (under,) = [w for w in warnings if w.get("check") == "undercut"]
    assert under["stage"] == 1 and under["member"] == "pinion" and under["teeth"] == 12
    assert valid(warnings, LIST_SCHEMA, LIST_SCHEMA)
