"""A Python warning other than a numeric RuntimeWarning raised inside a command (matplotlib's "Glyph ... missing from
font(s) DejaVu Sans" for a CJK design title under ``--plots``) is shown once, as a plain warning line, and the command
ends (trial tr29c, 2026-12-01). ``guarded`` showed it while the warnings were still being recorded, so showing one
appended it to the list being shown: an endless loop that held 2 GB after 40 s (``gearcli modes`` of a one-stage file
whose title holds 齿轮箱, ``--plots``: hung, killed by its timeout after 250 s; the same file without the title:
1.7 s). It is one ``warning:`` line like every other (no source path and line), and none with ``-q``.

The command runs in a child process under a 1.5 GB address-space limit, so that before the fix the loop ends in
a MemoryError (an internal error, exit 1) rather than hanging the test run."""

from __future__ import annotations

import subprocess
import sys
import textwrap

import pytest

CHILD = textwrap.dedent("""
    import resource, sys, warnings
    import click
    from gearcli.cli.common import guarded

    @click.command()
    @click.option("-q", "--quiet", is_flag=True)
    @guarded
    def cmd():
        for _ in range(2):
            warnings.warn("Glyph 40831 missing from font(s) DejaVu Sans.", UserWarning)
            warnings.warn("overflow encountered in exp", RuntimeWarning)
        click.echo("the command's output")

    resource.setrlimit(resource.RLIMIT_AS, (1536 * 2**20, 1536 * 2**20))
    cmd(sys.argv[1:])
""")


@pytest.mark.parametrize("quiet", [False, True], ids=["shown", "quiet"])
def test_a_user_warning_inside_a_command_is_shown_once_and_the_command_ends(quiet):
    res = subprocess.run([sys.executable, "-c", CHILD, *(["-q"] if quiet else [])], capture_output=True, text=True,
                         timeout=120)
    assert res.returncode == 0, res.stderr[-2000:]
    assert res.stdout == "the command's output\n"
    if quiet:
        assert res.stderr == ""
        return
    # each message once (two identical warnings), one plain line each, as gearcli's warnings are printed
    assert res.stderr.splitlines() == ["warning: numerical warning during the run: overflow encountered in exp",
                                       "warning: Glyph 40831 missing from font(s) DejaVu Sans."]
