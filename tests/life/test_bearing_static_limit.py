"""``[rating] min_static_safety_bearing`` without a gear rating (docs/bearings.md): a
``[rating]`` table that sets only the bearings' ISO 76 minimum rates no gear and needs none of the gear rating's
keys (it used to be refused: ``rating.required_life_h: missing required key``, then the oil, the materials' limits).

The figures by hand: one spur stage (m = 4 mm, z = 20/60, no profile shift, so alpha_wt = 20 deg), 600 N m on the
gear (d = 240 mm): F_t = 2 T / d = 5000 N, F_r = F_t tan 20 deg, no axial force; the gear at 70 mm between two
bearings at 0 and 200 mm carries F = F_t / cos 20 deg, a simply supported shaft: R_1 = F (200 - 70) / 200,
R_2 = F 70 / 200. ISO 76: P_0 = max(F_r, X_0 F_r + Y_0 F_a) = F_r (X_0 < 1, F_a = 0), s_0 = C_0 / P_0.
"""

from __future__ import annotations

import json
import math

import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli
from tests.life.scenes import ONE_STAGE

C0_KN = 10.0
F = 2 * 600e3 / 240.0 / math.cos(math.radians(20.0))  # N, the gear's load in the plane of the bearings
S0 = [C0_KN * 1e3 / (F * 130 / 200), C0_KN * 1e3 / (F * 70 / 200)]  # 2.89 and 5.37
SPUR = (ONE_STAGE.replace("helix_angle_deg = 15", "helix_angle_deg = 0")
        .replace('hand = "left"', 'hand = "spur"').replace('hand = "right"', 'hand = "spur"')
        .replace("kind = \"ball\"", f"kind = \"ball\"\nstatic_load_rating_kN = {C0_KN}\n"
                                    "static_factors = { X0 = 0.6, Y0 = 0.5 }"))


def _run(tmp_path, command: str, text: str, *args: str):
    path = tmp_path / "bearings.toml"
    path.write_text(text, encoding="utf-8")
    return CliRunner().invoke(cli, [command, str(path), "--format", "json", *args])


def _ok(res) -> dict:
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def _low(doc: dict) -> list[int]:
    return [w["bearing"] for w in doc["warnings"] if w["code"] == "bearing_static_safety_low"]


def test_the_static_safety_by_hand():
    assert_allclose(S0, [2.891, 5.370], rtol=1e-3)  # the hand figures themselves, to the digits quoted above


@pytest.mark.parametrize("minimum, low", [(None, []), (4.0, [1]), (6.0, [1, 2]), (2.5, [])])
def test_a_bearing_only_rating_table_sets_the_minimum_without_rating_the_gears(tmp_path, minimum, low):
    """s_0 = 2.89 and 5.37 by hand; the default minimum of a ball bearing is 1.0 (no warning); 4.0 warns for
    bearing 1 only, 6.0 for both, 2.5 for neither. No gear is rated (no materials' limits, no oil, no life)."""
    text = SPUR if minimum is None else f"{SPUR}\n[rating]\nmin_static_safety_bearing = {minimum}\n"
    doc = _ok(_run(tmp_path, "design", text))
    assert_allclose([b["static_safety"] for b in doc["bearings"]], S0, rtol=1e-9)
    assert_allclose([b["static_equivalent_load_N"] for b in doc["bearings"]], [F * 0.65, F * 0.35], rtol=1e-9)
    assert _low(doc) == low
    assert all(not st.get("rating") for st in doc["stages"])
    for w in (w for w in doc["warnings"] if w["code"] == "bearing_static_safety_low"):
        assert_allclose([w["s0"], w["s0_min"]], [S0[w["bearing"] - 1], minimum], rtol=1e-9)


def test_set_creates_the_bearing_only_table_and_simulate_applies_it(tmp_path):
    """``--set rating.min_static_safety_bearing=4`` on a file without [rating]: design warns for bearing 1 as above;
    simulate's window peak loads the bearings at least as much as the static load (s_0 min <= 2.89 < 4 for bearing 1,
    and bearing 2's >= 4 as long as its peak load stays within 5.37 / 4 of the static one)."""
    args = ("--set", "rating.min_static_safety_bearing=4")
    assert _low(_ok(_run(tmp_path, "design", SPUR, *args))) == [1]
    run = _ok(_run(tmp_path, "simulate", SPUR, *args, "--set", "simulation.duration_s=0.3"))
    s0_min = [b["static_safety_min"] for b in run["summary"]["bearings"]]
    assert s0_min[0] <= S0[0] * (1 + 1e-3) and s0_min[1] > 4.0
    low = [w for w in run["warnings"] if w["code"] == "bearing_static_safety_low"]
    assert {w["bearing"] for w in low} == {1}  # the design's (at the static load) and the window peak's
    assert any("at the peak of the simulated window" in w["message"] for w in low)


@pytest.mark.parametrize("table", ["[rating]\n", "[rating]\nmin_safety_pitting = 1.2\nmin_static_safety_bearing = 2\n"])
def test_a_rating_table_that_rates_the_gears_still_needs_its_life(tmp_path, table):
    """An empty [rating], or one with a gear rating key, is a gear rating: its missing life is exit 2 naming the key."""
    res = _run(tmp_path, "design", f"{SPUR}\n{table}")
    assert res.exit_code == 2 and "Traceback" not in res.output
    assert "bearings.toml: rating.required_life_h: missing required key" in res.stderr


def test_life_still_needs_the_gear_rating_and_says_why(tmp_path):
    res = _run(tmp_path, "life", f"{SPUR}\n[rating]\nmin_static_safety_bearing = 4.0\n")
    assert res.exit_code == 2 and "Traceback" not in res.output
    assert "bearings.toml: rating: gearcli life rates every member by ISO 6336-2/-3" in res.stderr
    assert "this file's [rating] sets only the bearings' min_static_safety_bearing" in res.stderr


def test_the_json_schema_says_the_same():
    """``gearcli schema`` accepts the bearing-only table and refuses a gear rating without its life, as loading does."""
    import tomllib

    from gearcli.config import json_schema
    from tests.jsonschema_subset import valid

    schema = json_schema()
    for table, accepted in (("min_static_safety_bearing = 4.0\n", True), ("", False),
                            ("min_safety_pitting = 1.2\nmin_static_safety_bearing = 2\n", False),
                            ("required_life_h = 20000\nmin_static_safety_bearing = 2\n", True)):
        data = tomllib.loads(f"{SPUR}\n[rating]\n{table}")
        assert valid(data, schema, schema) == accepted, table
