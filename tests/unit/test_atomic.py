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
