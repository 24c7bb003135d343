"""The matplotlib Agg canvas every figure module draws on: the figure, its atomic PNG write, the check that the
plot extra is installed.

matplotlib is an optional extra (``pip install 'gearcli[plot]'``), imported only when a figure is drawn; without
it :class:`PlotsUnavailable` says how to install it. The object-oriented API (``Figure`` + ``FigureCanvasAgg``),
never pyplot, so no global backend state is touched. The bottom of ``io``'s figure modules (``plots``,
``campbell``, ``sweep_plots``, ``life_plots`` import it, it imports none of them).
"""

from __future__ import annotations

import io
from pathlib import Path

from gearcli.io.atomic import write_atomic

INSTALL_HINT = "pip install 'gearcli[plot]'  (or: pip install matplotlib)"
DPI = 110


class PlotsUnavailable(ImportError):
    """matplotlib is not installed."""


def figure(rows: int, cols: int = 1, *, height: float = 2.3, width: float = 9.0, width_ratios=None, **kw):
    try:
        from matplotlib.backends.backend_agg import FigureCanvasAgg  # lazy: matplotlib, the optional plot extra
        from matplotlib.figure import Figure  # lazy: matplotlib, the optional plot extra
    except ImportError as exc:
        raise PlotsUnavailable(f"--plots needs matplotlib: {INSTALL_HINT}") from exc
    fig = Figure(figsize=(width, max(3.2, height * rows + 0.8)), dpi=DPI, layout="constrained")
    FigureCanvasAgg(fig)
    axes = fig.subplots(rows, cols, squeeze=False, width_ratios=width_ratios, **kw)
    return fig, axes


def save(fig, path: Path) -> Path:
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=DPI)
    write_atomic(path, buf.getvalue())
    return path


def check() -> None:
    """Fail early (before any directory is made) when matplotlib is missing."""
    try:
        import matplotlib  # noqa: F401  # lazy: matplotlib, the optional plot extra
    except ImportError as exc:
        raise PlotsUnavailable(f"--plots needs matplotlib: {INSTALL_HINT}") from exc
    return None
