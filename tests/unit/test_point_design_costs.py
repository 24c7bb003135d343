"""A sweep point's design and model, made cheaper (session 24): each short cut gives what the long way gave.

- ``--set`` texts parsed once per process (:func:`gearcli.config.overrides.parse`): two values of one key in a row
  keep their own values, an array is never shared between two parses, a bad text fails every time;
- the design file's subnormal rule (``StrictTable._no_subnormal``) answers a plain value without its search, and
  refuses exactly the magnitudes in (0, 2.2250738585072014e-308);
- ``design``'s warnings build a check's data only where it warns: a warned check's data hold the figures by hand;
- a result's finiteness check reads its floats by a plan per row of field types: the first non-finite number in
  field order, whatever the rows before it;
- a mesh spec's numbers are tested by their type first (a float): a flag, a NumPy integer or a non-finite number is
  refused as before, an int and a float subclass taken.
"""

from __future__ import annotations

import copy
import dataclasses
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest
from pydantic import ValidationError

from gearcli.config.bounds_types import StrictTable
from gearcli.config.load import load_variant
from gearcli.config.overrides import parse
from gearcli.config.schema import DesignFile
from gearcli.design import compute, compute_design
from gearcli.errors import ConfigError

SEED = Path(__file__).resolve().parents[2] / "configs" / "concrete_mixer.toml"
SMALLEST_NORMAL = 2.2250738585072014e-308  # IEEE 754 double's smallest normal number, 2^-1022


def test_two_values_of_one_key_in_a_row_keep_their_own_values():
    raw = SEED.read_bytes()
    texts = [("input.speed_rpm=700", "load.ramp_s=0.0"), ("input.speed_rpm=900.5", "load.ramp_s=0.0"),
             ("input.speed_rpm=700", "load.ramp_s=0.25")]
    for _ in range(2):  # the second round from the parsed texts
        got = [load_variant(raw, str(SEED), t) for t in texts]
        assert [(c.input.speed_rpm, c.load.ramp_s) for c in got] == [(700, 0.0), (900.5, 0.0), (700, 0.25)]
        assert all(c.input.speed_deg_s is None for c in got)  # the file's speed_deg_s replaced by each
    assert parse("input.speed_rpm=700").value == 700 and parse("input.speed_rpm=700.0").value == 700.0
    assert type(parse("input.speed_rpm=700").value) is int and type(parse("input.speed_rpm=700.0").value) is float


def test_an_array_value_is_never_shared_between_two_parses():
    text = "contact.transmission_error_um=[1.5, 2.5]"
    first = parse(text)
    first.value.append(99.0)  # what a caller may do to the data it was given
    assert parse(text).value == [1.5, 2.5]
    assert parse(text).value is not parse(text).value


def test_a_bad_text_fails_every_time():
    for _ in range(2):
        with pytest.raises(ConfigError) as err:
            parse("=5")
        assert err.value.source == "--set" and "expected KEY=VALUE" in err.value.message
        with pytest.raises(ConfigError) as err:
            parse("input..speed_rpm=5")
        assert err.value.key == "input..speed_rpm"


class _Table(StrictTable):
    x: float = 1.0
    n: int = 1
    name: str = ""
    flag: bool = False
    maybe: float | None = None
    items: list[float] = []
    rows: list[list[float]] = []
    named: dict[str, float] = {}


@pytest.mark.parametrize(("field", "value", "refused"), [
    ("x", 0.0, False), ("x", -0.0, False), ("x", 1.5, False), ("x", -1e-300, False),
    ("x", SMALLEST_NORMAL, False), ("x", -SMALLEST_NORMAL, False),
    ("x", 5e-324, True), ("x", -1e-310, True), ("x", SMALLEST_NORMAL / 2, True),
    ("n", 0, False), ("name", "5e-324", False), ("flag", True, False), ("maybe", None, False),
    ("maybe", 1e-320, True), ("items", [1.0, 0.0], False), ("items", [1.0, 1e-320], True),
    ("rows", [[1.0], [2.0, -5e-324]], True), ("named", {"a": 1.0}, False), ("named", {"a": 1e-315}, True),
])
def test_the_subnormal_rule_refuses_exactly_the_subnormal_magnitudes(field, value, refused):
    if refused:
        with pytest.raises(ValidationError) as err:
            _Table.model_validate({field: value})
        assert "a subnormal number is a mistake" in str(err.value)
        assert err.value.errors()[0]["loc"][0] == field
    else:
        assert getattr(_Table.model_validate({field: value}), field) == value


def test_warned_checks_keep_their_data_by_hand():
    """Stage 1 of the seed made a narrow spur pair of 13 teeth, hands still given: the spur-hand, undercut and
    face-width checks warn, each with the data its warning had before, the figures by hand."""
    doc = tomllib.loads(SEED.read_text())
    doc = copy.deepcopy(doc)
    st = doc["stage"][0]
    st["helix_angle_deg"] = 0.0
    st["pinion"].update(teeth=13, face_width_mm=20)
    st["gear"].update(face_width_mm=20)
    design = compute_design(DesignFile.model_validate(doc))
    data = {(d.data.get("check"), d.data.get("member")): d.data for d in design.diagnostics
            if d.data.get("stage") == 1}
    assert data[("spur_hand", None)] == {"check": "spur_hand", "stage": 1}
    h_ff = 1.25 - 0.38 * (1.0 - math.sin(math.radians(20.0)))  # ISO 53 profile A's straight flank, 0.99997
    sin2 = math.sin(math.radians(20.0)) ** 2  # spur: alpha_t = alpha_n
    undercut = data[("undercut", "pinion")]
    assert undercut["teeth"] == 13 and undercut["profile_shift"] == 0.0
    assert undercut["min_teeth"] == pytest.approx(2.0 * h_ff / sin2, rel=1e-12)  # 17.097
    assert undercut["min_profile_shift"] == pytest.approx(h_ff - 13 * sin2 / 2.0, rel=1e-12)  # 0.2396
    assert ("undercut", "gear") not in data  # 51 teeth: no undercut
    assert data[("face_width", None)]["face_width_ratio"] == pytest.approx(20.0 / (13 * 12.0), rel=1e-12)
    warned = [w for w in design.warnings if w.startswith("stage 1:")]
    assert any('hand given (pinion "left", gear "right")' in w for w in warned)
    assert any("face width / pinion pitch diameter b/d1 = 20/156 = 0.128 < 0.2" in w for w in warned)


@dataclasses.dataclass(frozen=True)
class _Inner:
    a: float
    b: float


@dataclasses.dataclass(frozen=True)
class _Outer:
    x: float
    inner: _Inner | None
    y: float | None


INF, NAN = float("inf"), float("nan")


@pytest.mark.parametrize(("result", "expected"), [
    (_Outer(1.0, _Inner(2.0, 3.0), 4.0), None),
    (_Outer(1.0, _Inner(2.0, INF), 4.0), ("b", INF)),  # the same types as the row before: its own answer
    (_Outer(1.0, None, -INF), ("y", -INF)),  # another row of types (an optional field None)
    (_Outer(INF, _Inner(NAN, 1.0), 1.0), ("x", INF)),  # the first in field order, nested ones in their place
    (_Outer(1.0, _Inner(NAN, 1.0), INF), ("a", NAN)),
    (_Outer(1, _Inner(2.0, 3.0), None), None),  # whole numbers are no floats
    (_Outer(1.0, _Inner(2.0, 3.0), np.float64("inf")), ("y", INF)),  # a float subclass is a float
    (_Outer(1.0, _Inner(2.0, 3.0), 4.0), None),
])
def test_the_first_non_finite_number_of_a_result_in_field_order(result, expected):
    found = compute._non_finite(result)
    if expected is None:
        assert found is None
    else:
        assert found is not None and found[0] == expected[0]
        assert (math.isnan(found[1]) and math.isnan(expected[1])) or found[1] == expected[1]


def _seed_mesh():
    from gearcli.api import spec_from_design  # a model spec of the seed: its first mesh

    cfg = load_variant(SEED.read_bytes(), str(SEED), ())
    return spec_from_design(cfg, compute_design(cfg)).meshes[0]


@pytest.mark.parametrize(("field", "value", "refused"), [
    ("stiffness_N_m_e", True, "MeshSpec.stiffness_N_m_e must be a finite number > 0, got True"),  # a flag, no number
    ("pinion_teeth", np.int64(21), "MeshSpec.pinion_teeth must be a finite number >= 1, got "),  # no int subclass
    ("static_tangential_N", NAN, "MeshSpec.static_tangential_N must be a finite number, got nan"),
    ("helix_angle_rad", 1.6, "MeshSpec.helix_angle_rad must be a finite angle below pi/2 rad, got 1.6"),
    ("backlash_m", 0, None), ("pinion_teeth", 21, None), ("helix_angle_rad", np.float64(0.2), None),
])
def test_a_mesh_spec_takes_plain_numbers_and_floats(field, value, refused):
    mesh = _seed_mesh()
    if refused is None:
        assert getattr(dataclasses.replace(mesh, **{field: value}), field) == value
    else:
        with pytest.raises(ValueError) as err:
            dataclasses.replace(mesh, **{field: value})
        assert str(err.value).startswith(refused)
