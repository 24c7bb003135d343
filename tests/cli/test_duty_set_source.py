"""A ``[[duty]]`` point's ``set`` given by ``--set`` names ``--set`` as the source of its error, as every other key a
``--set`` wrote does (DESIGN §5: the message names where the bad value was written); before, the file was named for a
value it does not hold. Written in the file, the same error names the file."""

from __future__ import annotations

from pathlib import Path

from click.testing import CliRunner

from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]
MIXER = ROOT / "configs" / "mixer_planetary_motor.toml"


def _error(*args: str) -> str:
    res = CliRunner().invoke(cli, ["design", *args, "--format", "json", "-q"])
    assert res.exit_code == 2, res.output
    lines = [line for line in res.output.splitlines() if line.strip()]
    assert len(lines) == 1 and "Traceback" not in res.output, res.output
    return lines[0]


def test_a_set_table_given_by_set_names_set():
    line = _error(str(MIXER), "--set", 'duty.0.set={"load.torque_nm"=5}')
    assert line.startswith("gearcli: --set: duty[0].set.load.torque_nm: unknown key 'torque_nm'"), line
    line = _error(str(MIXER), "--set", 'duty.1.set={"simulation.duration_s"=0}')
    assert line.startswith("gearcli: --set: duty[1].set.simulation.duration_s: must be ≥ 0.0001, got 0"), line


def test_a_set_table_in_the_file_names_the_file(tmp_path):
    text = MIXER.read_text(encoding="utf-8")
    head, sep, tail = text.partition('name = "')
    assert sep
    path = tmp_path / "mixer.toml"
    path.write_text(head + 'set = { "load.torque_nm" = 5 }\n' + sep + tail, encoding="utf-8")
    line = _error(str(path))
    assert line.startswith(f"gearcli: {path}: duty[0].set.load.torque_nm: unknown key 'torque_nm'"), line
