"""A load ``torque_speed`` table read past its last point is warned (design check ``load_table_beyond``): the
design and the run extend its last segment, a torque nobody measured (docs/physics.md, "Load against speed")."""

from __future__ import annotations

import copy
import math
import tomllib
from pathlib import Path

import pytest

from gearcli.config.schema import DesignFile
from gearcli.design import compute_design

SEED = Path(__file__).resolve().parents[2] / "configs" / "concrete_mixer.toml"
with SEED.open("rb") as _fh:
    SEED_DOC = tomllib.load(_fh)

# the seed's output speed by hand: 600 rpm through 51/21, 50/17 and 53/17
N_OUT = 600.0 * 21 * 17 * 17 / (51 * 50 * 53)


def _design(table):
    doc = copy.deepcopy(SEED_DOC)
    doc["load"] = {"torque_speed": table}
    return compute_design(DesignFile.model_validate(doc))


def _beyond(result):
    return [w for w in result.diagnostics if w.data.get("check") == "load_table_beyond"]


def test_a_table_ending_below_the_nominal_speed_is_warned_with_the_extended_torque():
    found = _beyond(_design([[0.0, 3000.0], [10.0, 4000.0], [20.0, 4500.0]]))
    assert len(found) == 1
    # the last segment (10 -> 20 rpm: 50 N m per rpm) extended to the output speed, by hand
    extended = 4500.0 + (4000.0 - 4500.0) / (10.0 - 20.0) * (N_OUT - 20.0)
    data = found[0].data
    assert data["output_speed_rpm"] == pytest.approx(N_OUT, rel=1e-12)
    assert data["table_last_rpm"] == 20.0 and data["table_last_torque_Nm"] == 4500.0
    assert data["load_torque_Nm"] == pytest.approx(extended, rel=1e-12)
    assert "load.torque_speed" in found[0].message and "20 rpm" in found[0].message
    assert f"{extended:.5g} N·m" in found[0].message


@pytest.mark.parametrize("last_rpm", [30.0, math.ceil(N_OUT * 1e6) / 1e6])
def test_a_table_reaching_the_nominal_speed_is_not_warned(last_rpm):
    assert not _beyond(_design([[0.0, 3000.0], [10.0, 4000.0], [last_rpm, 4600.0]]))


def test_a_constant_load_is_not_warned():
    doc = copy.deepcopy(SEED_DOC)
    assert not [w for w in compute_design(DesignFile.model_validate(doc)).diagnostics
                if w.data.get("check") == "load_table_beyond"]
