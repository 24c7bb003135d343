"""``gearcli report`` as rich tables (a terminal) or their plain-text rendering (``-o x.txt``)."""

from __future__ import annotations

from rich.console import Group, RenderableType
from rich.markup import escape
from rich.table import Table
from rich.text import Text

from gearcli.io.report_sections import Section, sections, solver_lines
from gearcli.report.result import Report


def section_table(section: Section) -> RenderableType:
    table = Table(title=escape(section.title), title_justify="left", header_style="bold")
    for header, align in zip(section.headers, section.align):
        table.add_column(escape(header), justify="left" if align == "l" else "right",
                         style="cyan" if align == "l" and header in ("quantity", "force") else None)
    previous = None
    for row in section.rows:
        if previous is not None and row[0] and row[0] != previous and section.align.startswith("ll"):
            table.rows[-1].end_section = True
        table.add_row(*(escape(c) for c in row))
        previous = row[0] or previous
    if not section.notes:
        return table
    return Group(table, Text("\n".join(section.notes), style="dim"), Text(""))


def report_tables(r: Report) -> list[RenderableType]:
    out: list[RenderableType] = [Text(f"gearcli report: {r.title or 'design'}", style="bold")]
    out += [section_table(s) for s in sections(r)]
    out.append(Text("\n".join(solver_lines(r))))
    if r.warnings:
        out.append(Text("warnings:\n" + "\n".join(f"  - {w}" for w in r.warnings), style="yellow"))
    return out
