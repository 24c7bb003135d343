"""Ctrl-C during `gearcli simulate -o FILE`: exit 130 with one line on stderr, no traceback, no output
file and no temporary file left behind; an existing FILE is left exactly as it was (DESIGN.md section 5).

A real process and a real SIGINT: the integration loop is Python code (scipy's solvers calling the
generated right-hand side), so the interrupt surfaces as KeyboardInterrupt between two evaluations, and
the CLI maps it to exit 130; `-o` is written atomically only after the run, so nothing is on disk yet.
The run is the 10 s scene stretched to 200 s (~25 s of integration), so SIGINT after ~1 s always lands
in the integration, well past the interpreter's start-up.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

LONG_RUN = Path(__file__).resolve().parents[2] / "configs" / "extreme" / "long_run.toml"
pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")


def interrupt_simulate(cwd: Path, *, after_s: float = 1.0) -> subprocess.CompletedProcess:
    cmd = [sys.executable, "-m", "gearcli", "simulate", str(LONG_RUN), "-o", "OUT.csv",
           "--set", "simulation.duration_s=200"]
    proc = subprocess.Popen(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(after_s)
    assert proc.poll() is None, "the run ended before it could be interrupted"
    proc.send_signal(signal.SIGINT)
    try:
        out, err = proc.communicate(timeout=30)
    finally:
        if proc.poll() is None:
            proc.kill()
    return subprocess.CompletedProcess(cmd, proc.returncode, out, err)


def test_ctrl_c_exits_130_and_leaves_no_file(tmp_path):
    res = interrupt_simulate(tmp_path)
    assert res.returncode == 130, res.stderr
    assert res.stderr.strip().splitlines()[-1] == "gearcli: interrupted"
    assert "Traceback" not in res.stderr and res.stdout == ""
    assert os.listdir(tmp_path) == []  # neither OUT.csv nor a .OUT.csv.*.tmp


def test_ctrl_c_leaves_an_existing_output_file_untouched(tmp_path):
    target = tmp_path / "OUT.csv"
    target.write_text("time_s,previous run\n0,1\n")
    before = target.stat()
    res = interrupt_simulate(tmp_path)
    assert res.returncode == 130, res.stderr
    assert target.read_text() == "time_s,previous run\n0,1\n"
    assert target.stat().st_mtime_ns == before.st_mtime_ns and target.stat().st_ino == before.st_ino
    assert sorted(os.listdir(tmp_path)) == ["OUT.csv"]


def test_ctrl_c_during_start_up_imports_is_exit_130_without_traceback(monkeypatch, capsys):
    # the interrupt arrives while gearcli.cli (click, pydantic, rich) is being imported: the entry point
    # must map it like any other interrupt. Simulated by making that import raise KeyboardInterrupt.
    import builtins

    from gearcli.__main__ import main

    real_import = builtins.__import__

    def interrupted_import(name, *args, **kwargs):
        if name == "gearcli.cli":
            raise KeyboardInterrupt
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", interrupted_import)
    with pytest.raises(SystemExit) as exc:
        main()
    assert exc.value.code == 130
    assert capsys.readouterr().err == "gearcli: interrupted\n"
