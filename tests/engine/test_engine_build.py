"""``gearcli engine build`` (issue 33, item 4): the compiled engine's first compilation as a step of its own, with
progress and the time it measured, never hidden in another command; a built cache is reported as such with what
loading it costs a process."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]
SEED = ROOT / "configs" / "concrete_mixer.toml"


def _gearcli(*args: str, **env: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "gearcli", *args], env=dict(os.environ, PYTHONPATH=str(ROOT), **env),
                          capture_output=True, text=True, timeout=1200)


def test_without_numba_the_build_is_a_usage_error(monkeypatch):
    from gearcli.engine import loader

    monkeypatch.setattr(loader, "available", lambda: False)
    res = CliRunner().invoke(cli, ["engine", "build"])
    assert res.exit_code == 2
    assert "numba" in res.output and "gearcli[fast]" in res.output and "Traceback" not in res.output


def test_a_built_cache_is_reported_with_its_load_time():
    pytest.importorskip("numba")
    first = _gearcli("engine", "build", "-q")  # builds it when this machine has not yet
    assert first.returncode == 0 and first.stderr == "", first.stderr
    res = _gearcli("engine", "build")
    assert res.returncode == 0, res.stderr
    assert res.stderr == ""  # nothing compiled: nothing to show
    lines = res.stdout.splitlines()
    assert lines[0].startswith("engine: already compiled; cached in ")
    assert re.fullmatch(r"engine: a process loads it in \d+\.\d\d s \(.*measured now\)", lines[1])


@pytest.mark.slow  # a whole compilation: 30-200 s on two cores
def test_a_first_build_shows_its_progress_and_measured_time(tmp_path):
    pytest.importorskip("numba")
    xdg = tmp_path / "xdg"
    res = _gearcli("engine", "build", XDG_CACHE_HOME=str(xdg))
    assert res.returncode == 0, res.stderr
    err = res.stderr.splitlines()
    cdir = str(xdg / "gearcli" / "numba")
    assert err[0].startswith("gearcli: compiling the integration engine (its first use here; cached in " + cdir)
    assert re.fullmatch(r"gearcli: compiled the integration engine in \d+\.\d s \(measured now; later runs load it "
                        r"from .*\)", err[-1])
    assert "about a minute" not in res.stderr
    assert res.stdout.startswith("engine: compiled in ")
    # a run after it compiles nothing, and says nothing about it
    run = _gearcli("simulate", str(SEED), "--format", "json", "--set", "simulation.engine=compiled",
                   "--set", "simulation.duration_s=0.05", "--set", "simulation.steps=50", XDG_CACHE_HOME=str(xdg))
    assert run.returncode == 0 and "compil" not in run.stderr, run.stderr
