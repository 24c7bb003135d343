"""``--debug`` shows the traceback (README, docs/usage.md, docs/plugins.md): through the console script's ``main()``,
which catches gearcli's own errors for click's output, a bad design file under ``--debug`` printed the one line and
no traceback, and a plug-in's bug no line of the plug-in. With ``--debug`` the traceback comes first, then the same
one line and the same exit code; without it, the line alone."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SEED = (ROOT / "configs" / "concrete_mixer.toml").read_text()


def _run(*args: str) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    return subprocess.run([sys.executable, "-m", "gearcli", *args], capture_output=True, text=True, env=env,
                          timeout=120, check=False)


@pytest.mark.parametrize("where", ["before", "after"])
def test_debug_shows_the_traceback_of_a_bad_design_file_then_its_line(tmp_path, where):
    bad = tmp_path / "bad.toml"
    bad.write_text(SEED.replace("teeth = 21", "teeth = 3"), encoding="utf-8")
    line = f"gearcli: {bad}: stage[0].pinion.teeth: must be ≥ 5, got 3"
    args = ["--debug", "design", str(bad)] if where == "before" else ["design", str(bad), "--debug"]
    r = _run(*args)
    assert r.returncode == 2, r.stderr
    assert r.stderr.startswith("Traceback (most recent call last):") and "ConfigError" in r.stderr
    assert r.stderr.rstrip().endswith(line)


def test_without_debug_a_bad_design_file_is_its_line_alone(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(SEED.replace("teeth = 21", "teeth = 3"), encoding="utf-8")
    plain = _run("design", str(bad))
    assert plain.returncode == 2 and plain.stderr.strip() == f"gearcli: {bad}: stage[0].pinion.teeth: must be ≥ 5, got 3"
