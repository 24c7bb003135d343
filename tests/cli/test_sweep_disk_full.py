"""A sweep whose `-o` file the disk stops taking mid-sweep (a full disk; here a file-size limit, RLIMIT_FSIZE, which
makes write() fail with EFBIG exactly as ENOSPC would, with SIGXFSZ ignored) ends as every refused `-o` does
(docs/output.md, "Exit codes": exit 2, one line naming the file, no traceback), keeps whole rows only, and a run of
the same command with room again completes the file with the same rows as a sweep never interrupted.

Before the fix: "gearcli: internal error: OSError: [Errno 27] File too large", exit 1, and the file ended in the
middle of a row.
"""

from __future__ import annotations

import csv
import os
import resource
import signal
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SEED = ROOT / "configs" / "concrete_mixer.toml"
SWEEP = ["--vary", "input.speed_rpm=400:700:8", "--jobs", "1", "--set", "simulation.duration_s=0.05",
         "--set", "simulation.steps=50"]
LIMIT = 3072  # bytes: the identity line, the header and a few of the eight rows

pytestmark = pytest.mark.skipif(not hasattr(resource, "RLIMIT_FSIZE") or not hasattr(signal, "SIGXFSZ"),
                                reason="needs RLIMIT_FSIZE and SIGXFSZ (POSIX)")


def _limited() -> None:
    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # write() then fails with EFBIG instead of killing the process
    resource.setrlimit(resource.RLIMIT_FSIZE, (LIMIT, LIMIT))


def _sweep(out: Path, limited: bool) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    return subprocess.run([sys.executable, "-m", "gearcli", "-q", "sweep", str(SEED), *SWEEP, "-o", str(out)],
                          capture_output=True, text=True, env=env, timeout=300,
                          preexec_fn=_limited if limited else None)


def _rows(path: Path) -> list[list[str]]:
    with path.open(encoding="utf-8", newline="") as fh:
        return list(csv.reader(line for line in fh if not line.startswith("#")))


def _comparable(rows: list[list[str]]) -> list[list[str]]:
    wall = rows[0].index("wall_s")
    return [r[:wall] + r[wall + 1:] for r in rows]


@pytest.mark.parametrize("suffix", [".csv", ".json"])
def test_full_disk_mid_sweep(tmp_path, suffix):
    out = tmp_path / f"sweep{suffix}"
    res = _sweep(out, limited=True)
    assert res.returncode == 2, res.stderr
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1 and "cannot write" in lines[0] and str(out.name) in lines[0], res.stderr
    assert "Traceback" not in res.stderr and "internal error" not in res.stderr
    assert not [p for p in tmp_path.iterdir() if p != out]  # no temporary file left behind
    if suffix == ".csv":
        rows = _rows(out)
        assert 1 <= len(rows) < 9  # the header and the rows that fitted
        assert {len(r) for r in rows} == {len(rows[0])}  # whole rows only: none cut by the full disk
        assert out.read_bytes().endswith(b"\n")


def test_resumed_after_full_disk_equals_uninterrupted(tmp_path):
    cut, whole = tmp_path / "cut.csv", tmp_path / "whole.csv"
    assert _sweep(cut, limited=True).returncode == 2
    assert _sweep(cut, limited=False).returncode == 0
    assert _sweep(whole, limited=False).returncode == 0
    assert _comparable(_rows(cut)) == _comparable(_rows(whole))
    assert len(_rows(whole)) == 9
