"""The report's dominant mesh-force frequency is the strongest line, not the largest Hann bin (trial tr25a).

A TE-excited two-stage train (19/75 then 19/68 at 1450 rpm, TE 2.0 / 0.6 um on stage 1) had stage 1's F_t lines
at 459.17 Hz (390.0 N, an independent solve_ivp model: 389.99 N) and 918.33 Hz (353.3 N) over a 0.16 s window
(resolution 6.25 Hz): the first lies 73.47 bins from DC, half a bin off, where the Hann window shows it at ~0.85 of
its amplitude, so the 918 Hz bin was the largest and the report named "918.2 Hz, 353 N, mesh harmonic 2" the
dominant peak. Reference here: the same two lines in closed form (sines of known amplitude and frequency).
"""

from __future__ import annotations

import numpy as np
import pytest

from gearcli.report.spectrum import force_spectrum


def _record(a1: float, a2: float) -> tuple[np.ndarray, np.ndarray]:
    t = np.linspace(0.14, 0.30, 1601)  # the scene's window: 1601 samples 0.1 ms apart
    f1 = 1450 / 60 * 19  # 459.17 Hz, between two bins
    force = 2914.0 + a1 * np.sin(2 * np.pi * f1 * t + 0.3) + a2 * np.sin(2 * np.pi * 2 * f1 * t - 1.1)
    return t, force


def test_strongest_line_between_bins_is_the_dominant_peak():
    t, force = _record(390.0, 353.3)
    sp = force_spectrum(t, force, (0.14, 0.30), stage=1, mesh_frequency_Hz=1450 / 60 * 19)
    assert abs(sp.peak_frequency_Hz - 459.17) <= sp.resolution_Hz  # the bin holding the 459 Hz line
    assert sp.peak_amplitude_N == pytest.approx(390.0, rel=2e-3)
    assert sp.matches == "mesh frequency"


def test_a_stronger_line_on_a_bin_stays_the_dominant_peak():
    t, force = _record(300.0, 353.3)  # now the 918 Hz line is the stronger one
    sp = force_spectrum(t, force, (0.14, 0.30), stage=1, mesh_frequency_Hz=1450 / 60 * 19)
    assert abs(sp.peak_frequency_Hz - 918.33) <= sp.resolution_Hz
    assert sp.peak_amplitude_N == pytest.approx(353.3, rel=2e-3)
    assert sp.matches == "mesh harmonic 2"
