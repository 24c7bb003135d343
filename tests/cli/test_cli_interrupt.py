"""Ctrl-C and SIGTERM during `gearcli simulate -o FILE`: exit 130 (143) with one line on stderr, no
traceback, no output file and no temporary file left behind; an existing FILE is left exactly as it was
(docs/output.md, "Files").

A real process and a real signal: the integration loop is Python code (scipy's solvers calling the
generated right-hand side), so the signal surfaces as an exception between two evaluations, and the CLI
maps it; `-o` is written atomically only after the run, so nothing is on disk yet. The run is the 10 s
scene stretched to 200 s (~25 s of integration). Deterministic: the signal is sent only once the process
has printed its design warning (a `[target]` it misses), i.e. once gearcli's handlers are in place and
the run is under way, never on a fixed sleep that a loaded machine can outlast.
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


def interrupt_simulate(cwd: Path, sig: int = signal.SIGINT) -> subprocess.CompletedProcess:
    cmd = [sys.executable, "-m", "gearcli", "simulate", str(LONG_RUN), "-o", "OUT.csv",
           "--set", "simulation.duration_s=200", "--set", "target.output_speed_rpm=1"]
    proc = subprocess.Popen(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert proc.stderr is not None
        ready = proc.stderr.readline()  # blocks until the design warning: the run is under way
        assert ready.startswith("warning: output speed"), ready
        time.sleep(0.2)  # into the scipy import or the integration; both map the signal the same way
        assert proc.poll() is None, "the run ended before it could be interrupted"
        proc.send_signal(sig)
        out, err = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
    return subprocess.CompletedProcess(cmd, proc.returncode, out, ready + err)


def test_ctrl_c_exits_130_and_leaves_no_file(tmp_path):
    res = interrupt_simulate(tmp_path)
    assert res.returncode == 130, res.stderr
    assert res.stderr.strip().splitlines()[-1] == "gearcli: interrupted"
    assert "Traceback" not in res.stderr and res.stdout == ""
    assert os.listdir(tmp_path) == []  # neither OUT.csv nor a .OUT.csv.*.tmp


def test_sigterm_exits_143_and_leaves_no_file(tmp_path):
    res = interrupt_simulate(tmp_path, signal.SIGTERM)
    assert res.returncode == 143, res.stderr
    assert res.stderr.strip().splitlines()[-1] == "gearcli: terminated"
    assert "Traceback" not in res.stderr and res.stdout == ""
    assert os.listdir(tmp_path) == []


def test_sigterm_during_the_write_removes_the_temporary_file(tmp_path, monkeypatch):
    # the signal lands while the bytes are being written: the handler raises Terminated there
    from gearcli.errors import Terminated
    from gearcli.io import atomic

    def terminated(fd):
        raise Terminated()

    monkeypatch.setattr(atomic.os, "fsync", terminated)
    (tmp_path / "OUT.csv").write_text("old\n")
    with pytest.raises(Terminated):
        atomic.write_atomic(tmp_path / "OUT.csv", "x" * 1_000_000)
    assert os.listdir(tmp_path) == ["OUT.csv"] and (tmp_path / "OUT.csv").read_text() == "old\n"


def test_the_console_script_installs_the_sigterm_handler(monkeypatch):
    import gearcli.cli as cli_module

    installed = {}
    monkeypatch.setattr(signal, "signal", lambda sig, handler: installed.setdefault(sig, handler))
    monkeypatch.setattr(cli_module, "cli", lambda **kw: None)
    cli_module.main()
    from gearcli.errors import Terminated

    with pytest.raises(Terminated):
        installed[signal.SIGTERM](signal.SIGTERM, None)


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
