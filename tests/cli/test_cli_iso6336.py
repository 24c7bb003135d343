"""`gearcli design` with the issue-10 inputs: power instead of torque, basic rack, gear bodies; exit codes."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]
SEED = str(ROOT / "configs" / "concrete_mixer.toml")


def design_json(*sets):
    args = ["design", SEED, "--format", "json"]
    for s in sets:
        args += ["--set", s]
    res = CliRunner().invoke(cli, args)
    return res, (json.loads(res.stdout) if res.exit_code == 0 else None)


def test_load_power_equals_the_torque_it_stands_for():
    """Seed: 5.31e6 N·mm on the output at 3600 °/s / 22.2689 = 161.66 °/s = 2.8215 rad/s: P = 14.982 kW.
    Giving that power (replacing the torque through --set) reproduces every torque."""
    _, ref = design_json()
    omega_out = math.radians(3600.0) * 6069 / 135150
    power = 5.31e6 * omega_out * 1e-6
    assert_allclose(power, 14.9822, rtol=1e-5)
    res, doc = design_json(f"load.power_kW={power!r}")
    assert res.exit_code == 0, res.stderr
    assert_allclose(doc["input_torque_Nmm"], ref["input_torque_Nmm"], rtol=1e-12)
    assert_allclose(doc["output_power_kW"], power, rtol=1e-12)
    assert_allclose(doc["input_power_kW"], power, rtol=1e-12)  # no losses in the seed
    st = doc["stages"][0]
    # pinion 1 at 600 rpm carrying 238.449 N·m: P = 238.449 · 62.832 / 1000 = 14.982 kW
    assert_allclose(st["pinion"]["torque_Nm"], 238.44905660377358, rtol=1e-12)
    assert_allclose(st["pinion"]["power_kW"], power, rtol=1e-12)


def test_input_power_for_a_torque_drive():
    res, doc = design_json("input.drive=torque", "input.power_kW=30")
    assert res.exit_code == 0, res.stderr
    # 30 kW at 3600 °/s = 62.832 rad/s: 477.46 N·m drives the input; the load stays the seed's
    res2, _ = design_json("input.drive=torque", "input.torque_Nm=477.4648292756861")
    assert res2.exit_code == 0


def test_torque_and_power_together_in_a_file_exit_2():
    text = Path(SEED).read_text().replace("[load]", "[load]\npower_kW = 10")
    res = CliRunner().invoke(cli, ["design", "-"], input=text)
    assert res.exit_code == 2
    assert "exactly one of torque_Nmm, torque_Nm, power_kW" in res.stderr and "load" in res.stderr


@pytest.mark.parametrize("sets, fragment", [
    (("input.power_kW=10",), 'only used with drive = "torque"'),
    (("stage.0.gear.web_thickness_mm=40",), "both web_thickness_mm and rim_thickness_mm"),
    (("stage.0.basic_rack.dedendum=0.9",), "dedendum"),
    (("stage.0.gear.bore_diameter_mm=-5",), "bore_diameter_mm"),
])
def test_bad_new_keys_exit_2_naming_the_key(sets, fragment):
    args = ["design", SEED]
    for s in sets:
        args += ["--set", s]
    res = CliRunner().invoke(cli, args)
    assert res.exit_code == 2
    assert fragment in res.stderr and "Traceback" not in res.stderr


def test_set_power_replaces_the_torque_of_the_file():
    """The file has torque_Nmm; --set load.power_kW replaces it (an exclusive group, like the speeds)."""
    res, doc = design_json("load.power_kW=10")
    assert res.exit_code == 0, res.stderr
    assert_allclose(doc["output_power_kW"], 10.0, rtol=1e-12)


def test_iso_outputs_in_json_and_table():
    res, doc = design_json("stage.1.gear.rim_thickness_mm=60", "stage.1.gear.web_thickness_mm=80",
                           "stage.1.gear.bore_diameter_mm=300")
    assert res.exit_code == 0, res.stderr
    st = doc["stages"][1]
    for key in ("iso6336_mesh_stiffness_beta_N_mm_um", "iso6336_factors", "reduced_mass_kg_mm",
                "resonance_speed_rpm", "resonance_ratio", "tip_alteration_coefficient", "working_pressure_angle_deg"):
        assert key in st
    # stage 2 gear: m_n = 18, b = 240, b_s/b = 1/3, s_R/m_n = 10/3: C_R = 1 + ln(1/3)/(5 e^(2/3)) = 0.887191
    assert_allclose(st["gear"]["gear_blank_factor"], 1 + math.log(1 / 3) / (5 * math.exp(2 / 3)), rtol=1e-12)
    assert_allclose(st["iso6336_factors"]["C_R"], 0.5 * (1 + 0.887191), rtol=1e-6)
    table = CliRunner().invoke(cli, ["design", SEED, "--format", "table"]).stdout
    for label in ("c_γβ", "m_red", "n_E1", "N = n1/n_E1", "[N·m]", "[kW]"):
        assert label in table, label
