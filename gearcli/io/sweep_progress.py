"""The sweep's progress on a terminal (stderr): points done, failures, rate, time left; silent in pipes."""

from __future__ import annotations

import sys
from typing import Any


class SweepProgress:
    def __init__(self, total: int, done: int = 0, *, enabled: bool = True) -> None:
        self.total, self.done, self.failed = total, done, 0
        self.enabled = enabled  # False with -q
        self.bar: Any = None

    def __enter__(self) -> SweepProgress:
        if self.enabled and sys.stderr.isatty():
            from rich.console import Console  # lazy: rich, only when a terminal shows the bar
            from rich.progress import (  # lazy: rich, only when a terminal shows the bar
                BarColumn,
                MofNCompleteColumn,
                Progress,
                TextColumn,
                TimeElapsedColumn,
                TimeRemainingColumn,
            )

            self.bar = Progress(TextColumn("sweep"), BarColumn(), MofNCompleteColumn(),
                                TextColumn("{task.fields[failed]} failed"),
                                TextColumn("{task.fields[rate]}"), TimeElapsedColumn(), TextColumn("left"),
                                TimeRemainingColumn(), console=Console(stderr=True), transient=True)
            self.bar.__enter__()
            self.task = self.bar.add_task("sweep", total=self.total, completed=self.done, failed=0, rate="")
        return self

    def advance(self, failed: bool) -> None:
        self.failed += int(failed)
        if self.bar is not None:
            self.bar.advance(self.task)
            speed = self.bar.tasks[0].speed
            self.bar.update(self.task, failed=self.failed, rate=f"{speed:.2f} points/s" if speed else "")

    def __exit__(self, *exc) -> None:
        if self.bar is not None:
            self.bar.__exit__(*exc)
