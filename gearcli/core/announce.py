"""Who shows a long step of a command on the terminal (the compiled engine's first build): the command line
installs a reporter (:mod:`gearcli.io.progress`, silent with ``-q``); without one the engine prints plain lines."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

_reporter: list[Any] = []


def set_build_reporter(reporter: Any) -> None:
    """Install the reporter of this process's engine builds (``start``/``step``/``note``/``finish``)."""
    _reporter[:] = [reporter]


def build_reporter() -> Any:
    """The installed reporter, or None."""
    return _reporter[0] if _reporter else None


class LineReporter:
    """The build as lines on stderr: what is compiled where, every ~15 s how far, and the time it took."""

    EVERY_S = 15.0
    reason = "its first use here"  # why the kernel is compiled (the loader says "again: --force", say)

    def __init__(self, quiet: bool = False) -> None:
        self.quiet = quiet
        self.last = 0.0
        self.damaged = 0  # damaged entries the build compiled again: the first named, the rest counted

    def _say(self, text: str) -> None:
        if not self.quiet:
            print(f"gearcli: {text}", file=sys.stderr, flush=True)

    def start(self, directory: Path) -> None:
        self._say(f"compiling the integration engine ({self.reason}; cached in {directory}) ...")

    def step(self, done: int, total: int, elapsed_s: float) -> None:
        if elapsed_s - self.last >= self.EVERY_S:
            self.last = elapsed_s
            self._say(f"compiling the integration engine: {done} of ~{total} functions, {elapsed_s:.0f} s")

    def note(self, line: str) -> None:
        self.damaged += 1
        if self.damaged == 1:  # one line however many entries were damaged (a truncated cache: a hundred)
            self._say(f"the engine cache had a damaged entry, compiled again: {line}")

    def finish(self, seconds: float, directory: Path, waited: bool = False) -> None:
        if self.damaged > 1:
            self._say(f"the engine cache had {self.damaged - 1} more damaged entries, compiled again too")
        if waited:
            self._say(f"another process compiled the integration engine; waited {seconds:.1f} s for it")
            return
        self._say(f"compiled the integration engine in {seconds:.1f} s (measured now; later runs load it from "
                  f"{directory})")
