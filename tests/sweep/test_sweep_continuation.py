"""Continuation: the start state of a continued point (README "Sweeps", the continuation rule)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
from numpy.testing import assert_allclose

from gearcli.model.layout import Layout
from gearcli.model.spec import DriveSpec, LoadSpec, MeshSpec, ModelSpec
from gearcli.sweep.continuation import continue_state


def _spec(speed_rad_s: float, *, kind: str = "speed", time_varying: bool = False) -> ModelSpec:
    def mesh(rp, rg):
        return MeshSpec(rp, rg, 0.2, 0.36, 0.2, 1e10, 1.5, 5e4, 1e-4, time_varying=time_varying)

    meshes = (mesh(0.12, 0.30), mesh(0.15, 0.42))
    return ModelSpec(meshes, (0.5, 2.0, 9.0), DriveSpec(kind, speed_rad_s, 0.0, 100.0), LoadSpec(500.0))


def _rates(spec: ModelSpec, y: np.ndarray, w_in: float) -> list[float]:
    """delta_k' = r_bp,k w_k - r_bg,k w_{k+1}, by hand from the speeds in y (w_1 prescribed or free)."""
    lay = Layout.of(spec)
    w = [w_in if lay.i_omega(i) is None else y[lay.i_omega(i)] for i in range(3)]
    return [m.base_radius_pinion_m * w[k] - m.base_radius_gear_m * w[k + 1] for k, m in enumerate(spec.meshes)]


def test_speed_drive_keeps_deflections_and_their_rates_and_moves_the_speeds():
    old, new = _spec(60.0), _spec(90.0)
    lay = Layout.of(old)
    y = np.zeros(lay.n_states)
    y[:2] = [3e-5, -1e-6]
    # rigid speeds 60 * 0.12/0.30 = 24 and 24 * 0.15/0.42 rad/s (by hand), plus a vibration
    y[lay.i_omega(1)], y[lay.i_omega(2)] = 24.0 + 0.7, 24.0 * 0.15 / 0.42 - 0.2
    y[lay.i_quad:] = [5.0, 4.0, 1.0]
    y0 = continue_state(y, old, new)
    assert y0 is not None
    assert_allclose(y0[:2], y[:2], rtol=0, atol=0)
    assert_allclose(_rates(new, y0, 90.0), _rates(old, y, 60.0), rtol=0, atol=1e-12)  # vibration carried over
    assert_allclose(y0[lay.i_omega(1)], 90.0 * 0.12 / 0.30 + 0.7, rtol=1e-14)  # new rigid speed + deviation
    assert_allclose(y0[lay.i_quad:], 0.0, atol=0)  # energy quadratures restart


def test_torque_drive_keeps_the_input_angle_state():
    old, new = _spec(60.0, kind="torque", time_varying=True), _spec(80.0, kind="torque", time_varying=True)
    lay = Layout.of(old)
    assert lay.i_theta is not None
    y = np.zeros(lay.n_states)
    y[lay.i_omega(0)], y[lay.i_omega(1)], y[lay.i_omega(2)] = 61.0, 24.0, 24.0 * 0.15 / 0.42
    y[lay.i_theta] = 12.5 * math.pi
    y0 = continue_state(y, old, new)
    assert y0 is not None and y0[lay.i_theta] == y[lay.i_theta]
    assert_allclose(y0[lay.i_omega(0)], 81.0, rtol=1e-14)
    assert_allclose(_rates(new, y0, 0.0), _rates(old, y, 0.0), atol=1e-12)


def test_a_different_state_layout_starts_cold():
    old = _spec(60.0, kind="torque")
    new = dataclasses.replace(old, meshes=tuple(dataclasses.replace(m, time_varying=True) for m in old.meshes))
    assert continue_state(np.zeros(Layout.of(old).n_states), old, new) is None
