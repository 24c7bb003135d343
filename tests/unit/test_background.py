"""The check pass on a second core (gearcli.simulate.background) and the console script's quick exit.

The background path must never change a number: the forked child runs the same code on a copy of the same
process, so the check pass it computes is compared bit for bit with the one computed after the run. Any
failure of the child falls back to computing in the parent. The quick exit (gearcli.__main__) must still
flush the output and run the atexit handlers.
"""

from __future__ import annotations

import dataclasses
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.simulate import background, estimate
from gearcli.simulate.run import run_simulation

ROOT = Path(__file__).resolve().parents[2]
SEED = ROOT / "configs" / "concrete_mixer.toml"
TIMES = ("wall_s", "compile_s")


@pytest.fixture
def forking(monkeypatch):
    """This process as the console script's, with forking allowed; skipped where it cannot fork."""
    monkeypatch.setattr(background, "_state", {"console": True, "allowed": True})
    monkeypatch.delenv(background.SERIAL_ENV, raising=False)
    if not background.available():
        pytest.skip("no fork here (not Linux, one CPU, threads running, or numba loaded)")
    return background


def _seed():
    cfg = load_design(str(SEED), []).design
    return cfg, compute_design(cfg)


def _without_times(x):
    if dataclasses.is_dataclass(x) and not isinstance(x, type):
        return _without_times({f.name: getattr(x, f.name) for f in dataclasses.fields(x)})
    if isinstance(x, dict):
        return {k: _without_times(v) for k, v in x.items() if k not in TIMES}
    if isinstance(x, (list, tuple)):
        return [_without_times(v) for v in x]
    if isinstance(x, np.ndarray):
        return x.tobytes()
    return x


def test_not_available_unless_the_console_script_allows_it(monkeypatch):
    monkeypatch.setattr(background, "_state", {"console": False, "allowed": False})
    background.allow()  # a library caller or a test running the command in its own process
    assert not background.available()
    assert background.start(os.getpid) is None


def test_serial_environment_variable_turns_it_off(forking, monkeypatch):
    monkeypatch.setenv(background.SERIAL_ENV, "1")
    assert not background.available()


def test_child_value_comes_back(forking):
    job = forking.start(np.arange, 5, key="k")
    assert job is not None and job.key == "k"
    assert np.array_equal(job.result(), np.arange(5))


def test_child_failure_gives_none(forking):
    job = forking.start(int, "not a number")  # raises ValueError in the child
    assert job is not None
    assert job.result() is None


def test_child_writes_nothing_to_the_terminal(forking, capfd):
    def noisy():
        print("from the child")
        sys.stderr.write("child stderr\n")
        return 7

    job = forking.start(noisy)
    assert job is not None and job.result() == 7
    out, err = capfd.readouterr()
    assert "from the child" not in out and "child stderr" not in err


def test_close_kills_and_reaps_a_running_child(forking):
    job = forking.start(time.sleep, 60)
    assert job is not None
    t0 = time.perf_counter()
    job.close()
    assert time.perf_counter() - t0 < 5
    with pytest.raises(ChildProcessError):  # reaped: no zombie left behind
        os.waitpid(job.pid, os.WNOHANG)
    assert job.result() is None


def test_seed_check_pass_in_the_background_equals_the_serial_one(forking, monkeypatch):
    """The seed is lightly damped, so its check pass starts at t = 0 and can run alongside the run."""
    cfg, design = _seed()
    serial_state = {"console": False, "allowed": False}
    with monkeypatch.context() as m:
        m.setattr(background, "_state", serial_state)
        serial = run_simulation(cfg, design, want_series=True)
    started = []
    real_start = background.start

    def spy(fn, *args, **kw):
        job = real_start(fn, *args, **kw)
        started.append(job)
        return job

    monkeypatch.setattr(background, "start", spy)
    forked = run_simulation(cfg, design, want_series=True)
    assert len(started) == 1 and started[0] is not None  # the check pass did run in a child
    assert forked.solver.check_pass["nfev"] == serial.solver.check_pass["nfev"] > 0
    assert _without_times(forked) == _without_times(serial)  # every number, bit for bit


def test_a_result_for_another_plan_is_not_taken(forking):
    """check_pass takes the early result only when it was computed for the run's own plan."""
    from gearcli.scene import build_model
    from gearcli.simulate.choice import choose_method
    from gearcli.simulate.guards import nfev_budget
    from gearcli.simulate.solver import integrate
    from gearcli.simulate.stats import steady_window

    cfg, design = _seed()
    model = build_model(cfg, design)
    sim = cfg.simulation
    window, _ = steady_window(model.spec, sim.duration_s, sim.window_start_s)
    choice = choose_method(model.spec, sim.duration_s, "DOP853", sim.rtol)
    t_eval = np.linspace(0.0, sim.duration_s, sim.steps + 1)
    run = integrate(model, t_eval, "DOP853", sim.rtol)
    budget = nfev_budget(choice.indicator, sim.rtol)

    class Foreign:
        key = ("another plan",)

        def result(self):
            raise AssertionError("a result computed for another plan must not be read")

    ref = estimate.check_pass(model, run, choice, window, max_nfev=budget)
    other = estimate.check_pass(model, run, choice, window, max_nfev=budget, early=Foreign())
    assert _without_times(other) == _without_times(ref)


def _gearcli(args, env_extra=None, code=None):
    env = dict(os.environ, PYTHONPATH=str(ROOT), **(env_extra or {}))
    cmd = [sys.executable, "-c", code] if code else [sys.executable, "-m", "gearcli", *args]
    return subprocess.run(cmd, cwd=ROOT, env=env, capture_output=True, text=True, timeout=120)


@pytest.mark.skipif(sys.platform != "linux", reason="the background check pass is Linux-only")
def test_console_script_gives_the_serial_numbers():
    forked = _gearcli(["simulate", str(SEED), "--format", "json"])
    serial = _gearcli(["simulate", str(SEED), "--format", "json"], {background.SERIAL_ENV: "1"})
    assert forked.returncode == serial.returncode == 0, forked.stderr + serial.stderr
    a, b = json.loads(forked.stdout), json.loads(serial.stdout)
    assert _without_times(a) == _without_times(b)
    assert forked.stderr == serial.stderr  # the same warnings, nothing from the child


def test_quick_exit_flushes_output_and_runs_atexit(tmp_path):
    marker, out = tmp_path / "atexit.txt", tmp_path / "run.json"
    code = (
        "import atexit, sys\n"
        f"atexit.register(lambda: open({str(marker)!r}, 'w').write('ran'))\n"
        "sys.stdout.write('partial line without newline')\n"  # buffered: must reach the pipe
        f"sys.argv = ['gearcli', 'simulate', {str(SEED)!r}, '--format', 'json', '-o', {str(out)!r}]\n"
        "from gearcli.__main__ import main\n"
        "main()\n"
    )
    proc = _gearcli([], code=code)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout == "partial line without newline"
    assert marker.read_text() == "ran"
    assert json.loads(out.read_text())["summary"]["stages"][0]["tangential_N"]["mean"] > 0


def test_quick_exit_keeps_the_exit_code_of_a_bad_file(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[simulation\n")
    proc = _gearcli(["simulate", str(bad), "--format", "json"])
    assert proc.returncode == 2
    assert str(bad) in proc.stderr and "Traceback" not in proc.stderr


@pytest.mark.skipif(sys.platform != "linux" or len(os.sched_getaffinity(0)) < 2 or os.environ.get("GEARCLI_FRESH"),
                    reason="the background path forks on Linux with two CPUs only")
def test_forking_tests_in_a_fresh_interpreter():
    """The tests above skip in a test process that has loaded numba or started threads (the full suite does):
    run them again where nothing else ran, and require that none of them skips."""
    env = dict(os.environ, PYTHONPATH=str(ROOT), GEARCLI_FRESH="1")
    proc = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-rs", __file__],
                          cwd=ROOT, env=env, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-2000:]
    assert "no fork here" not in proc.stdout and " passed" in proc.stdout, proc.stdout[-3000:]
