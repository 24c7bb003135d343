"""The window mean's bias from a partial period of an excitation (`window_partial_period`, gearcli/simulate/sampling.py).

Closed form: the mean of A cos(2 pi f t + phase) over a window of length T holding n = f T periods is
A sin(pi n) cos(2 pi f t_mid + phase) / (pi n), t_mid the window's middle: at most A |sin(pi n)| / (pi n), reached
where the window's middle meets a crest, and 0 for whole periods. The estimator recovers A from the window by
projection and states that bound; the warning fires where the bound exceeds the mean's target (1e-4 of the mean)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli
from gearcli.simulate import sampling
from gearcli.simulate.periodic import Excitation

F = 51.0  # Hz
MEAN = 3000.0  # N


def leak(n: float) -> float:
    return 1.0 / (2 * math.pi * n) + 1.0 / (math.pi * n) ** 2


def _window(n_periods: float, amplitude: float, phase: float = 0.0, samples: int = 20001):
    t = 0.44 + np.linspace(0.0, n_periods / F, samples)
    return t, MEAN + amplitude * np.cos(2 * math.pi * F * t + phase)


@pytest.mark.parametrize("n", [10.3, 10.5, 28.56, 3.25])
def test_the_bound_is_the_closed_form_of_a_sinusoid(n):
    amplitude = 813.0
    t, x = _window(n, amplitude)
    got_amplitude, bound = sampling.partial_period_bias(t, x, F)
    # the projection over a partial period leaks the negative-frequency image, A |sin(2 pi n)| / (2 pi n), and the
    # window mean's own bias (second order): leak(n) of A at most
    assert_allclose(got_amplitude, amplitude, rtol=leak(n))
    assert_allclose(bound, amplitude * abs(math.sin(math.pi * n)) / (math.pi * n), rtol=leak(n))


@pytest.mark.parametrize("n", [10.3, 28.56])
def test_the_window_mean_reaches_the_bound_where_its_middle_meets_a_crest(n):
    amplitude = 813.0
    t0, t1 = 0.44, 0.44 + n / F
    phase = -2 * math.pi * F * 0.5 * (t0 + t1)  # cos(2 pi f t_mid + phase) = 1
    t, x = _window(n, amplitude, phase)
    biased = float(np.trapezoid(x, t)) / float(t[-1] - t[0]) - MEAN
    exact = amplitude * math.sin(math.pi * n) / (math.pi * n)
    assert_allclose(biased, exact, rtol=1e-4)  # the trapezoid rule of 20001 samples against the closed form
    _, bound = sampling.partial_period_bias(t, x, F)
    assert abs(biased) <= bound * (1 + leak(n))


def test_whole_periods_carry_no_bias():
    t, x = _window(10.0, 813.0, phase=0.7)
    assert sampling.partial_period_bias(t, x, F)[1] < 1e-9 * MEAN
    assert abs(float(np.trapezoid(x, t)) / float(t[-1] - t[0]) - MEAN) < 1e-9 * MEAN


def test_the_warning_states_the_bound_and_the_window_of_whole_periods(monkeypatch):
    monkeypatch.setattr(sampling, "excitation_periods", lambda layout: [Excitation("stage 1 mesh", 1.0 / F)])
    t, x = _window(10.5, 50.0)  # bound 50 / (10.5 pi) = 1.516 N: 5e-4 of the mean, beyond 1e-4
    (w,) = sampling.window_period_warnings(None, t, [x], [MEAN])
    assert w.code == "window_partial_period" and w.data["stage"] == 1 and w.data["statistic"] == "mean"
    assert_allclose(w.data["estimated_bias_N"], 50.0 / (10.5 * math.pi), rtol=leak(10.5))
    assert_allclose(w.data["periods"], 10.5, rtol=1e-12)
    assert_allclose(w.data["window_start_s"], t[-1] - 10 / F, rtol=1e-12)  # its last 10 whole periods
    # a response 1e4 x smaller is within the target: no warning; nor without an excitation
    assert not sampling.window_period_warnings(None, t, [MEAN + (x - MEAN) * 1e-4], [MEAN])
    monkeypatch.setattr(sampling, "excitation_periods", lambda layout: [])
    assert not sampling.window_period_warnings(None, t, [x], [MEAN])


def test_an_unloaded_stage_s_bias_is_named_against_its_rms_not_its_mean(monkeypatch):
    # a stage with no static force refers its targets to the rms of its F_t (gearcli.simulate.estimate): the warning
    # said "(x of the mean)" of that rms (a rattling unloaded stage: 0.005 "of the mean" where the mean was 0.68 N
    # and the bound 0.41 N); it names the rms, and a loaded stage's words stay "of the mean"
    monkeypatch.setattr(sampling, "excitation_periods", lambda layout: [Excitation("stage 1 mesh", 1.0 / F)])
    t, x = _window(10.5, 50.0)
    rms = 80.0  # N: the reference the caller gives an unloaded stage
    (w,) = sampling.window_period_warnings(None, t, [x - MEAN], [rms], frozenset({1}))
    bound = 50.0 / (10.5 * math.pi)  # the closed form A |sin(pi n)| / (pi n)
    assert_allclose(w.data["relative_bias"], bound / rms, rtol=leak(10.5))
    assert f"of the rms {rms:.4g} N of the unloaded stage's F_t)" in w.message and "of the mean)" not in w.message
    (loaded,) = sampling.window_period_warnings(None, t, [x], [MEAN])
    assert f"({loaded.data['relative_bias']:.2g} of the mean)" in loaded.message


def test_a_run_warned_moves_its_mean_within_the_bound_when_its_window_holds_whole_periods():
    # configs/backlash_oscillator.toml: a 51 Hz mesh, the window 0.44 .. 1 s holds 28.56 of its periods
    config = Path(__file__).resolve().parents[2] / "configs" / "backlash_oscillator.toml"

    def run(*sets: str) -> dict:
        res = CliRunner().invoke(cli, ["simulate", str(config), "--format", "json", "-q",
                                       "--set", "simulation.error_estimate=false",
                                       *[a for s in sets for a in ("--set", s)]])
        assert res.exit_code == 0, res.output
        return json.loads(res.stdout)

    doc = run()
    (w,) = [w for w in doc["warnings"] if w["code"] == "window_partial_period"]
    assert_allclose(w["periods"], 0.56 * 51, rtol=1e-9)
    assert_allclose(w["window_start_s"], 1.0 - 28 / 51, rtol=1e-9)
    whole = run(f"simulation.window_start_s={w['window_start_s']!r}")
    assert not [x for x in whole["warnings"] if x["code"] == "window_partial_period"]
    moved = abs(doc["summary"]["stages"][0]["tangential_N"]["mean"] - whole["summary"]["stages"][0]["tangential_N"]["mean"])
    assert 1e-4 * 2969 < moved <= w["estimated_bias_N"]


def _settling_scene() -> str:
    """Two lightly loaded stages with 0.02 mm backlash, an 8 um transmission error on stage 1 (its 420 Hz mesh the
    only excitation), 1200 rpm in, 200 N m out, mesh damping ratio 0.02: a 0.1 s run whose window the start-up still
    rings in (window max 1262.4 N on stage 1 against the steady 1247.8 N of a 1 s run's last 0.2 s: 1.6 % of the
    static 935 N). At the default damping ratio 0.05 the window is steady (1249.68 N against 1249.67 N), which the
    settle test took for unsettled while the forced 420 Hz response leaked into its fit of the slow modes."""
    pair = ('{{ normal_module_mm = {m}, normal_pressure_angle_deg = 20, helix_angle_deg = {beta}, backlash_mm = 0.02, '
            'pinion = {{ teeth = {z1}, face_width_mm = {b}, hand = "{h1}" }}, '
            'gear = {{ teeth = {z2}, face_width_mm = {b}, hand = "{h2}" }}{extra} }}')
    stages = [pair.format(m=3, beta=12, z1=21, z2=50, b=40, h1="left", h2="right",
                          extra=", mesh = { transmission_error_um = [8.0] }"),
              pair.format(m=4, beta=10, z1=19, z2=53, b=50, h1="right", h2="left", extra="")]
    return (f'title = "settling"\nstage = [{", ".join(stages)}]\n'
            "input = { speed_rpm = 1200, ramp_s = 0.02 }\nload = { torque_Nm = 200, ramp_s = 0.02 }\n"
            "contact = { damping_ratio = 0.02 }\n"
            "simulation = { duration_s = 0.1, steps = 3000, error_estimate = false }\n")



def test_a_run_repeated_longer_to_settle_names_its_duration_beside_the_window_start(tmp_path):
    # a sweep row's or duty point's run is repeated with a later window (gearcli.simulate.settle): the whole periods
    # its warning suggests end at that longer run's end and start at one of its samples, so the window start alone,
    # on the file's 0.1 s, would hold a partial period again; the suggestion names that run's duration and steps
    # too, and a one-shot run of all three is not warned
    from gearcli import api
    from gearcli.simulate import run_simulation

    path = tmp_path / "settling.toml"
    path.write_text(_settling_scene())
    loaded, design = api.load_and_design(str(path))
    result = run_simulation(loaded.design, design, settle=True, error_estimate=False)
    assert result.steady.settle_runs >= 1 and result.window_s[1] > 0.1 + 1e-9
    warned = [d for d in result.diagnostics if d.code == "window_partial_period"]
    assert warned
    f_mesh = 21 * 1200 / 60.0  # Hz: the stage 1 mesh's transmission error, the scene's only excitation
    for w in warned:
        start, duration, steps = w.data["window_start_s"], w.data["duration_s"], w.data["steps"]
        assert duration == result.window_s[1] and steps == math.ceil(3000 * duration / 0.1)  # the samples scaled
        assert (f"--set simulation.duration_s={duration:.9g} --set simulation.steps={steps} "
                f"--set simulation.window_start_s={start:.9g}: its last") in w.message
        held = (duration - start) * f_mesh
        assert abs(held - round(held)) < 1e-6  # whole periods of the run that warned
        alone = (0.1 - start) * f_mesh  # what the window start alone gives the file's own run
        assert abs(alone - round(alone)) > 0.01
    data = warned[0].data
    res = CliRunner().invoke(cli, ["simulate", str(path), "--format", "json", "-q",
                                   "--set", f"simulation.duration_s={data['duration_s']!r}",
                                   "--set", f"simulation.steps={data['steps']}",
                                   "--set", f"simulation.window_start_s={data['window_start_s']!r}"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    assert not [x for x in doc["warnings"] if x["code"] == "window_partial_period"]
