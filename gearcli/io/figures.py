"""The matplotlib Agg canvas every figure module draws on: the figure, its atomic PNG write, the check that the
plot extra is installed.

matplotlib is an optional extra (``pip install 'gearcli[plot]'``), imported only when a figure is drawn; without
it :class:`PlotsUnavailable` says how to install it. The object-oriented API (``Figure`` + ``FigureCanvasAgg``),
never pyplot, so no global backend state is touched. The bottom of ``io``'s figure modules (``plots``,
``campbell``, ``sweep_plots``, ``life_plots`` import it, it imports none of them).
"""

from __future__ import annotations

import io
import os
import sys
import textwrap
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Literal

from gearcli.io.atomic import write_atomic

if TYPE_CHECKING:  # matplotlib and numpy are imported when a figure is drawn
    import numpy as np
    from matplotlib.figure import Figure

INSTALL_HINT = "pip install 'gearcli[plot]'  (or: pip install matplotlib)"
DPI = 110
Shared = Literal["none", "all", "row", "col"] | bool  # matplotlib's sharex, sharey


class PlotsUnavailable(ImportError):
    """matplotlib is not installed."""


def figure(rows: int, cols: int = 1, *, height: float = 2.3, width: float = 9.0,
           width_ratios: Sequence[float] | None = None, sharex: Shared = False,
           sharey: Shared = False) -> tuple[Figure, np.ndarray]:
    """A figure on the Agg canvas and its ``rows`` x ``cols`` axes (``sharex``, ``sharey`` as
    ``Figure.subplots`` takes them)."""
    _import_matplotlib()
    from matplotlib.backends.backend_agg import FigureCanvasAgg  # lazy: matplotlib, the optional plot extra
    from matplotlib.figure import Figure  # lazy: matplotlib, the optional plot extra
    fig = Figure(figsize=(width, max(3.2, height * rows + 0.8)), dpi=DPI, layout="constrained")
    FigureCanvasAgg(fig)
    axes = fig.subplots(rows, cols, squeeze=False, width_ratios=width_ratios, sharex=sharex, sharey=sharey)
    return fig, axes


def suptitle(fig: Figure, text: str, fontsize: float = 11) -> None:
    """The figure's title, wrapped onto as many lines as keep it inside the figure: it may hold the design file's
    ``title``, of any length (a long one ran off both edges of the PNG), and any characters: it is drawn as it is
    written, never as mathtext (a title "costs $12 and $3" lost its dollars to italics, and "$\\frac{1}{$" ended the
    command with an internal error)."""
    title = fig.suptitle(text, fontsize=fontsize, parse_math=False)
    renderer = fig.canvas.get_renderer()  # type: ignore[attr-defined]  # the Agg canvas (:func:`figure`)
    room = 0.97 * fig.bbox.width
    chars = len(text)
    while chars > 20 and title.get_window_extent(renderer).width > room:
        chars = min(chars - 1, int(chars * room / title.get_window_extent(renderer).width))
        title.set_text("\n".join(textwrap.wrap(text, chars)))


def save(fig: Figure, path: Path) -> Path:
    """The figure as a PNG at ``path``, written atomically."""
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=DPI)
    write_atomic(path, buf.getvalue())
    return path


def check() -> None:
    """Fail early (before any directory is made) when matplotlib is missing."""
    _import_matplotlib()


def _import_matplotlib() -> None:
    """Import matplotlib, or say how to install it. ``MPLBACKEND`` is set aside while it is first imported: gearcli
    draws on the Agg canvas itself and never selects a backend, but matplotlib validates the variable on import, and
    a value it does not know (a typo, a backend of another installation) made every ``--plots`` an internal error."""
    saved = None if "matplotlib" in sys.modules else os.environ.pop("MPLBACKEND", None)
    try:
        import matplotlib  # noqa: F401  # lazy: matplotlib, the optional plot extra
    except ImportError as exc:
        raise PlotsUnavailable(f"--plots needs matplotlib: {INSTALL_HINT}") from exc
    finally:
        if saved is not None:
            os.environ["MPLBACKEND"] = saved
