"""The compiled kernel with mesh excitation (transmission error on q = delta - e, stiffness harmonics, viscous
damping ratio), input torque ripple, load fluctuation, a speed drive's start angle and a load clock offset,
and runs that start at t0 > 0 (the periodic steady state, sweep continuation): against scipy's DOP853 on the
generated right-hand side, step for step, and against the generated Jacobian and the Python output laws."""

from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("numba")

from gearcli import engine  # noqa: E402
from gearcli.model import TorsionalModel  # noqa: E402
from gearcli.simulate.solver import integrate  # noqa: E402

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent / "unit"))
from test_model_excitation import SCENES  # noqa: E402
from test_radau import assert_kernel_jacobian  # noqa: E402
from test_step_for_step import assert_same, compiled_dop853, scene, scipy_dop853  # noqa: E402


def _phased(spec):
    """The scene as a continued sweep point: a speed drive's start angle, a load clock offset."""
    drive = dataclasses.replace(spec.drive, angle_rad=1.234) if spec.drive.kind == "speed" else spec.drive
    return dataclasses.replace(spec, drive=drive, load=dataclasses.replace(spec.load, clock_s=0.0371))


MODELS = {name: spec for name, spec in SCENES.items()}
MODELS.update({f"{name}, start angle and clock": _phased(spec) for name, spec in SCENES.items()})
DURATION_S = 0.12  # past the ramps (0.1 s): ripple, fluctuation and TE all act


@pytest.mark.parametrize("name", sorted(MODELS), ids=lambda n: n.replace(" ", "_"))
def test_same_steps_as_scipy_with_every_excitation(name):
    """Issue 15's acceptance on the excitation scenes: the same accepted steps and nfev as scipy's DOP853 on
    the generated right-hand side, samples to 1e-9."""
    model = TorsionalModel(MODELS[name])
    assert engine.unsupported(model.arrays, "DOP853") == []
    t_eval = np.linspace(0.0, DURATION_S, 241)
    atol = model.atol(1e-6)
    assert_same(scipy_dop853(model, t_eval, 1e-6, atol), compiled_dop853(model, t_eval, 1e-6, atol))


@pytest.mark.parametrize("name", sorted(MODELS), ids=lambda n: n.replace(" ", "_"))
def test_compiled_jacobian_is_the_generated_one_with_every_excitation(name):
    """The kernel's Jacobian (the TE's phase-rate column, the ripple's input-angle column, the TE's power in
    the input work) equals the generated ``jac`` at states along a run."""
    k = engine.load(quiet=True).kernel
    model = TorsionalModel(MODELS[name])
    t_eval = np.linspace(0.0, DURATION_S, 25)
    run = integrate(model, t_eval, "DOP853", 1e-6, engine="compiled")
    assert_kernel_jacobian(k, model, t_eval, run.y, rtol=1e-12)


@pytest.mark.parametrize("name", ["spur_oscillator_te", "concrete_mixer_te"])
def test_excited_output_channels_and_stored_energy_are_the_element_laws(name, monkeypatch):
    """Forces, energies, penetrations and the dynamic transmission error through the compiled laws: bit for
    bit the Python laws; the energy watch's stored energy (a TE mesh's at its phase) the same to 1e-12."""
    from gearcli.model import outputs
    from gearcli.simulate.guards import EnergyWatch

    cfg, model = scene(str(ROOT / "configs" / f"{name}.toml"))
    t_eval = np.linspace(0.0, cfg.simulation.duration_s, 401)
    run = integrate(model, t_eval, "DOP853", cfg.simulation.rtol, engine="compiled")
    k = engine.load(quiet=True).kernel
    fast = outputs.sample(model.layout, run.t, run.y)
    monkeypatch.setattr(outputs, "_loaded_kernel", lambda: None)
    slow = outputs.sample(model.layout, run.t, run.y)
    for a, b in zip(fast.connectors, slow.connectors, strict=True):
        for field in ("force", "potential_J", "penetration_m", "dte_m"):
            if hasattr(a, field):
                np.testing.assert_array_equal(getattr(a, field), getattr(b, field))
    watch = EnergyWatch(model, model.initial_state())
    packed = engine.pack(model.arrays)
    for j in range(1, t_eval.size, 40):
        y = np.ascontiguousarray(run.y[:, j])
        assert k.stored_energy(float(t_eval[j]), y, packed) == pytest.approx(watch._stored(float(t_eval[j]), y),
                                                                              rel=1e-12)


@pytest.mark.parametrize("name", ["spur_oscillator_te", "periodic_linear_mesh"])
def test_a_run_from_t0_is_scipys_on_both_engines(name):
    """integrate(..., t0 > 0, y0) as the periodic steady state calls it, period by period: the compiled run is
    gearcli's scipy run (same nfev and steps, samples to 1e-9)."""
    cfg, model = scene(str(ROOT / "configs" / f"{name}.toml"))
    T = cfg.simulation.duration_s
    head = integrate(model, np.linspace(0.0, 0.4 * T, 41), "DOP853", cfg.simulation.rtol)
    t0, y0 = float(head.t[-1]), head.y[:, -1]
    t_eval = t0 + np.linspace(0.0, 0.1 * T, 51)
    py = integrate(model, t_eval, "DOP853", cfg.simulation.rtol, y0=y0, t0=t0)
    cc = integrate(model, t_eval, "DOP853", cfg.simulation.rtol, y0=y0, t0=t0, engine="compiled")
    assert (cc.engine, py.engine) == ("compiled", "python")
    assert (cc.nfev, cc.steps, cc.status) == (py.nfev, py.steps, 0)
    scale = np.maximum(np.abs(py.y).max(axis=1, keepdims=True), 1e-300)
    assert np.max(np.abs(cc.y - py.y) / scale) <= 1e-9


def _numbers(x, path=""):
    """Every number of a JSON document by its path, run-dependent timings and the engine's own keys left out (the
    method choice's reason too: it quotes the wall times predicted on the run's engine; the prediction: its price is
    the engine's)."""
    if isinstance(x, dict):
        out = {}
        for k, v in x.items():
            if k not in ("wall_s", "total_wall_s", "compile_s", "engine", "engine_reason", "choice_reason", "input_sha256",
                         "prediction"):
                out.update(_numbers(v, f"{path}.{k}"))
        return out
    if isinstance(x, list):
        out = {}
        for i, v in enumerate(x):
            out.update(_numbers(v, f"{path}[{i}]"))
        return out
    return {path: x}


def _same_numbers(a: dict, b: dict) -> None:
    assert a.keys() == b.keys()
    for key, va in a.items():
        vb = b[key]
        if isinstance(va, float) and isinstance(vb, float):
            assert vb == pytest.approx(va, rel=1e-9, abs=1e-300), key
        else:
            assert va == vb, key


def test_periodic_steady_state_on_the_compiled_engine():
    """steady = "periodic" integrates period by period from each period's t0: on the compiled engine the same
    period, periodicity, evaluations and statistics as on scipy (the documents' numbers to 1e-9)."""
    import json

    from click.testing import CliRunner

    from gearcli.cli import cli

    docs = {}
    for eng in ("python", "compiled"):
        res = CliRunner().invoke(cli, ["simulate", str(ROOT / "configs" / "periodic_linear_mesh.toml"), "--format",
                                       "json", "--set", f"simulation.engine={eng}"], catch_exceptions=False)
        assert res.exit_code == 0, res.stderr
        docs[eng] = json.loads(res.stdout)
    assert docs["compiled"]["solver"]["engine"] == "compiled"
    assert docs["compiled"]["summary"]["steady"]["mode"] == "periodic"
    assert docs["compiled"]["summary"]["steady"]["converged"] is True
    _same_numbers(_numbers(docs["python"]), _numbers(docs["compiled"]))


def test_sweep_with_continuation_and_periodic_steady_state_on_the_compiled_engine():
    """A continued sweep (the mesh phase carried as the drive's start angle) of the TE backlash oscillator,
    up and down, periodic steady state: every row's numbers are the Python engine's to 1e-9."""
    import csv
    import io

    from click.testing import CliRunner

    from gearcli.cli import cli

    rows = {}
    for eng in ("python", "compiled"):
        res = CliRunner().invoke(cli, ["sweep", str(ROOT / "configs" / "spur_oscillator_te.toml"), "--vary",
                                       "input.speed_rpm=1800:2200:3", "--direction", "both", "--jobs", "1",
                                       "--set", "simulation.duration_s=0.06", "--set", "simulation.steps=1200",
                                       "--set", "simulation.window_start_s=0.03", "--set", "simulation.steady=periodic",
                                       "--set", f"simulation.engine={eng}"])
        assert res.exit_code == 0, res.stderr
        rows[eng] = list(csv.DictReader(io.StringIO(res.stdout)))
    assert len(rows["compiled"]) == 6 and {r["status"] for r in rows["compiled"]} == {"ok"}
    for a, b in zip(rows["python"], rows["compiled"], strict=True):
        for key in a:
            if key == "wall_s":
                continue
            try:
                va, vb = float(a[key]), float(b[key])
            except ValueError:
                assert a[key] == b[key], key
            else:
                assert vb == pytest.approx(va, rel=1e-9, abs=1e-300), key


def test_compiled_radau_with_transmission_error_is_as_accurate_as_scipys():
    """The compiled Radau (analytic Jacobian with the TE's partials) on the TE reducer: its mean and peak
    stage forces are as far from an rtol 1e-10 DOP853 reference as scipy's Radau at the same rtol."""
    import json

    from click.testing import CliRunner

    from gearcli.cli import cli

    def stages(*args):
        res = CliRunner().invoke(cli, ["simulate", str(ROOT / "configs" / "concrete_mixer_te.toml"), "--format", "json",
                                       "--set", "simulation.error_estimate=false", *args], catch_exceptions=False)
        assert res.exit_code == 0, res.stderr
        return [(s["tangential_N"]["mean"], s["tangential_N"]["max"]) for s in json.loads(res.stdout)["summary"]["stages"]]

    ref = stages("--set", "simulation.method=DOP853", "--set", "simulation.rtol=1e-10", "--set",
                 "simulation.engine=compiled")
    radau = {eng: stages("--set", "simulation.method=Radau", "--set", f"simulation.engine={eng}")
             for eng in ("python", "compiled")}
    for k, (mean, peak) in enumerate(ref):
        for j, value in enumerate((mean, peak)):
            err_py = abs(radau["python"][k][j] - value) / abs(value)
            err_cc = abs(radau["compiled"][k][j] - value) / abs(value)
            assert err_cc <= 3.0 * err_py + 1e-7, (k, j, err_cc, err_py)
