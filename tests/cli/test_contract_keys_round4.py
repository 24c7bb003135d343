"""Contract key audit, round 4: every key, column and JSON name DESIGN §5–§13 gives for the machine-readable outputs
other than ``gearcli design`` (simulate JSON/CSV with and without --series, modes, sweep CSV/JSON rows, life,
schema), on shipped scenes that exercise them, with the values checked against hand figures where cheap:

- planetary_stage.toml: sun 19, planet 17 (x3), ring 56 held, the carrier driven at 12.127 rpm; Willis ratio
  carrier/sun = z_s / (z_s + z_r) = 19/75, sun speed 12.127 x 75/19 rpm; the sun mesh's static force per planet
  at the reference circle F_t = T_sun / (N d_s / 2), d_s = m_n z_s / cos beta = 45 x 19 = 855 mm (spur).
- motor_duty_starts.toml: two helical stages 74/19 x 92/18, a DOL motor, bearings, a duty with starts.
- concrete_mixer_drivetrain.toml: motor and drum couplings, two flexible shafts (seed units, deg/s and N mm).
- concrete_mixer_te.toml: transmission-error excitation, swept over input speed and sampled over load torque.
"""

from __future__ import annotations

import csv
import io
import json
import tomllib
from pathlib import Path

import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]
CONFIGS = ROOT / "configs"
STATS = {"mean", "min", "max", "std"}
DTE = {"mean", "rms", "min", "max"}


def run(*args: str) -> str:
    res = CliRunner().invoke(cli, ["-q", *args], catch_exceptions=False)
    assert res.exit_code == 0, res.stderr
    return res.stdout


def run_json(*args: str) -> dict:
    return json.loads(run(*args))


def header(text: str) -> list[str]:
    return next(csv.reader(io.StringIO(text)))


def assert_warning_objects(doc: dict) -> None:
    """DESIGN §12: JSON ``warnings`` are objects {code (snake_case), message, data...}."""
    assert isinstance(doc["warnings"], list)
    for w in doc["warnings"]:
        assert isinstance(w, dict) and isinstance(w["message"], str) and w["message"]
        assert w["code"] == w["code"].lower() and " " not in w["code"]


def assert_provenance(doc: dict) -> None:
    """DESIGN §5: every JSON carries ``gearcli_version`` and ``input_sha256``."""
    assert isinstance(doc["gearcli_version"], str)
    assert len(doc["input_sha256"]) == 64


@pytest.fixture(scope="module")
def planetary_json() -> dict:
    return run_json("simulate", str(CONFIGS / "planetary_stage.toml"), "--format", "json", "--series")


@pytest.fixture(scope="module")
def motor_json() -> dict:
    return run_json("simulate", str(CONFIGS / "motor_duty_starts.toml"), "--format", "json")


def test_simulate_json_summary_solver_and_series_of_a_planetary_stage(planetary_json):
    doc = planetary_json
    assert_provenance(doc)
    assert_warning_objects(doc)
    s = doc["summary"]
    # §5 summary; §12 units: speed_rpm file -> rpm keys (output_speed_deg_s stays, §5)
    assert_allclose(s["ratio"], 19 / 75, rtol=1e-6)  # Willis, carrier driven, ring held: mean speeds agree
    assert_allclose(s["output_speed_rpm"], 12.127 * 75 / 19, rtol=1e-6)
    assert_allclose(s["output_speed_deg_s"], 12.127 * 75 / 19 * 6.0, rtol=1e-6)
    assert len(s["window_s"]) == 2 and s["window_s"][0] < s["window_s"][1]
    st = s["stages"][0]
    for key in ("tangential_N", "radial_N", "axial_N"):
        assert set(st[key]) >= STATS
    assert set(st["dte_um"]) >= DTE  # §6
    for key in ("contact_loss_fraction", "back_flank_fraction", "dynamic_factor", "runup_factor",
                "peak_tangential_N", "peak_time_s", "load_sharing_factor"):  # §6, §8, §11
        assert isinstance(st[key], float), key
    # the sun mesh's static force per planet at the reference circle (hand figure above)
    assert_allclose(abs(st["static_tangential_N"]), 999650.9e3 / (3 * 45 * 19 / 2), rtol=1e-6)
    assert set(st["mesh_stiffness"]) >= {"law", "K", "exponent", "linearised_N_mm", "iso_N_mm"}  # §7, §13
    assert st["mesh_stiffness"]["law"] == "iso6336"
    # §13: the calibrated tangent equals ISO's k_n
    assert_allclose(st["mesh_stiffness"]["linearised_N_mm"], st["mesh_stiffness"]["iso_N_mm"], rtol=1e-9)
    assert len(st["planets"]) == 3  # §11
    for planet in st["planets"]:
        for side in ("sun", "ring"):
            assert set(planet[side]["tangential_N"]) >= STATS and set(planet[side]["dte_um"]) >= DTE
    assert set(s["start"]) >= {"peak_over_rigid", "rigid_peak_N"}  # §13
    solver = doc["solver"]  # §5, §6, §13
    assert {"method", "rtol", "atol", "nfev", "njev", "steps", "wall_s", "energy_residual", "engine",
            "compile_s", "prediction", "course_changes"} <= set(solver)
    assert set(solver["prediction"]) >= {"nfev", "price_us_per_eval", "wall_s"}
    assert isinstance(solver["nfev"], int) and isinstance(solver["steps"], int)
    series = doc["series"]  # only with --series (§5)
    assert list(series)[0] == "time_s"
    assert {"shaft1_speed_rpm", "shaft2_speed_rpm", "input_torque_Nm", "stage1_tangential_N",
            "stage1_planet1_sun_tangential_N", "stage1_planet3_ring_tangential_N", "stage1_planet2_sun_dte_um",
            "stage1_planet2_ring_dte_um"} <= set(series)


def test_simulate_json_without_series_has_none(motor_json):
    assert "series" not in motor_json


def test_simulate_json_of_a_motor_start_with_bearings(motor_json):
    doc = motor_json
    assert_provenance(doc)
    assert_warning_objects(doc)
    s = doc["summary"]
    assert_allclose(s["ratio"], 74 / 19 * 92 / 18, rtol=1e-3)  # slip does not enter the reducer's ratio
    assert isinstance(s["start_time_s"], float) and 0 < s["start_time_s"] < s["window_s"][0]  # §9
    # operating slip of the four-pole motor (n_s = 1500 rpm) at its window-mean speed
    assert_allclose(s["operating_slip"], 1 - s["motor"]["operating_speed_rpm"] / 1500.0, rtol=1e-6)
    assert len(s["start"]["peak_over_rigid"]) == len(s["stages"]) == len(s["start"]["rigid_peak_N"])  # §13
    assert len(s["bearings"]) == 6  # §10: summary.bearings[j]
    for b in s["bearings"]:
        assert {"shaft", "position_mm", "radial_N", "axial_N", "static_safety_min"} <= set(b)
        assert set(b["radial_N"]) >= STATS and set(b["axial_N"]) >= STATS


def test_simulate_csv_columns_of_a_motor_scene_with_bearings():
    cols = header(run("simulate", str(CONFIGS / "motor_duty_starts.toml"), "--format", "csv"))
    assert cols[0] == "time_s"
    expected = ["shaft1_speed_rpm", "shaft2_speed_rpm", "shaft3_speed_rpm", "input_torque_Nm"]
    for k in (1, 2):
        expected += [f"stage{k}_{q}" for q in ("tangential_N", "radial_N", "axial_N", "penetration_mm", "dte_um")]
    expected += ["motor_speed_rpm", "drum_speed_rpm", "motor_torque_Nm", "input_coupling_torque_Nm",
                 "load_coupling_torque_Nm"]  # §6, §9 in the file's units (§12)
    expected += [f"bearing{j}_{q}" for j in range(1, 7) for q in ("radial_N", "axial_N")]  # §10
    assert set(expected) <= set(cols)
    assert cols.index("shaft1_speed_rpm") < cols.index("input_torque_Nm") < cols.index("stage1_tangential_N")


def test_simulate_csv_columns_of_a_flexible_drivetrain_in_seed_units():
    cols = header(run("simulate", str(CONFIGS / "concrete_mixer_drivetrain.toml"), "--format", "csv"))
    assert cols[:6] == ["time_s", "shaft1_speed_deg_s", "shaft2_speed_deg_s", "shaft3_speed_deg_s",
                        "shaft4_speed_deg_s", "input_torque_Nmm"]
    # §6 (a flexible shaft's twist, the motor and drum, the couplings) with §12's units of a torque_Nmm file
    assert {"shaft2_twist_deg", "shaft3_twist_deg", "motor_speed_deg_s", "drum_speed_deg_s",
            "input_coupling_torque_Nmm", "load_coupling_torque_Nmm", "stage3_penetration_mm",
            "stage3_dte_um"} <= set(cols)


def test_simulated_dynamic_factor_rating_in_simulate_json():
    doc = run_json("simulate", str(CONFIGS / "industrial_two_stage_rated.toml"), "--set",
                   "rating.dynamic_factor=simulated", "--format", "json")
    for st in doc["summary"]["stages"]:  # §8: the rating repeated at K_v = max(1, dynamic factor)
        r = st["rating"]
        assert r["K_v_source"] == "simulated"
        assert_allclose(r["K_v"], max(1.0, st["dynamic_factor"]), rtol=1e-9)
        assert {"standard", "K_A", "K_Hbeta", "K_Hbeta_source", "K_Fbeta", "K_Halpha", "K_Falpha", "Z_H", "Z_E",
                "Z_eps", "Z_beta", "Z_L", "Z_V", "Z_R", "Z_W", "Y_beta", "sigma_H0_MPa", "sigma_H_MPa"} <= set(r)
        for member in ("pinion", "gear"):
            assert {"load_cycles", "Z_BD", "sigma_H_MPa", "Z_NT", "Z_X", "sigma_HG_MPa", "sigma_HP_MPa", "S_H",
                    "Y_F", "Y_S", "Y_B", "Y_DT", "sigma_F0_MPa", "sigma_F_MPa", "Y_delta_rel_T", "Y_R_rel_T", "Y_X",
                    "Y_NT", "sigma_FG_MPa", "sigma_FP_MPa", "S_F"} <= set(r[member])


def test_modes_json_boundaries_shapes_energy_and_mesh_stiffness():
    doc = run_json("modes", str(CONFIGS / "concrete_mixer_drivetrain.toml"), "--format", "json")
    assert_provenance(doc)
    assert_warning_objects(doc)
    assert set(doc["boundaries"]) == {"clamped_input", "free"}  # §6
    free = doc["boundaries"]["free"]
    assert free[0]["rigid"] and free[0]["frequency_Hz"] == 0.0  # a free train's rigid-body mode
    for mode in doc["boundaries"]["clamped_input"]:
        assert {"mode", "frequency_Hz", "shape", "energy_share"} <= set(mode)
        assert_allclose(sum(mode["energy_share"].values()), 1.0, rtol=1e-9)  # shares of the modal strain energy
    assert len(doc["meshes"]) == 3  # §13: per mesh
    for mesh in doc["meshes"]:
        assert {"law", "K", "exponent", "linearised_N_mm", "iso_N_mm"} <= set(mesh["mesh_stiffness"])
    assert {w["code"] for w in doc["warnings"]} >= {"stiffness_not_iso"}  # the seed's hertz law, -88 % from ISO


def _seed_ratio() -> float:
    cfg = tomllib.loads((CONFIGS / "concrete_mixer_te.toml").read_text())
    ratio = 1.0
    for st in cfg["stage"]:
        ratio *= st["gear"]["teeth"] / st["pinion"]["teeth"]
    return ratio


SWEEP_STAGE = ("tangential_N_mean", "tangential_N_std", "tangential_N_min", "tangential_N_max", "dte_um_mean",
               "dte_um_rms", "dte_um_min", "dte_um_max", "contact_loss_fraction", "dynamic_factor", "runup_factor")


def _sweep_columns(key: str) -> list[str]:
    return [key, "direction", "status", "message",
            *[f"stage{k}_{c}" for k in (1, 2, 3) for c in SWEEP_STAGE], "output_speed_rpm", "nfev", "wall_s"]


@pytest.mark.parametrize("fmt", ["csv", "json"])
def test_sweep_rows_with_vary(fmt):
    out = run("sweep", str(CONFIGS / "concrete_mixer_te.toml"), "--vary", "input.speed_deg_s=3000,3600",
              "--jobs", "1", "--format", fmt)
    if fmt == "csv":
        rows = list(csv.DictReader(io.StringIO(out)))
        assert list(rows[0]) == _sweep_columns("input.speed_deg_s")  # §6, §12 (runup_factor)
    else:
        doc = json.loads(out)
        assert_provenance(doc)
        assert doc["columns"] == _sweep_columns("input.speed_deg_s")
        rows = doc["rows"]
        assert set(rows[0]) <= set(doc["columns"])
    for row, speed in zip(rows, (3000, 3600), strict=True):
        assert row["status"] == "ok"
        # the column carries its unit (rpm) whatever the file's: input deg/s / 6 over the teeth ratio
        assert_allclose(float(row["output_speed_rpm"]), speed / 6.0 / _seed_ratio(), rtol=1e-4)


def test_sweep_rows_with_random_name_the_sampled_key():
    rows = list(csv.DictReader(io.StringIO(run(
        "sweep", str(CONFIGS / "concrete_mixer_te.toml"), "--random", "load.torque_Nmm=normal(5.31e6,1e5)",
        "--samples", "2", "--seed", "3", "--jobs", "1", "--format", "csv"))))
    assert len(rows) == 2 and list(rows[0]) == _sweep_columns("load.torque_Nmm")
    for row in rows:
        assert row["status"] == "ok" and abs(float(row["load.torque_Nmm"]) - 5.31e6) < 1e6


def _modified_bearing_scene(tmp_path: Path) -> Path:
    """motor_duty_starts.toml with DESIGN §13's modified-life and static inputs on every bearing."""
    text = (CONFIGS / "motor_duty_starts.toml").read_text()
    text = text.replace("[lubricant]\nviscosity_40C_mm2_s = 220", "[lubricant]\nviscosity_40C_mm2_s = 220\n"
                        "viscosity_100C_mm2_s = 19\ntemperature_C = 70\ncontamination = \"normal\"")
    text = text.replace("[[bearing]]\n", "[[bearing]]\nfatigue_load_limit_kN = 4.5\npitch_diameter_mm = 100\n"
                        "reliability_percent = 95\nstatic_factors = { X0 = 0.6, Y0 = 0.5 }\n")
    assert text.count("fatigue_load_limit_kN") == 6 and "contamination" in text
    path = tmp_path / "modified_bearings.toml"
    path.write_text(text)
    return path


def test_life_json_static_route_with_modified_bearing_life(tmp_path):
    doc = run_json("life", str(_modified_bearing_scene(tmp_path)), "--static", "--format", "json")
    assert_provenance(doc)
    assert_warning_objects(doc)
    life = doc["life"]
    for st in life["stages"]:  # §10, §13
        for member in ("pinion", "gear"):
            for mode in ("pitting", "bending"):
                ml = st[member][mode]
                assert {"damage", "life_h", "safety", "bins", "below_endurance", "stress_safety",
                        "load_multiplier"} <= set(ml)
                assert ml["life_h"] is None if ml["below_endurance"] else ml["life_h"] > 0
                for b in ml["bins"]:
                    assert {"force_N", "stress_MPa", "cycles", "cycles_to_failure", "damage"} <= set(b)
    b = life["bearings"][0]  # shaft 1, a ball bearing (p = 3), C = 90 kN, C_0 = 54 kN, at 1480 rpm
    assert {"L10_h", "L10_Mrev", "equivalent_load_N", "kappa", "a_ISO", "a_1", "L_nm_Mrev", "L_nm_h",
            "static_equivalent_load_N", "static_safety"} <= set(b)
    l10 = (90e3 / b["equivalent_load_N"]) ** 3  # ISO 281: L10 = (C/P)^p million revolutions
    assert_allclose(b["L10_Mrev"], l10, rtol=1e-9)
    assert_allclose(b["L10_h"], l10 * 1e6 / (60 * 1480), rtol=1e-9)
    assert b["a_1"] == 0.64  # ISO 281 Table 12, 95 % reliability
    assert_allclose(b["L_nm_Mrev"], b["a_1"] * b["a_ISO"] * l10, rtol=1e-9)
    assert_allclose(b["static_safety"], 54e3 / b["static_equivalent_load_N"], rtol=1e-9)  # ISO 76: C_0 / P_0


def test_planetary_start_damage_names_sun_and_planet():
    """§10 names a planetary stage's members ``sun``, ``planet``, ``ring``; the life JSON's stages carried them
    beside the per-mesh entries, but ``points[i].start.damage`` (§13: per member and mode) gave only the per-mesh
    ``pinion``/``gear``/``planet_ring_side``/``planet_root``. Now the same names, the same entries as stages[k]."""
    doc = run_json("life", str(CONFIGS / "planetary_duty.toml"), "--set", "duty[0].starts=100", "--format", "json")
    life = doc["life"]
    start = life["points"][0]["start"]
    assert start["count"] == 100 and len(start["peak_tangential_N"]) == 1
    dmg = start["damage"][0]
    assert {"sun", "planet", "ring"} <= set(dmg)
    assert dmg["sun"] == dmg["pinion"]  # the sun is the sun–planet mesh's pinion
    flank = life["stages"][0]["planet"]["pitting"]["flank"]  # the planet flank the stage reports
    assert dmg["planet"]["pitting"] == dmg[{"sun_mesh": "gear", "ring_mesh": "planet_ring_side"}[flank]]["pitting"]
    assert dmg["planet"]["bending"] == dmg["planet_root"]["bending"]  # both meshes' bending on one root
    # the start's own classes ("rated (start)") in the sun's bins sum to its start damage
    bins = life["stages"][0]["sun"]["pitting"]["bins"]
    assert_allclose(dmg["sun"]["pitting"], sum(b["damage"] for b in bins if b["point"] == "rated (start)"),
                    rtol=1e-12)


def test_schema_is_a_json_schema_of_the_design_file():
    doc = json.loads(run("schema"))
    assert "json-schema.org" in doc["$schema"]
    assert {"stage", "input", "load", "simulation", "duty", "bearing"} <= set(doc["properties"])
