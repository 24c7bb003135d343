"""The compiled engine's cache directory, trusted only when it is the user's own (no numba import here).

A cache directory holds machine code and pickles that the engine loads and runs, so every directory gearcli
creates for it is made mode 0700, and one found already there is used only when it is a real directory (not a
symbolic link) owned by the user and writable by nobody else. A directory that fails is refused with a one-line
reason (:func:`check`); the caller then runs without it. Files in it are read and written without following a
symbolic link (:func:`read_json`, :func:`write_json`).
"""

from __future__ import annotations

import contextlib
import json
import os
import shutil
import stat
from pathlib import Path
from typing import Any


class CacheDamaged(Exception):
    """An entry of the engine cache cannot be read back (the message names the file and what was wrong);
    ``entry``: the paths to discard (a function's index and data files, or what stands where a directory belongs)."""

    def __init__(self, message: str, entry: tuple[str, ...] = ()) -> None:
        super().__init__(message)
        self.entry = entry


def discard_entry(paths: tuple[str, ...]) -> None:
    """Remove a damaged entry's files and directories (links removed, never followed)."""
    for path in paths:
        clear_entry(path)
        with contextlib.suppress(FileNotFoundError, IsADirectoryError):
            os.unlink(path)


def _uid() -> int | None:
    return os.geteuid() if hasattr(os, "geteuid") else None


def _problem(path: str, st: os.stat_result) -> str | None:
    """Why the directory entry ``st`` at ``path`` cannot be trusted (None: it can)."""
    if stat.S_ISLNK(st.st_mode):
        return f"{path} is a symbolic link"
    if not stat.S_ISDIR(st.st_mode):
        return f"{path} is not a directory"
    uid = _uid()
    if uid is not None and st.st_uid != uid:
        return f"{path} belongs to another user (uid {st.st_uid}, you are uid {uid})"
    if uid is not None and st.st_mode & 0o022:
        who = " and ".join(w for w, bit in (("its group", 0o020), ("other users", 0o002)) if st.st_mode & bit)
        return f"{path} is writable by {who} (mode {stat.S_IMODE(st.st_mode):04o})"
    return None


def make_private(path: str | os.PathLike) -> str | None:
    """Create the directory ``path`` with mode 0700 when it is missing (its parent must exist); why it cannot be
    trusted, or None."""
    p = os.fspath(path)
    try:
        os.mkdir(p, 0o700)
    except FileExistsError:
        pass
    except OSError as exc:
        return f"{p} cannot be created ({exc.strerror})"
    try:
        return _problem(p, os.lstat(p))
    except OSError as exc:
        return f"{p} cannot be examined ({exc.strerror})"


def check(base: Path, parts: tuple[str, ...]) -> str | None:
    """Create (0700) and check each directory ``base/parts[0]``, ``base/parts[0]/parts[1]``, ...: why the last one
    cannot hold the cache (the first failing directory and its fault), or None. ``base`` itself (``~/.cache``,
    ``$XDG_CACHE_HOME``, the temporary directory) is the user's or the system's and is not judged."""
    try:
        base.mkdir(mode=0o700, parents=True, exist_ok=True)  # a missing ~/.cache is created (the user's, private)
    except OSError as exc:
        return f"{base} cannot be created ({exc.strerror})"
    path = base
    for part in parts:
        path = path / part
        problem = make_private(path)
        if problem:
            return problem
    return None


def clear_entry(path: str | os.PathLike) -> None:
    """Remove what stands where a file is to be written when it is not a regular file (a directory, a link)."""
    with contextlib.suppress(FileNotFoundError):
        st = os.lstat(path)
        if stat.S_ISDIR(st.st_mode):
            shutil.rmtree(path)
        elif not stat.S_ISREG(st.st_mode):
            os.unlink(path)


def read_text(path: str | os.PathLike) -> str | None:
    """The UTF-8 text of the regular file ``path`` (not through a link), or None."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK)
    except OSError:
        return None
    try:
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            return None
        with os.fdopen(os.dup(fd), "rb") as fh:
            return fh.read().decode("utf-8")
    except (OSError, UnicodeDecodeError):
        return None
    finally:
        os.close(fd)


def read_json(path: Path) -> Any:
    """The JSON document in the regular file ``path`` (not through a link), or None when there is none or it is not
    readable JSON."""
    text = read_text(path)
    try:
        return json.loads(text) if text is not None else None
    except (ValueError, RecursionError):  # not JSON, or nested past the parser's recursion limit
        return None


def write_json(path: Path, doc: Any) -> bool:
    """Write ``doc`` to ``path`` through a private temporary file (``O_EXCL | O_NOFOLLOW``, 0600) renamed into place
    (a link planted at ``path`` is replaced, never followed); False when it could not be written."""
    tmp = f"{path}.tmp.{os.getpid()}.w"
    try:
        fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW, 0o600)
    except OSError:
        return False
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(json.dumps(doc))
        clear_entry(path)
        os.replace(tmp, path)
        return True
    except OSError:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        return False


def discard(path: Path) -> None:
    """Remove a damaged cache directory (its links are removed, never followed)."""
    shutil.rmtree(path, ignore_errors=True)


def remove_leftovers(path: Path, pid: int) -> None:
    """Remove the temporary files a build process ``pid`` left in the cache (it was killed mid-write)."""
    marker = f".tmp.{pid}."
    for root, _dirs, files in os.walk(path):
        for name in files:
            if marker in name:
                with contextlib.suppress(OSError):
                    os.unlink(os.path.join(root, name))
