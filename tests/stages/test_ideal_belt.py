"""A stage kind gearcli does not know, end to end: ``ideal_belt`` (this directory) registers its schema table and
its design, model and output facets in one module, and the schema, the design, the model, the simulation, the
modes and the printed tables and JSON take it with no gearcli file naming it. Every number is checked against a
hand calculation written out here (the belt's kinematics, its statics, the closed-form natural frequencies of a
spring on two inertias)."""

from __future__ import annotations

import json
import math
import tomllib
from dataclasses import replace
from pathlib import Path

import ideal_belt
import pytest
import tomli_w
from click.testing import CliRunner
from numpy.testing import assert_allclose
from pydantic import ValidationError

from gearcli import api
from gearcli.cli import cli
from gearcli.config.messages import translate
from gearcli.config.schema import DesignFile
from gearcli.model.assembly import Layout
from gearcli.model.linear import static_forces

ROOT = Path(__file__).resolve().parents[2]
CONFIG = ROOT / "configs" / "industrial_two_stage.toml"
RATED = ROOT / "configs" / "industrial_two_stage_rated.toml"
D_1, D_2, K, C, J_1, J_2 = 100.0, 250.0, 2.0e6, 50.0, 0.01, 0.2  # mm, mm, N/m, N s/m, kg m², kg m²
BELT = {"type": "test_belt", "pulley_in_diameter_mm": D_1, "pulley_out_diameter_mm": D_2, "stiffness_N_m": K,
        "damping_Ns_m": C, "pulley_in_inertia_kg_m2": J_1, "pulley_out_inertia_kg_m2": J_2}
R_1, R_2 = 0.5e-3 * D_1, 0.5e-3 * D_2  # m
BELT_ONLY = f"""title = "an ideal belt drive"

[[stage]]
type = "test_belt"
pulley_in_diameter_mm = {D_1}
pulley_out_diameter_mm = {D_2}
stiffness_N_m = {K}
damping_Ns_m = {C}
pulley_in_inertia_kg_m2 = {J_1}
pulley_out_inertia_kg_m2 = {J_2}

[input]
speed_rpm = 1450
ramp_s = 0.2

[load]
torque_Nm = 300
ramp_s = 0.2

[simulation]
duration_s = 0.6
steps = 2000
rtol = 1e-6
"""


@pytest.fixture
def belt():
    ideal_belt.register()
    yield
    ideal_belt.withdraw()


def _doc_with_belt(path: Path = CONFIG) -> dict:
    """The file's stage 2 (a gear pair) replaced by the belt."""
    doc = tomllib.loads(path.read_text(encoding="utf-8"))
    doc["stage"][1] = dict(BELT)
    doc.pop("target", None)  # the gear file's target speed is the gear train's
    doc.pop("bearing", None)
    return doc


def _write(tmp_path: Path, doc: dict | str) -> Path:
    path = tmp_path / "belt.toml"
    path.write_text(doc if isinstance(doc, str) else tomli_w.dumps(doc), encoding="utf-8")
    return path


def _run(*args: str) -> str:
    res = CliRunner().invoke(cli, list(args))
    assert res.exit_code == 0, res.output
    return res.stdout  # the warnings go to stderr


# --------------------------------------------------------------------------------------- the schema
def test_a_belt_stage_validates_as_its_own_table(belt):
    cfg = DesignFile.model_validate(_doc_with_belt())
    st = cfg.stage[1]
    assert isinstance(st, ideal_belt.BeltStage)
    assert_allclose(st.speed_ratio, 2.5, rtol=1e-15)  # d_2 / d_1 = 250 / 100


def test_a_bad_belt_key_and_an_unknown_type_are_named(belt):
    doc = _doc_with_belt()
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
        DesignFile.model_validate(_doc_with_belt())


# --------------------------------------------------------------------------------------- the design
def test_the_design_gives_the_belt_its_kinematics_and_statics(belt, tmp_path):
    """Stage 1 the file's gear pair (z 19/75, eta_1 = 0.98), stage 2 the belt. By hand: the belt turns its input
    pulley at n_1 / (75/19) and its output at that over i = d_2/d_1 = 2.5; with no loss the output pulley holds
    the load torque T_L = 1340 N m and the input pulley T_L / i (T_out = T_in i eta, eta = 1), which the gear pair
    delivers (its gear's torque); the tight span pulls F = T_L / r_2 and stretches F / k."""
    loaded = api.load(str(_write(tmp_path, _doc_with_belt())))
    d = api.design(loaded)
    gear, st = d.stages
    n_1, t_load, i_1 = 1450.0, 1340.0, 75 / 19
    assert_allclose(d.total_ratio, i_1 * 2.5, rtol=1e-14)  # the product of the stage ratios
    assert_allclose([st.input_speed_rpm, st.output_speed_rpm], [n_1 / i_1, n_1 / i_1 / 2.5], rtol=1e-14)
    assert_allclose([st.output_torque_Nm, st.input_torque_Nm], [t_load, t_load / 2.5], rtol=1e-14)
    assert_allclose(st.input_torque_Nm * st.ratio * 1.0, st.output_torque_Nm, rtol=1e-14)  # T_in i eta, eta = 1
    assert_allclose(gear.gear.torque_Nm, t_load / 2.5, rtol=1e-12)  # the pair drives the belt's input pulley
    assert_allclose(gear.pinion.torque_Nm, t_load / 2.5 / i_1 / 0.98, rtol=1e-12)
    assert_allclose(st.span_force_N, t_load / R_2, rtol=1e-14)  # 1340 / 0.125 = 10720 N
    assert_allclose(st.span_force_N, st.input_torque_Nm / R_1, rtol=1e-14)  # the same span seen from pulley 1
    assert_allclose(st.static_stretch_mm, t_load / R_2 / K * 1e3, rtol=1e-14)
    assert_allclose(st.belt_speed_m_s, n_1 / i_1 * math.pi / 30 * R_1, rtol=1e-14)
    # the pulleys' inertias on the chain's shafts: shaft 2 carries the gear and the input pulley
    assert_allclose(d.shafts[1].inertia_kg_m2, gear.gear.inertia_kg_m2 + J_1, rtol=1e-14)
    assert_allclose(d.shafts[2].inertia_kg_m2, J_2, rtol=1e-14)


def test_the_design_prints_the_belt_in_its_own_table_and_json(belt, tmp_path):
    path = str(_write(tmp_path, _doc_with_belt()))
    table = _run("design", path, "--format", "table")
    assert "belt stages" in table and "not rated (no gear mesh)" in table
    assert "│ span force F [N]" in table and "10720" in table
    assert "stage 2" not in table.split("belt stages")[0]  # the gear tables have the gear stage's column only
    doc = json.loads(_run("design", path, "--format", "json"))
    belt_json = doc["stages"][1]
    assert belt_json["type"] == "test_belt" and belt_json["rated"] is False
    assert_allclose([belt_json["ratio"], belt_json["span_force_N"]], [2.5, 1340.0 / R_2], rtol=1e-14)
    assert "pinion" not in belt_json and "type" not in doc["stages"][0]  # the gear stage's keys as they were


def test_a_rated_file_rates_the_gear_pair_and_says_the_belt_is_not_rated(belt, tmp_path):
    """A kind without a gear mesh is not rated, and the output says so (a warning, not a crash, not silence)."""
    path = str(_write(tmp_path, _doc_with_belt(RATED)))
    doc = json.loads(_run("design", path, "--format", "json"))
    assert doc["stages"][0]["rating"]["pinion"]["S_H"] > 0
    assert "rating" not in doc["stages"][1]
    (note,) = [w for w in doc["warnings"] if w.get("check") == "not_rated"]
    assert note["stage"] == 2 and "test_belt" in note["message"]


# ---------------------------------------------------------------------------------------- the model
def test_the_assembly_places_the_belt_with_its_levers(belt, tmp_path):
    """Stage 1 a gear pair from the file, stage 2 the belt. Rigid kinematics: the belt's output shaft turns at
    d_1/d_2 of its input shaft. Statics (independent of the code: a free body of each shaft): the output
    pulley holds the load torque, so the tight span pulls F = T_L / r_2; shaft 2 then carries F r_1 =
    T_L r_1 / r_2, which stage 1's gear takes as the line force T_L (r_1 / r_2) / r_b2, over the gear pair's
    efficiency eta_1 on its driving side (the file's lossy mesh); the belt is lossless."""
    loaded = api.load(str(_write(tmp_path, _doc_with_belt())))
    design = api.design(loaded)
    spec = api.model_spec(loaded.design, design)
    lay = Layout.of(spec)
    assert [b.label for b in lay.bodies] == ["shaft 1", "shaft 2", "shaft 3"]
    assert [x.label for x in lay.connectors] == ["stage 1 mesh", "stage 2 belt"]
    assert lay.stage_conn == (0, 1)  # the belt's span is its stage's connector
    g = design.stages[0]
    rho_2 = g.pinion.teeth / g.gear.teeth
    assert_allclose([b.ratio for b in lay.bodies], [1.0, rho_2, rho_2 * D_1 / D_2], rtol=1e-12)
    t_load = spec.load.torque_Nm
    r_b2 = 0.5e-3 * g.gear.base_diameter_mm
    forces = static_forces(lay)
    assert_allclose(forces[1], t_load / R_2, rtol=1e-12)
    assert_allclose(forces[0], t_load * (R_1 / R_2) / r_b2 / g.efficiency, rtol=1e-12)
    assert_allclose(lay.train_efficiency(), g.efficiency, rtol=1e-12)  # the gear pair's eta, the belt's 1
    # a stage model given by hand lands in the same place
    again = Layout.of(replace(spec, stage_models=(None, ideal_belt.model_of(
        ideal_belt.BeltStage.model_validate(BELT)))))
    assert_allclose(static_forces(again), forces, rtol=1e-15)


def test_modes_of_a_belt_are_the_closed_form_ones(belt, tmp_path):
    """A belt alone (shaft 1: pulley 1, J_1; shaft 2: pulley 2, J_2). The span's stiffness k acts on the stretch
    r_1 theta_1 - r_2 theta_2. Input clamped (speed drive): one degree of freedom, w^2 = k r_2^2 / J_2. Free:
    a rigid mode and w^2 = k (r_1^2 / J_1 + r_2^2 / J_2) (two inertias on one spring through their levers)."""
    loaded = api.load(str(_write(tmp_path, BELT_ONLY)))
    doc = json.loads(_run("modes", str(tmp_path / "belt.toml"), "--format", "json"))
    clamped = [m["frequency_Hz"] for m in doc["boundaries"]["clamped_input"] if not m["rigid"]]
    free = [m["frequency_Hz"] for m in doc["boundaries"]["free"] if not m["rigid"]]
    two_pi = 2 * math.pi
    assert_allclose(clamped, [math.sqrt(K * R_2**2 / J_2) / two_pi], rtol=1e-9)  # 62.91 Hz
    assert_allclose(free, [math.sqrt(K * (R_1**2 / J_1 + R_2**2 / J_2)) / two_pi], rtol=1e-9)  # 128.93 Hz
    assert loaded.design.stage[0].type == "test_belt"


# ------------------------------------------------------------------------------------ the simulation
def test_the_simulated_span_force_settles_on_the_static_one(belt, tmp_path):
    """The belt alone at a constant load after the ramps: the output pulley's mean acceleration over the window
    is nil, so the window mean of the span force is the static T_L / r_2 = 300 / 0.125 = 2400 N and the mean
    stretch F / k = 1.2 mm. What is left of the start rings at 62.9 Hz (zeta = c r_2^2 / (2 J_2 w) = 0.5 %,
    amplitude ~13 N): over the 0.32 s window (20 periods) its mean is below 0.1 N, hence rtol 1e-4. Printed in
    the belt's own table and JSON keys (span force, stretch), not as a gear mesh's."""
    path = str(_write(tmp_path, BELT_ONLY))
    doc = json.loads(_run("simulate", path, "--format", "json"))
    (st,) = doc["summary"]["stages"]
    f_static = 300.0 / R_2
    assert st["type"] == "test_belt" and "penetration_mm" not in st and "tangential_N" not in st
    assert_allclose(st["static_span_force_N"], f_static, rtol=1e-14)  # the design's, carried
    assert_allclose(st["span_force_N"]["mean"], f_static, rtol=1e-4)
    assert_allclose(st["stretch_um"]["mean"], f_static / K * 1e6, rtol=1e-4)
    assert_allclose(doc["summary"]["ratio"], D_2 / D_1, rtol=1e-5)  # no slip: the window-mean speeds' ratio
    assert not [w for w in doc["warnings"] if w["code"] == "contact_loss"]  # a belt has no flank to lose
    table = _run("simulate", path, "--format", "table")
    assert "belt stages over the steady window" in table and "mesh forces" not in table


@pytest.mark.parametrize("route", [("--static",), ()])
def test_life_refuses_a_kind_without_a_life_model_by_name(belt, tmp_path, route):
    """gearcli life counts gear teeth: a kind with no life facet (the belt has none) is exit 2 naming its stage's
    type, on both routes, before any run."""
    doc = _doc_with_belt(RATED)
    doc["duty"] = [{"name": "rated", "hours": 1000.0, "torque_Nm": 1000.0, "speed_rpm": 1450.0}]
    res = CliRunner().invoke(cli, ["life", str(_write(tmp_path, doc)), *route])
    assert res.exit_code == 2, res.output
    assert "stage[1].type" in res.stderr and 'a stage of type "test_belt" has none to rate' in res.stderr
    assert "Traceback" not in res.output


def test_report_refuses_a_kind_without_a_gear_mesh_by_name(belt, tmp_path):
    """gearcli report compares each gear mesh with its theory (mesh frequency, spectrum, K_v): a belt stage is exit
    2 naming the file and the stage's type, before any run."""
    path = _write(tmp_path, BELT_ONLY)
    res = CliRunner().invoke(cli, ["report", str(path), "--quick"])
    assert res.exit_code == 2, res.output
    assert f"{path}: stage[0].type:" in res.stderr and 'of type "test_belt", which has none' in res.stderr
