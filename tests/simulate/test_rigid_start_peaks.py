"""The rigid start's peak search on floats (:func:`gearcli.simulate.rigid_start._stage_force`, the scalar state of
a speed drive) against the array reference it replaces (:func:`rigid_start._tangential`, which every other user of
the rigid start keeps), and the refined peak against an independent brute-force search on a fine grid."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from gearcli import api
from gearcli.model.assembly import Layout
from gearcli.model.step import ramp_rates
from gearcli.scene import spec_from_design
from gearcli.simulate import rigid_start

ROOT = Path(__file__).resolve().parents[2]
# a speed drive with ramps (the seed), a load law (fan: speed squared), a planetary stage's planet meshes with a
# motor and a load proportional to speed, a load applied as a step (ramp_s = 0)
CASES = [("concrete_mixer.toml", ()), ("fan_drive.toml", ()), ("mixer_planetary_motor.toml", ()),
         ("concrete_mixer.toml", ("load.ramp_s=0",))]


def _layout(name: str, sets: tuple[str, ...]) -> Layout:
    loaded = api.load(str(ROOT / "configs" / name), list(sets))
    return Layout.of(spec_from_design(loaded.design, api.design(loaded)))


@pytest.mark.parametrize(("name", "sets"), CASES)
def test_the_stage_force_on_floats_is_the_array_reference_bit_for_bit(name, sets):
    lay = _layout(name, sets)
    coefficients = rigid_start._coefficients(lay)
    rng = np.random.default_rng(7)
    # states across and beyond the ramps, both signs of speed and acceleration, t = 0 exactly
    t = np.concatenate(([0.0], rng.uniform(0.0, 3.0, 200)))
    w = rng.normal(0.0, 150.0, t.size)
    a = rng.normal(0.0, 2000.0, t.size)
    ref = rigid_start._tangential(lay, t, w, a, coefficients)[2]
    for k in range(len(lay.stage_conn)):
        force = rigid_start._stage_force(lay, k, coefficients)
        got = np.array([force(float(tt), float(ww), float(aa)) for tt, ww, aa in zip(t, w, a, strict=True)])
        # the same operations in the same order: equal, not close (the JSON prints every digit of the peak)
        np.testing.assert_array_equal(got, ref[k])


def _brute_force_peaks(lay: Layout, duration_s: float) -> list[float]:
    """max |F_t| per stage of a speed drive's rigid start on a grid 50x finer than the tool's, by the array
    reference: the drive's speed and acceleration are the ramp's, exact (gearcli.model.step.ramp_rates)."""
    t = np.linspace(0.0, duration_s, 50 * (rigid_start.SAMPLES - 1) + 1)
    w, a = ramp_rates(t, lay.drive.ramp_s, lay.drive.speed_rad_s)
    ft = rigid_start._tangential(lay, t, w * np.ones_like(t), a * np.ones_like(t), rigid_start._coefficients(lay))[2]
    return [float(np.max(np.abs(f))) for f in ft]


@pytest.mark.parametrize("sets", [(), ("input.ramp_s=0.05", "load.ramp_s=0.3"), ("load.ramp_s=0",)])
def test_the_refined_peak_of_a_speed_drive_is_the_fine_grid_s(sets):
    lay = _layout("concrete_mixer.toml", sets)
    assert lay.speed_drive
    rigid = rigid_start.integrate(lay, 1.0)
    fine = _brute_force_peaks(lay, 1.0)
    grid = [float(np.max(np.abs(f))) for f in rigid.tangential_N]
    for peak, brute, coarse in zip(rigid.peak_tangential_N, fine, grid, strict=True):
        assert peak >= coarse  # the refinement never lowers the grid's peak
        # a smooth maximum: the fine grid's spacing (1e-5 s) leaves it below the continuous peak by a few 1e-9
        # relative (F'' dt^2 / 8), the refinement's tolerance (1e-12 s) by nothing visible
        assert peak >= brute * (1 - 1e-12)
        assert peak <= brute * (1 + 1e-7)
