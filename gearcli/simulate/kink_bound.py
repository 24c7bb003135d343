"""A bound on a sampled peak's miss from the secants on either side: where the parabola overshoots a kinked peak.

The sampling estimate (:mod:`gearcli.simulate.sampling`) fits a parabola through a local extreme and its two
neighbours. At a kink between samples (a viscous backlash mesh's force where the teeth come into or out of contact:
the spring's term starts with a slope of K q', the damper's c q' goes on smoothly) three points straddle two arms of
very different slope, and the parabola puts its vertex far beyond the peak: configs/spur_oscillator_te.toml at 2300 rpm
(2e5 N/mm, 0.1 mm backlash, 5 um TE) sampled every 25 us estimated its F_t min 102 N beyond the samples where the
continuous response (an independent solve_ivp model with exact contact switching) lies 0.84 N beyond, and the
suggested 110,000 steps estimated 7.2 N and asked for 390,000, as the estimate falls as h there, not h^2.

Bound. Where the five samples about a local max are concave (the secant slopes fall from left to right: s(-2,-1)
>= s(-1,0) >= 0 >= s(0,1) >= s(1,2)), a concave function through them lies below each secant extended beyond its
own interval, so on (0, h) it lies below both the secant of (-1, 0) and that of (1, 2), and on (-h, 0) below both
the secant of (-2, -1) and that of (0, 1): the higher of the two crossings bounds the peak. A kinked peak (two
concave arms) is concave, and the bound is exact for straight arms; the spur oscillator above: 3.4 N. On a smooth
peak the bound is at least twice the parabola's excess (a parabola with its vertex at p h from the centre sample,
0 <= p <= 1/2: (1/2 + p) h^2 |a| against p^2 h^2 |a|), so there the estimate stays the parabola's. An arm that is
slightly convex (the gap side's damper force c q' above: its secant slopes rise by 5e-4 of themselves a step) adds
its slopes' rise times the span the secant is extended over; samples far from concave (a peak sampled a few times,
an inflection between them) so keep the parabola's estimate.

Kinks. The parabola can also fall short of a kinked peak: a top sample on the shallow arm 0.8 h from the kink, its
neighbour on the steep arm, puts the vertex 2 N beyond a miss of 26 N (slopes 2e7 and 1.3e6 N/s, h = 25 us). Where
the largest of the three slope changes of the five samples is more than :data:`KINK` x the smaller of the outer two
and any rise of an arm's slopes (a kink between two samples leaves the change on its far side ~0, a parabola's
three are equal, samples chattering on an aliased vibration rise and fall; the spur oscillator's: 2.1e7 against
6.7e2 N/s), the peak is taken as kinked and the estimate is the secants' bound itself,
whichever is smaller.

Jumps. A force with a step between two samples (a spur mesh whose contact lines vary, ``time_varying``: K doubles as
the second pair enters, and F_t = K h^e with it, 36 N to 72 N in an instant on a 12-tooth servo pinion) has its
local max at the first sample of the upper arm, and the three samples about it straddle the step: the parabola put
its vertex ~1/8 of the step beyond (4.4 N, an estimate of 8.8 N "that no sampling resolves", since the step does not
shrink with h) where the samples miss at most the upper arm's own change over one step (0.36 N there). Where the
difference into (or out of) the top sample exceeds :data:`JUMP` x each of the other three of the five samples, the
top sample sits beside a step and the force's supremum between the samples is the upper arm's limit at the step: the
estimate is that arm extrapolated back (forward) over the step's interval, the larger of the secant's line and the
parabola through its three samples (0 where the arm rises away from the step: no peak between).
"""

from __future__ import annotations

import numpy as np

KINK = 4.0  # the largest slope change of five samples beyond this x the smaller outer one: a kink (module doc)
JUMP = 8.0  # a difference to the top sample beyond this x each of the other three of five samples: a step (module doc)


def _crossing(xa: np.ndarray, sa: np.ndarray, xb: np.ndarray, sb: np.ndarray, gap: np.ndarray) -> np.ndarray:
    """Value where the rising line ``xa + sa s`` (from the left sample, s from it) meets the falling line through
    ``xb`` at s = ``gap`` with slope ``sb`` (sa >= 0 >= sb, not both 0)."""
    s = (xb - xa - sb * gap) / (sa - sb)
    return xa + sa * s


def _slopes(rise: np.ndarray, fall: np.ndarray, sl: np.ndarray, sr: np.ndarray, rise_out: np.ndarray,
            fall_out: np.ndarray, sl_out: np.ndarray, sr_out: np.ndarray) -> tuple[np.ndarray, ...]:
    """The four secant slopes of the five samples about each centre sample, left to right. ``rise``/``fall``: the
    differences into and out of each centre sample over ``sl``/``sr``; ``rise_out``: into its left neighbour over
    ``sl_out``; ``fall_out``: out of its right neighbour over ``sr_out``."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return rise_out / sl_out, rise / sl, fall / sr, fall_out / sr_out


def concave_bound(xc: np.ndarray, rise: np.ndarray, fall: np.ndarray, sl: np.ndarray, sr: np.ndarray,
                  rise_out: np.ndarray, sl_out: np.ndarray, sr_out: np.ndarray,
                  slopes: tuple[np.ndarray, ...]) -> np.ndarray:
    """The bound's excess over the centre samples ``xc`` (module doc; +inf where the five samples are not
    concave), from their secant ``slopes`` (:func:`_slopes`)."""
    s0, s1, s2, s3 = slopes
    with np.errstate(divide="ignore", invalid="ignore"):
        peak = (s1 >= 0.0) & (s2 <= 0.0) & (s1 - s3 > 0.0) & (s0 - s2 > 0.0)
        right = _crossing(xc - rise, s1, xc + fall, s3, sl + sr) - xc  # on (0, h): secants (-1, 0) and (1, 2)
        left = _crossing(xc - rise - rise_out, s0, xc, s2, sl + sl_out) - xc  # on (-h, 0): (-2, -1) and (0, 1)
        # an arm slightly convex (its secant slopes rising by d over a step): its secant extended by up to two
        # steps may pass below it by ~d x those steps; that is added (0 on concave samples)
        bent = (np.maximum(s1 - s0, 0.0) * (sl + sl_out) + np.maximum(s3 - s2, 0.0) * (sr + sr_out))
        bound = np.maximum(np.maximum(left, right), 0.0) + bent
    return np.where(peak & np.isfinite(bound), bound, np.inf)


def kinked(slopes: tuple[np.ndarray, ...]) -> np.ndarray:
    """Where the largest of the three slope changes of the five samples' secant ``slopes`` is more than :data:`KINK`
    x the smaller of the outer two and any rise of an arm's slopes (module doc, "Kinks": a kink between two samples
    leaves the change on the far side ~0); a parabola's three are equal."""
    s0, s1, s2, s3 = slopes
    with np.errstate(invalid="ignore"):
        d1, d2, d3 = np.abs(s0 - s1), np.abs(s1 - s2), np.abs(s2 - s3)
        convex = np.maximum(s1 - s0, 0.0) + np.maximum(s3 - s2, 0.0)  # samples chattering on an arm: no kink
        return np.nan_to_num(np.maximum(np.maximum(d1, d2), d3) - KINK * (np.minimum(d1, d3) + convex),
                             nan=-1.0) > 0.0


def _arm_extension(step: np.ndarray, step_out: np.ndarray, h: np.ndarray, h_out: np.ndarray,
                   gap: np.ndarray) -> np.ndarray:
    """How far an arm rises above its end sample when continued over ``gap`` past it, away from its other two
    samples: ``step`` the change from its middle sample to the end sample (over ``h``), ``step_out`` from its far
    sample to the middle one (over ``h_out``); the larger of the secant's line and the parabola through the three
    samples, not below 0 (module doc, "Jumps")."""
    with np.errstate(divide="ignore", invalid="ignore"):
        slope, slope_out = step / h, step_out / h_out
        line = slope * gap
        parabola = line + (slope - slope_out) / (h + h_out) * gap * (gap + h)
    return np.maximum(np.maximum(line, parabola), 0.0)


def jump_excess(rise: np.ndarray, fall: np.ndarray, sl: np.ndarray, sr: np.ndarray, rise_out: np.ndarray,
                fall_out: np.ndarray, sl_out: np.ndarray, sr_out: np.ndarray) -> np.ndarray:
    """Where the top sample sits beside a step (module doc, "Jumps"), the upper arm's rise over the step's interval;
    +inf elsewhere. The upper arm needs its three samples; the lower arm's outer sample may be missing (the step
    between a window's first two samples or its last two)."""
    up, down = np.abs(rise), np.abs(fall)
    outer = np.fmax(np.abs(rise_out), np.abs(fall_out))  # nan only where both outer samples are missing
    with np.errstate(invalid="ignore"):
        into = (up > JUMP * np.maximum(outer, down)) & np.isfinite(fall_out)  # the step rises into the top sample
        out = (down > JUMP * np.maximum(outer, up)) & np.isfinite(rise_out)  # ... or falls out of it
    back = _arm_extension(-fall, -fall_out, sr, sr_out, sl)  # the right arm continued back over (-sl, 0)
    ahead = _arm_extension(rise, rise_out, sl, sl_out, sr)  # the left arm continued ahead over (0, sr)
    return np.where(into, back, np.where(out, ahead, np.inf))


def peak_excess(excess: np.ndarray, safety: float, xc: np.ndarray, rise: np.ndarray, fall: np.ndarray,
                sl: np.ndarray, sr: np.ndarray, rise_out: np.ndarray, fall_out: np.ndarray, sl_out: np.ndarray,
                sr_out: np.ndarray) -> np.ndarray:
    """The excess whose ``safety`` multiple is the estimate (module doc): beside a step the upper arm's extension
    over the step's interval, at a kink the secants' bound, else the smaller of ``safety`` x the parabola's
    ``excess`` and that bound (where the samples allow one)."""
    slopes = _slopes(rise, fall, sl, sr, rise_out, fall_out, sl_out, sr_out)
    bound = concave_bound(xc, rise, fall, sl, sr, rise_out, sl_out, sr_out, slopes) / safety
    kink = np.where(kinked(slopes) & np.isfinite(bound), bound, np.minimum(excess, bound))
    step = jump_excess(rise, fall, sl, sr, rise_out, fall_out, sl_out, sr_out)
    return np.where(np.isfinite(step), step, kink)
