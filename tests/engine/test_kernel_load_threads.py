"""Two threads of one process that run their first compiled simulations at once (a script using ``gearcli.api``
from a thread pool): the kernel is loaded once, by whichever asks first, the other waits for it
(``gearcli.engine.loader._LOCK``). Loading pops the kernel's modules from ``sys.modules`` and imports them anew, so
two threads loading together broke each other's import: one of them raised ``KeyError: 'gearcli.engine.kernel'``
(3 runs out of 3 before the lock). Checked in a fresh interpreter (a process loads the kernel once)."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import pytest

from gearcli import engine

ROOT = Path(__file__).resolve().parents[2]

SCRIPT = r"""
import json, sys, threading
from gearcli import api
from gearcli.io import serialize

cases = [[], ["input.speed_rpm=1200"]]
gate = threading.Barrier(len(cases))
out = [None] * len(cases)

def run(k):
    try:
        loaded, design = api.load_and_design(sys.argv[1], ["simulation.engine=compiled", *cases[k]])
        gate.wait()  # both reach the kernel's first load together
        doc = serialize.simulation_dict(api.simulate(loaded.design, design))
        out[k] = {"engine": doc["solver"]["engine"], "ratio": doc["summary"]["ratio"],
                  "output_speed_deg_s": doc["summary"]["output_speed_deg_s"],
                  "input_speed_deg_s": doc["summary"]["input_speed_deg_s"]}
    except BaseException as exc:
        out[k] = {"error": repr(exc)}

threads = [threading.Thread(target=run, args=(k,)) for k in range(len(cases))]
for t in threads:
    t.start()
for t in threads:
    t.join()
print(json.dumps(out))
"""


@pytest.mark.skipif(not engine.available(), reason="the compiled engine needs numba")
def test_two_threads_loading_the_kernel_at_once_both_run_compiled():
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    done = subprocess.run([sys.executable, "-c", SCRIPT, str(ROOT / "configs" / "concrete_mixer.toml")],
                          capture_output=True, text=True, env=env, timeout=600)
    assert done.returncode == 0, done.stderr[-2000:]
    rows = json.loads(done.stdout.strip().splitlines()[-1])
    assert [r.get("error") for r in rows] == [None, None], rows
    # the seed's train by hand: (51/21)(50/17)(53/17), its output at the input speed over that ratio
    ratio = (51 / 21) * (50 / 17) * (53 / 17)
    for row, rpm in zip(rows, (600.0, 1200.0), strict=True):  # the file's 3600 deg/s, then the --set speed
        assert row["engine"] == "compiled"
        assert math.isclose(row["input_speed_deg_s"], 6.0 * rpm, rel_tol=1e-12)
        assert math.isclose(row["ratio"], ratio, rel_tol=1e-4)
        assert math.isclose(row["output_speed_deg_s"], 6.0 * rpm / ratio, rel_tol=1e-4)
