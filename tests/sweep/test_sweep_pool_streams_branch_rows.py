"""On a process pool (``--jobs 2``) a continuation branch's rows reach the sweep as each point finishes, not when
the whole branch does (docs/sweeps.md: "Rows are written as tasks finish ... the file keeps every finished point"
after a Ctrl-C).

A branch is one task, run in order by one worker. The worker returned the branch's rows in one list at the task's
end, so a Ctrl-C before that kept none of its finished points (`--jobs 1` streams them: 20 of a branch's points
finished and written at `--jobs 1` were 0 rows at `--jobs 2`). Now a pool worker sends each row as its point ends.

The scenario runs in a child process with an injected evaluator (as test_sweep_worker_death.py does): two branches
of six points; each branch's last point waits until the consumer has received the ten points before it (a file the
consumer creates) and says whether it was released or gave up after 20 s. Rows are counted, not timed. A second
scenario kills a branch's worker after three of its rows were sent: the branch runs again alone and each point is
still one row (the three sent ones are computed again for the branch's state, not sent twice).
"""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap

import pytest

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="forkserver pool")

CHILD = textwrap.dedent("""
    import json, os, sys, time

    from gearcli.errors import SimulationError
    from gearcli.sweep.execute import execute
    from gearcli.sweep.spec import Point
    from gearcli.sweep.worker import Scene, Task

    WORK = sys.argv[1]
    RELEASE = os.path.join(WORK, "release")
    DIED = os.path.join(WORK, "died_once")


    def fake(scene, overrides, start=None, /, *, series=False, check=False):
        value = int(overrides[0].split("=")[1])
        if value in (5, 11):  # a branch's last point: waits for the consumer to hold the branch's other rows
            deadline = time.monotonic() + 20
            while not os.path.exists(RELEASE) and time.monotonic() < deadline:
                time.sleep(0.01)
            raise SimulationError(f"{'released' if os.path.exists(RELEASE) else 'gave up'} {value}")
        if value == 3 and sys.argv[2] == "die" and not os.path.exists(DIED):  # its worker dies the first time
            open(DIED, "w").close()
            os._exit(9)
        raise SimulationError(f"ran {value}")


    if __name__ == "__main__":
        branches = [[Point(i, (("load.torque_Nm", i),), "up") for i in range(k, k + 6)] for k in (0, 6)]
        tasks = [Task(Scene(b"", "plant.toml"), tuple(b), True, fake) for b in branches]
        got = []
        for row in execute(tasks, jobs=2):
            got.append([row["load.torque_Nm"], row["message"]])
            if len(got) == 10 and sys.argv[2] != "die":
                open(RELEASE, "w").close()
            if sys.argv[2] == "die" and len(got) == 4 and not os.path.exists(RELEASE):
                open(RELEASE, "w").close()  # (the dying branch's rows need not come first)
        print(json.dumps(got))
""")


def _run(tmp_path, mode: str) -> list:
    script = tmp_path / "child.py"
    script.write_text(CHILD, encoding="utf-8")
    done = subprocess.run([sys.executable, str(script), str(tmp_path), mode], capture_output=True, text=True,
                          timeout=240)
    assert done.returncode == 0 and "Traceback" not in done.stderr, done.stderr[-2000:]
    return json.loads(done.stdout.strip().splitlines()[-1])


def test_a_branch_on_a_pool_sends_each_row_as_its_point_finishes(tmp_path):
    got = _run(tmp_path, "stream")
    # every point once; each branch's last point ran after the consumer had received the ten points before them
    assert sorted(v for v, _ in got) == list(range(12))
    assert {v: m for v, m in got if v in (5, 11)} == {5: "released 5", 11: "released 11"}
    assert {v for v, _ in got[:10]} == set(range(12)) - {5, 11}
    # within a branch the rows come in the branch's order
    for branch in (range(6), range(6, 12)):
        assert [v for v, _ in got if v in branch] == list(branch)


def test_a_branch_whose_worker_dies_after_sending_rows_runs_again_without_sending_them_twice(tmp_path):
    got = _run(tmp_path, "die")
    assert (tmp_path / "died_once").exists()  # the worker did die under point 3
    assert sorted(v for v, _ in got) == list(range(12))  # one row per point, none twice, none lost
    assert {v: m for v, m in got if v not in (5, 11)} == {v: f"ran {v}" for v in range(12) if v not in (5, 11)}
