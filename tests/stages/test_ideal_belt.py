"""The stage-kind seams with a kind gearcli does not know: ``ideal_belt`` (this directory) registers its
schema table and its model facet, and the schema, the messages and the assembly take it with no gearcli file
naming it. (A design, a simulation and tables of a non-gear kind need the design result, the simulation's
per-stage statistics and the life facet split by kind too: ARCHITECTURE.md, "Stage kinds".)"""

from __future__ import annotations

import tomllib
from dataclasses import replace
from pathlib import Path

import ideal_belt
import pytest
from numpy.testing import assert_allclose
from pydantic import ValidationError

from gearcli import api
from gearcli.config.messages import translate
from gearcli.config.schema import DesignFile
from gearcli.model.assembly import Layout
from gearcli.model.linear import static_forces

ROOT = Path(__file__).resolve().parents[2]
CONFIG = ROOT / "configs" / "industrial_two_stage.toml"
BELT = {"type": "test_belt", "pulley_in_diameter_mm": 100.0, "pulley_out_diameter_mm": 250.0,
        "stiffness_N_m": 2.0e6, "damping_Ns_m": 50.0, "efficiency": 0.96}


@pytest.fixture
def belt():
    ideal_belt.register()
    yield
    ideal_belt.withdraw()


def _file_with_belt() -> dict:
    doc = tomllib.loads(CONFIG.read_text(encoding="utf-8"))
    doc["stage"][1] = dict(BELT)
    return doc


def test_a_belt_stage_validates_as_its_own_table(belt):
    cfg = DesignFile.model_validate(_file_with_belt())
    st = cfg.stage[1]
    assert isinstance(st, ideal_belt.BeltStage)
    assert_allclose(st.speed_ratio, 2.5, rtol=1e-15)  # d_2 / d_1 = 250 / 100


def test_a_bad_belt_key_and_an_unknown_type_are_named(belt):
    doc = _file_with_belt()
    doc["stage"][1]["stiffness_N_m"] = -1.0
    with pytest.raises(ValidationError) as exc:
        DesignFile.model_validate(doc)
    assert any(path == ("stage", 1, "stiffness_N_m") for path, _ in translate(exc.value))
    doc["stage"][1]["type"] = "bevel"
    with pytest.raises(ValidationError) as exc:
        DesignFile.model_validate(doc)
    (text,) = [t for path, t in translate(exc.value) if path == ("stage", 1, "type")]
    assert text == 'type must be "parallel" or "planetary" or "test_belt", got \'bevel\''


def test_without_the_registration_the_belt_is_refused():
    with pytest.raises(ValidationError):
        DesignFile.model_validate(_file_with_belt())


def test_the_assembly_places_the_belt_with_its_levers(belt):
    """Stage 1 a gear pair from the file, stage 2 the belt. Rigid kinematics: the belt's output shaft turns at
    d_1/d_2 of its input shaft. Statics (independent of the code: a free body of each shaft): the output
    pulley holds the load torque, so the tight span pulls F = T_L / r_2; shaft 2 then carries F r_1 =
    T_L r_1 / r_2, which stage 1's gear takes as the line force T_L (r_1 / r_2) / r_b2, over the gear pair's
    efficiency eta_1 on its driving side (the file's lossy mesh). The belt here is ideal (eta = 1): today the
    statics divide by a stage model's own efficiency only for planet meshes."""
    loaded = api.load(CONFIG, [])
    design = api.design(loaded)
    spec = api.model_spec(loaded.design, design)
    table = ideal_belt.BeltStage.model_validate({**BELT, "efficiency": 1.0})
    lay = Layout.of(replace(spec, stage_models=(None, ideal_belt.model_of(table))))
    assert [b.label for b in lay.bodies] == ["shaft 1", "shaft 2", "shaft 3"]
    assert [x.label for x in lay.connectors] == ["stage 1 mesh", "stage 2 belt"]
    g = design.stages[0]
    rho_2 = g.pinion.teeth / g.gear.teeth
    assert_allclose([b.ratio for b in lay.bodies], [1.0, rho_2, rho_2 * 100.0 / 250.0], rtol=1e-12)
    t_load, r_1, r_2 = spec.load.torque_Nm, 0.05, 0.125
    r_b2 = 0.5e-3 * g.gear.base_diameter_mm
    forces = static_forces(lay)
    assert_allclose(forces[1], t_load / r_2, rtol=1e-12)
    assert_allclose(forces[0], t_load * (r_1 / r_2) / r_b2 / g.efficiency, rtol=1e-12)
    # a lossy belt's efficiency counts in the train's (the gear pair's own eta from the file beside it)
    lossy = ideal_belt.model_of(ideal_belt.BeltStage.model_validate(BELT))
    assert_allclose(Layout.of(replace(spec, stage_models=(None, lossy))).train_efficiency(), g.efficiency * 0.96,
                    rtol=1e-12)
