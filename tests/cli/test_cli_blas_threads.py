"""The command line runs BLAS on one thread, as a Dask worker does, so that a sweep's rows on a cluster are those of
``--jobs`` (docs/sweeps.md). scipy's Radau factorises through OpenBLAS, whose results depend on its thread count:
before, a Python-engine Radau sweep of configs/planetary_stage.toml on a `dask worker` differed from the same sweep
with --jobs 1 or 2 on a 2-core machine (stage 1 mean F_t -11695.906432711 against -11695.906432540 N, std 1.8e-12
against 0), and a one-shot run took 6,433 evaluations on 2 threads against 6,561 on 1."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from gearcli.__main__ import BLAS_THREADS, one_blas_thread

SCENE = str(Path(__file__).resolve().parents[2] / "configs" / "planetary_stage.toml")
RUN = ["simulate", SCENE, "--set", "input.speed_rpm=1200", "--set", "load.torque_Nm=15000", "--set",
       "simulation.duration_s=0.2", "--set", "simulation.engine=python", "--set", "simulation.method=Radau",
       "--format", "json"]


def test_one_blas_thread_unless_the_user_chose(monkeypatch):
    for name in BLAS_THREADS:
        monkeypatch.delenv(name, raising=False)
    monkeypatch.setenv("OPENBLAS_NUM_THREADS", "4")
    one_blas_thread()
    assert [os.environ[n] for n in BLAS_THREADS] == ["1", "1", "4"]


def _run(extra_env: dict[str, str]) -> dict:
    env = {k: v for k, v in os.environ.items() if k not in BLAS_THREADS} | extra_env
    out = subprocess.run([sys.executable, "-m", "gearcli", *RUN], env=env, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    got = json.loads(out.stdout)
    return {"nfev": got["solver"]["nfev"], "stages": got["summary"]["stages"]}


def test_a_run_is_the_one_a_dask_worker_computes():
    """The reference: the environment a Dask worker's nanny gives its worker process (distributed's
    ``pre-spawn-environ``: OMP, MKL and OpenBLAS on one thread), against the command's own default."""
    dask = pytest.importorskip("dask")
    pytest.importorskip("distributed")
    worker_env = {k: str(v) for k, v in dask.config.get("distributed.nanny.pre-spawn-environ").items()
                  if k in BLAS_THREADS}
    assert worker_env == dict.fromkeys(BLAS_THREADS, "1")
    assert _run({}) == _run(worker_env)
