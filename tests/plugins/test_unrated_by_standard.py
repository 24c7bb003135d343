"""A rating standard that leaves gear stages unrated (docs/plugins.md: a plug-in standard may rate some kinds only):
``gearcli design`` says which stage (or which planetary stage's planet–ring mesh) has no safeties, naming the
standard, as it says of a stage kind without a gear mesh; ``gearcli life`` (static and dynamic route) refuses it with
exit 2 naming ``rating.standard`` and the stage, not ISO's ring keys, not an "internal error". And the dynamic life
route on a planetary stage whose ring ISO 6336 cannot rate (no flank roughness) is exit 2 naming the key before any
point runs, as the static route is (it was an internal error: AssertionError in the planet–ring member's rating)."""

from __future__ import annotations

import json
import tomllib
from dataclasses import replace
from pathlib import Path

import pytest
import tomli_w
from click.testing import CliRunner

from gearcli.cli import cli
from gearcli.design.iso6336 import ISO6336
from gearcli.rating import register
from gearcli.rating.registry import withdraw

ROOT = Path(__file__).resolve().parents[2]
NONE, SUN_ONLY = "test_rates_nothing", "test_sun_planet_only"


class RatesNothing:
    """A standard that returns every stage as it was given (rating None)."""

    name, title = NONE, "rates nothing (a test plug-in)"

    def check_inputs(self, cfg):
        return None

    def rate_design(self, cfg, stages):
        return tuple(stages), []

    def rate_simulation(self, cfg, design, stages):
        return tuple(stages), []

    def sn_curve(self, cfg, member, treatment, mode, variant):  # never asked: nothing is rated
        raise AssertionError("no rating, no curve")

    def curve_name(self, mode):
        return mode

    def table_rows(self, ratings, *, shared):
        return []


class SunPlanetOnly(RatesNothing):
    """ISO 6336 retitled, its planet–ring ratings dropped (a standard of external gears only)."""

    name, title = SUN_ONLY, "ISO 6336, external meshes only (a test plug-in)"

    def rate_design(self, cfg, stages):
        rated, _ = ISO6336.rate_design(cfg, stages)
        out = []
        for st in rated:
            st = replace(st, rating=replace(st.rating, standard=self.title))
            if st.planetary is not None:
                st = replace(st, planetary=replace(st.planetary, planet_ring=replace(st.planetary.planet_ring,
                                                                                     rating=None)))
            out.append(st)
        return tuple(out), []


@pytest.fixture
def standards():
    register(RatesNothing())
    register(SunPlanetOnly())
    yield
    withdraw(NONE)
    withdraw(SUN_ONLY)


def _train(tmp_path: Path, *, ring_roughness: bool = True) -> str:
    """The rated two-stage reducer's first stage, then the planetary stage of configs/planetary_stage.toml scaled
    down (sun input, ring held), with a one-point duty."""
    doc = tomllib.loads((ROOT / "configs" / "industrial_two_stage_rated.toml").read_text(encoding="utf-8"))
    doc.pop("target")
    doc["materials"]["34CrNiMo6"] = {"density_kg_m3": 7830, "youngs_modulus_MPa": 206000, "poisson_ratio": 0.3,
                                     "treatment": "through_hardened", "contact_fatigue_limit_MPa": 700,
                                     "bending_fatigue_limit_MPa": 290}
    member = {"face_width_mm": 60, "material": "18CrNiMo7-6", "flank_roughness_Rz_um": 3, "root_roughness_Rz_um": 10}
    ring = {"teeth": 81, "face_width_mm": 60, "material": "34CrNiMo6", "root_roughness_Rz_um": 10,
            "rim_thickness_mm": 20, **({"flank_roughness_Rz_um": 6} if ring_roughness else {})}
    planetary = {"type": "planetary", "normal_module_mm": 4, "normal_pressure_angle_deg": 20, "accuracy_grade": 6,
                 "sun": {"teeth": 21, **member}, "planet": {"teeth": 30, "count": 3, **member}, "ring": ring,
                 "carrier": {"inertia_kg_m2": 2.0}, "fixed": "ring", "input": "sun"}
    doc["stage"] = [doc["stage"][0], planetary]
    doc["load"]["torque_Nm"] = 300.0
    doc["duty"] = [{"name": "rated", "hours": 20000, "torque_Nm": 300.0, "speed_rpm": 1450.0}]
    path = tmp_path / "train.toml"
    path.write_text(tomli_w.dumps(doc), encoding="utf-8")
    return str(path)


def _run(*args: str):
    return CliRunner().invoke(cli, [*args, "-q"])


def _not_rated(path: str, standard: str) -> list[dict]:
    r = _run("design", path, "--set", f"rating.standard={standard}", "--format", "json")
    assert r.exit_code == 0, r.output
    return [w for w in json.loads(r.stdout)["warnings"] if w.get("check") == "not_rated"]


def test_design_names_each_gear_stage_the_standard_left_unrated(standards, tmp_path):
    path = _train(tmp_path)
    said = _not_rated(path, NONE)
    assert [(w["stage"], w["type"], w["standard"], w.get("mesh")) for w in said] == [
        (1, "parallel", NONE, None), (2, "planetary", NONE, None)]
    assert all("no safeties" in w["message"] and f'"{NONE}"' in w["message"] for w in said)
    said = _not_rated(path, SUN_ONLY)  # the sun–planet mesh rated, the planet–ring mesh not
    assert [(w["stage"], w["mesh"], w["standard"]) for w in said] == [(2, "planet_ring", SUN_ONLY)]
    assert _not_rated(path, "iso6336") == []  # ISO rates every mesh of this train


def test_iso_s_own_unrated_ring_warning_is_not_said_twice(tmp_path):
    r = _run("design", _train(tmp_path, ring_roughness=False), "--format", "json")
    assert r.exit_code == 0, r.output
    codes = [(w["code"], w.get("check")) for w in json.loads(r.stdout)["warnings"] if w.get("stage") == 2]
    assert ("mesh_not_rated", None) in codes and ("design", "not_rated") not in codes


@pytest.mark.parametrize("route", [("--static",), ()], ids=["static", "dynamic"])
def test_life_refuses_a_stage_its_standard_left_unrated_naming_the_standard(standards, tmp_path, route):
    path = _train(tmp_path)
    r = _run("life", path, *route, "--set", f"rating.standard={NONE}")
    assert r.exit_code == 2 and "Traceback" not in r.output
    assert f"train.toml: rating.standard: stage 1: the rating standard \"{NONE}\" leaves this parallel stage" \
        in r.output
    r = _run("life", path, *route, "--set", f"rating.standard={SUN_ONLY}")
    assert r.exit_code == 2 and "Traceback" not in r.output
    assert "train.toml: rating.standard: stage 2:" in r.output and f'"{SUN_ONLY}" leaves it unrated' in r.output


@pytest.mark.parametrize("route", [("--static",), ()], ids=["static", "dynamic"])
def test_life_on_a_ring_iso_cannot_rate_names_the_key_on_both_routes(tmp_path, route):
    r = _run("life", _train(tmp_path, ring_roughness=False), *route)
    assert r.exit_code == 2 and "internal error" not in r.output and "Traceback" not in r.output
    assert "train.toml: stage[1].ring.flank_roughness_Rz_um: stage 2: gearcli life rates the planet–ring mesh" \
        in r.output
