"""The repository documents and checks itself: the generated reference equals the committed one, no file
points outside the repository, and the JSON Schema is never looser than validation on the example and
bad-input files (a tiny checker for the subset of JSON Schema gearcli emits, itself tested here)."""

from __future__ import annotations

import subprocess
import tomllib
from pathlib import Path

import pytest
from jsonschema_subset import valid

from gearcli.config import json_schema, load_design
from gearcli.config.reference import design_file_reference
from gearcli.design.inputs import check_inputs
from gearcli.errors import ConfigError, DesignError

ROOT = Path(__file__).resolve().parents[2]


def test_committed_design_file_reference_is_the_generated_one():
    assert (ROOT / "docs" / "design-file.md").read_text() == design_file_reference(), \
        "regenerate: python -m gearcli.config.reference > docs/design-file.md"


def test_every_table_of_the_schema_has_a_section_in_the_reference():
    """A model the reference leaves out (the planetary stage's, the motor's were) is a key a user cannot look up."""
    from gearcli.config.reference import undocumented_tables

    assert undocumented_tables() == []


def test_no_file_cites_design_md_or_the_shared_directory():
    files = subprocess.run(["git", "ls-files"], cwd=ROOT, capture_output=True, text=True).stdout.split()
    if not files:
        pytest.skip("not a git checkout")
    offenders = [f for f in files if f.endswith((".py", ".md", ".toml", ".txt")) and (ROOT / f).exists()
                 and ("DESIGN" + ".md" in (ROOT / f).read_text(errors="replace")
                      or "../" + "shared" in (ROOT / f).read_text(errors="replace"))]  # spelled apart
    assert offenders == []


def test_the_checker_itself():
    root = {"$defs": {"T": {"type": "object", "properties": {"a": {"type": "number", "minimum": 1}},
                            "required": ["a"], "additionalProperties": False}}}
    ref = {"$ref": "#/$defs/T"}
    assert valid({"a": 2}, ref, root) and not valid({"a": 0}, ref, root) and not valid({}, ref, root)
    assert not valid({"a": 2, "b": 1}, ref, root) and not valid({"a": True}, ref, root)
    tiny = {"type": "number", "not": {"anyOf": [{"exclusiveMinimum": 0, "exclusiveMaximum": 1e-6}]}}
    assert valid(0, tiny, root) and valid(1.0, tiny, root) and not valid(1e-320, tiny, root)
    assert not valid(float("nan"), {"type": "number"}, root)


def _files() -> list[Path]:
    return sorted((ROOT / "configs").rglob("*.toml")) + sorted((ROOT / "tests" / "badinput").glob("*.toml"))


@pytest.mark.parametrize("path", _files(), ids=lambda p: p.name)
def test_schema_is_never_looser_than_validation(path):
    try:
        data = tomllib.loads(path.read_text())
    except tomllib.TOMLDecodeError:
        pytest.skip("a syntax error: no document to validate")  # the corpus's syntax-error files
    try:
        check_inputs(load_design(str(path)).design)  # validation and the design's checks of the inputs
        accepted = True
    except (ConfigError, DesignError):
        accepted = False
    if not accepted:
        # the schema may not accept what validation refuses, except the one rule JSON Schema cannot state:
        # a material reference must name a key of [materials] (docs/design-file.md says so)
        if valid(data, json_schema(), json_schema()):
            text_rules = ("design_material", "rule_")  # material references; main's excitation rules
            assert path.name.startswith(text_rules), f"{path.name}: the schema accepts what validation refuses"
    else:
        assert valid(data, json_schema(), json_schema()), f"{path.name}: the schema refuses a valid file"
