"""Running the tasks: in this process, on a local process pool, or on a Dask distributed cluster.

Rows come back in order of completion (per task on a pool or cluster, per point in this process).
Independent points are batched so that a task does real work (:func:`plan`); a continuation branch is
always one task, run in order. Pool workers ignore SIGINT: Ctrl-C reaches only this process, which
cancels what has not started and stops (the rows already yielded are kept by the caller).
"""

from __future__ import annotations

import dataclasses
import math
import os
import signal
from collections.abc import Iterable, Iterator, Sequence

from gearcli.errors import ConfigError
from gearcli.sweep.columns import failed_row
from gearcli.sweep.spec import Point, SweepSpec
from gearcli.sweep.worker import Scene, Task, iter_task, run_task

DISTRIBUTED_HINT = "pip install 'gearcli[distributed]'"
MAX_BATCH = 32  # points per task: a few seconds of work, while a Ctrl-C or a lost worker costs little
TASKS_PER_WORKER = 4  # enough tasks to balance the load between workers


def default_jobs() -> int:
    return os.cpu_count() or 1


def plan(spec: SweepSpec, scene: Scene, done: set[tuple], workers: int) -> tuple[list[Task], int]:
    """The tasks that produce every point not in ``done`` (idents), and how many points they return.

    A continuation branch is one task; its points up to the last missing one are computed (a point's
    start state needs its predecessors), the ones already written are not returned again."""
    tasks: list[Task] = []
    single: list[Point] = []
    todo = 0
    for branch in spec.branches():
        missing = [i for i, p in enumerate(branch) if p.ident not in done]
        if not missing:
            continue
        todo += len(missing)
        if len(branch) == 1 or not spec.direction:
            single.extend(branch[i] for i in missing)
            continue
        head = branch[:missing[-1] + 1]
        skip = frozenset(p.index for p in head if p.ident in done)
        tasks.append(Task(scene, tuple(head), True, skip))
    size = batch_size(len(single), workers)
    tasks += [Task(scene, tuple(single[i:i + size]), False) for i in range(0, len(single), size)]
    share = math.ceil(todo / max(1, workers))  # each worker's part of the sweep (engine = "auto" amortises over it)
    return [dataclasses.replace(t, runs_hint=share) for t in tasks], todo


def batch_size(n_points: int, workers: int) -> int:
    return max(1, min(MAX_BATCH, math.ceil(n_points / (max(1, workers) * TASKS_PER_WORKER))))


def execute(tasks: Sequence[Task], *, jobs: int = 1, scheduler: str | None = None) -> Iterator[dict]:
    """Every row of every task, in order of completion."""
    if scheduler:
        return _dask(tasks, scheduler)
    if jobs <= 1 or len(tasks) <= 1:  # no pool to start for one task
        return _inline(tasks)
    return _pool(tasks, jobs)


def _inline(tasks: Iterable[Task]) -> Iterator[dict]:
    for task in tasks:
        yield from iter_task(task)


def _ignore_sigint() -> None:
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def _lost(task: Task, exc: BaseException) -> list[dict]:
    """Rows for a task whose worker failed outright (not a point failure: a crash or a lost worker)."""
    msg = f"worker failed: {type(exc).__name__}: {exc}"
    return [{"_index": p.index, **failed_row(p.values, p.direction, msg, 0.0)}
            for p in task.points if p.index not in task.skip]


def _pool(tasks: Sequence[Task], jobs: int) -> Iterator[dict]:
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor, as_completed

    ctx = multiprocessing.get_context("forkserver")
    ctx.set_forkserver_preload(["gearcli.sweep.worker", "gearcli.simulate"])
    pool = ProcessPoolExecutor(max_workers=min(jobs, len(tasks)), mp_context=ctx, initializer=_ignore_sigint)
    try:
        futures = {pool.submit(run_task, t): t for t in tasks}
        for fut in as_completed(futures):
            try:
                rows = fut.result()
            except Exception as exc:  # noqa: BLE001 - a broken worker: its points become failed rows
                rows = _lost(futures[fut], exc)
            yield from rows
    finally:
        pool.shutdown(wait=False, cancel_futures=True)


def require_distributed() -> None:
    try:
        import distributed  # noqa: F401
    except ImportError:
        raise ConfigError(f"--scheduler needs dask.distributed: {DISTRIBUTED_HINT}", source="--scheduler") from None


def _dask(tasks: Sequence[Task], address: str) -> Iterator[dict]:
    require_distributed()
    from distributed import Client, as_completed

    try:
        client = Client(address, timeout="10s")
    except (OSError, TimeoutError, ValueError) as exc:
        raise ConfigError(f"cannot reach the Dask scheduler at {address}: {exc}", source="--scheduler") from None
    futures = []
    try:
        futures = [client.submit(run_task, t, pure=False) for t in tasks]
        by_key = {f.key: t for f, t in zip(futures, tasks, strict=True)}
        for fut in as_completed(futures):
            try:
                rows = fut.result()
            except Exception as exc:  # noqa: BLE001 - a lost worker or a task error: failed rows
                rows = _lost(by_key[fut.key], exc)
            yield from rows
    finally:
        if futures:
            client.cancel(futures)
        client.close()
