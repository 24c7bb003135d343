"""Progress of compiled runs (gearcli.simulate.solver._kernel_with_progress): the kernel runs in one call in a
worker thread and writes the time it has reached at every budget check; the caller's thread reports it. The
numbers are those of a run without progress, bit for bit; a terminal shows the bar, a pipe and -q do not."""

from __future__ import annotations

import os
import pty
import select
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.scene import build_model
from gearcli.simulate import solver
from gearcli.simulate.solver import STATUS_FINISHED, integrate

ROOT = Path(__file__).resolve().parents[2]


def _seed_model():
    cfg = load_design(str(ROOT / "configs" / "concrete_mixer.toml"), []).design
    return cfg, build_model(cfg, compute_design(cfg))


@pytest.mark.parametrize("method", ["DOP853", "Radau"])
def test_a_compiled_run_with_progress_is_bit_identical_and_reports_its_fraction(method, monkeypatch):
    cfg, model = _seed_model()
    t_eval = np.linspace(0.0, cfg.simulation.duration_s, cfg.simulation.steps + 1)
    plain = integrate(model, t_eval, method, 1e-6, engine="compiled")
    monkeypatch.setattr(solver, "PROGRESS_EVERY_S", 0.0)  # poll as often as the thread can
    seen: list[float] = []
    got = integrate(model, t_eval, method, 1e-6, engine="compiled", progress=seen.append)
    assert got.engine == "compiled" and got.status == plain.status == STATUS_FINISHED
    assert np.array_equal(got.y, plain.y)
    assert (got.nfev, got.njev, got.nlu, got.steps) == (plain.nfev, plain.njev, plain.nlu, plain.steps)
    assert seen and all(0.0 <= f <= 1.0 for f in seen) and seen == sorted(seen)
    # the last report is the time of the last budget check (every 64 accepted steps), after the kernel returned
    checks = plain.steps // 64
    assert checks >= 1 and 0.0 < seen[-1] <= 1.0


def test_an_error_in_the_worker_reaches_the_caller():
    def kernel(*_args):
        raise ValueError("from the kernel")

    with pytest.raises(ValueError, match="from the kernel"):
        solver._kernel_with_progress(kernel, (), np.zeros(17), (0.0, 1.0), lambda f: None)


def _thread_of_a_kernel_call(handlers: dict) -> str:
    """The name of the thread a progress-less compiled call runs its kernel in, with ``handlers`` installed."""
    import signal
    import threading

    from gearcli.core.signals import SIGNALS

    previous = {s: signal.getsignal(s) for s in SIGNALS}
    seen: list[str] = []
    try:
        for s in SIGNALS:
            signal.signal(s, handlers.get(s, signal.SIG_DFL))
        out = solver._kernel_with_progress(lambda *a: seen.append(threading.current_thread().name) or a, (1, 2),
                                           np.zeros(17), (0.0, 1.0), None)
    finally:
        for s, h in previous.items():
            signal.signal(s, h)
    assert out == (1, 2)  # the kernel's return, either way
    return seen[0]


def test_a_sweep_workers_kernel_runs_in_its_own_thread_and_a_cli_s_in_the_worker_thread():
    """A sweep's pool worker (SIGINT ignored, SIGTERM and SIGHUP the system's default action, which ends it at once)
    has no Python handler to hold back: the kernel is called directly, without a thread; with a handler (the CLI's
    KeyboardInterrupt) it runs in the worker thread, the handler deferred until it returns."""
    import signal
    import threading

    assert _thread_of_a_kernel_call({signal.SIGINT: signal.SIG_IGN}) == threading.current_thread().name
    assert _thread_of_a_kernel_call({signal.SIGINT: signal.default_int_handler}) == "gearcli-kernel"


def test_the_kernel_thread_is_started_once_and_serves_every_later_run():
    """The worker thread is kept for the process's later runs (a sweep's points): each call's kernel runs in the
    same thread, returns its own arguments, and an error in one run leaves the thread serving the next."""
    import signal
    import threading

    def ident(*a):
        return (threading.get_ident(), *a)

    previous = signal.getsignal(signal.SIGINT)
    signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        first = solver._kernel_with_progress(ident, (1,), np.zeros(17), (0.0, 1.0), None)
        with pytest.raises(ZeroDivisionError):
            solver._kernel_with_progress(lambda: 1 / 0, (), np.zeros(17), (0.0, 1.0), None)
        second = solver._kernel_with_progress(ident, (2,), np.zeros(17), (0.0, 1.0), None)
    finally:
        signal.signal(signal.SIGINT, previous)
    assert first[1:] == (1,) and second[1:] == (2,)
    assert first[0] == second[0] != threading.get_ident()


def _run_on_a_terminal(args: list[str]) -> tuple[int, bytes]:
    """``gearcli ARGS`` with stderr on a pseudo-terminal (stdout a pipe): (exit code, what the terminal got)."""
    master, slave = pty.openpty()
    env = dict(os.environ, PYTHONPATH=str(ROOT), COLUMNS="100", TERM="xterm")
    proc = subprocess.Popen([sys.executable, "-m", "gearcli", *args], cwd=ROOT, env=env, stdout=subprocess.PIPE,
                            stderr=slave, stdin=subprocess.DEVNULL)
    os.close(slave)
    got = b""
    while True:
        ready, _, _ = select.select([master], [], [], 0.2)
        if ready:
            try:
                chunk = os.read(master, 65536)
            except OSError:  # the child closed the terminal
                break
            if not chunk:
                break
            got += chunk
        elif proc.poll() is not None:
            break
    proc.stdout.read()
    os.close(master)
    return proc.wait(), got


# the conveyor for 30 s: ~5e6 evaluations on the compiled engine, a run of several seconds (the bar shows after
# 1 s; 6 s of it took ~1.5 s once the kernel lost numba's reference counting: too close to the bar's second)
LONG = ["simulate", "configs/conveyor.toml", "--format", "json", "--set", "simulation.duration_s=30",
        "--set", "simulation.steps=60000", "--set", "simulation.engine=compiled"]


@pytest.mark.slow
def test_a_long_compiled_simulate_shows_its_progress_on_a_terminal_and_nothing_with_q():
    code, shown = _run_on_a_terminal(LONG)
    assert code == 0 and b"simulate" in shown and b"/1000" in shown  # the bar: label and per mille
    code, quiet = _run_on_a_terminal([*LONG, "-q"])
    assert code == 0 and b"/1000" not in quiet and b"simulate" not in quiet


@pytest.mark.slow
def test_a_long_simulate_in_a_pipe_shows_no_progress():
    proc = subprocess.run([sys.executable, "-m", "gearcli", *LONG], cwd=ROOT, capture_output=True,
                          env=dict(os.environ, PYTHONPATH=str(ROOT)))
    assert proc.returncode == 0
    assert all(line.startswith("warning: ") for line in proc.stderr.decode().splitlines()), proc.stderr


@pytest.mark.slow
@pytest.mark.slow
def test_report_shows_its_runs_on_a_terminal_and_nothing_with_q():
    # the excited conveyor: its ladder's work lasts several seconds (~6 s on an idle machine). The unexcited seed's
    # runs settle and are solved for their equilibrium: its whole report took ~2 s whatever its duration, its ladder
    # close to the bar's first second, so the bar came or not by the machine's load
    args = ["report", "configs/conveyor.toml", "--format", "json"]
    code, shown = _run_on_a_terminal(args)
    assert code == 0 and b"rtol" in shown and b"\x1b[" in shown  # a live bar: the run it is at, cursor control
    code, quiet = _run_on_a_terminal([*args, "-q"])
    assert code == 0 and quiet == b""
