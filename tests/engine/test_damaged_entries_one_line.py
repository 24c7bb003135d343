"""A cache whose every entry is damaged (a truncated copy: ~100 entries) is named in one line, with the count of the
rest, not one stderr line per entry (docs/numerics.md: "a damaged cache ... is named in one line")."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from gearcli.engine import builder
from gearcli.io.progress import BuildProgress


class _Child:
    """The build child's stdout: 100 damaged entries met and compiled again, then its functions compiled."""

    def __init__(self, *args, **kwargs):
        lines = [f"{builder.PREFIX}damaged /c/e/mod.f{i}-1.py311.nbi: EOFError: Ran out of input" for i in range(100)]
        lines += [f"{builder.PREFIX}compiled f{i}" for i in range(5)]
        self.stdout = [(x + "\n").encode() for x in lines]
        self.pid = 1

    def wait(self, timeout=None):
        return 0


def test_a_hundred_damaged_entries_are_two_lines(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(subprocess, "Popen", _Child)
    monkeypatch.setattr(sys.stderr, "isatty", lambda: False, raising=False)
    builder.run(Path(tmp_path), BuildProgress())
    err = capsys.readouterr().err.splitlines()
    damaged = [x for x in err if "damaged entr" in x]
    assert len(damaged) == 2, err
    assert "mod.f0-1.py311.nbi" in damaged[0]  # the first named
    assert "99 more damaged entries" in damaged[1]
    assert err[0].startswith("gearcli: compiling the integration engine") and "compiled the integration engine in" in err[-1]


def test_one_damaged_entry_is_one_line(capsys):
    rep = BuildProgress()
    rep.note("x.nbi: EOFError")
    rep.finish(1.0, Path("/c"))
    err = capsys.readouterr().err.splitlines()
    assert [x for x in err if "damaged entr" in x] == ["gearcli: the engine cache had a damaged entry, compiled again: x.nbi: EOFError"]


def test_quiet_says_nothing(capsys):
    rep = BuildProgress(quiet=True)
    for _ in range(3):
        rep.note("x")
    rep.finish(1.0, Path("/c"))
    assert capsys.readouterr().err == ""


def _reasons(monkeypatch) -> list[str]:
    from gearcli.engine import loader

    seen: list[str] = []
    monkeypatch.setattr(builder, "run", lambda cdir, reporter: seen.append(reporter.reason) or 0.0)
    monkeypatch.delitem(loader._state, "quiet", raising=False)
    return seen


def test_a_rebuild_says_why_not_first_use(tmp_path, monkeypatch, capsys):
    """The build's first line says why it compiles: a first use, a damaged cache, or --force (it said 'its first
    use here' for all three)."""
    from gearcli.engine import loader
    from gearcli.engine.cachedir import CacheDamaged

    seen = _reasons(monkeypatch)
    cdir = tmp_path / "key"
    cdir.mkdir()
    entry = cdir / "x.nbi"
    entry.write_text("")
    loader._build(cdir, quiet=True)
    loader._discard(CacheDamaged("x.nbi: EOFError", (str(entry),)), cdir, quiet=True)
    loader._build(cdir, quiet=True)
    monkeypatch.setitem(loader._state, "why_build", "again, as --force asked")  # what build(force=True) records
    loader._build(cdir, quiet=True)
    loader._build(cdir, quiet=True)
    assert seen == ["its first use here", "again, its cache was damaged", "again, as --force asked",
                    "its first use here"]
    assert not entry.exists()
    rep = BuildProgress()
    rep.reason = "again, as --force asked"
    rep.start(cdir)
    assert capsys.readouterr().err.startswith("gearcli: compiling the integration engine (again, as --force asked; ")


def test_a_build_process_that_cannot_start_is_a_clear_failure(tmp_path, monkeypatch):
    """Popen's PermissionError (an interpreter this user may not execute) was an 'internal error'."""
    import pytest

    def denied(*args, **kwargs):
        raise PermissionError(13, "Permission denied")

    monkeypatch.setattr(subprocess, "Popen", denied)
    with pytest.raises(builder.BuildFailed, match="cannot start its build process .*Permission denied"):
        builder.run(tmp_path, BuildProgress(quiet=True))
