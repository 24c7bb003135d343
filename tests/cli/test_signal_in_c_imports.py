"""A Ctrl-C while a C extension initialises: acted on once the import returns, "gearcli: interrupted", exit 130.

A KeyboardInterrupt raised inside a C extension's initialisation is that extension's to handle, and two that gearcli
imports mishandle it:

- numba's ``numba._dispatcher`` imports ``numba._devicearray`` from its initialisation and prints a failure itself
  (``PyErr_Print``): a traceback ending in ``_find_and_load`` (CI: 1 of 18 timed SIGINTs, 0.76 s into a compiled
  ``simulate``), then "ImportError: numba._devicearray failed to import", which the probe before a compiled run
  (:func:`gearcli.engine.import_problem`) took for a broken numba: ``engine = "auto"`` went on in Python with the
  Ctrl-C dropped (exit 0, the engine's reason "numba is installed but cannot be imported").
- scipy's pybind11 modules (HiGHS, which scipy.integrate imports through scipy.optimize, at start-up:
  gearcli/__main__.py) made it "ImportError: initialization failed" (exit 1, a traceback; a timed SIGINT 1.4 s into
  a compiled ``simulate``) or aborted the process ("terminate called after throwing an instance of
  'pybind11::error_already_set'", exit 134).

Whether a timed signal lands inside an initialisation is a matter of microseconds; what is tested is the rule that
rules it out. The SIGINT is sent as the import starts (an audit hook on its "import" event), so every run hits it:
the import must finish whole, and the interrupt come after it.
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
DUTY = str(ROOT / "configs" / "mixer_duty.toml")

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")


def _child(module: str, body: str) -> str:
    """A script that sends itself SIGINT as ``module`` starts importing, reports at exit whether it did and whether
    ``whole`` (a module the import loads) is loaded, then runs ``body``."""
    return textwrap.dedent(f"""
        import atexit, os, signal, sys

        # a foreground process's SIGINT: one started in the background by a non-interactive shell (a CI runner's
        # `cmd &`) inherits SIGINT ignored, which Python and gearcli's start-up imports keep
        signal.signal(signal.SIGINT, signal.default_int_handler)
        SENT = []


        def at_the_import(event, args):
            if event == "import" and args[0] == {module!r} and not SENT:
                SENT.append(1)
                os.kill(os.getpid(), signal.SIGINT)


        @atexit.register
        def report():
            print("sent:", bool(SENT), "whole:", WHOLE in sys.modules, flush=True)


        sys.addaudithook(at_the_import)
    """) + textwrap.dedent(body)


GEARCLI = """
    import runpy

    sys.argv = ["gearcli", *sys.argv[1:]]
    runpy.run_module("gearcli", run_name="__main__")
"""

# the probe alone, under the console script's SIGINT handler: auto's path (a run that would go compiled probes it)
PROBE = """
    from gearcli.cli.common import on_sigint
    from gearcli import engine

    signal.signal(signal.SIGINT, on_sigint)
    try:
        why = engine.import_problem()
    except KeyboardInterrupt:
        print("interrupted after the import", flush=True)
    else:
        print("not interrupted:", why, flush=True)
"""


def _run(tmp_path: Path, script: str, whole: str, *args: str) -> subprocess.CompletedProcess:
    path = tmp_path / "child.py"
    path.write_text(f"WHOLE = {whole!r}\n" + script, encoding="utf-8")
    env = dict(os.environ, PYTHONPATH=str(ROOT), XDG_CACHE_HOME=str(tmp_path / "cache"))
    return subprocess.run([sys.executable, str(path), *args], cwd=tmp_path, env=env, capture_output=True, text=True,
                          timeout=300)


def _interrupted(proc: subprocess.CompletedProcess, tmp_path: Path) -> None:
    assert proc.returncode == 130, proc.stderr
    assert proc.stderr.strip().splitlines() == ["gearcli: interrupted"], proc.stderr
    assert proc.stdout.strip() == "sent: True whole: True"  # the import finished, then the interrupt came
    assert not (tmp_path / "out.csv").exists()


def test_a_compiled_run_interrupted_inside_numbas_import(tmp_path):
    pytest.importorskip("numba")
    proc = _run(tmp_path, _child("numba._devicearray", GEARCLI), "numba._dispatcher", "simulate", SEED, "--set",
                "simulation.engine=compiled", "-q", "-o", "out.csv")
    _interrupted(proc, tmp_path)
    assert not list((tmp_path / "cache").rglob("ready.json"))  # stopped before any build of the engine


def test_the_probe_interrupted_inside_numbas_import_raises_the_interrupt_after_it(tmp_path):
    pytest.importorskip("numba")
    proc = _run(tmp_path, _child("numba._devicearray", PROBE), "numba._dispatcher")
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.strip().splitlines() == ["interrupted after the import", "sent: True whole: True"]
    assert "Traceback" not in proc.stderr and "KeyboardInterrupt" not in proc.stderr, proc.stderr


@pytest.mark.parametrize(("command", "config"), [("simulate", SEED), ("life", DUTY)])
def test_a_ctrl_c_as_scipy_loads_at_start_up_waits_for_its_import(tmp_path, command, config):
    pytest.importorskip("scipy.optimize._highspy._core")  # the pybind11 module of the failures seen
    proc = _run(tmp_path, _child("scipy.integrate", GEARCLI), "scipy.optimize._highspy._core", command, config,
                "-q", "-o", "out.csv")
    _interrupted(proc, tmp_path)
