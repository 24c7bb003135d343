"""A sweep that lists a value twice (``--vary KEY=400,400,500``: a repeatability check) has one row per point, and
a re-run against its own -o file (complete, or cut short after the first point) leaves that same file: each
repeated point is done only when a row stands for it (docs/sweeps.md, "-o FILE is resumable")."""

from __future__ import annotations

import csv
import io
import json

import pytest
from click.testing import CliRunner

from gearcli.cli import cli
from gearcli.sweep import worker
from tests.sweep.test_sweep_resonance import SCENE

ARGS = ["--vary", "input.speed_rpm=400,400,500", "--set", "simulation.duration_s=0.1", "--jobs", "1"]
REAL = worker._evaluate


def _rows(path, suffix):
    text = path.read_text()
    if suffix == ".json":
        return json.loads(text)["rows"]
    return list(csv.DictReader(io.StringIO(text.partition("\n")[2])))


def _plain(rows):
    return [{k: v for k, v in r.items() if k != "wall_s"} for r in rows]


@pytest.mark.parametrize("suffix", [".csv", ".json"])
def test_repeated_values_keep_a_row_each_through_a_rerun_and_a_resume(tmp_path, monkeypatch, suffix):
    scene = tmp_path / "scene.toml"
    scene.write_text(SCENE)
    full, part = tmp_path / f"full{suffix}", tmp_path / f"part{suffix}"

    def sweep(out):
        return CliRunner().invoke(cli, ["sweep", str(scene), *ARGS, "-o", str(out)])

    assert sweep(full).exit_code == 0
    rows = _rows(full, suffix)
    assert [float(r["input.speed_rpm"]) for r in rows] == [400, 400, 500]
    assert rows[0]["stage1_tangential_N_mean"] == rows[1]["stage1_tangential_N_mean"]  # the same point, twice
    before = _rows(full, suffix)
    res = sweep(full)  # complete: nothing to run, nothing lost
    assert res.exit_code == 0 and "3 points" in res.stderr
    assert _plain(_rows(full, suffix)) == _plain(before)

    calls: list[int] = []

    def evaluate(evaluator, scene_, point, prev, check=False):
        if len(calls) == 1 and not resumed:
            raise KeyboardInterrupt
        calls.append(point.index)
        return REAL(evaluator, scene_, point, prev, check)

    resumed = False
    monkeypatch.setattr(worker, "_evaluate", evaluate)
    assert sweep(part).exit_code == 130 and len(_rows(part, suffix)) == 1  # the first 400 rpm point only
    resumed = True
    assert sweep(part).exit_code == 0
    assert calls == [0, 1, 2]  # the second 400 rpm point and the 500 rpm point ran on the resume
    assert _plain(_rows(part, suffix)) == _plain(before)
