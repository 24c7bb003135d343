"""The table primitives every ``io`` table module builds on: :class:`FittedTable` (number columns as wide as
their numbers, the rightmost left out with a note when even that does not fit), :class:`StageColumns` (a
column per stage, split into as many tables as the width holds), the widths, ``text`` (literal ``Text``, never
rich markup) and the number format ``_g`` (docs/output.md, "Tables").

The bottom of ``io``'s table modules: ``tables``, ``life_tables``, ``life_out`` and ``report_tables`` import it,
it imports none of them (the ``io`` layer's inner contract, ARCHITECTURE.md).
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import Literal

from rich.cells import cell_len
from rich.console import Console, ConsoleOptions, RenderResult
from rich.table import Table
from rich.text import Text

from gearcli.core.text import visible

FILE_WIDTH = 110  # text written to -o FILE or a pipe, unless COLUMNS says otherwise
MIN_WIDTH = 20
LABEL_WIDTH = 30  # the quantity column
CELL_WIDTH = 13  # a number like -1.2346e+05 and its padding


def text(value: str, style: str = "") -> Text:
    """A literal Text (no markup) with control characters escaped."""
    return Text(visible(value), style=style)


def output_width(terminal: bool = False) -> int:
    """COLUMNS when it is a usable number, else the terminal's width (on a terminal) or :data:`FILE_WIDTH`;
    never less than :data:`MIN_WIDTH` (``COLUMNS=0`` or garbage means "not told")."""
    try:
        cols = int(os.environ.get("COLUMNS", ""))
    except ValueError:
        cols = 0
    if cols >= MIN_WIDTH:
        return cols
    if terminal:
        try:
            size = os.get_terminal_size().columns
        except OSError:
            size = 0
        return size if size >= MIN_WIDTH else FILE_WIDTH
    return FILE_WIDTH


def terminal_console() -> Console:
    """The terminal's console: its width (see :func:`output_width`), no markup, no emoji codes."""
    return Console(width=output_width(terminal=True), markup=False, emoji=False, highlight=False)


@dataclass
class StageColumns:
    """A quantity table with one column per stage (or shaft), split into as many tables as the width needs."""

    title: str
    columns: Sequence[str]
    rows: Sequence[tuple[str, Sequence[str]]]

    def tables(self, width: int) -> list[FittedTable]:
        per = max(1, (width - LABEL_WIDTH) // CELL_WIDTH)
        n = len(self.columns)
        out = []
        for lo in range(0, n, per):
            hi = min(n, lo + per)
            span = self.columns[lo] if hi - lo == 1 else f"{self.columns[lo]}–{self.columns[hi - 1]}"
            title = self.title if hi - lo == n else f"{self.title} ({span})"
            out.append(_table(title, self.columns[lo:hi], [(lab, cells[lo:hi]) for lab, cells in self.rows]))
        return out

    def __rich_console__(self, console: Console, options: ConsoleOptions) -> RenderResult:
        yield from self.tables(options.max_width)


@dataclass
class FittedTable:
    """A table whose numbers are printed whole at any width (docs/output.md, "Tables"): a numeric column is
    exactly as wide as its longest cell, text columns (labels, headers) share the rest and fold; when even that
    does not fit, numeric columns are dropped from the right and a note under the table names them. Never a
    cut number (0.012387 shown as 0.01238) nor one folded over lines."""

    title: str
    headers: Sequence[str]
    rows: Sequence[Sequence[str]]
    numeric: Sequence[bool]  # per column: its cells are numbers (never folded)
    justify: Sequence[str] = ()  # per column "left"/"right" (default: right for numeric columns)
    styles: Sequence[str | None] = ()
    ends: Sequence[bool] = ()  # per row: a section ends after it
    MIN_TEXT = 5  # a text column folds, but not narrower than this
    MAX_WORD = 12  # ... and keeps its words whole up to this length

    def _cells(self, c: int) -> list[str]:
        return [visible(r[c]) for r in self.rows]

    def _natural(self, c: int) -> int:
        return max([cell_len(x) for x in self._cells(c)] + [cell_len(visible(self.headers[c])), 1])

    def _least(self, c: int) -> int:
        if self.numeric[c]:
            return max([cell_len(x) for x in self._cells(c)] + [1])
        words = [cell_len(w) for x in [*self._cells(c), visible(self.headers[c])] for w in x.split()] or [1]
        return min(self._natural(c), max(self.MIN_TEXT, min(max(words), self.MAX_WORD)))  # words whole if it can

    def compact(self, width: int) -> bool:
        """Whether the table needs its narrow form (no padding at the outer edges) to fit ``width``."""
        n = len(self.headers)
        return sum(self._natural(c) for c in range(n)) + 3 * n + 1 > width

    def columns_for(self, width: int) -> tuple[list[int], dict[int, int]]:
        """The columns kept at ``width`` and each one's width."""
        keep = list(range(len(self.headers)))
        edge = 0 if self.compact(width) else 2

        def frame(cols: list[int]) -> int:  # borders and padding: "│ a │ b │" (narrow form: "│a │ b│")
            return 3 * len(cols) - 1 + edge

        while sum(self._least(c) for c in keep) + frame(keep) > width and sum(self.numeric[c] for c in keep) > 1:
            keep.remove(max(c for c in keep if self.numeric[c]))
        widths = {c: self._least(c) for c in keep}
        room = max(0, width - frame(keep) - sum(widths.values()))
        # the width left over unfolds as many columns as it can, the cheapest first (a header of a few more
        # characters before a long label); what remains is shared evenly among the rest
        wanting = sorted((c for c in keep if self._natural(c) > widths[c]), key=lambda c: self._natural(c) - widths[c])
        for i, c in enumerate(wanting):
            need = self._natural(c) - widths[c]
            share = need if need <= room else room // (len(wanting) - i)
            widths[c] += share
            room -= share
        return keep, widths

    def __rich_console__(self, console: Console, options: ConsoleOptions) -> RenderResult:
        keep, widths = self.columns_for(options.max_width)
        table = Table(title=text(self.title), title_justify="left", header_style="bold",
                      pad_edge=not self.compact(options.max_width))
        for c in keep:
            justify: Literal["left", "right"] = "right" if self.numeric[c] else "left"
            if self.justify:
                justify = "left" if self.justify[c] == "left" else "right"
            style = self.styles[c] if self.styles else None
            table.add_column(text(self.headers[c]), justify=justify, overflow="fold", width=widths[c],
                             style=style or "")
        for i, row in enumerate(self.rows):
            table.add_row(*(text(row[c]) for c in keep), end_section=bool(self.ends and self.ends[i]))
        yield table
        dropped = [visible(self.headers[c]) for c in range(len(self.headers)) if c not in keep]
        if dropped:
            yield text(f"(column{'s' if len(dropped) > 1 else ''} {', '.join(dropped)} left out: "
                       f"{options.max_width} characters are too narrow to print every number whole; widen the "
                       "terminal (COLUMNS) or use --format csv/json)", "dim")


def _g(v: float | None, digits: int = 5) -> str:
    """A number to ``digits`` significant digits; "—" where it is undefined (None)."""
    return "—" if v is None else f"{v + 0.0:.{digits}g}"  # + 0.0: no negative zero


def spread_digits(v: float | None, mean: float | None) -> int:
    """Significant digits for a spread (a std, an rms about the mean) printed beside its mean: 3, more (at most 5,
    as the mean, min and max are printed) where 3 would round it by more than 1e-4 of the mean's magnitude, so
    a printed std stays within the statistics' stated accuracy, 1e-3 of the channel's mean (DESIGN §7): a std of
    1276.6 N about a mean of 1880 N prints 1276.6, not 1.28e+03 (3.4 N off, 1.8e-3 of the mean)."""
    digits = 3
    if v and mean and math.isfinite(v) and math.isfinite(mean):
        top = math.floor(math.log10(abs(v)))
        while digits < 5 and 0.5 * 10.0 ** (top - digits + 1) > 1e-4 * abs(mean):
            digits += 1
    return digits


def spread(v: float | None, mean: float | None) -> str:
    """A spread beside its mean, to :func:`spread_digits` significant digits; "—" where it is undefined."""
    return _g(v, spread_digits(v, mean))


def limits(values: Sequence[float] | None, digits: int) -> str:
    """A pair or triple of limits ([upper, lower], [e, m, i]) to ``digits`` decimals, "a / b"; "—" where absent."""
    return "—" if values is None else " / ".join(f"{v:.{digits}f}" for v in values)


def _table(title: str, columns: Sequence[str], rows: Iterable[tuple[str, Sequence[str]]]) -> FittedTable:
    body = [(label, *cells) for label, cells in rows]  # text(): '[mm]' is a unit, not rich markup
    return FittedTable(title, ["quantity", *columns], body, [False] + [True] * len(columns),
                       styles=["cyan"] + [None] * len(columns))


def _quantity_table(title: str, columns: Sequence[str], rows: Iterable[tuple[str, Sequence[str]]]) -> StageColumns:
    return StageColumns(title, list(columns), [(label, list(cells)) for label, cells in rows])
