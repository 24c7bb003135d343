"""``--plots DIR`` where ``-o`` writes its file, neither there yet (``-o out --plots out``, or ``-o out --plots
out/figs``), is refused before any work, exit 2 naming ``--plots``, nothing created (trial tr30a, 2026-12-01). Both
checks passed (a missing file, a directory that can be made), the whole run went by, ``-o`` wrote its file, and the
figures' directory could then not be made where it stands: exit 1, ``cannot write plots: File exists`` (``Not a
directory`` for the nested one), after a sweep's or a report's full computation."""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]
COMMANDS = {
    "modes": ["modes", str(ROOT / "configs" / "industrial_two_stage.toml")],
    "life": ["life", str(ROOT / "configs" / "mixer_duty.toml"), "--static"],
    "report": ["report", str(ROOT / "configs" / "industrial_two_stage.toml"), "--quick"],
    "sweep": ["sweep", str(ROOT / "configs" / "industrial_two_stage.toml"), "--vary", "input.speed_rpm=1450"],
}


@pytest.mark.parametrize("plots", ["out", "out/figs"], ids=["same", "inside"])
@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_plots_dir_where_the_output_file_goes_is_refused_up_front(tmp_path, monkeypatch, command, plots):
    monkeypatch.chdir(tmp_path)
    res = CliRunner().invoke(cli, [*COMMANDS[command], "-o", "out", "--plots", plots])
    assert res.exit_code == 2, res.output
    assert f"gearcli: {plots}: --plots needs a directory where -o writes its file (out)" in res.stderr
    assert "Traceback" not in res.output
    assert list(tmp_path.iterdir()) == []  # nothing written: no -o file, no directory


def test_plots_dir_beside_the_output_file_is_still_written(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    res = CliRunner().invoke(cli, [*COMMANDS["modes"], "-o", "out.csv", "--plots", "out", "-q"])
    assert res.exit_code == 0, res.output
    assert (tmp_path / "out.csv").is_file() and (tmp_path / "out" / "campbell.png").is_file()
