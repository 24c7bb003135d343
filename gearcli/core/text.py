"""User text (titles, names, keys) printed literally: never markup, never a control sequence.

A title is data, so every writer passes it through one of these before it reaches a terminal, a
markdown file, a CSV cell or an error message (docs/output.md, "Text fields"):

- :func:`visible` replaces control characters (C0, DEL, C1: ESC, BEL, newline, carriage return ...) and
  the bidirectional overrides with ``\\xNN``/``\\uNNNN`` escapes, so a title cannot move the cursor, ring
  the bell, start an OSC-8 hyperlink, begin a new line that looks like one of gearcli's messages, or
  reorder what is shown.
- :func:`shorten` also caps the length (a 1 MB key name is shown as its start, its end and its length).
- :func:`markdown_inline` also escapes the characters markdown would read as structure.
- :func:`csv_text_cell` neutralises spreadsheet formulas in text (never numeric) CSV cells;
  :func:`sweep_text_cell` also keeps ``#`` and line breaks out of a sweep file's cells.
- :func:`figure` writes a number to a few significant digits without an exponent for whole numbers.
- :func:`beside` writes a number checked against a limit with the digits that keep it on its side of the limit.
Rich markup is avoided at the source: writers hand rich ``Text`` objects, never markup strings.
"""

from __future__ import annotations

import math
import re

_BIDI = "\u061c\u200e\u200f\u202a\u202b\u202c\u202d\u202e\u2066\u2067\u2068\u2069"
_CONTROL = re.compile("[\x00-\x1f\x7f-\x9f" + _BIDI + "\u2028\u2029]")
_NAMED = {"\n": "\\n", "\r": "\\r", "\t": "\\t"}

MAX_SHOWN = 240


def _escape(ch: str) -> str:
    if ch in _NAMED:
        return _NAMED[ch]
    code = ord(ch)
    return f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}"


def visible(text: str) -> str:
    """``text`` with every control and bidi-override character written as an escape."""
    return _CONTROL.sub(lambda m: _escape(m.group()), text)


def shorten(text: str, limit: int = MAX_SHOWN) -> str:
    """:func:`visible`, and at most about ``limit`` characters: ``start…end (N characters)``."""
    if len(text) > limit:
        head, tail = text[: limit * 2 // 3], text[-(limit // 4):]
        return f"{visible(head)}…{visible(tail)} ({len(text)} characters)"
    return visible(text)


_MD_SPECIAL = re.compile(r"([\\`*_{}\[\]<>()#+!|~])")


def markdown_inline(text: str) -> str:
    """``text`` as literal inline markdown: controls escaped (no line break, so no heading or list can
    start), and markdown's structural characters backslash-escaped (no link, emphasis or HTML)."""
    return _MD_SPECIAL.sub(r"\\\1", visible(text))


_FORMULA_START = ("=", "+", "-", "@", "\t", "\r")


def csv_text_cell(text: str) -> str:
    """A text CSV cell a spreadsheet will not run: a leading ``=``, ``+``, ``-`` or ``@`` gets a ``'``
    (the OWASP advice for CSV injection); controls escaped. Numbers are never passed here."""
    shown = visible(text)
    return "'" + shown if text.startswith(_FORMULA_START) else shown


def sweep_text_cell(text: str) -> str:
    """A text cell of a sweep's CSV file: :func:`csv_text_cell` with no ``#`` (``No.``: a reader's comment
    character, ``pandas.read_csv(comment="#")``) and no line break (``; ``). A cell written so is written so again
    (the function is idempotent), so a resume compares a point's text value with the cell written for it by
    passing both through it (gearcli.sweep.spec: a point's ident)."""
    return csv_text_cell(text.replace("#", "No.").replace("\n", "; "))


def figure(x: float, digits: int) -> str:
    """``x`` to ``digits`` significant digits, whole numbers written out (a 100 % share as ``100``, not
    ``1e+02``; a 14389 °/s crossing as ``14389``); small numbers as ``format(x, '.{digits}g')``."""
    if x == 0.0 or not math.isfinite(x) or abs(x) >= 1e9 or math.floor(math.log10(abs(x))) < digits - 1:
        return format(x, f".{digits}g")
    return f"{x:.0f}"


def rounded_up(x: float, digits: int = 3) -> float:
    """``x`` rounded up to ``digits`` significant digits: a bound a warning advises (a window start after which a
    transient has settled, a rating that lasts a life) printed as the user will type it, on the safe side of the
    bound (2.1635 s to 2.17, not 2.16, which the next run finds a hair short)."""
    return _to_digits(x, digits, lambda q: math.ceil(q * (1 - 1e-12)))


def rounded_down(x: float, digits: int = 3) -> float:
    """``x`` rounded down to ``digits`` significant digits: a limit a refusal advises (the longest duration that fits a
    budget) printed as the user will type it, on its safe side (746.6 s to 746, not 747, which the budget refuses)."""
    return _to_digits(x, digits, math.floor)


def _to_digits(x: float, digits: int, rounding) -> float:
    if x <= 0.0 or not math.isfinite(x):
        return x
    step = 10.0 ** (math.floor(math.log10(x)) - digits + 1)
    return float(format(rounding(x / step) * step, f".{digits + 1}g"))


_PRECISION = re.compile(r"\.(\d+)([fg])$")


def beside(x: float, limit: float, spec: str = ".3g") -> str:
    """``x`` as ``format(x, spec)`` (a precision and ``f`` or ``g``, e.g. ``"+.2f"``), with more digits where that
    rounding would put the written number on the limit or across it: a warning's figure is read against the limit it
    names, so b/d1 = 1.5004 beside the limit 1.5 is written ``1.5004``, never "1.5 > 1.5"; a 14.018 teeth undercut
    limit beside z = 14, ``14.02``, never "14 < 14.0"."""
    match = _PRECISION.search(spec)
    if match is None or not math.isfinite(x) or not math.isfinite(limit) or x == limit:
        return format(x, spec)
    head, digits, kind = spec[: match.start()], int(match.group(1)), match.group(2)
    for n in range(digits, 18):
        text = format(x, f"{head}.{n}{kind}")
        if (float(text) > limit) == (x > limit) and float(text) != limit:
            return text
    return repr(x)
