"""The command line: parse, load, call the core, hand results to ``gearcli.io``.

Library errors become one-line messages on stderr with fixed exit codes (0 ok, 1 the run failed,
2 bad usage or bad design file, 130 interrupted); a traceback only with ``--debug``. Heavy modules
(scipy) are imported inside the commands that need them, so ``gearcli design`` starts fast.
"""

from __future__ import annotations

import functools
import sys
from pathlib import Path
from typing import Callable, Optional

import click

from gearcli import __version__
from gearcli.errors import EXIT_FAILED, EXIT_INTERRUPTED, EXIT_USAGE, DesignError, GearcliError

FORMATS = ("table", "csv", "json")
SUFFIX_FORMAT = {".json": "json", ".csv": "csv", ".md": "markdown", ".markdown": "markdown", ".txt": "table"}


def _fail(message: str, code: int) -> None:
    for line in message.splitlines() or [""]:
        click.echo(f"gearcli: {line}", err=True)
    sys.exit(code)


def guarded(fn: Callable) -> Callable:
    """Run a command body; map errors to messages and exit codes (traceback only with --debug)."""

    @functools.wraps(fn)
    def wrapper(*args, debug: bool = False, **kwargs):
        debug = debug or bool(click.get_current_context().find_root().params.get("debug"))
        try:
            return fn(*args, **kwargs)
        except GearcliError as exc:
            if debug:
                raise
            _fail(str(exc), exc.exit_code)
        except KeyboardInterrupt:
            _fail("interrupted", EXIT_INTERRUPTED)
        except (click.exceptions.Exit, click.ClickException, SystemExit):
            raise
        except Exception as exc:  # a bug: say so plainly, never a traceback without --debug
            if debug:
                raise
            _fail(f"internal error: {type(exc).__name__}: {exc} (run with --debug for the traceback)", EXIT_FAILED)

    return wrapper


def io_options(formats: tuple[str, ...] = FORMATS) -> Callable:
    """The options every data command shares: --set, --format, -o, --debug."""

    def decorate(fn: Callable) -> Callable:
        fn = click.option("--debug", is_flag=True, help="Show tracebacks on errors.")(fn)
        fn = click.option("-o", "--output", type=click.Path(dir_okay=False, writable=True),
                          help="Write to FILE atomically (format from its suffix unless --format).")(fn)
        fn = click.option("--format", "fmt", type=click.Choice(formats),
                          help="Output format [default: table on a terminal, csv in a pipe].")(fn)
        fn = click.option("--set", "overrides", multiple=True, metavar="KEY=VALUE",
                          help="Override a design-file key, e.g. --set stage.0.pinion.teeth=22 (repeatable).")(fn)
        return fn

    return decorate


def choose_format(fmt: Optional[str], output: Optional[str], allowed: tuple[str, ...]) -> str:
    if fmt:
        return fmt
    if output:
        inferred = SUFFIX_FORMAT.get(Path(output).suffix.lower(), "csv")
        return inferred if inferred in allowed else "csv"
    return "table" if sys.stdout.isatty() else "csv"


def emit(text: str, output: Optional[str]) -> None:
    """Data to ``-o FILE`` (atomically) or to stdout."""
    if output:
        from gearcli.io.atomic import write_atomic

        write_atomic(output, text)
    else:
        click.echo(text, nl=False)


def emit_tables(renderables, output: Optional[str]) -> None:
    from gearcli.io.tables import render

    if output or not sys.stdout.isatty():
        emit(render(renderables), output)
    else:
        from rich.console import Console

        render(renderables, console=Console())


def emit_as(fmt: str, output: Optional[str], result, *, sha256: str, json_doc: Callable[[], dict],
            csv_text: Callable[[], str], table_builder: str) -> None:
    """Write ``result`` in ``fmt``; only the chosen builder runs, and rich is imported only for tables
    (``table_builder`` names a function of :mod:`gearcli.io.tables`). JSON gets the meta keys."""
    if fmt == "json":
        from gearcli.io.serialize import to_json, with_meta

        emit(to_json(with_meta(json_doc(), sha256)), output)
    elif fmt == "csv":
        emit(csv_text(), output)
    else:
        from gearcli.io import tables

        emit_tables(getattr(tables, table_builder)(result), output)


def warn(lines) -> None:
    for line in lines:
        click.echo(f"warning: {line}", err=True)


def load_and_design(path: str, overrides):
    """Load and validate the design file, then run the design calculations."""
    from gearcli.config import load_design
    from gearcli.design import compute_design

    loaded = load_design(path, overrides)  # "-" reads sys.stdin.buffer (CliRunner swaps it too)
    try:
        design = compute_design(loaded.design)
    except DesignError as exc:
        raise DesignError(exc.message, key=exc.key, source=loaded.source) from exc
    return loaded, design


@click.group(context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="gearcli")
@click.option("--debug", is_flag=True, help="Show tracebacks on errors.")
def cli(debug: bool) -> None:
    """Design check and torsional dynamics of multi-stage helical gear reducers.

    FILE is a TOML design file ('-' reads stdin); `gearcli init` writes a starter one.
    """


@cli.command()
@click.argument("file", type=str)
@io_options()
@guarded
def design(file: str, overrides, fmt, output) -> None:
    """Ratios, speeds, torques, helical geometry, contact ratios, stiffness and static forces."""
    from gearcli.io import serialize

    loaded, result = load_and_design(file, overrides)
    emit_as(choose_format(fmt, output, FORMATS), output, result, sha256=loaded.sha256,
            json_doc=lambda: serialize.design_dict(result),
            csv_text=lambda: serialize.design_csv(result), table_builder="design_tables")
    warn(result.warnings)


@cli.command()
@click.argument("file", type=str)
@io_options()
@click.option("--series", is_flag=True, help="Include the time series in JSON output (CSV always has them).")
@guarded
def simulate(file: str, overrides, fmt, output, series: bool) -> None:
    """Torsional lumped-parameter simulation with nonlinear Hertz meshes."""
    loaded, design_result = load_and_design(file, overrides)  # bad input fails before scipy loads
    warn(design_result.warnings)
    fmt = choose_format(fmt, output, FORMATS)
    from gearcli.io import serialize
    from gearcli.simulate import run_simulation

    result = run_simulation(loaded.design, design_result, want_series=True)  # the window statistics need them
    emit_as(fmt, output, result, sha256=loaded.sha256,
            json_doc=lambda: serialize.simulation_dict(result, series=series),
            csv_text=lambda: serialize.simulation_csv(result), table_builder="simulation_tables")
    warn(result.warnings)


@cli.command()
@click.argument("file", required=False, type=click.Path(dir_okay=False))
@click.option("--force", is_flag=True, help="Overwrite FILE if it exists.")
@click.option("--debug", is_flag=True, help="Show tracebacks on errors.")
@guarded
def init(file: Optional[str], force: bool) -> None:
    """Write a commented starter design file (the seed reducer) to FILE, or to stdout."""
    from gearcli.config import starter_toml

    if file and Path(file).exists() and not force:
        _fail(f"{file}: exists; use --force to overwrite", EXIT_USAGE)
    emit(starter_toml(), file)
    if file:
        click.echo(f"wrote {file}; try: gearcli design {file}", err=True)


@cli.command()
@click.option("-o", "--output", type=click.Path(dir_okay=False, writable=True), help="Write to FILE atomically.")
@click.option("--debug", is_flag=True, help="Show tracebacks on errors.")
@guarded
def schema(output: Optional[str]) -> None:
    """Print the JSON Schema of the design file."""
    import json

    from gearcli.config import json_schema

    emit(json.dumps(json_schema(), indent=2) + "\n", output)


# ------------------------------------------------------------------------------------------ report
REPORT_FORMATS = ("table", "json", "markdown")


def _report_format(fmt: Optional[str], output: Optional[str]) -> str:
    """--format, else from -o's suffix (markdown unless .json/.txt), else table on a terminal and
    markdown in a pipe (a report does not fit CSV)."""
    if fmt:
        return fmt
    if output:
        inferred = SUFFIX_FORMAT.get(Path(output).suffix.lower())
        return inferred if inferred in REPORT_FORMATS else "markdown"
    return "table" if sys.stdout.isatty() else "markdown"


def _parse_rtols(ctx, param, value: Optional[str]):
    if value is None:
        return None
    try:
        rtols = tuple(float(v) for v in value.split(",") if v.strip())
    except ValueError:
        raise click.BadParameter(f"{value!r}: give comma-separated numbers, e.g. 1e-3,1e-6,1e-9") from None
    bad = [r for r in rtols if not 1e-13 <= r <= 1e-2]
    if not rtols or bad:
        raise click.BadParameter("every rtol must lie in [1e-13, 1e-2]" + (f", got {bad[0]:g}" if bad else ""))
    return rtols


class _StderrProgress:
    """A rich progress bar on stderr when it is a terminal; a silent no-op otherwise."""

    def __init__(self) -> None:
        self.bar = None

    def __enter__(self):
        if sys.stderr.isatty():
            from rich.console import Console
            from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

            self.bar = Progress(TextColumn("{task.description:<28}"), BarColumn(), MofNCompleteColumn(),
                                TimeElapsedColumn(), console=Console(stderr=True), transient=True)
            self.bar.__enter__()
            self.task = self.bar.add_task("report", total=None)
        return self

    def __call__(self, label: str, done: int, total: int) -> None:
        if self.bar is not None:
            self.bar.update(self.task, description=label, completed=done, total=total)

    def __exit__(self, *exc) -> None:
        if self.bar is not None:
            self.bar.__exit__(*exc)


@cli.command()
@click.argument("file", type=str)
@click.option("--set", "overrides", multiple=True, metavar="KEY=VALUE",
              help="Override a design-file key, e.g. --set simulation.duration_s=0.25 (repeatable).")
@click.option("--format", "fmt", type=click.Choice(REPORT_FORMATS),
              help="Output format [default: table on a terminal, markdown in a pipe].")
@click.option("-o", "--output", type=click.Path(dir_okay=False, writable=True),
              help="Write to FILE atomically (format from its suffix: .json, .md, .txt).")
@click.option("--accuracy", type=click.FloatRange(1e-12, 0.5), default=1e-4, show_default=True,
              help="Relative accuracy the recommended solver setting must meet.")
@click.option("--quick", is_flag=True, help="Skip the accuracy study (one simulation).")
@click.option("--rtols", callback=_parse_rtols, metavar="LIST",
              help="The accuracy ladder's tolerances, comma-separated [default: 1e-3,1e-4,...,1e-9].")
@click.option("--plots", "plots_dir", type=click.Path(file_okay=False), metavar="DIR",
              help="Also write speeds.png, mesh_forces.png, spectrum.png, work_precision.png to DIR. Needs "
                   "matplotlib (pip install 'gearcli[plot]'); without it: a warning, the rest of the report, exit 0.")
@click.option("--debug", is_flag=True, help="Show tracebacks on errors.")
@guarded
def report(file: str, overrides, fmt, output, accuracy: float, quick: bool, rtols, plots_dir) -> None:
    """Theory against simulation, the numerical error against run time, and plots."""
    from gearcli.io import serialize
    from gearcli.report import LadderSpec, build_report

    loaded, design_result = load_and_design(file, overrides)
    warn(design_result.warnings)
    fmt = _report_format(fmt, output)
    spec = LadderSpec(rtols=rtols) if rtols else LadderSpec()
    with _StderrProgress() as progress:
        rep = build_report(loaded.design, design_result, accuracy=accuracy, quick=quick, spec=spec,
                           progress=progress)
    if fmt == "json":
        from gearcli.io.report_json import report_dict

        emit(serialize.to_json(serialize.with_meta(report_dict(rep), loaded.sha256)), output)
    elif fmt == "markdown":
        from gearcli.io.markdown import report_markdown

        emit(report_markdown(rep, loaded.sha256), output)
    else:
        from gearcli.io.report_tables import report_tables

        emit_tables(report_tables(rep), output)
    warn(w for w in rep.warnings if w not in design_result.warnings)  # design ones went out first
    if plots_dir:
        _write_report_plots(rep, plots_dir)


def _write_report_plots(rep, plots_dir: str) -> None:
    """A missing optional dependency for an optional output: warn how to install it, exit 0."""
    from gearcli.io.plots import PlotsUnavailable, write_plots

    try:
        paths = write_plots(rep, plots_dir)
    except PlotsUnavailable as exc:
        warn([f"{exc}; the report itself is complete"])
        return
    except OSError as exc:
        _fail(f"{plots_dir}: cannot write plots: {exc.strerror or exc}", EXIT_FAILED)
    click.echo(f"wrote {', '.join(p.name for p in paths)} to {plots_dir}", err=True)
    if rep.accuracy is None:
        click.echo("work_precision.png needs the accuracy study: run without --quick", err=True)


# ------------------------------------------------------------------------------------------- sweep
SWEEP_FORMATS = ("csv", "json")


@cli.command()
@click.argument("file", type=str)
@click.option("--vary", multiple=True, metavar="KEY=START:STOP:N|KEY=v1,v2,...",
              help="Vary a key over N evenly spaced values (inclusive) or a list; several make a grid (repeatable).")
@click.option("--random", "randoms", multiple=True, metavar="KEY=normal(MU,SIGMA)|KEY=uniform(A,B)",
              help="Draw a key from a distribution, --samples times (repeatable).")
@click.option("--samples", type=click.IntRange(1, 1_000_000), help="Number of random samples.")
@click.option("--sampling", type=click.Choice(("lhs", "mc")), default="lhs", show_default=True,
              help="Latin hypercube (lhs) or plain Monte Carlo (mc).")
@click.option("--seed", type=click.IntRange(0, 2**63 - 1), help="Seed of the random samples (recorded in -o FILE).")
@click.option("--direction", type=click.Choice(("up", "down", "both")),
              help="Continuation along the first --vary key: each point starts from the previous one's final state.")
@click.option("--jobs", type=click.IntRange(1, 4096), help="Local worker processes [default: all cores].")
@click.option("--scheduler", metavar="ADDRESS",
              help="Run the points on a Dask distributed cluster (pip install 'gearcli[distributed]').")
@click.option("--set", "overrides", multiple=True, metavar="KEY=VALUE", help="Override a key of the base scene.")
@click.option("--format", "fmt", type=click.Choice(SWEEP_FORMATS), help="[default: from -o's suffix, else csv]")
@click.option("-o", "--output", type=click.Path(dir_okay=False),
              help="Write rows to FILE as they finish (.csv or .json); a re-run skips the points done.")
@click.option("--plots", "plots_dir", type=click.Path(file_okay=False), metavar="DIR",
              help="Response curves, Campbell diagram, histograms into DIR (pip install 'gearcli[plot]').")
@click.option("--debug", is_flag=True, help="Show tracebacks on errors.")
@guarded
def sweep(file: str, vary, randoms, samples, sampling, seed, direction, jobs, scheduler, overrides, fmt, output,
          plots_dir) -> None:
    """Simulate many operating points: grids, tolerance samples, continuation up and down in speed."""
    from gearcli.io.sweep_progress import SweepProgress
    from gearcli.sweep.session import prepare, run

    fmt = fmt or ("json" if output and Path(output).suffix.lower() == ".json" else "csv")
    session = prepare(file, overrides, vary=vary, randoms=randoms, samples=samples, sampling=sampling, seed=seed,
                      direction=direction, jobs=jobs, scheduler=scheduler, output=output, fmt=fmt)
    warn(session.design_warnings)
    with SweepProgress(session.todo + session.done, session.done) as progress:
        rows = run(session, progress.advance)
    failed = sum(r.get("status") != "ok" for r in rows)
    click.echo(f"sweep: {len(rows)} points, {failed} failed" + (f", written to {output}" if output else ""),
               err=True)
    if plots_dir:
        _write_sweep_plots(session, rows, plots_dir)
    if failed:
        sys.exit(EXIT_FAILED)


def _write_sweep_plots(session, rows, plots_dir: str) -> None:
    from gearcli.io.plots import PlotsUnavailable
    from gearcli.io.sweep_plots import write_sweep_plots

    try:
        paths = write_sweep_plots(session, rows, plots_dir)
    except PlotsUnavailable as exc:
        warn([f"{exc}; the sweep itself is complete"])
        return
    except OSError as exc:
        _fail(f"{plots_dir}: cannot write plots: {exc.strerror or exc}", EXIT_FAILED)
    click.echo(f"wrote {', '.join(p.name for p in paths)} to {plots_dir}", err=True)


def main() -> None:
    cli(prog_name="gearcli")


if __name__ == "__main__":  # pragma: no cover
    main()
