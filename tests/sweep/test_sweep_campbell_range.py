"""The sweep's Campbell diagram (`--plots`) spans the swept input speeds (docs/sweeps.md: "the Campbell diagram of
`gearcli modes --plots` over the swept range"), not 0 .. 1.2 x the file's speed.

A sweep of configs/spur_oscillator_te.toml over 2000-2800 rpm (the file runs at 1500 rpm) drew 0-2880 rpm, the
swept points crowded into the right third; one over 300-600 rpm drew 0-1800 rpm, the points in its first third,
and the crossings a user sweeps for were hard to read. The axis is now the swept range, and what it shows is still
the modes' physics: by hand the oscillator's one elastic mode (pinion speed-driven, gear J = 0.0063 kg m² on base
radius r_b = 25 · 3 mm · cos 20° / 2 = 35.24 mm, linear mesh k = 2e5 N/mm) is f_n = √(k r_b² / J) / 2π = 999 Hz, met by
the 25-tooth mesh's 1x order at n = 60 f_n / 25 = 2398 rpm: inside the 2000-2800 rpm axis, and marked there.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SCENE = (ROOT / "configs" / "spur_oscillator_te.toml").read_bytes()


def _figure(vary: str):
    from gearcli.api import design_case
    from gearcli.io.sweep_plots import _campbell
    from gearcli.sweep.modes import sweep_campbell
    from gearcli.sweep.spec import spec_from_options
    from gearcli.sweep.worker import Scene

    spec = spec_from_options((vary,), (), None, "lhs", None, None)
    got = sweep_campbell(spec, Scene(SCENE, "spur.toml"), design_case, lambda cfg: ("rpm", "Nm"))
    assert got is not None
    return got, _campbell(got)


def test_the_campbell_axis_is_the_swept_range_and_the_hand_crossing_is_on_it():
    pytest.importorskip("matplotlib")
    got, fig = _figure("input.speed_rpm=2000:2800:9")
    ax = fig.axes[0]
    assert ax.get_xlim() == pytest.approx((2000.0, 2800.0))
    r_b = 25 * 3.0 * math.cos(math.radians(20.0)) / 2 / 1000  # m
    f_n = math.sqrt(2e8 * r_b**2 / 0.0063) / (2 * math.pi)
    assert f_n == pytest.approx(999.3, abs=0.1)
    (crossing,) = [c for c in got.data.crossings if c.crossing.excitation == "stage 1 mesh 1x"]
    assert crossing.frequency_Hz == pytest.approx(f_n, rel=2e-3)
    assert crossing.crossing.input_speed_rpm == pytest.approx(60 * f_n / 25, rel=2e-3)  # 2398 rpm
    marked = [x for ln in ax.get_lines() if ln.get_marker() == "o" for x in ln.get_xdata()]
    assert any(abs(x - 60 * f_n / 25) < 5 for x in marked)  # the crossing's marker, inside the axis


def test_a_range_below_the_file_speed_is_drawn_alone_without_the_nominal_line():
    pytest.importorskip("matplotlib")
    _, fig = _figure("input.speed_rpm=300:600:4")
    ax = fig.axes[0]
    assert ax.get_xlim() == pytest.approx((300.0, 600.0))
    labels = [ln.get_label() for ln in ax.get_lines()]
    assert not any(lb.startswith("nominal speed") for lb in labels)  # 1500 rpm is off the axis: not in the legend


def test_a_sweep_of_one_speed_keeps_the_modes_range():
    pytest.importorskip("matplotlib")
    _, fig = _figure("input.speed_rpm=1000")
    assert fig.axes[0].get_xlim() == pytest.approx((0.0, 1.2 * 1500.0))
