"""A ``--vary`` (or ``--random``) of a ``[[duty]]`` key in a sweep says it has no effect (a warning naming the column,
exit 0), as the other options that cannot act do (tests/cli/test_noop_options.py): the duty is ``gearcli life``'s
operating points, a sweep point runs the file's ``[input]`` and ``[load]``. Before, ``--vary duty.1.hours=...`` ran
every point silently, each row the same run."""

from __future__ import annotations

import csv
import io
from pathlib import Path

from click.testing import CliRunner

from gearcli.cli import cli

DUTY = str(Path(__file__).resolve().parents[2] / "configs" / "mixer_duty.toml")
SHORT = ["--set", "simulation.duration_s=0.05", "--set", "simulation.steps=100", "--jobs", "1"]


def _said(res) -> list[str]:
    return [line for line in res.stderr.splitlines() if "no effect" in line]


def test_a_duty_key_swept_is_said_to_have_no_effect_and_gives_the_same_rows():
    res = CliRunner().invoke(cli, ["sweep", DUTY, "--vary", "duty[1].hours=100,200", *SHORT])
    assert res.exit_code == 0, res.stderr
    said = _said(res)
    assert len(said) == 1 and said[0].startswith("warning: --vary/--random duty[1].hours: [[duty]]"), said
    rows = list(csv.DictReader(io.StringIO(res.stdout)))
    assert [r["duty[1].hours"] for r in rows] == ["100", "200"]
    same = [{k: v for k, v in r.items() if k not in ("duty[1].hours", "wall_s")} for r in rows]
    assert same[0] == same[1]  # the one run, twice: the duty's hours act in no point


def test_a_key_of_the_point_says_nothing():
    res = CliRunner().invoke(cli, ["sweep", DUTY, "--vary", "input.speed_rpm=600", *SHORT])
    assert res.exit_code == 0, res.stderr
    assert not _said(res)
