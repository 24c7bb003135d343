"""``gearcli report --format markdown``: a report a person can read, or paste into an issue or a wiki."""

from __future__ import annotations

import gearcli
from gearcli.core.text import markdown_inline, visible
from gearcli.io.report_sections import Section, method_paragraph, sections, solver_lines
from gearcli.report.result import Report


def _escape(cell: str) -> str:
    """A table cell: literal text (controls escaped, so no line break can end the table), pipes escaped."""
    return visible(cell).replace("|", "\\|")


def pipe_table(section: Section) -> str:
    rule = ["---:" if a == "r" else "---" for a in section.align]
    lines = ["| " + " | ".join(_escape(h) for h in section.headers) + " |", "| " + " | ".join(rule) + " |"]
    lines += ["| " + " | ".join(_escape(c) for c in row) + " |" for row in section.rows]
    return "\n".join(lines)


def _section(section: Section, extra: str = "") -> str:
    parts = [f"## {section.title}", ""]
    if extra:
        parts += [extra, ""]
    parts.append(pipe_table(section))
    if section.notes:
        parts += [""] + [f"- {visible(n)}" for n in section.notes]
    return "\n".join(parts) + "\n"


def report_markdown(r: Report, sha256: str = "") -> str:
    head = [f"# gearcli report: {markdown_inline(r.title or 'design')}", ""]
    meta = f"gearcli {gearcli.__version__}" + (f", input sha256 `{sha256[:16]}…`" if sha256 else "")
    head += [meta, ""]
    body = []
    for s in sections(r):
        extra = ""
        if s.title.startswith("Numerical accuracy") and r.accuracy is not None:
            extra = "**Method.** " + method_paragraph(r.accuracy, (float(r.simulation.window_s[0]), float(r.simulation.window_s[1])))
        body.append(_section(s, extra))
    if r.accuracy_failure is not None:
        body.append("## Numerical accuracy\n\n**The accuracy study failed**: " + visible(r.accuracy_failure) +
                    ". The sections above are the file's own run, complete; its solver settings are not checked "
                    "against a reference.\n")
    elif r.accuracy is None:
        body.append("## Numerical accuracy\n\nSkipped (`--quick`).\n")
    body.append("## Solver and energy balance\n\n" + "\n".join(f"- {line}" for line in solver_lines(r)) + "\n")
    warnings = "\n".join(f"- {visible(w)}" for w in r.warnings) if r.warnings else "None."
    body.append(f"## Warnings\n\n{warnings}\n")
    return "\n".join(head) + "\n" + "\n".join(body)
