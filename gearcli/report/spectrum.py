"""Dominant frequency of a mesh force over the steady window (numpy FFT, no scipy needed), and the
amplitudes of the mesh orders (1x, 2x, 3x the mesh frequency) in the force and the DTE.

The force is detrended (least-squares line removed), multiplied by a Hann window and transformed
with a real FFT. The amplitude is scaled by 2 / sum(w), so a sine of amplitude A shows a peak of
A at its own frequency; between two bins the FFT's largest bin shows up to 15 % less (scalloping), so the
peak's amplitude is the maximum of the same windowed transform within half a bin of the largest
(:func:`peak_line_amplitude`). The frequency resolution is 1 / T with T = n dt the record length; with a
Hann window a spectral line spreads over about ±2 bins, which is also the tolerance used to name the peak.

A window of whole periods of a repeating response (a periodic steady state's orbit, ``whole_periods``) is
transformed as it is: the force less its
mean, without the window's closing sample (the first of the next period), with no window function. Every line of
the periodic response is a harmonic of the window's period and so lies on a bin, whose amplitude 2 |X_k| / n is the
line's exactly (a Hann window there would mix each bin with half of its neighbours': configs/periodic_linear_mesh.toml
showed its 51 Hz peak at 115 N beside the exact 135.9 N of the mesh-order table; a least-squares line would take a
periodic record's own slope out as a trend).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from gearcli.report.result import MeshOrder, Spectrum

MIN_SAMPLES = 16
#: relative std (to max(|mean|, 1 N)) below which a force is treated as constant: no peak to name
FLAT_RELATIVE = 1e-9
#: a peak "matches" a line when it lies within this many bins of it (Hann main lobe half-width)
MATCH_BINS = 2.0
MESH_ORDERS = (1, 2, 3)  # the mesh orders listed per stage
#: a Hann window shows a line between two bins down to 0.849 of its amplitude (half a bin off): a local maximum above
#: this share of the largest bin may be the strongest line (margin for neighbouring lines' leakage)
SCALLOP_FLOOR = 0.8
MAX_CANDIDATES = 8  # the strongest local maxima above SCALLOP_FLOOR whose line amplitude is measured
#: a frequency within this share of a bin of a harmonic of a whole-periods window is that harmonic (a mesh frequency
#: from the same speeds as the orbit's period differs from it by round-off); farther off it is no line of the response
ON_BIN = 1e-3


def order_amplitude(time_s: np.ndarray, x: np.ndarray, frequency_Hz: float, *, whole_periods: bool) -> float:
    """Amplitude of the component of ``x`` at ``frequency_Hz`` (a sine of amplitude A gives A).

    ``whole_periods``: the samples cover whole periods of the line on a uniform grid without their closing
    sample (a periodic steady state): the plain discrete Fourier coefficient ``2 |mean(x e^(-i w t))|``,
    exact for every harmonic of the period, and 0 at a frequency that is none (within :data:`ON_BIN` of a bin): a
    periodic response has no line between its harmonics, where the coefficient would only measure the leakage of
    those it has (a stage without excitation of its own behind an excited one: the orbit's period is the excited
    mesh's, and the quiet stage's mesh frequency 127.5 Hz, 0.26 of the 490 Hz period's bin, showed 525 N where the
    response has none). Otherwise the record is detrended and Hann-weighted,
    ``2 |sum(w x e^(-i w t))| / sum(w)``: no leakage from the record's ends, the other lines suppressed
    once they lie more than ~2 resolution bins away.
    """
    t = np.asarray(time_s, float)
    x = np.asarray(x, float)
    if t.size < 2 or frequency_Hz <= 0:
        return 0.0
    phase = np.exp(-2j * np.pi * frequency_Hz * (t - t[0]))
    if whole_periods:
        cycles = frequency_Hz * (t[-1] - t[0]) * t.size / (t.size - 1)  # over the window, its closing sample left out
        if abs(cycles - round(cycles)) > ON_BIN:  # no harmonic of the period: the periodic response has no line there
            return 0.0
        return float(2.0 * abs(np.mean((x - x.mean()) * phase)))
    u = t - t[0]
    detrended = x - np.polyval(np.polyfit(u, x, 1), u)
    w = np.hanning(t.size)
    return _hann_line(w * detrended, phase, float(w.sum()))


def _hann_line(weighted: np.ndarray, phase: np.ndarray, w_sum: float) -> float:
    """``2 |sum(w x e^(-i w t))| / sum(w)`` of the Hann-weighted detrended record ``weighted`` at the line whose
    ``e^(-i w t)`` is ``phase``: the amplitude of a sine there."""
    return float(2.0 * abs(np.sum(weighted * phase)) / w_sum)


def peak_line_amplitude(u: np.ndarray, weighted: np.ndarray, w_sum: float, freqs: np.ndarray, k: int,
                        bin_amplitude: float) -> float:
    """Amplitude of the line whose FFT peak is bin ``k``: the largest ``2 |sum(w x e^(-i 2 pi f u))| / sum(w)``
    over f within half a bin of the peak bin (where a line lies whose nearest bin is ``k``; never down to DC;
    ``weighted`` = the Hann-weighted detrended record, ``u`` its times from the first sample). An isolated sine of
    amplitude A gives A wherever it lies between the bins, where the bin itself shows down to 0.85 A (Hann
    scalloping); never below the bin's own value."""
    from scipy.optimize import minimize_scalar  # lazy: only a report with a fluctuating force needs it

    half = 0.5 * float(freqs[1] - freqs[0])
    lo, hi = max(float(freqs[k]) - half, float(freqs[0]) + half), min(float(freqs[k]) + half, float(freqs[-1]))
    if hi <= lo:
        return bin_amplitude

    def negative(f: float) -> float:
        return -_hann_line(weighted, np.exp(-2j * np.pi * f * u), w_sum)

    best = minimize_scalar(negative, bounds=(lo, hi), method="bounded",
                           options={"xatol": 1e-4 * (freqs[1] - freqs[0])})
    return max(bin_amplitude, -float(best.fun))


def dominant_line(u: np.ndarray, weighted: np.ndarray, w_sum: float, freqs: np.ndarray,
                  amplitude: np.ndarray) -> tuple[int, float]:
    """(bin, line amplitude) of the strongest line of a Hann-weighted spectrum: the largest line amplitude
    (:func:`peak_line_amplitude`) over the local maxima whose bin shows at least :data:`SCALLOP_FLOOR` of the
    largest bin (DC left out). A line between two bins shows down to 0.85 of its amplitude in its bin, so the
    largest bin is not always the strongest line's: a TE-excited stage's 390 N line at 459.2 Hz, 73.47 bins, showed
    less than the 353 N line at 918.3 Hz, 146.9 bins, which was named the dominant peak."""
    a = amplitude[1:]
    top = float(a.max())
    inner = np.ones(a.size, bool)
    inner[1:] &= a[1:] >= a[:-1]
    inner[:-1] &= a[:-1] >= a[1:]
    candidates = 1 + np.flatnonzero(inner & (a >= SCALLOP_FLOOR * top))
    candidates = candidates[np.argsort(amplitude[candidates])[::-1][:MAX_CANDIDATES]]
    best = (int(candidates[0]), -1.0)
    for k in candidates:
        line = peak_line_amplitude(u, weighted, w_sum, freqs, int(k), float(amplitude[k]))
        if line > best[1]:
            best = (int(k), line)
    return best


def mesh_orders(time_s: np.ndarray, force_N: np.ndarray, dte_um: np.ndarray | None, window_s: tuple[float, float],
                mesh_frequency_Hz: float, *, whole_periods: bool = False,
                orders: Sequence[int] = MESH_ORDERS) -> tuple[MeshOrder, ...]:
    """F_t (and DTE) amplitudes at ``orders`` x the mesh frequency over ``window_s`` (:func:`order_amplitude`;
    ``whole_periods`` leaves out the window's closing sample, the first of the next period); an order at or above
    the samples' Nyquist frequency (:func:`nyquist_Hz`) has no amplitude (None): the samples alias it."""
    t = np.asarray(time_s, float)
    mask = window_mask(t, window_s)
    if whole_periods:
        mask &= t < window_s[1] - 1e-9 * max(1.0, abs(window_s[1]))
    if mask.sum() < MIN_SAMPLES or mesh_frequency_Hz <= 0:
        return ()
    out = []
    nyquist = nyquist_Hz(t[mask])
    for h in orders:
        f = h * mesh_frequency_Hz
        if f >= nyquist:  # the samples cannot hold it: the projection would measure an alias (2 f_N - f)
            out.append(MeshOrder(h, f, None, None))
            continue
        dte = None if dte_um is None else order_amplitude(t[mask], np.asarray(dte_um)[mask], f,
                                                           whole_periods=whole_periods)
        out.append(MeshOrder(h, f, order_amplitude(t[mask], np.asarray(force_N)[mask], f, whole_periods=whole_periods),
                             dte))
    return tuple(out)


def nyquist_Hz(t: np.ndarray) -> float:
    """Half the sample rate of the window's samples, less one resolution bin 1/T: an order within a bin of it
    overlaps its own mirror image 2 f_N − f in the Hann main lobe (and exactly at f_N its sine part is invisible)."""
    span = float(t[-1] - t[0])
    dt = span / (t.size - 1)
    return 0.5 / dt - 1.0 / (t.size * dt)


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
    dte_um: np.ndarray | None = None,
    whole_periods: bool = False,
    other_meshes_Hz: Sequence[tuple[int, float]] = (),
    damped_modes: Sequence[tuple[float, float]] = (),
) -> Spectrum:
    """Hann-windowed amplitude spectrum of the detrended force over ``window_s`` (``whole_periods``: the plain DFT
    of the force less its mean over the window's whole periods); see the module doc. The
    mesh orders (:func:`mesh_orders`) are listed too, from ``dte_um`` as well when it is given.
    ``other_meshes_Hz``: (stage, mesh frequency) of the train's other stages, whose harmonics the peak may be
    (:func:`name_peak`)."""
    mask = window_mask(np.asarray(time_s, float), window_s)
    if whole_periods:  # the closing sample is the next period's first
        mask &= np.asarray(time_s, float) < window_s[1] - 1e-9 * max(1.0, abs(window_s[1]))
    t = np.asarray(time_s, float)[mask]
    f = np.asarray(force_N, float)[mask]
    n = t.size
    if n < MIN_SAMPLES or t[-1] <= t[0]:
        empty = np.zeros(0)
        span = (t[-1] - t[0]) if n >= 2 else (window_s[1] - window_s[0])  # a window of < 2 samples: its length
        return Spectrum(stage, empty, empty, None, 0.0, 1.0 / span if span > 0 else 0.0,
                        0.0, window_s, mesh_frequency_Hz, "too few samples in the window")
    dt = (t[-1] - t[0]) / (n - 1)
    x = t - t[0]
    if whole_periods:  # every line on a bin: the plain DFT's bins are the lines' amplitudes (module text)
        fluctuation = f - np.mean(f)
        amplitude = np.abs(np.fft.rfft(fluctuation)) * 2.0 / n
        if n % 2 == 0:
            amplitude[-1] /= 2.0  # the Nyquist bin has no mirror image
    else:
        fluctuation = f - np.polyval(np.polyfit(x, f, 1), x)
        w = np.hanning(n)
        amplitude = np.abs(np.fft.rfft(fluctuation * w)) * 2.0 / w.sum()
    freqs = np.fft.rfftfreq(n, dt)
    resolution = 1.0 / (n * dt)
    if np.std(fluctuation) <= FLAT_RELATIVE * max(abs(float(np.mean(f))), 1.0):
        return Spectrum(stage, freqs, amplitude, None, 0.0, resolution, freqs[-1], window_s,
                        mesh_frequency_Hz, "no fluctuation", whole_periods=whole_periods)
    if whole_periods:
        k = 1 + int(np.argmax(amplitude[1:]))  # skip the DC bin
        peak_amplitude = float(amplitude[k])
    else:
        k, peak_amplitude = dominant_line(x, fluctuation * w, float(w.sum()), freqs, amplitude)
    peak = float(freqs[k])
    orders = mesh_orders(time_s, force_N, dte_um, window_s, mesh_frequency_Hz, whole_periods=whole_periods)
    return Spectrum(stage, freqs, amplitude, peak, peak_amplitude, resolution, float(freqs[-1]), window_s,
                    mesh_frequency_Hz, name_peak(peak, resolution, mesh_frequency_Hz, natural_frequencies_Hz,
                                                 other_meshes_Hz, damped_modes), orders, whole_periods)


def name_peak(peak_Hz: float, resolution_Hz: float, mesh_Hz: float, natural_Hz: Sequence[float],
              other_meshes_Hz: Sequence[tuple[int, float]] = (),
              damped_modes: Sequence[tuple[float, float]] = ()) -> str:
    """The nearest known line within ±MATCH_BINS bins: a mesh harmonic (of this stage's mesh, or of another stage's,
    ``other_meshes_Hz`` = (stage, mesh frequency): a mesh's excitation reaches every mesh of the train through the
    shafts, so a force may be dominated by a neighbour's line) or a natural frequency; on a tie this stage's own
    mesh line first, then the other stages' in their order, then the natural frequencies. Where none of them
    matches, a damped mode (f_d, ζ) of ``damped_modes``: a ringing the undamped modes do not place, as a drum's
    mode against a motor whose slip damping holds it (the undamped free chain puts that mode elsewhere)."""
    lines: list[tuple[float, str]] = []
    if mesh_Hz > 0:
        lines.append((mesh_Hz, "mesh frequency"))
        lines += [(h * mesh_Hz, f"mesh harmonic {h}") for h in (2, 3)]
    for stage, f_mesh in other_meshes_Hz:
        if f_mesh > 0:
            lines.append((f_mesh, f"stage {stage} mesh frequency"))
            lines += [(h * f_mesh, f"stage {stage} mesh harmonic {h}") for h in (2, 3)]
    lines += [(fn, f"natural frequency {j}") for j, fn in enumerate(natural_Hz, start=1) if fn > 0]
    damped = [(fd, f"damped mode {fd:.4g} Hz (ζ {zeta:.2g})") for fd, zeta in damped_modes]
    return _nearest(peak_Hz, resolution_Hz, lines) or _nearest(peak_Hz, resolution_Hz, damped) or "none"


def _nearest(peak_Hz: float, resolution_Hz: float, lines: Sequence[tuple[float, str]]) -> str | None:
    """The name of the line nearest ``peak_Hz`` within ±MATCH_BINS bins (the first on a tie), or None."""
    best: tuple[float, str] | None = None
    for f_line, name in lines:
        d = abs(f_line - peak_Hz)
        if d <= MATCH_BINS * resolution_Hz and (best is None or d < best[0]):
            best = (d, name)
    return best[1] if best else None
