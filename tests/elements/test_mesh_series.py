"""The mesh's vectorised hook (``series``) gives at every sample what its scalar laws give sample by sample: the
force, the stored energy and both channels, over states on both flanks, in the backlash, unloaded and moving
apart, for the IMPACT and viscous laws and the exponents the schema allows; the outputs of a run use it and
keep the scalar laws' numbers."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gearcli.model import elements
from gearcli.model.elements import N_PARAM, mesh

EXPONENTS = (1.0, 1.5, 2.0)  # the exponents the law takes apart (products, sqrt)


def _row(exponent: float, half_gap_m: float, damping: float, viscous: float | None) -> np.ndarray:
    P = np.zeros(N_PARAM)
    cb = math.cos(math.radians(13.0))
    P[mesh.I_CB], P[mesh.I_CB2], P[mesh.I_K], P[mesh.I_E] = cb, cb * cb, 3.0e9, exponent
    d_full = 1e-4
    P[mesh.I_C], P[mesh.I_INVD], P[mesh.I_DC] = damping, 1.0 / d_full, 6.0 * damping / d_full
    P[mesh.I_HALF], P[mesh.I_D], P[mesh.I_Z] = half_gap_m, d_full, 17.0
    if viscous is not None:
        P[mesh.I_VIS], P[mesh.I_CV] = 1.0, viscous
    return P


def _scalar(P, d, dd):
    F = np.array([mesh.force(P, a, b, 0.0, 0.0)[0] for a, b in zip(d, dd, strict=True)])
    U = np.array([mesh.potential(P, a, 0.0) for a in d])
    ch = [np.array([mesh.channel(P, i, a, 0.0) for a in d]) for i in range(len(mesh.CHANNELS))]
    return F, U, ch


states = st.lists(st.tuples(st.floats(-2e-4, 2e-4), st.floats(-0.5, 0.5)), min_size=1, max_size=40)


@settings(max_examples=60, deadline=None)
@given(states, st.sampled_from(EXPONENTS), st.sampled_from((0.0, 2e-5)), st.sampled_from((0.0, 5e4)),
       st.sampled_from((None, 0.0, 3e3)))
def test_series_equals_the_scalar_laws(pairs, exponent, half_gap, damping, viscous):
    d = np.array([a for a, _ in pairs])
    dd = np.array([b for _, b in pairs])
    P = _row(exponent, half_gap, damping, viscous)
    F, U, ch = mesh.series(P, d, dd, np.zeros_like(d), np.zeros_like(d))
    F0, U0, ch0 = _scalar(P, d, dd)
    assert np.array_equal(F, F0)  # bit for bit: the same operations in the same order, the same pow
    assert np.array_equal(U, U0)
    for a, b in zip(ch, ch0, strict=True):
        assert np.array_equal(a, b)


@pytest.mark.parametrize("exponent", [1.3, 2.5])
def test_series_other_exponents_to_the_bit(exponent):
    d = np.linspace(-1.5e-4, 1.5e-4, 301)
    dd = np.linspace(0.3, -0.3, 301)
    P = _row(exponent, 1e-5, 5e4, None)
    F, U, _ = mesh.series(P, d, dd, np.zeros_like(d), np.zeros_like(d))
    F0, U0, _ = _scalar(P, d, dd)
    assert np.array_equal(F, F0) and np.array_equal(U, U0)


def test_phase_dependent_rows_are_left_to_the_scalar_laws():
    d = np.zeros(3)
    for index in (mesh.I_TV, mesh.I_NKS, mesh.I_NTE):
        P = _row(1.5, 0.0, 5e4, None)
        P[index] = 1.0
        assert mesh.series(P, d, d, d, d) is None
        assert elements.series_of(mesh, P, d, d, d, d) is None


def test_an_element_without_the_hook_has_no_series():
    from gearcli.model.elements import spring

    assert not hasattr(spring, elements.SERIES_HOOK)
    assert elements.series_of(spring, np.zeros(N_PARAM), np.zeros(2), np.zeros(2), np.zeros(2), np.zeros(2)) is None
