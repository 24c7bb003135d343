"""A tolerance study whose sweep process is killed outright (SIGKILL: ``kill -9``, the out-of-memory killer, a job's
time limit) mid-run: its pool workers end with it, and the same command run again finishes the set.

No handler runs on SIGKILL, so the sweep cannot end its workers itself. They went on computing their tasks' points
for nobody and then waited for ever (seen in the tr28e trial: two workers and the forkserver still there minutes
later, one blocked writing rows into the pipe nobody read, one reading a task queue nobody filled: every worker holds
both ends of the pool's queues, so neither sees an end of file), each holding its ~100 MB, and competing for the
cores with the re-run. The file keeps whole rows only (a row is written at once), and the re-run computes the rest.
"""

from __future__ import annotations

import csv
import io
import math
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="process groups, /proc")

SCENE = Path(__file__).parent / "data" / "tr28e_stage.toml"  # 21/67, m_n 3, beta 14 deg, 2500 N m on the gear
N = 24


def _group(pgid: int) -> list[int]:
    """The live (not zombie) processes of process group ``pgid``."""
    out = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[2]) == pgid and fields[0] != "Z":
            out.append(int(entry.name))
    return out


def _rows(path: Path) -> list[dict]:
    text = path.read_text(encoding="utf-8")
    return list(csv.DictReader(io.StringIO("".join(ln for ln in text.splitlines(True) if not ln.startswith("#")))))


def test_a_killed_sweep_leaves_no_worker_and_its_rerun_finishes_the_set(tmp_path):
    scene, out = SCENE, tmp_path / "study.csv"
    cmd = [sys.executable, "-m", "gearcli", "-q", "sweep", str(scene), "--samples", str(N), "--seed", "28",
           "--random", "stage.0.gear.face_width_mm=normal(42,1)", "--random", "stage.0.normal_module_mm=normal(3,0.01)",
           "--jobs", "2", "-o", str(out)]
    proc = subprocess.Popen(cmd, start_new_session=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    try:
        deadline = time.monotonic() + 120
        while time.monotonic() < deadline and proc.poll() is None:
            if out.exists() and len(_rows(out)) >= 1:
                break
            time.sleep(0.05)
        assert proc.poll() is None, "the sweep ended before it could be killed mid-run"
        os.kill(proc.pid, signal.SIGKILL)
        proc.wait(timeout=10)
        deadline = time.monotonic() + 20
        while _group(proc.pid) and time.monotonic() < deadline:
            time.sleep(0.1)
        left = _group(proc.pid)
        assert not left, f"processes of the killed sweep still running: {left}"
    finally:
        if _group(proc.pid):
            os.killpg(proc.pid, signal.SIGKILL)
        proc.stderr.close()
    kept = _rows(out)
    assert 1 <= len(kept) < N and all(r["status"] == "ok" for r in kept)

    done = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
    rows = _rows(out)
    assert len(rows) == N and all(r["status"] == "ok" for r in rows)
    for r in rows:  # every row the equilibrium: the output torque over the drawn gear's pitch radius, by hand
        d2 = 67 * float(r["stage.0.normal_module_mm"]) / math.cos(math.radians(14.0))  # mm
        f_t = 2500.0 / (d2 / 2e3)
        assert float(r["stage1_tangential_N_mean"]) == pytest.approx(f_t, rel=1e-9)
        assert float(r["stage1_tangential_N_std"]) == pytest.approx(0.0, abs=1e-9 * f_t)
