"""``gearcli report`` as rich tables (a terminal) or their plain-text rendering (``-o x.txt``)."""

from __future__ import annotations

from rich.console import Group, RenderableType
from rich.table import Table
from rich.text import Text

from gearcli.io.report_sections import Section, sections, solver_lines
from gearcli.io.tables import text
from gearcli.report.result import Report


def section_table(section: Section) -> RenderableType:
    table = Table(title=text(section.title), title_justify="left", header_style="bold")
    for header, align in zip(section.headers, section.align, strict=True):
        table.add_column(text(header), justify="left" if align == "l" else "right", overflow="fold",
                         style="cyan" if align == "l" and header in ("quantity", "force") else None)
    previous = None
    for row in section.rows:
        if previous is not None and row[0] and row[0] != previous and section.align.startswith("ll"):
            table.rows[-1].end_section = True
        table.add_row(*(text(c) for c in row))
        previous = row[0] or previous
    if not section.notes:
        return table
    return Group(table, text_lines(section.notes, "dim"), Text(""))


def report_tables(r: Report) -> list[RenderableType]:
    out: list[RenderableType] = [text(f"gearcli report: {r.title or 'design'}", "bold")]
    out += [section_table(s) for s in sections(r)]
    out.append(text_lines(solver_lines(r)))
    if r.warnings:
        out.append(text_lines(["warnings:", *(f"  - {w}" for w in r.warnings)], "yellow"))
    return out


def text_lines(lines, style: str = "") -> Text:
    """Lines of literal text (each line's controls escaped, the line breaks kept)."""
    return Text("\n").join(text(line, style) for line in lines)
