"""The compiled kernel's stop flag (issue 31): raised before or during a run, the kernel returns at its next accepted
step with status INTERRUPTED, its samples up to there intact, and a run without the flag is unchanged."""

from __future__ import annotations

import threading
import time
from pathlib import Path

import numpy as np
import pytest

from gearcli.engine import status as st

pytest.importorskip("numba")
ROOT = Path(__file__).resolve().parents[2]


def _args(duration_s: float, rtol: float):
    from gearcli import engine
    from gearcli.config import load_design
    from gearcli.design import compute_design
    from gearcli.scene import build_model
    from gearcli.simulate.solver import breakpoints

    cfg = load_design(str(ROOT / "configs" / "concrete_mixer.toml"), []).design
    model = build_model(cfg, compute_design(cfg))
    y = model.initial_state()
    n = y.size
    t_eval = np.linspace(0.0, duration_s, 2001)
    wpar = np.zeros(st.WP_STOP + 1)
    atol = np.array(np.broadcast_to(np.asarray(model.arrays.atol, dtype=float), (n,)))
    return (engine.pack(model.arrays), y, t_eval, np.array(breakpoints(model, duration_s, 0.0)), np.full(n, rtol),
            atol, np.int64(10**9), np.int64(0), wpar, np.empty(0)), wpar


@pytest.mark.parametrize("method", ["dop853", "radau"])
def test_a_raised_flag_stops_the_kernel_at_its_first_step(method):
    from gearcli import engine

    kernel = getattr(engine.load(quiet=True).kernel, method)
    args, wpar = _args(0.5, 1e-6)
    wpar[st.WP_STOP] = 1.0
    out, counters, floats, _ = kernel(*args)
    assert counters[2] == st.INTERRUPTED and counters[1] == 1  # one accepted step, then the flag was read
    assert floats[0] < 0.5


def test_a_flag_raised_from_another_thread_stops_a_long_run_early():
    from gearcli import engine

    kernel = engine.load(quiet=True).kernel.dop853
    args, wpar = _args(3000.0, 1e-10)  # ~30 s of work: still running when the flag is raised (30 s of the seed
    # took 0.36 s once the kernel lost numba's reference counts, finishing before the flag of a 0.2 s sleep)
    box = {}
    worker = threading.Thread(target=lambda: box.setdefault("r", kernel(*args)))
    worker.start()
    time.sleep(0.2)
    wpar[st.WP_STOP] = 1.0
    worker.join(30)
    assert not worker.is_alive()
    out, counters, floats, _ = box["r"]
    assert counters[2] == st.INTERRUPTED and 0.0 < floats[0] < 3000.0
    done = int(counters[3])
    assert np.all(np.isfinite(out[:, :done])) and np.all(np.isnan(out[:, done:]))  # samples up to the stop, no more
