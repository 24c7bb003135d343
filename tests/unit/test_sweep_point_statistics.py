"""A sweep point's statistics worked out once (session 24, issue 33): every planet mesh's window reduced as the rows
of one array (stats.planet_windows) and read by both the sampling estimate and the planets, against each mesh
reduced on its own as before (stats.channel_stats, numpy's 1-D reductions), bit for bit; and the compiled window
pass's contact fractions, whose split is skipped where no sample leaves contact, against the split worked out for
every row. Windows that move (random deflections), a window with a hole (a mask, not a slice), both window kinds."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from gearcli import api, engine
from gearcli.model import TorsionalModel, outputs
from gearcli.simulate import aliasing, planet_stats, stats
from gearcli.simulate.results import ChannelStats, DteStats

ROOT = Path(__file__).resolve().parents[2]


def _sampled(name: str, seed: int):
    loaded, design = api.load_and_design(str(ROOT / "configs" / f"{name}.toml"))
    model = TorsionalModel(api.model_spec(loaded.design, design))
    lay = model.layout
    t = np.linspace(0.0, 0.3, 301)
    rng = np.random.default_rng(seed)
    Y = np.repeat(model.initial_state()[:, None], t.size, axis=1)
    Y[lay.state.deflections] = model.deflection_scales()[:, None] * rng.uniform(-0.5, 2.0, (lay.n_conn, t.size))
    return model, t, outputs.sample(lay, t, Y)


MASKS = [lambda t: t >= 0.1, lambda t: (t >= 0.1) & ((t < 0.2) | (t > 0.22))]


@pytest.mark.parametrize("periodic", [False, True])
@pytest.mark.parametrize("holed", [False, True])
def test_every_planet_meshs_window_is_its_own_reductions_bit_for_bit(periodic, holed):
    model, t, s = _sampled("mixer_planetary_motor", 3)
    mask = MASKS[holed](t)
    every = planet_stats.planet_series(model, s)
    assert len(every) >= 6  # three planets, a sun and a ring mesh each
    windows = stats.planet_windows(t, mask, every, periodic)
    assert set(windows) == set(every)
    for key, (ft, dte) in every.items():
        q = dte[mask] * 1e6
        want = (stats.channel_stats(ft, mask, t, periodic=periodic),
                DteStats(float(stats.window_means(t[mask], q, periodic)[0]), float(q.std()), float(q.min()),
                         float(q.max())))
        w = ft[mask]
        plain = (float(w.mean()), float(w.std()), float(w.min()), float(w.max()))
        got, reduced = windows[key]
        assert (got.tangential_N, got.dte_um) == want and reduced == plain
        assert repr((got.tangential_N, got.dte_um, reduced)) == repr((*want, plain))  # every float's digits
        assert want[0] != ChannelStats(0.0, 0.0, 0.0, 0.0) and want[0].min < want[0].max  # a window that moves
    stage = next(iter(every))[0]
    assert stats.planet_windows(t, mask, every, periodic, stage) == {k: v for k, v in windows.items() if k[0] == stage}


@pytest.mark.parametrize("periodic", [False, True])
def test_the_sampling_estimate_and_the_planets_read_the_shared_windows_as_their_own(periodic):
    model, t, s = _sampled("mixer_planetary_motor", 5)
    spec, mask = model.spec, t >= 0.1
    every = planet_stats.planet_series(model, s)
    windows = stats.planet_windows(t, mask, every, periodic)
    rows = outputs.stage_rows(model.layout, s.meshes)
    per_stage = [tuple(rows[5 * k:5 * k + 5]) for k in range(len(spec.meshes))]
    statics = [m.static_tangential_N for m in spec.meshes]
    reduced = stats.window_reductions(t, mask, per_stage, statics, periodic, rows)
    args = (t, mask, per_stage, spec, [None] * len(statics), 300, periodic, 0.7, [0.0] * len(statics), reduced,
            model.layout, None)
    alone = aliasing.window_sampling(*args, every)
    shared = aliasing.window_sampling(*args, every, windows)
    assert shared == alone and repr(shared) == repr(alone)
    planetary = [k for k in range(len(spec.meshes)) if any(key[0] == k for key in every)]
    assert planetary
    for k in range(len(spec.meshes)):
        assert planet_stats.planets_of(model, s, mask, k, periodic, every, windows) == \
            planet_stats.planets_of(model, s, mask, k, periodic)


@pytest.mark.parametrize("periodic", [False, True])
def test_a_window_in_contact_throughout_has_the_splits_zero_fractions(monkeypatch, periodic):
    pytest.importorskip("numba")
    from gearcli.engine import kernel as compiled  # the kernel module, imported directly (bound to the cache)

    monkeypatch.setattr(engine, "loaded_kernel", lambda: compiled)
    t = np.linspace(0.0, 1.0, 401)
    mask = t >= 0.4
    rng = np.random.default_rng(11)
    pen = 1e-5 * (1.0 + 0.2 * rng.standard_normal(t.size))  # pressed throughout: no sample out of contact
    lost = np.where((t > 0.55) & (t < 0.6), 0.0, pen)  # a mesh that leaves contact for a while
    for pens in ([pen, 0.8 * pen], [pen, lost]):
        per_stage = [(1e3 * p, 0.3 * p, 0.1 * p, p * 1e3, p * 1e6) for p in pens]
        statics = [1000.0, 500.0]
        reduced = stats.window_reductions(t, mask, per_stage, statics, periodic)
        assert reduced is not None
        W = reduced.W
        split = stats.contact_fractions(reduced.tw, W[0::5], W[3::5], W[4::5], statics, periodic)  # every row
        assert reduced.contact[:2] == split
        assert (split[0][1] > 0.0) == (pens[1] is lost)  # the fractions worked out are not zeros alone
