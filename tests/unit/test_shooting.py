"""Shooting on the period map (gearcli.simulate.shooting) against closed forms.

The scene is the one-degree-of-freedom mesh of tests/reference/oscillator.py without backlash: the pinion
turns at a prescribed constant speed, so the dynamic transmission error q obeys the linear equation

    m_e q'' + c q' + k q = F_s - m_e e'',   e = E cos(Omega t)

whose periodic response is q = p0 + X cos(Omega t - theta) with X = E r^2 / sqrt((1 - r^2)^2 + (2 zeta r)^2),
tan theta = 2 zeta r / (1 - r^2), r = Omega / omega_n, and whose free motion has the eigenvalues
lambda = -zeta omega_n +- i omega_n sqrt(1 - zeta^2): over the period T = 2 pi / Omega its Floquet
multipliers are exp(lambda T). The period map is affine, so one Newton step lands on the orbit.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from gearcli.model.outputs import sample
from gearcli.simulate.shooting import augmented_atol, floquet, integrate_shooting
from tests.reference.oscillator import WN, oscillator

ZETA, E, P0 = 0.05, 5e-6, 10e-6


def _shoot(model, engine: str = "python", rtol: float = 1e-10):
    found = integrate_shooting(model, "DOP853", rtol, steps=400, duration_s=1.0, window_start_s=None, y0=None,
                               max_nfev=10**7, fastest_rad_s=WN, engine=engine)
    assert not hasattr(found, "status"), getattr(found, "message", "")
    return found


def _window_dte(model, found):
    run = found.run
    w = (run.t >= found.window_s[0] - 1e-15)
    s = sample(model.layout, run.t[w], run.y[:, w])
    return run.t[w], s.connectors[0].dte_m


@pytest.mark.parametrize("r", [0.5, 1.3])
def test_linear_oscillator_orbit_in_one_newton_step_amplitude_and_phase_exact(r):
    model = oscillator(r, te_m=(E,), zeta=ZETA, p0_m=P0)
    found = _shoot(model)
    st = found.steady
    assert st.method == "shooting" and st.converged and st.iterations == 1 and st.residual <= 1.0
    t, q = _window_dte(model, found)
    omega = r * WN
    X = E * r * r / math.sqrt((1 - r * r) ** 2 + (2 * ZETA * r) ** 2)
    theta = math.atan2(2 * ZETA * r, 1 - r * r)
    exact = P0 + X * np.cos(omega * t - theta)
    assert_allclose(q, exact, rtol=0, atol=1e-6 * X)
    assert_allclose(found.window_s[1] - found.window_s[0], 2 * math.pi / omega, rtol=1e-12)


@pytest.mark.parametrize("r", [0.5, 1.3])
def test_floquet_multipliers_are_exp_lambda_T(r):
    model = oscillator(r, te_m=(E,), zeta=ZETA, p0_m=P0)
    st = _shoot(model).steady
    T = 2 * math.pi / (r * WN)
    lam = complex(-ZETA * WN, WN * math.sqrt(1 - ZETA**2))
    expected = sorted([np.exp(lam * T), np.exp(lam.conjugate() * T)], key=lambda m: m.imag)
    got = sorted((complex(*m) for m in st.multipliers), key=lambda m: m.imag)
    assert_allclose(np.array(got), np.array(expected), atol=1e-6)
    assert st.stable and st.bifurcation == "none"
    assert_allclose(st.spectral_radius, math.exp(-ZETA * WN * T), rtol=1e-6)


def test_finite_difference_monodromy_where_the_variational_equations_are_unavailable():
    model = oscillator(0.5, te_m=(E,), zeta=ZETA, p0_m=P0)
    generated = model.rhs
    model.rhs = lambda t, y: generated(t, y)  # a right-hand side replaced in Python: no Jacobian goes with it
    st = _shoot(model, rtol=1e-10).steady
    assert st.monodromy == "finite differences" and st.converged and st.iterations == 1
    T = 2 * math.pi / (0.5 * WN)
    assert_allclose(st.spectral_radius, math.exp(-ZETA * WN * T), rtol=1e-4)


def test_compiled_variational_equations_equal_scipys():
    pytest.importorskip("numba")
    model = oscillator(1.3, te_m=(E,), zeta=ZETA, p0_m=P0)
    a, b = _shoot(model, "python").steady, _shoot(model, "compiled").steady
    assert b.method == "shooting" and b.iterations == 1
    assert_allclose(np.array(b.multipliers), np.array(a.multipliers), atol=1e-7)


def test_floquet_classification():
    # real multipliers near +1 (a fold: the branch turns back), near -1 (a period doubling); a lightly damped
    # mode's complex pair near the unit circle is no bifurcation
    fold = floquet(np.diag([0.95, 0.3]))
    assert fold.bifurcation == "fold" and fold.stable and fold.critical == (0.95, 0.0)
    pd = floquet(np.diag([-0.97, 0.2]))
    assert pd.bifurcation == "period doubling"
    a = 0.99 * np.array([[math.cos(2.0), -math.sin(2.0)], [math.sin(2.0), math.cos(2.0)]])
    ring = floquet(a)
    assert ring.bifurcation == "none" and ring.stable and abs(ring.spectral_radius - 0.99) < 1e-12
    assert not floquet(np.diag([1.2, 0.1])).stable


def test_monodromy_tolerances_scale_with_the_states():
    atol = np.array([1e-12, 1e-6, 0.0])  # a deflection (m), a speed (rad/s), a quadrature
    out = augmented_atol(atol, 2, 1e-6, factor=1.0)
    # Phi[i, k] maps a change of state k of its natural size atol_k / rtol to state i: held to atol_i
    assert_allclose(out[3:].reshape(2, 2, order="F") * (atol[:2] / 1e-6)[None, :], np.array([atol[:2]] * 2).T)


def test_fold_location_from_two_multipliers_of_a_saddle_node_branch():
    # near a saddle-node the real multiplier goes as mu = 1 - c sqrt(p - p*): two points give p* exactly
    from gearcli.sweep.continuation import fold_estimate

    p_star, c = 1404.09, 0.05
    mu_a, mu_b = (1 - c * math.sqrt(p - p_star) for p in (1412.0, 1406.0))  # a branch swept down to its end
    assert_allclose(fold_estimate(1412.0, mu_a, 1406.0, mu_b), p_star, rtol=1e-12)
    assert fold_estimate(1406.0, mu_b, 1412.0, mu_a) is None  # moving away from +1: no fold ahead


def test_kernel_lu_with_row_spans_solves_block_diagonal_systems_as_the_dense_loops():
    # the augmented Jacobian of the variational equations is block diagonal: the kernel's LU keeps each row's
    # nonzero span and skips the exact zeros outside it; the numbers are those of the dense loops, bit for bit
    pytest.importorskip("numba")
    import scipy.linalg

    from gearcli import engine

    k = engine.load(quiet=True).kernel
    rng = np.random.default_rng(3)
    for dtype in (np.float64, np.complex128):
        blocks = [rng.normal(size=(m, m)) + (1j * rng.normal(size=(m, m)) if dtype == np.complex128 else 0)
                  for m in (5, 3, 3, 3)]
        for blk in blocks:
            blk[0, 0] = 0.0  # a row exchange inside each block
        A = scipy.linalg.block_diag(*blocks).astype(dtype)
        b = rng.normal(size=A.shape[0]).astype(dtype)
        n = A.shape[0]
        dense, spans = A.copy(), A.copy()
        p_dense, p_spans = np.zeros(n, dtype=np.int64), np.zeros(3 * n, dtype=np.int64)
        x_dense, x_spans = b.copy(), b.copy()
        k.lu_factor(dense, p_dense)
        k.lu_solve(dense, p_dense, x_dense)
        k.lu_factor(spans, p_spans)
        k.lu_solve(spans, p_spans, x_spans)
        np.testing.assert_array_equal(x_spans, x_dense)
        assert_allclose(A @ x_spans, b, atol=1e-10 * np.linalg.cond(A))
        # each row's span stays inside its block
        starts = np.repeat([0, 5, 8, 11], [5, 3, 3, 3])
        assert np.all(p_spans[n:2 * n] >= starts) and np.all(p_spans[2 * n:] <= starts + np.repeat([5, 3, 3, 3],
                                                                                                      [5, 3, 3, 3]))
