"""The compiled output sampling without the channels no one reads (issue 33 item 3, session 13): an unexcited mesh's
DTE channel (its deflection) never evaluated, the check pass's line forces and the energy watch's potential without
channels, against the elements' scalar laws, the full sampling and numpy over the full sampled series."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from gearcli import api
from gearcli.model import TorsionalModel
from gearcli.model.outputs import connector_line_forces, mesh_line_forces, sample
from gearcli.simulate import run_simulation

ROOT = Path(__file__).resolve().parents[2]
# unexcited meshes (the seed), a transmission error (DTE evaluated), a planetary stage, a motor and coupling
SCENES = ("concrete_mixer", "concrete_mixer_te", "mixer_planetary_motor", "conveyor_motor")


def _model(name: str) -> TorsionalModel:
    loaded, design = api.load_and_design(str(ROOT / "configs" / f"{name}.toml"))
    return TorsionalModel(api.model_spec(loaded.design, design))


def _sampled(name: str):
    """A scene's layout, 41 sample times, states with random deflections (either flank, gaps open and closed) and
    their full sampling (every channel at every sample: the long way)."""
    model = _model(name)
    lay = model.layout
    t = np.linspace(0.0, 0.2, 41)
    rng = np.random.default_rng(13)
    Y = np.repeat(model.initial_state()[:, None], t.size, axis=1)
    Y[lay.state.deflections] = model.deflection_scales()[:, None] * rng.uniform(-0.5, 2.0, (lay.n_conn, t.size))
    return lay, t, Y, sample(lay, t, Y)


@pytest.mark.parametrize("name", SCENES)
def test_the_channels_are_the_elements_own_laws_and_an_unexcited_dte_the_deflection(name, laws):
    # the compiled laws leave an unexcited mesh's DTE channel out: its dte_m is the state's deflection, bit for bit;
    # every channel they do evaluate is the element's scalar law sample by sample
    lay, t, Y, whole = _sampled(name)
    for c, (x, cs) in enumerate(zip(lay.connectors, whole.connectors, strict=True)):
        d = Y[lay.state.delta(c)]
        np.testing.assert_array_equal(cs.deflection, d)
        phi = np.zeros(t.size) if not x.phased else None
        if x.role == "mesh" and not x.excited:
            np.testing.assert_array_equal(cs.dte_m, d)
        if phi is None or "penetration_m" not in x.element.CHANNELS:
            continue
        i = x.element.CHANNELS.index("penetration_m")
        law = [x.element.channel(x.params, i, float(dj), 0.0) for dj in d]
        np.testing.assert_allclose(cs.penetration_m, law, rtol=1e-15, atol=0.0)


@pytest.mark.parametrize("name", SCENES)
def test_the_line_forces_alone_are_the_sampled_forces(name, laws):
    # the check pass's line forces (no energy nor channel evaluated): the full sampling's, bit for bit
    lay, t, Y, whole = _sampled(name)
    for f, m in zip(mesh_line_forces(lay, t, Y), whole.meshes, strict=True):
        np.testing.assert_array_equal(f, m.force)
    every = list(range(lay.n_conn))
    for f, cs in zip(connector_line_forces(lay, t, Y, every), whole.connectors, strict=True):
        np.testing.assert_array_equal(f, cs.force)


def _stages(name: str, want_series: bool):
    loaded, design = api.load_and_design(str(ROOT / "configs" / f"{name}.toml"), ["simulation.engine=compiled"])
    return run_simulation(loaded.design, design, want_series=want_series, summary_start=False, settle=True)


@pytest.mark.parametrize("name", ["concrete_mixer", "planetary_stage", "extreme/five_stages"])
def test_a_row_without_series_has_the_statistics_of_every_sample(name):
    # a row (no series kept, its run-up sampled by the compiled laws without an unexcited mesh's DTE): its stages'
    # statistics, peaks and warnings are those of the run that keeps every series, its peaks numpy's over them
    from gearcli import engine

    if not engine.available():
        pytest.skip("the compiled engine is not installed")
    row, full = _stages(name, False), _stages(name, True)
    assert row.stages == full.stages
    assert [d.message for d in row.diagnostics] == [d.message for d in full.diagnostics]
    for k, st in enumerate(full.stages):  # a planetary stage's peak: its planets' sun meshes' too
        own = (f"stage{k + 1}", *(f"stage{k + 1}_planet{j + 1}_sun" for j in range(32)))
        ft = [v for c, v in full.series.items() if c.quantity == "tangential_force" and c.owner in own]
        assert ft and all(np.isfinite(v).all() for v in ft)
        peak = max(float(np.max(np.abs(v))) for v in ft)
        assert st.peak_tangential_N == peak and row.stages[k].peak_tangential_N == peak
