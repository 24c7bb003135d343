"""modes --plots: the Campbell diagram's lines are the orders and modes they say they are.

Read back from the figure ``gearcli modes --plots`` draws (its artists): each order line's slope is k z n / 60 per
input rpm, written here from the teeth (stage 1: z = 23 on the input; stage 2: z = 19 on shaft 2, which turns at
23/67 of the input), each mode line lies at the JSON's frequency, each crossing marker at f / (order's Hz per rpm)
and the speed axis is in the design file's unit (DESIGN §12: °/s for a ``speed_deg_s`` file, six times the rpm).
A crossing's label near the right edge ran out of the axes into the legend; every label lies inside the axes.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

pytest.importorskip("matplotlib")

from gearcli.cli import cli  # noqa: E402

SCENE = Path(__file__).parent / "data" / "two_stage_duty.toml"
I1 = 67 / 23  # stage 1 ratio
HZ_PER_RPM = {f"stage 1 mesh {k}x": k * 23 / 60 for k in (1, 2, 3)}
HZ_PER_RPM |= {f"stage 2 mesh {k}x": k * 19 / I1 / 60 for k in (1, 2, 3)}
HZ_PER_RPM |= {"shaft 1 1x": 1 / 60, "shaft 2 1x": 1 / I1 / 60, "shaft 3 1x": 1 / I1 / (61 / 19) / 60}


def _modes(path: Path, tmp_path: Path, monkeypatch):
    """``gearcli modes --format json --plots``: its JSON and the Campbell figure it saved."""
    from gearcli.io import campbell

    figs = []
    real = campbell._save
    monkeypatch.setattr(campbell, "_save", lambda fig, p: figs.append(fig) or real(fig, p))
    res = CliRunner().invoke(cli, ["modes", str(path), "--format", "json", "-q", "--plots", str(tmp_path / "p")])
    assert res.exit_code == 0, res.output
    assert sorted(p.name for p in (tmp_path / "p").iterdir()) == ["campbell.png"]
    (fig,) = figs
    return json.loads(res.stdout), fig


@pytest.mark.parametrize(("unit", "per_rpm"), [("rpm", 1.0), ("deg_s", 6.0)])
def test_order_lines_modes_and_crossings_against_the_teeth_and_the_json(tmp_path, monkeypatch, unit, per_rpm):
    path = tmp_path / "scene.toml"
    text = SCENE.read_text(encoding="utf-8")
    path.write_text(text if unit == "rpm" else text.replace("speed_rpm = 1200\nramp_s", "speed_deg_s = 7200\nramp_s"),
                    encoding="utf-8")
    doc, fig = _modes(path, tmp_path, monkeypatch)
    ax = fig.axes[0]
    assert ax.get_xlabel() == ("input speed [rpm]" if unit == "rpm" else "input speed [°/s]")
    lines = {ln.get_label(): ln for ln in ax.get_lines()}
    for name, slope in HZ_PER_RPM.items():
        x, y = (np.asarray(v, float) for v in lines[name].get_data())
        assert x[0] == 0.0 and y[0] == 0.0
        assert y[1:] / (x[1:] / per_rpm) == pytest.approx(slope, rel=1e-9), name  # f = k z n / 60
    clamped = [m for m in doc["boundaries"]["clamped_input"] if not m["rigid"]]
    frequencies = [m["frequency_Hz"] for m in clamped]
    horizontals = sorted(float(ln.get_ydata()[0]) for ln in ax.get_lines()
                         if len(ln.get_ydata()) == 2 and ln.get_ydata()[0] == ln.get_ydata()[1] and ln.get_ydata()[0] > 0)
    assert horizontals == pytest.approx(sorted(frequencies), rel=1e-12)
    nominal = lines[f"nominal speed {1200 * per_rpm:.5g} {'rpm' if unit == 'rpm' else '°/s'}"]
    assert list(nominal.get_xdata()) == pytest.approx([1200 * per_rpm] * 2)
    markers = [(float(ln.get_xdata()[0]), float(ln.get_ydata()[0])) for ln in ax.get_lines()
               if ln.get_marker() == "o"]
    expected = [(f / HZ_PER_RPM[c["excitation"]] * per_rpm, f) for m in clamped
                for f in [m["frequency_Hz"]] for c in m["crossings"]
                if c["source"] == "mesh" and c["input_speed_rpm"] is not None and f / HZ_PER_RPM[c["excitation"]] <= 1440]
    assert len(expected) >= 3  # mode 1 on stage 1's 2x and 3x, mode 2 on its 3x (1315 rpm, the label at the edge)
    assert np.array(sorted(markers)) == pytest.approx(np.array(sorted(expected)), rel=1e-9)
    fig.canvas.draw()
    box = ax.get_window_extent()
    for text in ax.texts:
        extent = text.get_window_extent()
        assert box.x0 - 1 <= extent.x0 and extent.x1 <= box.x1 + 1, text.get_text()


PLANETARY = Path(__file__).parent / "data" / "planetary_sun_input.toml"


@pytest.mark.parametrize(("member", "speeds", "mesh_Hz"), [
    ("sun", (1200.0, 1500.0), lambda n: 72 * n * 24 / 96 / 60),  # carrier at n 24/96, ring teeth x carrier speed
    ("carrier", (250.0, 300.0), lambda n: 72 * n / 60),
])
def test_a_planetary_sweeps_campbell_marks_the_input_speeds(tmp_path, member, speeds, mesh_Hz):
    """A planetary first stage's "pinion" is its sun, whose speed in the design is the mesh's, relative to the
    carrier (1125 rpm of a sun driven at 1500): the sweep's Campbell diagram marked the swept speeds there and
    ran its axis to them. The marks are the swept input speeds; the mesh frequencies ring teeth x carrier rpm / 60."""
    from gearcli.api import design_case
    from gearcli.io.sweep_plots import _campbell
    from gearcli.sweep.modes import campbell, sweep_campbell
    from gearcli.sweep.spec import spec_from_options
    from gearcli.sweep.worker import Scene

    text = PLANETARY.read_text(encoding="utf-8").replace('input = "sun"', f'input = "{member}"')
    text = text.replace("speed_rpm = 1500", f"speed_rpm = {speeds[-1]:g}")
    scene = Scene(text.encode(), "planetary.toml")
    key = "input.speed_rpm"
    points = campbell(scene, key, list(speeds), design_case)
    assert [p.input_rpm for p in points] == pytest.approx(list(speeds), rel=1e-12)
    assert [p.mesh_Hz[0] for p in points] == pytest.approx([mesh_Hz(n) for n in speeds], rel=1e-9)
    spec = spec_from_options([f"{key}={','.join(f'{n:g}' for n in speeds)}"], (), None, "lhs", None, None)
    got = sweep_campbell(spec, scene, design_case, lambda cfg: ("rpm", "Nm"))
    assert got.swept_rpm == pytest.approx(speeds, rel=1e-12)
    assert got.data.nominal_input_rpm == pytest.approx(speeds[-1], rel=1e-12)
    assert got.data.max_input_rpm == pytest.approx(speeds[-1], rel=1e-12)  # the range: the swept one (docs/sweeps.md)
    ax = _campbell(got).axes[0]
    (marks,) = [ln for ln in ax.get_lines() if ln.get_label() == "swept points"]
    assert list(marks.get_xdata()) == pytest.approx(list(speeds), rel=1e-12)
    assert ax.get_xlim() == pytest.approx(speeds, rel=1e-12)
