"""A varied key's column is the key path as the user wrote it (DESIGN §6: "column named by key path").

Both spellings of an indexed key are accepted (``stage[0].backlash_mm``, the spelling of every error message, and
``stage.0.backlash_mm``); the column, the JSON ``columns``, the plots' axis labels and the messages echo the one
given, and a resume matches the points by the key itself, so a file written with one spelling is resumed with the
other (only the missing points run) and ends as an uninterrupted run in the new spelling.
"""

from __future__ import annotations

import csv
import io
import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli.cli import cli
from gearcli.sweep.spec import spec_from_options
from tests.sweep.test_sweep_cli import _counting

SEED = str(Path(__file__).resolve().parents[2] / "configs" / "concrete_mixer.toml")
BRACKET, DOTTED = "stage[0].backlash_mm", "stage.0.backlash_mm"
VALUES = "0.2,0.3,0.4"


def sweep(*args):
    return CliRunner().invoke(cli, ["sweep", SEED, "--jobs", "1", *args])


def csv_rows(text: str) -> tuple[list[str], list[dict]]:
    body = text.partition("\n")[2] if text.startswith("#") else text
    reader = csv.DictReader(io.StringIO(body))
    rows = list(reader)
    return list(reader.fieldnames or []), rows


def without_wall(rows):
    return [{k: v for k, v in r.items() if k != "wall_s"} for r in rows]


@pytest.mark.parametrize("key", [BRACKET, DOTTED])
def test_csv_column_is_the_key_as_written(key):
    res = sweep("--vary", f"{key}={VALUES}", "--format", "csv")
    assert res.exit_code == 0, res.stderr
    header, rows = csv_rows(res.stdout)
    assert header[:2] == [key, "direction"]
    assert [float(r[key]) for r in rows] == [0.2, 0.3, 0.4]


def test_json_and_random_columns_are_the_keys_as_written(tmp_path):
    out = tmp_path / "mc.json"
    res = sweep("--vary", "load.torque_Nm=4000", "--random", f"{BRACKET}=uniform(0.2,0.3)", "--samples", "2",
                "--seed", "5", "-o", str(out))
    assert res.exit_code == 0, res.stderr
    doc = json.loads(out.read_text())
    assert doc["columns"][:3] == ["load.torque_Nm", BRACKET, "direction"]
    assert all(0.2 <= r[BRACKET] <= 0.3 for r in doc["rows"]) and len(doc["rows"]) == 2
    # the recorded arguments name the key itself (what a resume compares), whichever spelling was given
    assert doc["sweep"]["random"][0]["key"] == DOTTED


@pytest.mark.parametrize(("first", "then"), [(DOTTED, BRACKET), (BRACKET, DOTTED)])
@pytest.mark.parametrize("suffix", [".csv", ".json"])
def test_resume_across_spellings_runs_only_the_missing_points(tmp_path, monkeypatch, first, then, suffix):
    full, part = tmp_path / f"full{suffix}", tmp_path / f"part{suffix}"
    assert sweep("--vary", f"{then}={VALUES}", "-o", str(full)).exit_code == 0
    _counting(monkeypatch, fail_after=2)
    assert sweep("--vary", f"{first}={VALUES}", "-o", str(part)).exit_code == 130
    calls = _counting(monkeypatch)
    res = sweep("--vary", f"{then}={VALUES}", "-o", str(part))
    assert res.exit_code == 0, res.stderr
    assert calls == [2]  # the two points done under the other spelling are not run again
    if suffix == ".csv":
        (ha, ra), (hb, rb) = csv_rows(full.read_text()), csv_rows(part.read_text())
        assert ha == hb and ha[0] == then
        assert without_wall(ra) == without_wall(rb)
        assert full.read_text().partition("\n")[0] == part.read_text().partition("\n")[0]  # same identity line
    else:
        a, b = json.loads(full.read_text()), json.loads(part.read_text())
        assert a["columns"] == b["columns"] and a["columns"][0] == then
        assert a["sweep"] == b["sweep"] and without_wall(a["rows"]) == without_wall(b["rows"])


def test_messages_name_the_key_as_written():
    res = sweep("--vary", "stage[0].nosuch=1,2")
    assert res.exit_code == 2 and "--vary: stage[0].nosuch: unknown key" in res.stderr
    res = sweep("--vary", f"{BRACKET}=0.2", "--vary", f"{DOTTED}=0.3")
    assert res.exit_code == 2 and f"{BRACKET} and {DOTTED} are one key, varied twice" in res.stderr


def test_plot_axis_label_is_the_key_as_written():
    pytest.importorskip("matplotlib")
    from gearcli.io.sweep_plots import _response

    spec = spec_from_options([f"{BRACKET}={VALUES}", "load.torque_Nm=4000,5000"], [], None, "lhs", None, None)
    rows = []
    for p in (p for branch in spec.branches() for p in branch):
        x = float(p.values[0][1])  # type: ignore[arg-type]
        rows.append({**dict(p.cells()), "direction": p.direction, "status": "ok", "stage1_tangential_N_mean": 1e3 * x,
                     "output_speed_rpm": 20.0})
    fig = _response(rows, spec.axes[0].column, spec, 1)
    labels = {ax.get_xlabel() for ax in fig.axes} - {""}
    assert labels == {BRACKET}
    assert fig._suptitle.get_text() == f"sweep response against {BRACKET}"
    legend = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert any("load.torque_Nm=4000" in t for t in legend)


def test_a_points_messages_name_its_keys_as_written():
    spec = spec_from_options([f"{BRACKET}=0.25"], [], None, "lhs", None, None)
    point = spec.branches()[0][0]
    assert point.overrides() == [f"{DOTTED}=0.25"]  # what the point sets: the key itself
    assert point.shown() == f"{BRACKET}=0.25"  # what a row's message says (the family's checked point, a jump)
