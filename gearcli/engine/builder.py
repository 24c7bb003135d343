"""Compiling the kernel into the cache: a separate process, a visible step.

The first use of the compiled engine compiles ~100 numba functions (30-120 s). That happens in a child process
(``python -m gearcli.engine.builder_child DIR``, :mod:`gearcli.engine.builder_child`) so that the command that needs it stays in Python while it waits: it
reports each compiled function (:class:`Reporter`), and a Ctrl-C, SIGTERM or SIGHUP ends it at once (the child
is killed, its temporary files removed, the cache left without a ``ready`` mark: the next build starts over).
Compiling inside the command itself left a signal in numba's compiler (a ctypes-callback traceback, then exit 0).

The child holds ``build.lock`` in the cache directory while it compiles, so that parallel processes (a sweep's
workers) compile once: the others wait and find the cache ready. Damaged entries it meets are discarded and
compiled again (:data:`gearcli.engine.numba_cache.DAMAGED`, reported to the parent).
"""

from __future__ import annotations

import contextlib
import os
import subprocess
import sys
import time
from pathlib import Path
from typing import Protocol

from gearcli.engine import cachedir

PREFIX = "gearcli-build:"
EXPECTED_FUNCTIONS = 170  # numba functions a full build compiles (167 counted on 2026-11-28); a bar's total


class Reporter(Protocol):
    def start(self, directory: Path) -> None: ...

    def step(self, done: int, total: int, elapsed_s: float) -> None: ...

    def note(self, line: str) -> None: ...

    def finish(self, seconds: float, directory: Path, waited: bool = False) -> None: ...


class BuildFailed(Exception):
    """The build process failed (the message has its last lines)."""


def run(directory: Path, reporter: Reporter, expected: int = EXPECTED_FUNCTIONS) -> float:
    """Compile the kernel into ``directory`` in a child process, reporting progress; the seconds it took."""
    t0 = time.perf_counter()
    pkg_root = str(Path(__file__).resolve().parents[2])
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in (pkg_root, os.environ.get("PYTHONPATH", "")) if p),
               PYTHONDONTWRITEBYTECODE="1")  # a killed build leaves no half-written .pyc in the cache
    reporter.start(directory)
    try:
        proc = subprocess.Popen([sys.executable, "-m", "gearcli.engine.builder_child", str(directory)], env=env,
                                stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                start_new_session=True)  # a terminal's Ctrl-C is the parent's to act on
    except OSError as exc:  # the interpreter cannot be started again (permissions, no process left): named
        raise BuildFailed(f"compiling the integration engine failed: cannot start its build process "
                          f"({sys.executable}: {exc.strerror or exc})") from None
    other: list[str] = []
    done = 0
    waited = False
    try:
        assert proc.stdout is not None
        for raw in proc.stdout:
            line = raw.decode("utf-8", "replace").rstrip("\n")
            if line.startswith(PREFIX + "compiled"):
                done += 1
                reporter.step(done, max(expected, done), time.perf_counter() - t0)
            elif line == PREFIX + "ready":  # another process's build held the lock and finished it
                waited = True
            elif line.startswith(PREFIX + "damaged "):
                reporter.note(line[len(PREFIX + "damaged "):])
            elif not line.startswith(PREFIX):
                other.append(line)
        code = proc.wait()
    except BaseException:  # an interrupt (or anything) while waiting: the child goes, with its leftovers
        _kill(proc, directory)
        raise
    if code != 0:
        _kill(proc, directory)
        tail = "; ".join(x.strip() for x in other[-3:] if x.strip())
        raise BuildFailed(f"compiling the integration engine failed (exit {code}){': ' + tail if tail else ''}")
    seconds = time.perf_counter() - t0
    reporter.finish(seconds, directory, waited)
    return seconds


def _kill(proc: subprocess.Popen, directory: Path) -> None:
    with contextlib.suppress(OSError):
        proc.kill()
    with contextlib.suppress(Exception):
        proc.wait(timeout=30)
    if proc.stdout is not None:
        with contextlib.suppress(OSError):
            proc.stdout.close()
    cachedir.remove_leftovers(directory, proc.pid)
