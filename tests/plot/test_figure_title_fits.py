"""A figure's title holds the design file's `title`, which may be long (trial tr27a, 2026-12-01: a 118-character title
on the 11-inch Campbell diagram ran off both edges of the PNG, "ampbell diagram — ... lossy meshe"). It wraps
onto as many lines as keep it inside the figure, every word kept."""

from __future__ import annotations

from pathlib import Path

import pytest

from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.io.units import OutputUnits
from gearcli.model.assembly import Layout
from gearcli.model.modes import campbell_data
from gearcli.scene import spec_from_design

pytest.importorskip("matplotlib")

ROOT = Path(__file__).resolve().parents[2]
LONG = ("a three-stage helical reducer with flexible shafts and couplings, a Kloss motor, a fan load and lossy meshes, "
        "as the trial built it")


def test_a_long_title_stays_inside_the_campbell_figure():
    from gearcli.io.campbell import campbell_figure

    cfg = load_design(str(ROOT / "configs" / "conveyor.toml"), []).design
    data = campbell_data(Layout.of(spec_from_design(cfg, compute_design(cfg))))
    fig = campbell_figure(data, OutputUnits("rpm", "Nm"), LONG)
    fig.canvas.draw()
    title = fig._suptitle
    box = title.get_window_extent(fig.canvas.get_renderer())
    assert 0.0 <= box.x0 and box.x1 <= fig.bbox.width  # inside the PNG's pixels, left and right
    assert title.get_text().split() == f"Campbell diagram — {LONG}".split()  # every word, in order
    assert title.get_text().count("\n") >= 1  # 130 characters at 11 pt do not fit on 11 inches
