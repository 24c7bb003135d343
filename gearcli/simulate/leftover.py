"""The start-up transient a settled window still carries, in the error of its statistics (docs/numerics.md, "Honest
statistics": the transient left in a settled window).

The settle test (:mod:`gearcli.simulate.settle`) calls a window settled when every stage's fitted start-up transient at
the window's start is below 1 % of its static force, which is the dynamic factor's resolution; the window's ``min``,
``max`` and ``std`` claim 1e-3 of the mean (:data:`gearcli.simulate.estimate.TARGET`), and the check pass measures the
integration's error only, not the transient the window holds. The fit has that transient: per stage x(t) = sum of
Re(C_j e^(i omega_j tau)) e^(-sigma_j tau), tau from the window's start. Added to the steady force s(t), it moves
the window's max and min by at most max |x| (|max(s + x) - max(s)| <= max |x|) and its std by at most std(x)
(Minkowski's inequality), both taken over the window's samples, and it moves the window mean by exactly its own
window mean (the closed-form integral of the fitted decays), which the mean's 1e-4 target
(:data:`gearcli.simulate.estimate.MEAN_TARGET`) meets long before 1 % of the static force: a decay of 1 % over a
window of one period of its mode moves the mean by up to ~1.6e-3 of it. These are the transient's share of the stated
error (``error_estimate.transient_N``); where it exceeds the target the run warns ``statistics_unresolved`` naming the
statistic, the stage and the error, with what resolves it: a later window (from when the fitted envelope sum |C_j|
e^(-sigma_j tau) has fallen to half the target, the mean's where the mean is named, the window's length and sample
spacing kept), or the periodic steady state. A tighter rtol does not: the transient is physics, not the solver's
error.

Measured (a spur pair with motor and drum couplings at 2000 rpm, tests/simulate/test_settled_transient.py): settled with
0.77 % of its static force left, the 0.28-0.6 s window's max is 16137 N against the steady state's 16045 N (5.8e-3
of the mean) while the check pass estimated 0.04 N; the bound is 123 N."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import replace
from typing import Any

import numpy as np

from gearcli import diagnostics as dg
from gearcli.core.records import record
from gearcli.core.text import rounded_up
from gearcli.diagnostics import Diagnostic
from gearcli.simulate.estimate import MEAN_TARGET, TARGET

AMPLITUDE = ("min", "max", "std")  # the statistics a transient moves by more than its share of the mean
CLEAR = 0.5  # a later window is clear when the fitted envelope is within this share of the target


@record
class Leftover:
    """One stage's fitted transient in the window: ``peak_N`` (max |x| over the window's samples: the bound on the
    error of min and max), ``std_N`` (std of x: the bound on the std's), ``envelope_N`` (sum |C_j| at the window's
    start), ``clear_s`` (the time after the window's start from which the envelope is within :data:`CLEAR` x the
    target of ``reference_N``; None when a mode does not decay), ``dt_s`` (the window's sample spacing), ``mean_N``
    (the window mean of x: the window mean's error, signed) and ``clear_mean_s`` (as ``clear_s`` for the mean's
    target: an envelope that small bounds |mean x| too)."""

    stage: int  # 1-based
    peak_N: float
    std_N: float
    envelope_N: float
    reference_N: float
    clear_s: float | None
    dt_s: float
    mean_N: float = 0.0
    clear_mean_s: float | None = 0.0


def of_fit(stage: int, t: np.ndarray, terms: np.ndarray, sigmas: Sequence[float], omegas: Sequence[float],
           reference_N: float, mean_N: float = 0.0) -> Leftover:
    """The transient of the fitted ``terms`` (complex amplitudes at ``t[0]``, with decay rates ``sigmas`` and
    frequencies ``omegas``: :func:`gearcli.simulate.ringing.fit_transient_terms`) over the window's samples ``t``;
    ``mean_N``: its window mean (:func:`gearcli.simulate.ringing.window_mean` of the terms)."""
    tau = np.asarray(t, dtype=float) - float(t[0])
    x = np.zeros_like(tau)
    for c, sg, om in zip(terms, sigmas, omegas, strict=True):
        x += (complex(c) * np.exp(complex(-sg, om) * tau)).real
    amplitudes = [float(abs(c)) for c in terms]
    envelope = sum(amplitudes)
    return Leftover(stage, float(np.max(np.abs(x))) if x.size else 0.0, float(np.std(x)) if x.size else 0.0,
                    envelope, reference_N, _clear(amplitudes, list(sigmas), CLEAR * TARGET * reference_N),
                    float(tau[-1] / (tau.size - 1)) if tau.size > 1 else 0.0, float(mean_N),
                    _clear(amplitudes, list(sigmas), CLEAR * MEAN_TARGET * reference_N))


def _clear(amplitudes: list[float], sigmas: list[float], level: float) -> float | None:
    """The least tau >= 0 at which sum a_j e^(-sigma_j tau) <= level (bisection: the sum falls monotonically)."""
    def envelope(tau: float) -> float:
        return sum(a * math.exp(-s * tau) for a, s in zip(amplitudes, sigmas, strict=True))

    if envelope(0.0) <= level:
        return 0.0
    if level <= 0.0 or any(a > 0.0 and s <= 0.0 for a, s in zip(amplitudes, sigmas, strict=True)):
        return None
    lo, hi = 0.0, max(math.log(len(amplitudes) * a / level) / s for a, s in zip(amplitudes, sigmas, strict=True)
                      if a > 0.0)
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if envelope(mid) > level else (lo, mid)
    return hi


def _reference(stage: Any, left: Leftover) -> float:
    """The force the stage's statistics targets refer to (its error estimate's, else its sampling's |mean F_t|)."""
    for est in (getattr(stage, "error_estimate", None), getattr(stage, "sampling_error", None)):
        if est is not None and est.reference_N > 0.0:
            return float(est.reference_N)
    return left.reference_N


def _errors(left: Leftover) -> dict[str, float]:
    return {"mean": abs(left.mean_N), "min": left.peak_N, "max": left.peak_N, "std": left.std_N}


def _over(relative: dict[str, float]) -> list[str]:
    """The statistics whose relative error exceeds its target: the mean's MEAN_TARGET, the others' TARGET."""
    return [q for q in ("mean", *AMPLITUDE) if relative[q] > (MEAN_TARGET if q == "mean" else TARGET)]


def with_errors(stages: Sequence[Any], leftover: Sequence[Leftover]) -> tuple[Any, ...]:
    """``stages`` whose error estimate adds the transient left in the window (``transient_N``,
    ``transient_relative``; ``total_relative`` {min, max, std} and ``unresolved`` then cover it)."""
    by_stage = {left.stage: left for left in leftover}
    out = []
    for k, st in enumerate(stages):
        e, left = st.error_estimate, by_stage.get(k + 1)
        if e is None or left is None:
            out.append(st)
            continue
        ref = _reference(st, left)
        absolute = _errors(left)
        rel = {q: v / ref if ref > 0.0 else 0.0 for q, v in absolute.items()}
        total = dict(e.total_relative or {q: e.relative[q] for q in ("mean", "min", "max")})
        total["std"] = e.relative["std"]
        total.update({q: total[q] + rel[q] for q in ("mean", *AMPLITUDE)})
        over = set(_over(total))
        unresolved = tuple(q for q in ("mean", "min", "max", "std", "spectrum") if q in e.unresolved or q in over)
        out.append(replace(st, error_estimate=replace(e, transient_N=absolute, transient_relative=rel,
                                                      total_relative=total, unresolved=unresolved,
                                                      resolved=not unresolved)))
    return tuple(out)


def warnings(leftover: Sequence[Leftover], stages: Sequence[Any], window_s: tuple[float, float]) -> list[Diagnostic]:
    """``statistics_unresolved``, one per stage whose transient left in the (settled) window moves min, max or std
    by more than the target of its mean, or the mean by more than the mean's."""
    out = []
    length = window_s[1] - window_s[0]
    for left in leftover:
        st = stages[left.stage - 1] if left.stage <= len(stages) else None
        ref = _reference(st, left)
        absolute = _errors(left)
        bad = _over({q: v / ref for q, v in absolute.items()}) if ref > 0.0 else []
        if not bad:
            continue
        spread = [q for q in bad if q != "mean"]
        worst = max(spread or bad, key=lambda q: absolute[q])
        moved = (f"max and min by up to {left.peak_N:.3g} N" if {"min", "max"} <= set(bad) else "") + \
            (" and " if {"min", "max"} <= set(bad) and "std" in bad else "") + \
            (f"std by up to {left.std_N:.3g} N" if "std" in bad else "")
        moved = (f"{moved} ({absolute[worst] / ref:.2g} of the mean {ref:.5g} N, target {TARGET:g})" if spread else "") \
            + (" and " if spread and "mean" in bad else "") + \
            (f"mean by {left.mean_N:+.3g} N ({left.mean_N / ref:+.2g} of the mean {ref:.5g} N, target {MEAN_TARGET:g})"
             if "mean" in bad else "")
        clear = left.clear_mean_s if "mean" in bad else left.clear_s
        if clear is not None:
            start = rounded_up(window_s[0] + clear)  # printed as typed, on the settled side
            end = rounded_up(start + length)
            steps = math.ceil(end / left.dt_s) if left.dt_s > 0.0 else None
            later = (f"a later window resolves it (--set simulation.window_start_s={start:g} "
                     f"--set simulation.duration_s={end:g}"
                     + (f" --set simulation.steps={steps}" if steps is not None else "") + ", its length and sampling "
                     "kept), or ")
        else:
            start, later = None, ""
        out.append(dg.warning(
            dg.STATISTICS_UNRESOLVED,
            f"stage {left.stage}: F_t {', '.join(bad)} not resolved by the window: the start-up transient the settle "
            f"test fitted (±{left.envelope_N:.3g} N at the window's start, {100 * left.envelope_N / left.reference_N:.2g}"
            f" % of the {left.reference_N:.5g} N it is settled against, below the 1 % of a settled window) moves its "
            f"{moved}; {later}"
            "[simulation] steady = \"periodic\" does; a tighter rtol does not",
            stage=left.stage, statistics=bad, estimated_error_N=float(absolute[worst]),
            relative_error=float(absolute[worst] / ref), rtol=None, transient_N=float(left.envelope_N),
            window_start_s=start, **({"mean_bias_N": float(left.mean_N)} if "mean" in bad else {})))
    return out
