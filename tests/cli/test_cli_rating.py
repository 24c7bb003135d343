"""`gearcli design` / `simulate` with [rating]: warnings, JSON keys, missing keys (exit 2), simulated K_v."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]
WIND = str(ROOT / "configs" / "wind_turbine_5MW_narrow_face.toml")
RATED = str(ROOT / "configs" / "industrial_two_stage_rated.toml")
SEED = str(ROOT / "configs" / "concrete_mixer.toml")
STAGE_KEYS = {"standard", "K_A", "K_v", "K_v_source", "K_Hbeta", "K_Hbeta_source", "K_Fbeta", "K_Halpha", "K_Falpha",
              "Z_H", "Z_E", "Z_eps", "Z_beta", "Z_L", "Z_V", "Z_R", "Z_W", "Y_beta", "sigma_H0_MPa", "sigma_H_MPa",
              "pinion", "gear"}
MEMBER_KEYS = {"load_cycles", "Z_BD", "sigma_H_MPa", "Z_NT", "Z_X", "sigma_HG_MPa", "sigma_HP_MPa", "S_H", "Y_F",
               "Y_S", "Y_B", "Y_DT", "sigma_F0_MPa", "sigma_F_MPa", "Y_delta_rel_T", "Y_R_rel_T", "Y_X", "Y_NT",
               "sigma_FG_MPa", "sigma_FP_MPa", "S_F", "Y_M"}


def _message(w) -> str:
    return w if isinstance(w, str) else w["message"]  # bare strings, or {code, message, ...} objects


def test_narrow_wind_stage_warns_on_stderr_and_in_json():
    res = CliRunner().invoke(cli, ["design", WIND, "--format", "json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    rating = doc["stages"][0]["rating"]
    assert set(rating) == STAGE_KEYS and set(rating["pinion"]) == MEMBER_KEYS == set(rating["gear"])
    assert rating["standard"] == "ISO 6336:2006 method B" and rating["K_v_source"] == "iso"
    messages = [_message(w) for w in doc["warnings"]]
    for part in ("pinion", "gear"):
        for what, key in (("pitting", "S_H"), ("bending", "S_F")):
            assert rating[part][key] < 1.0
            assert any(f"stage 1 {part}" in m and what in m and key in m for m in messages), (part, key)
            assert any(f"stage 1 {part}" in line and what in line for line in res.stderr.splitlines())


def test_rated_industrial_reducer_is_safe_and_prints_a_rating_table():
    res = CliRunner().invoke(cli, ["design", RATED, "--format", "table"], env={"COLUMNS": "120"})
    assert res.exit_code == 0, res.output
    assert "strength rating, ISO 6336:2006 method B" in res.stdout
    for label in ("K_v", "Y_F", "σ_F0", "σ_FP", "S_F", "Z_H", "σ_H0", "σ_HP", "S_H"):
        assert label in res.stdout
    assert "safety" not in res.stderr


def test_without_rating_the_stage_rating_is_null():
    res = CliRunner().invoke(cli, ["design", SEED, "--format", "json"])
    assert res.exit_code == 0
    assert [s["rating"] for s in json.loads(res.stdout)["stages"]] == [None, None, None]


@pytest.mark.parametrize(("override", "key"), [
    ("stage.0.accuracy_grade", "stage[0].accuracy_grade"),
    ("stage.1.gear.root_roughness_Rz_um", "stage[1].gear.root_roughness_Rz_um"),
    ("lubricant.viscosity_40C_mm2_s", "lubricant.viscosity_40C_mm2_s"),
    ("rating.required_life_h", "rating.required_life_h"),
])
def test_missing_rating_key_is_exit_2_naming_file_and_key(tmp_path, override, key):
    import tomllib

    import tomli_w

    doc = tomllib.loads(Path(RATED).read_text())
    node = doc
    *parents, last = [int(p) if p.isdigit() else p for p in override.split(".")]
    for p in parents:
        node = node[p]
    del node[last]
    path = tmp_path / "rated.toml"
    path.write_text(tomli_w.dumps(doc))
    res = CliRunner().invoke(cli, ["design", str(path)])
    assert res.exit_code == 2
    assert str(path) in res.stderr and key in res.stderr
    assert "Traceback" not in res.output


def test_missing_material_treatment_is_exit_2(tmp_path):
    text = Path(RATED).read_text().replace('treatment = "case_carburized"\n', "")
    path = tmp_path / "rated.toml"
    path.write_text(text)
    res = CliRunner().invoke(cli, ["design", str(path)])
    assert res.exit_code == 2 and "materials.18CrNiMo7-6.treatment" in res.stderr


def test_simulate_carries_the_rating_at_the_simulated_dynamic_factor():
    args = ["simulate", RATED, "--set", "rating.dynamic_factor=simulated", "--set", "simulation.duration_s=0.3",
            "--set", "simulation.steps=600", "--format", "json"]
    res = CliRunner().invoke(cli, args)
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    design = json.loads(CliRunner().invoke(cli, ["design", RATED, "--format", "json"]).stdout)
    for k, stage in enumerate(doc["summary"]["stages"]):
        rating = stage["rating"]
        assert rating["K_v_source"] == "simulated"
        ft = stage["tangential_N"]
        window_factor = max(abs(ft["max"]), abs(ft["min"])) / abs(stage["simulated_static_tangential_N"])
        assert_allclose(stage["dynamic_factor"], window_factor, rtol=1e-12)  # the contract's dynamic_factor
        assert_allclose(rating["K_v"], max(1.0, stage["dynamic_factor"]), rtol=1e-12)  # K_v = max(1, it)
        iso = design["stages"][k]["rating"]
        assert iso["K_v_source"] == "iso"
        # everything but K_v and what follows from it is the design's rating
        for key in ("Z_H", "Z_E", "Z_eps", "Z_beta", "Y_beta", "sigma_H0_MPa"):  # K_Hβ (estimated) follows K_v
            assert_allclose(rating[key], iso[key], rtol=1e-12)
        for part in ("pinion", "gear"):  # σ_F ∝ K_v K_Fβ K_Fα: S_F at the simulated K_v
            assert_allclose(rating[part]["sigma_FG_MPa"], iso[part]["sigma_FG_MPa"], rtol=1e-12)
            assert_allclose(rating[part]["sigma_F_MPa"] / (rating["K_v"] * rating["K_Fbeta"] * rating["K_Falpha"]),
                            iso[part]["sigma_F_MPa"] / (iso["K_v"] * iso["K_Fbeta"] * iso["K_Falpha"]), rtol=1e-9)


def test_simulate_without_simulated_dynamic_factor_has_no_rating_key():
    args = ["simulate", RATED, "--set", "simulation.duration_s=0.3", "--set", "simulation.steps=600",
            "--format", "json"]
    res = CliRunner().invoke(cli, args)
    assert res.exit_code == 0, res.output
    assert all("rating" not in s for s in json.loads(res.stdout)["summary"]["stages"])


def test_report_prints_iso_beside_simulated_dynamic_factor():
    args = ["report", RATED, "--quick", "--set", "rating.dynamic_factor=simulated", "--set", "simulation.duration_s=0.3",
            "--set", "simulation.steps=600", "--format", "json"]
    res = CliRunner().invoke(cli, args)
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    sim_stages = doc["simulation"]["summary"]["stages"]
    assert [row["stage"] for row in doc["rating"]] == [1, 2]
    for row, stage in zip(doc["rating"], sim_stages, strict=True):
        assert row["K_v_iso_source"] == "iso" and row["K_v_iso"] > 1.0
        assert_allclose(row["K_v_simulated"], stage["rating"]["K_v"], rtol=1e-12)
        assert_allclose(row["min_S_H_simulated"], min(stage["rating"]["pinion"]["S_H"], stage["rating"]["gear"]["S_H"]))
    md = CliRunner().invoke(cli, [*args[:-2], "--format", "table"], env={"COLUMNS": "120"})
    assert md.exit_code == 0 and "Dynamic factor: ISO 6336-1 against the simulation" in md.stdout


def test_safety_warnings_carry_codes_and_data_in_design_and_simulate():
    """The diagnostics mechanism: codes pitting_safety_low / bending_safety_low with stage, member, mode, S, S_min;
    simulate keeps the design's codes and the facade adds the simulated rating's own (composed after the run)."""
    from gearcli import api
    from gearcli.config import load_design
    from gearcli.design import compute_design

    loaded = load_design(WIND, ["rating.dynamic_factor=simulated", "simulation.duration_s=0.3",
                                "simulation.steps=300"])
    design = compute_design(loaded.design)
    rated = [d for d in design.diagnostics if d.code.endswith("_safety_low")]  # the design checks' own are code "design"
    codes = {(d.code, d.data["member"], d.data["mode"]) for d in rated}
    assert codes == {("pitting_safety_low", p, "pitting") for p in ("pinion", "gear")} | \
        {("bending_safety_low", p, "bending") for p in ("pinion", "gear")}
    for d in rated:
        assert d.data["stage"] == 1 and d.data["S"] < d.data["S_min"] and d.message in design.warnings
    sim = api.simulate(loaded.design, design, want_series=False)
    sim_codes = [d.code for d in sim.diagnostics if d.code.endswith("_safety_low")]
    assert len(sim_codes) == 8  # the design's four (ISO K_v) and the simulated rating's four
    assert sum("simulated" in d.message for d in sim.diagnostics if d.code.endswith("_safety_low")) == 4
