"""Ctrl-C on a terminal while a sweep's process pool starts: exit 130 with gearcli's one line, no traceback from
any process of the group, no process left behind (docs/output.md, "Exit codes"; DESIGN §5: no traceback).

A terminal sends SIGINT to the whole foreground process group: the sweep, its forkserver and the workers. The
forkserver imports its preload (numpy, scipy, gearcli: about half a second) before it ignores SIGINT itself, so a
Ctrl-C then printed its KeyboardInterrupt traceback; and a worker being launched when the sweep went printed a
FileNotFoundError traceback (it read its start after the sweep had unlinked its queues' semaphores). The signal is
sent once the forkserver has begun importing its preload (numpy mapped into it): deterministic, no fixed sleep.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="process group signals, /proc")

SCENE = """
[[stage]]
normal_module_mm = 5
normal_pressure_angle_deg = 20
helix_angle_deg = 15
pinion = { teeth = 23, face_width_mm = 60, hand = "left" }
gear   = { teeth = 67, face_width_mm = 55, hand = "right" }
[input]
speed_deg_s = 6000
ramp_s = 0.1
[load]
torque_Nmm = 2.0e6
ramp_s = 0.1
[simulation]
duration_s = 1.0
steps = 1000
"""


def _children(pid: int) -> list[tuple[int, str]]:
    """(pid, command line) of every process whose parent is ``pid``."""
    out = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            stat = (entry / "stat").read_text()
            ppid = int(stat.rsplit(")", 1)[1].split()[1])
            if ppid == pid:
                out.append((int(entry.name), (entry / "cmdline").read_bytes().replace(b"\0", b" ").decode()))
        except (OSError, ValueError, IndexError):
            continue
    return out


def _importing_preload(pid: int) -> bool:
    """The forkserver is importing its preload: numpy's compiled core is mapped (scipy and gearcli follow)."""
    try:
        return "_multiarray_umath" in Path(f"/proc/{pid}/maps").read_text()
    except OSError:
        return True  # gone: nothing more to wait for


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_a_signal_to_the_group_while_the_pool_starts_leaves_no_traceback(tmp_path, sig):
    scene = tmp_path / "two_stage.toml"
    scene.write_text(SCENE)
    cmd = [sys.executable, "-m", "gearcli", "sweep", str(scene), "--vary", "input.speed_deg_s=2000:6000:200",
           "--jobs", "2", "-o", str(tmp_path / "rows.csv")]
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, start_new_session=True)
    server = None
    try:
        deadline = time.monotonic() + 60
        while server is None and proc.poll() is None and time.monotonic() < deadline:
            server = next((p for p, c in _children(proc.pid) if "forkserver import main" in c), None)
            time.sleep(0.002)
        assert server is not None, "the sweep started no forkserver"
        while not _importing_preload(server) and proc.poll() is None and time.monotonic() < deadline:
            time.sleep(0.002)
        os.killpg(proc.pid, sig)  # as a terminal does: the whole group
        _, err = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.communicate(timeout=10)
    stderr = err.decode()
    expected = {signal.SIGINT: (130, "interrupted"), signal.SIGTERM: (143, "terminated")}[sig]
    assert proc.returncode == expected[0], stderr
    assert "Traceback" not in stderr and "Error" not in stderr, stderr
    assert stderr.rstrip().splitlines()[-1] == f"gearcli: {expected[1]}", stderr
    deadline = time.monotonic() + 10
    while os.path.exists(f"/proc/{server}") and time.monotonic() < deadline:  # the server goes with its parent
        time.sleep(0.05)
    if os.path.exists(f"/proc/{server}") and "Z" not in Path(f"/proc/{server}/stat").read_text().split()[2]:
        os.kill(server, signal.SIGKILL)  # do not leave it to the next test
        pytest.fail("the forkserver outlived the sweep")
