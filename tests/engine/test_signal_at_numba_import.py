"""A Ctrl-C while numba is being imported (the probe before a compiled run: :func:`gearcli.engine.import_problem`).

numba's C extension ``numba._dispatcher`` imports ``numba._devicearray`` from its initialisation and prints a
failure itself (``PyErr_Print``): a KeyboardInterrupt raised in that import was a traceback on stderr (ending in
``_find_and_load``; CI met it 0.76 s into a compiled ``simulate``, 1 of 18 timed SIGINTs), then "ImportError:
numba._devicearray failed to import", which the probe took for a broken numba: ``engine = "auto"`` went on in
Python with the Ctrl-C dropped (exit 0, the engine's reason "numba is installed but cannot be imported").

The SIGINT is sent at that very import (an audit hook on the import of ``numba._devicearray``), not after a delay:
each run hits the moment. The run must say "gearcli: interrupted" and exit 130, with no traceback.
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

pytestmark = pytest.mark.skipif(not hasattr(os, "kill") or sys.platform == "win32", reason="POSIX signals")

HOOK = textwrap.dedent("""
    import os, signal, sys

    HIT = []


    def at_the_import(event, args):
        if event == "import" and args[0] == "numba._devicearray" and not HIT:
            HIT.append(1)
            os.kill(os.getpid(), signal.SIGINT)


    sys.addaudithook(at_the_import)
""")

CLI = HOOK + textwrap.dedent("""
    import runpy

    sys.argv = ["gearcli", *sys.argv[1:]]
    runpy.run_module("gearcli", run_name="__main__")
""")

# the probe alone, under the console script's SIGINT handler: auto's path (a run that would go compiled probes it)
PROBE = HOOK + textwrap.dedent("""
    from gearcli.cli.common import on_sigint
    from gearcli import engine

    signal.signal(signal.SIGINT, on_sigint)
    try:
        why = engine.import_problem()
    except KeyboardInterrupt:
        print("interrupted after the import:", "numba" in sys.modules, bool(HIT))
    else:
        print("not interrupted:", why)
""")


def _run(tmp_path: Path, script: str, *args: str) -> subprocess.CompletedProcess:
    path = tmp_path / "child.py"
    path.write_text(script, encoding="utf-8")
    env = dict(os.environ, PYTHONPATH=str(ROOT), XDG_CACHE_HOME=str(tmp_path / "cache"))
    return subprocess.run([sys.executable, str(path), *args], cwd=tmp_path, env=env, capture_output=True, text=True,
                          timeout=300)


def test_a_compiled_run_interrupted_inside_numbas_import_says_interrupted(tmp_path):
    pytest.importorskip("numba")
    proc = _run(tmp_path, CLI, "simulate", SEED, "--set", "simulation.engine=compiled", "-q", "-o", "out.json")
    assert proc.returncode == 130, proc.stderr
    assert proc.stderr.strip().splitlines() == ["gearcli: interrupted"], proc.stderr
    assert not (tmp_path / "out.json").exists()
    assert not list((tmp_path / "cache").rglob("ready.json"))  # stopped before any build of the engine


def test_the_probe_interrupted_inside_numbas_import_raises_the_interrupt_after_it(tmp_path):
    pytest.importorskip("numba")
    proc = _run(tmp_path, PROBE)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.strip() == "interrupted after the import: True True"  # numba imported whole, then the Ctrl-C
    assert "Traceback" not in proc.stderr and "KeyboardInterrupt" not in proc.stderr, proc.stderr
