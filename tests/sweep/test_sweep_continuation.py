"""Continuation: the start state of a continued point (README "Sweeps", the continuation rule)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from numpy.testing import assert_allclose

from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.scene import build_model
from gearcli.sweep.continuation import NO_RAMPS, continue_state

SEED = Path(__file__).resolve().parents[2] / "configs" / "concrete_mixer.toml"


def _model(*sets: str):
    cfg = load_design(str(SEED), list((*NO_RAMPS, *sets))).design
    return build_model(cfg, compute_design(cfg))


def _rates(model, y: np.ndarray, w_in: float) -> list[float]:
    """delta_c' = r_a w_a - r_b w_b, by hand from the speeds in y (the input body prescribed or free)."""
    lay = model.layout
    w = [w_in if lay.i_omega(i) is None else y[lay.i_omega(i)] for i in range(lay.n_bodies)]
    return [x.ra * w[x.a] - x.rb * w[x.b] for x in lay.connectors]


def test_speed_drive_keeps_deflections_and_their_rates_and_moves_the_speeds():
    old, new = _model("input.speed_rpm=600"), _model("input.speed_rpm=900")
    lay = old.layout
    y = old.initial_state()  # at rest on the rigid motion of 600 rpm (no ramps)
    y[:lay.n_conn] = [3e-5, -1e-6, 2e-6]
    deviation = 0.7
    y[lay.i_omega(1)] += deviation  # a vibration about the rigid speed
    y[lay.i_quad:] = 5.0
    y0 = continue_state(y, old, new)
    assert y0 is not None
    assert_allclose(y0[:lay.n_conn], y[:lay.n_conn], rtol=0, atol=0)
    w_old, w_new = 600 * 2 * np.pi / 60, 900 * 2 * np.pi / 60
    assert_allclose(_rates(new, y0, w_new), _rates(old, y, w_old), rtol=0, atol=1e-9)  # vibration carried over
    rigid_new = w_new * 21 / 51  # shaft 2's rigid speed at 900 rpm, by hand from the tooth counts
    assert_allclose(y0[lay.i_omega(1)], rigid_new + deviation, rtol=1e-9)
    assert_allclose(y0[lay.i_quad:], 0.0, atol=0)  # energy quadratures restart


def test_another_chain_starts_cold():
    old = _model()
    new = _model("stage.0.shaft.stiffness_Nm_rad=1e6")  # a flexible shaft: one more body and connector
    assert continue_state(old.initial_state(), old, new) is None
