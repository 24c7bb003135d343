"""A pool worker that dies costs the sweep its own task's points only, not every point that had not finished.

``ProcessPoolExecutor`` marks every unfinished future ``BrokenProcessPool`` when one worker dies (killed, out of
memory, a crash in compiled code). The sweep made all of them ``failed`` rows ("worker failed: BrokenProcessPool"),
and a re-run with the same ``-o`` took those rows as done: one worker killed 10 s into an 80-point sweep left 60
failed rows (6 of its 8 tasks), where docs/sweeps.md promises the dead worker's task's points only. Now the tasks
that had not started go on in a new pool, and each that had started runs again alone (up to twice): a task whose
worker dies alone on both tries is the culprit and its points not yet finished become ``failed`` rows (a pool worker
sends each row as its point ends: the points before the killing one are kept); a task that was only caught in the
break is computed, even where its own transient death first comes on its run alone.

The scenario runs in a child process with an injected evaluator (gearcli.api's is replaced, as in
test_sweep_injection.py): a point that kills its worker every time (value 5), one that kills it only the first
time (value 8, a transient death such as the out-of-memory killer), and points that run (each raises a
SimulationError naming its value, so its row shows that it ran). The rows are counted, not timed.
"""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap

import pytest

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="forkserver pool")

CHILD = textwrap.dedent("""
    import json, os, sys

    from gearcli.errors import SimulationError
    from gearcli.sweep.execute import execute
    from gearcli.sweep.spec import Point
    from gearcli.sweep.worker import Scene, Task

    MARK = sys.argv[1]


    def fake(scene, overrides, start=None, /, *, series=False, check=False):
        value = int(overrides[0].split("=")[1])
        if value == 5:  # kills its worker every time
            os._exit(9)
        if value == 8 and not os.path.exists(MARK):  # kills its worker the first time only
            open(MARK, "w").close()
            os._exit(9)
        raise SimulationError(f"ran {value}")


    if __name__ == "__main__":
        scene = Scene(b"", "plant.toml")
        points = [Point(i, (("load.torque_Nm", i),), "none") for i in range(12)]
        tasks = [Task(scene, tuple(points[i:i + 2]), False, fake) for i in range(0, 12, 2)]
        rows = list(execute(tasks, jobs=2))
        print(json.dumps([[r["load.torque_Nm"], r["status"], r["message"]] for r in rows]))
""")


def _rows(tmp_path, child: str) -> list:
    """The child scenario's rows, sorted by point: it exits 0 without a traceback, one row per point."""
    script = tmp_path / "child.py"
    script.write_text(child, encoding="utf-8")
    done = subprocess.run([sys.executable, str(script), str(tmp_path / "died_once")], capture_output=True,
                          text=True, timeout=240)
    assert done.returncode == 0 and "Traceback" not in done.stderr, done.stderr[-2000:]
    rows = sorted(json.loads(done.stdout.strip().splitlines()[-1]))
    assert [r[0] for r in rows] == list(range(12))  # one row per point, none lost, none twice
    return rows


def test_a_dead_worker_fails_its_own_task_and_the_others_run(tmp_path):
    rows = _rows(tmp_path, CHILD)
    assert all(status == "failed" for _, status, _ in rows)  # the fake evaluator fails every point it runs
    lost = [v for v, _, msg in rows if msg.startswith("worker failed: BrokenProcessPool")]
    # the point that kills its worker every time, nothing else: its task's point 4 ran before it, and a pool worker
    # sends each row as its point ends
    assert lost == [5]
    # every other point ran, the transient death's task (points 8 and 9) on its second try
    assert {v: msg for v, _, msg in rows if v not in lost} == {v: f"ran {v}" for v in range(12) if v != 5}
    assert (tmp_path / "died_once").exists()  # the transient death did happen


# the transient death's task caught in the break before it reached its own death (CI met it under load: the pool
# ended its worker between its start flag and point 8): its first run alone is where it dies, for the first time, and
# it runs on its second try alone. Held here: point 8's first sight waits to be ended by the break, and point 5 waits
# for it (at most 60 s) before it kills its worker
CAUGHT = CHILD.replace("""    if value == 5:  # kills its worker every time""", """    held = MARK + ".held"
    if value == 8 and not os.path.exists(held):  # caught in the break: ended by the pool before its own death
        open(held, "w").close()
        time.sleep(120)
    if value == 5:
        deadline = time.monotonic() + 60
        while not os.path.exists(held) and time.monotonic() < deadline:
            time.sleep(0.01)
    if value == 5:  # kills its worker every time""", 1).replace("import json, os, sys", "import json, os, sys, time", 1)
assert CAUGHT.count("held") == 5


def test_a_task_caught_in_the_break_that_then_dies_alone_once_runs_on_its_second_try(tmp_path):
    rows = _rows(tmp_path, CAUGHT)
    lost = [v for v, _, msg in rows if msg.startswith("worker failed: BrokenProcessPool")]
    assert lost == [5]
    assert {v: msg for v, _, msg in rows if v not in lost} == {v: f"ran {v}" for v in range(12) if v != 5}
    assert (tmp_path / "died_once").exists() and (tmp_path / "died_once.held").exists()


# the same scenario with the break landing while the round is still being submitted: submit() waits, after the
# task of the point that kills its worker, until that task's future is done (the pool broken under it), so the next
# submit raises BrokenProcessPool (under load a worker can die that early: CI met it as a traceback)
LATE_SUBMIT = CHILD.replace('if __name__ == "__main__":', textwrap.dedent('''
    import time
    from concurrent.futures import ProcessPoolExecutor

    real_submit = ProcessPoolExecutor.submit


    def submit_then_wait(self, fn, /, *args, **kwargs):
        fut = real_submit(self, fn, *args, **kwargs)
        if any(p.values[0][1] == 5 for p in args[1].points):  # the killing task: wait until the pool breaks
            deadline = time.monotonic() + 120
            while not fut.done() and time.monotonic() < deadline:
                time.sleep(0.01)
        return fut


    ProcessPoolExecutor.submit = submit_then_wait


    if __name__ == "__main__":''').strip("\n"), 1)


def test_a_worker_dead_before_the_round_is_submitted_costs_its_own_task_only(tmp_path):
    rows = _rows(tmp_path, LATE_SUBMIT)
    lost = [v for v, _, msg in rows if msg.startswith("worker failed: BrokenProcessPool")]
    assert lost == [5]
    assert {v: msg for v, _, msg in rows if v not in lost} == {v: f"ran {v}" for v in range(12) if v != 5}


# the break landing while submit() launches a worker (under load: CI hung on it, 2 runs in ~10). The round after the
# first break (tasks 3-5 on a new pool) launches its second worker in submit(task 4); its first worker runs tasks 3
# and 4 meanwhile and dies of point 8. The scenario holds that launch (CPython 3.11 launches workers in submit(),
# and its pool's thread fails the pool without submit()'s lock) until the pool is broken: either in the forkserver's
# handshake, the worker already forked (it entered the pool's table after the pool's thread had ended the workers it
# knew: never told to stop, it waited on its task queue and the pool's shutdown waited on it for ever), or before the
# launch began (the worker's start data refers to the task queue the break closed: OSError from submit(), a
# traceback)
HOLD_LAUNCH = '''
import time
from multiprocessing import forkserver

real_spawn = ProcessPoolExecutor._spawn_process
real_connect = forkserver.connect_to_new_process
HOLDING = []


def _holds_the_transient_death(pool):
    return (pool._processes and not os.path.exists(MARK)
            and any(p.values[0][1] == 8 for w in pool._pending_work_items.values() for p in w.args[1].points))


def _until_broken(pool):
    deadline = time.monotonic() + 120
    while not pool._broken and time.monotonic() < deadline:
        time.sleep(0.01)
    time.sleep(0.2)  # the pool's thread ends the workers it knows


def spawn_held(self):
    if _holds_the_transient_death(self):
        if WHERE == "before":
            _until_broken(self)
        else:
            HOLDING.append(self)
    try:
        real_spawn(self)
    finally:
        HOLDING.clear()


def connect_held(fds):
    got = real_connect(fds)
    for pool in HOLDING:
        _until_broken(pool)
    return got


ProcessPoolExecutor._spawn_process = spawn_held
forkserver.connect_to_new_process = connect_held


if __name__ == "__main__":'''


@pytest.mark.parametrize("where", ["during", "before"])
def test_a_worker_dead_while_another_is_launched_costs_its_own_task_only(tmp_path, where):
    child = LATE_SUBMIT.replace('\nif __name__ == "__main__":', f"\nWHERE = {where!r}\n" + HOLD_LAUNCH, 1)
    rows = _rows(tmp_path, child)
    lost = [v for v, _, msg in rows if msg.startswith("worker failed: BrokenProcessPool")]
    assert lost == [5]
    # the transient death's task (points 8 and 9) ran on its second try
    assert {v: msg for v, _, msg in rows if v not in lost} == {v: f"ran {v}" for v in range(12) if v != 5}
    assert (tmp_path / "died_once").exists()
