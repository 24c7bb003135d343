"""Force above the output samples' Nyquist frequency (gearcli.simulate.aliasing): found from the window by its
alias, its amplitude checked against the sinusoid put in and against a run sampled finely enough to resolve it."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_allclose

from gearcli.simulate import aliasing, sampling

FS = 4000.0  # samples a second
T0, T1 = 0.14, 0.5


def _window(components: list[tuple[float, float]], mean: float = 1000.0) -> tuple[np.ndarray, np.ndarray]:
    n = round((T1 - T0) * FS)
    t = T0 + np.arange(n + 1) / FS
    x = mean + sum(a * np.sin(2 * math.pi * f * t + 0.3) for f, a in components)
    return t, x


def test_a_sinusoid_above_nyquist_is_found_with_its_amplitude():
    # 2500 Hz sampled at 4 kHz shows at 1500 Hz with its own amplitude (a sinusoid keeps it when sampled)
    t, x = _window([(625.0, 50.0), (2500.0, 20.0)])
    got = aliasing.found(t, [x], [1000.0], 2000, ([(2500.0, "test line")], [625.0, 1250.0, 1875.0]))[0]
    assert got is not None
    assert_allclose(got["frequency_Hz"], 2500.0, rtol=1e-12)
    assert_allclose(got["alias_Hz"], FS - 2500.0, rtol=1e-12)
    assert_allclose(got["amplitude_N"], 20.0, rtol=1e-3)  # Hann projection: leakage of 625 Hz ~ (1/(875 T))^3
    assert_allclose(got["samples_per_period"], FS / 2500.0, rtol=1e-12)
    # 16 samples a period of 2500 Hz over the file's 0.5 s: 2000 steps x 16 / 1.6 = 20000
    assert got["steps"] == 20000


def test_a_component_below_the_target_is_not_force_the_window_carries():
    t, x = _window([(625.0, 50.0), (2500.0, 0.5 * sampling.TARGET * 1000.0)])
    assert aliasing.found(t, [x], [1000.0], 2000, ([(2500.0, "small")], [625.0])) == [None]


def test_an_alias_on_a_resolved_line_is_not_judged():
    # 3375 Hz aliases to 625 Hz, the resolved fundamental's: the projection cannot tell them apart
    t, x = _window([(625.0, 50.0)])
    assert aliasing.found(t, [x], [1000.0], 2000, ([(3375.0, "on the line")], [625.0])) == [None]


def test_a_locked_step_s_mean_miss_is_within_the_lock_bound():
    """A force stepping between 30 and 60 N (60 N over the first 37 % of each 0.5 ms period: mean 41.1 N by hand),
    sampled 10 times a period in lock with it: the samples see 60 N at 4 of their 10 phases, a trapezoid mean of
    42 N, 0.9 N off, whatever the rate of the samples; half the change over each step, averaged, is 3 N."""
    period, t = 5e-4, np.linspace(0.0, 0.05, 1001)
    force = np.where(np.mod(t / period + 1e-9, 1.0) < 0.37, 60.0, 30.0)
    mean = float(np.sum(0.5 * (force[1:] + force[:-1]) * np.diff(t))) / 0.05
    miss = abs(mean - (30.0 + 30.0 * 0.37))
    assert miss > 0.5  # the lock's miss: no sample between 0.3 and 0.37 of a period, ever
    assert miss <= aliasing.locked_bias_N(t, force) == pytest.approx(3.0, rel=1e-2)


def test_the_alias_folds_into_the_first_nyquist_band():
    assert_allclose(aliasing.alias_Hz(2500.0, FS), 1500.0, rtol=1e-12)
    assert_allclose(aliasing.alias_Hz(5100.0, FS), 1100.0, rtol=1e-12)
    assert_allclose(aliasing.alias_Hz(7500.0, FS), 500.0, rtol=1e-12)


ROOT = Path(__file__).resolve().parents[2]
#: configs/spur_oscillator_te.toml made a lightly damped TE-excited 2-DOF chain (the gear, and a driven machine on a
#: coupling) whose 4th TE harmonic (2500 Hz) drives its 2670 Hz mesh mode; 2000 steps over 0.5 s sample it 1.6 times
#: a period
CHAIN = ["stage[0].gear.inertia_kg_m2=0.0009", "stage[0].backlash_mm=0", "contact.damping_ratio=0.005",
         "contact.transmission_error_um=[5.0, 0.0, 0.0, 1.0]", "input.ramp_s=0.05", "load.torque_Nm=70",
         "load.ramp_s=0.05", "load.inertia_kg_m2=0.02", "load.coupling_stiffness_Nm_rad=5000",
         "load.coupling_damping_Nms_rad=2", "simulation.duration_s=0.5", "simulation.error_estimate=false"]


@pytest.fixture(scope="module")
def runs():
    from gearcli import api
    from gearcli.simulate import run_simulation

    out = {}
    for steps in (2000, 40000):
        loaded = api.load(str(ROOT / "configs" / "spur_oscillator_te.toml"), [*CHAIN, f"simulation.steps={steps}"])
        out[steps] = run_simulation(loaded.design, api.design(loaded))
    return out


def test_the_scene_at_2000_steps_is_flagged_against_a_resolved_run(runs):
    coarse, fine = runs[2000], runs[40000]
    se = coarse.stages[0].sampling_error
    assert se is not None and se.aliased is not None and not se.resolved
    assert_allclose(se.aliased["frequency_Hz"], 4 * 25 * 1500 / 60, rtol=1e-9)  # the TE's 4th mesh harmonic
    # the reference: the 2500 Hz amplitude of the run sampled 16 times a period (resolved), Hann-projected
    tw = fine.time_s[fine.time_s >= fine.window_s[0]]
    ft = np.asarray(next(v for k, v in fine.series.items() if k.quantity == "tangential_force"))[-tw.size:]
    w = 0.5 - 0.5 * np.cos(2 * math.pi * (tw - tw[0]) / (tw[-1] - tw[0]))
    reference = aliasing.amplitude(tw, ft - np.sum(w * ft) / np.sum(w), w, 2500.0)
    assert_allclose(se.aliased["amplitude_N"], reference, rtol=1e-2)
    # what the coarse samples miss of the max is beyond the interpolation's figure: no bound was claimed
    miss = fine.stages[0].tangential_N.max - coarse.stages[0].tangential_N.max
    assert miss > se.max_N
    codes = [(d.code, d.data.get("aliased_Hz")) for d in coarse.diagnostics]
    assert ("statistics_undersampled", se.aliased["frequency_Hz"]) in codes
    assert ("peak_undersampled", se.aliased["frequency_Hz"]) in codes
    fine_se = fine.stages[0].sampling_error
    assert fine_se is not None and fine_se.aliased is None


def test_a_high_harmonic_in_a_modes_band_is_a_candidate():
    """The chain at 1090 rpm (mesh 454.2 Hz) with a 6th TE harmonic: 2725 Hz, within the 2670 Hz mode's band,
    beyond the first 4 harmonics. 2000 steps (1.5 samples a period) flag it; the amplitude measured at its alias
    against the 40,000-step run's projection at 2725 Hz."""
    from gearcli import api
    from gearcli.simulate import run_simulation

    sets = [*CHAIN, "input.speed_rpm=1090", "contact.transmission_error_um=[5.0, 0.0, 0.0, 0.0, 0.0, 0.3]"]
    got = {}
    for steps in (2000, 40000):
        loaded = api.load(str(ROOT / "configs" / "spur_oscillator_te.toml"), [*sets, f"simulation.steps={steps}"])
        got[steps] = run_simulation(loaded.design, api.design(loaded))
    se, fine = got[2000].stages[0].sampling_error, got[40000]
    assert se is not None and se.aliased is not None
    assert_allclose(se.aliased["frequency_Hz"], 6 * 25 * 1090 / 60, rtol=1e-9)
    tw = fine.time_s[fine.time_s >= fine.window_s[0]]
    ft = np.asarray(next(v for k, v in fine.series.items() if k.quantity == "tangential_force"))[-tw.size:]
    w = 0.5 - 0.5 * np.cos(2 * math.pi * (tw - tw[0]) / (tw[-1] - tw[0]))
    assert_allclose(se.aliased["amplitude_N"], aliasing.amplitude(tw, ft - np.sum(w * ft) / np.sum(w), w, 6 * 25 * 1090 / 60),
                    rtol=1e-2)
    assert fine.stages[0].sampling_error.aliased is None
