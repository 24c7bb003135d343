"""Ctrl-C and SIGTERM during `gearcli simulate -o FILE`: exit 130 (143) with one line on stderr, no
traceback, no output file and no temporary file left behind; an existing FILE is left exactly as it was
(docs/output.md, "Files").

A real process and a real signal: the integration loop is Python code (scipy's solvers calling the
generated right-hand side), so the signal surfaces as an exception between two evaluations, and the CLI
maps it; `-o` is written atomically only after the run, so nothing is on disk yet. The run is the 10 s
scene stretched to 30 s with a 2 um transmission error on the Python engine (~45 s of integration on an idle
machine: the excitation keeps Radau's steps short, where the unexcited scene stretched to 600 s settled and took
long steps, done in ~1 s of computing, before its progress bar showed on an idle machine; `auto` would take the
compiled kernel for so long a run and finish it in seconds: tests/engine/test_signals.py signals that one). Deterministic: stderr is a terminal (a pseudo-terminal, as for a user pressing Ctrl-C),
so the run shows its progress bar, which appears only once the run has reported progress for a second
(gearcli.io.progress.SHOW_AFTER_S); the signal is sent when the bar is on the screen, i.e. with the
integration under way, never on a fixed sleep that a loaded machine can outlast (a signal sent 0.2 s after
the design warning, to a run `auto` had put on the warm compiled kernel, could arrive once the run was
over: exit 0). What the terminal shows is read as a terminal shows it (escape sequences and carriage
returns applied): its last line must be gearcli's one line.
"""

from __future__ import annotations

import os
import re
import select
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

LONG_RUN = Path(__file__).resolve().parents[2] / "configs" / "extreme" / "long_run.toml"
pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
CSI = re.compile(r"\x1b\[[0-9;?]*[A-Za-z]")  # the terminal's control sequences (cursor, colour, erase line)
BAR = re.compile(rb"\x1b\[2Ksimulate ")  # the progress bar's line drawn (erase the line, then its label)


def screen(raw: bytes) -> str:
    """The lines a terminal shows for ``raw``: control sequences applied (dropped), a carriage return starts the
    line again (the progress bar redraws itself so), empty lines left out."""
    text = CSI.sub("", raw.decode("utf-8", "replace")).replace("\r\n", "\n")
    lines = (line.split("\r")[-1] for line in text.split("\n"))
    return "\n".join(line for line in lines if line.strip())


def _read(fd: int, timeout: float) -> bytes:
    """What the pseudo-terminal has within ``timeout`` s (b"" at its end: the child closed it)."""
    if not select.select([fd], [], [], timeout)[0]:
        return b""
    try:
        return os.read(fd, 65536)
    except OSError:  # EIO: every writer has gone
        return b""


def interrupt_run(cmd: list[str], cwd: Path, sig: int) -> subprocess.CompletedProcess:
    """``cmd`` with stdout a pipe and stderr a terminal, ``sig`` sent once its progress bar shows; stderr as shown."""
    import pty

    leader, follower = pty.openpty()
    proc = subprocess.Popen(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=follower)
    os.close(follower)
    raw, out = b"", b""
    try:
        deadline = time.monotonic() + 120
        while not BAR.search(raw):  # the progress bar: the run is under way
            assert proc.poll() is None, f"the run ended before it could be interrupted: {screen(raw)}"
            assert time.monotonic() < deadline, f"no progress bar within 120 s: {screen(raw)}"
            raw += _read(leader, 1.0)
        assert screen(raw).startswith("warning: output speed"), screen(raw)  # the design's warning came first
        proc.send_signal(sig)
        out, _ = proc.communicate(timeout=60)
        while chunk := _read(leader, 1.0):  # the rest the child wrote before it went
            raw += chunk
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.communicate(timeout=10)
        os.close(leader)
    return subprocess.CompletedProcess(cmd, proc.returncode, out.decode(), screen(raw))


def interrupt_simulate(cwd: Path, sig: int = signal.SIGINT) -> subprocess.CompletedProcess:
    cmd = [sys.executable, "-m", "gearcli", "simulate", str(LONG_RUN), "-o", "OUT.csv",
           "--set", "simulation.duration_s=30", "--set", "contact.transmission_error_um=[2.0]",
           "--set", "target.output_speed_rpm=1",
           "--set", "simulation.engine=python"]  # scipy's loop: auto may take the compiled kernel, done in < 1 s
    return interrupt_run(cmd, cwd, sig)


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
    # the signal lands once the bytes are written, before the rename: the handler raises Terminated there
    from gearcli.errors import Terminated
    from gearcli.io import atomic

    def terminated(src, dst):
        raise Terminated()

    monkeypatch.setattr(atomic.os, "replace", terminated)
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
