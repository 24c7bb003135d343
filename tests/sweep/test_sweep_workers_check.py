"""Dask workers that cannot run this gearcli: --scheduler is exit 2 before anything runs (no task submitted, no -o
file), naming the worker and what it lacks. A worker without gearcli cannot load a task: Dask's worker process dies
on it, and the cluster then waits for ever for a worker that can (found with `dask worker` on loopback, 2026-11-30:
the sweep hung with an empty -o file). A worker of another version would compute other rows."""

from __future__ import annotations

import importlib

import pytest
from click.testing import CliRunner

from gearcli import __version__
from gearcli.cli import cli
from tests.sweep.test_sweep_scheduler_lost import SEED

execute = importlib.import_module("gearcli.sweep.execute")  # the package re-exports a function of that name
ARGS = ["--vary", "input.speed_rpm=300,600", "--set", "simulation.duration_s=0.2"]


def _fake_cluster(monkeypatch, answers: dict) -> list:
    """A scheduler whose workers answer ``client.run`` with ``answers``; returns the list of submitted tasks."""
    distributed = pytest.importorskip("distributed")
    submitted: list = []

    class Client:
        def __init__(self, address, timeout=None):
            pass

        def run(self, fn, on_error="raise"):
            assert on_error == "return"  # every worker's answer, a failure included, not the first error raised
            return dict(answers)

        def submit(self, fn, task, pure=False):
            submitted.append(task)
            raise AssertionError("a task was submitted to a cluster that cannot run it")

        def close(self):
            pass

    monkeypatch.setattr(distributed, "Client", Client)
    monkeypatch.setattr(importlib.import_module("gearcli.sweep.session"), "check_scheduler", lambda address: None)
    return submitted


@pytest.mark.parametrize("answer, words", [
    (Exception(ModuleNotFoundError("No module named 'gearcli'")), "cannot run gearcli"),
    ("0.0.1", "run another gearcli"),
])
def test_workers_that_cannot_run_this_gearcli_are_a_usage_error(tmp_path, monkeypatch, answer, words):
    submitted = _fake_cluster(monkeypatch, {"tcp://127.0.0.1:40001": __version__, "tcp://127.0.0.1:40002": answer})
    out = tmp_path / "w.csv"
    res = CliRunner().invoke(cli, ["sweep", SEED, *ARGS, "--scheduler", "tcp://127.0.0.1:1", "-o", str(out)])
    assert res.exit_code == 2, res.stderr
    line = res.stderr.strip().splitlines()[-1]
    assert line.startswith("gearcli: --scheduler: 1 of 2 Dask workers " + words), line
    assert "tcp://127.0.0.1:40002" in line and f"install gearcli {__version__}" in line
    assert ("No module named 'gearcli'" in line) if words == "cannot run gearcli" else ("0.0.1" in line)
    assert "Traceback" not in res.stderr and submitted == [] and not out.exists()


def test_workers_of_this_gearcli_pass(monkeypatch):
    _fake_cluster(monkeypatch, {"tcp://127.0.0.1:40001": __version__})
    execute.check_workers("tcp://127.0.0.1:1")  # no error
    _fake_cluster(monkeypatch, {})  # no worker yet: the tasks will wait for one, as Dask's do
    execute.check_workers("tcp://127.0.0.1:1")
