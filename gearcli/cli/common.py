"""What every command shares: error and signal handling (:func:`guarded`), the shared options, the output
target checks and writers, warnings on stderr."""

from __future__ import annotations

import functools
import os
import signal
import sys
import threading
import time
import traceback
import warnings as warnings_module
from collections.abc import Callable
from pathlib import Path

import click

from gearcli.core.text import shorten, visible
from gearcli.errors import (
    EXIT_BROKEN_PIPE,
    EXIT_FAILED,
    EXIT_HANGUP,
    EXIT_INTERRUPTED,
    EXIT_TERMINATED,
    ConfigError,
    GearcliError,
    OutputError,
    Terminated,
)
from gearcli.io import output as outfiles

FORMATS = ("table", "csv", "json")
SUFFIX_FORMAT = outfiles.SUFFIX_FORMAT


def fail(message: str, code: int) -> None:
    for line in message.splitlines() or [""]:
        click.echo(f"gearcli: {visible(line)}", err=True)
    sys.exit(code)


def broken_pipe() -> None:
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


def interrupted() -> bool:
    """A SIGINT reached this process (its handler ran): what an exit click gave it means (``Aborted!``, 1)."""
    return EXIT_INTERRUPTED in _SIGNALLED


def on_sigint(signum, frame) -> None:
    _SIGNALLED.append(EXIT_INTERRUPTED)
    raise KeyboardInterrupt


def on_sigterm(signum, frame) -> None:
    _SIGNALLED.append(EXIT_TERMINATED)
    raise Terminated()


def on_sighup(signum, frame) -> None:
    _SIGNALLED.append(EXIT_HANGUP)
    raise Terminated(EXIT_HANGUP)


_SIGNUMS = {EXIT_INTERRUPTED: signal.SIGINT, EXIT_TERMINATED: signal.SIGTERM,
            EXIT_HANGUP: getattr(signal, "SIGHUP", signal.SIGTERM)}


def on_unraisable(args) -> None:
    """``sys.unraisablehook`` of the console script. A signal's exception (KeyboardInterrupt, ``Terminated``) raised
    where Python cannot propagate it (a weakref callback of the import system's module locks while a command's lazy
    import runs, a finalizer) is printed and dropped by Python's own hook, and the command would run on to its end
    as if no signal had come (seen: SIGTERM 0.35 s into ``gearcli life``, the whole run done, exit 0). The signal is
    sent again from another thread instead, once the main thread has left this hook (:func:`_resend`), so that its
    handler runs in the code the callback interrupted and unwinds the command like any other signal."""
    if isinstance(args.exc_value, KeyboardInterrupt | Terminated) and _SIGNALLED:
        signum = _SIGNUMS[_SIGNALLED.pop()]  # its handler records it again
        threading.Thread(target=_resend, args=(signum,), name="gearcli-resignal", daemon=True).start()
        return
    sys.__unraisablehook__(args)


def _resend(signum: int, wait_s: float = 2.0) -> None:
    """Send ``signum`` to this process once the main thread is out of :func:`on_unraisable` (raised while it is
    still there, the handler's exception would be dropped again, by the hook's caller)."""
    main = threading.main_thread().ident
    deadline = time.monotonic() + wait_s
    while time.monotonic() < deadline:
        frame = sys._current_frames().get(main) if main is not None else None
        while frame is not None and frame.f_code is not on_unraisable.__code__:
            frame = frame.f_back
        if frame is None:
            break
        time.sleep(0.001)
    os.kill(os.getpid(), signum)


def signalled(exc: BaseException) -> None:
    """The one line and exit code of an interrupt (130), a SIGTERM (143) or a hangup (129)."""
    if isinstance(exc, KeyboardInterrupt):
        fail("interrupted", EXIT_INTERRUPTED)
    if exc.args == (EXIT_HANGUP,):
        fail("hangup", EXIT_HANGUP)
    fail("terminated", EXIT_TERMINATED)


def guarded(fn: Callable) -> Callable:
    """Run a command body; map errors to messages and exit codes (traceback only with --debug).
    Numeric RuntimeWarnings are collected and reported as one plain warning each, never raw."""

    @functools.wraps(fn)
    def wrapper(*args, debug: bool = False, quiet: bool = False, **kwargs):
        root = click.get_current_context().find_root()
        debug = debug or bool(root.params.get("debug"))
        _SIGNALLED.clear()  # this command's signals (a signal before it raised already; in-process callers run many)
        if quiet:
            click.get_current_context().meta["gearcli.quiet"] = True
        _show_engine_builds()
        try:
            from gearcli import api  # lazy: start-up time of --help

            api.check_environment()  # one rule for every command: a set GEARCLI_MEMORY_LIMIT_MB must be valid
            caught: list[warnings_module.WarningMessage] = []
            try:
                with warnings_module.catch_warnings(record=True) as caught:
                    warnings_module.simplefilter("always", RuntimeWarning)
                    return fn(*args, **kwargs)
            finally:  # once the recording has ended: inside it, showing a warning appended it to the list being
                _report_numeric_warnings(caught)  # shown, an endless loop (a CJK title's glyph warning: 2 GB, hung)
        except GearcliError as exc:
            if debug:  # the traceback, then the same one line and exit code (raised on, main() would print the line
                traceback.print_exc()  # alone: it catches gearcli's errors for click's own output)
            if _SIGNALLED:  # a signal's exception turned into a refusal: numba's C import made a SIGHUP 0.75 s into
                fail(_SIGNAL_WORDS[_SIGNALLED[0]], _SIGNALLED[0])  # a compiled run "numba cannot be imported" (exit 2)
            fail(str(exc), exc.exit_code)
        except BrokenPipeError:
            broken_pipe()
        except (KeyboardInterrupt, Terminated) as exc:
            signalled(exc)
        except (click.exceptions.Exit, click.ClickException, SystemExit):
            raise
        except Exception as exc:  # a bug: say so plainly, never a traceback without --debug
            if _SIGNALLED and not debug:  # a signal's exception turned into another inside a C extension (an
                fail(_SIGNAL_WORDS[_SIGNALLED[0]], _SIGNALLED[0])  # import's "initialization failed"): the signal
            if debug:
                raise
            fail(f"internal error: {type(exc).__name__}: {shorten(str(exc), 200)} "
                  "(run with --debug for the traceback)", EXIT_FAILED)

    return wrapper


def _show_engine_builds() -> None:
    """A first compilation of the engine inside this command shows as a step (silent with -q)."""
    from gearcli.io.progress import show_engine_builds  # lazy: start-up time of --help

    show_engine_builds(quiet=is_quiet())


def _report_numeric_warnings(caught) -> None:
    """The Python warnings of the run as plain warning lines, each message once and nothing with ``-q``: numpy/scipy
    RuntimeWarnings as numerical warnings, any other (matplotlib's glyph missing from the fonts of a title) as its
    message, without the source path and line Python's own display adds."""
    numeric: list[str] = []
    other: list[str] = []
    for w in caught:
        seen = numeric if issubclass(w.category, RuntimeWarning) else other
        if str(w.message) not in seen:
            seen.append(str(w.message))
    warn(f"numerical warning during the run: {shorten(m, 120)}" for m in numeric)
    warn(other)


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


def context_inputs() -> tuple[str | None, ...]:
    ctx = click.get_current_context(silent=True)
    if ctx is None:
        return ()
    return tuple(ctx.params[p] for p in INPUT_PARAMS if isinstance(ctx.params.get(p), str))


def check_target(fmt: str | None, out: str | None, formats: tuple[str, ...] = FORMATS, *,
                 pipe_format: str = "csv", file_default: str | None = None) -> outfiles.OutputTarget:
    """Check ``-o`` against the command's input file and formats (exit 2 before any computation)."""
    return outfiles.check_output(out, formats=formats, fmt=fmt, inputs=context_inputs(),
                               file_default=file_default or pipe_format, stdout_default=_tty_default(pipe_format))


Destination = None | str | outfiles.OutputTarget


def _target(dest: Destination) -> outfiles.OutputTarget:
    if isinstance(dest, outfiles.OutputTarget):
        return dest
    if dest is None or dest == outfiles.STDOUT or ("\0" not in dest and outfiles.open_descriptor(dest) == 1):
        return outfiles.OutputTarget(fmt="")
    return outfiles.OutputTarget(fmt="", path=outfiles.resolve_path(dest, context_inputs()), shown=dest)


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
    """Warnings on stderr, one line each, control characters escaped (a newline too: a name that holds one, a duty
    point's, stays inside its warning's line, so stderr lists the warnings the JSON does); nothing with ``-q``."""
    if is_quiet():
        return
    for line in lines:
        click.echo(f"warning: {visible(str(line))}", err=True)


def load_and_design(path: str, overrides):
    """Load and validate the design file, then run the design calculations (:mod:`gearcli.api`)."""
    from gearcli import api  # lazy: start-up time of --help

    return api.load_and_design(path, overrides)  # "-" reads sys.stdin.buffer (CliRunner swaps it too)



def check_plots_dir(plots_dir: str, names, target: outfiles.OutputTarget) -> None:
    """``--plots DIR`` of every command, before any work: a directory that can be written (or created), and
    no figure ``names`` may replace an input of the command or its -o file, nor land on a directory or device."""
    if os.path.lexists(plots_dir) and not os.path.isdir(plots_dir):
        raise OutputError("--plots needs a directory; this is a file", path=plots_dir)
    if target.path is not None and (target.path == (real := Path(os.path.realpath(plots_dir)))
                                    or target.path in real.parents):  # neither exists yet: the -o file, written
        # first, would stand where the directory is to be made, and the run fail after all its work (exit 1)
        raise OutputError(f"--plots needs a directory where -o writes its file ({shorten(target.shown)}); choose "
                          "another directory or another -o", path=plots_dir)
    outfiles.check_writable_dir(plots_dir, "--plots")  # a read-only DIR fails now, not after the computing
    outfiles.check_not_clobbering([Path(plots_dir) / name for name in names], [*context_inputs(), target.path],
                                  "--plots")



def write_figures(write, plots_dir: str, what: str) -> bool:
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
        fail(f"{plots_dir}: cannot write plots: {exc.strerror or exc}", EXIT_FAILED)
    if not is_quiet():
        click.echo(f"wrote {', '.join(visible(p.name) for p in paths)} to {visible(plots_dir)}" if paths else
                   f"no figures for {visible(plots_dir)}: {what} has no result to draw", err=True)
    return True



def check_sweep_plots_dir(plots_dir: str, file: str, target, vary) -> None:
    """As for report: no sweep figure may replace the input or the -o file."""
    names = ["campbell.png", "distributions.png"]
    if vary:  # the sweep's (modes has none; the figure module imports the sweep's layers)
        from gearcli.io.sweep_plots import response_name  # lazy: start-up time of --help

        names += [response_name(v.split("=", 1)[0].strip()) for v in vary]
    check_plots_dir(plots_dir, names, target)



class UsageError(click.UsageError):
    """click's usage error in gearcli's words: the usage and the help hint as click prints them, then the message
    with the ``gearcli:`` prefix every other error carries (click's was ``Error: ...``); exit 2 (DESIGN §5)."""

    def show(self, file=None) -> None:
        if self.ctx is not None:
            help_names = self.ctx.command.get_help_option_names(self.ctx)
            hint = (f"Try '{self.ctx.command_path} {max(help_names, key=len)}' for help.\n"
                    if self.ctx.command.get_help_option(self.ctx) is not None and help_names else "")
            click.echo(f"{self.ctx.get_usage()}\n{hint}", file=file, err=file is None, color=self.ctx.color)
        for line in self.format_message().splitlines() or [""]:
            click.echo(f"gearcli: {visible(line)}", file=file, err=file is None)


class Group(click.Group):
    """The command group whose usage errors, its own and its commands' (click's parsing and a command's
    ``click.UsageError``), are :class:`UsageError`'s."""

    def make_context(self, info_name, args, parent=None, **extra) -> click.Context:
        try:
            return super().make_context(info_name, args, parent, **extra)
        except UsageError:
            raise
        except click.UsageError as exc:
            raise UsageError(exc.format_message(), exc.ctx) from None

    def invoke(self, ctx: click.Context):
        try:
            return super().invoke(ctx)
        except UsageError:
            raise
        except click.UsageError as exc:
            raise UsageError(exc.format_message(), exc.ctx) from None
