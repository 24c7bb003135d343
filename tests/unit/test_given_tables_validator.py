"""The design file's validator of the tables a file gives (``gearcli.config.schema.validate_design``) is the whole
file's validator for that file: the same instance for every valid file and the same errors (location, message,
type) for every invalid one, in either order, and the class's own validator and JSON Schema keep every table.

The reference is pydantic's validator of the whole class (``DesignFile.model_validate``), built independently of
the restricted one."""

from __future__ import annotations

import copy
import os
import subprocess
import sys
import textwrap
import tomllib
from pathlib import Path

import pytest
from pydantic import ValidationError

from gearcli.config.schema import DesignFile, validate_design

ROOT = Path(__file__).resolve().parents[2]
FILES = sorted([*ROOT.glob("configs/*.toml"), *ROOT.glob("configs/extreme/*.toml"), *ROOT.glob("tests/badinput/*.toml"),
                *ROOT.glob("tests/reference/data/**/*.toml")])
SEED = ROOT / "configs" / "concrete_mixer.toml"


def _parsed(path: Path) -> dict | None:
    try:
        return tomllib.loads(path.read_text(encoding="utf-8-sig"))
    except (tomllib.TOMLDecodeError, UnicodeDecodeError):
        return None  # a syntax error: nothing to validate


def _outcome(validate, data: dict):
    try:
        result = validate(copy.deepcopy(data))
    except ValidationError as exc:
        return "error", [(e["loc"], e["msg"], e["type"]) for e in exc.errors(include_url=False)]
    return "valid", result, result.model_fields_set


def test_the_files_shipped_and_tested_validate_as_the_whole_class_does():
    compared = 0
    for path in FILES:
        data = _parsed(path)
        if data is None:
            continue
        assert _outcome(validate_design, data) == _outcome(DesignFile.model_validate, data), path.name
        compared += 1
    assert compared > 100  # configs/ and the bad inputs: valid and invalid files of every stage kind and table


@pytest.mark.parametrize("edit, what", [
    (lambda d: d["stage"][0].update(type="planetry"), "an unknown stage type names every registered kind"),
    (lambda d: d["stage"][0].update(type=5), "a stage type that is no string"),
    (lambda d: d["input"].update(motor={"rated_power_kW": -1}), "a motor table the file gives"),
    (lambda d: d["stage"][1].update(mesh={"exponent": 9}), "a mesh override in one stage"),
    (lambda d: d.update(bearing=[{"shaft": 1}]), "a bearing table"),
    (lambda d: d.update(rating={"required_life_h": "long"}), "a rating table"),
    (lambda d: d["stage"][0].update(shaft="stiff"), "a shaft table of the wrong type"),
    (lambda d: d.update(stage={"normal_module_mm": 3}), "stage as a table, not an array of tables"),
])
def test_errors_of_edited_seeds_are_the_whole_class_s(edit, what):
    data = tomllib.loads(SEED.read_text())
    edit(data)
    got = _outcome(validate_design, data)
    assert got[0] == "error", what
    assert got == _outcome(DesignFile.model_validate, data), what


def test_a_parallel_file_s_validator_holds_no_planetary_or_bearing_table_and_the_class_keeps_them():
    """In a fresh interpreter, as a one-shot command loads a file: what another test registered or built in this
    process (a plug-in kind's rebuild of the class) cannot hide or fake the restricted build."""
    code = textwrap.dedent(f"""
        import tomllib
        from pathlib import Path
        from gearcli.config import json_schema, schema
        from gearcli.config.schema import DesignFile, validate_design
        data = tomllib.loads(Path({str(SEED)!r}).read_text())
        validate_design(data)
        adapter = schema._BY_KINDS[(False, frozenset({{("parallel", schema.Stage)}}), frozenset())]  # kind, its table
        built = repr(adapter.core_schema)
        assert "PlanetaryStage" not in built and "Bearing" not in built and "Motor" not in built
        assert "Stage" in built and "PairGear" in built  # what the seed gives is validated
        # the class, its validator and its JSON Schema are the whole file's whatever was validated before
        assert "PlanetaryStage" in str(json_schema()) and "Bearing" in str(json_schema())
        planetary = tomllib.loads(Path({str(ROOT / "configs" / "planetary_stage.toml")!r}).read_text())
        assert type(DesignFile.model_validate(planetary).stage[0]).__name__ == "PlanetaryStage"
        print("ok")
    """)
    env = {**os.environ, "PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")}
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, cwd=ROOT)
    assert res.returncode == 0 and res.stdout.strip() == "ok", res.stderr[-2000:]