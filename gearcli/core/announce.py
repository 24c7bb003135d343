"""Who shows a long step of a command on the terminal (the compiled engine's first build): the command line
installs a reporter (:mod:`gearcli.io.progress`, silent with ``-q``); without one the engine prints plain lines."""

from __future__ import annotations

from typing import Any

_reporter: list[Any] = []


def set_build_reporter(reporter: Any) -> None:
    """Install the reporter of this process's engine builds (``start``/``step``/``note``/``finish``)."""
    _reporter[:] = [reporter]


def build_reporter() -> Any:
    """The installed reporter, or None."""
    return _reporter[0] if _reporter else None
