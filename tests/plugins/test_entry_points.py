"""Plug-ins installed as a package installs them (docs/plugins.md): an entry point of the group ``gearcli.plugins``
in a ``*.dist-info`` on the path, loaded by the CLI when a file names what no loaded code registered. The plug-in
(``plug_extras.py``, written from docs/plugins.md) gives a rating standard (ISO 6336 with raised minimum safeties)
and a stage kind (an ideal fixed ratio with a torsional stiffness); every figure is checked against ISO's own
rating of the same file or a closed form written out here. A plug-in that fails to load, raises or returns what
its protocol does not allow is a plain message naming it, never a traceback."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import plug_extras as px
import pytest
import tomli_w
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli
from gearcli.core import plugins
from gearcli.rating import register as register_standard
from gearcli.rating.registry import withdraw as withdraw_standard

ROOT = Path(__file__).resolve().parents[2]
RATED = str(ROOT / "configs" / "industrial_two_stage_rated.toml")
MIXER = str(ROOT / "configs" / "mixer_duty.toml")
PLANETARY = str(ROOT / "configs" / "planetary_duty.toml")
MARINE = ("--set", f"rating.standard={px.MARINE}")
I, K, J_IN, J_OUT, T_OUT, N_IN = 4.0, 2.0e5, 0.02, 0.5, 1340.0, 1450.0  # -, N m/rad, kg m², kg m², N m, rpm
FIXED = {"type": px.KIND, "ratio": I, "stiffness_Nm_rad": K, "damping_Nms_rad": 5.0,
         "input_inertia_kg_m2": J_IN, "output_inertia_kg_m2": J_OUT}
ONLY_FIXED = {"title": "a fixed ratio alone", "stage": [FIXED], "input": {"speed_rpm": N_IN, "ramp_s": 0.1},
              "load": {"torque_Nm": T_OUT, "ramp_s": 0.1},
              "simulation": {"duration_s": 0.4, "steps": 2000, "rtol": 1e-7}}


def _install(site: Path, entries: dict[str, str]) -> None:
    """What ``pip install`` leaves for the plug-in's package: its metadata and its entry points."""
    info = site / "gearcli_test_extras-0.1.dist-info"
    info.mkdir(parents=True)
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: gearcli-test-extras\nVersion: 0.1\n")
    lines = "".join(f"{k} = {v}\n" for k, v in entries.items())
    (info / "entry_points.txt").write_text(f"[{plugins.GROUP}]\n{lines}")


@pytest.fixture
def installed(tmp_path, monkeypatch):
    """The plug-in installed (its module is on the path already: tests/plugins), and a broken one beside it."""
    _install(tmp_path / "site", {"extras": "plug_extras:register", "broken": "plug_no_such_module"})
    monkeypatch.syspath_prepend(str(tmp_path / "site"))
    plugins.reset()
    yield tmp_path
    px.withdraw()
    plugins.reset()


def _invoke(*args: str):
    return CliRunner().invoke(cli, list(args))


def _json(*args: str) -> dict:
    r = _invoke(*args, "--format", "json", "-q")
    assert r.exit_code == 0, r.output
    return json.loads(r.stdout)


def _write(tmp_path: Path, doc: dict, name: str = "fixed.toml") -> str:
    path = tmp_path / name
    path.write_text(tomli_w.dumps(doc), encoding="utf-8")
    return str(path)


# ------------------------------------------------------------------------------------------------ discovery
def test_a_file_naming_only_built_in_names_never_scans_the_installed_packages():
    plugins.reset()
    _json("design", RATED)
    assert plugins._failures is None  # start-up time: the entry points are read only for an unknown name


def test_schema_has_the_plug_in_s_tables_and_warns_of_one_that_failed_to_load(installed):
    """``gearcli schema`` loads the plug-ins first (docs/plugins.md): the installed kind's table is in it, and the
    broken plug-in beside it, whose tables cannot be, is a warning naming it (exit 0: the schema is still whole)."""
    r = _invoke("schema")
    assert r.exit_code == 0, r.output
    assert f'"{px.KIND}"' in r.stdout
    assert "warning: plug-in 'broken' (plug_no_such_module) failed to load: ModuleNotFoundError" in r.stderr
    assert "the schema has none of its stage tables" in r.stderr and "Traceback" not in r.output
    assert _invoke("-q", "schema").stderr == ""


def test_a_plug_in_standard_loads_from_its_entry_point_and_rates_by_iso_at_its_minima(installed):
    """The plug-in is ISO 6336 with S_Hmin >= 1.4, S_Fmin >= 1.8: every safety is ISO's (the same formulas on the
    same file) and the permissible stresses are ISO 6336-2/-3's sigma_HP = sigma_HG / S_Hmin, sigma_FP =
    sigma_FG / S_Fmin at the raised minima (the file asks 1.25 and 1.5)."""
    iso = _json("design", RATED)["stages"]
    marine = _json("design", RATED, *MARINE)["stages"]
    for a, b in zip(iso, marine, strict=True):
        assert b["rating"]["standard"] == px.TITLE
        assert b["rating"].keys() == a["rating"].keys()  # the plug-in's rating keeps ISO's JSON keys
        for m in ("pinion", "gear"):
            ra, rb = a["rating"][m], b["rating"][m]
            assert_allclose([rb["S_H"], rb["S_F"]], [ra["S_H"], ra["S_F"]], rtol=1e-13)  # the same arithmetic
            assert_allclose([rb["sigma_HP_MPa"], rb["sigma_FP_MPa"]],
                            [ra["sigma_HG_MPa"] / 1.4, ra["sigma_FG_MPa"] / 1.8], rtol=1e-13)
            assert_allclose(ra["sigma_HP_MPa"], ra["sigma_HG_MPa"] / 1.25, rtol=1e-13)  # ISO at the file's 1.25
    table = _invoke("design", RATED, *MARINE, "--format", "table", "-q").stdout
    assert f"strength rating, {px.TITLE}" in table


def test_a_planetary_stage_s_planet_ring_mesh_is_rated_by_the_plug_in_too(installed):
    """Both meshes of a planetary stage carry the standard's title and its permissible stresses (S_Hmin 1.4 over
    the file's 1.0), the ring's safeties ISO's."""
    iso = _json("design", PLANETARY)["stages"][0]["meshes"][1]["rating"]
    sun, ring = (m["rating"] for m in _json("design", PLANETARY, *MARINE)["stages"][0]["meshes"])
    assert sun["standard"] == ring["standard"] == px.TITLE
    for m in ("pinion", "gear"):
        assert_allclose(ring[m]["S_H"], iso[m]["S_H"], rtol=1e-13)
        assert_allclose(ring[m]["sigma_HP_MPa"], iso[m]["sigma_HG_MPa"] / 1.4, rtol=1e-13)


def test_the_plug_in_standard_warns_at_its_own_minimum(installed):
    """At 2400 N m out the stage 1 pinion's S_H is about 1.38: above the file's 1.25 (ISO: no warning), below the
    plug-in's 1.4 (a warning naming stage, member and mode)."""
    more = ("--set", "load.torque_Nm=2400")
    iso = _invoke("design", RATED, *more, "--format", "json")
    marine = _invoke("design", RATED, *more, *MARINE, "--format", "json")
    s_h = json.loads(marine.stdout)["stages"][0]["rating"]["pinion"]["S_H"]
    assert 1.25 < s_h < 1.4
    assert "pitting (flank) safety" not in iso.stderr
    assert "stage 1 pinion (z = 19): pitting (flank) safety" in marine.stderr and "minimum 1.4" in marine.stderr


def test_life_and_the_simulated_rating_use_the_plug_in_standard(installed):
    """Life sums damage on the standard's S–N curves and its load classes re-rated by its optional
    ``rate_at_force`` (ISO's here: sigma_HG / Z_NT and the class stresses do not depend on S_Hmin, so the damage
    is ISO's to the last digits; without ``rate_at_force`` the classes' stresses would be scaled, 4e-7 off on
    stage 3) under the standard's title; the simulated-K_v rating of a run is the plug-in's too."""
    iso = _json("life", MIXER)["life"]
    marine = _json("life", MIXER, *MARINE)["life"]
    assert marine["standard"] == px.TITLE
    for a, b in zip(iso["stages"], marine["stages"], strict=True):
        for m in ("pinion", "gear"):
            for mode in ("pitting", "bending"):
                assert_allclose(b[m][mode]["damage"], a[m][mode]["damage"], rtol=1e-12)
    run = _json("simulate", RATED, *MARINE, "--set", "rating.dynamic_factor=simulated",
                "--set", "simulation.duration_s=0.3")
    r = run["summary"]["stages"][0]["rating"]
    assert r["standard"] == px.TITLE and r["K_v_source"] == "simulated"
    assert_allclose(r["pinion"]["sigma_HP_MPa"], r["pinion"]["sigma_HG_MPa"] / 1.4, rtol=1e-13)


def test_a_plug_in_stage_kind_loads_from_its_entry_point(installed, tmp_path):
    """One ideal fixed ratio i = 4, T_out = 1340 N m: by hand T_in = T_out / i = 335 N m, n_out = 1450 / 4 rpm,
    the static twist T_in / k rad. Modes: the input held (a speed drive), one mode omega² = k i² / J_out; the
    input free, omega² = k (1/J_in + i²/J_out) (J_out seen from the input is J_out / i²)."""
    path = _write(tmp_path, ONLY_FIXED)
    (st,) = _json("design", path)["stages"]
    assert st["type"] == px.KIND and st["rated"] is False
    assert_allclose([st["input_torque_Nm"], st["output_speed_rpm"], st["static_twist_deg"]],
                    [T_OUT / I, N_IN / I, math.degrees(T_OUT / I / K)], rtol=1e-13)
    modes = _json("modes", path)["boundaries"]
    (held,) = [m for m in modes["clamped_input"] if not m["rigid"]]
    assert_allclose(held["frequency_Hz"], math.sqrt(K * I**2 / J_OUT) / (2 * math.pi), rtol=1e-9)
    (free,) = [m for m in modes["free"] if not m["rigid"]]
    assert_allclose(free["frequency_Hz"], math.sqrt(K * (1 / J_IN + I**2 / J_OUT)) / (2 * math.pi), rtol=1e-9)
    run = _json("simulate", path)["summary"]["stages"][0]
    assert run["type"] == px.KIND
    assert_allclose(run["static_input_torque_Nm"], T_OUT / I, rtol=1e-12)
    assert_allclose(run["input_torque_Nm"]["mean"], T_OUT / I, rtol=1e-3)  # the window's mean: the static torque


def test_an_unknown_name_lists_the_plug_ins_and_says_which_failed_to_load(installed, tmp_path):
    r = _invoke("design", RATED, "--set", "rating.standard=agma2101")
    assert r.exit_code == 2 and "Traceback" not in r.output
    assert "rating.standard" in r.output and f'"{px.MARINE}"' in r.output and '"iso6336"' in r.output
    assert "plug-in 'broken' (plug_no_such_module) failed to load: ModuleNotFoundError" in r.output
    path = _write(tmp_path, {**ONLY_FIXED, "stage": [{**FIXED, "type": "bevel"}]})
    r = _invoke("design", path)
    assert r.exit_code == 2 and "fixed.toml: stage[0].type:" in r.output
    assert f'"{px.KIND}"' in r.output and '"planetary"' in r.output


def test_a_plug_in_that_fails_to_load_is_named_where_its_name_is_asked(tmp_path, monkeypatch):
    _install(tmp_path / "site", {"broken": "plug_no_such_module"})
    monkeypatch.syspath_prepend(str(tmp_path / "site"))
    plugins.reset()
    try:
        r = _invoke("design", _write(tmp_path, ONLY_FIXED))
    finally:
        plugins.reset()
    assert r.exit_code == 2 and "Traceback" not in r.output
    assert (f'fixed.toml: stage[0].type: unknown stage type "{px.KIND}"; registered: "parallel", "planetary"; '
            "plug-in 'broken' (plug_no_such_module) failed to load: ModuleNotFoundError") in r.output


def test_a_fresh_process_finds_the_installed_plug_in(installed, tmp_path):
    """The console script as a user runs it: nothing imported by a test, only the installed entry point."""
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(tmp_path / "site"), str(Path(__file__).parent),
                                                          str(ROOT)])}
    out = subprocess.run([sys.executable, "-m", "gearcli", "design", RATED, *MARINE, "--format", "json", "-q"],
                         capture_output=True, text=True, env=env, timeout=120)
    assert out.returncode == 0, out.stderr
    assert json.loads(out.stdout)["stages"][0]["rating"]["standard"] == px.TITLE


# ------------------------------------------------------------------------------------------------ the guard
MESSAGES = {
    "raises": "raised ZeroDivisionError: float division by zero",
    "nan": "returned stage 1's rating: pinion.safety('pitting') = nan: a number ≥ 0 was expected",
    "untitled": "returned stage 1's rating titled 'ISO 6336:2006 method B': its standard must be the standard's title",
    "dict": "returned stage 1's rating as dict: a rated mesh is a dataclass",
    "short": "returned 1 stages for 2",
    "warning_text": "returned the warning 'a plain string', not a gearcli.diagnostics.Diagnostic",
    "ring_untitled": "returned stage 1's planet–ring rating titled 'ISO 6336:2006 method B'",
}


@pytest.mark.parametrize("how", px.MISBEHAVING)
def test_a_standard_that_raises_or_breaks_its_protocol_is_named_not_a_traceback(how):
    std = px._Misbehaving(how)
    register_standard(std)
    try:
        r = _invoke("design", PLANETARY if how == "ring_untitled" else RATED, "--set", f"rating.standard={std.name}")
    finally:
        withdraw_standard(std.name)
    assert r.exit_code == 1, r.output
    assert "Traceback" not in r.output and "internal error" not in r.output
    assert f'rating standard "{std.name}" (plug_extras): rate_design {MESSAGES[how]}' in r.output


class _Raising(px.FixedRatioDesign):
    def result(self, cfg, pairs, k, kin, mesh):
        raise ValueError("the ratio table has no row for 4")


@pytest.fixture
def raising_kind():
    px.register()
    px.kinds.withdraw(px.KIND, "design")  # another module's facet replaces the plug-in's only once it is withdrawn
    px.kinds.provide(px.KIND, "design", _Raising())
    yield
    px.withdraw()


def test_a_stage_kind_that_raises_is_named_not_a_traceback(raising_kind, tmp_path):
    r = _invoke("design", _write(tmp_path, ONLY_FIXED))
    assert r.exit_code == 1 and "Traceback" not in r.output and "internal error" not in r.output
    assert (f'stage type "{px.KIND}" (test_entry_points): its design facet\'s result raised ValueError: the ratio '
            "table has no row for 4") in r.output


def test_debug_shows_where_in_the_plug_in_it_raised(raising_kind, tmp_path):
    """docs/plugins.md: `--debug` shows the traceback of a plug-in's bug (its own frame), then the same line."""
    r = _invoke("design", _write(tmp_path, ONLY_FIXED), "--debug")
    assert r.exit_code == 1
    assert "Traceback" in r.stderr and 'raise ValueError("the ratio table has no row for 4")' in r.stderr
    assert r.stderr.splitlines()[-1] == (f'gearcli: stage type "{px.KIND}" (test_entry_points): its design facet\'s '
                                         "result raised ValueError: the ratio table has no row for 4")


def test_a_stage_kind_without_a_facet_a_command_needs_is_named(tmp_path):
    px.register()
    px.kinds.withdraw(px.KIND, "model")
    try:
        r = _invoke("simulate", _write(tmp_path, ONLY_FIXED))
    finally:
        px.withdraw()
    assert r.exit_code == 1 and "Traceback" not in r.output and "internal error" not in r.output
    assert f'stage type "{px.KIND}" has no model facet registered (the stage types with one: "parallel", ' in r.output


def test_a_plug_in_element_runs_on_the_python_engine_with_the_closed_form_modes(installed, tmp_path):
    """The stage placing the plug-in's own element (the spring's law under its name, not compiled): the same
    closed-form modes as above, and a run whose engine choice says the compiled kernel does not know the element
    (``auto`` falls back to Python, the kernel and its cache untouched)."""
    path = _write(tmp_path, {**ONLY_FIXED, "stage": [{**FIXED, "law": "test_plugin_spring"}]})
    modes = _json("modes", path)
    assert modes["elements"] == ["stage 1 fixed ratio"]
    (held,) = [m for m in modes["boundaries"]["clamped_input"] if not m["rigid"]]
    assert_allclose(held["frequency_Hz"], math.sqrt(K * I**2 / J_OUT) / (2 * math.pi), rtol=1e-9)
    run = _json("simulate", path)
    assert run["solver"]["engine"] == "python"
    assert "connector kinds" in run["solver"]["engine_reason"]
    assert_allclose(run["summary"]["stages"][0]["input_torque_Nm"]["mean"], T_OUT / I, rtol=1e-3)


def test_the_report_names_the_plug_in_standard_s_k_v_as_the_design_s(installed, tmp_path):
    """`gearcli report` sets the design's K_v beside the simulated one: ISO 6336-1's under ISO 6336, the
    plug-in standard's own (its title, "K_v design") under a plug-in."""
    out = tmp_path / "report.md"
    r = _invoke("report", RATED, *MARINE, "--set", "simulation.duration_s=0.3", "-q", "-o", str(out))
    assert r.exit_code == 0, r.output
    text = out.read_text(encoding="utf-8")
    assert f"## Dynamic factor: {px.TITLE} against the simulation" in text and "| K_v design |" in text
    assert "K_v ISO" not in text


def test_set_reaches_into_a_plug_in_stage_s_table(installed, tmp_path):
    """``--set stage.0.ratio=2`` walks into the plug-in's table (its kind loaded before the overrides apply, in the
    main process and in a sweep's workers): T_in = T_out / i = 670 N m. On a stage whose type no kind registered
    the message names the type and the registered kinds (not "a value, not a table")."""
    path = _write(tmp_path, ONLY_FIXED)
    (st,) = _json("design", path, "--set", "stage.0.ratio=2")["stages"]
    assert_allclose(st["input_torque_Nm"], T_OUT / 2.0, rtol=1e-13)
    r = _invoke("sweep", path, "--vary", "stage.0.ratio=2,4", "--jobs", "2", "-q", "--format", "json")
    assert r.exit_code == 0, r.output
    rows = json.loads(r.stdout)["rows"] if r.stdout.lstrip().startswith("{") else json.loads(r.stdout)
    assert [row["status"] for row in rows] == ["ok", "ok"]
    bevel = _write(tmp_path, {**ONLY_FIXED, "stage": [{**FIXED, "type": "bevel"}]}, "bevel.toml")
    r = _invoke("design", bevel, "--set", "stage.0.ratio=2")
    assert r.exit_code == 2 and "Traceback" not in r.output
    assert ('--set: stage.0.ratio: stage[0] is of type "bevel", which no stage kind registered (registered: '
            '"parallel", "planetary", "test_fixed_ratio"') in r.output
