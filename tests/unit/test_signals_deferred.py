"""gearcli.core.signals.deferred: a signal inside the block raises nothing there, raises the kernel's stop flag, and
is acted on by the previous handler when the block ends (issue 31: signals during compiled runs).

The signals are raised in the test's own thread (``signal.raise_signal``), whose C handler then runs at once (sent to
the process, one may land on another thread of a test worker)."""

from __future__ import annotations

import signal

import numpy as np
import pytest

from gearcli.core import signals


class Stopped(BaseException):
    pass


def _raise_stopped(signum, frame):
    raise Stopped(signum)


@pytest.fixture
def term_handler():
    previous = signal.getsignal(signal.SIGTERM)
    signal.signal(signal.SIGTERM, _raise_stopped)
    yield
    signal.signal(signal.SIGTERM, previous)


@pytest.fixture
def int_handler():
    """Python's own SIGINT handler for the test: a process started in the background by a shell (CI's runner can
    be one) inherits SIGINT ignored, and an ignored signal stays ignored in the block (the last test)."""
    previous = signal.getsignal(signal.SIGINT)
    signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, previous)


def test_a_signal_is_held_until_the_block_ends_and_sets_the_flag(int_handler):
    flag = np.zeros(17)
    reached = []
    with pytest.raises(KeyboardInterrupt):
        with signals.deferred(flag, 16) as pending:
            signal.raise_signal(signal.SIGINT)
            for _ in range(1000):  # bytecodes: the handler has run by now
                pass
            reached.append(pending())
    assert reached == [signal.SIGINT]  # the block ran to its end
    assert flag[16] == 1.0
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler  # restored
    assert signals.pending() is None


def test_the_previous_handler_acts_and_only_the_first_signal_counts(term_handler, int_handler):
    with pytest.raises(Stopped) as got:
        with signals.deferred():
            signal.raise_signal(signal.SIGTERM)
            signal.raise_signal(signal.SIGINT)
            for _ in range(1000):
                pass
    assert got.value.args == (signal.SIGTERM,)


def test_nested_blocks_deliver_once_at_the_outermost(term_handler):
    outer_flag, inner_flag = np.zeros(1), np.zeros(1)
    after_inner = []
    with pytest.raises(Stopped):
        with signals.deferred(outer_flag):
            with signals.deferred(inner_flag):
                signal.raise_signal(signal.SIGTERM)
                for _ in range(1000):
                    pass
            after_inner.append(True)  # the inner block's end did not raise
            with signals.deferred(np.zeros(1)) as _:
                pass
    assert after_inner == [True] and outer_flag[0] == inner_flag[0] == 1.0


def test_an_ignored_signal_stays_ignored():
    previous = signal.getsignal(signal.SIGINT)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        flag = np.zeros(1)
        with signals.deferred(flag):
            assert signal.getsignal(signal.SIGINT) is signal.SIG_IGN
            signal.raise_signal(signal.SIGINT)
            for _ in range(1000):
                pass
        assert flag[0] == 0.0 and signals.pending() is None
    finally:
        signal.signal(signal.SIGINT, previous)


def test_a_worker_thread_runs_the_block_as_is():
    import threading

    seen = []

    def work():
        with signals.deferred(np.zeros(1)) as pending:
            seen.append(pending())

    t = threading.Thread(target=work)
    t.start()
    t.join()
    assert seen == [None]


def test_a_default_handler_is_held_in_the_block_and_restored_after():
    previous = signal.getsignal(signal.SIGTERM)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    try:
        with signals.deferred():
            assert signal.getsignal(signal.SIGTERM) is signals._remember  # held: no termination inside the block
        assert signal.getsignal(signal.SIGTERM) is signal.SIG_DFL  # the same handler back, as the enum member
    finally:
        signal.signal(signal.SIGTERM, previous)


def test_a_signal_whose_handler_is_the_default_takes_its_default_action_after_the_block():
    import subprocess
    import sys

    code = ("import signal, sys\n"
            "from gearcli.core import signals\n"
            "signal.signal(signal.SIGTERM, signal.SIG_DFL)\n"
            "with signals.deferred():\n"
            "    signal.raise_signal(signal.SIGTERM)\n"
            "    print('block ran to its end', flush=True)\n"
            "print('not reached', flush=True)\n")
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert res.returncode == -signal.SIGTERM  # terminated by the signal itself, once the block ended
    assert res.stdout == "block ran to its end\n"
