"""The periodic steady state's parts on constructed inputs with known answers (no solver).

Period detection on maps whose periodic orbits are known in closed form: the logistic map
x -> r x (1 - x) has a stable fixed point 1 - 1/r for 1 < r < 3, a stable 2-cycle
x± = (r + 1 ± sqrt((r - 3)(r + 1))) / (2 r) for 3 < r < 1 + sqrt(6) (3.449), a stable 4-cycle up to
3.544, and is chaotic at r = 3.9 (May, Nature 261, 1976). Common periods of excitation sets by hand.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from gearcli.report.spectrum import mesh_orders, order_amplitude
from gearcli.simulate.periodic import (
    Excitation,
    boundary_residual,
    common_period,
    detect_period,
    history_needed,
    mesh_period_s,
    periods_cap,
    ripple_period_s,
)
from gearcli.simulate.results import REGIME_DOUBLE_SIDED, REGIME_NO_IMPACT, REGIME_SINGLE_SIDED
from gearcli.simulate.stats import mesh_response, time_fraction

RTOL = 1e-9
ATOL = np.array([1e-12])


def _first_repeat(states: list[np.ndarray]) -> tuple[int, int, float]:
    """Feed the states one by one, as the run does: (k, boundary index, residual) at the first repeat."""
    for n in range(2, len(states) + 1):
        rep = detect_period(states[max(0, n - history_needed()):n], RTOL, ATOL)
        if rep.k:
            return rep.k, n - 1, rep.residual
    return 0, len(states) - 1, math.inf


def _logistic(r: float, n: int, x0: float = 0.3) -> list[np.ndarray]:
    x, out = x0, []
    for _ in range(n):
        out.append(np.array([x]))
        x = r * x * (1.0 - x)
    return out


def test_fixed_point_of_the_logistic_map_is_period_1_at_its_closed_form():
    states = _logistic(2.8, 400)
    k, n, residual = _first_repeat(states)
    assert k == 1 and residual <= 1.0
    # the state found is the fixed point 1 - 1/r, to the tolerance the detector promises (rtol |x| + atol)
    assert abs(states[n][0] - (1 - 1 / 2.8)) <= RTOL * (1 - 1 / 2.8) + 1e-12 + 1e-9


def test_two_cycle_of_the_logistic_map_is_period_2_with_the_closed_form_points():
    r = 3.2
    states = _logistic(r, 600)
    k, n, _ = _first_repeat(states)
    assert k == 2
    root = math.sqrt((r - 3.0) * (r + 1.0))
    expected = sorted([(r + 1 + root) / (2 * r), (r + 1 - root) / (2 * r)])
    # within the detector's own tolerance: contraction of the 2-cycle is |f'(x+) f'(x-)| = |4 + 2r - r^2| = 0.16
    assert_allclose(sorted([states[n][0], states[n - 1][0]]), expected, rtol=1e-8)


def test_four_cycle_of_the_logistic_map_is_period_4():
    k, _, _ = _first_repeat(_logistic(3.5, 2000))
    assert k == 4


def test_chaotic_logistic_map_has_no_period():
    k, _, _ = _first_repeat(_logistic(3.9, 2000))
    assert k == 0


def test_quasi_periodic_rotation_has_no_period():
    # x_n on a circle turned by the golden angle each period: never repeats, though it comes close
    theta = 2 * math.pi * (math.sqrt(5) - 1) / 2
    states = [np.array([1 + math.cos(n * theta), 1 + math.sin(n * theta)]) for n in range(2000)]
    rep = [detect_period(states[max(0, n - history_needed()):n], RTOL, np.array([1e-12, 1e-12]))
           for n in range(2, 2000)]
    assert all(r.k == 0 for r in rep)


def test_a_dying_vibration_in_phase_with_7_periods_is_not_a_subharmonic():
    # a free vibration completing 9 cycles in 7 periods, decaying by 2 % per period towards the fixed point 1:
    # y_n - y_(n-7) is small early, but it is a transient; the detector waits and reports period-1
    rho, theta = 0.98, 2 * math.pi * 9 / 7
    states = [np.array([1.0 + 1e-3 * rho**n * math.cos(n * theta)]) for n in range(3000)]
    k, n, _ = _first_repeat(states)
    assert k == 1
    # and only once the transient is within the tolerance of the fixed point
    assert 1e-3 * rho**n <= 2 * (RTOL * 1.0 + 1e-12)


def test_boundary_residual_is_in_units_of_the_tolerance():
    # the worst state decides: 4e-9 / (1e-9 x 2 + 1e-12) = 1.999 for the first, 5e-12 / 1e-12 = 5 for the second
    now, then, atol = np.array([2.0, 0.0]), np.array([2.0 + 4e-9, 5e-12]), np.array([1e-12, 1e-12])
    assert_allclose(boundary_residual(now, then, 1e-9, atol), 5.0, rtol=1e-9)
    assert_allclose(boundary_residual(now[:1], then[:1], 1e-9, atol[:1]), 4e-9 / (2e-9 + 1e-12), rtol=1e-6)


# -------------------------------------------------------------------------------- common period
def test_mesh_and_ripple_periods_by_hand():
    # 17 teeth at 180 rpm: 51 Hz; order 2 at 600 rpm: 20 Hz
    assert_allclose(mesh_period_s(17, 180 * 2 * math.pi / 60), 1 / 51, rtol=1e-14)
    assert_allclose(ripple_period_s(2, 600 * 2 * math.pi / 60), 1 / 20, rtol=1e-14)


def test_common_period_of_rational_excitations_is_the_least_common_multiple():
    got = common_period([Excitation("a", 1 / 50), Excitation("b", 1 / 30), Excitation("c", 1 / 12)])
    assert got.exact
    assert_allclose(got.period_s, 1 / math.gcd(50, 30, 12) / 1.0, rtol=1e-12)  # 1/2 s: 50, 30, 12 Hz share 2 Hz


def test_common_period_of_the_seed_mesh_frequencies():
    # seed reducer at 600 rpm: 210 Hz, 210 x 17/51 = 70 Hz, 70 x 17/50 = 23.8 Hz; common frequency 1.4 Hz
    mesh_hz = [210.0, 70.0, 23.8]
    got = common_period([Excitation(f"stage {k + 1} mesh", 1 / f) for k, f in enumerate(mesh_hz)])
    assert got.exact
    assert_allclose(got.period_s, 1 / 1.4, rtol=1e-9)


def test_a_common_period_of_few_slow_but_many_fast_periods_is_found():
    # 20.3 Hz and 116.4 Hz: 203/10 and 1164/10 Hz with gcd(203, 1164) = 1 share 0.1 Hz, a 10 s common period holding
    # 203 of the slower periods and 1164 of the faster ones. It was reported "not a rational fraction" (the bound of
    # 1000 was put on the count of the faster periods, not on that of the slower ones the period spans).
    assert math.gcd(203, 1164) == 1
    got = common_period([Excitation("stage 1 mesh", 1 / 116.4), Excitation("load fluctuation 20.3 Hz", 1 / 20.3)])
    assert got.exact
    assert_allclose(got.period_s, 10.0, rtol=1e-9)
    # three helical stages 19/75, 19/68, 23/71 at 1450 rpm: mesh frequencies f1, f1 19/75, f1 19 23 / (75 68); over
    # 5100ths of f1 they are 5100, 1292 and 437 with gcd 1, so they share f1 / 5100: 437 periods of the slowest mesh
    f1 = 19 * 1450 / 60
    assert math.gcd(5100, 1292, 437) == 1
    mesh_hz = [f1, f1 * 19 / 75, f1 * 19 * 23 / (75 * 68)]
    got = common_period([Excitation(f"stage {k + 1} mesh", 1 / f) for k, f in enumerate(mesh_hz)])
    assert got.exact
    assert_allclose(got.period_s, 5100 / f1, rtol=1e-9)
    assert_allclose(got.period_s / (1 / mesh_hz[2]), 437, rtol=1e-9)


def test_a_common_period_beyond_1000_slowest_periods_is_not_used():
    # 77.7 Hz beside 2875/3 Hz (25 teeth at 2300 rpm): 233.1/3 and 2875/3 share 0.1/3 Hz, 2331 periods of 77.7 Hz
    got = common_period([Excitation("stage 1 mesh", 3 / 2875), Excitation("load fluctuation 77.7 Hz", 1 / 77.7)])
    assert not got.exact
    assert got.period_s == pytest.approx(1 / 77.7, rel=1e-15)
    assert "no common period" in got.source


def test_incommensurate_excitations_take_the_slowest_period_and_say_so():
    got = common_period([Excitation("stage 1 mesh", 1 / 51.0), Excitation("load fluctuation", 1 / (51.0 * math.sqrt(2)))])
    assert not got.exact
    assert got.period_s == pytest.approx(1 / 51.0, rel=1e-15)
    assert "no common period" in got.source


def test_no_excitation_has_no_common_period():
    assert common_period([]) is None


def test_periods_cap_is_the_duration_and_at_most_2000():
    assert periods_cap(1.3, 0.3, 0.1) == 10
    assert periods_cap(0.2, 0.3, 0.1) == 0
    assert periods_cap(1e4, 0.0, 1e-3) == 2000


# ------------------------------------------------------------------------- fractions and regimes
def test_time_fraction_of_a_sine_below_minus_half_is_one_third():
    # sin(2 pi t) < -1/2 on (7/12, 11/12) of each period: 1/3 of the time
    t = np.linspace(0.0, 3.0, 30001)
    flag = np.sin(2 * np.pi * t) < -0.5
    assert_allclose(time_fraction(t, flag, periodic=False), 1 / 3, atol=2 / 30000)  # one sample each crossing
    tp = np.linspace(0.0, 3.0, 30000, endpoint=False)  # whole periods without the closing sample
    assert_allclose(time_fraction(tp, np.sin(2 * np.pi * tp) < -0.5, periodic=True), 1 / 3, atol=2 / 30000)


def _response(force, pen, static=1000.0):
    t = np.linspace(0.0, 1.0, force.size)
    return mesh_response(t, np.ones_like(t, bool), pen * 1e3, force, pen, static)


def test_regime_classification():
    n = 1000
    loaded = _response(np.full(n, 900.0), np.full(n, 0.01))
    assert loaded["regime"] == REGIME_NO_IMPACT and loaded["contact_loss_fraction"] == 0.0
    f = np.full(n, 900.0)
    f[200:300] = 0.0
    single = _response(f, np.where(f > 0, 0.01, 0.0))
    assert single["regime"] == REGIME_SINGLE_SIDED
    assert_allclose(single["contact_loss_fraction"], 0.1, atol=2e-3)
    assert single["back_flank_fraction"] == 0.0
    pen = np.where(f > 0, 0.01, 0.0)
    f2, pen[250:280] = f.copy(), -0.002  # the back flank struck inside the gap
    f2[250:280] = -300.0
    double = _response(f2, pen)
    assert double["regime"] == REGIME_DOUBLE_SIDED
    assert_allclose(double["back_flank_fraction"], 0.03, atol=2e-3)
    # under load reversal the loaded flank is the back one: contact there is not a back-flank impact
    reversed_ = _response(-np.full(n, 900.0), np.full(n, -0.01), static=-1000.0)
    assert reversed_["regime"] == REGIME_NO_IMPACT and reversed_["back_flank_fraction"] == 0.0
    # a force that reverses without a sample out of contact: across a backlash the teeth crossed the gap between
    # samples (double-sided), without one there is no gap to cross and nothing strikes
    swing = 900.0 * np.sin(np.linspace(0.0, 6 * np.pi, n) + 0.1) + 400.0
    t = np.linspace(0.0, 1.0, n)
    crossing = [mesh_response(t, np.ones(n, bool), swing, swing, swing * 1e-5, 400.0, gapless=g) for g in (False, True)]
    assert [c["contact_loss_fraction"] for c in crossing] == [0.0, 0.0]
    assert [c["regime"] for c in crossing] == [REGIME_DOUBLE_SIDED, REGIME_NO_IMPACT]


def test_dte_statistics_rms_is_about_the_mean():
    t = np.linspace(0.0, 1.0, 4000, endpoint=False)
    q = 5.0 + 2.0 * np.sin(2 * np.pi * 10 * t)
    out = mesh_response(t, np.ones_like(t, bool), q, np.full_like(t, 100.0), np.full_like(t, 0.01), 100.0,
                        periodic=True)
    assert_allclose([out["dte_um"].mean, out["dte_um"].rms], [5.0, 2.0 / math.sqrt(2)], rtol=1e-12)
    assert_allclose([out["dte_um"].min, out["dte_um"].max], [3.0, 7.0], rtol=1e-6)


# ------------------------------------------------------------------------------ mesh orders
def test_mesh_order_amplitudes_exact_over_whole_periods():
    f = 51.0
    t = np.linspace(0.0, 2 / f, 800, endpoint=False)
    x = 3000 + 136 * np.cos(2 * np.pi * f * t + 0.3) + 29 * np.sin(4 * np.pi * f * t) + 3.7 * np.cos(6 * np.pi * f * t)
    got = [order_amplitude(t, x, h * f, whole_periods=True) for h in (1, 2, 3)]
    assert_allclose(got, [136, 29, 3.7], rtol=1e-10)


def test_mesh_order_amplitudes_of_a_window_that_is_not_whole_periods():
    # 20.37 periods, Hann-weighted: the orders come out to ~1 % of the largest line (leakage bound)
    f = 51.0
    t = np.linspace(0.0, 20.37 / f, 8000)
    x = 3000 + 136 * np.cos(2 * np.pi * f * t) + 29 * np.sin(4 * np.pi * f * t)
    orders = mesh_orders(t, x, 0.01 * x, (0.0, t[-1]), f)
    assert [o.order for o in orders] == [1, 2, 3]
    assert_allclose([o.tangential_N for o in orders[:2]], [136, 29], atol=0.01 * 136)
    assert orders[2].tangential_N < 0.01 * 136
    assert_allclose(orders[0].dte_um, 1.36, atol=0.0136)
