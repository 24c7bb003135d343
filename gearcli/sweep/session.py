"""One ``gearcli sweep`` run: check the arguments, match an existing ``-o`` file, run, write, order.

:func:`prepare` does everything that can fail with a usage error (exit 2) before any point runs; then
:func:`run` streams the rows to the output as they finish and, at the end, leaves them in point order.
On Ctrl-C the output keeps every finished row and the interrupt propagates (exit 130 from the CLI).

The controller loads, designs, simulates and writes nothing itself: the caller (:mod:`gearcli.api`) hands it
the base file loaded and designed, and injects how a point is evaluated (``evaluate``,
:class:`~gearcli.sweep.worker.PointEvaluator`: :func:`gearcli.api.evaluate_point`), how an existing ``-o``
file is read (``read_previous``) and where the rows go (``open_sink``, a :class:`RowSink` factory;
:mod:`gearcli.io.sweep_file` gives both).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from itertools import chain
from typing import Protocol

from gearcli import __version__, engine
from gearcli.config import DesignFile, LoadedDesign
from gearcli.config.bounds import check_memory, memory_estimate_bytes, output_samples
from gearcli.config.load import integer_keys, list_keys, table_keys
from gearcli.config.overrides import SOURCE, blames_key
from gearcli.core.jsontypes import JsonObject
from gearcli.errors import ConfigError
from gearcli.results import DesignResult
from gearcli.stages.design import design_kind
from gearcli.sweep.columns import FAILED, OK, Row, columns
from gearcli.sweep.execute import (
    check_scheduler,
    check_workers,
    default_jobs,
    execute,
    jobs_cap,
    plan,
    require_distributed,
)
from gearcli.sweep.family import Carrier, unresolved_row
from gearcli.sweep.load_law import load_law_of
from gearcli.sweep.resume import check_same, done_counts, identity, ordered, relabel, row_ident, seed_for
from gearcli.sweep.spec import SPEED_KEYS, SweepSpec, SweepUsageError, spec_from_options
from gearcli.sweep.worker import PointEvaluator, Scene, Task, check_keys


class RowSink(Protocol):
    """Where rows go: ``add`` each as it arrives, ``finish`` with all rows in point order, ``close`` on an
    interruption (leaving what is done); ``rows`` what it holds."""

    rows: list[Row]

    def add(self, row: Row) -> None: ...

    def finish(self, ordered: Sequence[Row]) -> None: ...

    def close(self) -> None: ...


#: (output, format, columns, identity, previous rows) -> the sink
SinkFactory = Callable[[str | None, str, Sequence[str], JsonObject, Sequence[Row]], RowSink]
#: the identity and rows of an existing output file; (None, []) when there is none
PreviousReader = Callable[[str], tuple[JsonObject | None, list[Row]]]


def _none_previous(output: str) -> tuple[JsonObject | None, list[Row]]:
    return None, []


@dataclass
class Session:
    spec: SweepSpec
    scene: Scene
    cfg: DesignFile  # the validated base design file
    design: DesignResult
    columns: list[str]
    identity: JsonObject
    previous: list[Row]
    tasks: list[Task]
    todo: int
    done: int
    jobs: int
    scheduler: str | None
    output: str | None
    fmt: str
    design_warnings: tuple[str, ...]
    notes: tuple[str, ...] = ()  # about the run itself (--jobs capped), printed as warnings

#: the row formats a sweep writes (``--format``; ``gearcli.io.sweep_file``'s sinks)
FORMATS = ("csv", "json")
ENGINE_KEY = "simulation.engine"


def prepare(raw: bytes, loaded: LoadedDesign, design: DesignResult, sets: Sequence[str], *, vary: Sequence[str],
            randoms: Sequence[str], samples: int | None, sampling: str, seed: int | None, direction: str | None,
            jobs: int | None, scheduler: str | None, output: str | None, fmt: str, evaluate: PointEvaluator,
            read_previous: PreviousReader = _none_previous) -> Session:
    """The checked sweep of the base file ``raw`` (``loaded`` and ``design`` with the ``sets`` applied): every
    usage error raised before any point runs; ``output``, when given, read for a resume by ``read_previous``;
    the points evaluated by ``evaluate`` when :func:`run` runs them."""
    if fmt not in FORMATS:  # the CLI's choice; a script's typo would otherwise write CSV silently
        raise SweepUsageError(f"must be one of {', '.join(FORMATS)}, got {fmt!r}", source="--format")
    if scheduler is not None:  # '' too: an empty address is a mistake, never a silent local run
        require_distributed()
        check_scheduler(scheduler)
        check_workers(scheduler)
    stored: JsonObject | None = None
    previous: list[Row] = []
    if output:
        stored, previous = read_previous(output)
        previous = [r for r in previous if r.get("status") in (OK, FAILED)]  # a corrupted status: computed again
    spec = spec_from_options(vary, randoms, samples, sampling, seed_for(seed, stored, bool(randoms)), direction)
    previous = relabel(previous, spec)  # a key spelled otherwise by the run that wrote them (stage.0.x, stage[0].x)
    scene = Scene(raw, loaded.source, tuple(sets), len(design.stages), load_law_of(loaded.design))
    check_memory(loaded.design, fmt="json", series=False, source=loaded.source)  # each point's run, in memory
    try:
        check_keys(scene, spec.branches()[0][0])
    except ConfigError as exc:
        raise _named_by_option(exc, spec, sets) from None
    _no_whole_lists_or_tables(spec, scene)
    _no_continuous_integers(spec, scene)
    _no_fractional_counts(spec, scene)
    check_motor_speed(spec.keys, loaded.design, loaded.source)
    if scheduler is None:
        _compiled_here(spec, loaded, sets)
    ident = identity(spec, loaded.sha256, __version__)
    if stored is not None and output:
        check_same(stored, ident, output)
    sharing = [st.index for st in design.stages if design_kind(st).shares_load]  # their load-sharing columns
    written = columns(spec.columns, len(design.stages), sharing)
    previous = [r for r in previous if all(c in r for c in written)]  # another version's columns: computed again
    done = done_counts(previous, spec.columns)
    workers, notes = capped_jobs(jobs, loaded.design, len(design.stages), scheduler)
    notes += _life_only_keys(spec)
    unresolved = {row_ident(r, spec.columns) for r in previous if unresolved_row(r)}  # verdicts a resume needs again
    tasks, todo = plan(spec, scene, done, 1 if scheduler is None and workers == 1 else workers, evaluate, unresolved)
    if scheduler is None and workers > 1 and len(tasks) > 1:  # a pool: its workers stay quiet, the sweep says it once

        notes += tuple(n for n in (engine.compilation_pending(),) if n)
    previous = ordered(previous, spec)
    return Session(spec, scene, loaded.design, design, written, ident,
                   previous, tasks, todo, len(previous), workers, scheduler, output, fmt, tuple(design.warnings), notes)


def _compiled_here(spec: SweepSpec, loaded: LoadedDesign, sets: Sequence[str]) -> None:
    """``engine = "compiled"`` (the file's, a ``--set``'s or a ``--vary`` value) where numba, the ``fast`` extra, is
    missing or cannot be imported: the usage error ``simulate`` gives (exit 2, before any point runs), not a
    ``failed`` row per point. A local sweep's workers are this machine's processes; a Dask cluster's workers have
    their own installation, and their rows say it."""
    varied = [(a.label or a.key, v) for a in spec.axes if a.key == ENGINE_KEY for v in a.values]
    if not any(v == "compiled" for _, v in varied) and (varied or loaded.design.simulation.engine != "compiled"):
        return
    problem = engine.compiled_problem()
    if problem is None:
        return
    if varied:
        raise SweepUsageError(problem, source="--vary", key=varied[0][0])
    raise ConfigError(problem, source=SOURCE if blames_key(ENGINE_KEY, sets) else loaded.source, key=ENGINE_KEY)


def _named_by_option(exc: ConfigError, spec: SweepSpec, sets: Sequence[str]) -> ConfigError:
    """A bad key of ``--vary`` or ``--random`` named by that option, not ``--set`` (the keys are checked as
    overrides): ``gearcli: --vary: nosuch.x: unknown key ...``."""
    if exc.source != SOURCE or any(s.partition("=")[0].strip() == exc.key for s in sets):
        return exc
    for option, varied in (("--vary", spec.axes), ("--random", spec.randoms)):
        written = next((v.column for v in varied if v.key == exc.key), None)
        if written is not None:  # named as the user wrote it (stage[0].x or stage.0.x)
            return ConfigError(exc.message, source=option, key=written)
    return exc


def _no_whole_lists_or_tables(spec: SweepSpec, scene: Scene) -> None:
    """A list (``tooth_thickness_allowance_mm``, ``transmission_error_um``) or a table (``contact``) drawn as a whole,
    or varied over a value that is no array (no inline table), would get one number (or word) at a point, which no
    such key holds: that point would fail (a ``--vary`` of reals was refused as if the key took whole numbers).
    Refused before any runs, naming the entries or keys to vary instead. ``--vary KEY=[1, 0.5],[2, 0.1]`` varies a
    list over whole arrays."""
    given: list[tuple[str, str, str, str, tuple | None]] = [
        ("--vary", a.key, a.column, "=v1,v2,...", a.values) for a in spec.axes]
    given += [("--random", d.key, d.column, f"={d.kind}(...)", None) for d in spec.randoms]
    keys = [key for _, key, _, _, _ in given]
    lists = set(list_keys(scene.raw, scene.source, scene.sets, keys))
    tables = set(table_keys(scene.raw, scene.source, scene.sets, keys))
    for option, key, column, how, values in given:
        if key not in lists and key not in tables:
            continue
        whole = list if key in lists else dict
        odd = None if values is None else next((v for v in values if not isinstance(v, whole)), None)
        if values is not None and odd is None:
            continue  # whole arrays (inline tables), one a point
        one = "draws one number" if values is None else f"gives a point {odd!r}"
        verb = "draw" if values is None else "vary"
        if key in lists:
            raise SweepUsageError(f"{column} is a list, and {option} {one}: {verb} its entries by index, "
                                  f"{option} '{column}.0{how}' (the first; .1 the second ...; in a list of tables "
                                  f"the entry's key: {column}.0.KEY)"
                                  + ("" if values is None else f", or whole arrays, {option} '{column}=[a, b],[c, d]'"),
                                  source=option)
        raise SweepUsageError(f"{column} is a table, and {option} {one}: {verb} one of its keys, "
                              f"{option} '{column}.KEY{how}'", source=option)


def _no_continuous_integers(spec: SweepSpec, scene: Scene) -> None:
    """A key that takes no real number (a tooth or planet count, a whole-number choice) drawn from a continuous
    distribution would fail at every point: refused before any runs (a list or a table by
    :func:`_no_whole_lists_or_tables` before)."""
    whole = integer_keys(scene.raw, scene.source, scene.sets, [d.key for d in spec.randoms])
    if whole:
        d = next(d for d in spec.randoms if d.key == whole[0])
        raise SweepUsageError(f"{d.column} takes no real number (a whole number, a choice, a text or true/false), "
                              f"{d.kind}(...) draws real numbers: every point "
                              "would fail; vary it over its values with --vary KEY=v1,v2,... or --vary KEY=START:STOP:N",
                              source="--random")




def _no_fractional_counts(spec: SweepSpec, scene: Scene) -> None:
    """A ``--vary`` value written as a real number on a key that takes whole numbers (a tooth or planet count): no
    file could hold it (a file's ``teeth = 21.0`` is refused too), so the sweep is refused before any point runs, as
    ``--random`` on such a key is. A range's steps make such values (``stage.0.pinion.teeth=20:21:3`` steps by 0.5,
    and its 20 and 21 came out 20.0 and 21.0), and so do real ends (``20.0:22.0:3``): every point was a failed row."""
    reals = [(a, v) for a in spec.axes for v in a.values if isinstance(v, float)]
    if not reals:
        return
    whole = set(integer_keys(scene.raw, scene.source, scene.sets, sorted({a.key for a, _ in reals})))
    bad = sorted(((a, v) for a, v in reals if a.key in whole), key=lambda av: av[1].is_integer())  # a fraction first
    if not bad:
        return
    axis, value = bad[0]
    how = (f"{value!r} is one of its values" if not value.is_integer() else
           f"{value!r} is written as a real number (write {int(value)})")
    raise SweepUsageError(f"{axis.column} takes whole numbers, and {how}: list whole values (--vary "
                          f"{axis.column}=v1,v2,...), or give START:STOP:N with whole START and STOP and a whole step "
                          "(STOP - START)/(N - 1)", source="--vary")


def check_motor_speed(keys: Sequence[str], cfg: DesignFile, source: str) -> None:
    """A speed sweep on a motor drive: with ``starting = "vfd"`` on a nameplate motor the drive's supply follows each
    row's speed (:func:`gearcli.scene.motor_spec`); any other start, and a VFD on a ``torque_speed`` table (no rated
    point to set the supply by), runs at its own curve's speed, so varying the input speed would design each row at
    a speed the motor does not run: refused (exit 2) naming what to vary instead."""
    table = cfg.input.motor is not None and cfg.input.motor.torque_speed is not None
    if cfg.input.drive != "motor" or (cfg.input.starting == "vfd" and not table) or "input.drive" in keys:
        return
    varied = [k for k in keys if k in SPEED_KEYS]
    if varied:
        how = ('starting = "vfd" on a torque_speed table: a converter\'s supply follows the speed with a nameplate '
               "motor only (its rated slip speed sets the supply), a table runs at its own synchronous speed"
               if cfg.input.starting == "vfd" else
               f'starting = "{cfg.input.starting}": the motor runs at the speed its curve and the load give')
        raise ConfigError(f'drive = "motor" with {how}, so varying the input speed would design each row at a speed '
                          "the motor does not run. Vary it with a frequency converter on a nameplate motor "
                          "(--set 'input.starting=\"vfd\"': the supply follows each row's speed), sweep a prescribed speed "
                          "(--set 'input.drive=\"speed\"'), "
                          "or vary the load (load.torque_Nm) or the motor (input.motor) instead",
                          source=source, key=varied[0])


def _life_only_keys(spec: SweepSpec) -> tuple[str, ...]:
    """A note per varied key of a ``[[duty]]`` table: the duty is ``gearcli life``'s, a sweep point runs the file's
    ``[input]`` and ``[load]``, so every value of such a key gives the same run (the rows differ in that column only)."""
    return tuple(f"--vary/--random {column}: [[duty]] is gearcli life's operating points; a sweep point runs the "
                 "file's [input] and [load], so this key has no effect on its rows (vary input.speed_rpm or "
                 "load.torque_Nm instead, or run gearcli life)"
                 for key, column in zip(spec.keys, spec.columns, strict=True) if key.split(".")[0] == "duty")


def capped_jobs(jobs: int | None, cfg: DesignFile, n_stages: int, scheduler: str | None) -> tuple[int, tuple[str, ...]]:
    """Local worker processes: ``--jobs`` (default: every usable core), at most what the machine's cores and
    memory carry (:func:`gearcli.sweep.execute.jobs_cap`); a note when ``--jobs`` asked for more."""
    if scheduler:
        return jobs or default_jobs(), ()

    cap, why = jobs_cap(memory_estimate_bytes(output_samples(cfg.simulation), n_stages, "json", False))
    wanted = jobs or default_jobs()
    if wanted <= cap:
        return wanted, ()
    note = f"--jobs {wanted} capped at {cap} worker process{'es' if cap != 1 else ''} ({why})"
    return cap, (note,) if jobs else ()


def run(session: Session, open_sink: SinkFactory, on_row: Callable[[bool], None] = lambda failed: None) -> list[Row]:
    """Run the session's tasks; every row goes to the sink as it arrives. Returns all rows in point order."""
    sink = open_sink(session.output, session.fmt, session.columns, session.identity, session.previous)
    rows_in = execute(session.tasks, jobs=session.jobs, scheduler=session.scheduler)
    carrier = Carrier(session.tasks)  # independent rows take their family's verdict here, whichever task ran them
    try:
        for row in chain((r for got in rows_in for r in carrier.add(got)), carrier.rest()):
            sink.add(row)
            on_row(row.get("status") == FAILED)
    except BaseException:
        close = getattr(rows_in, "close", None)
        if close is not None:  # a pool stops its workers now, whichever line the interrupt hit
            close()
        sink.close()
        raise
    rows = ordered(sink.rows, session.spec)
    sink.finish(rows)
    return rows
