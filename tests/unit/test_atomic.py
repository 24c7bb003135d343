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

    monkeypatch.setattr(os, "fsync", boom)
    with pytest.raises(KeyboardInterrupt):
        write_atomic(target, "new\n")
    assert target.read_text() == "old\n"
    assert [p.name for p in tmp_path.iterdir()] == ["a.csv"]
