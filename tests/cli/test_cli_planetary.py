"""CLI tests for planetary stages: the design JSON and CSV of a mixed train, modes, simulate's per-planet
outputs, and what the model refuses (exit 2 naming file and key, no output file)."""

from __future__ import annotations

import csv
import io
import json
from pathlib import Path

import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]
GEARBOX = str(ROOT / "configs" / "wind_turbine_gearbox.toml")
STAGE = str(ROOT / "configs" / "planetary_stage.toml")


@pytest.fixture
def runner() -> CliRunner:
    return CliRunner()


def run(runner, *args):
    return runner.invoke(cli, list(args), catch_exceptions=False)


def test_design_json_of_a_mixed_train(runner):
    res = run(runner, "design", GEARBOX, "--format", "json")
    assert res.exit_code == 0, res.stderr
    doc = json.loads(res.stdout)
    first, second, third = doc["stages"]
    for st, (zs, zr) in ((first, (19, 56)), (second, (18, 93))):
        assert st["type"] == "planetary"
        assert {"sun", "planet", "ring", "carrier", "ratio", "meshes"} <= set(st)
        assert [m["name"] for m in st["meshes"]] == ["sun_planet", "planet_ring"]
        sun_rating, ring_rating = st["meshes"][0]["rating"], st["meshes"][1]["rating"]
        assert set(ring_rating) == set(sun_rating) and set(ring_rating["pinion"]) == set(sun_rating["pinion"])
        assert set(ring_rating["gear"]) == set(sun_rating["gear"])
        assert ring_rating["gear"]["S_F"] > 0.0 and ring_rating["pinion"]["S_F"] > 0.0  # both roots rated
        assert ring_rating["pinion"]["Y_M"] == sun_rating["gear"]["Y_M"] == 0.7  # the planet, an idler
        assert_allclose(st["ratio"], 1 / (1 + zr / zs), rtol=1e-12)  # carrier in, sun out, ring held
        assert st["ring"]["speed_rpm"] == 0.0 and st["planet"]["count"] == 3
        assert_allclose(st["carrier"]["torque_Nm"], st["sun"]["torque_Nm"] * (1 + zr / zs), rtol=1e-12)
    assert "type" not in third and {"pinion", "gear"} <= set(third)  # the parallel stage's output unchanged
    # the train: 1/(1 + 56/19) / (1 + 93/18) * 24/95
    assert_allclose(doc["total_ratio"], 1 / (1 + 56 / 19) / (1 + 93 / 18) * 24 / 95, rtol=1e-12)
    # a stage after a planetary one is driven by its output member: stage 2's carrier turns as stage 1's sun
    assert_allclose(second["carrier"]["speed_rpm"], first["sun"]["speed_rpm"], rtol=1e-12)
    assert_allclose(third["pinion"]["speed_rpm"], second["sun"]["speed_rpm"], rtol=1e-12)


def test_design_csv_has_the_union_of_the_columns(runner):
    res = run(runner, "design", GEARBOX, "--format", "csv")
    assert res.exit_code == 0, res.stderr
    rows = list(csv.DictReader(io.StringIO(res.stdout)))
    assert len(rows) == 3
    assert rows[0]["planet_ring_iso6336_mesh_stiffness_N_mm_um"] and rows[2]["planet_ring_iso6336_mesh_stiffness_N_mm_um"] == ""
    assert rows[2]["pinion_teeth"] == "95" and rows[0]["sun_teeth"] == "19"


def test_modes_of_a_planetary_stage(runner):
    res = run(runner, "modes", STAGE, "--format", "json")
    assert res.exit_code == 0, res.stderr
    doc = json.loads(res.stdout)
    text = json.dumps(doc)
    assert "stage 1 planet 3" in text


def test_simulate_reports_every_planet(runner, tmp_path):
    out = tmp_path / "sim.json"
    res = run(runner, "simulate", STAGE, "--format", "json", "-o", str(out), "--set", "simulation.duration_s=0.3")
    assert res.exit_code == 0, res.stderr
    st = json.loads(out.read_text())["summary"]["stages"][0]
    assert len(st["planets"]) == 3 and set(st["planets"][0]) == {"index", "sun", "ring"}
    assert_allclose(st["load_sharing_factor"], 1.0, atol=1e-9)


def test_time_varying_stiffness_on_planet_meshes_runs(runner, tmp_path):
    """Time-varying contact-line stiffness on planet meshes (refused before: now phased per planet and between
    each planet's sun and ring mesh from the geometry)."""
    out = tmp_path / "sim.json"
    res = run(runner, "simulate", STAGE, "--format", "json", "-o", str(out), "--set", "simulation.duration_s=0.3",
              "--set", "stage.0.mesh.time_varying=true")
    assert res.exit_code == 0, res.stderr
    assert len(json.loads(out.read_text())["summary"]["stages"][0]["planets"]) == 3


def test_a_phased_mesh_after_planetary_stages_runs(runner, tmp_path):
    """A transmission error on the parallel stage after two planetary stages (refused before: its phase comes
    from the planetary output's angle now)."""
    out = tmp_path / "sim.json"
    res = run(runner, "simulate", GEARBOX, "--format", "json", "-o", str(out), "--set", "simulation.duration_s=0.3",
              "--set", "stage.2.mesh.transmission_error_um=[2.0]")
    assert res.exit_code == 0, res.stderr
    assert len(json.loads(out.read_text())["summary"]["stages"]) == 3


def test_transmission_error_on_planet_meshes_runs(runner, tmp_path):
    out = tmp_path / "sim.json"
    res = run(runner, "simulate", STAGE, "--format", "json", "-o", str(out), "--set", "simulation.duration_s=0.3",
              "--set", "stage.0.mesh.transmission_error_um=[2.0]")
    assert res.exit_code == 0, res.stderr
    assert len(json.loads(out.read_text())["summary"]["stages"][0]["planets"]) == 3


def test_report_compares_the_output_member_and_the_flank_sign(runner, tmp_path):
    out = tmp_path / "report.json"
    res = run(runner, "report", STAGE, "--quick", "--format", "json", "-o", str(out))
    assert res.exit_code == 0, res.stderr
    rows = json.loads(out.read_text())["comparison"]
    stage_rows = {r["quantity"]: r for r in rows if r["stage"] == 1}
    # the sun (output) at 12.127 rpm x (1 + 56/19); F_t theory with the model's flank sign
    assert_allclose(stage_rows["output_speed_deg_s"]["theory"], 12.127 * 6 * (1 + 56 / 19), rtol=1e-12)
    assert abs(stage_rows["tangential_N"]["error_percent"]) < 0.01


def test_design_table_shows_the_planet_ring_rating(runner):
    """The planet–ring mesh's rating sits below the planetary stages' table, planet / ring per cell: both roots
    rated, the idler planet's Y_M 0.7, the internal mesh's own K_v; the same figures as JSON's meshes[1].rating."""
    res = runner.invoke(cli, ["design", STAGE, "--format", "table"], env={"COLUMNS": "160"}, catch_exceptions=False)
    assert res.exit_code == 0, res.stderr
    out = res.stdout
    head = "planet–ring mesh strength rating, ISO 6336:2006 method B"
    assert head in out and out.index("planetary stages") < out.index(head)
    section = out[out.index(head):out.index("shafts")]
    doc = json.loads(run(runner, "design", STAGE, "--format", "json").stdout)
    rating = doc["stages"][0]["meshes"][1]["rating"]
    planet, ring = rating["pinion"], rating["gear"]
    row = next(line for line in section.splitlines() if "root safety S_F" in line)
    assert f"{planet['S_F']:.3g} / {ring['S_F']:.3g}" in row
    row = next(line for line in section.splitlines() if "mean stress Y_M" in line)
    assert "0.7 / 1" in row
    row = next(line for line in section.splitlines() if "dynamic factor K_v" in line)
    assert f"{rating['K_v']:.4g} ({rating['K_v_source']})" in row


def test_design_csv_carries_the_ring_root(runner):
    res = run(runner, "design", STAGE, "--format", "csv")
    assert res.exit_code == 0, res.stderr
    rows = list(csv.DictReader(io.StringIO(res.stdout)))
    assert float(rows[0]["planet_ring_rating_gear_S_F"]) > 0.0
    assert float(rows[0]["planet_ring_rating_pinion_Y_M"]) == 0.7
    assert float(rows[0]["planet_ring_resonance_ratio"]) > 0.0


def test_simulate_rates_planetary_stages_at_the_simulated_dynamic_factor(runner):
    """`rating.dynamic_factor = "simulated"` on a train with planetary stages (an internal error before): each
    stage's rating is the design's at K_v = max(1, its simulated dynamic factor), the planetary ones as their
    sun–planet mesh with the design's K_gamma (σ_F / (K_v K_Fβ K_Fα) and σ_H0 as the design's)."""
    res = run(runner, "simulate", GEARBOX, "--set", "rating.dynamic_factor=simulated", "--set",
              "simulation.duration_s=0.3", "--format", "json", "-q")
    assert res.exit_code == 0, res.stderr
    design = json.loads(run(runner, "design", GEARBOX, "--format", "json").stdout)
    stages = json.loads(res.stdout)["summary"]["stages"]
    assert len(stages) == 3
    for st, ds in zip(stages, design["stages"], strict=True):
        rating = st["rating"]
        iso = ds["meshes"][0]["rating"] if ds.get("type") == "planetary" else ds["rating"]
        assert rating["K_v_source"] == "simulated"
        # a planetary stage's K_v is its most loaded planet's sun mesh: at the equilibrium (no excitation) the
        # planets share the load equally to rounding, so K_v and the stage's factor agree to rounding
        assert_allclose(rating["K_v"], max(1.0, st["dynamic_factor"]), rtol=1e-9)
        assert_allclose(rating["sigma_H0_MPa"], iso["sigma_H0_MPa"], rtol=1e-12)
        for part in ("pinion", "gear"):
            assert_allclose(rating[part]["sigma_F_MPa"] / (rating["K_v"] * rating["K_Fbeta"] * rating["K_Falpha"]),
                            iso[part]["sigma_F_MPa"] / (iso["K_v"] * iso["K_Fbeta"] * iso["K_Falpha"]), rtol=1e-9)
