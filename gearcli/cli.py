"""The command line: parse, load, call the core, hand results to ``gearcli.io``.

Library errors become one-line messages on stderr with fixed exit codes (0 ok, 1 the run failed,
2 bad usage or bad design file, 130 interrupted); a traceback only with ``--debug``. Heavy modules
(scipy) are imported inside the commands that need them, so ``gearcli design`` starts fast.
"""

from __future__ import annotations

import functools
import json
import math
import os
import signal
import sys
import warnings as warnings_module
from collections.abc import Callable
from pathlib import Path

import click

from gearcli import __version__
from gearcli.core.text import shorten, visible
from gearcli.errors import (
    EXIT_BROKEN_PIPE,
    EXIT_FAILED,
    EXIT_HANGUP,
    EXIT_INTERRUPTED,
    EXIT_TERMINATED,
    EXIT_USAGE,
    ConfigError,
    GearcliError,
    OutputError,
    Terminated,
)
from gearcli.io import output as outfiles
from gearcli.io import streams

FORMATS = ("table", "csv", "json")
SUFFIX_FORMAT = outfiles.SUFFIX_FORMAT


def _fail(message: str, code: int) -> None:
    for line in message.splitlines() or [""]:
        click.echo(f"gearcli: {visible(line)}", err=True)
    sys.exit(code)


def _broken_pipe() -> None:
    """The reader of our output went away (``| head -1``): exit 141 quietly, as a SIGPIPE'd program does.
    stdout is pointed at /dev/null so that the interpreter's last flush cannot complain either."""
    for stream in (sys.stdout, sys.stderr):
        try:
            fd = os.open(os.devnull, os.O_WRONLY)
            os.dup2(fd, stream.fileno())
            os.close(fd)
        except (OSError, ValueError, AttributeError):
            pass
    sys.exit(EXIT_BROKEN_PIPE)


_SIGNALLED: list[int] = []  # the exit codes of the signals this process received (SIGINT, SIGTERM, SIGHUP)
_SIGNAL_WORDS = {EXIT_INTERRUPTED: "interrupted", EXIT_TERMINATED: "terminated", EXIT_HANGUP: "hangup"}


def _on_sigint(signum, frame) -> None:
    _SIGNALLED.append(EXIT_INTERRUPTED)
    raise KeyboardInterrupt


def _on_sigterm(signum, frame) -> None:
    _SIGNALLED.append(EXIT_TERMINATED)
    raise Terminated()


def _on_sighup(signum, frame) -> None:
    _SIGNALLED.append(EXIT_HANGUP)
    raise Terminated(EXIT_HANGUP)


def guarded(fn: Callable) -> Callable:
    """Run a command body; map errors to messages and exit codes (traceback only with --debug).
    Numeric RuntimeWarnings are collected and reported as one plain warning each, never raw."""

    @functools.wraps(fn)
    def wrapper(*args, debug: bool = False, quiet: bool = False, **kwargs):
        root = click.get_current_context().find_root()
        debug = debug or bool(root.params.get("debug"))
        if quiet:
            click.get_current_context().meta["gearcli.quiet"] = True
        _show_engine_builds()
        try:
            from gearcli import api  # lazy: start-up time of --help

            api.check_environment()  # one rule for every command: a set GEARCLI_MEMORY_LIMIT_MB must be valid
            with warnings_module.catch_warnings(record=True) as caught:
                warnings_module.simplefilter("always", RuntimeWarning)
                try:
                    return fn(*args, **kwargs)
                finally:
                    _report_numeric_warnings(caught)
        except GearcliError as exc:
            if debug:
                raise
            _fail(str(exc), exc.exit_code)
        except BrokenPipeError:
            _broken_pipe()
        except KeyboardInterrupt:
            _fail("interrupted", EXIT_INTERRUPTED)
        except Terminated as exc:
            if exc.args == (EXIT_HANGUP,):
                _fail("hangup", EXIT_HANGUP)
            _fail("terminated", EXIT_TERMINATED)
        except (click.exceptions.Exit, click.ClickException, SystemExit):
            raise
        except Exception as exc:  # a bug: say so plainly, never a traceback without --debug
            if _SIGNALLED and not debug:  # a signal's exception turned into another inside a C extension (an
                _fail(_SIGNAL_WORDS[_SIGNALLED[0]], _SIGNALLED[0])  # import's "initialization failed"): the signal
            if debug:
                raise
            _fail(f"internal error: {type(exc).__name__}: {shorten(str(exc), 200)} "
                  "(run with --debug for the traceback)", EXIT_FAILED)

    return wrapper


def _show_engine_builds() -> None:
    """A first compilation of the engine inside this command shows as a step (silent with -q)."""
    from gearcli.io.progress import show_engine_builds  # lazy: start-up time of --help

    show_engine_builds(quiet=is_quiet())


def _report_numeric_warnings(caught) -> None:
    """numpy/scipy RuntimeWarnings as one line each (no source path, no repeated lines)."""
    seen: list[str] = []
    for w in caught:
        if issubclass(w.category, RuntimeWarning) and str(w.message) not in seen:
            seen.append(str(w.message))
        elif not issubclass(w.category, RuntimeWarning):
            warnings_module.showwarning(w.message, w.category, w.filename, w.lineno)
    warn(f"numerical warning during the run: {shorten(m, 120)}" for m in seen)


def quiet_option(fn: Callable) -> Callable:
    return click.option("-q", "--quiet", is_flag=True,
                        help="No warnings or progress on stderr (errors are still printed).")(fn)


def is_quiet() -> bool:
    ctx = click.get_current_context(silent=True)
    while ctx is not None:
        if ctx.meta.get("gearcli.quiet") or ctx.params.get("quiet"):
            return True
        ctx = ctx.parent
    return False


def io_options(formats: tuple[str, ...] = FORMATS) -> Callable:
    """The options every data command shares: --set, --format, -o, -q, --debug."""

    def decorate(fn: Callable) -> Callable:
        fn = click.option("--debug", is_flag=True, help="Show tracebacks on errors.")(fn)
        fn = quiet_option(fn)
        fn = outfiles.output_option()(fn)
        fn = click.option("--format", "fmt", type=click.Choice(formats),
                          help="Output format [default: from -o's suffix; table on a terminal, csv in a pipe].")(fn)
        fn = click.option("--set", "overrides", multiple=True, metavar="KEY=VALUE",
                          help="Override a design-file key, e.g. --set stage.0.pinion.teeth=22 (repeatable).")(fn)
        return fn

    return decorate


def _tty_default(pipe_format: str) -> Callable[[], str]:
    return lambda: "table" if sys.stdout.isatty() else pipe_format


def csv_table_option(default: str, what: str) -> Callable:
    """``--table``: which table ``--format csv`` writes, the command's own (``default``) or the bearings'."""
    return click.option("--table", "csv_table", type=click.Choice((default, "bearings")), default=default,
                        show_default=True,
                        help=f"The CSV's table: {what}, or bearings (a row per [[bearing]], its JSON figures: "
                             "L10, ISO 281 modified life, ISO 76 static safety; docs/bearings.md).")


def wants_bearing_csv(csv_table: str, default: str, fmt: str, loaded) -> bool:
    """True for ``--table bearings``; exit 2 (before any long computation) with another format than CSV or a
    design file without ``[[bearing]]`` tables."""
    if csv_table == default:
        return False
    if fmt != "csv":
        raise click.UsageError(f"--table {csv_table} chooses the table of --format csv; the {fmt} output shows "
                               "every table")
    if not loaded.design.bearing:
        raise ConfigError("--table bearings: the design file has no [[bearing]] table", key="bearing",
                          source=loaded.source)
    return True


#: the parameters of any command that name a file it reads: the design file, ``life --series``. The one rule
#: that protects inputs: neither ``-o`` nor ``--plots`` may write over any of them (a sweep's resume file is
#: its ``-o``, which ``--plots`` may not write over either).
INPUT_PARAMS = ("file", "series")


def _context_inputs() -> tuple[str | None, ...]:
    ctx = click.get_current_context(silent=True)
    if ctx is None:
        return ()
    return tuple(ctx.params[p] for p in INPUT_PARAMS if isinstance(ctx.params.get(p), str))


def check_target(fmt: str | None, out: str | None, formats: tuple[str, ...] = FORMATS, *,
                 pipe_format: str = "csv", file_default: str | None = None) -> outfiles.OutputTarget:
    """Check ``-o`` against the command's input file and formats (exit 2 before any computation)."""
    return outfiles.check_output(out, formats=formats, fmt=fmt, inputs=_context_inputs(),
                               file_default=file_default or pipe_format, stdout_default=_tty_default(pipe_format))


Destination = None | str | outfiles.OutputTarget


def _target(dest: Destination) -> outfiles.OutputTarget:
    if isinstance(dest, outfiles.OutputTarget):
        return dest
    if dest is None or dest == outfiles.STDOUT:
        return outfiles.OutputTarget(fmt="")
    return outfiles.OutputTarget(fmt="", path=outfiles.resolve_path(dest, _context_inputs()), shown=dest)


def emit(text: str, dest: Destination) -> None:
    """Data to the checked ``-o`` file (atomically, through a symlink) or to stdout."""
    outfiles.write_output(_target(dest), text)


def emit_tables(renderables, dest: Destination) -> None:
    from gearcli.io.table_kit import terminal_console  # lazy: rich, start-up time of --help
    from gearcli.io.tables import render  # lazy: rich, start-up time of --help

    target = _target(dest)
    if not target.is_stdout or not sys.stdout.isatty():
        encoding = (getattr(sys.stdout, "encoding", None) or "utf-8") if target.is_stdout else "utf-8"
        emit(render(renderables, encoding=encoding) or "", target)
    else:
        render(renderables, console=terminal_console())


def emit_as(fmt: str, dest: Destination, result, *, sha256: str, json_doc: Callable[[], dict],
            csv_text: Callable[[], str], table_builder: str) -> None:
    """Write ``result`` in ``fmt``; only the chosen builder runs, and rich is imported only for tables
    (``table_builder`` names a function of :mod:`gearcli.io.tables`). JSON gets the meta keys."""
    if fmt == "json":
        from gearcli.io.serialize import to_json, with_meta  # lazy: start-up time of --help

        emit(to_json(with_meta(json_doc(), sha256)), dest)
    elif fmt == "csv":
        emit(csv_text(), dest)
    else:
        from gearcli.io import tables  # lazy: start-up time of --help

        emit_tables(getattr(tables, table_builder)(result), dest)


def warn(lines) -> None:
    """Warnings on stderr, one line each, control characters escaped; nothing with ``-q``."""
    if is_quiet():
        return
    for line in lines:
        for part in str(line).splitlines() or [""]:
            click.echo(f"warning: {visible(part)}", err=True)


def load_and_design(path: str, overrides):
    """Load and validate the design file, then run the design calculations (:mod:`gearcli.api`)."""
    from gearcli import api  # lazy: start-up time of --help

    return api.load_and_design(path, overrides)  # "-" reads sys.stdin.buffer (CliRunner swaps it too)


@click.group(context_settings={"help_option_names": ["-h", "--help"]}, epilog="""\b
Examples:
  gearcli init mixer.toml
  gearcli design mixer.toml
  gearcli simulate mixer.toml -o run.csv
  gearcli report mixer.toml -o report.md
Shell completion (bash): eval "$(_GEARCLI_COMPLETE=bash_source gearcli)"
""")
@click.version_option(__version__, prog_name="gearcli")
@click.option("--debug", is_flag=True, help="Show tracebacks on errors.")
@quiet_option
def cli(debug: bool, quiet: bool) -> None:
    """Design check and torsional dynamics of multi-stage helical gear reducers.

    FILE is a TOML design file ('-' reads stdin); `gearcli init` writes a starter one.
    """


@cli.command(epilog="""\b
Examples:
  gearcli design mixer.toml
  gearcli design mixer.toml --format json -o design.json
  gearcli design mixer.toml --set stage.0.pinion.teeth=22 --format csv
  gearcli init - | gearcli design -
""")
@click.argument("file", type=str)
@io_options()
@csv_table_option("stages", "stages (a row per stage)")
@guarded
def design(file: str, overrides, fmt, output, csv_table: str = "stages") -> None:
    """Ratios, speeds, torques, helical geometry, contact ratios, stiffness and static forces."""
    from gearcli import api  # lazy: start-up time of --help
    from gearcli.io import serialize  # lazy: start-up time of --help

    target = check_target(fmt, output)
    loaded, result = load_and_design(file, overrides)
    bearings = wants_bearing_csv(csv_table, "stages", target.fmt, loaded)
    result = api.with_resonances(loaded.design, result)
    emit_as(target.fmt, target, result, sha256=loaded.sha256,
            json_doc=lambda: serialize.design_dict(result),
            csv_text=lambda: serialize.design_bearings_csv(result) if bearings else serialize.design_csv(result),
            table_builder="design_tables")
    warn(result.warnings)


@cli.command(epilog="""\b
Examples:
  gearcli simulate mixer.toml
  gearcli simulate mixer.toml -o run.csv
  gearcli simulate mixer.toml --format json --series -o run.json
  gearcli simulate mixer.toml --set simulation.duration_s=2 --set simulation.steps=20000
""")
@click.argument("file", type=str)
@io_options()
@click.option("--series", is_flag=True, help="Include the time series in JSON output (CSV always has them).")
@click.option("--dump-model", is_flag=True, help="Print the scene's generated equations (Python source) and exit.")
@csv_table_option("series", "series (a row per output sample)")
@guarded
def simulate(file: str, overrides, fmt, output, series: bool, dump_model: bool = False,
             csv_table: str = "series") -> None:
    """Torsional lumped-parameter simulation with nonlinear Hertz meshes."""
    from gearcli import api  # lazy: start-up time of --help

    target = check_target(fmt, output)
    loaded, design_result = load_and_design(file, overrides)  # bad input fails before scipy loads
    bearings = wants_bearing_csv(csv_table, "series", target.fmt, loaded)
    if dump_model:
        emit(api.model_source(loaded.design, design_result), target)  # -o FILE honoured (atomically)
        return
    # the bearings' CSV holds no series: budgeted as the JSON summary
    api.check_budget(loaded, design_result, output_format="json" if bearings else target.fmt, series=series)
    warn(design_result.warnings)
    from gearcli.io import serialize  # lazy: start-up time of --help
    from gearcli.io.progress import TerminalProgress  # lazy: start-up time of --help

    with TerminalProgress("simulate", enabled=not is_quiet()) as progress:  # a long run on a terminal
        result = api.simulate_file(loaded, design_result, progress=progress.fraction)
    emit_as(target.fmt, target, result, sha256=loaded.sha256,
            json_doc=lambda: serialize.simulation_dict(result, series=series),
            csv_text=lambda: (serialize.simulation_bearings_csv(result) if bearings
                              else serialize.simulation_csv(result)), table_builder="simulation_tables")
    warn(w for w in result.warnings if w not in design_result.warnings)  # the design's went out first


@cli.command(epilog="""\b
Examples:
  gearcli modes mixer.toml
  gearcli modes mixer.toml --format json -o modes.json
  gearcli modes mixer.toml --set stage.0.shaft.stiffness_Nm_rad=2e6
  gearcli modes mixer.toml --plots figures
""")
@click.argument("file", type=str)
@io_options()
@click.option("--plots", "plots_dir", type=click.Path(file_okay=False), metavar="DIR",
              help="Also write the Campbell diagram campbell.png to DIR (pip install 'gearcli[plot]').")
@guarded
def modes(file: str, overrides, fmt, output, plots_dir=None) -> None:
    """Natural frequencies (clamped input and free), mode shapes, modal strain-energy shares, mesh orders."""
    from gearcli import api  # lazy: start-up time of --help
    from gearcli.io import modes_out, serialize  # lazy: start-up time of --help

    target = check_target(fmt, output)
    if plots_dir:
        _check_sweep_plots_dir(plots_dir, file, target, ())
    loaded, design_result = load_and_design(file, overrides)
    warn(design_result.warnings)
    analyses = api.modes(loaded.design, design_result)
    if target.fmt == "json":
        emit(serialize.to_json(serialize.with_meta(modes_out.modes_document(analyses, design_result), loaded.sha256)),
             target)
    elif target.fmt == "csv":
        emit(modes_out.modes_csv(analyses), target)
    else:
        emit_tables(modes_out.modes_tables(analyses), target)
    if plots_dir:
        _write_campbell(loaded, api.campbell(loaded.design, design_result), plots_dir)


def _write_figures(write, plots_dir: str, what: str) -> bool:
    """``--plots DIR`` of any command: ``write()`` returns the written paths; without matplotlib a warning and
    exit 0 (``what`` is the command's output, complete without them); an unwritable directory exit 1. Whether
    the figures were written."""
    from gearcli.io.figures import PlotsUnavailable  # lazy: start-up time of --help

    try:
        paths = write()
    except PlotsUnavailable as exc:
        warn([f"{exc}; {what} itself is complete"])
        return False
    except OSError as exc:
        _fail(f"{plots_dir}: cannot write plots: {exc.strerror or exc}", EXIT_FAILED)
    if not is_quiet():
        click.echo(f"wrote {', '.join(visible(p.name) for p in paths)} to {visible(plots_dir)}", err=True)
    return True


def _write_campbell(loaded, data, plots_dir: str) -> None:
    """``modes --plots``: the Campbell diagram at the drive's boundary."""
    from gearcli.io import units  # lazy: start-up time of --help
    from gearcli.io.campbell import write_campbell  # lazy: start-up time of --help

    _write_figures(lambda: [write_campbell(data, units.of_design_file(loaded.design), plots_dir, loaded.design.title)],
                   plots_dir, "the modes output")


@cli.command(epilog="""\b
Examples:
  gearcli init mixer.toml
  gearcli init - > mixer.toml
""")
@click.argument("file", required=False, type=str)
@click.option("--force", is_flag=True, help="Overwrite FILE if it exists.")
@quiet_option
@click.option("--debug", is_flag=True, help="Show tracebacks on errors.")
@guarded
def init(file: str | None, force: bool) -> None:
    """Write a commented starter design file (the seed reducer) to FILE, or to stdout ('-' or none)."""
    from gearcli import api  # lazy: start-up time of --help

    target = outfiles.check_output(file, formats=("toml",), stdout_as="'-'")
    if target.path is not None and target.path.exists() and not force:
        _fail(f"{visible(file or '')}: exists; use --force to overwrite", EXIT_USAGE)
    emit(api.starter_toml(), target)
    if target.path is not None and not is_quiet():
        click.echo(f"wrote {visible(target.shown)}; try: gearcli design {visible(target.shown)}", err=True)


@cli.command(epilog="""\b
Examples:
  gearcli schema -o gearcli.schema.json
  gearcli schema | python -m json.tool
""")
@outfiles.output_option("Write to FILE atomically ('-' is stdout).")
@quiet_option
@click.option("--debug", is_flag=True, help="Show tracebacks on errors.")
@guarded
def schema(output: str | None) -> None:
    """Print the JSON Schema of the design file."""
    from gearcli import api  # lazy: start-up time of --help

    target = outfiles.check_output(output, formats=("json",))
    emit(json.dumps(api.design_file_schema(), indent=2) + "\n", target)


# ------------------------------------------------------------------------------------------ report
REPORT_FORMATS = ("table", "json", "markdown")
MAX_RTOLS = 12  # the default ladder has 7 rungs; each rung is a full simulation


def _parse_rtols(ctx, param, value: str | None):
    if value is None:
        return None
    try:
        rtols = tuple(float(v) for v in value.split(",") if v.strip())
    except ValueError:
        raise click.BadParameter(f"{value!r}: give comma-separated numbers, e.g. 1e-3,1e-6,1e-9") from None
    bad = [r for r in rtols if not 1e-13 <= r <= 1e-2]
    if not rtols or bad:
        raise click.BadParameter("every rtol must lie in [1e-13, 1e-2]" + (f", got {bad[0]:g}" if bad else ""))
    if len(rtols) > MAX_RTOLS:
        raise click.BadParameter(f"at most {MAX_RTOLS} tolerances, got {len(rtols)}")
    if len(set(rtols)) != len(rtols):
        twice = next(r for r in rtols if rtols.count(r) > 1)
        raise click.BadParameter(f"{twice:g} is given twice; each tolerance once")
    return rtols


def _finite_accuracy(ctx, param, value: float) -> float:
    if not math.isfinite(value) or not 1e-12 <= value <= 0.5:
        raise click.BadParameter(f"must be a number in [1e-12, 0.5], got {value!r}")
    return value


@cli.command(epilog="""\b
Examples:
  gearcli report mixer.toml -o report.md
  gearcli report mixer.toml --quick --format json -o report.json
  gearcli report mixer.toml --plots figures --accuracy 1e-5
  gearcli report mixer.toml --rtols 1e-4,1e-6,1e-8 --set simulation.duration_s=0.3
""")
@click.argument("file", type=str)
@click.option("--set", "overrides", multiple=True, metavar="KEY=VALUE",
              help="Override a design-file key, e.g. --set simulation.duration_s=0.25 (repeatable).")
@click.option("--format", "fmt", type=click.Choice(REPORT_FORMATS),
              help="Output format [default: table on a terminal, markdown in a pipe].")
@outfiles.output_option("Write to FILE atomically ('-' is stdout; format from the suffix: .json, .md, .txt).")
@click.option("--accuracy", type=float, callback=_finite_accuracy, default=1e-4, show_default=True,
              help="Relative accuracy the recommended solver setting must meet.")
@click.option("--quick", is_flag=True, help="Skip the accuracy study (one simulation).")
@click.option("--rtols", callback=_parse_rtols, metavar="LIST",
              help="The accuracy ladder's tolerances, comma-separated [default: 1e-3,1e-4,...,1e-9].")
@click.option("--plots", "plots_dir", type=click.Path(file_okay=False), metavar="DIR",
              help="Also write campbell.png, speeds.png, mesh_forces.png, spectrum.png, work_precision.png to DIR. Needs "
                   "matplotlib (pip install 'gearcli[plot]'); without it: a warning, the rest of the report, exit 0.")
@quiet_option
@click.option("--debug", is_flag=True, help="Show tracebacks on errors.")
@guarded
def report(file: str, overrides, fmt, output, accuracy: float, quick: bool, rtols, plots_dir) -> None:
    """Theory against simulation, the numerical error against run time, and plots."""
    from gearcli import api  # lazy: start-up time of --help
    from gearcli.io import serialize  # lazy: start-up time of --help

    target = check_target(fmt, output, REPORT_FORMATS, pipe_format="markdown")
    if plots_dir:
        _check_plots_dir(plots_dir, file, target)
    loaded, design_result = load_and_design(file, overrides)
    api.check_budget(loaded, design_result)  # the file's own run; the ladder's runs bound themselves
    warn(design_result.warnings)
    fmt = target.fmt
    from gearcli.io.progress import TerminalProgress  # lazy: start-up time of --help

    with TerminalProgress("report", enabled=not is_quiet()) as progress:
        rep = api.report_file(loaded, design_result, accuracy=accuracy, quick=quick, rtols=rtols, progress=progress)
    if fmt == "json":
        from gearcli.io.report_json import report_dict  # lazy: start-up time of --help

        emit(serialize.to_json(serialize.with_meta(report_dict(rep), loaded.sha256)), target)
    elif fmt == "markdown":
        from gearcli.io.markdown import report_markdown  # lazy: start-up time of --help

        emit(report_markdown(rep, loaded.sha256), target)
    else:
        from gearcli.io.report_tables import report_tables  # lazy: start-up time of --help

        emit_tables(report_tables(rep), target)
    warn(w for w in rep.warnings if w not in design_result.warnings)  # design ones went out first
    if plots_dir:
        _write_report_plots(rep, plots_dir)


def check_plots_dir(plots_dir: str, names, target: outfiles.OutputTarget) -> None:
    """``--plots DIR`` of every command, before any work: a directory that can be written (or created), and
    no figure ``names`` may replace an input of the command or its -o file, nor land on a directory or device."""
    if os.path.lexists(plots_dir) and not os.path.isdir(plots_dir):
        raise OutputError("--plots needs a directory; this is a file", path=plots_dir)
    outfiles.check_writable_dir(plots_dir, "--plots")  # a read-only DIR fails now, not after the computing
    outfiles.check_not_clobbering([Path(plots_dir) / name for name in names], [*_context_inputs(), target.path],
                                  "--plots")


def _check_plots_dir(plots_dir: str, file: str, target) -> None:
    from gearcli.io.plots import FIGURE_NAMES  # lazy: start-up time of --help

    check_plots_dir(plots_dir, FIGURE_NAMES, target)


def _write_report_plots(rep, plots_dir: str) -> None:
    from gearcli.io.plots import write_plots  # lazy: start-up time of --help

    if _write_figures(lambda: write_plots(rep, plots_dir), plots_dir, "the report") and not is_quiet() \
            and rep.accuracy is None:
        click.echo("work_precision.png needs the accuracy study: run without --quick", err=True)


# ------------------------------------------------------------------------------------------- sweep
SWEEP_FORMATS = ("csv", "json")


@cli.command(epilog="""\b
Examples:
  gearcli sweep mixer.toml --vary input.speed_rpm=300:1500:13 -o speed.csv --plots figures
  gearcli sweep mixer.toml --vary input.speed_rpm=300:1500:13 --direction both -o hysteresis.csv
  gearcli sweep mixer.toml --vary load.torque_Nmm=2e6,5.31e6 --vary stage.0.backlash_mm=0,0.2 -o grid.json
  gearcli sweep mixer.toml --random 'stage.0.backlash_mm=normal(0.25,0.02)' --samples 50 --seed 1 -o mc.csv
""")
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
@outfiles.output_option("Write rows to FILE as they finish (.csv or .json; '-' is stdout); a re-run skips the "
                        "points done.")
@click.option("--plots", "plots_dir", type=click.Path(file_okay=False), metavar="DIR",
              help="Response curves, Campbell diagram, histograms into DIR (pip install 'gearcli[plot]').")
@quiet_option
@click.option("--debug", is_flag=True, help="Show tracebacks on errors.")
@guarded
def sweep(file: str, vary, randoms, samples, sampling, seed, direction, jobs, scheduler, overrides, fmt, output,
          plots_dir) -> None:
    """Simulate many operating points: grids, tolerance samples, continuation up and down in speed."""
    from gearcli import api  # lazy: start-up time of --help
    from gearcli.io.sweep_progress import SweepProgress  # lazy: start-up time of --help

    target = outfiles.check_output(output, formats=SWEEP_FORMATS, fmt=fmt, inputs=_context_inputs())  # before work
    if plots_dir:
        _check_sweep_plots_dir(plots_dir, file, target, vary)
    output = target.shown if target.path is not None else None
    session = api.prepare_sweep(file, overrides, vary=vary, randoms=randoms, samples=samples, sampling=sampling, seed=seed,
                      direction=direction, jobs=jobs, scheduler=scheduler,
                      output=str(target.path) if target.path is not None else None, fmt=target.fmt)
    warn(session.design_warnings)
    warn(session.notes)  # --jobs capped by the machine
    with SweepProgress(session.todo + session.done, session.done, enabled=not is_quiet()) as progress:
        rows = api.run_sweep(session, progress.advance)
    failed = sum(r.get("status") != "ok" for r in rows)
    if failed or not is_quiet():  # -q: silent unless points failed (an error is still said)
        click.echo(f"sweep: {len(rows)} points, {failed} failed" + (f", written to {visible(output)}" if output else ""),
                   err=True)
    if plots_dir:
        _write_sweep_plots(session, rows, plots_dir)
    if failed:
        sys.exit(EXIT_FAILED)


def _check_sweep_plots_dir(plots_dir: str, file: str, target, vary) -> None:
    """As for report: no sweep figure may replace the input or the -o file."""
    names = ["campbell.png", "distributions.png"]
    names += [f"response_{v.split('=', 1)[0].strip().replace('.', '_')}.png" for v in vary]
    check_plots_dir(plots_dir, names, target)


def _write_sweep_plots(session, rows, plots_dir: str) -> None:
    from gearcli import api  # lazy: start-up time of --help
    from gearcli.io.sweep_plots import write_sweep_plots  # lazy: start-up time of --help

    _write_figures(lambda: write_sweep_plots(session, rows, plots_dir, api.sweep_campbell(session)), plots_dir,
                   "the sweep")


# -------------------------------------------------------------------------------------------- life
@cli.command(epilog="""\b
Examples:
  gearcli life mixer_duty.toml --static
  gearcli life mixer_duty.toml --format json -o life.json
  gearcli life mixer_duty.toml --series torque_history.csv --static
  gearcli life mixer_duty.toml --plots figures/
""")
@click.argument("file", type=str)
@io_options()
@click.option("--static", "static", is_flag=True,
              help="Rate each duty point's static forces with the rating's K_v (one load class per point) "
                   "instead of simulating it.")
@click.option("--series", "series", metavar="FILE.csv",
              help="A measured history (time_s,torque_Nm,speed_rpm) instead of the [[duty]] tables.")
@click.option("--classes", type=click.IntRange(1, 1000), default=10, show_default=True,
              help="Torque classes of a --series history.")
@click.option("--miner", type=click.Choice(("iso", "elementary", "modified")), default="iso", show_default=True,
              help="The S-N curve below the knee (ISO 6336-6 Miner variants, docs/life.md).")
@click.option("--plots", "plots_dir", type=click.Path(file_okay=False), metavar="DIR",
              help="Also write pitting.png and bending.png (spectra against the S-N curves) to DIR "
                   "(pip install 'gearcli[plot]').")
@csv_table_option("classes", "classes (a row per load class)")
@guarded
def life(file: str, overrides, fmt, output, static: bool, series, classes: int, miner: str, plots_dir,
         csv_table: str = "classes") -> None:
    """Duty cycle to life: load spectra, ISO 6336-6 Miner damage per member, ISO 281 bearing lives."""
    from gearcli import api  # lazy: start-up time of --help
    from gearcli.io.life_out import life_bearings_csv, life_csv, life_dict  # lazy: start-up time of --help

    target = check_target(fmt, output)
    if plots_dir:
        check_plots_dir(plots_dir, ("pitting.png", "bending.png"), target)
    session = api.prepare_life(file, overrides, series=series, classes=classes)
    bearings = wants_bearing_csv(csv_table, "classes", target.fmt, session.loaded)
    warn(session.design.warnings)
    from gearcli.io.progress import TerminalProgress  # lazy: start-up time of --help

    with TerminalProgress("life", enabled=not is_quiet()) as progress:
        result = api.life(session, static=static, variant=miner, progress=progress)
    emit_as(target.fmt, target, result, sha256=session.loaded.sha256, json_doc=lambda: life_dict(result),
            csv_text=lambda: life_bearings_csv(result) if bearings else life_csv(result),
            table_builder="life_tables")
    warn(w for w in result.warnings if w not in session.design.warnings)
    if plots_dir:
        _write_life_plots(result, plots_dir)


def _write_life_plots(result, plots_dir: str) -> None:
    from gearcli.io.life_plots import write_life_plots  # lazy: start-up time of --help

    _write_figures(lambda: write_life_plots(result, plots_dir), plots_dir, "the life calculation")


@cli.group(epilog="""\b
Examples:
  gearcli engine build
  gearcli engine build --force
""")
def engine() -> None:
    """The compiled integration engine (the fast extra, numba): its cache."""


@engine.command("build", epilog="""\b
Examples:
  gearcli engine build          # once after installing (CI and the install instructions run it)
  gearcli engine build --force  # discard the cache and compile again
""")
@click.option("--force", is_flag=True, help="Discard the cached kernel and compile it again.")
@quiet_option
@click.option("--debug", is_flag=True, help="Show tracebacks on errors.")
@guarded
def engine_build(force: bool) -> None:
    """Compile the integration kernel into the cache now (with progress), so that no run pays for it."""
    from gearcli import api  # lazy: start-up time of --help

    built = api.engine_build(force=force, quiet=is_quiet())
    if built.refused:  # compiled, but nothing cached: the command's purpose failed
        _fail(f"the kernel compiled, but nothing was cached: {built.refused}", EXIT_FAILED)
    if built.build_s:
        click.echo(f"engine: compiled in {built.build_s:.1f} s; cached in {built.directory}")
    else:
        click.echo(f"engine: already compiled; cached in {built.directory}")
    click.echo(f"engine: a process loads it in {built.load_s:.2f} s (numba import, kernel module, one entry; measured now)")


def main() -> None:
    """The console script: SIGTERM unwinds like Ctrl-C (temporary files removed), then exit 143."""
    streams.guard()  # a closed stdout/stderr (>&-): a clean message, never a traceback
    signal.signal(signal.SIGINT, _on_sigint)  # KeyboardInterrupt, remembered (guarded)
    signal.signal(signal.SIGTERM, _on_sigterm)
    if hasattr(signal, "SIGHUP"):  # the terminal went away: unwind like SIGTERM (temporary files removed)
        signal.signal(signal.SIGHUP, _on_sighup)
    try:
        cli(prog_name="gearcli")
    except GearcliError as exc:  # click's own output (--help, --version) on a closed stdout
        _fail(str(exc), exc.exit_code)
    except SystemExit as exc:
        # click's own output (--help, --version) meets a closed pipe: click pacifies stdout and exits 1
        if exc.code == 1 and type(sys.stdout).__name__.endswith("PacifyFlushWrapper"):
            _broken_pipe()
        raise
    except BrokenPipeError:
        _broken_pipe()
    except OSError as exc:  # click's own output (--help, --version) on a device that refuses it (> /dev/full)
        outfiles.drop_buffered(sys.stdout)
        _fail(f"{outfiles.STDOUT_NAME}: cannot write: {exc.strerror or exc}", EXIT_USAGE)


if __name__ == "__main__":  # pragma: no cover
    main()
