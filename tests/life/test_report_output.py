"""Life and safety printed as a rating report prints them (docs/life.md, "Output"): an infinite life where no
class exceeds the endurance limit, the spectrum's stress safety beside its load multiplier, and a planetary
stage's planet–ring mesh never dropped without a word."""

from __future__ import annotations

import csv
import io
import json
import math
from pathlib import Path

from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli
from tests.life.scenes import RATED
from tests.life.test_life_cli import YNT, ZNT, _cycles_to_failure

CONFIGS = Path(__file__).resolve().parents[2] / "configs"


def _run(tmp_path, text: str, *args: str):
    path = tmp_path / "scene.toml"
    path.write_text(text)
    return CliRunner().invoke(cli, ["life", str(path), "--static", "-q", *args])


def test_stress_safety_beside_the_load_multiplier(tmp_path):
    """σ_H ∝ √F (pitting): the factor on stress that makes D = 1 is √ of the load multiplier; σ_F ∝ F (bending):
    the same number. Checked by scaling every class's stress by it and summing the damage by hand."""
    res = _run(tmp_path, RATED, "--format", "json")
    stage = json.loads(res.stdout)["life"]["stages"][0]
    for member in ("pinion", "gear"):
        for mode, nodes in (("pitting", ZNT), ("bending", YNT)):
            ml = stage[member][mode]
            assert ml["load_multiplier"] == ml["safety"]
            s = ml["stress_safety"]
            assert_allclose(s, math.sqrt(ml["safety"]) if mode == "pitting" else ml["safety"], rtol=1e-12)
            d = sum(b["cycles"] / _cycles_to_failure(b["stress_MPa"] * s / b["endurance_MPa"], nodes)
                    for b in ml["bins"])
            assert_allclose(d, 1.0, rtol=1e-7)


def test_a_spectrum_below_the_endurance_limit_is_infinite(tmp_path):
    """RATED's roots are far below their endurance limit (the Y_NT curve's last node, 0.85 σ_FE-based at 1e10):
    JSON life_h null with below_endurance true, CSV the same, tables ∞ (never hours / 1e-11)."""
    res = _run(tmp_path, RATED, "--format", "json")
    stage = json.loads(res.stdout)["life"]["stages"][0]
    bending = stage["pinion"]["bending"]
    assert all(b["stress_MPa"] < 0.85 * b["endurance_MPa"] for b in bending["bins"])
    assert bending["below_endurance"] is True and bending["life_h"] is None and bending["damage"] > 0
    pitting = stage["pinion"]["pitting"]  # above the limit: a finite life, hours / D
    assert pitting["below_endurance"] is False
    assert_allclose(pitting["life_h"], 20000.0 / pitting["damage"], rtol=1e-12)
    rows = list(csv.DictReader(io.StringIO(_run(tmp_path, RATED, "--format", "csv").stdout)))
    root = [r for r in rows if r["member"] == "pinion" and r["mode"] == "bending"]
    assert root and all(r["below_endurance"] == "True" and r["life_h"] == "" for r in root)
    table = _run(tmp_path, RATED, "--format", "table").stdout
    life_row = next(line for line in table.splitlines() if "life bending [h]" in line)
    assert "∞" in life_row and "e+" not in life_row
    assert "stress safety S_H pitting (on σ)" in table and "load multiplier pitting (on F)" in table


def test_planetary_nominal_stress_and_k_gamma_in_the_table(tmp_path):
    """A planetary stage's rating table lists K_γ with the load factors; σ_H0 is ISO's nominal stress:
    σ_H / σ_H0 = √(K_A K_γ K_v K_Hβ K_Hα) in the JSON (the pitch-point σ_H; Z_B/Z_D apply per member)."""
    cfg = CONFIGS / "planetary_duty.toml"
    res = CliRunner().invoke(cli, ["design", str(cfg), "--format", "json", "--set", "rating.load_sharing_factor=1.15"])
    assert res.exit_code == 0, res.output
    st = json.loads(res.stdout)["stages"][0]
    ratings = [st["rating"]] if "rating" in st else [m["rating"] for m in st["meshes"]]
    for r in ratings:
        assert r["K_gamma"] == 1.15
        assert_allclose(r["sigma_H_MPa"],
                        r["sigma_H0_MPa"] * math.sqrt(r["K_A"] * 1.15 * r["K_v"] * r["K_Hbeta"] * r["K_Halpha"]),
                        rtol=1e-12)
    table = CliRunner().invoke(cli, ["design", str(cfg), "--format", "table"]).stdout
    assert "load-sharing factor K_γ" in table


def test_the_unrated_planet_ring_mesh_is_named(tmp_path):
    """Without the ring's flank roughness the planet–ring mesh cannot be rated: `design` says which mesh and the
    key (a warning), `life` stops with exit 2 naming it."""
    text = (CONFIGS / "planetary_duty.toml").read_text().replace(
        'material = "34CrNiMo6", flank_roughness_Rz_um = 8, ', 'material = "34CrNiMo6", ')
    assert text != (CONFIGS / "planetary_duty.toml").read_text()
    path = tmp_path / "p.toml"
    path.write_text(text)
    res = CliRunner().invoke(cli, ["design", str(path), "--format", "json"])
    assert res.exit_code == 0, res.output
    warnings = [w for w in json.loads(res.stdout)["warnings"] if w["code"] == "mesh_not_rated"]
    assert len(warnings) == 1 and warnings[0]["key"] == "stage[0].ring.flank_roughness_Rz_um"
    assert "planet–ring mesh is not rated" in warnings[0]["message"]
    res = CliRunner().invoke(cli, ["life", str(path), "--static", "--format", "json", "-q"])
    assert res.exit_code == 2 and "stage[0].ring.flank_roughness_Rz_um" in res.stderr
