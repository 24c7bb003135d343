"""numba installed but not importable (built for another numpy, a broken install: here a shim on PYTHONPATH whose
import raises): `engine = "compiled"` and `gearcli engine build` are the documented usage error (exit 2) naming the
extra and numba's own error, never an attempted compilation that fails with exit 1; `auto` runs on Python."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from gearcli import engine
from gearcli.engine import loader
from tests.engine.test_choice import seed_arrays

ROOT = Path(__file__).resolve().parents[2]
SEED = str(ROOT / "configs" / "concrete_mixer.toml")


def _gearcli(tmp_path: Path, *args: str) -> subprocess.CompletedProcess:
    shim = tmp_path / "shim" / "numba"
    shim.mkdir(parents=True)
    (shim / "__init__.py").write_text('raise ImportError("numba built against another numpy")\n')
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(tmp_path / "shim"), str(ROOT)]),
               XDG_CACHE_HOME=str(tmp_path / "cache"))
    return subprocess.run([sys.executable, "-m", "gearcli", *args], cwd=tmp_path, env=env, capture_output=True,
                          text=True, timeout=300)


def test_compiled_run_is_a_usage_error_naming_the_extra(tmp_path):
    proc = _gearcli(tmp_path, "simulate", SEED, "--set", "simulation.engine=compiled", "-q", "-o", "out.json")
    assert proc.returncode == 2, proc.stderr
    assert "simulation.engine" in proc.stderr and "gearcli[fast]" in proc.stderr
    assert "numba built against another numpy" in proc.stderr and "Traceback" not in proc.stderr
    assert "compiling" not in proc.stderr  # no build attempted
    assert not (tmp_path / "out.json").exists()


def test_engine_build_is_a_usage_error_naming_the_extra(tmp_path):
    proc = _gearcli(tmp_path, "engine", "build")
    assert proc.returncode == 2, proc.stderr
    assert "gearcli[fast]" in proc.stderr and "numba built against another numpy" in proc.stderr
    assert "compiling" not in proc.stderr and "Traceback" not in proc.stderr


def test_auto_stays_on_python_with_the_reason(monkeypatch):
    monkeypatch.setattr(engine, "available", lambda: True)  # numba's package is found ...
    monkeypatch.setattr(engine, "import_problem", lambda: "ImportError: no")  # ... but does not import
    monkeypatch.delitem(loader._state, "loaded", raising=False)
    choice = engine.choose("auto", seed_arrays(), "DOP853", 1e9)  # a run long enough for auto to go compiled
    assert choice.engine == "python" and "cannot be imported" in choice.reason


@pytest.mark.parametrize("requested", ["auto", "python"])
def test_a_short_or_python_run_never_imports_numba_to_check(monkeypatch, requested):
    """The probe imports numba: only where the run would load the compiled engine anyway."""
    monkeypatch.setattr(engine, "import_problem", lambda: pytest.fail("probed numba"))
    monkeypatch.delitem(loader._state, "loaded", raising=False)
    assert engine.choose(requested, seed_arrays(), "DOP853", 10.0).engine == "python"
