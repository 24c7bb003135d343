"""Typed errors and the exit codes the CLI maps them to (DESIGN.md section 5)."""

from __future__ import annotations

EXIT_OK = 0
EXIT_FAILED = 1  # the run failed: solver failure, infeasible design
EXIT_USAGE = 2  # bad usage or bad design file
EXIT_INTERRUPTED = 130


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
        where = ": ".join(p for p in (self.source, self.key) if p)
        return f"{where}: {self.message}" if where else self.message


class DesignError(GearcliError):
    """The design is infeasible (e.g. an external helical pair of the same hand)."""

    exit_code = EXIT_USAGE

    def __init__(self, message: str, *, key: str | None = None, source: str | None = None):
        self.key = key
        self.source = source
        self.message = message
        where = ": ".join(p for p in (source, key) if p)
        super().__init__(f"{where}: {message}" if where else message)


class SimulationError(GearcliError):
    """The integration failed or diverged; the message names the likely cause and the fix."""

    exit_code = EXIT_FAILED
