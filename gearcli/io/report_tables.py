"""``gearcli report`` as rich tables (a terminal) or their plain-text rendering (``-o x.txt``)."""

from __future__ import annotations

from collections.abc import Iterable

from rich.console import Group, RenderableType
from rich.text import Text

from gearcli.io.report_sections import Section, sections, solver_lines
from gearcli.io.table_kit import FittedTable, text
from gearcli.report.result import Report


def section_table(section: Section) -> RenderableType:
    """A report section as a table whose numbers (the right-aligned columns) are printed whole at any width."""
    ends = [False] * len(section.rows)
    previous = None
    for i, row in enumerate(section.rows):
        if previous is not None and row[0] and row[0] != previous and section.align.startswith("ll"):
            ends[i - 1] = True
        previous = row[0] or previous
    table = FittedTable(section.title, section.headers, section.rows, [a == "r" for a in section.align],
                        justify=["left" if a == "l" else "right" for a in section.align],
                        styles=["cyan" if a == "l" and h in ("quantity", "force") else None
                                for h, a in zip(section.headers, section.align, strict=True)], ends=ends)
    if not section.notes:
        return table
    return Group(table, text_lines(section.notes, "dim"), Text(""))


def report_tables(r: Report) -> list[RenderableType]:
    out: list[RenderableType] = [text(f"gearcli report: {r.title or 'design'}", "bold")]
    out += [section_table(s) for s in sections(r)]
    if r.accuracy_failure is not None:
        out.append(text_lines([f"Numerical accuracy: the study failed: {r.accuracy_failure}"], "red"))
    out.append(text_lines(solver_lines(r)))
    if r.warnings:
        out.append(text_lines(["warnings:", *(f"  - {w}" for w in r.warnings)], "yellow"))
    return out


def text_lines(lines: Iterable[str], style: str = "") -> Text:
    """Lines of literal text (each line's controls escaped, the line breaks kept)."""
    return Text("\n").join(text(line, style) for line in lines)
