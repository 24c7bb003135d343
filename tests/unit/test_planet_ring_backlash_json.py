"""A planetary stage's design JSON gives its planet–ring mesh the stage's ``backlash_mm`` (DESIGN §11: each mesh
with the keys of a parallel stage), the gap the model applies to that mesh as to the sun–planet one; it had none."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("backlash_mm", [0.0, 0.25])
def test_both_planet_meshes_carry_the_stage_backlash(backlash_mm):
    res = CliRunner().invoke(cli, ["design", str(ROOT / "configs" / "planetary_stage.toml"), "--format", "json",
                                   "--set", f"stage.0.backlash_mm={backlash_mm}"])
    assert res.exit_code == 0, res.output
    stage = next(s for s in json.loads(res.stdout)["stages"] if s.get("type") == "planetary")
    assert {m["name"]: m["backlash_mm"] for m in stage["meshes"]} == {"sun_planet": backlash_mm,
                                                                     "planet_ring": backlash_mm}
