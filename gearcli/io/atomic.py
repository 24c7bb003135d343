"""Atomic file output: write a temporary file beside the target, then rename it into place.

A failed or interrupted run therefore never leaves a truncated file, and an existing file is only
replaced once the new content is complete (docs/output.md, "Files"). Which paths may be written at all
(no directory, device, FIFO or input file) is decided before by :mod:`gearcli.io.output`.
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path


def _final_mode(target: Path) -> int:
    """The mode the file would get from ``open(target, "w")``: the replaced file's, else 0666 less umask."""
    try:
        return target.stat().st_mode & 0o7777
    except FileNotFoundError:
        umask = os.umask(0)
        os.umask(umask)
        return 0o666 & ~umask


def write_atomic(path: str | os.PathLike, data: str | bytes) -> None:
    """Write ``data`` to ``path`` atomically (same-directory temp file, fsync, ``os.replace``)."""
    target = Path(os.path.realpath(path))  # through a symlink: the link stays, its target is replaced
    if target.exists() and not target.is_file():
        raise IsADirectoryError(21, "not a regular file", str(path))
    payload = data.encode("utf-8") if isinstance(data, str) else data
    fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=target.parent or ".")
    try:
        os.chmod(tmp, _final_mode(target))  # mkstemp makes 0600; a plain open() would honour the umask
        with os.fdopen(fd, "wb") as fh:
            fh.write(payload)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, target)
    except BaseException:  # includes KeyboardInterrupt: never leave the temp file behind
        try:
            os.unlink(tmp)
        except FileNotFoundError:
            pass
        raise
