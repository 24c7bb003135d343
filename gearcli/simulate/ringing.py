"""An undecayed transient in the "steady" window: a lightly damped mode that still rings from the run-up.

The linearised chain at full load gives every mode's damped frequency ``omega_d`` and decay rate ``sigma``
(the eigenvalues of the first-order deflection system, :mod:`gearcli.model.linear`). A mode whose decay
time ``1 / sigma`` exceeds the window's length (:data:`DECAY_WINDOWS`) decays by less than ``1 - exp(-1)`` =
63 % across the window: the window cannot tell its run-up vibration from a steady one, so its std, min, max
and the dynamic factor take it for steady. For such modes the window's F_t of every stage is fitted by least
squares with the free decay itself,

    F_t(t) ~ c + sum_j e^(-sigma_j (t - t0)) (a_j cos omega_j (t - t0) + b_j sin omega_j (t - t0)),

and the transient's amplitude at the window's start is ``hypot(a_j, b_j)`` (at its end times
``e^(-sigma_j L)``); each omega_j is first refined within 5 % to the frequency the record rings at (a Hertzian or
rattling mesh softens with its amplitude: :func:`_refine_omega`), and each sigma_j is then refined to the one the record's envelope fits best (within 0.25 .. 4
times the linearised one: the nonlinear meshes and the couplings damp at their own amplitude), to the
trials' resolution (:data:`SIGMA_UNCERTAINTY`, the warning's ``damping_ratio_uncertainty``). The linearisation is
the one ``modes`` makes (:func:`gearcli.model.linear.damped_eigenvalues`: the motor's slip damping and the load
law's dT/dw included), so a mode's damping ratio there and the fitted one agree within that resolution. A transient whose amplitude at the window's end is at least :data:`MIN_FRACTION` of the
stage's static force is warned about, with what would settle it: a later window (the time at which the
vibration has decayed to that fraction), more damping on the element that dominates the mode, or the
periodic steady state.

The mean averages a ringing mode out over many of its periods, but only down to about A / (omega L) of a window L
long, not to the mean's 1e-4 target where the transient is a sizeable share of the force: the fitted terms give the
transients' share of the window mean in closed form (:func:`window_mean`, every slow mode fitted summed), and where it
exceeds ``MEAN_TARGET`` of the reference the warning names the mean too, with that share (``mean_bias_N``). The seed
reducer, which has no excitation, is such a case: its 58 Hz mode decays in ~1.1 s, four of its 0.26 s windows, the
window's std of stage 1's F_t (476 N) is that transient, and its window mean lies 7.71 N (4.2e-3) below the static
1851.1 N, 7.54 N of it the fitted transients' (58, 112 and 184 Hz modes). A two-stage train whose soft intermediate
shaft rings at 4.2 Hz (0.2 % damping) through a 4.24-20 s window: mean 2.936 N above the static F_t by hand, fitted
2.942 N (tests/field/test_field_ringing_mean.py). Before, the warning named std, min, max and the dynamic factor only
and the mean read as resolved to 1e-4.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from gearcli import diagnostics as dg
from gearcli.core.records import record
from gearcli.core.text import rounded_up
from gearcli.diagnostics import Diagnostic
from gearcli.model.damping import decay_rate
from gearcli.model.modes import modal_analysis
from gearcli.simulate.estimate import MEAN_TARGET
from gearcli.simulate.periodic import excitation_periods
from gearcli.simulate.sampling import PARTIAL_HARMONICS

if TYPE_CHECKING:
    from gearcli.model import TorsionalModel
    from gearcli.simulate.choice import Choice

DECAY_WINDOWS = 1.0  # a mode whose decay time exceeds the window length rings through it
SIGMA_TRIALS = np.geomspace(0.25, 4.0, 25)  # the refinement's trial decay rates, in units of the linearised one
# the fit's resolution: the refined decay rate (and the damping ratio with it) lies within this relative distance of
# the record's best one, half a trial step (16^(1/48) - 1 = 5.9 %)
SIGMA_UNCERTAINTY = math.sqrt(float(SIGMA_TRIALS[1] / SIGMA_TRIALS[0])) - 1.0
MIN_FRACTION = 0.01  # of the stage's static force, at the window's end
MAX_MODES = 6  # the slowest candidates fitted at once (the fit needs far fewer columns than samples)
FIT_SAMPLES = 4000  # a longer window is thinned to about this many samples for the fit ...
SAMPLES_PER_PERIOD = 16  # ... unless that leaves fewer per period of the fastest mode fitted
TRIALS = 25  # decay rates tried per mode between 0.25 and 4 x the linearised one
MIN_SAMPLES_PER_PERIOD = 4.0  # a mode fitted needs this many samples per period (2 is Nyquist's bare minimum)


@record
class Ringing:
    """An undecayed run-up transient of one mode in one stage's window."""

    stage: int  # 1-based
    frequency_Hz: float  # damped frequency of the ringing mode
    decay_time_s: float  # 1 / sigma (inf when undamped)
    damping_ratio: float
    amplitude_start_N: float  # fitted transient amplitude in F_t at the window's start
    amplitude_end_N: float  # ... at its end
    reference_N: float  # the stage's |static F_t| (an unloaded stage: its window mean |F_t|, see ``loaded``)
    settle_time_s: float  # when the amplitude falls to MIN_FRACTION of the reference (inf if never)
    loaded: bool = True  # False: the stage carries no static force, the reference is the window's mean |F_t|
    # what the stage's fitted run-up transients (every slow mode fitted) add to its window-mean F_t: their integral
    # over the window / its length, in closed form (:func:`window_mean`)
    mean_bias_N: float = 0.0
    # the other stages whose window mean the fitted transients move beyond MEAN_TARGET of their reference:
    # (stage, share in N, share relative to the reference)
    other_means: tuple[tuple[int, float, float], ...] = ()

    @property
    def fraction_end(self) -> float:
        return self.amplitude_end_N / self.reference_N

    @property
    def biases_mean(self) -> bool:
        """Whether the transient moves the window's mean F_t beyond the mean's target (MEAN_TARGET of the reference)."""
        return abs(self.mean_bias_N) > MEAN_TARGET * self.reference_N


def window_mean(term: complex, sigma: float, omega: float, length_s: float) -> float:
    """The mean over [0, length_s] of the free decay Re(term e^(i omega tau)) e^(-sigma tau): the closed-form
    integral Re(term (e^((i omega - sigma) L) - 1) / (i omega - sigma)) / L."""
    z = complex(-sigma, omega)
    if length_s <= 0.0 or z == 0:
        return 0.0
    return float((term * (np.exp(z * length_s) - 1.0) / z).real / length_s)


def slow_modes(eigenvalues: np.ndarray, window_s: tuple[float, float],
               dt_s: float = 0.0) -> list[tuple[float, float]]:
    """(sigma, omega_d) of the oscillating modes whose decay time exceeds DECAY_WINDOWS window lengths and that
    a fit over samples ``dt_s`` apart can tell apart (:func:`fittable`), slowest decay first, at most MAX_MODES."""
    length = window_s[1] - window_s[0]
    lam = np.asarray(eigenvalues, dtype=complex)
    out = [(decay_rate(z), float(z.imag)) for z in lam if z.imag > 0.0]
    out = [(s, w) for s, w in out if s * DECAY_WINDOWS * length < 1.0 and w * length > math.pi]  # > half a period
    return fittable(out, length, dt_s)[:MAX_MODES]


def fittable(modes: list[tuple[float, float]], length_s: float, dt_s: float) -> list[tuple[float, float]]:
    """The modes (sigma, omega_d) a free-decay fit over a window ``length_s`` long, sampled ``dt_s`` apart, can
    tell apart, slowest decay first. A mode with fewer than :data:`MIN_SAMPLES_PER_PERIOD` samples per period
    (near or past Nyquist) aliases onto the slower ones, and two modes closer in frequency than the window
    resolves (Rayleigh: 2 pi / length; a repeated eigenvalue of equal planets is the extreme case) are one
    oscillation in it: either way their columns in the fit are nearly parallel and the least-squares amplitudes
    run off in opposite directions (1e10 N on a record that moves 4e5 N: a 0.05 s run of 50 steps). The
    slower-decaying of two close modes stands for both; an unresolvable one is left to the model-free tests."""
    out: list[tuple[float, float]] = []
    for s, w in sorted(modes):
        if w * dt_s <= 2.0 * math.pi / MIN_SAMPLES_PER_PERIOD and all(abs(w - w2) * length_s >= 2.0 * math.pi
                                                                     for _, w2 in out):
            out.append((s, w))
    return out


def _columns(tau: np.ndarray, sigma: np.ndarray, cos: np.ndarray, sin: np.ndarray) -> np.ndarray:
    """Design matrices of the free-decay fit per stage: sigma (S, M) the decay rates, cos and sin (M, n) the
    modes' oscillations; (S, n, 1 + 2M) with a constant column, then e^(-sigma tau) cos and sin per mode."""
    return _design(np.exp(-sigma[:, :, None] * tau), cos, sin)


def _design(env: np.ndarray, cos: np.ndarray, sin: np.ndarray, skip: int = -1,
            extra: np.ndarray | None = None) -> np.ndarray:
    """:func:`_columns` from the modes' envelopes ``env`` (S, M, n) = e^(-sigma tau), without mode ``skip``'s
    two columns (-1: all modes), written in place (the same numbers as stacking them); ``extra`` (k, n): more
    columns after the modes' (the steady forced lines fitted jointly, :func:`_forced_lines`)."""
    S, M, n = env.shape
    modes = [i for i in range(M) if i != skip]
    k = 0 if extra is None else extra.shape[0]
    out = np.empty((S, 1 + 2 * len(modes) + k, n))
    out[:, 0] = 1.0
    for col, i in enumerate(modes):
        np.multiply(env[:, i], cos[i], out=out[:, 1 + 2 * col])
        np.multiply(env[:, i], sin[i], out=out[:, 2 + 2 * col])
    if k:
        out[:, 1 + 2 * len(modes):] = extra
    return out.transpose(0, 2, 1)


def _orthonormal(A: np.ndarray) -> np.ndarray:
    """An orthonormal basis (..., n, r) of the columns of A (..., n, p), dropping the dependent ones' weight."""
    q, r = np.linalg.qr(A)
    d = np.abs(np.diagonal(r, axis1=-2, axis2=-1))
    return q * (d > 1e-12 * np.maximum(d.max(axis=-1, keepdims=True), np.finfo(float).tiny))[..., None, :]


def _project_out(q: np.ndarray, x: np.ndarray, out: np.ndarray | None = None) -> np.ndarray:
    """The rows of x ((S, k, n), or (k, n) shared by every stage) minus their projections on the columns of
    q (S, n, r) (matrix products: BLAS; a shared x is not copied per stage). ``out``: an (S, k, n) array to
    write them in (the same numbers; a large result allocated afresh for every mode costs more than the
    products)."""
    if out is None:
        return x - (x @ q) @ q.transpose(0, 2, 1)
    np.matmul(x @ q, q.transpose(0, 2, 1), out=out)
    return np.subtract(x, out, out=out)


FORCED_GUARD = 3.0  # a forced line within this many half-bandwidths of a fitted mode is left to the fit


def forced_rad_s(layout) -> tuple[float, ...]:
    """The steady lines of the scene's forced response: each excitation's fundamental and first harmonics
    (:func:`gearcli.simulate.periodic.excitation_periods`, as the window's partial-period bound counts them)."""
    return tuple(2 * math.pi * j / ex.period_s for ex in excitation_periods(layout) if ex.period_s > 0.0
                 for j in range(1, PARTIAL_HARMONICS + 1))


SEPARABLE = 0.5  # a mode's decaying columns keep at least this fraction of their norm off a near forced line's


def _forced_lines(tau: np.ndarray, modes: np.ndarray, sigma: np.ndarray,
                  forced: tuple[float, ...]) -> np.ndarray | None:
    """The columns (2k, n) of the steady forced lines at the ``forced`` angular frequencies that the fit takes with
    the modes' free decays (None: none). A resonant forced response is no transient, and left in the record it
    leaks into the modes' columns (a spur chain at its 2840 Hz mesh resonance, 878 N of F_t: its 112 Hz coupling
    transient, 4.5 N at the window start by a closed-form steady state, was fitted at 12-27 N as the window start
    moved by 0.1-10 ms, settled and unsettled in turn). The lines are fitted jointly with the modes, not taken out of
    the record first: over a window of partial periods a large line leaks into the others and into the modes'
    columns, which the record alone would keep (a two-stage chain at its 489 Hz resonance, a 3.7 kN line at 483 Hz:
    its 161-644 Hz lines taken out of the record alone left 57 N rms of it, and the mode's run-up, 202 N at the
    window's start by a fit of the whole record, came out at 117 N with a decay rate 4 times too slow). A line
    within FORCED_GUARD half-bandwidths (sigma, or the window's resolution 2 pi / T) of a fitted mode, its alias on
    the samples included, is taken only where the decay tells the two apart: every mode's columns keep at least
    SEPARABLE of their norm off the near lines' (over sigma T = 10 a mode keeps 89 % off a line at its very
    frequency; over sigma T = 1, 28 %: such a line cannot be told from the mode's transient and stays in the record,
    where it counts as transient, the safe side)."""
    if not forced or tau.size < 2:
        return None
    unique: list[float] = []  # one line per frequency (a stage's 3rd mesh harmonic may be the next one's 1st)
    for w in sorted(forced):
        if not unique or w - unique[-1] > 1e-9 * w:
            unique.append(w)
    forced = tuple(unique)
    dt = float(tau[1] - tau[0])
    nyquist = math.pi / dt
    width = np.maximum(np.abs(sigma), 2 * math.pi / max(float(tau[-1]), dt))
    near = [bool(np.any(np.abs(abs((w + nyquist) % (2 * nyquist) - nyquist) - modes) <= FORCED_GUARD * width))
            for w in forced]

    def columns(lines: list[float]) -> np.ndarray:
        w = np.array(lines)[:, None] * tau
        return np.concatenate((np.cos(w), np.sin(w)))  # (2k, n)

    lines = [w for w, n in zip(forced, near, strict=True) if not n]
    close = [w for w, n in zip(forced, near, strict=True) if n]
    if close:
        cols = columns(close)
        q = _orthonormal(np.column_stack([np.ones_like(tau), cols.T]))
        env = np.exp(-np.abs(sigma)[:, None] * tau)
        decays = np.concatenate((env * np.cos(modes[:, None] * tau), env * np.sin(modes[:, None] * tau)))
        decays = decays - decays.mean(axis=1, keepdims=True)
        left = np.linalg.norm(decays - (decays @ q) @ q.T, axis=1)
        if np.all(left >= SEPARABLE * np.maximum(np.linalg.norm(decays, axis=1), np.finfo(float).tiny)):
            lines += close
    return columns(lines) if lines else None


def fit_transients(t: np.ndarray, X: np.ndarray, modes: list[tuple[float, float]], *,
                   refine: bool = True, forced: tuple[float, ...] = ()) -> tuple[np.ndarray, np.ndarray]:
    """:func:`fit_transient` of every column of ``X`` (shape (n, S): one stage's F_t per column) at once:
    amplitudes (S, M) at ``t[0]`` and the decay rates used (S, M) (:func:`fit_transient_terms`)."""
    terms, sigma, _ = fit_transient_terms(t, X, modes, refine=refine, forced=forced)
    return np.abs(terms), sigma


def fit_transient_terms(t: np.ndarray, X: np.ndarray, modes: list[tuple[float, float]], *, refine: bool = True,
                        forced: tuple[float, ...] = ()) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The free decays of every column of ``X`` (shape (n, S): one stage's F_t per column) at once: each mode's
    term as a complex amplitude C (S, M), the term being Re(C e^(i omega_d (t - t[0]))) e^(-sigma (t - t[0]))
    (|C| its amplitude at ``t[0]``), the decay rates used (S, M) and the frequencies omega_d used (M,).

    ``refine``: each mode's frequency first (:func:`_refine_omega`: a nonlinear mesh rings at its amplitude's
    frequency, not the linearised one), then its decay rate, to the ones that fit the record best.

    Vectorised: the modes' oscillations are computed once; refining mode j projects the record and every
    trial's two columns off the other columns (a variable projection: one small QR per stage), so that the
    25 trials of all stages are one batched 2 x 2 solve, and the final fit is one batched QR."""
    X = np.asarray(X, dtype=float).reshape(t.size, -1)
    S, M = X.shape[1], len(modes)
    base = np.array(modes, dtype=float).reshape(M, 2)
    if not modes or t.size < 2 * M + 4:
        return np.zeros((S, M), dtype=complex), np.broadcast_to(base[:, 0], (S, M)).copy(), base[:, 1].copy()
    # a long record is thinned for the fit (its cost is samples x columns x trials), keeping at least
    # SAMPLES_PER_PERIOD samples per period of the fastest mode fitted (not further: a faster forced response in
    # the record would alias onto the modes)
    dt = (t[-1] - t[0]) / max(t.size - 1, 1)
    fastest = float(base[:, 1].max())
    stride = max(1, min(t.size // FIT_SAMPLES, int(2 * math.pi / (fastest * dt * SAMPLES_PER_PERIOD)) if dt > 0 else 1))
    tau = t[::stride] - t[0]
    Y = X[::stride].T - X[::stride].mean(axis=0)[:, None]  # (S, n), centred: the constant column takes the rest
    extra = _forced_lines(tau, base[:, 1], base[:, 0], forced)  # the steady forced lines: fitted with the modes
    cos, sin = np.cos(base[:, 1:2] * tau), np.sin(base[:, 1:2] * tau)  # (M, n)
    sigma = np.broadcast_to(base[:, 0], (S, M)).copy()
    factors = np.geomspace(0.25, 4.0, TRIALS)
    envelopes = np.exp(-sigma[:, :, None] * tau)  # (S, M, n), each mode's updated as it is refined
    if refine:
        buffer = np.empty((S, 2 * TRIALS, tau.size))  # every mode's projected trials, in turn
        trial = np.empty((TRIALS, 2, tau.size))
        for j in range(M):
            if base[j, 0] <= 0.0:
                continue
            # the other columns, once per distinct set of decay rates: stages whose modes decay alike share the
            # basis, the projected trials and their Gram matrices (the same numbers as one per stage)
            reps, group = _distinct(np.delete(sigma, j, axis=1))
            q = _orthonormal(_design(envelopes[reps], cos, sin, skip=j, extra=extra))  # (G, n, r)
            yp = _project_out(q[group], Y[:, None, :])  # (S, 1, n)
            w = _refine_omega(tau, base, j, q, group, yp)
            if w != base[j, 1]:
                base[j, 1] = w
                cos[j], sin[j] = np.cos(w * tau), np.sin(w * tau)
            env = np.exp(-(base[j, 0] * factors)[:, None] * tau)  # (TRIALS, n)
            np.multiply(env, cos[j], out=trial[:, 0])
            np.multiply(env, sin[j], out=trial[:, 1])
            tp = _project_out(q, trial.reshape(-1, tau.size), out=buffer[:len(reps)])
            tp = tp.reshape(len(reps), TRIALS, 2, tau.size)
            g = (tp @ tp.transpose(0, 1, 3, 2) + 1e-300 * np.eye(2))[group]  # (S, TRIALS, 2, 2)
            b = np.stack([tp[group[i]] @ yp[i].T for i in range(S)])  # (S, TRIALS, 2, 1)
            gain = (b * np.linalg.solve(g, b)).sum(axis=(2, 3))
            sigma[:, j] = base[j, 0] * factors[np.argmax(gain, axis=1)]  # the least residual: the most explained
            envelopes[:, j] = np.exp(-sigma[:, j, None] * tau)
    reps, group = _distinct(sigma)
    q, r = np.linalg.qr(_design(envelopes[reps], cos, sin, extra=extra))
    coef = np.stack([np.linalg.lstsq(r[group[i]], q[group[i]].T @ Y[i], rcond=None)[0] for i in range(S)])
    # a cos + b sin = Re((a - i b) e^(i omega tau)); the forced lines' columns after the modes' are not returned
    return coef[:, 1:1 + 2 * M:2] - 1j * coef[:, 2:2 + 2 * M:2], sigma, base[:, 1].copy()


FREQUENCY_BAND = 0.05  # a mode's frequency is refined within this fraction of the linearised one ...
FREQUENCY_TRIALS = 41  # ... on at most this many trials, a quarter of the window's resolution 2 pi / T apart


def _refine_omega(tau: np.ndarray, base: np.ndarray, j: int, q: np.ndarray, group: np.ndarray,
                  yp: np.ndarray) -> float:
    """Mode j's frequency that fits the records ``yp`` (S, 1, n; the other columns ``q`` projected out) best, within
    FREQUENCY_BAND of ``base[j, 1]`` and at least half the window's resolution from the other modes: the linearised
    frequency is the small-amplitude one, and a Hertzian or rattling mesh softens with its amplitude (the backlash
    oscillator, configs/backlash_oscillator.toml, rings at 64.4 Hz where the linearisation gives 66.1: over its
    0.56 s window that is a turn of phase, and a fit at 66.1 Hz saw 812 N decaying in 0.37 s where 2980 N decayed
    in 1.35 s). Each stage's gain is taken relative to its record's norm, so that every stage counts alike."""
    length = float(tau[-1])
    w0 = float(base[j, 1])
    if length <= 0.0:
        return w0
    step = 0.5 * math.pi / length
    half = min(int(math.ceil(FREQUENCY_BAND * w0 / step)), (FREQUENCY_TRIALS - 1) // 2)
    if half < 1:
        return w0
    trials = w0 + np.linspace(-FREQUENCY_BAND * w0, FREQUENCY_BAND * w0, 2 * half + 1)
    others = np.delete(base[:, 1], j)
    keep = np.all(np.abs(trials[:, None] - others[None, :]) >= math.pi / length, axis=1)
    trials = trials[keep] if keep.any() else np.array([w0])
    env = np.exp(-max(float(base[j, 0]), 0.0) * tau)
    phase = trials[:, None] * tau
    c, s = env * np.cos(phase), env * np.sin(phase)  # (K, n): each trial's two columns
    # the projected columns' Gram matrix per basis group, <P x, P y> = <x, y> - <Q^T x, Q^T y>, and their products
    # with the projected records, <P x, P r> = <x, P r> (P symmetric and idempotent): a closed-form 2 x 2 solve
    qc, qs = c @ q, s @ q  # (G, K, r)
    g00 = np.einsum("kn,kn->k", c, c)[None] - np.einsum("gkr,gkr->gk", qc, qc)
    g11 = np.einsum("kn,kn->k", s, s)[None] - np.einsum("gkr,gkr->gk", qs, qs)
    g01 = np.einsum("kn,kn->k", c, s)[None] - np.einsum("gkr,gkr->gk", qc, qs)
    b0, b1 = yp[:, 0] @ c.T, yp[:, 0] @ s.T  # (S, K)
    g00, g11, g01 = g00[group], g11[group], g01[group]
    det = np.maximum(g00 * g11 - g01 * g01, 1e-300)
    gain = (g11 * b0 * b0 - 2.0 * g01 * b0 * b1 + g00 * b1 * b1) / det  # (S, K): the record's share each explains
    norm = np.maximum((yp[:, 0] ** 2).sum(axis=1), np.finfo(float).tiny)
    return float(trials[int(np.argmax((gain / norm[:, None]).sum(axis=0)))])


def _distinct(rows: np.ndarray) -> tuple[list[int], np.ndarray]:
    """The first index of each distinct row of ``rows`` (S, k), and each row's group (index into them)."""
    first: dict[bytes, int] = {}
    group = np.empty(rows.shape[0], dtype=np.intp)
    reps: list[int] = []
    for s in range(rows.shape[0]):
        key = np.ascontiguousarray(rows[s]).tobytes()
        if key not in first:
            first[key] = len(reps)
            reps.append(s)
        group[s] = first[key]
    return reps, group


def fit_transient(t: np.ndarray, x: np.ndarray, modes: list[tuple[float, float]], *,
                  refine: bool = True) -> tuple[list[float], list[float]]:
    """Amplitude at ``t[0]`` of each mode's free decay in ``x`` (least squares with a constant), and the decay
    rates used: the linearised ones, each refined (``refine``) to the one that fits the record best among
    0.25 .. 4 x it (the nonlinear meshes and couplings damp at their own amplitude: the envelope decides)."""
    amplitudes, sigmas = fit_transients(t, np.asarray(x, dtype=float)[:, None], modes, refine=refine)
    return [float(a) for a in amplitudes[0]], [float(s) for s in sigmas[0]]


def can_ring(x: np.ndarray, reference_N: float) -> bool:
    """Whether a window's record can hold a transient worth a warning: a mode whose amplitude stays at least
    MIN_FRACTION of the reference through the window spans over half a period of it (:func:`slow_modes`), so it
    moves the record by at least that much peak to peak; a record that moves by less than half of it is
    not fitted (a steady, unexcited window: nothing rings)."""
    return x.size > 0 and float(np.ptp(x)) >= 0.5 * MIN_FRACTION * abs(reference_N)


def ringing(t: np.ndarray, mask: np.ndarray, forces_N: list[np.ndarray], static_N: list[float],
            eigenvalues: np.ndarray, window_s: tuple[float, float],
            floors_N: list[float] | None = None, forced: tuple[float, ...] = ()) -> list[Ringing]:
    """Per slow mode, the stage where its transient is largest relative to the static force, when that
    amplitude at the window's end reaches MIN_FRACTION of it."""
    tw = t[mask]
    modes = slow_modes(eigenvalues, window_s, (tw[-1] - tw[0]) / (tw.size - 1) if tw.size > 1 else 0.0)
    if not modes:
        return []
    length = window_s[1] - window_s[0]
    floors = floors_N or [0.0] * len(static_N)
    refs = [abs(float(ref)) or max(float(np.mean(np.abs(ft[mask]))), floor)
            for ft, ref, floor in zip(forces_N, static_N, floors, strict=True)]
    stages = [k for k, (ft, ref) in enumerate(zip(forces_N, refs, strict=True)) if ref > 0.0 and can_ring(ft[mask], ref)]
    best: dict[int, Ringing] = {}
    if not stages:
        return []
    terms, sigmas, omegas = fit_transient_terms(tw, np.column_stack([forces_N[k][mask] for k in stages]), modes,
                                                forced=forced)
    modes = [(m[0], float(w)) for m, w in zip(modes, omegas, strict=True)]  # the frequencies the record rings at
    # each stage's window-mean share of every slow mode fitted, those decayed below MIN_FRACTION by the window's end too
    biases = [sum(window_mean(complex(c), float(sg), m[1], length) for c, sg, m in zip(terms[i], sigmas[i], modes,
                                                                                       strict=True))
              for i in range(len(stages))]
    moved = [(k + 1, b, b / refs[k]) for k, b in zip(stages, biases, strict=True) if abs(b) > MEAN_TARGET * refs[k]]
    for i, k in enumerate(stages):
        ref, bias = refs[k], biases[i]
        others = tuple(m for m in moved if m[0] != k + 1)
        for j, term in enumerate(terms[i]):
            sigma, omega = float(sigmas[i, j]), modes[j][1]
            a0 = float(abs(term))
            a1 = a0 * math.exp(-sigma * length)
            if a1 < MIN_FRACTION * ref:
                continue
            settle = (window_s[0] + math.log(a0 / (MIN_FRACTION * ref)) / sigma) if sigma > 0 else math.inf
            r = Ringing(k + 1, omega / (2 * math.pi), 1.0 / sigma if sigma > 0 else math.inf,
                        sigma / math.hypot(sigma, omega), a0, a1, ref, settle, float(static_N[k]) != 0.0, bias, others)
            if j not in best or r.fraction_end > best[j].fraction_end:
                best[j] = r
    return [best[j] for j in sorted(best)]


def reference_words(reference_N: float, loaded: bool) -> str:
    """What a transient is measured against: the stage's static force, or, for a stage that carries none (an
    unloaded train's rattle), the window's mean |F_t| that stands in for it."""
    if loaded:
        return f"the static {reference_N:.5g} N"
    return f"the window's mean |F_t| {reference_N:.5g} N, the stage carrying no static load"


def statistics(r: Ringing) -> str:
    """The statistics the transient moves: std, min, max and the dynamic factor always; the mean too where its share
    of the window's mean is beyond the mean's target."""
    return ("mean, " if r.biases_mean else "") + "std, min, max, dynamic_factor"


def _statistics_words(r: Ringing) -> str:
    mean = (f"mean (the fitted run-up transients move it by {r.mean_bias_N:+.4g} N, {r.mean_bias_N / r.reference_N:+.2g} "
            f"of the reference, beyond the mean's target {MEAN_TARGET:g}), " if r.biases_mean else "")
    return f"{mean}std, min, max and dynamic factor"


def _other_means_words(r: Ringing) -> str:
    if not r.other_means:
        return ""
    moved = " and ".join(f"of stage {k} by {b:+.4g} N ({rel:+.2g})" for k, b, rel in r.other_means)
    return f"; they move the window mean {moved} too, beyond the mean's target"


def message(r: Ringing, window_s: tuple[float, float], element: str) -> str:
    decay = f"decay time {r.decay_time_s:.3g} s" if math.isfinite(r.decay_time_s) else "undamped"
    later = (f"a window from about {rounded_up(r.settle_time_s):g} s on (simulation.duration_s beyond it, "
             f"simulation.window_start_s = {rounded_up(r.settle_time_s):g})" if math.isfinite(r.settle_time_s)
             else "a later window does not help (the mode is undamped)")
    verb = "dominate" if element.endswith("meshes") else "dominates"  # a planetary's tied meshes name several
    dominated = f" on the {element}, which {verb} the mode" if element else ""
    return (f"the steady window {window_s[0]:.4g}–{window_s[1]:.4g} s still rings: the {r.frequency_Hz:.3g} Hz mode "
            f"({decay}, {100 * r.damping_ratio:.2g} % of critical damping) carries a run-up vibration of "
            f"±{r.amplitude_start_N:.4g} N in stage {r.stage}'s F_t at the window's start and ±{r.amplitude_end_N:.4g} N "
            f"at its end ({100 * r.fraction_end:.2g} % of {reference_words(r.reference_N, r.loaded)}), so the window's "
            f"{_statistics_words(r)} include an undecayed transient{_other_means_words(r)}. To settle it: "
            f"{later}; more damping{dominated}; or [simulation] steady = \"periodic\"")


def ringing_warnings(model: TorsionalModel, choice: Choice, t: np.ndarray, mask: np.ndarray,
                     forces_N: list[np.ndarray], static_N: list[float], window,
                     floors_N: list[float] | None = None) -> list[Diagnostic]:
    """An undecayed run-up transient in the fixed window (:mod:`gearcli.simulate.ringing`), naming the element
    that dominates the ringing mode (the modal analysis at the run's boundary, nearest frequency)."""
    found = ringing(t, mask, forces_N, static_N, choice.run_eigenvalues, window, floors_N, forced_rad_s(model.layout))
    if not found:
        return []
    modes = [m for m in modal_analysis(model.layout, choice.boundary).modes if not m.rigid]
    out = []
    for r in found:
        near = min(modes, key=lambda m: abs(m.frequency_Hz - r.frequency_Hz), default=None)
        element = near.dominant if near is not None else ""
        out.append(dg.warning(dg.WINDOW_RINGING, message(r, window, element), stage=r.stage,
                              statistic=statistics(r), mode_frequency_Hz=r.frequency_Hz,
                              decay_time_s=r.decay_time_s if math.isfinite(r.decay_time_s) else None,
                              damping_ratio=r.damping_ratio, damping_ratio_uncertainty=SIGMA_UNCERTAINTY,
                              amplitude_start_N=r.amplitude_start_N,
                              amplitude_end_N=r.amplitude_end_N, reference_N=r.reference_N,
                              settle_time_s=r.settle_time_s if math.isfinite(r.settle_time_s) else None,
                              element=element, mean_bias_N=r.mean_bias_N,
                              other_stages_mean_bias_N=[{"stage": k, "mean_bias_N": b} for k, b, _ in r.other_means]))
    return out
