"""A sweep point's post-processing shortcuts of the twelfth session (issue 33 item 3) against the long way, bit for
bit: the order sources and the modes' damping made once for the points of one chain, the energy balance's stored
energy at its two ends alone, the stages' series without the output channels, and the sampled stored energy left out
before the balance's first sample (the compiled laws and the scalar ones)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from gearcli import api
from gearcli.model import TorsionalModel
from gearcli.model import modes as modes_mod
from gearcli.model.outputs import potential_energy, sample
from gearcli.simulate import run as run_mod

ROOT = Path(__file__).resolve().parents[2]
# a speed drive (no body damping), motors whose slope damps the input body and a fan law the load body (the
# modes' damping changes with the speed there), a planetary stage, five stages, time-varying mesh stiffness
SCENES = ("concrete_mixer", "fan_drive", "mixer_planetary_motor", "conveyor_motor", "extreme/five_stages",
          "wind_turbine_gearbox")
SPEEDS = (None, 300.0, 1234.5)


def _model(name: str, rpm: float | None = None) -> TorsionalModel:
    sets = [] if rpm is None else [f"input.speed_rpm={rpm!r}"]
    loaded, design = api.load_and_design(str(ROOT / "configs" / f"{name}.toml"), sets)
    return TorsionalModel(api.model_spec(loaded.design, design))


@pytest.mark.parametrize("name", SCENES)
def test_the_order_sources_shared_by_a_chains_points_are_each_points_own(name):
    for rpm in SPEEDS:
        lay = _model(name, rpm).layout
        assert modes_mod.excitation_sources(lay) == modes_mod._excitation_sources(lay)
    # another chain (other tooth counts) has its own
    other = _model("concrete_mixer", 500.0).layout
    assert modes_mod.excitation_sources(other) == modes_mod._excitation_sources(other)


@pytest.mark.parametrize("name", SCENES)
def test_the_modes_damping_kept_with_the_chain_is_each_points_own(name):
    for rpm in SPEEDS:
        lay = _model(name, rpm).layout
        for boundary in ("clamped_input", "free"):
            und = modes_mod._undamped(lay, boundary, 1.0)
            kept = modes_mod._damping(lay, und)
            again = modes_mod._damping(lay, und)  # the kept one
            fresh = modes_mod._damping_of(lay, und)  # the long way
            for a, b, c in zip(kept, again, fresh, strict=True):
                np.testing.assert_array_equal(a, c)
                assert b is a and not a.flags.writeable


def test_the_modes_damping_follows_the_body_damping():
    # a fan law damps the load body by T_L g'(w): half the load, half the damping there; one chain's eigenproblem
    # asked with either body damping gives each its own ratios, not the one kept first
    def model(torque: float) -> TorsionalModel:
        loaded, design = api.load_and_design(str(ROOT / "configs" / "fan_drive.toml"), [f"load.torque_Nm={torque!r}"])
        return TorsionalModel(api.model_spec(loaded.design, design))

    a, b = model(600.0).layout, model(1200.0).layout
    und = modes_mod._undamped(a, "free", 1.0)
    first = modes_mod._damping(a, und)[1]
    second = modes_mod._damping(b, und)[1]
    np.testing.assert_array_equal(first, modes_mod._damping_of(a, und)[1])
    np.testing.assert_array_equal(second, modes_mod._damping_of(b, und)[1])
    assert not np.array_equal(first, second)


@pytest.mark.parametrize("name", SCENES)
def test_the_stored_energy_at_the_ends_is_the_whole_series_ends(name, laws):
    model = _model(name)
    lay = model.layout
    rng = np.random.default_rng(3)
    t = np.linspace(0.0, 0.2, 41)
    y = model.initial_state()
    Y = np.repeat(y[:, None], t.size, axis=1)
    Y[lay.state.deflections] = model.deflection_scales()[:, None] * rng.uniform(-0.5, 2.0, (lay.n_conn, t.size))
    s = sample(lay, t, Y)
    for tv in (False, True):
        whole = potential_energy(lay, s, time_varying=tv)
        np.testing.assert_array_equal(potential_energy(lay, s, time_varying=tv, at=[7, -1]), whole[[7, -1]])
    # the balance from a sample on, read in place: the balance of the samples from there, the same numbers
    assert model.energy(s, Y, start=7) == model.energy(s.tail(7), Y[:, 7:])
    assert model.energy(s, Y) == model.energy(s.tail(0), Y)
    # the stored energy left out before the balance's first sample: every other series the same, bit for bit
    part = sample(lay, t, Y, energy_from=30)
    for a, b in zip(part.connectors, s.connectors, strict=True):
        for f in ("force", "deflection", "penetration_m", "dte_m"):
            np.testing.assert_array_equal(getattr(a, f), getattr(b, f))
        assert np.isnan(a.potential_J[:30]).all()
        np.testing.assert_array_equal(a.potential_J[30:], b.potential_J[30:])
    assert model.energy(part.tail(30), Y[:, 30:]) == model.energy(s.tail(30), Y[:, 30:])


@pytest.mark.parametrize("name", SCENES)
def test_the_stages_series_without_the_channels_are_the_channels(name):
    model = _model(name)
    lay = model.layout
    t = np.linspace(0.0, 0.1, 21)
    Y = np.repeat(model.initial_state()[:, None], t.size, axis=1)
    Y[lay.state.deflections] = model.deflection_scales()[:, None] * np.linspace(0.5, 1.5, t.size)[None, :]
    s = sample(lay, t, Y)
    ch, whole, rows = run_mod._series(model, s, True)
    none, alone, _ = run_mod._series(model, s, False)
    assert ch and none == {}
    for k, (a, b) in enumerate(zip(alone, whole, strict=True)):
        for j, (x, y) in enumerate(zip(a, b, strict=True)):
            np.testing.assert_array_equal(x, y)
            np.testing.assert_array_equal(rows[5 * k + j], y)  # the stages' rows of one array, in order


@pytest.mark.parametrize("name", SCENES)
def test_a_window_read_in_place_has_the_masks_means(name):
    # the ratio's shaft speeds: a contiguous window's view reduces as the mask's copy does, bit for bit
    from gearcli.simulate import stats

    model = _model(name)
    t = np.linspace(0.0, 0.5, 2001)
    rng = np.random.default_rng(5)
    w = 100.0 + rng.standard_normal((model.layout.n_bodies, t.size))
    mask = stats.window_mask(t, (0.2437, 0.5))
    sel = stats.window_slice(mask)
    assert isinstance(sel, slice)
    for b in model.layout.shaft_body:
        assert float(w[b][sel].mean()) == float(w[b][mask].mean())
