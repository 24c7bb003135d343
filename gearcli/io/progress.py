"""Progress of long work on a terminal: a rich bar on stderr, silent in a pipe and with ``-q``.

The core reports progress through callbacks and never prints (``gearcli.simulate.run.simulate_model``'s
``progress(fraction)``, ``gearcli.report.build_report``'s ``progress(label, done, total)``); this module turns
them into a transient bar. A bar appears only once the work has taken :data:`SHOW_AFTER_S`, so that a short
command does not flicker.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path
from typing import Any

from gearcli.core import announce
from gearcli.core.announce import LineReporter

SHOW_AFTER_S = 1.0


class TerminalProgress:
    """``with TerminalProgress("simulate", enabled=not quiet) as p``: ``p(label, done, total)`` for counted work
    (a report's runs), ``p.fraction(x)`` for one long run (0..1). A no-op unless stderr is a terminal."""

    def __init__(self, label: str, *, enabled: bool = True) -> None:
        self.label = label
        self.enabled = enabled and sys.stderr.isatty()
        self.bar: Any = None
        self.task: Any = None
        self.start = time.perf_counter()

    def __enter__(self) -> TerminalProgress:
        self.start = time.perf_counter()
        return self

    def _ensure(self) -> bool:
        if not self.enabled:
            return False
        if self.bar is None:
            if time.perf_counter() - self.start < SHOW_AFTER_S:
                return False
            from rich.console import Console  # lazy: rich, only when a terminal shows the bar

            # lazy: rich, only when a terminal shows the bar
            from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

            self.bar = Progress(TextColumn("{task.description:<28}"), BarColumn(), MofNCompleteColumn(),
                                TimeElapsedColumn(), console=Console(stderr=True), transient=True)
            self.bar.__enter__()
            self.task = self.bar.add_task(self.label, total=None)
        return True

    def __call__(self, label: str, done: int, total: int) -> None:
        if self._ensure():
            self.bar.update(self.task, description=label, completed=done, total=total)

    def fraction(self, done: float) -> None:
        """One run, ``done`` of it (0..1), shown in per mille."""
        if self._ensure():
            self.bar.update(self.task, description=self.label, completed=int(1000 * min(max(done, 0.0), 1.0)),
                            total=1000)

    def __exit__(self, *exc: object) -> None:
        if self.bar is not None:
            self.bar.__exit__(*exc)
            self.bar = None


class BuildProgress(LineReporter):
    """The compiled engine's first build as a step (:mod:`gearcli.engine.builder`'s reporter): the engine's plain
    lines (:class:`gearcli.core.announce.LineReporter`: when it starts, every ~15 s, the measured time when it ends),
    and on a terminal a bar of the functions compiled instead of the periodic lines; nothing with ``-q``."""

    def __init__(self, *, quiet: bool = False) -> None:
        super().__init__(quiet)
        self.bar: TerminalProgress | None = None

    def start(self, directory: Path) -> None:
        super().start(directory)
        if not self.quiet and sys.stderr.isatty():
            self.bar = TerminalProgress("compiling the engine").__enter__()
            self.bar.start -= SHOW_AFTER_S  # at once: the step was announced

    def step(self, done: int, total: int, elapsed_s: float) -> None:
        if self.bar is not None:
            self.bar("compiling the engine", done, total)
        else:
            super().step(done, total, elapsed_s)

    def finish(self, seconds: float, directory: Path, waited: bool = False) -> None:
        if self.bar is not None:
            self.bar.__exit__(None, None, None)
            self.bar = None
        super().finish(seconds, directory, waited)


def show_engine_builds(*, quiet: bool) -> None:
    """Install :class:`BuildProgress` as this process's reporter of engine builds (:mod:`gearcli.core.announce`)."""
    announce.set_build_reporter(BuildProgress(quiet=quiet))
