"""An undecayed transient in the "steady" window: a lightly damped mode that still rings from the run-up.

The linearised chain at full load gives every mode's damped frequency ``omega_d`` and decay rate ``sigma``
(the eigenvalues of the first-order deflection system, :mod:`gearcli.model.linear`). A mode whose decay
time ``1 / sigma`` exceeds the window's length (:data:`DECAY_WINDOWS`) decays by less than ``1 - exp(-1)`` =
63 % across the window: the window cannot tell its run-up vibration from a steady one, so its std, min, max
and the dynamic factor take it for steady. For such modes the window's F_t of every stage is fitted by least
squares with the free decay itself,

    F_t(t) ~ c + sum_j e^(-sigma_j (t - t0)) (a_j cos omega_j (t - t0) + b_j sin omega_j (t - t0)),

and the transient's amplitude at the window's start is ``hypot(a_j, b_j)`` (at its end times
``e^(-sigma_j L)``); each sigma_j is then refined to the one the record's envelope fits best (within 0.25 .. 4
times the linearised one: the nonlinear meshes and the couplings damp at their own amplitude), to the
trials' resolution (:data:`SIGMA_UNCERTAINTY`, the warning's ``damping_ratio_uncertainty``). The linearisation is
the one ``modes`` makes (:func:`gearcli.model.linear.damped_eigenvalues`: the motor's slip damping and the load
law's dT/dw included), so a mode's damping ratio there and the fitted one agree within that resolution. A transient whose amplitude at the window's end is at least :data:`MIN_FRACTION` of the
stage's static force is warned about, with what would settle it: a later window (the time at which the
vibration has decayed to that fraction), more damping on the element that dominates the mode, or the
periodic steady state.

The mean averages a ringing mode out over many of its periods; std, min and max do not. The seed reducer,
which has no excitation, is such a case: its 58 Hz mode decays in ~1.1 s, four of its 0.26 s windows, and
the window's std of stage 1's F_t (476 N) is that transient; it is warned about.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

DECAY_WINDOWS = 1.0  # a mode whose decay time exceeds the window length rings through it
SIGMA_TRIALS = np.geomspace(0.25, 4.0, 25)  # the refinement's trial decay rates, in units of the linearised one
# the fit's resolution: the refined decay rate (and the damping ratio with it) lies within this relative distance of
# the record's best one, half a trial step (16^(1/48) - 1 = 5.9 %)
SIGMA_UNCERTAINTY = math.sqrt(float(SIGMA_TRIALS[1] / SIGMA_TRIALS[0])) - 1.0
MIN_FRACTION = 0.01  # of the stage's static force, at the window's end
MAX_MODES = 6  # the slowest candidates fitted at once (the fit needs far fewer columns than samples)
FIT_SAMPLES = 4000  # a longer window is thinned to about this many samples for the fit ...
SAMPLES_PER_PERIOD = 16  # ... unless that leaves fewer per period of the fastest mode fitted


@dataclass(frozen=True)
class Ringing:
    stage: int  # 1-based
    frequency_Hz: float  # damped frequency of the ringing mode
    decay_time_s: float  # 1 / sigma (inf when undamped)
    damping_ratio: float
    amplitude_start_N: float  # fitted transient amplitude in F_t at the window's start
    amplitude_end_N: float  # ... at its end
    reference_N: float  # the stage's |static F_t|
    settle_time_s: float  # when the amplitude falls to MIN_FRACTION of the reference (inf if never)

    @property
    def fraction_end(self) -> float:
        return self.amplitude_end_N / self.reference_N


def slow_modes(eigenvalues: np.ndarray, window_s: tuple[float, float]) -> list[tuple[float, float]]:
    """(sigma, omega_d) of the oscillating modes whose decay time exceeds DECAY_WINDOWS window lengths,
    slowest decay first, at most MAX_MODES."""
    length = window_s[1] - window_s[0]
    lam = np.asarray(eigenvalues, dtype=complex)
    out = [(max(-float(z.real), 0.0), float(z.imag)) for z in lam if z.imag > 0.0]
    out = [(s, w) for s, w in out if s * DECAY_WINDOWS * length < 1.0 and w * length > math.pi]  # > half a period
    return sorted(out)[:MAX_MODES]


def _lstsq(tau: np.ndarray, x: np.ndarray, modes: list[tuple[float, float]]) -> tuple[np.ndarray, float]:
    cols = [np.ones_like(tau)]
    for sigma, omega in modes:
        env = np.exp(-sigma * tau)
        cols += [env * np.cos(omega * tau), env * np.sin(omega * tau)]
    A = np.column_stack(cols)
    coef, *_ = np.linalg.lstsq(A, x, rcond=None)
    return coef, float(np.sum((A @ coef - x) ** 2))


def fit_transient(t: np.ndarray, x: np.ndarray, modes: list[tuple[float, float]], *,
                  refine: bool = True) -> tuple[list[float], list[float]]:
    """Amplitude at ``t[0]`` of each mode's free decay in ``x`` (least squares with a constant), and the decay
    rates used: the linearised ones, each refined (``refine``) to the one that fits the record best among
    0.25 .. 4 x it (the nonlinear meshes and couplings damp at their own amplitude: the envelope decides)."""
    if not modes or t.size < 2 * len(modes) + 4:
        return [0.0] * len(modes), [s for s, _ in modes]
    # a long record is thinned for the fit (its cost is samples x columns x trials), keeping at least
    # SAMPLES_PER_PERIOD samples per period of the fastest mode fitted
    dt = (t[-1] - t[0]) / max(t.size - 1, 1)
    fastest = max(w for _, w in modes)
    stride = max(1, min(t.size // FIT_SAMPLES, int(2 * math.pi / (fastest * dt * SAMPLES_PER_PERIOD)) if dt > 0 else 1))
    t, x = t[::stride], x[::stride]
    tau = t - t[0]
    modes = list(modes)
    if refine:
        for j, (sigma, omega) in enumerate(modes):
            if sigma <= 0.0:
                continue
            trials = [(sigma * f, omega) for f in SIGMA_TRIALS]
            errs = [_lstsq(tau, x, modes[:j] + [m] + modes[j + 1:])[1] for m in trials]
            modes[j] = trials[int(np.argmin(errs))]
    coef, _ = _lstsq(tau, x, modes)
    return [float(math.hypot(coef[1 + 2 * j], coef[2 + 2 * j])) for j in range(len(modes))], [s for s, _ in modes]


def ringing(t: np.ndarray, mask: np.ndarray, forces_N: list[np.ndarray], static_N: list[float],
            eigenvalues: np.ndarray, window_s: tuple[float, float]) -> list[Ringing]:
    """Per slow mode, the stage where its transient is largest relative to the static force, when that
    amplitude at the window's end reaches MIN_FRACTION of it."""
    modes = slow_modes(eigenvalues, window_s)
    if not modes:
        return []
    length = window_s[1] - window_s[0]
    tw = t[mask]
    best: dict[int, Ringing] = {}
    for k, (ft, ref) in enumerate(zip(forces_N, static_N, strict=True)):
        ref = abs(float(ref)) or float(np.mean(np.abs(ft[mask])))
        if ref <= 0.0:
            continue
        amplitudes, sigmas = fit_transient(tw, ft[mask], modes)
        for j, a0 in enumerate(amplitudes):
            sigma, omega = sigmas[j], modes[j][1]
            a1 = a0 * math.exp(-sigma * length)
            if a1 < MIN_FRACTION * ref:
                continue
            settle = (window_s[0] + math.log(a0 / (MIN_FRACTION * ref)) / sigma) if sigma > 0 else math.inf
            r = Ringing(k + 1, omega / (2 * math.pi), 1.0 / sigma if sigma > 0 else math.inf,
                        sigma / math.hypot(sigma, omega), a0, a1, ref, settle)
            if j not in best or r.fraction_end > best[j].fraction_end:
                best[j] = r
    return [best[j] for j in sorted(best)]


def message(r: Ringing, window_s: tuple[float, float], element: str) -> str:
    decay = f"decay time {r.decay_time_s:.3g} s" if math.isfinite(r.decay_time_s) else "undamped"
    later = (f"a window from about {r.settle_time_s:.3g} s on (simulation.duration_s beyond it, "
             f"simulation.window_start_s = {r.settle_time_s:.3g})" if math.isfinite(r.settle_time_s)
             else "a later window does not help (the mode is undamped)")
    dominated = f" on the {element}, which dominates the mode" if element else ""
    return (f"the steady window {window_s[0]:.4g}–{window_s[1]:.4g} s still rings: the {r.frequency_Hz:.3g} Hz mode "
            f"({decay}, {100 * r.damping_ratio:.2g} % of critical damping) carries a run-up vibration of "
            f"±{r.amplitude_start_N:.4g} N in stage {r.stage}'s F_t at the window's start and ±{r.amplitude_end_N:.4g} N "
            f"at its end ({100 * r.fraction_end:.2g} % of the static {r.reference_N:.5g} N), so the window's std, "
            "min, max and dynamic factor include an undecayed transient. To settle it: "
            f"{later}; more damping{dominated}; or [simulation] steady = \"periodic\"")
