"""One computation on a second core: a forked child computes a function's value and sends it back.

The one-shot ``gearcli simulate`` uses it for the first pass of its error estimate (the check pass of
:mod:`gearcli.simulate.estimate`) when that pass starts where the run starts: the two integrations are
independent, and on a machine with a free core the check pass then costs no wall time (the seed: ~0.05 s
of a 0.6 s command). The child runs the same code on a copy of the same process, so its numbers are the
numbers the serial path computes, bit for bit (a test compares them).

Only where it is safe and pays:

- the console script's ``simulate`` command turned it on (:func:`console` from :mod:`gearcli.__main__`,
  then :func:`allow`); a library caller, a test running the command in its own process, a report or a
  sweep (whose cores are already busy) never forks;
- Linux (``fork`` without the macOS caveats), at least two CPUs in this process's affinity mask, one Python
  thread, numba not loaded (its thread pools are not fork-safe; the compiled engine's check pass is cheap
  anyway);
- ``GEARCLI_SERIAL=1`` in the environment turns it off.

The child never writes to the terminal or to a file (its standard streams go to /dev/null), ignores Ctrl-C
(the parent handles it and kills the child), dies with the parent (``PR_SET_PDEATHSIG``), and leaves with
``os._exit`` (no atexit handlers, no buffered output flushed twice). Any failure in the child (an
exception, a signal, a truncated answer) makes :meth:`Job.result` return None, and the caller computes the
value itself: the background path can make a command faster, never different.
"""

from __future__ import annotations

import os
import pickle
import signal
import sys
import threading
from collections.abc import Callable
from typing import Any

SERIAL_ENV = "GEARCLI_SERIAL"
_state = {"console": False, "allowed": False}
_KEPT: list = []  # a child's original standard streams (see _detach)


def console() -> None:
    """This process is the console script (:mod:`gearcli.__main__`): a command may :func:`allow` forking."""
    _state["console"] = True


def allow() -> None:
    """Let this process run computations in the background, if it is the console script's."""
    _state["allowed"] = _state["console"]


def available() -> bool:
    """Whether :func:`start` would fork now (module doc)."""
    if not _state["allowed"] or sys.platform != "linux" or not hasattr(os, "fork"):
        return False
    if os.environ.get(SERIAL_ENV, "").strip() not in ("", "0"):
        return False
    try:
        cpus = len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        return False
    return cpus >= 2 and threading.active_count() == 1 and "numba" not in sys.modules


class _Child:
    """A forked child and the pipe ends this process holds; each descriptor closed once."""

    def __init__(self, pid: int, **fds: int) -> None:
        self.pid = pid
        self.fds = dict(fds)
        self._done = False

    def _close_fd(self, name: str) -> None:
        fd = self.fds.get(name, -1)
        if fd >= 0:  # once: a number closed twice may by then be another file's
            self.fds[name] = -1
            try:
                os.close(fd)
            except OSError:
                pass

    def _read_all(self, name: str) -> bytes:
        chunks = []
        try:
            while chunk := os.read(self.fds[name], 1 << 20):
                chunks.append(chunk)
        finally:
            self._close_fd(name)
        return b"".join(chunks)

    def close(self) -> None:
        """End the child (killed if it is still running) and reap it."""
        if self._done:
            return
        self._done = True
        for name in list(self.fds):
            self._close_fd(name)
        try:
            os.kill(self.pid, signal.SIGKILL)
        except OSError:
            pass
        _reap(self.pid)


class Job(_Child):
    """A forked child computing one value; :meth:`result` waits for it, :meth:`close` ends it."""

    def __init__(self, pid: int, fd: int, key: Any) -> None:
        super().__init__(pid, answer=fd)
        self.key = key

    def result(self) -> Any | None:
        """The child's value, or None if it failed in any way (the caller then computes it itself)."""
        if self._done:
            return None
        try:
            data = self._read_all("answer")
        except OSError:
            data = b""
        self._done = True
        _, status = _reap(self.pid)
        if status != 0 or not data:
            return None
        try:
            return pickle.loads(data)
        except Exception:  # noqa: BLE001 - a truncated or foreign answer: compute it here
            return None


def _reap(pid: int) -> tuple[int, int]:
    while True:
        try:
            _, status = os.waitpid(pid, 0)
            return pid, status
        except InterruptedError:
            continue
        except ChildProcessError:
            return pid, -1


def start(fn: Callable[..., Any], *args: Any, key: Any = None) -> Job | None:
    """Fork a child computing ``fn(*args)`` (picklable value); None when :func:`available` says no or the fork
    fails. ``key``: what the caller checks before taking the value (the inputs it was computed for)."""
    if not available():
        return None
    try:
        r, w = os.pipe()
    except OSError:
        return None
    parent = os.getpid()
    try:
        pid = os.fork()
    except OSError:
        os.close(r)
        os.close(w)
        return None
    if pid == 0:  # the child: compute, send, leave without running anything of the parent's exit
        code = 1
        try:
            os.close(r)
            _detach(parent)
            data = memoryview(pickle.dumps(fn(*args), protocol=pickle.HIGHEST_PROTOCOL))
            while data:
                data = data[os.write(w, data):]
            code = 0
        except BaseException:  # noqa: BLE001 - the parent computes the value itself
            pass
        finally:
            os._exit(code)
    os.close(w)
    return Job(pid, r, key)


def _detach(parent: int) -> None:
    """The child: no terminal output, no Ctrl-C (the parent kills it), death with the parent."""
    import gc

    gc.disable()  # a short computation on a copy of the parent's heap: no collections touching its pages
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)
    devnull = os.open(os.devnull, os.O_RDWR)
    for fd in (0, 1, 2):
        os.dup2(devnull, fd)
    os.close(devnull)
    # Python-level streams too (they may write to other descriptors: a test's capture); the parent's are kept
    # alive, never flushed here, so that what the parent has buffered is written once, by the parent
    _KEPT.extend((sys.stdout, sys.stderr))
    sys.stdout = sys.stderr = open(os.devnull, "w")  # noqa: SIM115 - for the child's life
    try:
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
    except Exception:  # noqa: BLE001 - without it the child still ends with its computation
        pass
    if os.getppid() != parent:  # the parent died before the line above
        os._exit(1)
