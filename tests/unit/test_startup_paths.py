"""The faster paths of a one-shot run give what the plain ones give: the check pass on the run's own samples,
the channels' scalar laws on Python floats, the check pass's line forces and the energy watch's stored energy
without the channels they never read, and the generated model's template found without Python's tokenizer."""

from __future__ import annotations

import io
import tokenize
from pathlib import Path

import numpy as np

from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.model import codegen
from gearcli.model.elements import KIND_MESH
from gearcli.model.elements.mesh import dynamic_transmission_error, penetration
from gearcli.model.outputs import (
    connector_series,
    kinetic_energy,
    mesh_line_forces,
    potential_energy,
    sample,
    stored_energy,
)
from gearcli.scene import build_model
from gearcli.simulate import estimate
from gearcli.simulate.choice import choose_method
from gearcli.simulate.solver import integrate
from gearcli.simulate.stats import steady_window

SEED = Path(__file__).resolve().parents[2] / "configs" / "concrete_mixer.toml"


def _seed_run():
    cfg = load_design(str(SEED), []).design
    model = build_model(cfg, compute_design(cfg))
    sim = cfg.simulation
    choice = choose_method(model.spec, sim.duration_s, sim.method, sim.rtol)
    run = integrate(model, np.linspace(0.0, sim.duration_s, sim.steps + 1), choice.method, sim.rtol,
                    max_nfev=10**7, engine="python")
    window, _ = steady_window(model.spec, sim.duration_s, sim.window_start_s)
    return model, choice, run, window


def test_check_pass_on_the_runs_own_samples_equals_sampling_the_window_again():
    model, choice, run, window = _seed_run()
    again = estimate.check_pass(model, run, choice, window, max_nfev=10**7)
    reused = estimate.check_pass(model, run, choice, window, max_nfev=10**7,
                                 sampled=sample(model.layout, run.t, run.y))
    assert len(again.errors) == len(model.spec.meshes) == 3
    assert again.errors == reused.errors  # every statistic's error, bit for bit
    assert (again.nfev, again.rtol, again.from_s, again.passes) == (reused.nfev, reused.rtol, reused.from_s, reused.passes)


def test_channels_are_the_scalar_law_at_each_sample():
    model, _, run, _ = _seed_run()
    lay = model.layout
    s = sample(lay, run.t, run.y)
    picks = [0, 1, run.t.size // 2, run.t.size - 1]
    for c, x in enumerate(lay.connectors):
        cs = connector_series(lay, c, run.y, s.omega_rad_s, s.theta_rad)
        assert x.kind == KIND_MESH and cs.force.shape == run.t.shape
        for j in picks:  # the element's own law, called here sample by sample on numpy scalars
            d = run.y[c, j]
            dd = x.ra * s.omega_rad_s[x.a, j] - x.rb * s.omega_rad_s[x.b, j]
            assert cs.force[j] == x.element.force(x.params, d, dd, 0.0, 0.0)[0]
            assert cs.potential_J[j] == x.element.potential(x.params, d, 0.0)
            assert cs.penetration_m[j] == penetration(x.params, d, 0.0)
            assert cs.dte_m[j] == dynamic_transmission_error(x.params, d, 0.0)
        assert np.any(cs.force != 0.0)  # the meshes carry load


def test_the_check_pass_line_forces_are_the_samples_mesh_forces_bit_for_bit():
    model, _, run, _ = _seed_run()
    lay = model.layout
    tail = slice(run.t.size // 2, None)  # a window: the check pass samples the run's tail
    full = [m.line_force_N for m in sample(lay, run.t[tail], run.y[:, tail]).meshes]
    alone = mesh_line_forces(lay, run.t[tail], run.y[:, tail])
    assert len(alone) == len(full) == 3
    for a, f in zip(alone, full, strict=True):
        assert a.shape == f.shape and np.array_equal(a, f)  # the same law on the same floats: equal, not close


def test_the_energy_watch_stored_energy_is_the_samples_bit_for_bit():
    model, _, run, _ = _seed_run()
    lay = model.layout
    for j in (0, 1, run.t.size // 3, run.t.size - 1):
        s = sample(lay, np.array([run.t[j]]), run.y[:, j][:, None])
        expected = float(kinetic_energy(lay, s.omega_rad_s)[0]) + float(potential_energy(lay, s, time_varying=False)[0])
        assert stored_energy(lay, float(run.t[j]), run.y[:, j]) == expected
    assert expected > 0.0  # the train moves and the meshes are loaded at the end of the run


def _tokenizer_template(source: str) -> tuple[str, tuple[float, ...]]:
    """The reference: every NUMBER token of Python's tokenizer that is not a plain integer, replaced in order."""
    lines = source.splitlines(True)
    values: list[float] = []
    spans = []
    for tok in tokenize.generate_tokens(io.StringIO(source).readline):
        if tok.type == tokenize.NUMBER and not tok.string.isdigit():
            spans.append((tok.start[0] - 1, tok.start[1], tok.end[1], f"_k{len(values)}"))
            values.append(float(tok.string))
    for row, a, b, name in reversed(spans):
        lines[row] = lines[row][:a] + name + lines[row][b:]
    return "".join(lines), tuple(values)


def test_the_template_finds_the_literals_the_tokenizer_finds():
    configs = SEED.parent
    for name in ("concrete_mixer.toml", "mixer_planetary_motor.toml", "concrete_mixer_te.toml", "lossy_reducer.toml",
                 "mixer_time_varying_backlash.toml", "conveyor_motor.toml"):
        cfg = load_design(str(configs / name), []).design
        source = codegen.source_of(build_model(cfg, compute_design(cfg)).layout)
        template, constants = codegen._template(source)
        assert (template, constants) == _tokenizer_template(source), name
        assert len(constants) > 10  # every scene has its inertias, levers and ramps as literals
