"""Running the tasks: in this process, on a local process pool, or on a Dask distributed cluster.

Rows come back in order of completion (per point in this process and on a pool, whose workers send each row as its
point ends; per task on a cluster).
Independent points are batched so that a task does real work (:func:`plan`); a continuation branch is
always one task, run in order. Pool workers ignore SIGINT: Ctrl-C reaches only this process, which
cancels what has not started and stops (the rows already yielded are kept by the caller).
"""

from __future__ import annotations

import dataclasses
import logging
import math
import multiprocessing
import multiprocessing.connection
import os
import signal
import socket
import threading
from collections import Counter
from collections.abc import Callable, Collection, Generator, Iterable, Iterator, Mapping, Sequence
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from multiprocessing import forkserver
from typing import Any, NamedTuple, cast
from urllib.parse import urlsplit

from gearcli import __version__, engine
from gearcli.core.signals import deferred
from gearcli.core.text import shorten
from gearcli.errors import ConfigError, SimulationError
from gearcli.sweep.columns import Row, failed_row
from gearcli.sweep.family import Family, family_of
from gearcli.sweep.spec import Point, SweepSpec
from gearcli.sweep.worker import PointEvaluator, Scene, Task, iter_task, run_task

DISTRIBUTED_HINT = "pip install 'gearcli[distributed]'"
MAX_BATCH = 32  # points per task: a few seconds of work, while a Ctrl-C or a lost worker costs little
TASKS_PER_WORKER = 4  # enough tasks to balance the load between workers


WORKER_BASE_BYTES = 128 * 2**20  # a pool worker with gearcli, numpy and scipy loaded: ~90 MB RSS measured, rounded up


def usable_cores() -> int:
    """The cores this process may run on (its CPU affinity), else the machine's count."""
    try:
        return len(os.sched_getaffinity(0)) or 1
    except (AttributeError, OSError):
        return os.cpu_count() or 1


def available_memory_bytes() -> float | None:
    """Memory available to new processes (``MemAvailable`` of /proc/meminfo), or None where unknown."""
    try:
        with open("/proc/meminfo", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    return float(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    try:
        return float(os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE"))
    except (AttributeError, ValueError, OSError):
        return None


def default_jobs() -> int:
    return usable_cores()


def jobs_cap(point_bytes: float) -> tuple[int, str]:
    """The most worker processes this machine carries: one per usable core, and as many as the available
    memory holds at ``WORKER_BASE_BYTES + point_bytes`` each (``point_bytes``: one point's samples, the memory
    estimate of gearcli.config.bounds). Returns the cap and the reason in words."""
    cores = usable_cores()
    avail = available_memory_bytes()
    per = WORKER_BASE_BYTES + max(0.0, point_bytes)
    by_memory = max(1, int(avail // per)) if avail is not None else cores
    cap = max(1, min(cores, by_memory))
    memory = f", {avail / 2**30:.3g} GiB available at ~{per / 2**20:.0f} MiB per worker" if avail is not None else ""
    return cap, f"{cores} usable core{'s' if cores != 1 else ''}{memory}"


def plan(spec: SweepSpec, scene: Scene, done: Mapping[tuple[str, ...], int], workers: int,
         evaluate: PointEvaluator, unresolved: Collection[tuple[str, ...]] = ()) -> tuple[list[Task], int]:
    """The tasks that produce every point not in ``done`` (idents and how many rows of each the file holds: the
    first that many points of an ident are done), and how many points they return; each evaluates its points
    with ``evaluate``.

    A continuation branch is one task; its points up to the last missing one are computed (a point's
    start state needs its predecessors), the ones already written are not returned again. Independent points go in
    batches; a family (:mod:`gearcli.sweep.family`) with points to run whose checked point is written with an
    unresolved verdict (its ident in ``unresolved``) has that point run again, not returned, for the verdict."""
    tasks: list[Task] = []
    single: list[Point] = []
    checked: list[Point] = []  # independent checked points already written (their family's verdict: gearcli.sweep.family)
    todo = 0
    left = Counter(done)
    for branch in spec.branches():
        written = [_take(left, p.ident) for p in branch]
        missing = [i for i, w in enumerate(written) if not w]
        independent = len(branch) == 1 or not spec.direction
        if independent:
            checked.extend(p for p, w in zip(branch, written, strict=True) if w and Family.needs_check(p.index)
                           and p.ident in unresolved)
        if not missing:
            continue
        todo += len(missing)
        if independent:
            single.extend(branch[i] for i in missing)
            continue
        head = branch[:missing[-1] + 1]
        skip = frozenset(p.index for p, w in zip(head, written, strict=False) if w)
        tasks.append(Task(scene, tuple(head), True, evaluate, skip))
    families = {family_of(p.index) for p in single}
    again = {p.index: p for p in checked if family_of(p.index) in families}  # written: run for the verdict alone
    single = sorted([*single, *again.values()], key=lambda p: p.index)
    size = batch_size(len(single), workers)
    tasks += [Task(scene, tuple(part), False, evaluate, frozenset(again) & {p.index for p in part})
              for part in (single[i:i + size] for i in range(0, len(single), size))]
    share = math.ceil(todo / max(1, workers))  # each worker's part of the sweep (engine = "auto" amortises over it)
    # loading the kernel priced alike for every point, at any --jobs, after a resume, on any machine load
    price = engine.sweep_load_share_s(sum(len(b) for b in spec.branches()))
    return [dataclasses.replace(t, runs_hint=share, load_share_s=price) for t in tasks], todo


def _take(left: Counter, ident: tuple[str, ...]) -> bool:
    """Whether a row of ``ident`` is left in the file for this point (and count it as used)."""
    if left[ident] > 0:
        left[ident] -= 1
        return True
    return False


def batch_size(n_points: int, workers: int) -> int:
    return max(1, min(MAX_BATCH, math.ceil(n_points / (max(1, workers) * TASKS_PER_WORKER))))


def execute(tasks: Sequence[Task], *, jobs: int = 1, scheduler: str | None = None) -> Iterator[Row]:
    """Every row of every task, in order of completion."""
    if scheduler:
        return _dask(tasks, scheduler)
    if jobs <= 1 or len(tasks) <= 1:  # no pool to start for one task
        return _inline(tasks)
    return _pool(tasks, jobs)


def _inline(tasks: Iterable[Task]) -> Iterator[Row]:
    for task in tasks:
        yield from iter_task(task)


def _ignore_sigint() -> None:
    """A pool worker's start: Ctrl-C is the parent's to handle; the compilation notice is the parent's too."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)

    engine.quiet_compilation()


def _lost(task: Task, exc: BaseException) -> list[Row]:
    """Rows for a task whose worker failed outright (not a point failure: a crash or a lost worker)."""
    msg = f"worker failed: {type(exc).__name__}: {exc}"
    return [{"_index": p.index, **failed_row(p.cells(), p.direction, msg, 0.0)}
            for p in task.points if p.index not in task.skip]


def _pool(tasks: Sequence[Task], jobs: int) -> Iterator[Row]:
    """Every row of ``tasks`` on a pool of ``jobs`` worker processes. A worker that dies (killed, out of memory, a
    crash in compiled code) breaks a ``ProcessPoolExecutor`` for every task not yet finished, not only its own: the
    tasks that had not started go on in a new pool, and each that had started runs again alone, so that only the
    dead worker's own task becomes ``failed`` rows (it dies alone too, :func:`_alone`) and the others' points are
    computed."""
    queue, idle_breaks = list(tasks), 0
    while queue:
        started, broken, queue = yield from _pool_round(queue, jobs)
        idle_breaks = idle_breaks + 1 if broken is not None and not started else 0
        if idle_breaks >= 2:  # two pools in a row broke with no task of theirs started: this pool cannot run them
            for task in queue:
                yield from _lost(task, cast(BaseException, broken))
            return
        for task in started:
            yield from _alone(task)


ALONE_TRIES = 2  # a task caught in a pool's break runs alone up to this many times before its points are failed


def _alone(task: Task) -> Iterator[Row]:
    """Run a task caught in a pool's break again on a pool of its own. A worker that dies under it alone is the
    task's own death, but maybe not a lasting one (the out-of-memory killer, another process's burst): a task
    interrupted by another's break before it reached its own transient death meets that death here for the first
    time. It is tried again alone, and becomes ``failed`` rows only when its worker dies on every try."""
    lost: BaseException | None = None
    for _ in range(ALONE_TRIES):
        started, lost, _ = yield from _pool_round([task], 1)
        if lost is None:
            return
        if not started:  # every row it had to send was sent before its worker died
            return
        task = started[0]
    yield from _lost(task, cast(BaseException, lost))


def _pool_round(tasks: Sequence[Task], jobs: int) -> Generator[Row, None, _Round]:
    """Run ``tasks`` on one pool, yielding their rows; returns (the tasks that had started when the pool broke, the
    exception that broke it (None: it did not), the tasks that had not started)."""
    ctx = multiprocessing.get_context("forkserver")
    ctx.set_forkserver_preload(["gearcli.sweep.worker", "gearcli.simulate", "gearcli.api"])
    _start_forkserver_deaf()
    marks = ctx.RawArray("b", len(tasks))  # a worker sets its task's flag as it starts it
    sent = ctx.SimpleQueue()  # (task number, row) as each point ends: a branch's rows before the branch ends
    pool = ProcessPoolExecutor(max_workers=min(jobs, len(tasks)), mp_context=ctx, initializer=_start_worker,
                               initargs=(marks, sent))
    started: list[tuple[int, Task]] = []  # (task number, what of it is left to run)
    unstarted: list[tuple[int, Task]] = []
    broken: BaseException | None = None
    got: dict[int, set[int]] = {i: set() for i in range(len(tasks))}  # the points each task's rows came for
    try:
        # submitting starts the workers (the first waits for the forkserver's preload): a signal meanwhile is held
        # until each has started and is in the pool's table, where the handler below ends it; raised inside
        # Process.start it left a worker that read its start after we had gone (a FileNotFoundError traceback)
        futures: dict = {}
        caught: list[tuple[int, Task]] = []  # submitted as the pool broke, without a future: it may have started
        with deferred():
            for i, t in enumerate(tasks):
                try:
                    futures[pool.submit(_run_marked, i, t)] = (i, t)
                except (BrokenProcessPool, OSError) as exc:  # a worker died while the round was being submitted
                    if not isinstance(exc, BrokenProcessPool) and not _is_broken(pool):
                        raise
                    # OSError: the break came while this submit launched a worker, after its check of the pool
                    # (the pool's queue closed under the launch): the task is in the pool's table, maybe started
                    broken = exc if isinstance(exc, BrokenProcessPool) else BrokenProcessPool(_is_broken(pool))
                    caught = [] if isinstance(exc, BrokenProcessPool) else [(i, t)]
                    unstarted.extend((n, t) for n, t in enumerate(tasks) if n >= i + len(caught))  # never submitted
                    break
        pending = set(futures)
        while pending:
            done, pending = wait(pending, timeout=ROW_POLL_S, return_when=FIRST_COMPLETED)
            yield from _received(sent, got)  # a done task's rows were all sent before it returned
            for fut in done:
                i, task = futures[fut]
                try:
                    fut.result()
                except BrokenProcessPool as exc:  # a worker died: this task's or another's
                    broken = exc
                    if marks[i]:
                        started.extend((i, t) for t in _rest(task, got[i]))
                    else:
                        unstarted.append((i, task))
                except Exception as exc:  # noqa: BLE001 - a task that failed outright: its points become failed rows
                    yield from _lost(_without(task, got[i]), exc)
        if _is_broken(pool):
            _end_strays(pool)
        for i, task in caught:
            if marks[i]:
                started.extend((i, t) for t in _rest(task, got[i]))
            else:
                unstarted.append((i, task))
    except BaseException:  # Ctrl-C, SIGTERM/SIGHUP, the consumer gone (GeneratorExit): no worker outlives us
        _stop_workers(pool)
        raise
    finally:
        pool.shutdown(wait=True, cancel_futures=True)  # joins the pool's thread: its queues and semaphores released
        sent.close()
    return _Round([t for _, t in sorted(started, key=lambda it: it[0])], broken,
                  [t for _, t in sorted(unstarted, key=lambda it: it[0])])


ROW_POLL_S = 0.05  # how often the parent looks for rows sent while no task ends


def _received(sent, got: dict[int, set[int]]) -> Iterator[Row]:
    """The rows the workers have sent so far, noting each task's points whose rows (or verdicts alone) came."""
    while not sent.empty():
        i, row = sent.get()
        got[i].add(int(row["_index"]))
        yield row


def _without(task: Task, sent: set[int]) -> Task:
    """``task`` with the points whose rows were sent not returned again: a branch computes them again for its
    state (its ``skip``), independent points are left out."""
    if task.continuation:
        return dataclasses.replace(task, skip=task.skip | sent)
    return dataclasses.replace(task, points=tuple(p for p in task.points if p.index not in sent))


def _rest(task: Task, sent: set[int]) -> list[Task]:
    """What of a task caught in a pool's break is left to run: none when every row it had to send came."""
    left = _without(task, sent)
    return [left] if any(p.index not in left.skip for p in left.points) else []


class _Round(NamedTuple):
    started: list[Task]  # had started when the pool broke
    broken: BaseException | None  # what broke the pool (None: it did not)
    unstarted: list[Task]


_MARKS = None  # a pool worker's view of its round's started-task flags (:func:`_start_worker`)
_SENT: Any = None  # a pool worker's end of its round's row queue (a SimpleQueue)


def _start_worker(marks, sent) -> None:
    """A pool worker's start: the round's started-task flags and row queue; Ctrl-C is the parent's
    (:func:`_ignore_sigint`)."""
    global _MARKS, _SENT
    _MARKS, _SENT = marks, sent
    _ignore_sigint()
    _end_with_parent()


def _end_with_parent() -> None:
    """End this pool worker as soon as the sweep's process is gone. A parent that is killed outright (SIGKILL, the
    out-of-memory killer, a job's time limit) ends no worker: each went on computing its task's points for nobody,
    then waited for ever, blocked writing rows into a pipe no one reads or reading a task queue no one fills (every
    worker holds both ends of the pool's queues, so neither ever sees an end of file), with its memory held and the
    forkserver kept alive beside it. The parent's sentinel (the pipe it started the worker through) reads ready the
    moment the parent's process ends, however it ends."""
    parent = multiprocessing.parent_process()
    if parent is None:
        return

    def watch() -> None:
        multiprocessing.connection.wait([parent.sentinel])
        # killed as its parent was: no handler runs (a SIGTERM would unwind into a row written to a pipe no one
        # reads, the very block this ends) and nothing is left for anyone to read
        os.kill(os.getpid(), signal.SIGKILL)

    threading.Thread(target=watch, name="gearcli-parent-watch", daemon=True).start()


def _run_marked(index: int, task: Task) -> None:
    """Run a task in a pool worker, first flagging it started (a worker that dies is then known to have held it),
    and send each row to the parent as its point ends (a branch's too: a Ctrl-C keeps its finished points)."""
    if _MARKS is not None:
        _MARKS[index] = 1
    for row in iter_task(task):
        _SENT.put((index, row))


def _start_forkserver_deaf() -> None:
    """Start the forkserver with SIGINT ignored, a disposition that exec keeps and Python then leaves alone (so its
    workers inherit it too): Ctrl-C on a terminal reaches the whole process group, and a forkserver still starting
    Python or importing its preload (half a second of numpy, scipy and gearcli) died of it with a KeyboardInterrupt
    traceback on the user's terminal. This process handles Ctrl-C (exit 130) and ends the workers. (A blocked
    signal mask would keep a Ctrl-C of these few milliseconds for us, but the server's exec does not inherit it.)"""
    if threading.current_thread() is not threading.main_thread():  # no handler to swap there
        forkserver.ensure_running()
        return
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        forkserver.ensure_running()
    finally:
        signal.signal(signal.SIGINT, previous)


def _is_broken(pool) -> str:
    """Why the pool is broken ('': it is not): a worker died and the pool's thread failed its futures."""
    return getattr(pool, "_broken", "") or ""


def _end_strays(pool) -> None:
    """End the workers of a broken pool that are still alive. The pool's thread ends those in its table when a
    worker dies, but a worker that ``submit`` was launching at that moment (CPython 3.11 launches them there, and
    its thread fails the pool without the lock ``submit`` holds) enters the table after, is never told to stop, and
    waits on its task queue for ever: ``shutdown(wait=True)`` then waited for the pool's thread, which waits to join that worker (a sweep
    hung with its rows written). Called once every submit has returned: no worker is launched after it."""
    _end([p for p in list((getattr(pool, "_processes", None) or {}).values()) if p.is_alive()])


def _end(processes: list) -> None:
    for proc in processes:
        proc.terminate()
    for proc in processes:
        proc.join(timeout=10)


def _stop_workers(pool) -> None:
    """End the pool's workers now (each is mid-point; its rows are lost, the rows already yielded are kept).
    ``ProcessPoolExecutor.terminate_workers`` exists from Python 3.14; before, the pool's own process table."""
    terminate = getattr(pool, "terminate_workers", None)
    if terminate is not None:
        terminate()
    processes = list((getattr(pool, "_processes", None) or {}).values())
    # and a worker started but not yet in the pool's table (the signal came while the pool was launching it):
    # left running, it reads its start from the parent after the parent has gone (its queues' semaphores
    # unlinked) and prints a FileNotFoundError traceback on the user's terminal
    processes += [p for p in multiprocessing.active_children() if p not in processes]
    _end(processes)
    _release_result_reader(pool)


def _release_result_reader(pool) -> None:
    """Close this process's end of the pool's result pipe once its workers are gone. A worker ended while it was
    writing its task's rows leaves half a message in the pipe; the pool's manager thread, reading it, waited for
    the rest for ever, and ``shutdown(wait=True)`` (and the interpreter's exit, which joins that thread) with it:
    a Ctrl-C or SIGTERM hung the sweep with its finished rows unwritten. With no writer left the read ends (EOF),
    the thread marks the pool broken and ends."""
    writer = getattr(getattr(pool, "_result_queue", None), "_writer", None)
    if writer is not None:
        writer.close()


def require_distributed() -> None:
    try:
        import distributed  # noqa: F401  # lazy: distributed, the optional dask extra
    except ImportError:
        raise ConfigError(f"--scheduler needs dask.distributed: {DISTRIBUTED_HINT}", source="--scheduler") from None


SCHEDULER_TIMEOUT_S = 5.0  # connecting, the scheduler's greeting, the client's handshake: each bounded
SCHEDULER_SCHEMES = ("tcp", "tls", "ws", "wss", "ucx", "inproc")  # Dask's comm protocols; only tcp:// is probed
MAX_GREETING_BYTES = 2**30  # the first frame a Dask scheduler sends is its handshake: a few dozen bytes


def scheduler_endpoint(address: str) -> tuple[str, str, int]:
    """``tcp://HOST:PORT`` (or another Dask protocol), ``HOST:PORT`` as (scheme, host, port); ConfigError otherwise."""
    text = address.strip()
    if not text:
        raise ConfigError("an empty address: give the scheduler's tcp://HOST:PORT, or leave out --scheduler to run "
                          "on this machine", source="--scheduler")
    scheme, sep, _ = text.partition("://")
    scheme = scheme.lower() if sep else "tcp"
    if scheme not in SCHEDULER_SCHEMES:
        raise ConfigError(f"{shorten(text)}: a Dask scheduler's address is tcp://HOST:PORT (or another Dask protocol: "
                          f"{', '.join(SCHEDULER_SCHEMES[1:])}), not {shorten(scheme)}://", source="--scheduler")
    if scheme == "inproc":  # a scheduler in this very process (a test, a library caller)
        return scheme, text, 0
    try:
        parts = urlsplit(text if sep else f"tcp://{text}")
        host, port = parts.hostname, parts.port
    except ValueError:
        host, port = None, None
    if not host or port is None or port == 0 or parts.path not in ("", "/"):
        raise ConfigError(f"{shorten(text)}: expected tcp://HOST:PORT (a Dask scheduler listens on 8786 by default)",
                          source="--scheduler")
    return scheme, host, port


def check_scheduler(address: str, timeout_s: float = SCHEDULER_TIMEOUT_S) -> None:
    """Fail fast and clearly (exit 2) unless a Dask scheduler answers at ``address``: the address well formed,
    the port open within ``timeout_s``, and for tcp:// the scheduler's greeting (a Dask scheduler speaks first,
    a length-prefixed frame) received within ``timeout_s``. A web server or any silent service is refused
    here, before a client could read an HTTP status line as a frame length or wait on it for ever."""
    scheme, host, port = scheduler_endpoint(address)
    shown = shorten(address.strip())
    if scheme == "inproc":
        return
    try:
        sock = socket.create_connection((host, port), timeout=timeout_s)
    except OSError as exc:
        why = "no answer" if isinstance(exc, TimeoutError) else (exc.strerror or str(exc))
        raise ConfigError(f"cannot reach a Dask scheduler at {shown}: {why}", source="--scheduler") from None
    with sock:
        if scheme != "tcp":
            return
        sock.settimeout(timeout_s)
        greeting = b""
        try:
            while len(greeting) < 8:
                chunk = sock.recv(8 - len(greeting))
                if not chunk:
                    break
                greeting += chunk
        except OSError:
            pass
    if len(greeting) < 8:
        raise ConfigError(f"{shown} is not a Dask scheduler: it did not greet within {timeout_s:g} s (a Dask "
                          "scheduler's address is tcp://HOST:8786 by default, not its dashboard)", source="--scheduler")
    if greeting.startswith((b"HTTP", b"<")) or int.from_bytes(greeting, "little") > MAX_GREETING_BYTES:
        raise ConfigError(f"{shown} is not a Dask scheduler: it speaks another protocol", source="--scheduler")


def worker_gearcli() -> str:
    """What a Dask worker answers :func:`check_workers` with: its gearcli's version (a worker without gearcli
    cannot even load this function, and answers with that error)."""
    return __version__  # the worker's: it loads this module from its own gearcli


def check_workers(address: str) -> None:
    """Exit 2 (ConfigError naming ``--scheduler``) before anything runs when a worker of the cluster at ``address``
    cannot run the sweep's tasks: it has no gearcli (it could not load a task, and Dask would wait for a worker that
    can, for ever) or another version than this one (its rows would not be this version's). A cluster with no
    worker yet passes: its tasks wait for workers as Dask's do."""
    from distributed import Client  # lazy: distributed, the optional dask extra

    try:
        client = Client(address, timeout=f"{SCHEDULER_TIMEOUT_S:g}s")
    except (OSError, TimeoutError, ValueError, MemoryError) as exc:
        raise ConfigError(f"cannot reach the Dask scheduler at {address}: {type(exc).__name__}: {exc}",
                          source="--scheduler") from None
    quiet = _quiet_dask_client()
    try:
        answers = client.run(worker_gearcli, on_error="return")
    finally:
        client.close()
        quiet()
    broken = {w: a for w, a in answers.items() if isinstance(a, BaseException)}
    if broken:
        worker, err = sorted(broken.items(), key=lambda kv: kv[0])[0]
        what = str(err) if type(err) is Exception else f"{type(err).__name__}: {err}"  # distributed wraps a remote error
        raise ConfigError(f"{len(broken)} of {len(answers)} Dask workers cannot run gearcli ({worker}: "
                          f"{shorten(what)}): install gearcli {__version__} on every worker "
                          f"(pip install 'gearcli[distributed]=={__version__}')", source="--scheduler")
    other = {w: a for w, a in answers.items() if a != __version__}
    if other:
        worker, version = sorted(other.items())[0]
        raise ConfigError(f"{len(other)} of {len(answers)} Dask workers run another gearcli ({worker}: "
                          f"{shorten(str(version))}; this is {__version__}): install gearcli {__version__} on every "
                          "worker, so that a point's row is the one this version computes", source="--scheduler")


def _dask(tasks: Sequence[Task], address: str) -> Iterator[Row]:
    require_distributed()
    from distributed import Client, as_completed  # lazy: distributed, the optional dask extra

    check_scheduler(address)
    try:
        client = Client(address, timeout=f"{SCHEDULER_TIMEOUT_S:g}s")
    except (OSError, TimeoutError, ValueError, MemoryError) as exc:
        raise ConfigError(f"cannot reach the Dask scheduler at {address}: {type(exc).__name__}: {exc}",
                          source="--scheduler") from None
    futures = []
    quiet = _quiet_dask_client()
    try:
        futures = [client.submit(run_task, t, pure=False) for t in tasks]
        by_key = {f.key: t for f, t in zip(futures, tasks, strict=True)}
        done = 0
        for fut in as_completed(futures):
            try:
                rows = fut.result()
            except Exception as exc:  # noqa: BLE001 - a lost worker or a task error: failed rows
                if scheduler_lost(exc):
                    raise SchedulerLost(_lost_words(address, done, len(tasks))) from None
                rows = _lost(by_key[fut.key], exc)
            done += 1
            yield from rows
    finally:
        if futures:
            client.cancel(futures)
        client.close()
        quiet()


class SchedulerLost(SimulationError):
    """The Dask scheduler went away mid-sweep: the sweep stops (exit 1); the rows written so far stay in ``-o``."""


def scheduler_lost(exc: BaseException) -> bool:
    """Whether a task's error is the client's lost connection to the scheduler (not the task's, nor a worker's):
    its points did not fail, they did not run, so they are not written as failed rows (a re-run runs them)."""
    return getattr(exc, "reason", None) == "scheduler-connection-lost"


def _lost_words(address: str, done: int, total: int) -> str:
    return (f"--scheduler: lost the Dask scheduler at {address} after {done} of {total} tasks: the sweep stops; "
            "the points that finished are kept in the -o file, and the same command run again (with a scheduler "
            "or without --scheduler) runs only the rest")


def _quiet_dask_client() -> Callable[[], None]:
    """Keep the Dask client's own log records (a reconnect's traceback when the scheduler goes away) off stderr:
    gearcli says what happened in one line. Returns the function that restores the loggers' levels."""
    names = ("distributed.client", "distributed.comm", "distributed.core", "distributed.batched")
    loggers = [logging.getLogger(n) for n in names]
    levels = [lg.level for lg in loggers]
    for lg in loggers:
        lg.setLevel(logging.CRITICAL)

    def restore() -> None:
        for lg, level in zip(loggers, levels, strict=True):
            lg.setLevel(level)
    return restore
