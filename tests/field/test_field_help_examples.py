"""Issue 21, field test: every command's --help ends with examples (the README promises it), and each example
parses with the command's own options."""

from __future__ import annotations

import shlex

import pytest
from click.testing import CliRunner

from gearcli.cli import cli


@pytest.mark.parametrize("name", sorted(cli.commands))
def test_help_ends_with_examples_that_parse(name):
    res = CliRunner().invoke(cli, [name, "--help"])
    assert res.exit_code == 0, res.output
    head, sep, examples = res.stdout.rpartition("Examples:")
    assert sep, f"gearcli {name} --help has no examples"
    lines = [line.strip() for line in examples.strip().splitlines()]
    assert lines and all(line.startswith(("gearcli ", "eval ")) for line in lines), lines
    command = cli.commands[name]
    for line in lines:
        if not line.startswith(f"gearcli {name}"):
            continue  # a pipeline's other half (gearcli init - | gearcli design -)
        tokens = shlex.split(line.split("|")[0])[2:]
        args = tokens[:tokens.index(">")] if ">" in tokens else tokens  # the shell's redirection is not ours
        command.make_context(name, list(args))  # unknown options or bad values raise here
