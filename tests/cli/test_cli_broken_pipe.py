"""`gearcli ... | head -1`: when the reader of stdout goes away, every command exits 141 (128 + SIGPIPE, what a
shell reports for a program SIGPIPE killed) and prints nothing: no traceback, no "internal error", no
"Exception ignored" from the interpreter's last flush (docs/output.md, "Exit codes")."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SEED = str(ROOT / "configs" / "concrete_mixer.toml")
SHORT = ["--set", "simulation.duration_s=0.05", "--set", "simulation.steps=50"]
COMMANDS = {
    "design": ["design", SEED],
    "design-json": ["design", SEED, "--format", "json"],
    "simulate": ["simulate", SEED, "--format", "csv", *SHORT],
    "report": ["report", SEED, "--quick", *SHORT],
    "modes": ["modes", SEED],
    "sweep": ["sweep", SEED, "--vary", "input.speed_rpm=500,600", "--jobs", "1", *SHORT],
    "schema": ["schema"],
    "init": ["init", "-"],
    "help": ["--help"],
    "design-help": ["design", "--help"],
    "version": ["--version"],
}


@pytest.mark.parametrize("name", COMMANDS)
def test_a_closed_pipe_exits_141_quietly(name, tmp_path):
    r, w = os.pipe()
    os.close(r)  # the reader is gone before gearcli writes a byte
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    with open(tmp_path / "stderr", "wb") as err:
        proc = subprocess.run([sys.executable, "-m", "gearcli", "-q", *COMMANDS[name]], stdout=w, stderr=err,
                              env=env, timeout=120)
    os.close(w)
    stderr = (tmp_path / "stderr").read_text()
    assert proc.returncode == 141, (proc.returncode, stderr)
    assert stderr.strip() in ("", "sweep: 2 points, 0 failed"), stderr  # sweep's summary is on stderr


def test_a_reader_that_goes_away_mid_output_exits_141(tmp_path):
    """`gearcli simulate f.toml | head -1`: the reader takes the first bytes and leaves while gearcli's write
    of a CSV several times the pipe's 64 KiB waits in the pipe. The kernel lets that write through partly and
    sends SIGPIPE (ignored by Python); CPython's buffered writer returned the short count without an error and the
    text layer dropped the rest, so the cut output ended as exit 0. The rest must meet EPIPE: exit 141, quiet."""
    r, w = os.pipe()
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    with open(tmp_path / "stderr", "wb") as err:
        # 0.05 s at 4000 steps: 4001 rows of 21 columns, about 1 MB of CSV
        proc = subprocess.Popen([sys.executable, "-m", "gearcli", "-q", "simulate", SEED, "--format", "csv",
                                 "--set", "simulation.duration_s=0.05", "--set", "simulation.steps=4000"],
                                stdout=w, stderr=err, env=env)
        os.close(w)
        first = os.read(r, 64)  # blocks until gearcli has begun to write
        os.close(r)
        code = proc.wait(timeout=120)
    assert first.startswith(b"time_s,")
    assert code == 141, (tmp_path / "stderr").read_text()
    assert (tmp_path / "stderr").read_text().strip() == ""
