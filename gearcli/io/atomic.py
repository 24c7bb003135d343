"""Atomic file output: write a temporary file beside the target, then rename it into place.

A failed or interrupted run therefore never leaves a truncated file, and an existing file is only
replaced once the new content is complete (docs/output.md, "Files"). Which paths may be written at all
(no directory, device, FIFO or input file) is decided before by :mod:`gearcli.io.output`.

Only a file that is a checkpoint (a sweep's resumable ``-o``: hours of finished points) is also flushed to the disk
before the rename (``durable``), so that it survives a machine crash too. A command's one-shot output is not: it is
recomputed by running the command again, and the flush is a wait on the disk, not work (the seed's ``simulate -o``
on ext4: ``fsync`` ~4 ms and the ``rename`` after it ~4 ms more, against ~0.2 ms for the rename alone;
docs/performance.md, "The one-shot simulate, session 18").

Where the system has them (Linux: ``O_TMPFILE``, named through ``/proc/self/fd``), the bytes go to an unnamed file in the
target's directory, which gets its temporary name only once it is complete, just before the rename: a run killed
outright while it writes (SIGKILL, the out-of-memory killer), whose cleanup never runs, leaves nothing behind, where
a named temporary file would stay as a half-written ``.NAME.xxxx.tmp`` beside the output. Elsewhere (another system,
a filesystem without ``O_TMPFILE``) the temporary file is named from the start, as before.
"""

from __future__ import annotations

import os
import secrets
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
    mode = _final_mode(target)
    if _write_unnamed(target, payload, mode, durable):
        return
    fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=target.parent or ".")
    try:
        os.chmod(tmp, mode)  # mkstemp makes 0600; a plain open() would honour the umask
        with os.fdopen(fd, "wb") as fh:
            _fill(fh, payload, durable)
        os.replace(tmp, target)
    except BaseException:  # includes KeyboardInterrupt: never leave the temp file behind
        _discard(tmp)
        raise


def _fill(fh, payload: bytes, durable: bool) -> None:
    fh.write(payload)
    fh.flush()
    if durable:
        os.fsync(fh.fileno())


def _discard(tmp: str | None) -> None:
    if tmp is None:
        return
    try:
        os.unlink(tmp)
    except FileNotFoundError:
        pass


def _unnamed_file(directory: Path) -> int | None:
    """A file without a name in ``directory`` (``O_TMPFILE``), or None where the system or the filesystem has none."""
    flag = getattr(os, "O_TMPFILE", 0)
    if not flag:
        return None
    try:
        return os.open(directory, flag | os.O_WRONLY | os.O_CLOEXEC, 0o600)
    except OSError:  # not supported here (EOPNOTSUPP; EISDIR on an old kernel), or refused: the named file says why
        return None


def _link_fd(fd: int, name: str) -> None:
    """The unnamed file ``fd`` gets ``name``: the link of its ``/proc/self/fd`` entry, followed (``open(2)``'s way to
    name an ``O_TMPFILE`` file, open to any user); :class:`FileExistsError` where ``name`` exists, another
    :class:`OSError` where it cannot be linked (no ``/proc``: the caller writes a named file instead)."""
    # a dir fd makes Python call linkat(..., AT_SYMLINK_FOLLOW) (the path is absolute: the fd is not read); without
    # one it calls link(), which links the /proc entry itself and fails across devices (EXDEV)
    os.link(f"/proc/self/fd/{fd}", name, src_dir_fd=fd, follow_symlinks=True)


def _name_it(fd: int, target: Path) -> str | None:
    """Give the complete unnamed file ``fd`` a temporary name beside ``target``; None where it cannot be linked."""
    for _ in range(100):
        tmp = str(target.parent / f".{target.name}.{secrets.token_hex(4)}.tmp")
        try:
            _link_fd(fd, tmp)
        except FileExistsError:
            continue
        except OSError:
            return None
        return tmp
    return None


def _write_unnamed(target: Path, payload: bytes, mode: int, durable: bool) -> bool:
    """The write through an unnamed file (module doc); False, nothing written, where it cannot be had."""
    fd = _unnamed_file(target.parent)
    if fd is None:
        return False
    tmp: str | None = None
    try:
        with os.fdopen(fd, "wb") as fh:
            os.fchmod(fh.fileno(), mode)  # O_TMPFILE's mode is 0600, as mkstemp's
            _fill(fh, payload, durable)
            tmp = _name_it(fh.fileno(), target)
        if tmp is None:
            return False
        os.replace(tmp, target)
    except BaseException:  # an interrupt between the name and the rename: the name goes again
        _discard(tmp)
        raise
    return True
