"""A member softer than every ISO 6336 gear material is warned as outside the rating's scope.

ISO 6336-2's Z_E table lists the standard's gear materials: steel 206,000 N/mm², cast steel 202,000, nodular cast
iron 173,000, grey cast iron 118,000-126,000, tin bronze 113,000 and cast tin bronze 103,000. ISO 6336-5's strength
values are steels' and cast irons'. A polymer (POM, ~2,800 N/mm²) or an aluminium alloy (~70,000) is none of them,
and its safeties would be a steel's; grey cast iron and the steels stay quiet.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli.cli import cli

RATED = str(Path(__file__).resolve().parents[2] / "configs" / "industrial_two_stage_rated.toml")


def _scope_warnings(modulus_MPa: float) -> list[dict]:
    res = CliRunner().invoke(cli, ["design", RATED, "--format", "json",
                                   "--set", f"materials.18CrNiMo7-6.youngs_modulus_MPa={modulus_MPa}"])
    assert res.exit_code == 0, res.stderr
    return [w for w in json.loads(res.stdout)["warnings"]
            if w["code"] == "rating_out_of_range" and w.get("quantity") == "youngs_modulus_MPa"]


@pytest.mark.parametrize("modulus_MPa", [2_800.0, 70_000.0])  # POM, an aluminium alloy
def test_a_polymer_or_light_alloy_member_is_outside_the_rating(modulus_MPa):
    found = _scope_warnings(modulus_MPa)
    # two stages, pinion and gear each
    assert sorted((w["stage"], w["member"]) for w in found) == [(1, "gear"), (1, "pinion"), (2, "gear"), (2, "pinion")]
    assert all(w["value"] == modulus_MPa and f"{modulus_MPa:,.0f} N/mm²" in w["message"] for w in found)


@pytest.mark.parametrize("modulus_MPa", [103_000.0, 118_000.0, 206_000.0])  # cast tin bronze, grey iron, steel
def test_iso_materials_are_within_it(modulus_MPa):
    assert _scope_warnings(modulus_MPa) == []
