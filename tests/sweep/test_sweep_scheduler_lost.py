"""A Dask scheduler that goes away mid-sweep: the sweep stops in one line naming --scheduler (exit 1, no traceback);
the rows that finished stay in the -o file, the points that never ran are not written as failed rows, and the same
command run again without --scheduler runs only the rest, to the file an uninterrupted --jobs 1 sweep writes."""

from __future__ import annotations

import csv
import importlib
import io
from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli.cli import cli

execute = importlib.import_module("gearcli.sweep.execute")  # the package re-exports a function of that name
SEED = str(Path(__file__).resolve().parents[2] / "configs" / "concrete_mixer.toml")
# 40 independent points: several batches (tasks), the first of which runs before the scheduler goes
ARGS = ["--vary", "input.speed_rpm=300:1500:40", "--set", "simulation.duration_s=0.3"]


class _Future:
    def __init__(self, fn, task, key, lost):
        self.fn, self.task, self.key, self.lost = fn, task, key, lost

    def result(self):
        if self.lost:  # what distributed's client raises for every pending future once the scheduler is gone
            distributed = pytest.importorskip("distributed")
            raise distributed.client.FutureCancelledError(self.key, "scheduler-connection-lost",
                                                          "Client lost the connection to the scheduler.")
        return self.fn(self.task)


class _Client:
    """A client whose scheduler runs the first task and then goes away."""

    first_points = 0

    def __init__(self, address, timeout=None):
        self.n = 0

    def submit(self, fn, task, pure=False):
        self.n += 1
        if self.n == 1:
            _Client.first_points = len(task.points)
        return _Future(fn, task, f"run_task-{self.n}", lost=self.n > 1)

    def cancel(self, futures):
        pass

    def close(self):
        pass


def _rows(path: Path) -> list[dict]:
    rows = list(csv.DictReader(io.StringIO(path.read_text().partition("\n")[2])))
    return [{k: v for k, v in r.items() if k != "wall_s"} for r in rows]


def test_a_lost_scheduler_stops_the_sweep_and_a_rerun_finishes_it(tmp_path, monkeypatch):
    distributed = pytest.importorskip("distributed")
    monkeypatch.setattr(distributed, "Client", _Client)
    monkeypatch.setattr(distributed, "as_completed", iter)
    monkeypatch.setattr(execute, "check_scheduler", lambda address: None)
    monkeypatch.setattr(importlib.import_module("gearcli.sweep.session"), "check_scheduler", lambda address: None)
    monkeypatch.setattr(importlib.import_module("gearcli.sweep.session"), "check_workers", lambda address: None)
    out = tmp_path / "lost.csv"
    runner = CliRunner()
    res = runner.invoke(cli, ["sweep", SEED, *ARGS, "--scheduler", "tcp://127.0.0.1:1", "-o", str(out)])
    assert res.exit_code == 1, res.stderr
    assert "--scheduler" in res.stderr and "lost the Dask scheduler" in res.stderr and "after 1 of " in res.stderr
    assert "Traceback" not in res.stderr
    kept = _rows(out)
    assert 0 < _Client.first_points < 40  # the sweep was cut: some points ran, some did not
    assert len(kept) == _Client.first_points and {r["status"] for r in kept} == {"ok"}  # no 'failed' row for the rest

    again = runner.invoke(cli, ["sweep", SEED, *ARGS, "--jobs", "1", "-o", str(out)])
    assert again.exit_code == 0, again.stderr
    clean = tmp_path / "clean.csv"
    assert runner.invoke(cli, ["sweep", SEED, *ARGS, "--jobs", "1", "-o", str(clean)]).exit_code == 0
    assert _rows(out) == _rows(clean)  # the resumed file is the uninterrupted one, bit for bit (but wall_s)


def test_a_lost_worker_is_still_a_failed_row():
    """Only the scheduler's loss stops the sweep; a task's own error (a killed worker) stays failed rows."""
    assert not execute.scheduler_lost(RuntimeError("KilledWorker"))
    distributed = pytest.importorskip("distributed")
    assert execute.scheduler_lost(distributed.client.FutureCancelledError("k", "scheduler-connection-lost"))
    assert not execute.scheduler_lost(distributed.client.FutureCancelledError("k", "cancelled by the user"))
