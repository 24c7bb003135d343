"""A Ctrl-C that lands while click parses the command line (or before a command body's guard) exits 130 with
"gearcli: interrupted", as one in the body does (docs/output.md, exit codes): click turned it into "Aborted!"
and exit 1 (a SIGINT 0.35 s into a compiled `simulate` in CI, tests/engine/test_signals.py)."""

from __future__ import annotations

import subprocess
import sys
import textwrap
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

CHILD = textwrap.dedent("""
    import sys

    from gearcli import cli as c
    from gearcli.cli import common


    def parse(*args, **kwargs):  # the SIGINT handler runs while click parses: it records the signal and raises
        common.on_sigint(2, None)


    c.cli.make_context = parse
    sys.argv = ["gearcli", "design", "configs/concrete_mixer.toml"]
    c.main()
""")


def test_a_ctrl_c_during_parsing_exits_130_with_one_line():
    res = subprocess.run([sys.executable, "-c", CHILD], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert res.returncode == 130, (res.returncode, res.stderr)
    assert "gearcli: interrupted" in res.stderr and "Traceback" not in res.stderr
