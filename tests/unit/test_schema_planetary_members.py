"""The JSON Schema's rule that a planetary stage's input and held members differ applies only to the keys a file
gives (robustness campaign, round 4): a stage giving neither (the defaults: the sun drives, the ring is held) was
refused by `gearcli schema`'s schema and accepted by validation."""

from __future__ import annotations

import copy

import pytest
import tomli_w
from jsonschema_subset import valid

from gearcli.config import json_schema, load_design
from gearcli.errors import ConfigError

DOC = {"input": {"speed_rpm": 1000}, "load": {"torque_Nm": 100},
       "stage": [{"type": "planetary", "normal_module_mm": 3, "sun": {"teeth": 20, "face_width_mm": 30},
                  "planet": {"teeth": 31, "face_width_mm": 30, "count": 3}, "ring": {"teeth": 82, "face_width_mm": 30}}]}


@pytest.mark.parametrize(("given", "ok"), [
    ({}, True),  # defaults: input sun, fixed ring
    ({"input": "carrier"}, True), ({"fixed": "carrier"}, True), ({"input": "ring", "fixed": "sun"}, True),
    ({"input": "ring"}, False),  # the default held member is the ring
    ({"fixed": "sun"}, False),  # the default input is the sun
    ({"input": "carrier", "fixed": "carrier"}, False),
])
def test_schema_and_validation_agree_on_the_planetary_members(tmp_path, given, ok):
    doc = copy.deepcopy(DOC)
    doc["stage"][0].update(given)
    schema = json_schema()
    assert valid(doc, schema, schema) is ok
    f = tmp_path / "planetary.toml"
    f.write_text(tomli_w.dumps(doc))
    if ok:
        load_design(str(f))
    else:
        with pytest.raises(ConfigError):
            load_design(str(f))
