"""No module of the package is over 600 lines (the house limit; CONTRIBUTING.md aims at ~400: a module that grows
past it is split by what its parts do). Parallel branches each under the limit can exceed it when merged."""

from __future__ import annotations

from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[2] / "gearcli"
LIMIT = 600


def test_no_module_of_the_package_is_over_the_limit():
    long = {str(p.relative_to(PACKAGE)): n for p in PACKAGE.rglob("*.py")
            if (n := len(p.read_text(encoding="utf-8").splitlines())) > LIMIT}
    assert not long, f"modules over {LIMIT} lines: {long}"
