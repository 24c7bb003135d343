"""``gearcli.config.schema.validate_design`` (the validator of the stage kinds a file names) on a file naming a
plug-in stage kind: the same instance and the same errors as the whole class's validator (``DesignFile``, rebuilt
with the plug-in's table), alone and beside a parallel stage; and a plug-in table swapped (withdrawn, provided
again: docs/plugins.md, "Testing a plug-in") is validated by the new table, not by a validator cached for the old."""

from __future__ import annotations

import copy
import tomllib
from pathlib import Path
from typing import Annotated

import plug_extras as px
import pytest
from pydantic import Field, ValidationError

from gearcli.config.schema import DesignFile, register_stage_table, validate_design
from gearcli.stages import kinds

ROOT = Path(__file__).resolve().parents[2]
FIXED = {"type": px.KIND, "ratio": 4.0, "stiffness_Nm_rad": 2e5, "input_inertia_kg_m2": 0.02,
         "output_inertia_kg_m2": 0.5}


@pytest.fixture
def table():
    register_stage_table(px.KIND, px.FixedRatioStage)
    yield
    kinds.withdraw(px.KIND, "table")
    DesignFile.model_rebuild(force=True)


def _mixed() -> dict:
    doc = tomllib.loads((ROOT / "configs" / "industrial_two_stage_rated.toml").read_text(encoding="utf-8"))
    doc.pop("target", None)  # the ratio changes
    doc["stage"].insert(1, dict(FIXED))
    return doc


def _alone() -> dict:
    return {"stage": [dict(FIXED)], "input": {"speed_rpm": 1450}, "load": {"torque_Nm": 1340}}


def _outcome(validate, data: dict):
    try:
        result = validate(copy.deepcopy(data))
    except ValidationError as exc:
        return "error", [(e["loc"], e["msg"], e["type"]) for e in exc.errors(include_url=False)]
    return "valid", result, result.model_fields_set


EDITS = [
    (lambda s: None, "valid"),
    (lambda s: s.update(ratio=-1.0), "a bound"),
    (lambda s: s.update(belt=3), "an unknown key"),
    (lambda s: s.pop("stiffness_Nm_rad"), "a missing key"),
    (lambda s: s.update(ratio="four"), "a text for a number"),
    (lambda s: s.update(mesh={"exponent": 1.0}), "a mesh table on a kind without one"),
    (lambda s: s.update(planet={"count": 3}), "a planetary key"),
    (lambda s: s.update(type="test_no_such_kind"), "an unknown type names every registered kind"),
]


@pytest.mark.parametrize("build", [_mixed, _alone], ids=["beside parallel stages", "alone"])
@pytest.mark.parametrize("edit, what", EDITS, ids=[w for _, w in EDITS])
def test_a_plug_in_kind_validates_as_the_whole_class_does(table, build, edit, what):
    doc = build()
    edit(next(s for s in doc["stage"] if s.get("type") == px.KIND or "ratio" in s))
    assert _outcome(validate_design, doc) == _outcome(DesignFile.model_validate, doc), what


def test_a_swapped_plug_in_table_is_the_one_validate_design_uses(table):
    doc = _mixed()
    validate_design(copy.deepcopy(doc))  # a validator of {parallel, test_fixed_ratio} built with the first table

    class Narrow(px.FixedRatioStage):
        ratio: Annotated[float, Field(gt=0, le=2.0)]  # the swapped table refuses the file's ratio 4

    kinds.withdraw(px.KIND, "table")
    kinds.provide(px.KIND, "table", Narrow)
    DesignFile.model_rebuild(force=True)
    expected = _outcome(DesignFile.model_validate, doc)
    assert expected[0] == "error" and expected[1][0][0] == ("stage", 1, px.KIND, "ratio")
    assert _outcome(validate_design, doc) == expected


def test_a_withdrawn_plug_in_kind_is_not_named_by_a_validator_cached_while_it_was_registered():
    """An unknown kind's error names every registered kind. A validator of all kinds cached while the plug-in's kind
    was registered was kept, keyed by the tables the file gives only, after the kind was withdrawn (docs/plugins.md,
    "Testing a plug-in": withdraw, then rebuild the class): CI saw 'test_fixed_ratio' named among the expected tags
    by ``validate_design`` and not by the class, in a process where a plug-in test had run first."""
    doc = _alone()
    doc["stage"][0] = {**doc["stage"][0], "type": "planetery"}
    register_stage_table(px.KIND, px.FixedRatioStage)
    try:
        assert px.KIND in str(_outcome(validate_design, doc))  # the plug-in's kind is named while registered
    finally:
        kinds.withdraw(px.KIND, "table")
        DesignFile.model_rebuild(force=True)
    expected = _outcome(DesignFile.model_validate, doc)
    assert expected[0] == "error" and px.KIND not in str(expected) and "'parallel', 'planetary'" in str(expected)
    assert _outcome(validate_design, doc) == expected
