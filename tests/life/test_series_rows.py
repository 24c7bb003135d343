"""``gearcli life --series``: a bad history row is exit 2 naming the file, the row and the column (no output
written), and a square history with reverse and idle stretches counted by hand."""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli
from tests.life.scenes import RATED

HEADER = "time_s,torque_Nm,speed_rpm\n"


@pytest.mark.parametrize(("body", "row", "column"), [
    ("0,1500,1500\n10,nan,1500\n20,1,1\n", "row 3", "column torque_Nm"),
    ("0,1500,1500\n10,,1500\n20,1,1\n", "row 3", "column torque_Nm"),
    ("0,1500,1500\n10,1500\n20,1,1\n", "row 3", "column speed_rpm"),
    ("0,1500,1500\n1e400,1500,1500\n", "row 3", "column time_s"),
    ("0,1500,1500\n10,1500,fast\n20,1,1\n", "row 3", "column speed_rpm"),
    ("0,1500,1500\n10,1500,1500\n10,1200,1500\n20,1,1\n", "row 4", "column time_s"),  # a repeated stamp
    ("0,1500,1500\n\n20,1500,1500\n10,1200,1500\n30,1,1\n", "row 5", "column time_s"),  # unsorted, after a blank
    # finite cells beyond the design file's bounds: the classing's width (1e308 - -1e308) and a class's mean
    # speed (1e308 rpm x 10 s) overflowed: an internal error (exit 1), or "got inf" naming a class
    ("0,-1e308,1500\n10,1e308,1500\n20,1,1\n", "row 2", "column torque_Nm"),
    ("0,1500,1500\n10,1500,1e308\n20,1,1\n", "row 3", "column speed_rpm"),
    ("0,1500,1500\n10,1500,-300000\n20,1,1\n", "row 3", "column speed_rpm"),  # reverse, in magnitude
    # steps of 5e-324 s made the history's hours 0: an internal error (ZeroDivisionError) in its verdict
    ("0,1500,1500\n5e-324,1500,1500\n1e-323,1,1\n", "row 3", "column time_s"),
    ("0,1500,1500\n1,1500,1500\n1.0000000000000002,1,1\n", "row 4", "column time_s"),  # 2.2e-16 s
])
def test_bad_row_names_file_row_and_column(tmp_path, body, row, column):
    path, csv, out = tmp_path / "s.toml", tmp_path / "h.csv", tmp_path / "out.json"
    path.write_text(RATED)
    csv.write_text(HEADER + body)
    res = CliRunner().invoke(cli, ["life", str(path), "--static", "--series", str(csv), "-o", str(out)])
    assert res.exit_code == 2, res.output
    assert str(csv) in res.stderr and f"{row}, {column}" in res.stderr and "Traceback" not in res.stderr
    assert not out.exists()


def test_a_twice_named_column_is_exit_2(tmp_path):
    """Two torque_Nm columns: which is the history is ambiguous (it used to take the first silently)."""
    path, csv = tmp_path / "s.toml", tmp_path / "h.csv"
    path.write_text(RATED)
    csv.write_text("time_s,torque_Nm,speed_rpm,torque_Nm\n0,1500,1500,9\n10,1500,1500,9\n")
    res = CliRunner().invoke(cli, ["life", str(path), "--static", "--series", str(csv)])
    assert res.exit_code == 2 and "torque_Nm" in res.stderr and str(csv) in res.stderr


def test_square_history_with_reverse_and_idle_rows_counted_by_hand(tmp_path):
    """1000 h at 2400 N·m and 1500 rpm, 3000 h at 1200 N·m turning in reverse at -750 rpm, then 0.5 h idle
    (a 9000 N·m stall at zero speed, no revolutions); the last row only ends the history. By hand: the pinion
    makes 1000·60·1500 = 9e7 and 3000·60·750 = 1.35e8 revolutions (|n| dt), the gear (z2/z1 = 3) a third
    of each; each revolution is one load cycle of a tooth; the reverse level's force is half the other's."""
    path, csv = tmp_path / "s.toml", tmp_path / "h.csv"
    path.write_text(RATED)
    t1, t2, t3 = 1000 * 3600.0, 4000 * 3600.0, 4000.5 * 3600.0
    csv.write_text(HEADER + f"0,2400,1500\n{t1},1200,-750\n{t2},9000,0\n{t3},2400,1500\n")
    res = CliRunner().invoke(cli, ["life", str(path), "--static", "--series", str(csv), "--format", "json", "-q"])
    assert res.exit_code == 0, res.output
    life = json.loads(res.stdout)["life"]
    assert_allclose(life["hours"], 4000.0, rtol=1e-12)  # the idle half hour is no duty
    for member, per_rev in (("pinion", 1.0), ("gear", 1.0 / 3.0)):
        bins = sorted(life["stages"][0][member]["pitting"]["bins"], key=lambda b: b["force_N"])
        assert_allclose([b["cycles"] for b in bins], [1.35e8 * per_rev, 9e7 * per_rev], rtol=1e-12)
        assert_allclose(bins[0]["force_N"] / bins[1]["force_N"], 0.5, rtol=1e-12)  # static forces ∝ torque


def test_classes_without_a_series_is_a_usage_error(tmp_path):
    """--classes only classes a --series history: given with the [[duty]] tables it was silently ignored."""
    path, out = tmp_path / "s.toml", tmp_path / "out.json"
    path.write_text(RATED)
    res = CliRunner().invoke(cli, ["life", str(path), "--static", "--classes", "3", "-o", str(out)])
    assert res.exit_code == 2 and "--classes" in res.stderr and "--series" in res.stderr
    assert "Traceback" not in res.output and not out.exists()


def test_a_class_spanning_zero_torque_is_split_by_the_torque_sign(tmp_path):
    """The torque's sign chooses the flank (and the bearings' reaction directions), so one class must not mix the
    two: a history of 1 h at -120 N·m (1000 rpm), 100 h at +100 N·m (1200 rpm) and 10 h at 900 N·m (1480 rpm) in 3
    classes of width (900 + 120)/3 = 340 N·m puts -120 and +100 into class 1. Hand classing, split by sign: class 1's
    negative part (-120 N·m, 1 h, 1000 rpm), its positive part (+100 N·m, 100 h, 1200 rpm), class 3 (900 N·m, 10 h,
    1480 rpm). Unsplit, class 1 became one point of -120 N·m over 101 h: a 101 h load reversal on the back flanks
    (and its reversed bearing loads) out of one hour of it."""
    path, csv = tmp_path / "s.toml", tmp_path / "h.csv"
    path.write_text(RATED)
    csv.write_text(HEADER + f"0,-120,1000\n{3600.0},100,1200\n{101 * 3600.0},900,1480\n{111 * 3600.0},0,1480\n")
    res = CliRunner().invoke(cli, ["life", str(path), "--static", "--series", str(csv), "--classes", "3",
                                   "--format", "json", "-q"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    points = sorted((p["torque_Nm"], p["hours"], p["speed_rpm"]) for p in doc["life"]["points"])
    assert_allclose(points, [(-120.0, 1.0, 1000.0), (100.0, 100.0, 1200.0), (900.0, 10.0, 1480.0)], rtol=1e-12)
    names = [p["name"] for p in doc["life"]["points"]]
    assert len(set(names)) == 3 and all(n.startswith("class ") for n in names)
    reversals = [w for w in doc["warnings"] if "load reversal" in w["message"]]
    assert len(reversals) == 1 and "-120" in reversals[0]["message"]
