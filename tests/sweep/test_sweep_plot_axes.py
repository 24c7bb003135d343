"""The response plot's y axes: a statistic that is constant to roundoff is drawn as the constant it is.

An unexcited scene's sweep rows are its equilibrium (docs/sweeps.md): F_t std 0, DTE rms 0, dynamic factor 1 and
the same mean F_t at every speed, each to the last bits of a double. Before, matplotlib autoscaled those panels to
the roundoff (a "F_t standard deviation" axis of 0 to 9e-13 N, a mean of "1e-9 + 3.715366283e3"), so the seed
speed sweep of docs/sweeps.md drew noise as if it were a response.
"""

from __future__ import annotations

import pytest

pytest.importorskip("matplotlib")

from gearcli.io.sweep_plots import _response  # noqa: E402
from gearcli.sweep.spec import spec_from_options  # noqa: E402

SPEEDS = (300.0, 600.0, 900.0, 1200.0)
F_T = 1851.1  # N, the seed's stage 1 static tangential force
DTE = 12.756  # µm, its static deflection


def _rows(std, mean_jitter):
    spec = spec_from_options([f"input.speed_rpm={','.join(map(str, SPEEDS))}"], [], None, "lhs", None, None)
    rows = []
    for i, p in enumerate(p for branch in spec.branches() for p in branch):
        mean = F_T + mean_jitter[i]
        rows.append({**dict(p.values), "direction": p.direction, "status": "ok",
                     "stage1_tangential_N_mean": mean, "stage1_tangential_N_min": mean,
                     "stage1_tangential_N_max": mean, "stage1_tangential_N_std": std[i],
                     "stage1_dte_um_mean": DTE, "stage1_dte_um_min": DTE, "stage1_dte_um_max": DTE,
                     "stage1_dte_um_rms": 3.6e-15 * (i % 2), "stage1_contact_loss_fraction": 0.0,
                     "stage1_dynamic_factor": 1.0 + 4.4e-16 * i, "stage1_runup_factor": 10.0 - 3.0 * i,
                     "output_speed_rpm": p.values[0][1] / 22.27})
    return spec, rows


def _axis(fig, title):
    return next(ax for ax in fig.axes if ax.get_title() == f"stage 1: {title}")


def test_roundoff_panels_are_drawn_as_constants_at_their_scale():
    # the roundoff of a double at 1851 N is 2.3e-13 N: the std and mean differ by a few ulps from point to point
    spec, rows = _rows(std=[4.5e-13, 9.1e-13, 0.0, 6.8e-13], mean_jitter=[0.0, 2.3e-13, -4.5e-13, 0.0])
    fig = _response(rows, "input.speed_rpm", spec, 1)
    std = _axis(fig, "F_t standard deviation (N)").get_ylim()
    # the std axis spans 5 % of the mean force (92.6 N) above zero: a zero std reads as zero, not as noise
    assert std[0] <= 0.0 <= std[1]
    assert std[1] == pytest.approx(0.05 * F_T, rel=1e-6)  # 5 % of the mean F_t, the std's scale
    mean = _axis(fig, "tangential force F_t (N)").get_ylim()
    assert mean == pytest.approx((0.95 * F_T, 1.05 * F_T), rel=1e-6)  # ±5 % of the force itself
    rms = _axis(fig, "DTE rms (µm)").get_ylim()
    assert rms[1] == pytest.approx(0.05 * DTE, rel=1e-6)  # 5 % of the mean DTE, the rms's scale
    dyn = _axis(fig, "dynamic factor: window max / static F_t (-)").get_ylim()
    assert dyn == pytest.approx((0.95, 1.05), rel=1e-6)  # a factor's scale is 1
    for ax in fig.axes:  # no "1e-9 + 3.715e3" offset or "1e-13" multiplier on any axis
        ax.figure.canvas.draw()
        assert ax.yaxis.get_major_formatter().get_offset() == "", ax.get_title()


def test_a_real_response_keeps_matplotlib_autoscale():
    """A std that varies by hundreds of newtons (a resonance) and a run-up factor of 10 to 1 are data, not
    roundoff: their axes cover the data as matplotlib chose them, not a ±5 % band."""
    spec, rows = _rows(std=[700.0, 430.0, 160.0, 60.0], mean_jitter=[-8.0, -3.0, 1.0, 0.5])
    fig = _response(rows, "input.speed_rpm", spec, 1)
    lo, hi = _axis(fig, "F_t standard deviation (N)").get_ylim()
    assert lo <= 60.0 and hi >= 700.0 and hi < 0.05 * F_T * 10  # autoscaled round the data (60..700 N)
    lo, hi = _axis(fig, "tangential force F_t (N)").get_ylim()
    assert lo <= F_T - 8.0 and hi >= F_T + 1.0 and hi - lo < 0.05 * F_T  # a 9 N spread, not pinned to ±92 N
    lo, hi = _axis(fig, "run-up factor: run peak / static F_t (-)").get_ylim()
    assert lo <= 1.0 and hi >= 10.0


# the random samples' distributions.png: the same rule on its x axes (a tolerance study of an unexcited scene draws
# every sample at its equilibrium, std 0 and dynamic factor 1 to roundoff; before, its histograms and ECDFs spread
# 1e-12 N of std and "1e-6 + 1" of dynamic factor over the whole panel as if they were a distribution)

def _samples(peaks, std, dyn, rms):
    return [{"status": "ok", "stage1_tangential_N_mean": F_T, "stage1_tangential_N_max": p,
             "stage1_tangential_N_std": s, "stage1_dynamic_factor": d, "stage1_dte_um_mean": DTE,
             "stage1_dte_um_rms": r} for p, s, d, r in zip(peaks, std, dyn, rms, strict=True)]


def _panel(fig, xlabel, side):
    axes = [ax for ax in fig.axes if ax.get_xlabel() == xlabel]
    return axes[side]  # 0: the histogram, 1: the ECDF


def test_distributions_draw_roundoff_statistics_as_one_bar_at_their_scale():
    from gearcli.io.sweep_plots import _distributions

    rows = _samples(peaks=[1700.0, 1851.1, 2000.0, 2100.0], std=[4.5e-13, 9.1e-13, 0.0, 1.36e-12],
                    dyn=[1.0, 1.0 + 4.4e-16, 1.0 - 2.2e-16, 1.0], rms=[0.0, 3.6e-15, 1.8e-15, 0.0])
    fig = _distributions(rows, 1)
    for side in (0, 1):
        lo, hi = _panel(fig, "F_t std (N)", side).get_xlim()
        assert lo <= 0.0 <= hi and hi == pytest.approx(0.05 * F_T, rel=1e-6)  # 5 % of the mean F_t
        lo, hi = _panel(fig, "dynamic factor (-)", side).get_xlim()
        assert (lo, hi) == pytest.approx((0.95, 1.05), rel=1e-6)  # a factor's scale is 1
        lo, hi = _panel(fig, "DTE rms (µm)", side).get_xlim()
        assert hi == pytest.approx(0.05 * DTE, rel=1e-6)  # 5 % of the mean DTE
    bars = [p for p in _panel(fig, "F_t std (N)", 0).patches if p.get_height() > 0]
    assert len(bars) == 1 and bars[0].get_height() == 4  # every sample in the one bar at 0
    fig.canvas.draw()
    for ax in fig.axes:
        assert ax.xaxis.get_major_formatter().get_offset() == "", ax.get_xlabel()
    # the peaks vary by hundreds of newtons: data, autoscaled round them
    lo, hi = _panel(fig, "peak F_t in window (N)", 0).get_xlim()
    assert lo <= 1700.0 and hi >= 2100.0 and hi - lo < 0.5 * F_T


def test_a_grids_many_curves_legend_hides_no_panel_title_and_no_data():
    """A speed sweep on a grid of 5 backlash values draws 15 legend entries (5 curves x mean/min/max): inside the
    first 2-inch panel the legend covered its title ("stage 1: tangential force F_t (N)") and its curves. It goes
    below the panels: it overlaps no axes, no axes title and not the figure's title."""
    spec = spec_from_options([f"input.speed_rpm={','.join(map(str, SPEEDS))}",
                              "stage.0.backlash_mm=0.05,0.1,0.15,0.2,0.3"], [], None, "lhs", None, None)
    rows = [{**dict(p.cells()), "direction": p.direction, "status": "ok", "stage1_tangential_N_mean": F_T,
             "stage1_tangential_N_min": F_T - 100.0 * i, "stage1_tangential_N_max": F_T + 100.0 * i,
             "output_speed_rpm": 20.0} for i, p in enumerate(p for branch in spec.branches() for p in branch)]
    fig = _response(rows, spec.axes[0].column, spec, 1)
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    legends = [leg for leg in [*fig.legends, *(ax.get_legend() for ax in fig.axes)] if leg is not None]
    assert len(legends) == 1 and len(legends[0].get_texts()) == 15
    box = legends[0].get_window_extent(renderer)
    for ax in fig.axes:
        if ax.get_visible():
            assert not box.overlaps(ax.get_window_extent(renderer)), ax.get_title()
            assert not box.overlaps(ax.title.get_window_extent(renderer)), ax.get_title()
    assert not box.overlaps(fig._suptitle.get_window_extent(renderer))
    assert fig.bbox.x0 - 0.5 <= box.x0 and box.x1 <= fig.bbox.x1 + 0.5 and box.y0 >= fig.bbox.y0 - 0.5  # inside it


def _grid_figure(axis_values: str, other: str):
    spec = spec_from_options([axis_values, other], [], None, "lhs", None, None)
    rows = [{**dict(p.cells()), "direction": p.direction, "status": "ok", "stage1_tangential_N_mean": F_T + i,
             "stage1_tangential_N_min": F_T - 100.0, "stage1_tangential_N_max": F_T + 100.0 + i,
             "output_speed_rpm": 20.0} for i, p in enumerate(p for branch in spec.branches() for p in branch)]
    return _response(rows, spec.axes[0].column, spec, 1)


def test_a_long_keys_legend_keeps_every_label_inside_the_figure():
    """A one-stage figure is 5.2 inches wide; the legend below it had two columns of labels such as
    "(stage[0].mesh.transmission_error_um.0=2) mean", 6.5 inches together: both columns lost their ends outside
    the figure ("tage[0]...", "...error_um.0=4"). Every legend text lies wholly inside the saved figure."""
    fig = _grid_figure("input.speed_rpm=800,1200,1600", "stage[0].mesh.transmission_error_um.0=0,2,4")
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    (legend,) = fig.legends
    texts = legend.get_texts()
    assert len(texts) == 9 and texts[0].get_text() == "(stage[0].mesh.transmission_error_um.0=0) mean"
    for text in texts:
        box = text.get_window_extent(renderer)
        assert fig.bbox.x0 <= box.x0 and box.x1 <= fig.bbox.x1, text.get_text()
        assert fig.bbox.y0 <= box.y0, text.get_text()


def test_a_grid_of_more_than_ten_curves_gives_each_its_own_colour():
    """An 11 x 2 grid drawn against its second key has 11 curves (one per speed): matplotlib's cycle C0 ... C9 gave
    the 1st (800 rpm) and the 11th (1800 rpm) the same blue, indistinguishable in one panel."""
    from matplotlib.colors import to_rgba

    speeds = ",".join(str(800 + 100 * i) for i in range(11))
    fig = _grid_figure("stage.0.backlash_mm=0.05,0.1", f"input.speed_rpm={speeds}")
    curves = fig.axes[-1].get_lines()  # the output-speed panel: one line per curve
    assert len(curves) == 11
    assert len({to_rgba(line.get_color()) for line in curves}) == 11


def test_a_grids_tolerance_distributions_are_one_per_grid_point():
    """--vary input.speed_rpm=1000,1200 with --samples 4: each speed's four samples are its tolerance distribution.
    Pooled, the two speeds' F_t std (about 311 N and 568 N on tr18c's stage) made one two-humped histogram and an
    ECDF that climbed to 0.5 at the first speed's samples. Each speed has its own ECDF (its samples' i/4 steps to
    1) and histogram (four counts), in its own colour."""
    from matplotlib.colors import to_rgba

    from gearcli.io.sweep_plots import _distributions

    stds = {"1000": [309.0, 311.0, 312.0, 314.0], "1200": [560.0, 566.0, 568.0, 571.0]}
    rows = [{"input.speed_rpm": n, "direction": "none", "status": "ok", "stage1_tangential_N_std": s,
             "stage1_tangential_N_mean": F_T, "stage1_tangential_N_max": F_T + 2 * s,
             "stage1_dynamic_factor": 1 + 2 * s / F_T, "stage1_dte_um_mean": DTE, "stage1_dte_um_rms": s / 690}
            for n, ss in stds.items() for s in ss]
    fig = _distributions(rows, 1, ["input.speed_rpm"])
    ecdfs = _panel(fig, "F_t std (N)", 1).get_lines()
    assert len(ecdfs) == 2 and len({to_rgba(line.get_color()) for line in ecdfs}) == 2
    for line, ss in zip(ecdfs, stds.values(), strict=True):
        # the rise from 0 at the first sample, then i/4 (tests/plot/test_plot_truth_sweep.py: the ECDF's rise)
        assert list(line.get_xdata()) == [ss[0], *ss] and list(line.get_ydata()) == [0.0, 0.25, 0.5, 0.75, 1.0]
    hist = _panel(fig, "F_t std (N)", 0)
    by_colour: dict = {}
    for bar in hist.patches:
        by_colour[to_rgba(bar.get_facecolor())] = by_colour.get(to_rgba(bar.get_facecolor()), 0) + bar.get_height()
    assert sorted(by_colour.values()) == [4, 4]
    legend = _panel(fig, "peak F_t in window (N)", 0).get_legend()  # on the first panel
    assert [t.get_text() for t in legend.get_texts()] == ["input.speed_rpm=1000", "input.speed_rpm=1200"]
    assert "4 random samples at each of 2 grid points" in fig._suptitle.get_text()
