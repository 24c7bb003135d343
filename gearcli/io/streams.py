"""Closed standard streams: ``gearcli design f >&-`` (stdout closed) or ``2>&-`` (stderr closed).

Python starts such a process with ``sys.stdout`` (``sys.stderr``) set to None, and the descriptor free:
the next file gearcli opened (an ``-o`` file's temporary file) would become descriptor 1, and a stray write
to "stdout" would land in it. :func:`guard` therefore holds the closed descriptor on ``/dev/null`` at once
and puts a stand-in stream in its place:

- stdout: every write raises :class:`~gearcli.errors.StdoutClosed` (one clean message, exit 2): data
  asked for on a closed stdout cannot be delivered, and saying so beats losing it silently. A command
  that writes to ``-o FILE`` never writes to stdout and runs as usual.
- stderr: messages are dropped (there is nowhere to say anything); the exit code still tells.
"""

from __future__ import annotations

import io
import os
import sys

from gearcli.errors import StdoutClosed


class _ClosedBinary(io.RawIOBase):
    def writable(self) -> bool:
        return True

    def write(self, b) -> int:
        raise StdoutClosed()


class ClosedStdout(io.TextIOBase):
    """The stand-in for a closed stdout: not a terminal, UTF-8, every write refused."""

    closed_stdout = True  # gearcli.io.output.check_output refuses stdout as a destination before any work

    def __init__(self) -> None:
        super().__init__()
        self.buffer = _ClosedBinary()

    @property
    def encoding(self) -> str:  # type: ignore[override]
        return "utf-8"

    @property
    def errors(self) -> str:  # type: ignore[override]
        return "strict"

    def writable(self) -> bool:
        return True

    def write(self, s: str) -> int:
        raise StdoutClosed()

    def flush(self) -> None:  # nothing is ever buffered
        return None

    def isatty(self) -> bool:
        return False

    def fileno(self) -> int:
        return 1


def _descriptor_closed(fd: int) -> bool:
    try:
        os.fstat(fd)
    except OSError:
        return True
    return False


def _hold(fd: int) -> None:
    """Point descriptor ``fd`` at /dev/null, so that no file gearcli opens can take its number."""
    null = os.open(os.devnull, os.O_RDWR)
    if null != fd:
        os.dup2(null, fd)
        os.close(null)


def guard() -> None:
    """Replace a closed stdout or stderr (see the module text); a no-op when both are open."""
    if sys.stdout is None or _descriptor_closed(1):
        if _descriptor_closed(1):
            _hold(1)
        sys.stdout = ClosedStdout()
    if sys.stderr is None or _descriptor_closed(2):
        if _descriptor_closed(2):
            _hold(2)
        sys.stderr = open(os.devnull, "w", encoding="utf-8")  # noqa: SIM115 - lives as long as the process
