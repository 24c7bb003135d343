"""The build process (``python -m gearcli.engine.builder_child DIR``, started by :func:`gearcli.engine.builder.run`):
compile (or load and repair) every kernel entry into ``DIR``, one line per compiled function on stdout for the
parent's progress, under ``build.lock`` so that parallel builds of one cache compile once.
"""

from __future__ import annotations

import contextlib
import ctypes
import os
import signal
import sys
import time
from pathlib import Path

from gearcli.engine import cachedir, loader
from gearcli.engine.builder import PREFIX


def _die_with_parent() -> None:
    """Linux: this process is killed when its parent dies (a killed command leaves no compiler running)."""
    with contextlib.suppress(Exception):
        ctypes.CDLL(None, use_errno=True).prctl(1, int(signal.SIGKILL))  # PR_SET_PDEATHSIG


def child(directory: Path) -> int:
    """The build process: compile (or load and repair) every kernel entry into ``directory``; exit status."""
    import fcntl  # lazy: POSIX only (no fcntl on Windows)

    _die_with_parent()
    lock_path = directory / "build.lock"
    cachedir.clear_entry(lock_path)
    fd = os.open(lock_path, os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW, 0o600)
    fcntl.flock(fd, fcntl.LOCK_EX)  # parallel builds of the same cache: one compiles, the others wait for it
    if loader.ready(directory):
        print(PREFIX + "ready", flush=True)
        return 0
    from numba.core import event  # lazy: numba, the optional fast extra

    class Listener(event.Listener):
        def on_start(self, ev: event.Event) -> None:
            pass

        def on_end(self, ev: event.Event) -> None:
            print(f"{PREFIX}compiled {getattr(ev.data.get('dispatcher'), '__name__', '')}", flush=True)

    t0 = time.perf_counter()
    event.register("numba:compile", Listener())
    kernel, damaged = loader.import_kernel(directory, strict=False)
    loader.warm_up(kernel)
    for line in damaged():
        print(f"{PREFIX}damaged {line}", flush=True)
    loader.mark_ready(directory, time.perf_counter() - t0)
    return 0


if __name__ == "__main__":  # pragma: no cover - run by run() in a child process
    sys.exit(child(Path(sys.argv[1])))
