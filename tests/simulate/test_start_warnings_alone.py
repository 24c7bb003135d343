"""The start's warnings without its summary (``start_summary(summary=False)``, a sweep point's: its row reads no
``summary.start``): the same warnings as the whole summary's, whether the early exit is taken (every run peak within
the threshold of the rigid start's largest force on its grid, a lower bound of the refined peak, or of a speed
drive's force at the grid's last sample, a lower bound of that largest) or not; the bounds' premises; and a sweep
point's result against a full run's."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from gearcli import api
from gearcli.model.assembly import Layout
from gearcli.scene import spec_from_design
from gearcli.simulate import rigid_start, run_simulation
from gearcli.sweep.worker import Scene

ROOT = Path(__file__).resolve().parents[2]
# speed drives (ramped, a load step, a fan law on the load) and drives whose rigid start is integrated: a motor with
# a fan load, a motor on a planetary stage
SPEED = [("concrete_mixer.toml", ()), ("concrete_mixer.toml", ("load.ramp_s=0",)),
         ("concrete_mixer.toml", ("load.speed_exponent=2",))]
CASES = [*SPEED, ("fan_drive.toml", ()), ("mixer_planetary_motor.toml", ())]


def _layout(name: str, sets: tuple[str, ...]) -> Layout:
    loaded = api.load(str(ROOT / "configs" / name), list(sets))
    return Layout.of(spec_from_design(loaded.design, api.design(loaded)))


def _runs(lay: Layout, duration_s: float, amplitude: float) -> tuple[np.ndarray, list[np.ndarray]]:
    """Stage forces of a made-up elastic start: the rigid start's own F_t with a decaying 40 Hz swing of
    ``amplitude`` times it (the run's peak ~ (1 + amplitude) x the rigid one), on a grid other than the rigid's."""
    rigid = rigid_start.integrate(lay, duration_s)
    t = np.linspace(0.0, duration_s, 3001)
    swing = 1.0 + amplitude * np.exp(-t / (0.3 * duration_s)) * np.sin(2 * math.pi * 40.0 * t)
    return t, [np.interp(t, rigid.time_s, f) * swing for f in rigid.tangential_N]


@pytest.mark.parametrize(("name", "sets"), CASES)
@pytest.mark.parametrize("amplitude", [0.0, 0.5, 1.5])
@pytest.mark.parametrize("warn", [1.0, 1.3, 2.0])
def test_the_warnings_alone_are_the_whole_summarys_warnings(name, sets, amplitude, warn):
    lay = _layout(name, sets)
    boundary = "clamped_input" if lay.speed_drive else "free"
    t, forces = _runs(lay, 1.0, amplitude)
    window = (0.6, 1.0)
    whole, want = rigid_start.start_summary(lay, boundary, t, forces, window, warn)
    doc, got = rigid_start.start_summary(lay, boundary, t, forces, window, warn, summary=False)
    assert whole is not None and doc is None
    assert [(d.code, d.message, d.data) for d in got] == [(d.code, d.message, d.data) for d in want]


@pytest.mark.parametrize(("name", "sets"), CASES)
def test_the_grids_largest_force_bounds_the_refined_peak(name, sets):
    lay = _layout(name, sets)
    rigid = rigid_start.integrate(lay, 1.0)
    for grid, peak in zip(rigid.tangential_N, rigid.peak_tangential_N, strict=True):
        assert 0.0 < float(np.max(np.abs(grid))) <= peak


@pytest.mark.parametrize(("name", "rpm"), [("concrete_mixer.toml", 450.0), ("mixer_planetary_motor.toml", None)])
def test_a_sweep_points_result_is_the_full_runs_without_summary_start(name, rpm):
    path = ROOT / "configs" / name
    sets = () if rpm is None else (f"input.speed_rpm={rpm!r}",)
    point = api.evaluate_point(Scene(path.read_bytes(), str(path), (), 3), sets).result
    loaded = api.load(str(path), list(sets))
    design = api.design(loaded)
    full = run_simulation(loaded.design, design, want_series=False, error_estimate=False, settle=True)
    assert "start" not in (point.extra or {}) and "start" in (full.extra or {})
    assert point.warnings == full.warnings
    assert point.stages == full.stages


@pytest.mark.parametrize(("name", "sets"), SPEED)
def test_the_sampled_bound_before_the_grid_takes_only_exits_the_grid_takes(name, sets):
    """The early exit before the grid (:func:`rigid_start._no_warning_at_end`, a speed drive's): its forces at a few
    of the grid's times are the grid's own numbers there, bit for bit (every sample checked), so their largest
    bounds the grid's largest from below and every exit it takes the grid's test takes too."""
    lay = _layout(name, sets)
    duration = 1.7
    rigid = rigid_start.integrate(lay, duration)
    coefficients = rigid_start._coefficients(lay)
    state = rigid_start._speed_state(lay)
    for k, grid in enumerate(rigid.tangential_N):
        force = rigid_start._stage_force(lay, k, coefficients)
        np.testing.assert_array_equal([force(float(tt), *state(float(tt))) for tt in rigid.time_s], grid)
    top = [float(np.max(np.abs(f))) for f in rigid.tangential_N]
    taken = 0
    for scale in (0.5, 1.0, 1.04, 1.5, 1.99, 2.0, 2.5):
        peaks = [scale * t for t in top]
        for warn in (1.0, 1.3, 2.0):
            if rigid_start._no_warning_at_end(lay, duration, peaks, warn):
                taken += 1
                assert rigid_start._no_warning(peaks, rigid.tangential_N, warn)
    assert taken > 0  # the bound is taken where the peaks lie well within the threshold


@pytest.mark.parametrize(("duration", "samples"), [(1.7, rigid_start.SAMPLES), (3.0, 2001), (0.37, 4001), (1e-3, 2),
                                                   (2.5, 7)])
def test_a_grid_time_is_linspaces_own(duration, samples):
    grid = np.linspace(0.0, duration, samples)
    got = [rigid_start._grid_time(i, duration, samples) for i in range(samples)]
    np.testing.assert_array_equal(got, grid)
