"""Contact-line length of the plane of action (time-varying mesh stiffness), against geometry.

L(phi) / L_mean with L_mean = b eps_alpha / cos(beta_b); see gearcli/model/contact_lines.py.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose

from gearcli.model.contact_lines import contact_length_factor, contact_length_range, contact_length_slope

GRID = np.linspace(0.0, 1.0, 200_001)[:-1]  # fine grid over one mesh period


@given(eps_alpha=st.floats(1.05, 2.6), eps_beta=st.floats(0.0, 3.5))
@settings(max_examples=60, deadline=None)
def test_mean_over_a_period_is_the_mean_length(eps_alpha, eps_beta):
    # The mean of L over a period is the plane's area over the line spacing: b eps_alpha / cos(beta_b),
    # i.e. a factor of 1. Midpoint-rule error on a 2e5 grid of a piecewise-linear (or step) function
    # with <= 8 kinks/steps per period: <= 8 x (1/2e5) x max jump (~2) ~ 1e-4.
    mean = contact_length_factor(GRID + 0.5 / GRID.size, eps_alpha, eps_beta).mean()
    assert_allclose(mean, 1.0, atol=2e-4)


@pytest.mark.parametrize("eps_alpha", [1.2, 1.6139, 1.99, 2.3])
def test_spur_is_the_rectangular_wave_between_floor_and_ceil_pairs(eps_alpha):
    # spur: L = (number of pairs) x b; mean b eps_alpha -> factor n / eps_alpha, n in {floor, ceil}
    f = contact_length_factor(GRID, eps_alpha, 0.0)
    pairs = np.rint(f * eps_alpha)
    assert_allclose(f * eps_alpha, pairs, atol=1e-12)  # whole numbers of pairs only
    assert set(np.unique(pairs)) == {math.floor(eps_alpha), math.ceil(eps_alpha)}
    # the two-pair zone lasts (eps_alpha - 1) of a base pitch when 1 < eps_alpha < 2 (grid resolution 5e-6)
    if eps_alpha < 2:
        assert_allclose(np.mean(pairs == 2), eps_alpha - 1.0, atol=1e-5)
    lo, hi = contact_length_range(eps_alpha, 0.0)
    assert_allclose([lo, hi], [math.floor(eps_alpha) / eps_alpha, math.ceil(eps_alpha) / eps_alpha], rtol=1e-12)


@pytest.mark.parametrize("eps_beta", [1.0, 2.0, 3.0])
@pytest.mark.parametrize("eps_alpha", [1.3, 1.6139, 2.2])
def test_integer_overlap_ratio_gives_constant_length(eps_alpha, eps_beta):
    # each line spans exactly eps_beta base pitches: the sum of clipped overlaps is eps_alpha eps_beta
    # for every phase (the classic "integer overlap ratio -> constant mesh stiffness")
    assert_allclose(contact_length_factor(GRID, eps_alpha, eps_beta), 1.0, rtol=1e-12)


def test_helical_single_line_lengths_by_hand():
    # eps_alpha = 1.5, eps_beta = 0.5, phi = 0.25: lines at x = 0.25 (covers [0.25, 0.75], all inside:
    # 0.5) and x = 1.25 (covers [1.25, 1.75], clipped at 1.5: 0.25); x = -0.75 covers [-0.75, -0.25]:
    # outside. Sum 0.75, over eps_alpha eps_beta = 0.75 -> factor 1.0. At phi = 0.9: x = 0.9 ([0.9, 1.4],
    # 0.5) and x = -0.1 ([-0.1, 0.4] -> 0.4); sum 0.9 -> 1.2.
    assert_allclose(contact_length_factor(0.25, 1.5, 0.5), 1.0, rtol=1e-14)
    assert_allclose(contact_length_factor(0.9, 1.5, 0.5), 1.2, rtol=1e-14)
    assert_allclose(contact_length_factor(np.array([1.25, -0.1]), 1.5, 0.5), [1.0, 1.2], rtol=1e-12)  # periodic


@given(phi=st.floats(0.0, 1.0), eps_alpha=st.floats(1.05, 2.6), eps_beta=st.floats(0.05, 2.5))
@settings(max_examples=80, deadline=None)
def test_slope_matches_finite_differences_away_from_kinks(phi, eps_alpha, eps_beta):
    h = 1e-7
    kinks = np.array([0.0, eps_alpha % 1.0, (eps_alpha - eps_beta) % 1.0, (-eps_beta) % 1.0, 1.0])
    if np.min(np.abs(phi - kinks)) < 10 * h:
        return  # the piecewise-linear L has no derivative at its kinks
    fd = (contact_length_factor(phi + h, eps_alpha, eps_beta) - contact_length_factor(phi - h, eps_alpha, eps_beta)) / (2 * h)
    # slope values are (integers)/(eps_alpha eps_beta) <= ~40; rounding of the difference ~ 1e-16/1e-7
    assert_allclose(contact_length_slope(phi, eps_alpha, eps_beta), fd, atol=1e-6)


def test_range_of_a_helical_mesh_by_hand():
    # eps_alpha = 1.5, eps_beta = 0.5, lines at phi - 1, phi, phi + 1: overlaps (phi - 0.5)+, 0.5 and
    # (0.5 - phi)+, total 0.5 + |phi - 0.5| in [0.5, 1.0]; over eps_alpha eps_beta = 0.75: [2/3, 4/3]
    lo, hi = contact_length_range(1.5, 0.5)
    assert_allclose([lo, hi], [2.0 / 3.0, 4.0 / 3.0], rtol=1e-9)
    phi = np.linspace(0.0, 1.0, 101)
    assert_allclose(contact_length_factor(phi, 1.5, 0.5), (0.5 + np.abs(phi % 1.0 - 0.5)) / 0.75, rtol=1e-12)


@given(phi=st.floats(-3.0, 3.0), eps_alpha=st.floats(1.05, 2.6), eps_beta=st.one_of(st.just(0.0), st.floats(0.0, 3.5)))
@settings(max_examples=100, deadline=None)
def test_scalar_form_used_by_the_rhs_matches_the_array_form(phi, eps_alpha, eps_beta):
    from gearcli.model.contact_lines import scalar_factor

    assert_allclose(scalar_factor(eps_alpha, eps_beta)(phi), contact_length_factor(phi, eps_alpha, eps_beta),
                    rtol=1e-12, atol=1e-12)
