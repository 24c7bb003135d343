"""`--plots` does not depend on the environment's matplotlib backend.

gearcli draws on matplotlib's Agg canvas and never selects a backend, so headless (no MPLBACKEND, no display) and
with any MPLBACKEND the figures are written. matplotlib validates MPLBACKEND when it is imported: before, a value
it does not know (a typo, a backend of another installation) made `gearcli modes --plots` exit 1 with
"internal error: ValueError: Key backend: 'nonsense' is not a valid value for backend".
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("matplotlib")

ROOT = Path(__file__).resolve().parents[2]
SEED = ROOT / "configs" / "concrete_mixer.toml"
PNG = b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize("backend", [None, "nonsense", "TkAgg"])
def test_modes_plots_whatever_mplbackend_says(tmp_path, backend):
    env = {k: v for k, v in os.environ.items() if k not in ("MPLBACKEND", "DISPLAY")}
    if backend is not None:
        env["MPLBACKEND"] = backend
    env["PYTHONPATH"] = str(ROOT) + os.pathsep + env.get("PYTHONPATH", "")
    out = tmp_path / "figs"
    res = subprocess.run([sys.executable, "-m", "gearcli", "-q", "modes", str(SEED), "--format", "json",
                          "--plots", str(out)], env=env, capture_output=True, text=True, timeout=120)
    assert res.returncode == 0, res.stderr
    assert "internal error" not in res.stderr
    assert (out / "campbell.png").read_bytes()[:8] == PNG


def test_the_variable_is_given_back_after_the_import():
    """The process's environment is left as it was (a child process, a user's later pyplot, sees the variable)."""
    code = ("import os; os.environ['MPLBACKEND'] = 'nonsense'; from gearcli.io import figures; figures.check(); "
            "import matplotlib; print(os.environ['MPLBACKEND'], matplotlib.get_backend() != 'nonsense')")
    env = {**os.environ, "PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")}
    res = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120)
    assert res.returncode == 0, res.stderr
    assert res.stdout.split() == ["nonsense", "True"]
