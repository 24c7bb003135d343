"""Issue 21, field test: `gearcli modes FILE --plots DIR` draws a Campbell diagram worth a design review (speed
to 1.2x nominal, frequency to the highest order there, a log axis for a wide span, crossings marked by how
strongly they are excited, the nominal speed, the margin band); the sweep's Campbell is the same drawing."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli.cli import cli
from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.io.units import OutputUnits
from gearcli.model.assembly import Layout
from gearcli.model.modes import campbell_data
from gearcli.scene import spec_from_design

pytest.importorskip("matplotlib")

ROOT = Path(__file__).resolve().parents[2]
CONVEYOR = str(ROOT / "configs" / "conveyor.toml")
ONE_STAGE = str(ROOT / "configs" / "extreme" / "one_stage.toml")


def _layout(path: str) -> Layout:
    cfg = load_design(path, []).design
    return Layout.of(spec_from_design(cfg, compute_design(cfg)))


def test_campbell_data_of_one_stage_by_hand():
    """21 teeth at 600 rpm: the mesh order 3x reaches 3 x 21 x 720 / 60 = 756 Hz at 1.2 x nominal; the mesh
    order h meets the mode f at 60 f / (21 h) rpm."""
    data = campbell_data(_layout(ONE_STAGE))
    assert data.nominal_input_rpm == pytest.approx(600.0) and data.max_input_rpm == pytest.approx(720.0)
    assert data.top_Hz == pytest.approx(3 * 21 * 720 / 60)
    (mode,) = data.modes
    for c in data.crossings:
        if c.crossing.excitation.startswith("stage 1 mesh"):
            h = int(c.crossing.excitation.split()[-1][0])
            assert c.crossing.input_speed_rpm == pytest.approx(60 * mode.frequency_Hz / (21 * h), rel=1e-12)
            assert c.crossing.input_speed_rpm <= 720.0


def test_conveyor_figure_has_log_axis_nominal_line_margin_bands_and_marked_crossings():
    from gearcli.io.campbell import campbell_figure

    data = campbell_data(_layout(CONVEYOR))
    fig = campbell_figure(data, OutputUnits("rpm", "Nm"), "conveyor")
    ax = fig.axes[0]
    assert ax.get_yscale() == "log"  # 4.9 Hz drum mode to a 1.7 kHz mesh order: three decades
    assert ax.get_xlim() == pytest.approx((0.0, 1.2 * 1480.0))
    assert ax.get_ylim()[1] >= data.top_Hz  # up to the highest order at 1.2 x nominal (1687 Hz)
    assert data.top_Hz == pytest.approx(3 * 19 * 1.2 * 1480 / 60)
    vertical = [ln for ln in ax.get_lines() if len(set(ln.get_xdata())) == 1 and "nominal" in ln.get_label()]
    assert vertical and vertical[0].get_xdata()[0] == pytest.approx(1480.0)
    bands = [p for p in ax.patches]  # one +-10 % band per mode drawn
    assert len(bands) >= 3
    markers = [ln for ln in ax.get_lines() if ln.get_marker() == "o"]
    assert len(markers) == sum(c.frequency_Hz <= ax.get_ylim()[1] for c in data.crossings)
    assert "input speed [rpm]" in ax.get_xlabel()


def test_modes_plots_writes_a_png(tmp_path):
    res = CliRunner().invoke(cli, ["modes", CONVEYOR, "--plots", str(tmp_path / "fig"), "--format", "json"])
    assert res.exit_code == 0, res.output
    png = (tmp_path / "fig" / "campbell.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 20_000


def test_sweep_campbell_is_the_same_drawing(tmp_path, monkeypatch):
    from gearcli.io import campbell

    calls = []
    real = campbell.campbell_figure

    def spy(data, units, title="", swept=None):
        calls.append((data, units, swept))
        return real(data, units, title, swept)

    monkeypatch.setattr(campbell, "campbell_figure", spy)
    out = tmp_path / "s.csv"
    res = CliRunner().invoke(cli, ["sweep", str(ROOT / "configs" / "concrete_mixer.toml"), "--vary",
                                   "input.speed_rpm=300:900:3", "--jobs", "1", "-o", str(out), "--plots",
                                   str(tmp_path / "p")])
    assert res.exit_code == 0, res.output
    assert (tmp_path / "p" / "campbell.png").exists()
    ((data, units, swept),) = calls
    assert swept == pytest.approx([300.0, 600.0, 900.0]) and units.speed == "rpm"
    assert data.max_input_rpm == pytest.approx(900.0)  # the swept range beyond 1.2 x the file's 600 rpm
    assert data.top_Hz == pytest.approx(3 * 21 * 900 / 60)
    assert math.isclose(data.nominal_input_rpm, 600.0)


@pytest.mark.parametrize("path", [CONVEYOR, str(ROOT / "configs" / "industrial_two_stage_rated.toml")])
def test_campbell_legend_hides_no_title(path):
    """Every text of the drawing stays readable: the legend (beside the axes) overlaps neither the figure title nor
    the axes title (the boundary, margin and marker key, wrapped to the axes' width) nor the plotting area. Before,
    a figure legend in the top right corner ran over the end of both titles ("... rated", "... share / 2ζ)")."""
    from gearcli.io.campbell import campbell_figure

    cfg = load_design(path, []).design
    title = str(cfg.title)
    fig = campbell_figure(campbell_data(_layout(path)), OutputUnits("rpm", "Nm"), title)
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    ax = fig.axes[0]
    legend = (ax.get_legend() or fig.legends[0]).get_window_extent(renderer)  # the one legend, wherever it is
    texts = [fig._suptitle, ax.title, ax._left_title]  # the figure title, the centre and the left axes title
    for text in texts:
        if text.get_text():
            box = text.get_window_extent(renderer)
            assert not legend.overlaps(box), text.get_text()
            assert box.x1 <= fig.bbox.x1 + 0.5 and box.x0 >= -0.5, text.get_text()  # inside the picture
    assert legend.x0 >= ax.get_window_extent(renderer).x1  # beside the plotting area, not over the curves
    assert legend.x1 <= fig.bbox.x1 + 0.5
    left = ax._left_title.get_window_extent(renderer)
    assert left.x1 <= ax.get_window_extent(renderer).x1 + 0.5  # the wrapped key fits the axes' width


COINCIDENT = ROOT / "tests" / "field" / "data" / "coincident_orders.toml"


def test_coincident_orders_crossing_a_mode_get_one_label():
    """tr19e: stage 1's mesh 1x (order 20 per input revolution) and stage 2's mesh 3x (3 x 20 / 3 = 20) are one line;
    their crossings with mode 1 were labelled twice, one text printed over the other. The mode by hand: shafts 2
    (J = 0.06) and 3 (J = 0.3) with the input held, transverse mesh stiffness k cos^2 beta_b on base radii
    r_b = z m_n cos(alpha_t) / (2 cos beta)."""
    import numpy as np

    from gearcli.io.campbell import campbell_figure

    path = COINCIDENT
    beta, alpha_n = math.radians(15.0), math.radians(20.0)
    alpha_t = math.atan(math.tan(alpha_n) / math.cos(beta))
    k = 4e8 * (1.0 - (math.sin(beta) * math.cos(alpha_n)) ** 2)  # N/m along the transverse line of action

    def rb(z: int, m: float) -> float:
        return z * m * 1e-3 * math.cos(alpha_t) / (2 * math.cos(beta))

    g1, p2, g2 = rb(60, 3.0), rb(20, 4.0), rb(50, 4.0)
    K = np.array([[k * (g1 ** 2 + p2 ** 2), -k * p2 * g2], [-k * p2 * g2, k * g2 ** 2]])
    f1 = math.sqrt(min(np.linalg.eigvals(np.linalg.solve(np.diag([0.06, 0.3]), K)).real)) / (2 * math.pi)
    data = campbell_data(_layout(str(path)))
    mode1 = min((m for m in data.modes if not m.rigid), key=lambda m: m.frequency_Hz)
    assert mode1.frequency_Hz == pytest.approx(f1, rel=1e-9)  # 489.17 Hz
    on_mode1 = {c.crossing.excitation: c.crossing.input_speed_rpm for c in data.crossings if c.mode == mode1.number}
    for name in ("stage 1 mesh 1x", "stage 2 mesh 3x"):  # 60 f / 20 = 1467.5 rpm, near the nominal 1500
        assert on_mode1[name] == pytest.approx(60 * f1 / 20, rel=1e-9)
    fig = campbell_figure(data, OutputUnits("rpm", "Nm"), "coincident")
    labels = [t.get_text() for t in fig.axes[0].texts if "× mode 1" in t.get_text()]
    assert labels == ["stage 1 mesh 1x, stage 2 mesh 3x × mode 1"]
