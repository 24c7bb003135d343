"""``steady = "periodic"`` on a start that no ramp bounds: the run-up is sampled, so its figures are the run's.

The periodic search starts where the ramps end. Without ramps (a step of the load at t = 0) or with a motor (whose
start lasts until it reaches its operating point) that was t = 0: nothing of the start was sampled, the output jumped
from t = 0 to the found period, and the whole-run figures came from that period alone: a load step on a linear mesh
gave runup_factor 1.000 (the damped oscillator's step response peaks at 1.859x), and a motor's direct start gave
start_time_s 0.221 s, interpolated across the 0.28 s gap (the start takes 0.166 s) and peak_over_rigid 0.50. The
run-up now lasts to the fixed window's default start (a motor's to at least 1.25x its rigid start), sampled as a
window run samples it.
"""

from __future__ import annotations

import json
import math
from types import SimpleNamespace

import numpy as np
import pytest
import tomli_w
from click.testing import CliRunner

from gearcli.cli import cli
from gearcli.simulate.periodic import run_up_end


def _pair(module_mm: float, teeth: tuple[int, int], gear_inertia_kg_m2: float) -> dict:
    """A spur pair of face width 30 mm whose gear has the given inertia."""
    return {"normal_module_mm": module_mm,
            "pinion": {"teeth": teeth[0], "face_width_mm": 30, "hand": "spur"},
            "gear": {"teeth": teeth[1], "face_width_mm": 30, "hand": "spur", "inertia_kg_m2": gear_inertia_kg_m2}}


def _step(zeta: float, steady: str) -> dict:
    """A load step of 200 N·m at t = 0 on a linear spur mesh (the pinion at a prescribed 600 rpm)."""
    return {"title": "step load on a linear spur mesh", "stage": [_pair(3, (24, 48), 0.2)],
            "contact": {"stiffness": 2e5, "exponent": 1, "damping_ratio": zeta},
            "input": {"speed_rpm": 600}, "load": {"torque_Nm": 200},
            "simulation": {"duration_s": 0.2, "steps": 8000, "steady": steady}}


def _motor(steady: str) -> dict:
    """A table motor (100 N·m flat to 1400 rpm, then linear to 0 at 1500 rpm), started direct on a 20/60 spur pair
    whose gear has 0.5 kg·m², against 150 N·m."""
    return {"title": "table motor, direct start", "stage": [_pair(2, (20, 60), 0.5)],
            "input": {"speed_rpm": 1450, "drive": "motor",
                      "motor": {"torque_speed": [[0, 100], [1400, 100], [1500, 0]]}},
            "load": {"torque_Nm": 150}, "simulation": {"duration_s": 1.0, "steps": 10000, "steady": steady}}


def _summary(tmp_path, doc: dict) -> dict:
    path = tmp_path / "scene.toml"
    path.write_text(tomli_w.dumps(doc))
    res = CliRunner().invoke(cli, ["simulate", str(path), "--format", "json"])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)["summary"]


def _step_peak_over_static(zeta: float) -> float:
    """The damped oscillator m x'' + c x' + k x = F H(t) from rest: the largest spring-and-damper force k x + c x'
    over F (closed form, sampled finely over the first period)."""
    wd = math.sqrt(1.0 - zeta * zeta)
    t = np.linspace(0.0, 2.0 * math.pi / wd, 200001)
    decay = np.exp(-zeta * t)
    x = 1.0 - decay * (np.cos(wd * t) + zeta / wd * np.sin(wd * t))
    v = decay / wd * np.sin(wd * t)
    return float(np.max(x + 2.0 * zeta * v))


@pytest.mark.parametrize("zeta", [0.05, 0.2])
def test_a_load_step_peaks_as_the_damped_oscillator(tmp_path, zeta):
    s = _summary(tmp_path, _step(zeta, "periodic"))
    st = s["stages"][0]
    expected = _step_peak_over_static(zeta)  # 1.859 at ζ = 0.05, 1.572 at 0.2
    assert st["runup_factor"] == pytest.approx(expected, rel=2e-3)
    assert s["start"]["peak_over_rigid"][0] == pytest.approx(expected, rel=2e-3)  # the rigid start: the static force
    assert st["tangential_N"]["mean"] == pytest.approx(st["static_tangential_N"], rel=1e-6)  # the equilibrium


def test_a_motor_start_is_timed_from_its_samples(tmp_path):
    s = _summary(tmp_path, _motor("periodic"))
    # rigid start by hand: J = J_pinion + J_gear / 3², the load 150 / 3 = 50 N·m at the motor. Flat 100 N·m to
    # 1400 rpm: t1 = J ω1 / 50; then T_m - 50 = (1450 - n) N·m with n in rpm, a first-order approach to 1450 rpm with
    # τ = J / (60 / 2π), from 1400 to 98 % of 1450 = 1421 rpm in τ ln(50 / 29)
    j_pinion = 7800 * math.pi * 0.030 * 0.040**4 / 32  # steel disc, pitch diameter 40 mm, face 30 mm
    j = j_pinion + 0.5 / 9.0
    t1 = j * 1400 * math.pi / 30 / 50.0
    tau = j / (60.0 / (2.0 * math.pi))
    assert s["start_time_s"] == pytest.approx(t1 + tau * math.log(50.0 / 29.0), rel=2e-3)  # 0.1662 s
    window = _summary(tmp_path, _motor("window"))
    for key in ("runup_factor", "peak_tangential_N"):  # the same start as the window run's (was the period's own)
        assert s["stages"][0][key] == pytest.approx(window["stages"][0][key], rel=1e-3)
    assert s["start"]["peak_over_rigid"][0] > 1.0  # was 0.50: the period's force over the rigid start's peak


def _model(drive: str = "speed", ramp_s: float = 0.0):
    spec = SimpleNamespace(drive=SimpleNamespace(kind=drive, ramps_end_s=ramp_s), load=SimpleNamespace(ramp_s=0.0))
    return SimpleNamespace(spec=spec, layout=None)


@pytest.mark.parametrize(("model", "window_start_s", "from_rest", "steady"), [
    (_model(ramp_s=0.3), None, True, "periodic"),  # a ramp bounds the start: the run-up ends with it, as before
    (_model(), 0.05, True, "periodic"),  # the file's window start
    (_model(), None, False, "periodic"),  # a continued sweep point: no start
    (_model(), None, True, "window"),  # a window run
])
def test_the_run_up_is_kept_where_a_ramp_or_the_file_bounds_it(model, window_start_s, from_rest, steady):
    sim = SimpleNamespace(steady=steady, duration_s=1.0, window_start_s=window_start_s)
    assert run_up_end(model, sim, from_rest=from_rest) == window_start_s
