"""``--plots DIR`` where a figure's name is a symlink into a directory that does not exist (a dangling link left by
an earlier layout): refused before the run as ``-o`` refuses such a link, exit 2, one line naming the figure and the
missing directory, the ``-o`` file left as it was. Before, the check looked only at what the link's target is (it is
nothing), the run wrote ``-o`` and the first figures, then failed on that one: exit 1 after the output, naming the
directory alone ("cannot write plots: No such file or directory")."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]
SEED = str(ROOT / "configs" / "concrete_mixer.toml")
DUTY = str(ROOT / "configs" / "mixer_duty.toml")


@pytest.mark.parametrize(("command", "figure"), [
    (["modes", SEED], "campbell.png"),
    (["life", DUTY, "--static"], "bending.png"),
], ids=["modes", "life"])
def test_a_figure_linked_into_a_missing_directory_is_exit_2_before_the_run(tmp_path, command, figure):
    plots, gone = tmp_path / "figures", tmp_path / "moved" / "away"
    plots.mkdir()
    os.symlink(gone / figure, plots / figure)
    out = tmp_path / "out.json"
    out.write_text("the previous run's\n")
    res = CliRunner().invoke(cli, [*command, "--plots", str(plots), "-o", str(out), "-q"])
    assert res.exit_code == 2, res.output
    lines = [line for line in res.output.splitlines() if line.strip()]
    assert len(lines) == 1, res.output
    assert str(plots / figure) in lines[0] and "no such directory" in lines[0] and str(gone) in lines[0]
    assert "Traceback" not in res.output
    assert out.read_text() == "the previous run's\n"
    assert sorted(p.name for p in plots.iterdir()) == [figure]  # nothing written beside the link
    assert os.path.islink(plots / figure) and not (tmp_path / "moved").exists()
