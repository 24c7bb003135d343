"""Typed errors and the exit codes the CLI maps them to (docs/output.md, "Exit codes")."""

from __future__ import annotations

from gearcli.core.plugins import NameConflict
from gearcli.core.text import shorten

EXIT_OK = 0
EXIT_FAILED = 1  # the run failed: solver failure, infeasible design
EXIT_USAGE = 2  # bad usage or bad design file
EXIT_INTERRUPTED = 130
EXIT_TERMINATED = 143  # 128 + SIGTERM, as a shell reports it
EXIT_HANGUP = 129  # 128 + SIGHUP: the terminal went away; handled like SIGTERM
EXIT_BROKEN_PIPE = 141  # 128 + SIGPIPE: the reader went away (`gearcli ... | head -1`); nothing printed


def located(message: str, source: str | None, key: str | None) -> str:
    """``source: key: message``, each part printed literally and capped (a hostile key cannot flood a terminal)."""
    where = ": ".join(shorten(p) for p in (source, key) if p)
    text = shorten(message, 2000)
    return f"{where}: {text}" if where else text


class GearcliError(Exception):
    """Base class of every error gearcli reports to a user (never with a traceback)."""

    exit_code = EXIT_FAILED


class ConfigError(GearcliError):
    """The design file (or a ``--set`` override) is wrong. ``source`` names the file, ``key`` the path."""

    exit_code = EXIT_USAGE

    def __init__(self, message: str, *, source: str | None = None, key: str | None = None):
        self.source = source
        self.key = key
        self.message = message
        super().__init__(self.format())

    def format(self) -> str:
        return located(self.message, self.source, self.key)


class DesignError(GearcliError):
    """The design is infeasible (e.g. an external helical pair of the same hand)."""

    exit_code = EXIT_USAGE

    def __init__(self, message: str, *, key: str | None = None, source: str | None = None):
        self.key = key
        self.source = source
        self.message = message
        super().__init__(located(message, source, key))


class PluginError(GearcliError):
    """A plug-in (a stage kind or a rating standard registered from outside gearcli, docs/plugins.md) raised, or
    returned what its protocol does not allow: the message names the plug-in, what was asked and what it did."""


#: what third-party code (a plug-in's facet, standard, table property or register) may raise that gearcli names as
#: the plug-in's fault: any Exception, and SystemExit (a plug-in's ``sys.exit()`` ended the command silently, with
#: its code: exit 0 and no output); KeyboardInterrupt stays the user's Ctrl-C
PLUGIN_FAULTS: tuple[type[BaseException], ...] = (Exception, SystemExit)


class PluginConflict(PluginError, NameConflict):
    """Two registrants of one stage type or rating standard name (two plug-ins, or a plug-in and gearcli's own
    built-in name): refused, naming both and the name (docs/plugins.md, "Names")."""


class SimulationError(GearcliError):
    """The integration failed or diverged; the message names the likely cause and the fix."""

    exit_code = EXIT_FAILED


class RunTooLong(SimulationError):
    """A run stopped a few seconds in because its pace projects far over the computing budget: refused
    like a resource estimate (exit 2), with the duration that would fit."""

    exit_code = EXIT_USAGE


class StudyTooLong(RunTooLong):
    """A whole study (the report's accuracy ladder) out of its computing budget: it ends the study, where one
    rung's own failure would only be a row of it."""


class OutputError(GearcliError):
    """An output path that must not be written (a directory, a device, the input ...): nothing is written."""

    exit_code = EXIT_USAGE

    def __init__(self, message: str, *, path: str):
        self.path = path
        self.message = message
        super().__init__(f"{path}: {message}")


class ResourceError(GearcliError):
    """A run whose memory or cost estimate exceeds a stated bound: refused before it starts."""

    exit_code = EXIT_USAGE


class StdoutClosed(GearcliError):
    """Standard output is closed (``>&-``) and the command has data for it (gearcli.io.streams)."""

    exit_code = EXIT_USAGE

    def __init__(self) -> None:
        super().__init__("standard output is closed, so the output has nowhere to go: write it to a file with "
                         "-o FILE, or leave stdout open")


class Terminated(BaseException):
    """SIGTERM (or SIGHUP: ``args == (EXIT_HANGUP,)``) arrived: unwinds like KeyboardInterrupt, so temporary
    files are removed (exit 143, 129)."""
