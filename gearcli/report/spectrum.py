"""Dominant frequency of a mesh force over the steady window (numpy FFT, no scipy needed).

The force is detrended (least-squares line removed), multiplied by a Hann window and transformed
with a real FFT. The amplitude is scaled by 2 / sum(w), so a sine of amplitude A shows a peak of
about A. The frequency resolution is 1 / T with T = n dt the record length; with a Hann window a
spectral line spreads over about ±2 bins, which is also the tolerance used to name the peak.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from gearcli.report.result import Spectrum

MIN_SAMPLES = 16
#: relative std (to max(|mean|, 1 N)) below which a force is treated as constant: no peak to name
FLAT_RELATIVE = 1e-9
#: a peak "matches" a line when it lies within this many bins of it (Hann main lobe half-width)
MATCH_BINS = 2.0


def window_mask(time_s: np.ndarray, window_s: tuple[float, float]) -> np.ndarray:
    """Samples inside the closed steady window [from, to] (a small slack for rounding of t)."""
    eps = 1e-9 * max(1.0, abs(window_s[1]))
    return (time_s >= window_s[0] - eps) & (time_s <= window_s[1] + eps)


def force_spectrum(
    time_s: np.ndarray,
    force_N: np.ndarray,
    window_s: tuple[float, float],
    *,
    stage: int,
    mesh_frequency_Hz: float,
    natural_frequencies_Hz: Sequence[float] = (),
) -> Spectrum:
    """Hann-windowed amplitude spectrum of the detrended force over ``window_s``; see the module doc."""
    mask = window_mask(np.asarray(time_s, float), window_s)
    t = np.asarray(time_s, float)[mask]
    f = np.asarray(force_N, float)[mask]
    n = t.size
    if n < MIN_SAMPLES or t[-1] <= t[0]:
        empty = np.zeros(0)
        return Spectrum(stage, empty, empty, None, 0.0, float("inf") if n < 2 else 1.0 / (t[-1] - t[0]),
                        0.0, window_s, mesh_frequency_Hz, "too few samples in the window")
    dt = (t[-1] - t[0]) / (n - 1)
    x = t - t[0]
    detrended = f - np.polyval(np.polyfit(x, f, 1), x)
    w = np.hanning(n)
    amplitude = np.abs(np.fft.rfft(detrended * w)) * 2.0 / w.sum()
    freqs = np.fft.rfftfreq(n, dt)
    resolution = 1.0 / (n * dt)
    if np.std(detrended) <= FLAT_RELATIVE * max(abs(float(np.mean(f))), 1.0):
        return Spectrum(stage, freqs, amplitude, None, 0.0, resolution, freqs[-1], window_s,
                        mesh_frequency_Hz, "no fluctuation")
    k = 1 + int(np.argmax(amplitude[1:]))  # skip the DC bin
    peak = float(freqs[k])
    return Spectrum(stage, freqs, amplitude, peak, float(amplitude[k]), resolution, float(freqs[-1]), window_s,
                    mesh_frequency_Hz, name_peak(peak, resolution, mesh_frequency_Hz, natural_frequencies_Hz))


def name_peak(peak_Hz: float, resolution_Hz: float, mesh_Hz: float, natural_Hz: Sequence[float]) -> str:
    """The nearest known line within ±MATCH_BINS bins: a mesh harmonic or a natural frequency."""
    lines: list[tuple[float, str]] = []
    if mesh_Hz > 0:
        lines.append((mesh_Hz, "mesh frequency"))
        lines += [(h * mesh_Hz, f"mesh harmonic {h}") for h in (2, 3)]
    lines += [(fn, f"natural frequency {j}") for j, fn in enumerate(natural_Hz, start=1) if fn > 0]
    best: tuple[float, str] | None = None
    for f_line, name in lines:
        d = abs(f_line - peak_Hz)
        if d <= MATCH_BINS * resolution_Hz and (best is None or d < best[0]):
            best = (d, name)
    return best[1] if best else "none"
