"""Steady-state window, channel statistics, per-stage dynamics and the simulation's warnings."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import replace
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from gearcli import diagnostics as dg
from gearcli import engine
from gearcli.design.checks import STATIC_APPROACH_MODULE_FRACTION as PENETRATION_MODULE_FRACTION  # one limit for both
from gearcli.diagnostics import Diagnostic
from gearcli.model.spec import MeshSpec, ModelSpec
from gearcli.simulate.results import (
    REGIME_DOUBLE_SIDED,
    REGIME_NO_IMPACT,
    REGIME_SINGLE_SIDED,
    ChannelStats,
    DteStats,
    StageDynamics,
)

if TYPE_CHECKING:
    from gearcli.model.outputs import Sampled

SETTLE_FRACTION = 0.2  # of the time left after the slower ramp (docs/physics.md, "Torsional model")
WARN_ENERGY_RESIDUAL = 1e-3
WARN_PEAK_OVER_RIGID = 2.0  # smooth run-ups amplify the rigid-body force by a few % (seed: 1.05)
NO_RAMP_WINDOW_FRACTION = 0.8  # window start when the ramps outlast the run: the last 20 %


def steady_window(spec: ModelSpec, duration_s: float,
                  start_s: float | None) -> tuple[tuple[float, float], list[Diagnostic]]:
    """``(from, to)`` of the steady window and any warning about it.

    Default: from the end of the slower ramp (input, a soft start's voltage ramp included, and load) plus 20 % of
    the remaining time, to the end. ``start_s`` (``simulation.window_start_s``) overrides the start; it must lie before the end
    (ValueError otherwise: the caller checks the design file).
    """
    if start_s is not None and start_s >= duration_s:
        raise ValueError(f"the window start {start_s:g} s is not before the end of the run {duration_s:g} s")
    ramps = max(spec.drive.ramps_end_s, spec.load.ramp_s)
    if ramps >= duration_s:  # whoever chose the window's start (a settle re-run's too): it lies in the ramps
        start = NO_RAMP_WINDOW_FRACTION * duration_s if start_s is None else float(start_s)
        return (start, duration_s), [dg.warning(
            dg.RAMPS_OUTLAST_RUN, f"the ramps ({ramps:g} s) outlast the run ({duration_s:g} s): the statistics "
            f"window [{start:.4g}, {duration_s:g}] s is not steady; lengthen duration_s", ramps_s=ramps)]
    if start_s is not None:
        return (float(start_s), duration_s), []
    return (ramps + SETTLE_FRACTION * (duration_s - ramps), duration_s), []


def window_mask(t: np.ndarray, window: tuple[float, float]) -> np.ndarray:
    eps = 1e-9 * max(1.0, abs(window[1]))
    return (t >= window[0] - eps) & (t <= window[1] + eps)


def window_slice(mask: np.ndarray) -> slice | np.ndarray:
    """The window's samples as a slice (indexing gives a view, the same numbers as the mask's copy) when they are
    contiguous, as a window of ascending times is; else the mask itself. A boolean mask is read from its first true
    sample to its next false one (``argmax``, ``argmin``: without the index array of every true sample)."""
    if mask.dtype == np.bool_ and mask.ndim == 1 and mask.size:
        first = int(mask.argmax())
        if not mask[first]:  # no sample in the window
            return mask
        rest = mask[first:]
        k = int(rest.argmin())
        if rest[k]:  # true to the end
            return slice(first, mask.size)
        end = first + k
        return mask if mask[end:].any() else slice(first, end)
    idx = np.flatnonzero(mask)
    if idx.size and int(idx[-1]) - int(idx[0]) + 1 == idx.size:
        return slice(int(idx[0]), int(idx[-1]) + 1)
    return mask


def window_means(tw: np.ndarray, W: np.ndarray, periodic: bool) -> np.ndarray:
    """The window mean of every row of ``W`` (samples at the times ``tw``): the integral of the channel over the
    window by the trapezoid rule on the sample grid, over the window's length (DESIGN section 7: the mean comes
    from the integral); for whole periods sampled uniformly without their closing sample (``periodic``) the plain
    mean, which is the trapezoid rule of the periodic signal. The plain mean of a window's samples counts both its
    ends in full and errs by (mean - (x_0 + x_N)/2) / N: a rattling mesh (F_t from 0 to 4.5x its mean) sampled
    1600 times was 6e-4 off, six times the mean's 1e-4 target, where the trapezoid rule is 1e-5 off."""
    W = W if isinstance(W, np.ndarray) and W.ndim == 2 else np.atleast_2d(W)
    if periodic or W.shape[1] < 2 or tw[-1] <= tw[0]:
        # numpy's mean of a float64 array is its sum along the rows divided by the count: the same division here,
        # without np.mean's Python wrapper
        return np.add.reduce(W, axis=1) / W.shape[1] if W.dtype == np.float64 and W.shape[1] else W.mean(axis=1)
    dt = np.diff(tw)
    return np.sum(0.5 * (W[:, 1:] + W[:, :-1]) * dt[None, :], axis=1) / (tw[-1] - tw[0])


def planet_windows(t: np.ndarray, mask: np.ndarray, every: dict[tuple[int, int, str], tuple[np.ndarray, np.ndarray]],
                   periodic: bool, stage: int | None = None) -> dict[tuple[int, int, str], tuple[Any, tuple]]:
    """Every planet mesh of ``every`` (:func:`gearcli.simulate.planet_stats.planet_series`; ``stage``: that stage's
    alone) over the window ``mask`` of the times ``t``: its F_t and DTE (um) statistics (a PlanetMeshDynamics) and
    its F_t's (plain mean, std, min, max), the sampling estimate's (:func:`gearcli.simulate.sampling.stage_sampling`'s
    ``reduced``). Each statistic one numpy reduction along the rows of one array of every mesh's window: the numbers
    of a mesh at a time (numpy reduces a contiguous row as the 1-D row alone, as :func:`stages_dynamics` reads)."""
    from gearcli.simulate.planet_results import PlanetMeshDynamics  # lazy: a planetary stage only

    keys = [key for key in every if stage is None or key[0] == stage]
    if not keys:
        return {}
    sel = window_slice(mask)
    tw, F = t[sel], np.stack([every[key][0][sel] for key in keys])
    Q = np.stack([every[key][1][sel] for key in keys])
    Q *= 1e6  # um: the same products, in place
    f_mean, q_mean = (window_means(tw, X, periodic).tolist() for X in (F, Q))
    f_min, f_max, f_std = (r.tolist() for r in (F.min(axis=1), F.max(axis=1), F.std(axis=1)))
    f_plain = f_mean if periodic else F.mean(axis=1).tolist()  # periodic: the window mean is numpy's plain mean
    q_min, q_max, q_std = (r.tolist() for r in (Q.min(axis=1), Q.max(axis=1), Q.std(axis=1)))
    return {key: (PlanetMeshDynamics(ChannelStats(f_mean[r], f_min[r], f_max[r], f_std[r]),
                                     DteStats(q_mean[r], q_std[r], q_min[r], q_max[r])),
                  (f_plain[r], f_std[r], f_min[r], f_max[r])) for r, key in enumerate(keys)}


def channel_stats(x: np.ndarray, mask: np.ndarray | slice, t: np.ndarray | None = None, *,
                  periodic: bool = False) -> ChannelStats:
    """mean, min, max, std of the channel ``x`` over the window ``mask``; the mean the integral's
    (:func:`window_means`) where the times ``t`` are given, else the samples' plain mean."""
    w = x[mask]
    mean = float(w.mean()) if t is None or w.size == 0 else float(window_means(t[mask], w, periodic)[0])
    return ChannelStats(mean, float(w.min()), float(w.max()), float(w.std()))


def stage_dynamics(k: int, t: np.ndarray, mask: np.ndarray, ft: np.ndarray, fr: np.ndarray, fa: np.ndarray,
                   pen_mm: np.ndarray, static_tangential_N: float, dte_um: np.ndarray | None = None, *,
                   periodic: bool = False, simulated_static_N: float | None = None,
                   gapless: bool = False) -> StageDynamics:
    """Window statistics and the run's peak |F_t| (over the output samples) of stage ``k`` (0-based), and
    the mesh response over the window (:func:`mesh_response`) when ``dte_um`` is given.

    Both factors refer to ``simulated_static_N``, the static F_t of the load the simulation applies with the
    losses its dynamics model (default: the design's ``static_tangential_N``): ``dynamic_factor`` = the
    steady window's max |F_t| over it (K_v as the rating means it), ``runup_factor`` = the whole run's
    peak |F_t| over it (the start-up overshoot)."""
    i = int(np.argmax(np.abs(ft)))
    peak = float(abs(ft[i]))
    ref = float(static_tangential_N if simulated_static_N is None else simulated_static_N)
    sel = window_slice(mask)  # every statistic over the window's samples, read in place
    window_max = float(np.max(np.abs(ft[sel]))) if np.any(mask) else math.nan
    factor = window_max / abs(ref) if ref != 0 and math.isfinite(window_max) else None
    runup = peak / abs(ref) if ref != 0 else None
    response = {} if dte_um is None else mesh_response(t, sel, dte_um, ft, pen_mm, static_tangential_N,
                                                       periodic=periodic, gapless=gapless)
    return StageDynamics(k + 1, channel_stats(ft, sel, t, periodic=periodic), channel_stats(fr, sel, t, periodic=periodic),
                         channel_stats(fa, sel, t, periodic=periodic), channel_stats(pen_mm, sel, t, periodic=periodic),
                         float(static_tangential_N), peak, float(t[i]), factor,
                         **response, runup_factor=runup, simulated_static_tangential_N=ref)


class Reduced(NamedTuple):
    """Every stage's window reductions (:func:`window_reductions`), rows as :func:`stages_dynamics` stacks them:
    five a stage (F_t, F_r, F_a, penetration, DTE)."""

    tw: np.ndarray  # the window's times
    W: np.ndarray  # the window's samples, a row a channel
    whole: np.ndarray  # each stage's F_t over the run
    means: np.ndarray  # the window means (the integral's, :func:`window_means`)
    plain: np.ndarray  # the samples' plain means
    mins: np.ndarray
    maxs: np.ndarray
    stds: np.ndarray  # about the plain mean
    peaks_at: np.ndarray  # a stage's index of its run's first largest |F_t|
    contact: tuple  # :func:`_contact`'s
    sel: slice | np.ndarray  # the window's samples (:func:`window_slice` of the mask): read by the callers too

    def force(self, k: int) -> tuple[float, float, float, float]:
        """Stage ``k``'s (0-based) F_t over the window: (plain mean, std, min, max)."""
        r = 5 * k
        return float(self.plain[r]), float(self.stds[r]), float(self.mins[r]), float(self.maxs[r])

    def penetration(self, k: int) -> tuple[float, float]:
        """Stage ``k``'s (0-based) penetration over the window, mm: (min, max)."""
        r = 5 * k + 3
        return float(self.mins[r]), float(self.maxs[r])


def window_reductions(t: np.ndarray, mask: np.ndarray, per_stage: Sequence[Sequence[np.ndarray]],
                      static_tangential_N: Sequence[float], periodic: bool,
                      rows: np.ndarray | None = None) -> Reduced | None:
    """The reductions :func:`stages_dynamics` reads (and a stage's sampling estimate: its F_t's plain mean, std,
    min and max, :func:`gearcli.simulate.sampling.stage_sampling`), once; None where it takes a stage at a time (an
    empty window, a stage without its five series). ``rows``: an array whose leading rows are ``per_stage``'s series
    in order (:func:`gearcli.model.outputs.stage_rows`), where the caller made them so: the window's rows copied from
    it at once."""
    if not per_stage or any(len(p) != 5 for p in per_stage):
        return None
    sel = window_slice(mask)
    if not isinstance(sel, slice) and not np.any(mask):  # (a slice is never empty: window_slice)
        return None
    n = 5 * len(per_stage)
    if rows is not None and rows.dtype == np.float64 and rows.ndim == 2 and rows.shape[0] >= n:
        whole = np.ascontiguousarray(rows[0:n:5])  # F_t over the run: its peaks
        W = np.ascontiguousarray(rows[:n, sel])  # (5 n, window): rows per stage
    else:
        whole = np.stack([np.asarray(p[0], dtype=float) for p in per_stage])
        W = np.stack([np.asarray(x, dtype=float)[sel] for p in per_stage for x in p])
    tw = t[sel]
    means, plain, mins, maxs, stds, peaks_at, contact = _reductions(tw, W, whole, static_tangential_N, periodic)
    return Reduced(tw, W, whole, means, plain, mins, maxs, stds, peaks_at, contact, sel)


def stages_dynamics(t: np.ndarray, mask: np.ndarray, per_stage: Sequence[Sequence[np.ndarray]],
                    static_tangential_N: Sequence[float], *, periodic: bool = False,
                    simulated_static_N: Sequence[float | None] | None = None, gapless: Sequence[bool] = (),
                    reduced: Reduced | None = None,
                    **fields: Sequence[Any]) -> list[StageDynamics]:
    """:func:`stage_dynamics` of every stage at once (``per_stage``: each stage's (F_t, F_r, F_a, penetration in mm,
    DTE in um)), ``fields`` (one entry per stage) set on each: the same numbers, each statistic a reduction along a
    row of one array of every stage's window (numpy reduces a contiguous row as the row alone), in a few calls where
    a stage at a time makes a few dozen. ``gapless``: per stage, whether its mesh has no backlash (missing: it may).
    ``reduced``: :func:`window_reductions` of the same arguments, where the caller has them."""
    n = len(per_stage)
    gaps = [bool(gapless[k]) if k < len(gapless) else False for k in range(n)]
    simulated = list(simulated_static_N) if simulated_static_N is not None else [None] * n
    if reduced is None:
        reduced = window_reductions(t, mask, per_stage, static_tangential_N, periodic)
    if reduced is None:  # an empty window: one stage at a time
        return [replace(stage_dynamics(k, t, mask, p[0], p[1], p[2], p[3], static_tangential_N[k],
                                       p[4] if len(p) > 4 else None, periodic=periodic,
                                       simulated_static_N=simulated[k], gapless=gaps[k]),
                        **{f: v[k] for f, v in fields.items()})
                for k, p in enumerate(per_stage)]
    tw, W, whole, means, _, mins, maxs, stds, peaks_at, contact, _ = reduced
    window_max = np.maximum(np.abs(mins[0::5]), np.abs(maxs[0::5]))  # the window's max |F_t|: its min's or max's
    means, mins, maxs, stds = means.tolist(), mins.tolist(), maxs.tolist(), stds.tolist()  # float() of each, at once
    responses = _responses(tw, W[4::5], W[0::5], W[3::5], static_tangential_N, periodic,
                           (means[4::5], stds[4::5], mins[4::5], maxs[4::5]), gaps, contact)  # the DTE rows' reductions

    def channel(j: int) -> ChannelStats:
        return ChannelStats(means[j], mins[j], maxs[j], stds[j])

    out = []
    for k in range(n):
        i = int(peaks_at[k])
        peak = float(abs(whole[k, i]))
        given = simulated[k]
        ref = float(static_tangential_N[k]) if given is None else float(given)
        wmax = float(window_max[k])
        r = 5 * k
        named = {**responses[k], "runup_factor": peak / abs(ref) if ref != 0 else None,
                 "simulated_static_tangential_N": ref, **{f: v[k] for f, v in fields.items()}}  # fields win, as replace
        out.append(StageDynamics(
            k + 1, channel(r), channel(r + 1), channel(r + 2), channel(r + 3), float(static_tangential_N[k]), peak,
            float(t[i]), wmax / abs(ref) if ref != 0 and math.isfinite(wmax) else None, **named))
    return out


def _reductions(tw: np.ndarray, W: np.ndarray, whole: np.ndarray, static_tangential_N: Sequence[float],
                periodic: bool) -> tuple[Any, ...]:
    """The reductions of :func:`stages_dynamics`: every row of the window's ``W`` (sampled at ``tw``, five rows a
    stage) its window mean, plain mean, min, max and std; each stage's index of its run's first largest |F_t| (``whole``: F_t
    over the run, a stage a row); and its contact's fractions and flags (:func:`_contact`). In one compiled pass
    where this process has loaded the compiled engine (:func:`gearcli.engine.window.window_statistics`: numpy's
    numbers bit for bit), else numpy's reductions; numpy's too where a window value is not finite (its min and
    max carry the NaN the compiled pass's would not)."""
    kernel = engine.loaded_kernel()
    if kernel is not None:
        loaded = _loaded_signs(static_tangential_N)
        stats, peaks_at, fractions, flags = kernel.window_statistics(W, whole, tw, bool(periodic), loaded)
        if np.isfinite(stats).all():
            # the flags as the compiled pass counts them; the fractions split at the crossings (contact_fractions)
            on = flags > 0  # no flag raised (every mesh in contact on its loaded flank): contact_fractions' zeros
            split = contact_fractions(tw, W[0::5], W[3::5], W[4::5], static_tangential_N, periodic, on) \
                if on.any() else ([0.0] * len(on), [0.0] * len(on))
            contact = (*split, on[:, 0], on[:, 1])
            return stats[:, 0], stats[:, 4], stats[:, 1], stats[:, 2], stats[:, 3], peaks_at, contact
    return (window_means(tw, W, periodic), W.mean(axis=1), W.min(axis=1), W.max(axis=1), W.std(axis=1),
            np.argmax(np.abs(whole), axis=1), _contact(tw, W[0::5], W[3::5], W[4::5], static_tangential_N, periodic))


def _loaded_signs(static_tangential_N: Sequence[float]) -> np.ndarray:
    """Per stage, the sign of the flank its static load presses (+1 the drive flank, also under no load; -1 the
    back flank): what :func:`mesh_response` calls the loaded flank."""
    return np.array([-1.0 if s < 0 else 1.0 for s in static_tangential_N])


def _contact(tw: np.ndarray, f: np.ndarray, p: np.ndarray, q: np.ndarray, static_tangential_N: Sequence[float],
             periodic: bool) -> tuple:
    """Per row of the window's F_t ``f``, penetration ``p`` and DTE ``q``: the time fractions without contact and on
    the back flank (:func:`contact_fractions`), and whether any sample is so."""
    loaded = _loaded_signs(static_tangential_N)
    lost = (f == 0.0) | (p == 0.0)
    back = loaded[:, None] * p < 0.0
    flagged = np.stack([np.any(lost, axis=1), np.any(back, axis=1)], axis=1)
    return (*contact_fractions(tw, f, p, q, static_tangential_N, periodic, flagged), flagged[:, 0], flagged[:, 1])


def contact_fractions(tw: np.ndarray, f: np.ndarray, p: np.ndarray, q: np.ndarray,
                      static_tangential_N: Sequence[float], periodic: bool,
                      flagged: np.ndarray | None = None) -> tuple[list[float], list[float]]:
    """Per row of the window's F_t ``f``, signed penetration ``p`` and DTE ``q``: the time fractions without contact
    and on the back flank (:func:`mesh_response`), each sample interval where contact begins or ends split where the
    penetration crosses 0, not at its middle. In contact p = c_b q -+ h (the gap's half h along the normal, c_b its
    cosine: :mod:`gearcli.model.elements.mesh`), so the penetration the contact sample's side would have at the
    gap's sample is p_c + s (q_g - q_c), s = dp/dq read off the window's touching samples: linear interpolation, an
    error of order dt² where counting samples (the trapezoid rule of the flags) errs by up to a sample a crossing.
    That count aliased where the samples fall a whole number per mesh period: a spur oscillator sampled 40 times a
    period read 0.400 (80 times: 0.3875) against 0.388 of its continuous response. An interval of a zero force
    pressed (the IMPACT law's clamp) or from flank to flank keeps the trapezoid's half. ``flagged``: per row,
    (no contact, back flank) whether any sample is so, where the caller counted it (a flag no sample raises is a
    fraction of exactly 0, without its split)."""
    loaded = _loaded_signs(static_tangential_N)
    lost_out: list[float] = []
    back_out: list[float] = []
    for k in range(f.shape[0]):
        if flagged is not None and not flagged[k, 0]:
            lost_out.append(0.0)
        else:
            lost_out.append(_split_fraction(tw, (f[k] == 0.0) | (p[k] == 0.0), p[k], q[k], periodic, False))
        if flagged is not None and not flagged[k, 1]:
            back_out.append(0.0)
        else:
            back_out.append(_split_fraction(tw, loaded[k] * p[k] < 0.0, p[k], q[k], periodic, True))
    return lost_out, back_out


def _split_fraction(tw: np.ndarray, flag: np.ndarray, p: np.ndarray, q: np.ndarray, periodic: bool,
                    touching_flag: bool) -> float:
    """:func:`time_fraction` of ``flag`` with its changes split at the interpolated crossing of p = 0
    (:func:`contact_fractions`); ``touching_flag``: the flag holds on the touching side (the back flank) rather
    than on the gap's (contact lost)."""
    n = flag.size
    if n < 2 or tw[-1] <= tw[0]:
        return time_fraction(tw, flag, periodic=periodic)
    if periodic:  # whole periods without their closing sample: the last interval closes on the first sample
        t = np.append(tw, tw[-1] + (tw[1] - tw[0]))
        flag, p, q = np.append(flag, flag[:1]), np.append(p, p[:1]), np.append(q, q[:1])
    else:
        t = tw
    x = flag.astype(float)
    weight = 0.5 * (x[1:] + x[:-1])
    changes = np.flatnonzero(x[1:] != x[:-1])
    slope = _penetration_slope(p, q) if changes.size else None
    if slope is not None:
        g = np.where(p[changes + 1] == 0.0, changes + 1, changes)  # the gap's sample of each change
        c = np.where(g == changes + 1, changes, changes + 1)  # and the touching one
        pc = p[c]
        beyond = pc + slope * (q[g] - q[c])  # the touching side's penetration continued to the gap's sample
        # a crossing of the gap's edge (not a zero force pressed, nor flank to flank), on the interpolated line
        edge = (pc != 0.0) & (p[g] == 0.0) & (flag[c] == touching_flag) & (beyond * pc < 0.0)
        touching = pc[edge] / (pc[edge] - beyond[edge])  # the interval's part in contact
        weight[changes[edge]] = touching if touching_flag else 1.0 - touching
    if periodic:
        return float(np.mean(weight))
    return float(np.sum(weight * np.diff(t)) / (t[-1] - t[0]))


def _penetration_slope(p: np.ndarray, q: np.ndarray) -> float | None:
    """dp/dq (c_b and the units' scale) from the window's neighbouring samples touching one flank; None: none."""
    same = (p[1:] * p[:-1] > 0.0) & (q[1:] != q[:-1])
    if not np.any(same):
        return None
    slopes = np.diff(p)[same] / np.diff(q)[same]
    return float(np.median(slopes))


def leaves_flank(s: Sampled, window: tuple[float, float], gapless: Sequence[bool] = ()) -> bool:
    """Whether a mesh leaves its (mean) flank in the window: a gap or the other flank, penetration <= 0 at a sample.
    Such a response is not smooth: an error made in the run-up is not forgotten at the linear modes' decay rate, and
    where responses coexist the run-up picks one (the check pass then starts at t = 0: gearcli/simulate/estimate.py).
    ``gapless``: per mesh, whether it has no backlash (:func:`gapless_meshes`; missing: it may). A gapless mesh whose
    force reverses crosses no gap and strikes nothing (its law is continuous through zero penetration: a linear one is
    the same line on both flanks), so it does not count: a linear gapless train is a linear system, whose response is
    unique and converges with rtol like any other."""
    w = s.time_s >= window[0]
    return any(bool(np.any(m.penetration_m[w] * np.sign(np.mean(m.penetration_m[w])) <= 0.0))
               for k, m in enumerate(s.meshes) if not (k < len(gapless) and gapless[k]))


def gapless_meshes(spec) -> list[bool]:
    """Per stage mesh of the model ``spec``, whether it has no backlash (a force reversal crosses no gap)."""
    return [m.backlash_m == 0.0 for m in spec.meshes]


def _time_fractions(t: np.ndarray, flags: np.ndarray, periodic: bool) -> list[float]:
    """:func:`time_fraction` of every row of ``flags`` (the same reductions, along the rows)."""
    x = flags.astype(float)
    if periodic or x.shape[1] < 2 or t[-1] <= t[0]:
        return [float(v) for v in x.mean(axis=1)] if x.shape[1] else [0.0] * x.shape[0]
    return [float(v / (t[-1] - t[0])) for v in np.sum(0.5 * (x[:, 1:] + x[:, :-1]) * np.diff(t)[None, :], axis=1)]


def time_fraction(t: np.ndarray, flag: np.ndarray, *, periodic: bool) -> float:
    """Fraction of the window ``t[0] .. t[-1]`` where ``flag`` holds, from the samples: the trapezoid
    rule on the sample grid; for whole periods sampled uniformly without their closing sample
    (``periodic``), the plain mean, which is the trapezoid rule of the periodic signal."""
    return _time_fractions(t, np.asarray(flag)[None, :], periodic)[0]


def mesh_response(t: np.ndarray, mask: np.ndarray | slice, dte_um: np.ndarray, ft: np.ndarray, pen_mm: np.ndarray,
                  static_tangential_N: float, *, periodic: bool = False, gapless: bool = False) -> dict:
    """DTE statistics (rms about the mean), the time fractions without contact and in contact on the back
    flank, and the impact regime, over the window ``mask``.

    Without contact: the teeth inside the backlash (zero penetration; a viscous ``damping_ratio`` mesh still
    carries its damping force there) or pressed with a zero force (the IMPACT law's clamp). The loaded flank
    is the one the static load presses (the drive flank when the load is zero); the back flank is the other
    one. Regime: "no impact" when no sample of the window is without contact, "single-sided impact" when
    some is but none touches the back flank, else "double-sided impact". A ``gapless`` mesh (no backlash) that
    moves to its back flank without a sample out of contact has no gap to cross and strikes nothing: "no impact"
    (its force reverses, which the contact-loss warning says); a mesh with backlash that touches its back flank
    has crossed the gap, sampled or not: "double-sided impact".
    """
    return _responses(t[mask], dte_um[mask][None, :], ft[mask][None, :], pen_mm[mask][None, :], [static_tangential_N],
                      periodic, gapless=[gapless])[0]


def _responses(tw: np.ndarray, q: np.ndarray, f: np.ndarray, p: np.ndarray, static_tangential_N: Sequence[float],
               periodic: bool, q_stats: tuple[np.ndarray | Sequence[float], ...] | None = None,
               gapless: Sequence[bool] = (), contact: tuple | None = None) -> list[dict]:
    """:func:`mesh_response` of every row of the window's DTE ``q``, F_t ``f`` and penetration ``p`` (a stage a row,
    ``tw`` the window's times): one reduction along the rows each (numpy reduces a contiguous row as the row
    alone, so a single row gives the 1-D numbers); ``q_stats``: the rows' (window means, std, min, max) and
    ``contact`` their :func:`_contact` where the caller has reduced them already."""
    lost_fraction, back_fraction, any_lost, any_back = contact if contact is not None \
        else _contact(tw, f, p, q, static_tangential_N, periodic)
    means, stds, mins, maxs = q_stats if q_stats is not None else (window_means(tw, q, periodic), q.std(axis=1),
                                                                    q.min(axis=1), q.max(axis=1))
    return [{"dte_um": DteStats(float(means[k]), float(stds[k]), float(mins[k]), float(maxs[k])),
             "contact_loss_fraction": lost_fraction[k], "back_flank_fraction": back_fraction[k],
             "regime": _regime(bool(any_lost[k]), bool(any_back[k]), k < len(gapless) and bool(gapless[k]))}
            for k in range(q.shape[0])]


def _regime(lost: bool, back: bool, gapless: bool) -> str:
    """The impact regime of :func:`mesh_response` from whether a sample was out of contact, one on the back flank,
    and whether the mesh has no backlash (then a move to the back flank without a lost sample crosses no gap)."""
    if back and (lost or not gapless):
        return REGIME_DOUBLE_SIDED
    return REGIME_SINGLE_SIDED if lost else REGIME_NO_IMPACT


def impact_damped(mesh: MeshSpec) -> bool:
    """Whether the mesh's damping is the IMPACT STEP ramp (a positive C and no ``damping_ratio``): only then has it
    a full-damping depth; a viscous mesh (``damping_ratio``, the round-4 default) keeps C and d unused."""
    return mesh.damping_ratio is None and mesh.damping_Ns_m > 0


def loaded_flank(load_factor: float) -> float:
    """-1 where the load law's torque at the operating point (``load_factor`` x the nominal one,
    :func:`gearcli.model.damping.operating_load_factor`) has the other sign than the nominal one, whose static forces
    name the loaded flank (a torque_speed table through 0: the train runs with its other flank loaded); else 1."""
    return -1.0 if load_factor < 0.0 else 1.0


def contact_warnings(spec: ModelSpec, mask: np.ndarray, penetration_m: list[np.ndarray | None],
                     static_penetration_m: np.ndarray, reduced: Reduced | None = None,
                     planets: Sequence[Diagnostic] = (), flank: float = 1.0) -> list[Diagnostic]:
    """Penetration beyond the full-damping depth (IMPACT-damped meshes) or 10 % of the module; loss of contact on the loaded
    flank in the steady window (a loaded mesh that separates or crosses to its other flank rattles).

    The full-damping depth d is read two ways: the seed paper calls it the "maximum allowable
    penetration", while in Adams it is only where the damping ramp ends, often set below the static
    approach on purpose (configs/industrial_two_stage.toml). The warning is given only when the static
    penetration lies below d, i.e. when the law was set up in the seed's sense and a transient exceeds it.

    ``planets``: the planet meshes' contact-loss warnings, with the planet named
    (:func:`gearcli.simulate.planet_stats.planet_contact_warnings`), added to the list; a planetary stage among them
    is not warned again for its channel, planet 1's sun mesh (one of theirs). ``flank``: :func:`loaded_flank`.

    ``reduced``: the window's reductions of the same stages (:func:`window_reductions`), where the caller has them:
    a loaded flank loses contact in the window exactly when the window's least (drive flank) or largest (back flank)
    penetration is on the other side of 0 (:meth:`Reduced.penetration`: a finite one's sign that of the metres its
    millimetres scale); the samples are read only for a warning's fraction.
    """
    out, planet_stages = [], {d.data["stage"] for d in planets}
    sel = window_slice(mask) if reduced is None else None  # the window's samples read in place
    for k, (m, pen) in enumerate(zip(spec.meshes, penetration_m, strict=True)):
        if pen is None:  # a stage whose connector is no mesh (a belt's span): no contact to lose
            continue
        deepest = float(np.max(np.abs(pen)))
        if impact_damped(m) and static_penetration_m[k] < m.full_damping_m < deepest:
            out.append(dg.warning(dg.PENETRATION_BEYOND_DAMPING, f"stage {k + 1}: penetration reached "
                                  f"{deepest * 1e3:.3g} mm, beyond the full-damping depth {m.full_damping_m * 1e3:.3g} mm "
                                  "(the damping saturates there)", stage=k + 1, penetration_m=deepest))
        if m.normal_module_m > 0 and deepest > PENETRATION_MODULE_FRACTION * m.normal_module_m:
            out.append(dg.warning(dg.PENETRATION_OVER_MODULE, f"stage {k + 1}: penetration reached "
                                  f"{deepest * 1e3:.3g} mm, more than 10 % of the normal module "
                                  f"({m.normal_module_m * 1e3:.3g} mm): the contact law is far outside its validity",
                                  stage=k + 1, penetration_m=deepest))
        loaded = flank * math.copysign(1.0, m.static_tangential_N)  # the flank that carries the static load
        if k + 1 in planet_stages or m.static_tangential_N == 0 or not _loses_contact(pen, mask, sel, loaded,
                                                            None if reduced is None else reduced.penetration(k)):
            continue
        lost = loaded * pen[window_slice(mask) if sel is None else sel] <= 0.0
        if np.any(lost):
            out.append(dg.warning(dg.CONTACT_LOSS, f"stage {k + 1}: {contact_loss_words(loaded, m, lost)}",
                                  stage=k + 1, fraction=float(lost.mean())))
    return out + list(planets)


def contact_loss_words(loaded: float, m: MeshSpec, lost: np.ndarray) -> str:
    """The contact-loss warning's words for a mesh whose ``loaded`` flank (+1 drive, -1 back) loses contact at the
    window's samples ``lost``."""
    flank = "drive" if loaded > 0 else "back"
    what = ("tooth impacts (rattle) — the load is too small for the vibration" if m.backlash_m > 0 else
            "without backlash the other flank takes the force at once, no gap to cross and no impact, but the "
            "mesh force reverses — the vibration's force exceeds the static load")
    return f"the loaded ({flank}) flank loses contact in the steady window ({100.0 * lost.mean():.3g} % of the samples): {what}"


def _loses_contact(pen: np.ndarray, mask: np.ndarray, sel: slice | np.ndarray | None, loaded: float,
                   extremes: tuple[float, float] | None) -> bool:
    """Whether a sample of the window has ``loaded * pen <= 0`` (:func:`contact_warnings`): from the window's least
    and largest penetration where both are finite, else from the samples."""
    if extremes is not None and math.isfinite(extremes[0]) and math.isfinite(extremes[1]):
        return extremes[0] <= 0.0 if loaded > 0 else extremes[1] >= 0.0
    return bool(np.any(loaded * pen[window_slice(mask) if sel is None else sel] <= 0.0))


def peak_warnings(spec: ModelSpec, peak_line_forces_N, rigid_line_forces_N) -> list[Diagnostic]:
    """A run-up peak far above the rigid-body estimate is an impact or a numerical artefact; with a drive or
    a load applied instantly (``ramp_s = 0``) it is the physical shock of that step, which no tolerance
    removes: the fix named is then a ramp."""
    instant = [name for name, ramp, value in (("[input]", spec.drive.ramp_s, spec.drive.speed_rad_s
                                                if spec.drive.kind == "speed" else spec.drive.torque_Nm),
                                               ("[load]", spec.load.ramp_s, spec.load.torque_Nm))
               if ramp == 0 and value != 0]
    if instant:
        fix = (f"the {' and '.join(instant)} step{'s' if len(instant) > 1 else ''} at t = 0 (ramp_s = 0) "
               "shock the mesh: give ramp_s > 0 (several periods of the lowest natural frequency) for a smooth "
               "run-up; a tighter rtol does not change a physical shock")
    else:
        fix = "a violent impact or a numerical artefact — check with a tighter rtol"
    out = []
    for k, (peak, rigid) in enumerate(zip(peak_line_forces_N, rigid_line_forces_N, strict=True)):
        if rigid > 0 and peak > WARN_PEAK_OVER_RIGID * rigid:
            out.append(dg.warning(dg.PEAK_OVER_RIGID, f"stage {k + 1}: peak mesh force is {peak / rigid:.3g}x the "
                                  f"rigid-body estimate of the run (inertia plus load): {fix}", stage=k + 1,
                                  ratio=peak / rigid))
    return out


def model_warnings(spec: ModelSpec) -> list[Diagnostic]:
    """Warnings about the model itself, before the run (none at present: stage efficiencies act in the dynamics)."""
    return []


def ratio_of(mean_in: float, mean_out: float) -> tuple[float, list[Diagnostic]]:
    """mean w_in / mean w_out; 0 with a warning when the output stands still."""
    if abs(mean_out) <= 1e-12 * max(abs(mean_in), 1.0) or not math.isfinite(mean_in / mean_out):
        return 0.0, [dg.warning(dg.OUTPUT_STANDS_STILL,
                                "the output shaft stands still in the steady window: the dynamic ratio is undefined (0)")]
    return mean_in / mean_out, []
