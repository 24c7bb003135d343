"""``--plots`` pointing at a file: one line naming the option and the path, exit 2, nothing written (DESIGN §5:
messages name the file and the key, no usage block). click's own Path check printed its three-line usage error
("Usage: ... Try ... Error: Invalid value for '--plots': Directory ... is a file") before gearcli's check ran."""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]
SEED = str(ROOT / "configs" / "concrete_mixer.toml")


@pytest.mark.parametrize("command", [
    ["modes", SEED],
    ["report", SEED, "--quick"],
    ["sweep", SEED, "--vary", "input.speed_rpm=300:600:2"],
    ["life", str(ROOT / "configs" / "mixer_duty.toml"), "--static"],
], ids=["modes", "report", "sweep", "life"])
def test_plots_at_a_file_is_one_line_and_exit_2(tmp_path, command):
    afile = tmp_path / "figures"
    afile.write_text("not a directory\n")
    out = tmp_path / "out.json"
    res = CliRunner().invoke(cli, [*command, "--plots", str(afile), "-o", str(out)])
    assert res.exit_code == 2, res.output
    lines = [line for line in res.output.splitlines() if line.strip()]
    assert len(lines) == 1 and "--plots needs a directory" in lines[0] and str(afile) in lines[0]
    assert "Usage:" not in res.output
    assert not out.exists() and afile.read_text() == "not a directory\n"
