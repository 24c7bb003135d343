"""What every driver does after an accepted step (the explicit Runge-Kutta one and Radau), in the Python solver
loop's order (gearcli.simulate.solver._segment): count and trace the step, stop on a non-finite state, sample (the
driver's own interpolant, at the samples :func:`samples_due` names), then :func:`guards`: the evaluation budget,
the priced work budget with its projection (``RunTooLong``), the energy watch, the stop flag. And the output array
a run starts with (:func:`start`).
"""

from __future__ import annotations

import numpy as np

from gearcli.engine import status as st
from gearcli.engine.assembly import quadrature, stored_energy
from gearcli.engine.numba_cache import jit, jit_alloc
from gearcli.engine.packing import IP_Q_INPUT, IP_Q_LOAD

STATUS_FINISHED, STATUS_BUDGET, STATUS_NONFINITE = st.FINISHED, st.BUDGET, st.NONFINITE
STATUS_ENERGY, STATUS_PROJECTED, STATUS_INTERRUPTED = st.ENERGY, st.PROJECTED, st.INTERRUPTED
# wpar layout: the energy watch (e0, w0, scale, margin), the run's start t0, then (optional: a run without them has
# no priced work budget) the budget (cap, project after, projection limit, check every) and the prices
# (eval, jac, lu, step) of gearcli.core.cost, and the span (t_start, t_end) the pace is projected over
WP_E0, WP_W0, WP_SCALE, WP_MARGIN, WP_T0 = 0, 1, 2, 3, 4
WP_CAP, WP_AFTER, WP_LIMIT, WP_EVERY, WP_P_EVAL, WP_P_JAC, WP_P_LU, WP_P_STEP, WP_SPAN0, WP_SPAN1 = range(5, 15)
N_WPAR = 15
WP_PROGRESS = st.WP_PROGRESS  # optional: the time reached, written at every budget check (a progress bar reads it)
WP_STOP = st.WP_STOP  # optional: the stop flag a signal handler sets (gearcli.core.signals), read after every step
WP_MAX_STEP = st.WP_MAX_STEP  # optional: the explicit methods' step ceiling (scipy's max_step)


@jit
def step_accepted(t, y, steps, trace, t_eval, done):
    """The step count is ``steps`` (this step included): trace it, check the state; (status, samples due up to)."""
    if steps <= trace.size:
        trace[steps - 1] = t
    total = 0.0
    for i in range(y.size):
        total += y[i]
    if not np.isfinite(total):
        return STATUS_NONFINITE, done
    return STATUS_FINISHED, samples_due(t_eval, done, t)

@jit
def samples_due(t_eval, done, t):
    """The index past the last sample at or before ``t``, from ``done`` on."""
    upto = done
    while upto < t_eval.size and t_eval[upto] <= t:
        upto += 1
    return upto

@jit
def priced_work(nfev, njev, nlu, steps, wpar):
    """:func:`gearcli.core.cost.priced_work_s` with the prices in ``wpar``."""
    return nfev * wpar[WP_P_EVAL] + njev * wpar[WP_P_JAC] + nlu * wpar[WP_P_LU] + steps * wpar[WP_P_STEP]

@jit
def guards(t, y, nfev, njev, nlu, steps, finished, max_nfev, watch_every, wpar, model, watched):
    """The evaluation budget, the priced work budget (spent, or a pace projected over its limit: as
    :func:`gearcli.simulate.guards.over_budget`, checked every ``wpar[WP_EVERY]`` steps) and the energy watch
    every ``watch_every`` steps; ``watched`` receives (energy created, energy scale). At each budget check the
    time reached goes to ``wpar[WP_PROGRESS]`` when ``wpar`` has that entry (a progress bar). A raised stop flag
    (``wpar[WP_STOP]``, when present) ends the run at once. Returns a status."""
    if wpar.size > WP_STOP and wpar[WP_STOP] != 0.0:
        return STATUS_INTERRUPTED
    if nfev > max_nfev:
        return STATUS_BUDGET
    if wpar.size >= N_WPAR and steps % np.int64(wpar[WP_EVERY]) == 0:
        if wpar.size > WP_PROGRESS:
            wpar[WP_PROGRESS] = t
        work = priced_work(nfev, njev, nlu, steps, wpar)
        if work > wpar[WP_CAP]:
            return STATUS_BUDGET
        if work > wpar[WP_AFTER]:
            span = wpar[WP_SPAN1] - wpar[WP_SPAN0]
            frac = (t - wpar[WP_SPAN0]) / span if span > 0 else 1.0
            if frac <= 0 or work / frac > wpar[WP_LIMIT] * wpar[WP_CAP]:
                return STATUS_PROJECTED
    if watch_every > 0 and (steps % watch_every == 0 or finished):
        work = y[quadrature(model, IP_Q_INPUT)] - y[quadrature(model, IP_Q_LOAD)]
        watched[0] = (stored_energy(t, y, model) - wpar[WP_E0]) - (work - wpar[WP_W0])
        watched[1] = max(wpar[WP_SCALE], abs(work - wpar[WP_W0]))
        if watched[0] > wpar[WP_MARGIN] * watched[1]:
            return STATUS_ENERGY
    return STATUS_FINISHED

@jit_alloc
def start(y0, t_eval, wpar):
    """The output array with the samples at or before the run's start filled; (out, samples done)."""
    n = y0.size
    m = t_eval.size
    out = np.full((n, m), np.nan)
    done = 0
    while done < m and t_eval[done] <= wpar[WP_T0]:
        out[:, done] = y0
        done += 1
    for j in range(done, m):
        if t_eval[j] <= wpar[WP_T0]:
            out[:, j] = y0
    return out, done
