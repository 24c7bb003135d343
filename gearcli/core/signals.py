"""Signals (SIGINT, SIGTERM, SIGHUP) held back while code that must not be unwound runs.

Python runs a signal's handler in the main thread between two bytecodes, and the default SIGINT handler (and
gearcli's SIGTERM and SIGHUP handlers, :func:`gearcli.cli.main`) raise there. Inside numba's compiler or cache
loader that exception lands in a ctypes callback of llvmlite (printed and swallowed: the run went on and exited
0) or under a dispatcher that then returns a result with the exception set (``SystemError``); raised in the main
thread while a worker thread runs the compiled kernel, it let the interpreter shut down under the running kernel
(a segfault after "interrupted").

:func:`deferred` installs handlers that only remember the signal and raise a stop flag (a one-element numpy array
the compiled kernel reads after every step: :data:`gearcli.engine.status.WP_STOP`); when the block ends, the
first signal that arrived is handed to the handler that was there before (KeyboardInterrupt, ``Terminated``, or
the default action), in ordinary Python code, once the kernel has returned.
"""

from __future__ import annotations

import importlib
import signal
import threading
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

SIGNALS = tuple(getattr(signal, name) for name in ("SIGINT", "SIGTERM", "SIGHUP") if hasattr(signal, name))


def _unwrapped() -> tuple[Callable[..., Any], Callable[..., Any]]:
    """``getsignal`` and ``signal`` of ``_signal``, the C module under :mod:`signal` (CPython's; the wrappers where it
    is missing): the same handlers read and installed, without the wrappers' conversions to and from the enums,
    which raise and catch an exception for every function handler (``Handlers(f)``, ``int(f)``), ~15 us of the ~20
    us a block took. They give SIG_DFL and SIG_IGN as the integers 0 and 1, equal to the enum members."""
    try:
        raw = importlib.import_module("_signal")
    except ImportError:
        return signal.getsignal, signal.signal
    return raw.getsignal, raw.signal


_getsignal, _setsignal = _unwrapped()


_pending: list[int] = []  # signals that arrived inside the outermost deferred block, in order
_flags: list[Any] = []  # the stop flags of the blocks open now (array-likes: entry [index] set to 1.0)


def _remember(signum: int, frame: object) -> None:
    _pending.append(signum)
    for flag, index in _flags:
        flag[index] = 1.0


def handled() -> bool:
    """Whether a Python handler could run for SIGINT, SIGTERM or SIGHUP here: in the main thread, one of them has a
    callable handler (a sweep's pool worker ignores SIGINT and leaves SIGTERM and SIGHUP to the system's default
    action, which ends it at once, compiled code running or not: nothing there for :func:`deferred` to hold back)."""
    if threading.current_thread() is not threading.main_thread():
        return False
    return any(callable(_getsignal(s)) for s in SIGNALS)


def pending() -> int | None:
    """The first signal held back by the open :func:`deferred` blocks (None: none)."""
    return _pending[0] if _pending else None


@contextmanager
def deferred(flag: Any = None, index: int = 0) -> Iterator[Callable[[], int | None]]:
    """Hold SIGINT, SIGTERM and SIGHUP back during the block (``flag[index] = 1.0`` when one arrives, so that a
    running kernel stops at its next step), then deliver the first one as the previous handler would have.
    Yields :func:`pending`. Outside the main thread (where no handler can be installed) the block runs as is;
    a signal whose handler is ``SIG_IGN`` stays ignored."""
    if threading.current_thread() is not threading.main_thread():
        yield pending
        return
    previous = {s: _getsignal(s) for s in SIGNALS}
    outermost = not any(h is _remember for h in previous.values())
    # a block inside another finds the handlers it would install already there: it leaves them (what it would
    # restore on leaving is the same _remember), the stop flag and the delivery stay as they are
    installed = [s for s, h in previous.items() if h is not None and h is not _remember and not _ignored(h)]
    for s in installed:
        _setsignal(s, _remember)
    entry = (flag, index) if flag is not None else None
    if entry is not None:
        _flags.append(entry)
        if _pending:  # a signal already held by an enclosing block stops this kernel too
            flag[index] = 1.0
    try:
        yield pending
    finally:
        if entry is not None:
            _flags.remove(entry)
        for s in installed:
            _setsignal(s, previous[s])
        if outermost and _pending:
            _deliver(_pending[0], previous.get(_pending[0]))


def _ignored(handler: Any) -> bool:
    """Whether ``handler`` is SIG_IGN (the enum member or the integer 1 the unwrapped ``getsignal`` gives)."""
    return not callable(handler) and handler == signal.SIG_IGN


def _deliver(signum: int, handler: Any) -> None:
    """Act on ``signum`` as ``handler`` (the one the block replaced) would have."""
    _pending.clear()
    if callable(handler):
        handler(signum, None)  # raises KeyboardInterrupt / Terminated
    elif handler == signal.SIG_DFL:
        signal.raise_signal(signum)  # the default action (terminate), now that nothing runs under us
