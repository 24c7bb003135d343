"""The command line: parse, load, call the core, hand results to ``gearcli.io``.

Library errors become one-line messages on stderr with fixed exit codes (0 ok, 1 the run failed,
2 bad usage or bad design file, 130 interrupted); a traceback only with ``--debug``. Heavy modules
(scipy) are imported inside the commands that need them, so ``gearcli design`` starts fast.

The package by concern: :mod:`~gearcli.cli.common` (error and signal handling, shared options, output targets),
:mod:`~gearcli.cli.design_cmds` (design, simulate, modes, init, schema), :mod:`~gearcli.cli.study_cmds`
(report, sweep, life), :mod:`~gearcli.cli.engine_cmds` (engine build); here the group and the console script.
"""

from __future__ import annotations

import signal
import sys

import click

from gearcli import __version__
from gearcli.cli import design_cmds, engine_cmds, study_cmds
from gearcli.cli.common import (
    FORMATS,
    INPUT_PARAMS,
    SUFFIX_FORMAT,
    Group,
    broken_pipe,
    check_plots_dir,
    check_target,
    emit,
    emit_as,
    emit_tables,
    fail,
    guarded,
    interrupted,
    io_options,
    is_quiet,
    on_sighup,
    on_sigint,
    on_sigterm,
    on_unraisable,
    quiet_option,
    signalled,
    warn,
)
from gearcli.errors import EXIT_USAGE, GearcliError, Terminated
from gearcli.io import output as outfiles
from gearcli.io import streams

__all__ = ["FORMATS", "INPUT_PARAMS", "SUFFIX_FORMAT", "check_plots_dir", "check_target", "cli", "emit", "emit_as",
           "emit_tables", "guarded", "io_options", "is_quiet", "main", "quiet_option", "warn"]


@click.group(cls=Group, context_settings={"help_option_names": ["-h", "--help"]}, epilog="""\b
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


for _command in (design_cmds.design, design_cmds.simulate, design_cmds.modes, design_cmds.init, design_cmds.schema,
                 study_cmds.report, study_cmds.sweep, study_cmds.life, engine_cmds.engine):
    cli.add_command(_command)


def main() -> None:
    """The console script: SIGTERM unwinds like Ctrl-C (temporary files removed), then exit 143."""
    streams.guard()  # a closed stdout/stderr (>&-): a clean message, never a traceback
    signal.signal(signal.SIGINT, on_sigint)  # KeyboardInterrupt, remembered (guarded)
    signal.signal(signal.SIGTERM, on_sigterm)
    if hasattr(signal, "SIGHUP"):  # the terminal went away: unwind like SIGTERM (temporary files removed)
        signal.signal(signal.SIGHUP, on_sighup)
    sys.unraisablehook = on_unraisable  # a signal's exception dropped inside a callback: the signal again
    try:
        cli(prog_name="gearcli")
    except GearcliError as exc:  # click's own output (--help, --version) on a closed stdout
        fail(str(exc), exc.exit_code)
    except (KeyboardInterrupt, Terminated) as exc:  # a signal outside a command's body (click's parsing, a lazy
        signalled(exc)  # import before the body's guard): the same one line and exit code, never a traceback
    except SystemExit as exc:
        # a Ctrl-C during click's own parsing, or before a command body's guard, is click's KeyboardInterrupt: it
        # prints "Aborted!" and exits 1; the signal's exit code and line instead (a SIGINT 0.35 s into a compiled
        # simulate, tests/engine/test_signals.py)
        if exc.code == 1 and interrupted():
            signalled(KeyboardInterrupt())
        # click's own output (--help, --version) meets a closed pipe: click pacifies stdout and exits 1
        if exc.code == 1 and type(sys.stdout).__name__.endswith("PacifyFlushWrapper"):
            broken_pipe()
        raise
    except BrokenPipeError:
        broken_pipe()
    except OSError as exc:  # click's own output (--help, --version) on a device that refuses it (> /dev/full)
        outfiles.drop_buffered(sys.stdout)
        fail(f"{outfiles.STDOUT_NAME}: cannot write: {exc.strerror or exc}", EXIT_USAGE)


if __name__ == "__main__":  # pragma: no cover
    main()
