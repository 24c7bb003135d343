"""Atomic file output: write a temporary file beside the target, then rename it into place.

A failed or interrupted run therefore never leaves a truncated file, and an existing file is only
replaced once the new content is complete (docs/output.md, "Files"). Which paths may be written at all
(no directory, device, FIFO or input file) is decided before by :mod:`gearcli.io.output`.

Only a file that is a checkpoint (a sweep's resumable ``-o``: hours of finished points) is also flushed to the disk
before the rename (``durable``), so that it survives a machine crash too. A command's one-shot output is not: it is
recomputed by running the command again, and the flush is a wait on the disk, not work (the seed's ``simulate -o``
on ext4: ``fsync`` ~4 ms and the ``rename`` after it ~4 ms more, against ~0.2 ms for the rename alone;
docs/performance.md, "The one-shot simulate, session 18").
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


def write_atomic(path: str | os.PathLike, data: str | bytes, *, durable: bool = False) -> None:
    """Write ``data`` to ``path`` atomically (same-directory temp file, ``os.replace``); ``durable``: the temp file
    is flushed to the disk (``fsync``) before the rename (module doc)."""
    target = Path(os.path.realpath(path))  # through a symlink: the link stays, its target is replaced
    if target.exists() and not target.is_file():
        raise IsADirectoryError(21, "not a regular file", str(path))
    payload = data.encode("utf-8") if isinstance(data, str) else data
    fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=target.parent or ".")
    try:
        os.chmod(tmp, _final_mode(target))  # mkstemp makes 0600; a plain open() would honour the umask
        with os.fdopen(fd, "wb") as fh:
            fh.write(payload)
            if durable:
                fh.flush()
                os.fsync(fh.fileno())
        os.replace(tmp, target)
    except BaseException:  # includes KeyboardInterrupt: never leave the temp file behind
        try:
            os.unlink(tmp)
        except FileNotFoundError:
            pass
        raise
