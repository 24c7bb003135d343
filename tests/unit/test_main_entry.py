"""The entry point's command word: the commands that integrate import numpy and scipy first (gearcli/__main__.py)."""

from gearcli.__main__ import INTEGRATING, NUMERIC, command_word
from gearcli.cli import cli


def test_command_word_skips_the_global_options():
    assert command_word(["-q", "--debug", "simulate", "seed.toml", "-o", "run.csv"]) == "simulate"
    assert command_word(["report", "-", "-o", "r.md"]) == "report"


def test_no_command_word():
    assert command_word([]) is None
    assert command_word(["--version"]) is None


def test_the_numeric_commands_are_commands():
    assert INTEGRATING <= NUMERIC <= set(cli.commands)
