"""The output contract on an engineer's own scenes (DESIGN §3, §5, §11): every key a parallel stage's JSON names is
on each mesh of a planetary stage too, in the contract's unit, with the value a hand calculation gives."""

from __future__ import annotations

import json
import math
import sys

import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

# a sun-driven planetary stage, ring held: 24/24/72, 4 planets ((24 + 72)/4 = 24, equally spaced), m_n 2, spur;
# the planets and the ring of one steel (E = 2.1e5 MPa, nu = 0.3)
PLANETARY = """
title = "planetary 24/24/72, 4 planets, ring held, sun in"
[materials.steel]
density_kg_m3 = 7850
youngs_modulus_MPa = 2.1e5
poisson_ratio = 0.3
[materials.soft]
density_kg_m3 = 7200
youngs_modulus_MPa = 1.7e5
poisson_ratio = 0.26
[[stage]]
type = "planetary"
normal_module_mm = 2
normal_pressure_angle_deg = 20
sun    = { teeth = 24, face_width_mm = 25, material = "steel" }
planet = { teeth = 24, face_width_mm = 25, count = 4, material = "steel" }
ring   = { teeth = 72, face_width_mm = 25, material = "soft" }
fixed = "ring"
input = "sun"
[input]
speed_rpm = 3000
[load]
torque_Nm = 400
"""

# DESIGN §5: the keys of a parallel stage that §11 gives each planetary mesh ("each with the keys of a parallel stage")
STAGE_KEYS = {"contact_ratio_transverse", "overlap_ratio", "contact_ratio_total", "center_distance_mm",
              "equivalent_radius_mm", "effective_modulus_MPa", "hertz_stiffness_N_mm1_5", "mesh_frequency_Hz",
              "static_force_N", "iso6336_single_pair_stiffness_N_mm_um", "iso6336_mesh_stiffness_N_mm_um",
              "iso6336_mesh_stiffness_beta_N_mm_um", "iso6336_factors", "reduced_mass_kg_mm", "resonance_speed_rpm",
              "resonance_ratio", "rating", "mesh_stiffness", "static_approach_mm", "linearised_stiffness_N_mm"}


def _e_star(e1: float, nu1: float, e2: float, nu2: float) -> float:
    """DESIGN §3: 1/E* = (1 − ν1²)/E1 + (1 − ν2²)/E2, MPa."""
    return 1.0 / ((1.0 - nu1 ** 2) / e1 + (1.0 - nu2 ** 2) / e2)


def _design(tmp_path, text: str, *args: str) -> dict:
    path = tmp_path / "scene.toml"
    path.write_text(text, encoding="utf-8")
    res = CliRunner().invoke(cli, ["-q", "design", str(path), *args])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def test_every_planetary_mesh_has_a_parallel_stages_keys_with_its_own_effective_modulus(tmp_path):
    doc = _design(tmp_path, PLANETARY, "--format", "json")
    meshes = doc["stages"][0]["meshes"]
    assert [m["name"] for m in meshes] == ["sun_planet", "planet_ring"]
    for mesh in meshes:
        assert STAGE_KEYS <= set(mesh), (mesh["name"], sorted(STAGE_KEYS - set(mesh)))
    sun_planet, planet_ring = meshes
    # steel on steel: 1/E* = 2 (1 − 0.09)/2.1e5 -> E* = 115 384.6 MPa; steel planet on the soft ring: its own E*
    assert_allclose(sun_planet["effective_modulus_MPa"], 2.1e5 / (2 * 0.91), rtol=1e-12)
    assert_allclose(planet_ring["effective_modulus_MPa"], _e_star(2.1e5, 0.3, 1.7e5, 0.26), rtol=1e-12)
    # and the Hertz value on it is §3's K = 4/3 √R E* (R = r_p r_r / (r_r − r_p) for the concave ring flank)
    r_p, r_r = 24.0, 72.0  # pitch radii, mm: z m / 2
    radius = r_p * r_r / (r_r - r_p)
    assert_allclose(planet_ring["equivalent_radius_mm"], radius, rtol=1e-12)
    assert_allclose(planet_ring["hertz_stiffness_N_mm1_5"],
                    4.0 / 3.0 * radius ** 0.5 * _e_star(2.1e5, 0.3, 1.7e5, 0.26), rtol=1e-12)
    # §3's h_0 and k_lin of the default law (iso6336, e = 1.5, DESIGN §13): its tangent e K h0^(e-1) is ISO's
    # k_n = c_γα b (spur: cos β_b = 1) at the static normal force, so h0 = e F_n / k_n; F_n per planet from the
    # sun's torque: 400 N·m on the carrier / (1 + 72/24) = 100 N·m, over 4 planets at r_s = 24 mm, / cos 20°
    f_n = 100e3 / 4 / 24.0 / math.cos(math.radians(20.0))
    k_n = planet_ring["iso6336_mesh_stiffness_N_mm_um"] * 1e3 * 25.0
    assert_allclose(planet_ring["linearised_stiffness_N_mm"], k_n, rtol=1e-9)
    assert_allclose(planet_ring["static_approach_mm"], 1.5 * f_n / k_n, rtol=1e-9)


def test_the_planet_ring_modulus_is_a_csv_column_too(tmp_path):
    path = tmp_path / "scene.toml"
    path.write_text(PLANETARY, encoding="utf-8")
    res = CliRunner().invoke(cli, ["-q", "design", str(path), "--format", "csv"])
    assert res.exit_code == 0, res.output
    head, row = res.stdout.splitlines()[:2]
    cells = dict(zip(head.split(","), row.split(","), strict=True))
    assert_allclose(float(cells["planet_ring_effective_modulus_MPa"]), _e_star(2.1e5, 0.3, 1.7e5, 0.26), rtol=1e-12)


# ------------------------------------------------------------------ simulate --dump-model: the file it names

SPUR = """
title = "spur pair 20/40, m 3"
[materials.steel]
density_kg_m3 = 7850
youngs_modulus_MPa = 2.1e5
poisson_ratio = 0.3
[[stage]]
normal_module_mm = 3
normal_pressure_angle_deg = 20
pinion = { teeth = 20, face_width_mm = 30, material = "steel" }
gear   = { teeth = 40, face_width_mm = 30, material = "steel" }
[input]
speed_rpm = 1500
ramp_s = 0.05
[load]
torque_Nm = 200
ramp_s = 0.05
"""


@pytest.mark.parametrize("name", ["run.csv", "run.json", "run.md", "run.toml"])
def test_dump_model_refuses_a_data_suffix_and_writes_nothing(tmp_path, name):
    """DESIGN §7: a suffix chooses the format and one that contradicts it is exit 2 naming the path: the equations
    are Python source, never CSV or JSON under that name (a pipeline reading run.csv would choke on them)."""
    path = tmp_path / "spur.toml"
    path.write_text(SPUR, encoding="utf-8")
    out = tmp_path / name
    res = CliRunner().invoke(cli, ["simulate", str(path), "--dump-model", "-o", str(out)])
    assert res.exit_code == 2, res.output
    assert res.stderr.startswith(f"gearcli: {out}: --dump-model writes the equations as Python source")
    assert "Traceback" not in res.stderr
    assert list(tmp_path.iterdir()) == [path]


@pytest.mark.parametrize("name", ["model.py", "model.txt", "model"])
def test_dump_model_writes_python_source_to_a_source_or_text_name(tmp_path, name):
    path = tmp_path / "spur.toml"
    path.write_text(SPUR, encoding="utf-8")
    out = tmp_path / name
    res = CliRunner().invoke(cli, ["simulate", str(path), "--dump-model", "-o", str(out)])
    assert res.exit_code == 0, res.output
    assert res.stdout == "" and res.stderr == ""
    source = out.read_text(encoding="utf-8")
    compile(source, str(out), "exec")  # it is Python
    assert "def rhs(t, y):" in source


def test_dump_model_warns_that_the_runs_output_options_have_no_effect(tmp_path):
    path = tmp_path / "spur.toml"
    path.write_text(SPUR, encoding="utf-8")
    res = CliRunner().invoke(cli, ["simulate", str(path), "--dump-model", "--format", "json", "--series"])
    assert res.exit_code == 0, res.output
    assert "def rhs(t, y):" in res.stdout and not res.stdout.lstrip().startswith("{")
    lines = res.stderr.splitlines()
    assert [line.split(" chooses")[0] for line in lines] == ["warning: --format", "warning: --series"]
    assert all(line.endswith("it has no effect") for line in lines)
    quiet = CliRunner().invoke(cli, ["-q", "simulate", str(path), "--dump-model", "--format", "json"])
    assert quiet.exit_code == 0 and quiet.stderr == ""


# ------------------------------------------------------------------ docs/output.md names every warning code

def test_output_md_lists_every_warning_code_the_tool_emits():
    """DESIGN §12: `code` is stable and a program switches on it, so the contract page's list of codes names every
    code gearcli can emit (the diagnostics' codes and the rating's and the bearings' own)."""
    import inspect
    from pathlib import Path

    from gearcli import diagnostics
    from gearcli.design import bearing_life, iso6336, rating

    codes = {v for k, v in vars(diagnostics).items() if k.isupper() and isinstance(v, str) and v.islower()
             and v.replace("_", "").isalpha() and not k.startswith("_")}
    codes |= {rating.PITTING_LOW, rating.BENDING_LOW, rating.OUT_OF_RANGE, rating.NOT_ISO, iso6336.UNRATED_MESH,
              bearing_life.STATIC_SAFETY_LOW, bearing_life.KAPPA_OUT_OF_RANGE, bearing_life.AXIAL_NOT_RATED}
    assert {"design", "stiffness_not_iso", "window_ringing", "pitting_safety_low"} <= codes  # the harvest works
    page = (Path(inspect.getfile(diagnostics)).resolve().parents[1] / "docs" / "output.md").read_text(encoding="utf-8")
    assert sorted(c for c in codes if f"`{c}`" not in page) == []


# ------------------------------------------------------------------ --plots without the plot extra

RATED_SPUR = SPUR.replace('poisson_ratio = 0.3\n', 'poisson_ratio = 0.3\ntreatment = "case_carburized"\n'
                          'contact_fatigue_limit_MPa = 1500\nbending_fatigue_limit_MPa = 450\n', 1).replace(
    'material = "steel" }', 'material = "steel", flank_roughness_Rz_um = 3, root_roughness_Rz_um = 10 }').replace(
    "[input]", "accuracy_grade = 6\n[input]", 1) + """
[lubricant]
viscosity_40C_mm2_s = 150
[rating]
required_life_h = 20000
[[duty]]
name = "full"
hours = 20000
torque_Nm = 200
speed_rpm = 1500
"""


@pytest.mark.parametrize("args", [("life", "--static"), ("modes",)])
def test_plots_without_matplotlib_warn_and_create_no_directory(tmp_path, monkeypatch, args):
    """docs/sweeps.md, docs/life.md: without the plot extra --plots is a warning and exit 0, the command's output
    whole; and nothing is left behind (life made the empty directory before it found matplotlib missing)."""
    path = tmp_path / "spur.toml"
    path.write_text(RATED_SPUR, encoding="utf-8")
    monkeypatch.setitem(sys.modules, "matplotlib", None)  # import matplotlib -> ImportError
    plots = tmp_path / "figures"
    res = CliRunner().invoke(cli, [args[0], str(path), *args[1:], "--format", "json", "--plots", str(plots)])
    assert res.exit_code == 0, res.output
    assert "--plots needs matplotlib" in res.stderr and "itself is complete" in res.stderr
    json.loads(res.stdout)  # the output is whole
    assert not plots.exists()


# ------------------------------------------------------------------ life --series: the history is an input

def test_life_series_input_sha256_covers_the_history(tmp_path):
    """DESIGN §5: every JSON carries `input_sha256`, the provenance of its inputs; `life --series` reads two, the
    design file and the history, and two different histories gave one hash for two different lives. It is now the
    sha256 of the file's bytes, then b"\\0--series " and the history's bytes (hashlib here, independently)."""
    import hashlib

    path = tmp_path / "spur.toml"
    path.write_text(RATED_SPUR, encoding="utf-8")
    docs, hashes = [], []
    for i, speed in enumerate((1500, 1000)):
        history = tmp_path / f"h{i}.csv"
        history.write_text(f"time_s,torque_Nm,speed_rpm\n0,200,{speed}\n3600,200,{speed}\n", encoding="utf-8")
        res = CliRunner().invoke(cli, ["-q", "life", str(path), "--series", str(history), "--static",
                                       "--format", "json"])
        assert res.exit_code == 0, res.output
        docs.append(json.loads(res.stdout))
        h = hashlib.sha256(path.read_bytes())
        h.update(b"\0--series " + history.read_bytes())
        hashes.append(h.hexdigest())
    assert [d["input_sha256"] for d in docs] == hashes
    assert hashes[0] != hashes[1]
    # without --series: the plain sha256sum of the design file, as before
    res = CliRunner().invoke(cli, ["-q", "life", str(path), "--static", "--format", "json"])
    assert json.loads(res.stdout)["input_sha256"] == hashlib.sha256(path.read_bytes()).hexdigest()
