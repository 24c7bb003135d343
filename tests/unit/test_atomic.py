"""Atomic output: complete file or nothing, with the permissions an ordinary write would give."""

from __future__ import annotations

import os
import stat

import pytest

from gearcli.io.atomic import write_atomic


def test_new_file_gets_0666_less_umask(tmp_path):
    old = os.umask(0o022)
    try:
        write_atomic(tmp_path / "a.csv", "x\n")
    finally:
        os.umask(old)
    assert stat.S_IMODE((tmp_path / "a.csv").stat().st_mode) == 0o644
    assert (tmp_path / "a.csv").read_text() == "x\n"


def test_replaced_file_keeps_its_mode(tmp_path):
    target = tmp_path / "a.csv"
    target.write_text("old\n")
    target.chmod(0o640)
    write_atomic(target, b"new\n")
    assert target.read_text() == "new\n"
    assert stat.S_IMODE(target.stat().st_mode) == 0o640


def test_failure_while_writing_leaves_the_old_file_and_no_temp(tmp_path, monkeypatch):
    target = tmp_path / "a.csv"
    target.write_text("old\n")

    def boom(*_):
        raise KeyboardInterrupt

    monkeypatch.setattr(os, "replace", boom)  # the interrupt lands after the bytes, before the rename
    with pytest.raises(KeyboardInterrupt):
        write_atomic(target, "new\n")
    assert target.read_text() == "old\n"
    assert [p.name for p in tmp_path.iterdir()] == ["a.csv"]


@pytest.mark.parametrize("durable", [False, True])
def test_only_a_durable_write_flushes_to_the_disk_before_the_rename(tmp_path, monkeypatch, durable):
    # a sweep's checkpoint is fsync'ed before it replaces the old one; a one-shot output is not (a wait, not work)
    calls = []
    real_fsync, real_replace = os.fsync, os.replace
    monkeypatch.setattr(os, "fsync", lambda fd: (calls.append("fsync"), real_fsync(fd))[1])
    monkeypatch.setattr(os, "replace", lambda a, b: (calls.append("replace"), real_replace(a, b))[1])
    write_atomic(tmp_path / "a.csv", "new\n", durable=durable)
    assert calls == (["fsync", "replace"] if durable else ["replace"])
    assert (tmp_path / "a.csv").read_text() == "new\n"


def test_a_sweep_file_is_written_as_a_durable_checkpoint(tmp_path, monkeypatch):
    from gearcli.io import sweep_file

    seen = []
    monkeypatch.setattr(sweep_file, "write_atomic", lambda path, text, **kw: seen.append(kw))
    sweep_file.JsonFile(str(tmp_path / "s.json"), ["a"], {"sweep": {}}, [])
    sweep_file.CsvFile(str(tmp_path / "s.csv"), ["a"], {"sweep": {}}, []).close()
    assert seen == [{"durable": True}, {"durable": True}]


_KILLED_MID_WRITE = """
import os, signal, sys
from gearcli.io import atomic
os.fsync = lambda fd: os.kill(os.getpid(), signal.SIGKILL)  # killed outright after the bytes, before any rename
atomic.write_atomic(sys.argv[1], "new\\n" * 100000, durable=True)
"""


@pytest.mark.skipif(not hasattr(os, "O_TMPFILE"), reason="an unnamed temporary file needs Linux's O_TMPFILE")
def test_a_run_killed_while_it_writes_leaves_no_temporary_file(tmp_path):
    # SIGKILL runs no cleanup: a named temporary file stayed, half-written, as .a.csv.xxxx.tmp beside the output (tr30a)
    import signal
    import subprocess
    import sys

    target = tmp_path / "a.csv"
    target.write_text("old\n")
    proc = subprocess.run([sys.executable, "-c", _KILLED_MID_WRITE, str(target)], capture_output=True, timeout=60)
    assert proc.returncode == -signal.SIGKILL
    assert target.read_text() == "old\n"
    assert [p.name for p in tmp_path.iterdir()] == ["a.csv"]


def _write_and_list(tmp_path) -> list[str]:
    link = tmp_path / "link.csv"
    link.symlink_to("a.csv")
    (tmp_path / "a.csv").write_text("old\n")
    (tmp_path / "a.csv").chmod(0o640)
    write_atomic(link, "new\n")
    assert link.is_symlink() and (tmp_path / "a.csv").read_text() == "new\n"
    assert stat.S_IMODE((tmp_path / "a.csv").stat().st_mode) == 0o640
    return sorted(p.name for p in tmp_path.iterdir())


def test_without_an_unnamed_file_a_named_temporary_file_does_the_write(tmp_path, monkeypatch):
    from gearcli.io import atomic

    monkeypatch.setattr(atomic, "_unnamed_file", lambda directory: None)  # another system, or a filesystem without
    assert _write_and_list(tmp_path) == ["a.csv", "link.csv"]


def test_an_unnamed_file_that_cannot_be_linked_falls_back_and_leaves_nothing(tmp_path, monkeypatch):
    import errno

    from gearcli.io import atomic

    def refuse(fd, name):
        raise OSError(errno.EXDEV, "Invalid cross-device link")

    monkeypatch.setattr(atomic, "_link_fd", refuse)
    assert _write_and_list(tmp_path) == ["a.csv", "link.csv"]
