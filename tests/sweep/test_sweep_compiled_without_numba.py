"""A local sweep that asks for ``engine = "compiled"`` where numba, the ``fast`` extra, is missing or cannot be
imported: DESIGN §6 makes that "a clear usage error naming the extra to install" (exit 2, §5), as ``simulate``,
``report`` and ``life`` give it. The sweep gave instead one ``failed`` row per point and exit 1, and wrote its output
file: the same refusal repeated for every point of a grid that could never run."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli import engine
from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]
SEED = ROOT / "configs" / "concrete_mixer.toml"
VARY = ["--vary", "input.speed_deg_s=3000,3600", "--jobs", "1"]


@pytest.fixture
def no_numba(monkeypatch):
    """numba not installed: what ``find_spec`` says on a machine without the extra."""
    monkeypatch.setattr(engine, "available", lambda: False)


@pytest.mark.parametrize(("options", "named"), [
    (["--set", "simulation.engine=compiled"], "--set: simulation.engine"),
    (["--vary", "simulation.engine=python,compiled"], "--vary: simulation.engine"),
])
def test_compiled_without_numba_is_exit_2_before_any_point(no_numba, tmp_path, options, named):
    out = tmp_path / "rows.csv"
    res = CliRunner().invoke(cli, ["sweep", str(SEED), *VARY, *options, "-o", str(out)])
    assert res.exit_code == 2, res.output
    assert named in res.output and "gearcli[fast]" in res.output and "Traceback" not in res.output
    assert not out.exists()  # refused before any point ran: no file, no failed rows


def test_the_file_s_own_engine_is_named_with_the_file(no_numba, tmp_path):
    design = tmp_path / "compiled.toml"
    design.write_text(SEED.read_text().replace('method = "auto"', 'method = "auto"\nengine = "compiled"'))
    res = CliRunner().invoke(cli, ["sweep", str(design), *VARY, "-o", str(tmp_path / "rows.csv")])
    assert res.exit_code == 2, res.output
    assert f"{design}: simulation.engine" in res.output and "gearcli[fast]" in res.output


def test_points_that_do_not_ask_for_it_still_run_on_python(no_numba, tmp_path):
    out = tmp_path / "rows.csv"
    res = CliRunner().invoke(cli, ["sweep", str(SEED), "--vary", "simulation.engine=python,auto", "--jobs", "1",
                                   "-o", str(out)])
    assert res.exit_code == 0, res.output
    assert out.read_text().count(",ok,") == 2


def test_numba_installed_but_not_importable_names_its_error(tmp_path):
    """A numba that cannot be imported (built for another numpy: a shim whose import raises), in a fresh process."""
    shim = tmp_path / "shim" / "numba"
    shim.mkdir(parents=True)
    (shim / "__init__.py").write_text('raise ImportError("numba built against another numpy")\n')
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(tmp_path / "shim"), str(ROOT)]),
               XDG_CACHE_HOME=str(tmp_path / "cache"))
    proc = subprocess.run([sys.executable, "-m", "gearcli", "sweep", str(SEED), *VARY, "--set",
                           "simulation.engine=compiled", "-o", "rows.csv"], cwd=tmp_path, env=env,
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 2, proc.stderr
    assert "--set: simulation.engine" in proc.stderr and "numba built against another numpy" in proc.stderr
    assert "Traceback" not in proc.stderr and not (tmp_path / "rows.csv").exists()
