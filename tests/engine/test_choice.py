"""Which engine runs: what sends a scene to Python, auto's cost rule, the usage error without numba."""

from __future__ import annotations

import dataclasses
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from gearcli import engine
from gearcli.errors import ConfigError

ROOT = Path(__file__).resolve().parents[2]


def seed_arrays(name: str = "concrete_mixer.toml"):
    from gearcli.config import load_design
    from gearcli.design import compute_design
    from gearcli.scene import build_model

    cfg = load_design(str(ROOT / "configs" / name), []).design
    return build_model(cfg, compute_design(cfg)).arrays


def test_seed_and_excited_scenes_are_supported_and_each_unknown_feature_is_named():
    arrays = seed_arrays()
    assert engine.unsupported(arrays, "DOP853") == []
    for name in ("concrete_mixer_te.toml", "spur_oscillator_te.toml", "concrete_mixer_drivetrain.toml"):
        assert engine.unsupported(seed_arrays(name), "DOP853") == [], name  # excitation and springs: compiled
    ripple = dataclasses.replace(arrays, drive_ripple=np.array([[0.05, 1.0]]), load_fluct=np.array([[0.1, 2.0]]))
    assert engine.unsupported(ripple, "DOP853") == []
    kind = arrays.conn_kind.copy()
    kind[0] = 7  # a connector kind the kernel has no law for
    assert any("connector kinds [7]" in r for r in engine.unsupported(dataclasses.replace(arrays, conn_kind=kind),
                                                                       "DOP853"))
    springs = seed_arrays("concrete_mixer_drivetrain.toml")
    c = int(np.flatnonzero(springs.conn_kind == 0)[0])
    param = springs.conn_param.copy()
    param[c, -1] = 0.3  # a parameter column the spring law does not read
    assert any("element parameters" in r for r in engine.unsupported(dataclasses.replace(springs, conn_param=param),
                                                                      "DOP853"))
    assert any("method BDF" in r for r in engine.unsupported(arrays, "BDF"))
    assert engine.unsupported(arrays, "Radau") == []


def test_auto_weighs_the_load_cost_against_the_python_run(monkeypatch):
    """At the prices of gearcli.core.cost (scipy's DOP853 ~10.5 us per evaluation all included, the compiled
    one ~0.8 us, plus the load): with a 0.5 s load, 10^4 evaluations (0.1 s in Python) stay in Python and 10^6
    (10 s) go compiled; shared by 1000 runs the load costs 0.5 ms per run and 10^4 evaluations go compiled too.
    Radau is taken compiled on the same rule, one-shot runs included (it agrees with scipy to the tolerance)."""
    from gearcli.core import cost

    monkeypatch.setattr(engine, "available", lambda: True)
    monkeypatch.setattr(engine, "expected_load_s", lambda: 0.5)
    monkeypatch.setitem(engine._runs, "expected", 1)  # a fresh process: nothing announced
    arrays = seed_arrays()
    python_s = 1e4 * cost.seconds_per_eval("python", "DOP853")  # by hand: 1e4 x (8 + 30 / 12) us = 0.105 s
    assert python_s == pytest.approx(0.105)
    assert engine.choose("auto", arrays, "DOP853", 1e4).engine == "python"
    assert engine.choose("auto", arrays, "DOP853", 1e6).engine == "compiled"
    assert engine.choose("auto", arrays, "Radau", 1e6).engine == "compiled"  # a one-shot run too
    assert engine.choose("auto", arrays, "Radau", 1e3).engine == "python"  # 0.03 s in Python: not worth the load
    engine.expect_runs(999)
    assert engine.choose("auto", arrays, "DOP853", 1e4).engine == "compiled"
    with engine.batch(10):  # a report's ladder, a sweep task
        assert engine.choose("auto", arrays, "Radau", 1e6).engine == "compiled"
        assert engine.choose("auto", arrays, "BDF", 1e6).engine == "python"
    assert engine.choose("python", arrays, "DOP853", 1e9).engine == "python"


def test_a_sweeps_batch_prices_the_load_alike_whatever_the_process_has_loaded_or_measured(monkeypatch):
    """A sweep's points (gearcli.sweep.execute) price loading the kernel alike in every worker: nothing where it is
    cached (each worker loads it once against the sweep's many runs), a compilation's 60 s over all the sweep's
    points where it is not. 10^4 Radau evaluations (0.34 s in Python at ~34 us each, by gearcli.core.cost; ~0.01 s
    compiled) then go compiled whether this process has loaded the kernel or last measured a 3 s load, where the
    process's own figure decides each differently (the rows of a sweep then differed with --jobs and with the
    machine's load)."""
    from gearcli.core import cost

    monkeypatch.setattr(engine, "available", lambda: True)
    monkeypatch.setitem(engine._runs, "expected", 1)
    monkeypatch.setattr(engine, "cached_or_loaded", lambda: False)
    assert engine.sweep_load_share_s(600) == pytest.approx(0.1)  # 60 s of compilation over 600 points
    monkeypatch.setattr(engine, "cached_or_loaded", lambda: True)
    share = engine.sweep_load_share_s(2)
    assert share == 0.0
    arrays = seed_arrays()
    python_s = cost.predicted_wall_s("python", "Radau", 1e4)
    compiled_s = cost.predicted_wall_s("compiled", "Radau", 1e4, share)
    assert compiled_s < python_s < compiled_s + 3.0  # the measured 3 s would have kept it on scipy
    picks = set()
    for measured in (0.0, 3.0):  # loaded already; or a slow last load measured
        monkeypatch.setattr(engine, "expected_load_s", lambda m=measured: m)
        with engine.batch(1):  # the process's own figure: the choices differ
            picks.add(engine.choose("auto", arrays, "Radau", 1e4).engine)
    assert picks == {"python", "compiled"}
    for measured in (0.0, 3.0):
        monkeypatch.setattr(engine, "expected_load_s", lambda m=measured: m)
        with engine.batch(1, share):
            assert engine.load_share_s() == share
            assert engine.choose("auto", arrays, "Radau", 1e4).engine == "compiled"
    assert engine.load_share_s() == engine.expected_load_s() / engine._runs["expected"]  # the batch's price is gone


def test_compiled_without_numba_is_a_usage_error_naming_the_extra(monkeypatch):
    monkeypatch.setattr(engine, "available", lambda: False)
    with pytest.raises(ConfigError) as err:
        engine.choose("compiled", seed_arrays(), "DOP853", 1e4)
    assert "gearcli[fast]" in str(err.value)
    assert engine.choose("auto", seed_arrays(), "DOP853", 1e9).engine == "python"


def test_cli_exit_2_without_numba():
    code = ("import sys; sys.modules['numba'] = None\n"
            "from gearcli.__main__ import main\n"
            "sys.argv = ['gearcli', 'simulate', 'configs/concrete_mixer.toml', '--set', 'simulation.engine=compiled']\n"
            "main()\n")
    proc = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 2
    assert "gearcli[fast]" in proc.stderr and "simulation.engine" in proc.stderr
    assert "Traceback" not in proc.stderr


def test_unsupported_method_requested_compiled_runs_on_python_with_the_reason():
    pytest.importorskip("numba")
    from gearcli.config import load_design
    from gearcli.design import compute_design
    from gearcli.simulate import run_simulation

    path = str(ROOT / "configs" / "stiff_linear_mesh.toml")
    cfg = load_design(path, ["simulation.engine=compiled", "simulation.method=BDF", "simulation.steps=200"]).design
    sim = run_simulation(cfg, compute_design(cfg), want_series=False)
    assert sim.solver.method == "BDF" and sim.solver.engine == "python"
    assert "method BDF" in sim.solver.engine_reason
    assert any(d.code == "engine_fallback" for d in sim.diagnostics)
    cfg = load_design(path, ["simulation.engine=compiled", "simulation.steps=200"]).design
    sim = run_simulation(cfg, compute_design(cfg), want_series=False)
    assert (sim.solver.method, sim.solver.engine) == ("Radau", "compiled")
    assert sim.solver.njev > 0 and not any(d.code == "engine_fallback" for d in sim.diagnostics)
