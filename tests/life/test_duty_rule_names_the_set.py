"""A `[[duty]]` rule that a `--set` breaks names the `--set`, as design's and the schema's errors do (docs/usage.md:
"Errors are one line naming the file and the key path"); the file is named only when the file itself breaks it.

`gearcli life mixer_duty.toml --set duty.0.hours=0 --set duty.1.hours=0 --set duty.2.hours=0` said
`mixer_duty.toml: duty: every [[duty]] point has hours = 0`, where the file gives 3000, 12000 and 1500 hours.
"""

from __future__ import annotations

from pathlib import Path

from click.testing import CliRunner

from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]
DUTY = ROOT / "configs" / "mixer_duty.toml"


def _error(*args: str) -> str:
    res = CliRunner().invoke(cli, ["life", *args, "--static", "--format", "json", "-q"], catch_exceptions=False)
    assert res.exit_code == 2, res.output
    assert "Traceback" not in res.stderr
    return res.stderr.strip()


def test_every_point_emptied_by_set_names_the_set():
    msg = _error(str(DUTY), "--set", "duty.0.hours=0", "--set", "duty.1.hours=0", "--set", "duty.2.hours=0")
    assert msg.startswith("gearcli: --set: duty: every [[duty]] point has hours = 0"), msg


def test_a_name_repeated_by_set_names_the_set():
    msg = _error(str(DUTY), "--set", 'duty.1.name="charging"')
    assert msg.startswith("gearcli: --set: duty[1].name: 'charging' is already the name of duty[0]"), msg


def test_starts_without_hours_by_set_names_the_set():
    msg = _error(str(DUTY), "--set", "duty.0.hours=0", "--set", "duty.0.starts=3")
    assert msg.startswith("gearcli: --set: duty[0].hours: 0 hours with starts = 3"), msg


def test_the_files_own_repeated_name_still_names_the_file(tmp_path):
    path = tmp_path / "dup.toml"
    path.write_text(DUTY.read_text().replace('name = "mixing"', 'name = "charging"'))
    # a --set elsewhere does not take the blame
    msg = _error(str(path), "--set", "stage.0.pinion.teeth=22")
    assert msg.startswith(f"gearcli: {path}: duty[1].name: 'charging' is already the name of duty[0]"), msg
