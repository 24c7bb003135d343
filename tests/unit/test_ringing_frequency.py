"""The window-ringing fit refines a mode's frequency, not only its decay rate (gearcli.simulate.ringing).

configs/backlash_oscillator.toml (a Hertzian mesh with backlash, rattling lightly) linearises to a 66.1 Hz mode, but
its run-up rings at 64.4 Hz in the 0.44-1 s window (an independent least-squares fit of the run's F_t, frequency and
decay free: 2982 N at the window's start, decay time 1.35 s). Fitted at 66.1 Hz, a turn of phase over the window, the
warning read ±812 N decaying in 0.37 s and a window from 1.66 s on to settle it; that window rang with ±1134 N and
the next advice moved to 5.04 s, then 6.17 s. Here the same record in closed form: a free decay at 64.4 Hz beside the
51 Hz mesh excitation's forced line, fitted from the 66.1 Hz linearised mode."""

from __future__ import annotations

import math

import numpy as np
from numpy.testing import assert_allclose

from gearcli.simulate.ringing import fit_transient_terms

F_TRUE, SIGMA_TRUE, A_TRUE, PHASE = 64.4, 1 / 1.35, 2982.0, 0.7
F_LIN, SIGMA_LIN = 66.1, 2 * math.pi * 66.1 * 0.0065  # the linearised mode: 0.65 % of critical damping
F_MESH = 51.0


def _record() -> tuple[np.ndarray, np.ndarray]:
    t = 0.44 + np.arange(1121) / 2000.0  # the window 0.44-1 s at 2 kHz
    tau = t - t[0]
    x = (2981.7 + A_TRUE * np.exp(-SIGMA_TRUE * tau) * np.cos(2 * math.pi * F_TRUE * tau + PHASE)
         + 785.0 * np.cos(2 * math.pi * F_MESH * t + 0.3))
    return t, x


def test_a_mode_ringing_off_its_linearised_frequency_is_fitted_at_its_own():
    t, x = _record()
    forced = tuple(2 * math.pi * F_MESH * k for k in (1, 2, 3))
    terms, sigma, omega = fit_transient_terms(t, x[:, None], [(SIGMA_LIN, 2 * math.pi * F_LIN)], forced=forced)
    step_Hz = 0.25 / (t[-1] - t[0])  # the trials' spacing: a quarter of the window's resolution
    assert abs(omega[0] / (2 * math.pi) - F_TRUE) <= 0.5 * step_Hz + 1e-9
    assert_allclose(abs(terms[0, 0]), A_TRUE, rtol=0.03)
    assert_allclose(sigma[0, 0], SIGMA_TRUE, rtol=0.12)  # the decay-rate trials' step, 12 %
    end = abs(terms[0, 0]) * math.exp(-sigma[0, 0] * (t[-1] - t[0]))
    assert_allclose(end, A_TRUE * math.exp(-SIGMA_TRUE * (t[-1] - t[0])), rtol=0.05)


def test_a_mode_at_its_linearised_frequency_keeps_it():
    t = np.arange(2000) / 2000.0
    x = 100.0 + 50.0 * np.exp(-2.0 * t) * np.sin(2 * math.pi * 30.0 * t)
    terms, sigma, omega = fit_transient_terms(t, x[:, None], [(2.0, 2 * math.pi * 30.0)])
    assert_allclose(omega[0], 2 * math.pi * 30.0, rtol=1e-12)
    assert_allclose(abs(terms[0, 0]), 50.0, rtol=1e-6)
    assert_allclose(sigma[0, 0], 2.0, rtol=1e-9)
