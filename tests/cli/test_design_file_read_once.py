"""``gearcli life`` and ``gearcli sweep`` read the design file once, as ``design``, ``simulate``, ``modes`` and
``report`` do (trial tr30a, 2026-12-01). They read it for its hash, then again to parse it: a file that can be read
once, a pipe (the shell's ``gearcli life <(sed ... f.toml)``, ``/dev/fd/63``), had nothing the second time and was
refused, exit 2 "is a FIFO with nothing written to it (no writer)", while ``design <(...)`` ran; and a file rewritten
between the two reads would have been parsed from other bytes than those its ``input_sha256`` names.

The reference is the pipe's bytes hashed here by ``hashlib``: the run's ``input_sha256`` is theirs."""

from __future__ import annotations

import hashlib
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _through_a_pipe(text: bytes, *args: str) -> subprocess.CompletedProcess:
    """``gearcli ARGS`` with the design file a pipe holding ``text``, its writer gone (the whole file in the pipe's
    buffer), named /dev/fd/N as a shell's process substitution names it."""
    read_end, write_end = os.pipe()
    try:
        assert len(text) < 60_000  # the pipe's buffer holds it whole
        os.write(write_end, text)
        os.close(write_end)
        write_end = -1
        return subprocess.run([sys.executable, "-m", "gearcli", *(a.replace("PIPE", f"/dev/fd/{read_end}")
                                                                   for a in args)],
                              pass_fds=(read_end,), capture_output=True, text=True, timeout=180, cwd=ROOT)
    finally:
        os.close(read_end)
        if write_end >= 0:
            os.close(write_end)


@pytest.mark.skipif(not Path("/dev/fd").is_dir(), reason="a pipe named /dev/fd/N")
def test_life_reads_a_piped_design_file_once():
    text = (ROOT / "configs" / "mixer_duty.toml").read_bytes()
    res = _through_a_pipe(text, "life", "PIPE", "--static", "--format", "json", "-q")
    assert res.returncode == 0, res.stderr
    assert json.loads(res.stdout)["input_sha256"] == hashlib.sha256(text).hexdigest()


@pytest.mark.skipif(not Path("/dev/fd").is_dir(), reason="a pipe named /dev/fd/N")
def test_sweep_reads_a_piped_design_file_once():
    text = (ROOT / "configs" / "industrial_two_stage.toml").read_bytes()
    res = _through_a_pipe(text, "sweep", "PIPE", "--vary", "input.speed_rpm=1450", "--set", "simulation.steps=200",
                          "--set", "simulation.duration_s=0.05", "--jobs", "1", "--format", "json", "-q")
    assert res.returncode == 0, res.stderr
    doc = json.loads(res.stdout)
    sets = b"\0--set simulation.steps=200\0--set simulation.duration_s=0.05"  # docs/output.md, "Provenance"
    assert doc["input_sha256"] == hashlib.sha256(text + sets).hexdigest()
    assert [(r["input.speed_rpm"], r["status"]) for r in doc["rows"]] == [(1450, "ok")]
