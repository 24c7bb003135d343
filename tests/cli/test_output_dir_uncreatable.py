"""``-o FILE`` in a directory that takes no new file although ``os.access`` says it may be written (root, or a
filesystem such as /proc, where the atomic write's temporary file cannot be made): refused before any computing,
exit 2, one line naming the path (DESIGN §7). Before, the check passed and the command ran to its end (a sweep or a
long simulation: all of it) and only then failed to write, its warnings printed above the error."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]
SEED = str(ROOT / "configs" / "concrete_mixer.toml")  # its design warns (the target speed missed): lines above
DUTY = str(ROOT / "configs" / "mixer_duty.toml")
TARGET = "/proc/gearcli-no-such-file.json"


@pytest.mark.skipif(not os.path.isdir("/proc/self"), reason="needs Linux's /proc")
@pytest.mark.parametrize("command", [
    ["design", SEED],
    ["simulate", SEED],
    ["modes", SEED],
    ["report", SEED, "--quick"],
    ["sweep", SEED, "--vary", "load.torque_Nmm=1e6,2e6"],
    ["life", DUTY, "--static"],
], ids=lambda c: c[0])
def test_an_output_where_no_file_can_be_made_is_exit_2_before_the_run(command):
    res = CliRunner().invoke(cli, [*command, "-o", TARGET, "--format", "json"])
    assert res.exit_code == 2, res.output
    lines = [line for line in res.output.splitlines() if line.strip()]
    assert len(lines) == 1, res.output  # no warning of a design or a run before it: nothing was computed
    assert TARGET in lines[0] and "cannot write in /proc" in lines[0], res.output
    assert "Traceback" not in res.output


def test_the_output_probe_leaves_nothing_behind(tmp_path):
    from gearcli.io.output import resolve_path

    assert resolve_path(str(tmp_path / "out.json")) == tmp_path / "out.json"
    assert list(tmp_path.iterdir()) == []
