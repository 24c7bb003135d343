"""``--table bearings``: the bearings' figures as CSV, one row per [[bearing]], in ``design``, ``simulate`` and
``life`` (docs/bearings.md, "CSV"): every JSON figure of a bearing under its JSON name, the same number (the
CSV writes a float's repr), the by-hand figures of ``test_bearing_modified`` in the design's row, empty cells
where a bearing lacks C_0 / C_u, and exit 2 where the table cannot be written. Its ``bearing`` column counts
from 1 in ``[[bearing]]`` order, as the ``bearing{j}_radial_N`` channels and the warnings' ``bearing`` do."""

from __future__ import annotations

import csv
import io
import json
import tomllib

import pytest
from numpy.testing import assert_allclose

from tests.life.scenes import RATED
from tests.life.test_bearing_modified import _hand, _run, _with_keys


def _csv(tmp_path, command: str, *args: str) -> list[dict[str, str]]:
    res = _run(tmp_path, command, _with_keys(), "--format", "csv", "--table", "bearings", *args)
    assert res.exit_code == 0, res.output
    return list(csv.DictReader(io.StringIO(res.stdout)))


def _json(tmp_path, command: str, *args: str) -> dict:
    res = _run(tmp_path, command, _with_keys(), "--format", "json", *args)
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def _same(row: dict[str, str], doc: dict, key: str) -> None:
    value = doc[key]
    if isinstance(value, bool):
        assert row[key] == str(value), key
    elif isinstance(value, (int, float)):
        assert float(row[key]) == value, key
    else:
        assert row[key] == value, key


def test_design_rows_are_the_json_bearings(tmp_path):
    rows, doc = _csv(tmp_path, "design"), _json(tmp_path, "design")
    assert [int(r["bearing"]) for r in rows] == list(range(1, len(doc["bearings"]) + 1))
    for row, b in zip(rows, doc["bearings"], strict=True):
        for key in b:
            _same(row, b, key)
    # bearing 1 carries the new keys: its row holds the figures worked by hand from its reactions
    for key, value in _hand(doc["bearings"][0]).items():
        assert_allclose(float(rows[0][key]), value, rtol=1e-12, err_msg=key)
    # the others have no C_0, C_u: empty cells, not zeros
    assert rows[1]["static_safety"] == rows[1]["kappa"] == rows[1]["L_nm_h"] == ""


def test_life_rows_carry_the_duty_figures_and_one_column_per_point(tmp_path):
    rows, doc = _csv(tmp_path, "life", "--static"), _json(tmp_path, "life", "--static")
    bearings, points = doc["life"]["bearings"], doc["life"]["points"]
    assert len(rows) == len(bearings) and len(points) == 3
    for row, b in zip(rows, bearings, strict=True):
        for key, value in b.items():
            if isinstance(value, list):  # per duty point, 1-based in the order of life.points
                assert [float(row[f"{key}_{i + 1}"]) for i in range(len(value))] == value, key
            else:
                _same(row, b, key)
    first = rows[0]
    assert {"L_nm_Mrev", "L_nm_h", "a_ISO", "kappa", "static_safety", "static_safety_min", "kappa_points_3",
            "a_ISO_points_1"} <= set(first)
    # the duty's effective a_ISO is L_nm / (a_1 L10) (docs/bearings.md), from the row's own columns
    assert_allclose(float(first["a_ISO"]), float(first["L_nm_Mrev"]) / (float(first["a_1"]) * float(first["L10_Mrev"])),
                    rtol=1e-12)


def test_simulate_rows_carry_the_window_peak_safety(tmp_path):
    rows, doc = _csv(tmp_path, "simulate"), _json(tmp_path, "simulate")
    bearings = doc["summary"]["bearings"]
    assert len(rows) == len(bearings)
    assert float(rows[0]["static_safety_min"]) == bearings[0]["static_safety_min"]
    assert float(rows[0]["radial_N_max"]) == bearings[0]["radial_N"]["max"]
    assert rows[1]["static_safety_min"] == ""


def test_without_the_option_the_csv_is_todays(tmp_path):
    plain = _run(tmp_path, "design", _with_keys(), "--format", "csv")
    stages = _run(tmp_path, "design", _with_keys(), "--format", "csv", "--table", "stages")
    assert plain.exit_code == stages.exit_code == 0
    assert plain.stdout == stages.stdout and plain.stdout.startswith("index,")


@pytest.mark.parametrize("command", ["design", "life"])
def test_the_table_needs_csv_and_bearings(tmp_path, command):
    extra = ("--static",) if command == "life" else ()
    res = _run(tmp_path, command, _with_keys(), "--format", "json", "--table", "bearings", *extra)
    assert res.exit_code == 2 and "--format csv" in res.output and "Traceback" not in res.output
    text = RATED.split("[[bearing]]")[0] + "\n" + RATED[RATED.index("[[duty]]"):]
    res = _run(tmp_path, command, text, "--format", "csv", "--table", "bearings", *extra)
    assert res.exit_code == 2 and "no [[bearing]] table" in res.output and "scene.toml" in res.output
    assert "Traceback" not in res.output


def test_bearing_numbers_count_from_one_as_the_channels_and_warnings_do(tmp_path):
    """A script joins the bearings' table to the simulated channels and the warnings by the bearing's number: row
    ``bearing`` j is the j-th ``[[bearing]]`` table of the file (read here with tomllib), the one whose window
    statistics are the channel ``bearing{j}_radial_N`` and which a warning's ``bearing`` j names."""
    tables = tomllib.loads(_with_keys())["bearing"]
    design_rows, design = _csv(tmp_path, "design"), _json(tmp_path, "design")
    for row in design_rows:
        j = int(row["bearing"])
        assert 1 <= j <= len(tables)
        assert (int(row["shaft"]), float(row["position_mm"])) == (tables[j - 1]["shaft"], tables[j - 1]["position_mm"])
    named = [w for w in design["warnings"] if "bearing" in w and "radial_N" in w]
    assert named  # the scene's locating roller bearing carries F_a without factors
    by_number = {int(r["bearing"]): r for r in design_rows}
    for w in named:
        assert float(by_number[w["bearing"]]["radial_N"]) == pytest.approx(w["radial_N"], rel=1e-12)
    sim_rows = _csv(tmp_path, "simulate")
    series = _run(tmp_path, "simulate", _with_keys(), "--format", "csv")
    assert series.exit_code == 0, series.output
    columns = list(csv.DictReader(io.StringIO(series.stdout)))
    window = _json(tmp_path, "simulate")["summary"]["window_s"]
    inside = [c for c in columns if window[0] - 1e-12 <= float(c["time_s"]) <= window[1] + 1e-12]
    for row in sim_rows:
        j = int(row["bearing"])
        peak = max(float(c[f"bearing{j}_radial_N"]) for c in inside)
        assert float(row["radial_N_max"]) == pytest.approx(peak, rel=1e-9), j
