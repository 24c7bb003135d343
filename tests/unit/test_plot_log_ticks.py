"""work_precision.png's wall-time axes: tick labels that do not overlap.

The compiled engine's rungs take 1.5-26 ms: an x axis just over a decade on a panel a third of a 12.5 in figure,
where matplotlib labels its minor ticks too ("2x10^-3 3x10^-3 4x10^-3 6x10^-3" ran into each other on the seed's
report). :func:`gearcli.io.plots.log_ticks` labels plain numbers at 1-9, 1-2-5 or 1 per decade by the span.
"""

from __future__ import annotations

import pytest

pytest.importorskip("matplotlib")

from gearcli.io.figures import figure  # noqa: E402
from gearcli.io.plots import log_ticks  # noqa: E402


def _labels(ax):
    ax.figure.canvas.draw()
    renderer = ax.figure.canvas.get_renderer()
    ticks = [t for t in ax.xaxis.get_major_ticks() + ax.xaxis.get_minor_ticks()
             if t.label1.get_visible() and t.label1.get_text()
             and ax.get_xlim()[0] <= t.get_loc() <= ax.get_xlim()[1]]
    return [(t.label1.get_text(), t.label1.get_window_extent(renderer)) for t in ticks]


def _panel(walls):
    fig, axes = figure(1, 3, sharey=True, height=3.9, width=12.5)  # work_precision.png's layout
    ax = axes[0][0]
    ax.loglog(walls, [1e-6 * (i + 1) for i in range(len(walls))], "o-")
    return ax


@pytest.mark.parametrize("walls", [
    [0.00095, 0.0012, 0.0017, 0.0031, 0.0041, 0.0073, 0.013, 0.018, 0.026],  # the seed's compiled ladder
    [0.0021, 0.0024, 0.0029, 0.0033],  # under half a decade
    [0.0004, 0.003, 0.05, 0.9, 7.0],  # four decades (scipy's Radau at 1e-9)
])
def test_wall_time_labels_do_not_overlap(walls):
    ax = _panel(walls)
    log_ticks(ax)
    labels = _labels(ax)
    assert len(labels) >= 2, labels  # the axis is read: at least two labelled values
    for (a, box_a), (b, box_b) in zip(labels, labels[1:], strict=False):
        assert box_a.x1 < box_b.x0, (a, b)  # sorted left to right, with a gap
    for text, _ in labels:
        float(text)  # plain numbers: 0.002, not 2x10^-3


def test_the_premise_matplotlib_alone_overlaps_there():
    """Without log_ticks matplotlib labels the minor ticks of the seed's axis, and they overlap (the defect)."""
    ax = _panel([0.0015, 0.0031, 0.0041, 0.0073, 0.026])
    labels = sorted(_labels(ax), key=lambda lb: lb[1].x0)
    overlaps = [(a, b) for (a, box_a), (b, box_b) in zip(labels, labels[1:], strict=False) if box_a.x1 >= box_b.x0]
    assert overlaps, labels
