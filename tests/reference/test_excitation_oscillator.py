"""The transmission-error excited mesh against independent references (tests/reference/oscillator.py):

- linear limit (no backlash, exponent 1): the steady DTE is the closed-form response of a single degree
  of freedom to base excitation, q - q_s = X cos(Omega t + psi - theta) with, for r = Omega / omega_n,
  X = e r^2 / sqrt((1 - r^2)^2 + (2 zeta r)^2), tan(theta) = 2 zeta r / (1 - r^2) (m_e q'' + c q' + k q =
  F_s - m_e e'', e = E cos(Omega t + psi): the forcing m_e Omega^2 E cos(...)), and q_s = F_s / k;
- backlash (Kahraman & Singh 1990): no impact at low excitation with the mean DTE at the static deflection
  plus half the backlash; single-sided impacts near resonance; double-sided at high excitation and low
  load; two coexisting steady responses inside the softening hysteresis band;
- the energy balance with the TE's work in the input work.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose
from oscillator import SAMPLES, K, mesh_rad_s, oscillator, run, tail

E = 5e-6  # m
P0 = 10e-6  # m: static deflection F_s / k


def fit(t: np.ndarray, q: np.ndarray, om: float) -> tuple[float, float, float]:
    """Least squares of q = a0 + a cos(om t) + b sin(om t) over whole periods: (mean, amplitude, phase)."""
    A = np.column_stack([np.ones_like(t), np.cos(om * t), np.sin(om * t)])
    (a0, a, b), *_ = np.linalg.lstsq(A, q, rcond=None)
    return a0, math.hypot(a, b), math.atan2(-b, a)


@pytest.mark.parametrize("r", [0.3, 0.6, 0.85, 0.97, 1.0, 1.03, 1.2, 1.5, 2.0])
def test_linear_dte_is_the_closed_form_sdof_response(r):
    zeta, psi = 0.1, 0.4
    model = oscillator(r, te_m=(E,), te_phase_rad=(psi,), zeta=zeta)
    om = mesh_rad_s(model)
    # transients decay as exp(-zeta w_n t): 14 / (zeta w_n) leaves exp(-14) ~ 1e-6 of the start's offset
    settle = math.ceil(14.0 / (zeta * 2 * math.pi * 1000.0) * om / (2 * math.pi))
    t, q, it, s = run(model, settle + 10, q0=P0 + E * math.cos(psi), rtol=1e-10)
    mean, amp, phase = fit(tail(t, 10), tail(q, 10), om)
    X = E * r**2 / math.sqrt((1 - r**2) ** 2 + (2 * zeta * r) ** 2)
    theta = math.atan2(2 * zeta * r, 1 - r**2)
    assert_allclose(amp, X, rtol=1e-4, err_msg=f"r = {r}")
    assert abs(math.remainder(phase - (psi - theta), 2 * math.pi)) < 1e-4, f"r = {r}: phase {phase}"
    assert_allclose(mean, P0, rtol=1e-6)  # F_s / k
    # the energy balance with the TE's work in the input work, relative to the (smallest) damping loss
    en = model.energy(s, it.y)
    assert abs(en.residual_J) < 1e-6 * en.damping_loss_J


def _regime(q: np.ndarray, half_gap: float) -> str:
    """No impact (always on the drive flank), single-sided (leaves it, never reaches the back flank),
    double-sided (reaches the back flank)."""
    if q.min() > half_gap:
        return "no impact"
    return "double-sided" if q.min() < -half_gap else "single-sided"


B = 1e-4  # m of backlash: a gap of 50 um on either side


def test_no_impact_mean_dte_is_static_deflection_plus_half_backlash():
    # e = 0.5 um at resonance: the linear amplitude e / (2 zeta) = 5 um stays below p0 = 10 um
    model = oscillator(1.0, te_m=(0.5e-6,), backlash_m=B)
    t, q, _, _ = run(model, 300, q0=P0 + B / 2 + 0.5e-6)
    assert _regime(tail(q, 20), B / 2) == "no impact"
    mean, amp, _ = fit(tail(t, 20), tail(q, 20), mesh_rad_s(model))
    assert_allclose(mean, P0 + B / 2, rtol=1e-7)  # F_s / k + b / 2, from statics
    assert_allclose(amp, 0.5e-6 / (2 * 0.05), rtol=1e-4)  # and the linear resonance amplitude


def test_single_and_double_sided_impacts_as_published():
    # near resonance, e = 5 um: the linear amplitude (50 um) exceeds p0: the drive flank separates;
    # light load (p0 = 2 um) and e = 20 um: the gear crosses the backlash and hits the back flank
    single = oscillator(0.9, te_m=(E,), backlash_m=B)
    t, q, _, s = run(single, 300, q0=P0 + B / 2)
    assert _regime(tail(q, 20), B / 2) == "single-sided"
    assert _reported(t, s) == "single-sided impact"
    double = oscillator(0.8, te_m=(4 * E,), backlash_m=B, p0_m=2e-6)
    t, q, _, s = run(double, 300, q0=2e-6 + B / 2)
    assert _regime(tail(q, 20), B / 2) == "double-sided"
    assert _reported(t, s) == "double-sided impact"
    assert (tail(s.connectors[0].force, 20) < 0).any()  # the back flank pushes
    quiet = oscillator(0.6, te_m=(E,), backlash_m=B)
    t, q, _, s = run(quiet, 300, q0=P0 + B / 2)
    assert _regime(tail(q, 20), B / 2) == "no impact" and _reported(t, s) == "no impact"


def _reported(t, s) -> str:
    """The regime gearcli reports over the last 20 periods (gearcli.simulate.stats.mesh_response)."""
    from gearcli.simulate.stats import mesh_response

    mask = np.zeros(t.size, bool)
    mask[-(20 * SAMPLES + 1):-1] = True
    ms = s.connectors[0]
    return mesh_response(t, mask, ms.dte_m * 1e6, ms.force, ms.penetration_m * 1e3, K * P0)["regime"]


def test_coexisting_responses_inside_the_hysteresis_band():
    # r = 0.75: from rest on the static deflection the gear stays in contact (linear amplitude
    # e r^2/|1 - r^2| ~ 6.4 um < p0); thrown off the flank it settles on the impacting branch instead
    model = oscillator(0.75, te_m=(E,), backlash_m=B)
    _, quiet, _, _ = run(model, 400, q0=P0 + B / 2)
    _, loud, _, _ = run(model, 400, q0=P0 + B / 2, qd0=60e-6 * 2 * math.pi * 1000.0)
    a_quiet = np.ptp(tail(quiet, 20)) / 2
    a_loud = np.ptp(tail(loud, 20)) / 2
    r = 0.75
    assert_allclose(a_quiet, E * r**2 / math.sqrt((1 - r**2) ** 2 + (0.1 * r) ** 2), rtol=1e-3)
    assert _regime(tail(quiet, 20), B / 2) == "no impact"
    assert _regime(tail(loud, 20), B / 2) == "single-sided"
    assert a_loud > 3 * a_quiet
    # both are steady: the last two groups of 10 periods repeat
    for q in (quiet, loud):
        assert_allclose(tail(q, 10), tail(q, 20)[:10 * SAMPLES], atol=1e-4 * np.ptp(tail(q, 20)))
