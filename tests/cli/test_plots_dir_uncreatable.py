"""``--plots`` in a directory that refuses new entries although ``os.access`` says it may be written (root, or a
filesystem such as /proc): refused before the run, exit 2, one line naming the path, and the ``-o`` file not written.
Before, the check passed, the run wrote ``-o`` and then failed to create the figures' directory: exit 1 after the
output (a failed run that left its output)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]
SEED = str(ROOT / "configs" / "concrete_mixer.toml")
UNCREATABLE = "/proc/gearcli-no-such-dir/figures"


@pytest.mark.skipif(not os.path.isdir("/proc/self"), reason="needs Linux's /proc")
@pytest.mark.parametrize("command", [
    ["modes", SEED],
    ["report", SEED, "--quick"],
], ids=["modes", "report"])
def test_plots_where_no_directory_can_be_made_is_exit_2_before_the_run(tmp_path, command):
    out = tmp_path / "out.json"
    res = CliRunner().invoke(cli, [*command, "--plots", UNCREATABLE, "-o", str(out)])
    assert res.exit_code == 2, res.output
    lines = [line for line in res.output.splitlines() if line.strip()]
    assert len(lines) == 1 and UNCREATABLE in lines[0] and "--plots" in lines[0], res.output
    assert "Traceback" not in res.output
    assert not out.exists()


def test_probe_leaves_nothing_behind(tmp_path):
    from gearcli.io.output import check_writable_dir

    check_writable_dir(str(tmp_path / "a" / "b"), "--plots")
    assert list(tmp_path.iterdir()) == []
