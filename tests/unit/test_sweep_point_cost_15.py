"""What a sweep point computes, session 15 (issue 33 item 3): a periodic window's sampling estimate reads no modes, so
the run's damped eigenvalues (:attr:`gearcli.simulate.choice.Choice.run_eigenvalues`) are not worked out for it; a
fixed window's aliasing check still reads them. Checked against the plain path (the eigenvalues handed in) and
against a sinusoid put in at a mode above the samples' Nyquist frequency (its amplitude, a closed form)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_allclose

from gearcli import api
from gearcli.model import TorsionalModel
from gearcli.simulate import aliasing, sampling
from gearcli.simulate import choice as choice_mod
from gearcli.sweep.worker import Scene

ROOT = Path(__file__).resolve().parents[2]
SEED = ROOT / "configs" / "concrete_mixer.toml"
FS, T0, T1, MODE_HZ = 4000.0, 0.14, 0.5, 2500.0  # samples a second; the window; a mode above FS / 2


def _seed():
    loaded, design = api.load_and_design(str(SEED), [])
    model = TorsionalModel(api.model_spec(loaded.design, design))
    return model.spec, model.layout


def _window(spec, amplitude_N: float):
    """Stage 1's F_t: its static force and a sinusoid at MODE_HZ; the other stages constant; (t, mask, per_stage)."""
    n = round((T1 - T0) * FS)
    t = T0 + np.arange(n + 1) / FS
    per_stage = []
    for k, m in enumerate(spec.meshes):
        ft = m.static_tangential_N + (amplitude_N * np.sin(2.0 * math.pi * MODE_HZ * t + 0.3) if k == 0 else 0.0 * t)
        per_stage.append((ft, 0.2 * ft, 0.1 * ft, np.full_like(t, 0.01), np.full_like(t, 5.0)))
    return t, np.ones(t.size, dtype=bool), per_stage


def _sampling(spec, layout, t, mask, per_stage, periodic: bool, eigenvalues):
    n = len(spec.meshes)
    return aliasing.window_sampling(t, mask, per_stage, spec, [None] * n, 2000, periodic, 1.0, [0.0] * n, None,
                                    layout, eigenvalues)


def test_a_periodic_windows_estimate_reads_no_modes_and_a_fixed_windows_finds_one_above_nyquist():
    spec, layout = _seed()
    amplitude = 0.05 * spec.meshes[0].static_tangential_N  # well above the sampling target of the static force
    assert amplitude > sampling.TARGET * spec.meshes[0].static_tangential_N
    t, mask, per_stage = _window(spec, amplitude)
    mode = np.array([complex(-5.0, 2.0 * math.pi * MODE_HZ), complex(-5.0, -2.0 * math.pi * MODE_HZ)])
    fixed = _sampling(spec, layout, t, mask, per_stage, False, mode)
    hit = fixed[0].aliased
    assert hit is not None and not fixed[0].resolved
    assert_allclose(hit["frequency_Hz"], MODE_HZ, rtol=1e-12)
    assert_allclose(hit["alias_Hz"], FS - MODE_HZ, rtol=1e-12)
    assert_allclose(hit["amplitude_N"], amplitude, rtol=1e-3)  # a sinusoid keeps its amplitude when sampled
    assert all(se is not None and se.aliased is None for se in fixed[1:])
    assert _sampling(spec, layout, t, mask, per_stage, False, None)[0].aliased is None  # the mode made the finding
    # a periodic window: the same estimate with the modes, without them, and without any finding
    with_modes = _sampling(spec, layout, t, mask, per_stage, True, mode)
    assert with_modes == _sampling(spec, layout, t, mask, per_stage, True, None)
    assert all(se is not None and se.aliased is None for se in with_modes)


def _counted(monkeypatch) -> list[int]:
    calls = [0]
    real = choice_mod.damped_eigenvalues

    def counting(*args, **kwargs):
        calls[0] += 1
        return real(*args, **kwargs)

    monkeypatch.setattr(choice_mod, "damped_eigenvalues", counting)
    return calls


@pytest.mark.parametrize("settle", [True, "window"])
def test_a_sweep_point_solves_the_damped_eigenproblem_only_where_its_window_reads_it(monkeypatch, settle):
    """The seed's sweep point (its equilibrium: a periodic window; ``settle="window"``: a fixed window) against the
    same point whose sampling estimate is handed the run's eigenvalues (the plain path): the same stages and
    warnings; a fixed window's point reads them."""
    scene = Scene(SEED.read_bytes(), str(SEED), (), 3)
    point = ("input.speed_rpm=700.0",)
    calls = _counted(monkeypatch)
    lean = api.evaluate_point(scene, point, settle=settle).result
    assert lean.steady is not None and (lean.steady.mode == "periodic") == (settle is True)
    assert (calls[0] == 0) == (settle is True)
    real = aliasing.window_sampling

    def handed(t, mask, per_stage, spec, errors, steps, periodic, share, floors, reduced=None, layout=None,
               eigenvalues=None, planets=None, planet_reduced=None):
        if eigenvalues is None:  # the plain path: the run's own eigenvalues, as before
            eigenvalues = choice_mod.damped_eigenvalues(layout, seen[-1].reported.forces)
        return real(t, mask, per_stage, spec, errors, steps, periodic, share, floors, reduced, layout, eigenvalues,
                    planets, planet_reduced)

    seen: list = []
    choose = choice_mod.choose_method

    def remembered(*args, **kwargs):
        seen.append(choose(*args, **kwargs))
        return seen[-1]

    from gearcli.simulate import run as run_mod

    monkeypatch.setattr(run_mod, "choose_method", remembered)
    monkeypatch.setattr(aliasing, "window_sampling", handed)
    plain = api.evaluate_point(scene, point, settle=settle).result
    assert lean.stages == plain.stages
    assert lean.warnings == plain.warnings
    assert lean.output_speed_deg_s == plain.output_speed_deg_s
