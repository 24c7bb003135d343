"""A plug-in stage whose reverse efficiency differs from its forward one (a worm's backdrive, docs/plugins.md
"Losses"): under a reversed load the design takes the reverse one, T_in = T_out eta_r / i, and the dynamics the
forward one (the mesh element loses one eta whichever way the power flows, docs/physics.md), T_in = T_out eta / i.
``gearcli design`` says so with the factor eta / eta_r, which ``simulate``'s settled input torque then shows: both
torques checked against those hand formulas on a train of the stage alone (a chain of plug_chain.py given a
backdrive efficiency). A forward load, or equal efficiencies, say nothing."""

from __future__ import annotations

import json
from dataclasses import replace
from typing import Annotated, Literal

import plug_chain as pc
import pytest
import tomli_w
from click.testing import CliRunner
from numpy.testing import assert_allclose
from pydantic import Field

from gearcli.cli import cli
from gearcli.config.schema import DesignFile, register_stage_table
from gearcli.stages import kinds

KIND = "test_backdriven_chain"
Z1, Z2, PITCH, ETA, ETA_R, T_L, N_IN = 17, 51, 19.05, 0.9, 0.6, 600.0, 600.0  # -, -, mm, -, -, N m, rpm


class BackdrivenStage(pc.ChainStage):
    type: Literal["test_backdriven_chain"]  # type: ignore[assignment]
    backdrive_efficiency: Annotated[float, Field(gt=0, le=1)] = 1.0


class BackdrivenDesign(pc.ChainDesign):
    def reverse_efficiency(self, table, k):
        return table.backdrive_efficiency

    def result(self, cfg, pairs, k, kin, mesh):
        return replace(super().result(cfg, pairs, k, kin, mesh), type=KIND)


@pytest.fixture
def kind():
    register_stage_table(KIND, BackdrivenStage)
    kinds.provide(KIND, "design", BackdrivenDesign())
    kinds.provide(KIND, "model", pc.ChainModelKind())
    kinds.provide(KIND, "io", pc.ChainOutput())
    yield
    for facet in ("table", "design", "model", "io"):
        kinds.withdraw(KIND, facet)
    DesignFile.model_rebuild(force=True)


def _file(tmp_path, torque_Nm: float, eta_r: float) -> str:
    stage = {"type": KIND, "driver_teeth": Z1, "driven_teeth": Z2, "pitch_mm": PITCH, "chain_efficiency": ETA,
             "backdrive_efficiency": eta_r, "stiffness_N_m": 2.0e7, "damping_Ns_m": 2000.0,
             "driver_inertia_kg_m2": 0.02, "driven_inertia_kg_m2": 0.2}
    doc = {"title": "a backdriven chain alone", "stage": [stage], "input": {"speed_rpm": N_IN, "ramp_s": 0.05},
           "load": {"torque_Nm": torque_Nm, "ramp_s": 0.05}, "simulation": {"duration_s": 0.3, "steps": 600}}
    path = tmp_path / "chain.toml"
    path.write_text(tomli_w.dumps(doc), encoding="utf-8")
    return str(path)


def _json(*args: str) -> dict:
    r = CliRunner().invoke(cli, [*args, "--format", "json", "-q"])
    assert r.exit_code == 0, r.output
    return json.loads(r.stdout)


def test_a_reversed_load_says_the_design_and_the_dynamics_differ_by_eta_over_eta_r(kind, tmp_path):
    path, i = _file(tmp_path, -T_L, ETA_R), Z2 / Z1
    design = _json("design", path)
    assert_allclose(design["input_torque_Nm"], -T_L * ETA_R / i, rtol=1e-12)  # the design's: eta_r
    said = [w for w in design["warnings"] if w.get("check") == "reverse_efficiency"]
    assert len(said) == 1 and said[0]["stage"] == 1 and said[0]["type"] == KIND
    assert_allclose(said[0]["factor"], ETA / ETA_R, rtol=1e-12)
    assert f"{ETA / ETA_R:.4g}x the design's" in said[0]["message"]
    sim = _json("simulate", path)["summary"]
    assert_allclose(sim["input_torque_Nm"], -T_L * ETA / i, rtol=1e-3)  # the dynamics': eta (docs/physics.md)
    assert_allclose(sim["input_torque_Nm"] / design["input_torque_Nm"], said[0]["factor"], rtol=1e-3)


@pytest.mark.parametrize(("torque", "eta_r"), [(T_L, ETA_R), (-T_L, ETA)], ids=["forward load", "equal efficiencies"])
def test_nothing_is_said_where_the_dynamics_lose_what_the_design_does(kind, tmp_path, torque, eta_r):
    design = _json("design", _file(tmp_path, torque, eta_r))
    assert not [w for w in design["warnings"] if w.get("check") == "reverse_efficiency"]
    assert_allclose(abs(design["input_torque_Nm"]), T_L * (1 / ETA if torque > 0 else ETA) / (Z2 / Z1), rtol=1e-12)
