"""A planetary stage that cannot be assembled, an impossible planetary input, and what every command reports of a
planetary stage (issues 30 item 3, 31 and 32 item 4): each a regression test that failed before.

Hand numbers: the mixer's planetary (configs/mixer_planetary_motor.toml) is sun 18, planets 45, ring 108, m_n 3 mm,
spur, zero profile shifts: a = (18 + 45) 3/2 = 94.5 mm, the planet's tip d_a = (45 + 2) 3 = 141 mm, and planets
assemble at whole multiples of 360/(18 + 108) = 2.857142...° from planet 1.
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]
MIXER = str(ROOT / "configs" / "mixer_planetary_motor.toml")
STAGE = str(ROOT / "configs" / "planetary_stage.toml")
PARALLEL_RATED = str(ROOT / "configs" / "industrial_two_stage_rated.toml")


def run(*args, env=None):
    return CliRunner(env=env).invoke(cli, list(args), catch_exceptions=False)


def sets(*items):
    return sum((["--set", s] for s in items), [])


# ------------------------------------------------------------------------------------------------ assembly
def test_sun_19_with_ring_108_and_3_planets_is_exit_2_naming_the_spacing():
    res = run("design", MIXER, *sets("stage.0.sun.teeth=19"))
    assert res.exit_code == 2
    assert "planet spacing" in res.stderr and "(19 + 108)/3" in res.stderr and "42.33" in res.stderr
    assert "stage[0].planet.count" in res.stderr and "Traceback" not in res.stderr


def test_a_minus_2_mm_concentricity_error_is_exit_2():
    """The ring profile shift that puts the planet–ring working centre distance 2 mm inside the sun–planet one
    (94.5 mm): cos a_wt = (z_r - z_p) m cos a / (2 a_w), inv a_wt = inv a + 2 tan a (x_p + x_r)/(z_p - z_r)."""
    alpha = math.radians(20)
    a_w = 94.5 - 2.0
    a_wt = math.acos((108 - 45) * 3 * math.cos(alpha) / (2 * a_w))
    inv = math.tan(a_wt) - a_wt
    x_r = (inv - (math.tan(alpha) - alpha)) * (45 - 108) / (2 * math.tan(alpha))
    res = run("design", MIXER, *sets(f"stage.0.ring.profile_shift={x_r!r}"))
    assert res.exit_code == 2, res.stderr
    assert "concentricity" in res.stderr and "-2.0000 mm" in res.stderr and "94.5000" in res.stderr
    assert "stage[0].ring.profile_shift" in res.stderr


def test_six_planets_whose_tips_overlap_is_exit_2_naming_the_adjacency():
    """126/6 = 21 spaces them equally, but 2 a sin(30°) = 94.5 mm < d_a = 141 mm: overlap 46.5 mm."""
    res = run("design", MIXER, *sets("stage.0.planet.count=6"))
    assert res.exit_code == 2
    assert "adjacency" in res.stderr and "94.5000 mm" in res.stderr and "141.0000 mm" in res.stderr
    assert "46.5" in res.stderr


def test_declared_unequal_spacing_assembles_and_phases_the_model():
    step = 360 / 126
    angles = [0.0, 40 * step, 84 * step]  # 114.2857...°, 240°: whole multiples of the step
    spec = f"stage.0.planet.angles_deg=[{', '.join(repr(a) for a in angles)}]"
    res = run("design", MIXER, "--format", "json", *sets(spec))
    assert res.exit_code == 0, res.stderr
    st = json.loads(res.stdout)["stages"][0]
    assert_allclose(st["planet_angles_deg"], angles, rtol=1e-12)
    from gearcli import api

    loaded = api.load(MIXER, [spec])
    design = api.design(loaded)
    p = api.model_spec(loaded.design, design).stage_models[0]
    # planet 2's sun mesh leads planet 1's by z_s psi/360 = 18 x 114.2857/360 = 5.714 cycles; its ring mesh by
    # -z_r psi/360 = -34.286 cycles (Parker & Lin's phasing, from the declared angle)
    assert_allclose(p.mesh_phase_cycles(1, "sun"), 18 * angles[1] / 360, rtol=1e-12)
    assert_allclose(p.mesh_phase_cycles(2, "ring"), -108 * angles[2] / 360, rtol=1e-12)


@pytest.mark.parametrize(("angles", "words"), [
    ("[0, 120.5, 240]", "whole multiples of 360/(z_s + z_r)"),
    ("[0, 120]", "one angle per planet (3), got 2"),
    ("[0, 0, 240]", "same position"),
])
def test_a_bad_planet_angle_is_exit_2_naming_the_key(angles, words):
    res = run("design", MIXER, *sets(f"stage.0.planet.angles_deg={angles}"))
    assert res.exit_code == 2
    assert words in res.stderr and "stage[0].planet.angles_deg" in res.stderr


def test_existing_planetary_configs_assemble():
    for name in ("planetary_stage.toml", "planetary_duty.toml", "wind_turbine_gearbox.toml",
                 "mixer_planetary_motor.toml"):
        res = run("design", str(ROOT / "configs" / name), "--format", "json")
        assert res.exit_code == 0, (name, res.stderr)


# ---------------------------------------------------------------------------------------- impossible inputs
def test_a_helical_ring_needs_the_planets_hand():
    helical = ("stage.0.helix_angle_deg=10", "stage.0.sun.hand=left", "stage.0.planet.hand=right")
    res = run("design", MIXER, *sets(*helical, "stage.0.ring.hand=left"))
    assert res.exit_code == 2
    assert "stage[0].ring.hand" in res.stderr and '"right"' in res.stderr
    ok = run("design", MIXER, "--format", "json", *sets(*helical, "stage.0.ring.hand=right"))
    assert ok.exit_code == 0, ok.stderr
    assert json.loads(ok.stdout)["stages"][0]["ring"]["hand"] == "right"


def test_load_sharing_factor_without_a_planetary_stage_is_refused():
    res = run("design", PARALLEL_RATED, *sets("rating.load_sharing_factor=1.1"))
    assert res.exit_code == 2
    assert "rating.load_sharing_factor" in res.stderr and "no planetary stage" in res.stderr


def test_planet_pin_bearings_far_from_the_planet_warn(tmp_path):
    text = Path(MIXER).read_text().replace("planet_stage = 1\nposition_mm = 180", "planet_stage = 1\nposition_mm = 100000")
    path = tmp_path / "far.toml"
    path.write_text(text)
    res = run("design", str(path), "--format", "json")
    assert res.exit_code == 0, res.stderr
    warnings = json.loads(res.stdout)["warnings"]
    far = [w for w in warnings if w.get("check") == "bearing_position"]
    # the seventh [[bearing]] of the file, numbered from 1 as every warning's ``bearing`` and channel is
    assert len(far) == 1 and far[0]["bearing"] == 7 and far[0]["distance_mm"] == pytest.approx(99800.0)
    assert far[0]["message"].startswith("bearing 7: ") and "bearing[6].position_mm" in far[0]["message"]


def test_pin_bearings_without_the_planets_axial_position_name_the_planet_key(tmp_path):
    text = Path(MIXER).read_text().replace(", bore_diameter_mm = 60, axial_position_mm = 200,", ", bore_diameter_mm = 60,")
    path = tmp_path / "noaxial.toml"
    path.write_text(text)
    res = run("design", str(path))
    assert res.exit_code == 2
    assert "stage[0].planet.axial_position_mm" in res.stderr and "planet pins of stage 1" in res.stderr
    assert "shaft 1" not in res.stderr


def test_a_carrier_held_stage_writes_no_negative_zero():
    held = sets("stage.0.fixed=carrier", "stage.0.input=sun")
    for fmt in ("json", "csv"):
        res = run("design", STAGE, "--format", fmt, *held)
        assert res.exit_code == 0, res.stderr
        assert not re.search(r"(?<![\w.])-0(\.0+)?(?![\w.])", res.stdout), fmt
    res = run("simulate", STAGE, "--format", "table", *held, *sets("simulation.duration_s=0.2"))
    assert res.exit_code == 0, res.stderr
    assert not re.search(r"(?<![\w.])-0(?![\w.])", res.stdout)


# ------------------------------------------------------------------------------------------------ outputs
def test_periodic_steady_state_of_an_unexcited_planetary_is_no_fold(tmp_path):
    """The two unit multipliers of the closed planet loops (6 mesh deflections over 4 free bodies) are
    structural: left out, the equilibrium is judged stable, no bifurcation."""
    out = tmp_path / "p.json"
    res = run("simulate", STAGE, "--format", "json", "-o", str(out), *sets("simulation.steady=periodic"))
    assert res.exit_code == 0, res.stderr
    steady = json.loads(out.read_text())["summary"]["steady"]
    assert steady["bifurcation"] == "none" and steady["stable"] is True
    assert "fold" not in res.stderr
    assert all(abs(complex(*m) - 1) > 0.1 for m in steady["multipliers"])
    assert "2 multiplier(s) exactly 1 by construction" in steady["note"]


def test_narrow_terminal_keeps_the_planet_table_numbers_whole():
    res = run("simulate", STAGE, "--format", "table", env={"COLUMNS": "60"})
    assert res.exit_code == 0, res.stderr
    table = res.stdout[res.stdout.index("planets over the steady window"):]
    table = table[:table.index("dynamic ratio")]
    assert not re.search(r"\de\s*│", table) and not re.search(r"│\s*\+\d", table)  # no '-7.7946e' / '+05' split
    assert re.search(r"-7\.79\d*e\+05", table)


def test_report_quick_minimum_safeties_count_the_planet_ring_mesh(tmp_path):
    out = tmp_path / "r.json"
    res = run("report", STAGE, "--quick", "--format", "json", "-o", str(out))
    assert res.exit_code == 0, res.stderr
    doc = json.loads(out.read_text())
    design = run("design", STAGE, "--format", "json")
    st = json.loads(design.stdout)["stages"][0]
    ratings = [m["rating"] for m in st["meshes"]]
    row = doc["rating"][0]
    assert_allclose(row["min_S_H_iso"], min(r[m]["S_H"] for r in ratings for m in ("pinion", "gear")), rtol=1e-12)
    assert_allclose(row["min_S_F_iso"], min(r[m]["S_F"] for r in ratings for m in ("pinion", "gear")), rtol=1e-12)
    assert row["min_S_H_iso"] < 0.9  # the ring's 0.861, not the sun mesh's 1.374


def test_simulated_dynamic_factor_rates_the_planet_ring_mesh_too(tmp_path):
    out = tmp_path / "s.json"
    res = run("simulate", STAGE, "--format", "json", "-o", str(out), *sets("rating.dynamic_factor=simulated"))
    assert res.exit_code == 0, res.stderr
    st = json.loads(out.read_text())["summary"]["stages"][0]
    ring = st["planet_ring_rating"]
    assert ring["K_v_source"] == "simulated"
    static = abs(st["static_tangential_N"])  # lossless stage: the ring mesh's static force equals the sun mesh's
    peak = max(max(abs(p["ring"]["tangential_N"]["max"]), abs(p["ring"]["tangential_N"]["min"])) for p in st["planets"])
    assert_allclose(ring["K_v"], max(1.0, peak / static), rtol=1e-9)
    assert "planet–ring mesh strength rating at the simulated K_v" in run(
        "simulate", STAGE, "--format", "table", *sets("rating.dynamic_factor=simulated")).stdout


def test_design_table_shows_the_members_and_labels_per_planet_values():
    res = run("design", MIXER, "--format", "table", env={"COLUMNS": "200"})
    assert res.exit_code == 0, res.stderr
    out = res.stdout
    for label in ("sun: speed [rpm] / torque [N·m] / power [kW]", "carrier: speed [rpm] / torque [N·m] / power [kW]",
                  "ring: speed [rpm] / torque [N·m] / power [kW]", "moment balance T_sun + T_carrier + T_ring",
                  "per planet, carrier frame: sun-side / planet torque [N·m]",
                  "planet speed relative to the carrier [rpm]"):
        assert label in out
    # the planetary column's 'pinion' rows are empty: its members are in its own table
    pinion_torque = next(line for line in out.splitlines() if "pinion torque [N·m]" in line)
    assert "—" in pinion_torque
    only_planetary = run("design", STAGE, "--format", "table", env={"COLUMNS": "200"}).stdout
    assert "pinion torque" not in only_planetary


def test_a_stage_efficiency_no_mesh_efficiency_gives_is_exit_2():
    """Sun in, ring held: eta = (1 + eta_0 u)/(1 + u) >= 1/(1 + u) = 1/7 = 0.1429 whatever the meshes lose."""
    res = run("design", MIXER, *sets("stage.0.efficiency=0.12"))
    assert res.exit_code == 2
    assert "stage[0].efficiency" in res.stderr and "0.1429" in res.stderr
