"""sweep --plots: a point that failed has no statistics, but its key value is marked (trial tr29c, 2026-12-01). A sweep
over the pinion's teeth 4, 19 and 21 whose teeth = 4 failed (the schema's minimum is 5) drew every panel over 19-21
alone, as if 4 had never been asked; now each panel carries a × at its foot at every failed point's value, the axis
spans them, and the title counts them."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

pytest.importorskip("matplotlib")

from gearcli.io.sweep_plots import _response  # noqa: E402

KEY = "stage.0.pinion.teeth"


def _ok(teeth: int, speed: float) -> dict:
    return {KEY: teeth, "direction": "none", "status": "ok", "stage1_tangential_N_mean": 4000.0 * 21 / teeth,
            "stage1_tangential_N_min": 3900.0, "stage1_tangential_N_max": 4100.0, "stage1_tangential_N_std": 50.0,
            "stage1_dynamic_factor": 1.03, "output_speed_rpm": speed}


def test_failed_points_are_marked_on_every_panel_at_their_key_values():
    ok = [_ok(19, 340.0), _ok(21, 376.1)]
    failed = [{KEY: v, "direction": "none", "status": "failed", "message": f"stage[0].pinion.teeth: must be ≥ 5, got {v}"}
              for v in (4, 3)] + [{KEY: "fast", "direction": "none", "status": "failed", "message": "not a number"}]
    fig = _response(ok, KEY, SimpleNamespace(columns=[KEY]), 1, failed)
    fig.canvas.draw()
    panels = [ax for ax in fig.axes if ax.get_visible()]
    assert len(panels) == 4  # F_t, its std, the dynamic factor, the output speed
    for ax in panels:
        marks = [line for line in ax.get_lines() if line.get_marker() == "x"]
        assert len(marks) == 1, ax.get_title()
        assert sorted(marks[0].get_xdata()) == [3, 4]  # the failed rows' teeth; "fast" is no value on the axis
        assert list(marks[0].get_ydata()) == [0.0, 0.0]  # at the panel's foot, in axes fraction
        lo, hi = ax.get_xlim()
        assert lo <= 3 and hi >= 21, ax.get_title()
        data = [line for line in ax.get_lines() if line.get_marker() != "x"]
        assert all(set(line.get_xdata()) == {19, 21} for line in data)  # the curves: the ok points only
    assert "failed point" in [t.get_text() for t in panels[0].get_legend().get_texts()]
    title = fig._suptitle  # wrapped to the figure's width, every word kept
    assert title.get_text().split() == f"sweep response against {KEY} (× on the axis: 2 failed points)".split()
    box = title.get_window_extent(fig.canvas.get_renderer())
    assert 0.0 <= box.x0 and box.x1 <= fig.bbox.width


def test_a_sweep_without_failed_points_draws_no_marks():
    fig = _response([_ok(19, 340.0), _ok(21, 376.1)], KEY, SimpleNamespace(columns=[KEY]), 1, [])
    assert not [line for ax in fig.axes for line in ax.get_lines() if line.get_marker() == "x"]
    assert fig._suptitle.get_text() == f"sweep response against {KEY}"


def test_the_distributions_title_counts_the_samples_that_failed():
    """--samples 5 of which 2 failed: three samples drawn (the histogram's bars hold 3), the title says 3 drawn and
    2 failed, not drawn."""
    from gearcli.io.sweep_plots import _distributions

    rows = [{"status": "ok", "direction": "none", "stage1_tangential_N_max": v, "stage1_tangential_N_std": 0.1 * v}
            for v in (4010.0, 4100.0, 4250.0)]
    fig = _distributions(rows, 1, [], failed=2)
    hist = next(ax for ax in fig.axes if ax.get_xlabel() == "peak F_t in window (N)" and ax.patches)
    assert sum(bar.get_height() for bar in hist.patches) == 3
    assert fig._suptitle.get_text().split() == "distributions over 3 random samples (2 failed, not drawn)".split()
    assert _distributions(rows, 1, [])._suptitle.get_text() == "distributions over 3 random samples"


def test_a_long_keys_title_stays_inside_a_one_stage_figure():
    """The response figure of one stage is 5.2 in wide; "sweep response against stage.0.mesh.transmission_error_phase_deg.0"
    at 11 pt is wider and ran off both edges of the PNG; it wraps, every word kept."""
    key = "stage.0.mesh.transmission_error_phase_deg.0"
    rows = [{**_ok(21, 376.1), key: v} for v in (0.0, 90.0)]
    fig = _response(rows, key, SimpleNamespace(columns=[key]), 1)
    fig.canvas.draw()
    title = fig._suptitle
    box = title.get_window_extent(fig.canvas.get_renderer())
    assert 0.0 <= box.x0 and box.x1 <= fig.bbox.width
    assert title.get_text().split() == f"sweep response against {key}".split()
