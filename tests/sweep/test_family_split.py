"""Trial tr16c: an independent point takes its family's verdict (gearcli.sweep.family) whichever task ran it, so a
sweep's rows, warnings included, are the same at --jobs 1, --jobs 2, on a Dask cluster and after a resume. Before,
the verdict reached only the points after the checked one in the same task: a 73-point speed sweep at --jobs 2
(batches of 10) left 7 rows without the unresolved-statistics warning that --jobs 1 (batches of 19) gave them, and
a resumed file differed from the uninterrupted one."""

from __future__ import annotations

import csv
import importlib
import io
import itertools
from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli.cli import cli
from gearcli.sweep import family
from gearcli.sweep.family import CHECK_EVERY, Carrier
from gearcli.sweep.spec import spec_from_options
from gearcli.sweep.worker import Scene

execute = importlib.import_module("gearcli.sweep.execute")  # the package re-exports a function of that name
WARNING = "stage 1: F_t max not resolved"


def _row(index, pace, *, checked=False, status="ok", message="own", unresolved=WARNING, method="DOP853"):
    row = {"_index": index, "status": status, "message": message}
    if status == "ok":
        row.update(_method=method, _engine="compiled", _rtol=1e-6, _pace=pace)
    if checked:
        row["_checked"] = True
        if status == "ok":
            row.update(_checked_at=f"input.speed_rpm={index}", _unresolved=unresolved)
    return row


def _rows():
    f1 = CHECK_EVERY  # the second family's checked point
    return [
        _row(0, 1000.0, checked=True),  # family 0: unresolved at pace 1000
        _row(1, 1400.0),  # 1.4x the pace: alike (PACE_RATIO 1.5)
        _row(2, 1600.0),  # 1.6x: not alike
        _row(3, 1000.0, method="Radau"),  # another method: not alike
        _row(4, 0.0, status="failed", message="stage[0].pinion.teeth: must be >= 5"),
        _row(f1, 1000.0, checked=True, status="failed", message="solver failed"),  # family 1: no verdict
        _row(f1 + 1, 1000.0),
    ]


def _through(rows):
    carrier = Carrier()
    out = [r for got in rows for r in carrier.add(dict(got))] + list(carrier.rest())
    return sorted(out, key=lambda r: r["_index"])


def test_a_row_takes_its_familys_verdict_in_whatever_order_the_rows_arrive():
    rows = _rows()
    first = _through(rows)
    for order in itertools.islice(itertools.permutations(rows), 0, None, 97):  # tasks finish in any order
        assert _through(order) == first
    by = {r["_index"]: r for r in first}
    assert set(by) == {0, 1, 2, 3, 4, CHECK_EVERY, CHECK_EVERY + 1}
    assert all(not k.startswith("_") or k == "_index" for r in first for k in r)  # the hidden fields are gone
    assert by[0]["message"] == "own"  # the checked row's own warnings are its run's
    assert by[1]["message"] == f"own; {WARNING} (estimated at the family's checked point input.speed_rpm=0)"
    assert by[2]["message"] == by[3]["message"] == "own"  # not alike: nothing carried
    assert by[4]["message"] == "stage[0].pinion.teeth: must be >= 5"
    assert by[CHECK_EVERY + 1]["message"] == "own"  # its checked point failed: no verdict


def test_a_resolved_verdict_carries_nothing_and_a_verdict_alone_is_not_a_row():
    carrier = Carrier()
    waiting = list(carrier.add(_row(5, 1000.0)))
    assert waiting == []  # waits for its family's checked row
    verdict = {**_row(0, 1000.0, checked=True, unresolved=""), "_verdict_only": True}  # a resume's rerun, unwritten
    (row,) = carrier.add(verdict)
    assert row == {"_index": 5, "status": "ok", "message": "own"}


def test_a_row_whose_checked_point_never_came_is_written_without_a_verdict():
    carrier = Carrier()
    assert list(carrier.add(_row(CHECK_EVERY + 3, 1000.0))) == []
    assert list(carrier.rest()) == [{"_index": CHECK_EVERY + 3, "status": "ok", "message": "own"}]


def test_a_family_whose_checked_point_is_written_resolved_streams_its_rows():
    """A resume whose family's checked point is in the file with a resolved verdict (it carries nothing, and no task
    runs it): the family's rows have no verdict to wait for, so they are written as they come, not held to the end
    of the sweep (where a Ctrl-C would have dropped them)."""
    n = 2 * CHECK_EVERY
    spec = spec_from_options([f"input.speed_rpm=100:{100 + n - 1}:{n}"], [], None, "lhs", None, None)
    points = [b[0] for b in spec.branches()]
    written = CHECK_EVERY + 3  # family 1's checked point and two more are in the file
    tasks, _ = execute.plan(spec, Scene(b"", "x.toml"), {p.ident: 1 for p in points[:written]}, 2, None)
    carrier = Carrier(tasks)
    row = _row(written, 1000.0)
    assert list(carrier.add(dict(row))) == [{"_index": written, "status": "ok", "message": "own"}]
    assert list(carrier.rest()) == []
    # a family whose checked point does run still waits for it
    fresh = Carrier(execute.plan(spec, Scene(b"", "x.toml"), {}, 2, None)[0])
    assert list(fresh.add(_row(3, 1000.0))) == [] and len(list(fresh.rest())) == 1


@pytest.mark.parametrize("workers", [1, 2, 7])
def test_a_resume_runs_a_written_checked_point_again_unwritten(workers):
    n = 3 * CHECK_EVERY
    spec = spec_from_options([f"input.speed_rpm=100:{100 + n - 1}:{n}"], [], None, "lhs", None, None)
    points = [b[0] for b in spec.branches()]
    written = CHECK_EVERY + 3  # the file holds points 0 .. CHECK_EVERY + 2: family 1's checked point among them
    done = {p.ident: 1 for p in points[:written]}
    scene = Scene(b"", "x.toml")
    tasks, todo = execute.plan(spec, scene, done, workers, None)  # every written verdict resolved: nothing again
    assert todo == n - written and sorted(p.index for t in tasks for p in t.points) == list(range(written, n))
    assert not any(t.skip for t in tasks)
    unresolved = {points[CHECK_EVERY].ident, points[0].ident}  # its row said 'not resolved ... at the run's rtol'
    tasks, todo = execute.plan(spec, scene, done, workers, None, unresolved)
    assert todo == n - written
    run = sorted(p.index for t in tasks for p in t.points)
    skipped = sorted(i for t in tasks for i in t.skip)
    assert skipped == [CHECK_EVERY]  # run for its verdict, not written again
    assert run == [CHECK_EVERY, *range(written, n)]  # family 0 is whole in the file: its checked point is not rerun


def _scene(tmp_path: Path) -> str:
    """A two-stage reducer with transmission error rattling near the mode its first mesh crosses (720 Hz at
    1877 rpm): its runs leave F_t's extremes unresolved (a mesh leaves its flank), a verdict to carry."""
    path = tmp_path / "two_stage.toml"
    path.write_text("""
materials.steel = { density_kg_m3 = 7850, youngs_modulus_MPa = 2.1e5, poisson_ratio = 0.3 }
[[stage]]
normal_module_mm = 4
normal_pressure_angle_deg = 20
helix_angle_deg = 15
backlash_mm = 0.08
pinion = { teeth = 23, face_width_mm = 50, hand = "left", material = "steel" }
gear   = { teeth = 71, face_width_mm = 48, hand = "right", material = "steel" }
mesh   = { transmission_error_um = [3.0, 1.0], transmission_error_phase_deg = [0, 30] }
[[stage]]
normal_module_mm = 6
normal_pressure_angle_deg = 20
helix_angle_deg = 12
backlash_mm = 0.1
pinion = { teeth = 19, face_width_mm = 80, hand = "right", material = "steel" }
gear   = { teeth = 67, face_width_mm = 78, hand = "left", material = "steel" }
mesh   = { transmission_error_um = [4.0], transmission_error_phase_deg = [45] }
[contact]
stiffness = "iso6336"
exponent = 1
damping_ratio = 0.04
[input]
speed_rpm = 1500
ramp_s = 0.05
[load]
torque_Nm = 1200
ramp_s = 0.05
[simulation]
duration_s = 0.3
steps = 3000
""")
    return str(path)


def _table(path: Path) -> tuple[str, list[dict]]:
    head, _, body = path.read_text().partition("\n")
    return head, [{k: v for k, v in r.items() if k != "wall_s"} for r in csv.DictReader(io.StringIO(body))]


@pytest.mark.slow  # ~5 s: three small sweeps of a rattling scene
def test_rows_are_the_same_however_the_points_are_split_and_resumed(tmp_path, monkeypatch):
    monkeypatch.setattr(family, "CHECK_EVERY", 3)  # families of 3: points 0-2 and 3-5
    scene = _scene(tmp_path)
    args = ["sweep", scene, "--vary", "input.speed_rpm=1825:1950:6", "--jobs", "1"]
    runner = CliRunner()
    whole = tmp_path / "whole.csv"
    monkeypatch.setattr(execute, "batch_size", lambda n, workers: n)  # one task
    res = runner.invoke(cli, [*args, "-o", str(whole)])
    assert res.exit_code == 0, res.output
    monkeypatch.setattr(execute, "batch_size", lambda n, workers: 2)  # tasks [0 1] [2 3] [4 5]: 4, 5 apart from 3
    split = tmp_path / "split.csv"
    assert runner.invoke(cli, [*args, "-o", str(split)]).exit_code == 0
    head, rows = _table(whole)
    assert _table(split) == (head, rows)
    carried = [r for r in rows if "family's checked point input.speed_rpm=1900" in r["message"]]
    assert carried  # the comparison holds a carried verdict (rows 4, 5 from point 3)
    # a file cut after point 3 (the second family's checked point written, 4 and 5 not): the resume runs 3 again
    resumed = tmp_path / "resumed.csv"
    lines = whole.read_text().splitlines(keepends=True)
    resumed.write_text("".join(lines[:2 + 4]))
    assert runner.invoke(cli, [*args, "-o", str(resumed)]).exit_code == 0
    assert _table(resumed) == (head, rows)


@pytest.mark.parametrize("workers", [1, 2, 7])
def test_every_task_prices_the_kernel_load_over_the_whole_sweep(workers, monkeypatch):
    """engine = "auto" in a sweep: each point prices loading the kernel alike (gearcli.engine.sweep_load_share_s:
    a compilation's 60 s over all the sweep's points where nothing is cached), the same in every task at any
    --jobs and after a resume, so a point's engine, and so its row, does not depend on how the sweep was split (it
    did: each worker priced its own part of the sweep, at the load time its last process measured)."""
    from gearcli import engine

    monkeypatch.setattr(engine, "cached_or_loaded", lambda: False)
    monkeypatch.setattr(engine, "available", lambda: True)  # numba installed
    n = 3 * CHECK_EVERY
    spec = spec_from_options([f"input.speed_rpm=100:{100 + n - 1}:{n}"], [], None, "lhs", None, None)
    points = [b[0] for b in spec.branches()]
    scene = Scene(b"", "x.toml")
    for done in ({}, {p.ident: 1 for p in points[:CHECK_EVERY + 3]}):  # a fresh sweep; a resume
        tasks, _ = execute.plan(spec, scene, done, workers, None)
        assert tasks and all(t.load_share_s == pytest.approx(60.0 / n) for t in tasks)
