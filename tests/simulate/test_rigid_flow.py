"""The rigid start's walk through a lossy chain (:mod:`gearcli.simulate.rigid_flow`) against the statics of a
lossy train written here: at rest in the rigid state (dw/dt = 0) the input must hold the load reflected with
1/eta of every mesh while the power flows forward (the train turning with the load's torque against it) and with
eta of every mesh while the load drives the train backwards (the power flowing from the load): T_L / (i eta_1
eta_2) and T_L eta_1 eta_2 / i. The walk is what the rigid start takes where a mesh's power flow turns against
the load's (tests/reference/test_rigid_start_losses.py, a rolled-back soft start)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from gearcli import api
from gearcli.model.assembly import Layout
from gearcli.scene import spec_from_design
from gearcli.simulate import rigid_flow, rigid_start

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def lay() -> Layout:
    # the industrial two-stage reducer at 97 % a stage: 19/75 and 19/68, 1340 N·m at the output
    loaded = api.load(str(ROOT / "configs" / "lossy_reducer.toml"), ["load.speed_exponent=0"])
    return Layout.of(spec_from_design(loaded.design, api.design(loaded)))


@pytest.fixture(scope="module")
def plan(lay) -> rigid_flow.Plan:
    out = rigid_flow.plan(lay, rigid_start._coefficients(lay))
    assert out is not None  # a lossy chain
    return out


@pytest.mark.parametrize("direction", [1.0, -1.0])
def test_the_walked_statics_lose_on_the_side_the_power_flows_to(lay, plan, direction):
    i = (75 / 19) * (68 / 19)
    eta = 0.97 * 0.97
    load = 1340.0
    w = direction * 1450 * math.pi / 30
    need, forces = rigid_flow.walk(plan, w, 0.0, load)
    hand = load / (i * eta) if direction > 0 else load * eta / i
    assert need == pytest.approx(hand, rel=1e-9)
    # stage 2's mesh: the gear's side carries the load over its base radius; the law's force is the pinion's
    # (over eta) when the power flows forward, the gear's own when it flows back
    r_bg = lay.connectors[1].rb
    assert forces[1] == pytest.approx(load / r_bg / (0.97 if direction > 0 else 1.0), rel=1e-9)


def test_the_fixed_direction_holds_where_the_power_flows_with_the_load(plan):
    w = 1450 * math.pi / 30
    # turning forward against the load: the fixed (forward) direction's forces are the walk's, no walk taken
    assert not rigid_flow.needs_walk(plan, w, 0.0, 1340.0)
    # the same state turning backwards (a rolled-back start), and the first instant of a start from rest: walked
    assert rigid_flow.needs_walk(plan, -w, 0.0, 1340.0)
    assert rigid_flow.needs_walk(plan, 0.0, 100.0, 1340.0)
    # the array test gives the same verdicts
    mask = rigid_flow.needs_walk_mask(plan, np.array([w, -w, 0.0]), np.array([0.0, 0.0, 100.0]), np.full(3, 1340.0))
    assert mask.tolist() == [False, True, True]
