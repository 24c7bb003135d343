"""The repository documents and checks itself: the generated reference equals the committed one, no file
points outside the repository, and the JSON Schema is never looser than validation on the example and
bad-input files (a tiny checker for the subset of JSON Schema gearcli emits, itself tested here)."""

from __future__ import annotations

import subprocess
import tomllib
from pathlib import Path

import pytest

from gearcli.config import json_schema, load_design
from gearcli.config.reference import design_file_reference
from gearcli.design.checks import check_inputs
from gearcli.errors import ConfigError, DesignError

ROOT = Path(__file__).resolve().parents[2]


def test_committed_design_file_reference_is_the_generated_one():
    assert (ROOT / "docs" / "design-file.md").read_text() == design_file_reference(), \
        "regenerate: python -m gearcli.config.reference > docs/design-file.md"


def test_no_file_cites_design_md_or_the_shared_directory():
    files = subprocess.run(["git", "ls-files"], cwd=ROOT, capture_output=True, text=True).stdout.split()
    if not files:
        pytest.skip("not a git checkout")
    offenders = [f for f in files if f.endswith((".py", ".md", ".toml", ".txt")) and (ROOT / f).exists()
                 and ("DESIGN" + ".md" in (ROOT / f).read_text(errors="replace")
                      or "../" + "shared" in (ROOT / f).read_text(errors="replace"))]  # spelled apart
    assert offenders == []


# --------------------------------------------------------------------------- a tiny JSON Schema checker
def valid(value, schema: dict, root: dict) -> bool:
    """Whether ``value`` satisfies ``schema`` (the subset pydantic emits: $ref, anyOf, allOf, not, type,
    enum, const, bounds, min/maxLength, min/maxItems, properties, required, additionalProperties)."""
    if "$ref" in schema:
        return valid(value, root["$defs"][schema["$ref"].rsplit("/", 1)[1]], root)
    if "anyOf" in schema and not any(valid(value, s, root) for s in schema["anyOf"]):
        return False
    if "allOf" in schema and not all(valid(value, s, root) for s in schema["allOf"]):
        return False
    if "not" in schema and valid(value, schema["not"], root):
        return False
    if "enum" in schema and value not in schema["enum"]:
        return False
    if "const" in schema and value != schema["const"]:
        return False
    t = schema.get("type")
    types = {"number": (int, float), "integer": (int,), "string": (str,), "boolean": (bool,), "object": (dict,),
             "array": (list,), "null": (type(None),)}
    if t is not None:
        if not isinstance(value, types[t]) or (t in ("number", "integer") and isinstance(value, bool)):
            return False
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        if value != value or value in (float("inf"), float("-inf")):
            return False
        for key, ok in (("minimum", value >= schema.get("minimum", value)),
                        ("maximum", value <= schema.get("maximum", value))):
            if key in schema and not ok:
                return False
        if "exclusiveMinimum" in schema and not value > schema["exclusiveMinimum"]:
            return False
        if "exclusiveMaximum" in schema and not value < schema["exclusiveMaximum"]:
            return False
    if isinstance(value, str) and len(value) > schema.get("maxLength", len(value)):
        return False
    if isinstance(value, list):
        if not schema.get("minItems", 0) <= len(value) <= schema.get("maxItems", len(value)):
            return False
        if "items" in schema and not all(valid(v, schema["items"], root) for v in value):
            return False
    if isinstance(value, dict):
        props = schema.get("properties", {})
        if any(k not in value for k in schema.get("required", [])):
            return False
        extra = schema.get("additionalProperties", True)
        for k, v in value.items():
            if k in props:
                if not valid(v, props[k], root):
                    return False
            elif extra is False:
                return False
            elif isinstance(extra, dict) and not valid(v, extra, root):
                return False
        if "maxProperties" in schema and len(value) > schema["maxProperties"]:
            return False
    return True


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
