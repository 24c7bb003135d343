"""A signal whose exception Python cannot propagate (raised inside a weakref callback, as the import system's
module-lock callback did when SIGTERM arrived 0.35 s into `gearcli life`: "Exception ignored in:
<function _get_module_lock.<locals>.cb>", the whole run done, exit 0) still ends the command: the console
script's unraisable hook sends the signal again, and its handler unwinds the code the callback interrupted."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

SCRIPT = r"""
import signal, sys, time, weakref
from gearcli.cli import common
from gearcli.errors import Terminated

signal.signal(signal.SIGTERM, common.on_sigterm)   # what gearcli.cli.main installs
signal.signal(signal.SIGINT, common.on_sigint)
sys.unraisablehook = common.on_unraisable

class Held:
    pass

def arrives_in_the_callback(_):
    common.on_sigterm(signal.SIGTERM, None)  # the handler, run where the signal landed: inside the callback

try:
    held = Held()
    ref = weakref.ref(held, arrives_in_the_callback)
    del held  # the callback runs; its Terminated cannot propagate
    t0 = time.monotonic()
    while time.monotonic() - t0 < 5.0:  # the command's own work, which the signal must interrupt
        time.sleep(0.001)
    print("ran to the end")
except Terminated:
    print("terminated", common._SIGNALLED)
"""


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
def test_a_signal_dropped_in_a_callback_still_ends_the_command():
    res = subprocess.run([sys.executable, "-c", SCRIPT], capture_output=True, text=True, timeout=60,
                         env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"})
    assert res.stdout.strip() == "terminated [143]", res.stdout + res.stderr
    assert "Exception ignored" not in res.stderr and "Traceback" not in res.stderr


OTHER = r"""
import sys, weakref
from gearcli.cli import common

sys.unraisablehook = common.on_unraisable

class Held:
    pass

def fails(_):
    raise ValueError("boom")

held = Held()
ref = weakref.ref(held, fails)
del held
print("went on")
"""


def test_other_unraisable_exceptions_keep_pythons_report():
    res = subprocess.run([sys.executable, "-c", OTHER], capture_output=True, text=True, timeout=60,
                         env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"})
    assert res.returncode == 0 and res.stdout.strip() == "went on"
    assert "Exception ignored" in res.stderr and "ValueError: boom" in res.stderr
