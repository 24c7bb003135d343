"""A Ctrl-C during the start-up imports of numpy and scipy (gearcli/__main__.py) is acted on once they return.

A KeyboardInterrupt raised inside a C extension's initialisation is that extension's to handle: scipy's pybind11
modules (HiGHS, which scipy.integrate imports through scipy.optimize) made it "ImportError: initialization failed"
(exit 1 and a traceback; a timed SIGINT 1.4 s into a compiled ``simulate`` under load) or aborted the process
("terminate called after throwing an instance of 'pybind11::error_already_set'", exit 134). Whether a signal lands
inside such an initialisation is a matter of microseconds; what is tested is the rule that rules it out: a SIGINT
sent as ``scipy.integrate`` starts importing (an audit hook) leaves the import to finish whole, HiGHS's module
included, and then the run says "gearcli: interrupted" and exits 130.
"""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SEED = str(ROOT / "configs" / "concrete_mixer.toml")

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")

CHILD = textwrap.dedent("""
    import atexit, os, runpy, signal, sys

    SENT = []


    def at_scipy_integrate(event, args):
        if event == "import" and args[0] == "scipy.integrate" and not SENT:
            SENT.append(1)
            os.kill(os.getpid(), signal.SIGINT)


    @atexit.register
    def whole():
        print("sent:", bool(SENT), "HiGHS imported:", "scipy.optimize._highspy._core" in sys.modules, flush=True)


    sys.addaudithook(at_scipy_integrate)
    sys.argv = ["gearcli", *sys.argv[1:]]
    runpy.run_module("gearcli", run_name="__main__")
""")


@pytest.mark.parametrize("command", ["simulate", "life"])
def test_a_ctrl_c_as_scipy_loads_waits_for_its_import_then_interrupts(tmp_path, command):
    pytest.importorskip("scipy.optimize._highspy._core")  # the pybind11 module the rule protects
    script = tmp_path / "child.py"
    script.write_text(CHILD, encoding="utf-8")
    config = SEED if command == "simulate" else str(ROOT / "configs" / "mixer_duty.toml")
    env = dict(os.environ, PYTHONPATH=str(ROOT), XDG_CACHE_HOME=str(tmp_path / "cache"))
    proc = subprocess.run([sys.executable, str(script), command, config, "-q", "-o", "out.csv"], cwd=tmp_path,
                          env=env, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 130, proc.stderr
    assert proc.stderr.strip().splitlines() == ["gearcli: interrupted"], proc.stderr
    assert proc.stdout.strip() == "sent: True HiGHS imported: True"  # the import finished before the interrupt
    assert not (tmp_path / "out.csv").exists()
