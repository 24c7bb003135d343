"""The rating seam (issue 34): a standard registered in one module (``nominal_stress.py``, tests only) and
selected by ``[rating] standard`` flows through design, the simulated-K_v rating, life and the output; an unknown
name is exit 2 naming the key and the registered names. Every figure is the test standard's closed form, written
out here from the design's forces and geometry."""

from __future__ import annotations

import json
import math
from pathlib import Path

import nominal_stress as ns
import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli
from gearcli.rating import names

MIXER = str(Path(__file__).resolve().parents[2] / "configs" / "mixer_duty.toml")
SELECT = ("--set", "rating.standard=nominal_stress")


def _run(*args: str) -> dict:
    r = CliRunner().invoke(cli, [*args, "--format", "json", "-q"])
    assert r.exit_code == 0, r.output
    return json.loads(r.output)


def _contact_stress(st: dict, force_N: float, k_v: float = 1.0) -> float:
    """σ_H = 475 sqrt(K_v F_t / (b d_1) (u + 1) / u), the test standard's formula by hand."""
    u = st["gear"]["teeth"] / st["pinion"]["teeth"]
    return 475.0 * math.sqrt(k_v * force_N / (st["face_width_mm"] * st["pinion"]["pitch_diameter_mm"]) * (u + 1) / u)


def test_the_test_standard_is_registered_beside_iso6336():
    import gearcli.design.iso6336  # noqa: F401  # registers ISO 6336 (loaded by a rated design, gearcli.rating is below)

    assert {"iso6336", "nominal_stress"} <= set(names())


def test_design_rates_every_stage_by_the_selected_standard():
    doc = _run("design", MIXER, *SELECT)
    for st in doc["stages"]:
        r = st["rating"]
        f_t = abs(st["static_force_N"]["tangential"])
        sigma_h = _contact_stress(st, f_t)
        sigma_f = 4.5 * f_t / (st["face_width_mm"] * st["normal_module_mm"])
        assert r["standard"] == ns.TITLE and r["K_v_source"] == "nominal"
        # the mixer's steel: σ_Hlim 1500 MPa, σ_Flim 430 MPa (times Y_ST = 2); rel 1e-12: the same closed form
        assert_allclose([r["pinion"]["S_H"], r["gear"]["S_F"]], [1500.0 / sigma_h, 860.0 / sigma_f], rtol=1e-12)
        assert_allclose(r["pinion"]["load_cycles"], 60.0 * abs(st["pinion"]["speed_rpm"]) * 16500, rtol=1e-12)
    table = CliRunner().invoke(cli, ["design", MIXER, *SELECT, "--format", "table", "-q"]).output
    assert "strength rating, nominal stress (a test standard)" in table and "pitting safety p / g" in table


def test_an_unknown_standard_is_exit_2_naming_the_key_and_the_registered_names():
    r = CliRunner().invoke(cli, ["design", MIXER, "--set", "rating.standard=agma2001", "--format", "json"])
    assert r.exit_code == 2
    assert "rating.standard" in r.output and '"agma2001"' in r.output and '"iso6336"' in r.output


def test_life_sums_miner_damage_on_the_standard_s_own_curves():
    """Static route, σ_Hlim lowered to 1000 MPa: charging (300 kN·m) lies below the flat endurance limit, mixing
    and discharging on the Basquin line N = 1e5 (1.6 / y)^k, k = ln(5e7/1e5) / ln 1.6, y = σ_H / 1000."""
    lowered = ("--set", "materials.steel.contact_fatigue_limit_MPa=1000")
    st = _run("design", MIXER, *SELECT)["stages"][0]
    life = _run("life", MIXER, "--static", *SELECT, *lowered)["life"]
    assert life["standard"] == ns.TITLE
    pitting = life["stages"][0]["pinion"]["pitting"]
    assert pitting["curve"] == "nominal pitting Basquin line (test)"
    k = math.log(5e7 / 1e5) / math.log(1.6)
    duty = {"charging": (3000, 600), "mixing": (12000, 600), "discharging": (1500, 450)}  # hours, input rpm
    damage = 0.0
    for b in pitting["bins"]:
        sigma = _contact_stress(st, b["force_N"])
        hours, rpm = duty[b["point"]]
        n = hours * 60.0 * rpm  # the pinion turns at the input speed, one mate
        y = sigma / 1000.0
        assert_allclose([b["stress_MPa"], b["cycles"]], [sigma, n], rtol=1e-12)
        if y < 1.0:
            assert b["cycles_to_failure"] is None and b["damage"] == 0.0
            continue
        damage += n / (1e5 * (1.6 / y) ** k)
    assert damage > 1.0  # the lowered limit puts the duty well into finite life
    assert_allclose(pitting["damage"], damage, rtol=1e-10)  # power law by hand against the curve's segments
    assert_allclose(pitting["life_h"], 16500.0 / damage, rtol=1e-10)


def test_the_facade_rates_a_run_at_its_simulated_dynamic_factor_by_the_selected_standard():
    doc = _run("simulate", MIXER, *SELECT, "--set", "rating.dynamic_factor=simulated",
               "--set", "simulation.duration_s=0.3", "--set", "simulation.steps=600")
    design = _run("design", MIXER, *SELECT)["stages"]
    for st, sd in zip(design, doc["summary"]["stages"], strict=True):
        r = sd["rating"]
        assert r["standard"] == ns.TITLE and r["K_v_source"] == "simulated"
        assert_allclose(r["K_v"], max(1.0, sd["dynamic_factor"]), rtol=1e-12)
        assert_allclose(r["pinion"]["sigma_H_MPa"],
                        _contact_stress(st, abs(st["static_force_N"]["tangential"]), r["K_v"]), rtol=1e-12)


@pytest.mark.parametrize("standard", ["iso6336", "nominal_stress"])
def test_report_reads_the_safeties_of_either_standard(standard):
    doc = _run("report", MIXER, "--quick", "--set", f"rating.standard={standard}",
               "--set", "simulation.duration_s=0.3", "--set", "simulation.steps=600")
    design = _run("design", MIXER, "--set", f"rating.standard={standard}")["stages"]
    rows = doc["rating"]
    for st, row in zip(design, rows, strict=True):
        least = min(st["rating"][m]["S_H"] for m in ("pinion", "gear"))
        assert_allclose(row["min_S_H_iso"], least, rtol=1e-12)
