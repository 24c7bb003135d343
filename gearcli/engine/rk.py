"""The explicit Runge-Kutta driver (:func:`rk_run`): ``scipy.integrate``'s ``RungeKutta`` loop transcribed, the method
read as data (a :class:`~gearcli.engine.tableau.Tableau`: DOP853 or RK45).

The initial step of ``select_initial_step`` and the step ceiling ``max_step`` (``wpar[WP_MAX_STEP]``), the stage
sums, the error norm (DOP853's combined 5th/3rd-order one), SAFETY 0.9, MIN_FACTOR 0.2, MAX_FACTOR 10, the
rejected-step rule (no growth right after a rejection), the minimum step ``10 ulp(t)``, the clamp at ``t_bound``, and
the dense output (DOP853's three extra stages, counted in nfev as scipy counts them) at the requested samples. The
run is integrated in segments between the ramp ends, with a fresh solver (and initial step) at each, as
:mod:`gearcli.simulate.solver` does.
"""

from __future__ import annotations

import math

import numpy as np

from gearcli.engine.common import select_initial_step
from gearcli.engine.guards import STATUS_FINISHED, WP_MAX_STEP, WP_SCALE, WP_T0, guards, start, step_accepted
from gearcli.engine.linalg import dot_self, gemm, gemv_t
from gearcli.engine.numba_cache import jit, jit_alloc
from gearcli.engine.rhs import rhs
from gearcli.engine.status import FAILED as STATUS_FAILED
from gearcli.engine.tableau import KIND_RK45

# scipy's step-size control (rk.py, common.py)
SAFETY, MIN_FACTOR, MAX_FACTOR = 0.9, 0.2, 10.0


@jit
def _stage_sum(K, a, s, h, y, dst, dv):
    """dst = y + (K[:s].T @ a[:s]) * h."""
    gemv_t(K, s, a, dv)
    for i in range(y.size):
        dst[i] = y[i] + dv[i] * h

@jit
def rk_step(t, y, f, h, K, y_new, f_new, ytmp, dv, model, th, fc, tab):
    """scipy's ``rk_step``: the stages of the tableau ``tab``, then ``f(t + h, y_new)``."""
    C, A, B = tab.c, tab.a, tab.b
    s_n = B.size
    n = y.size
    for i in range(n):
        K[0, i] = f[i]
    for s in range(1, s_n):
        _stage_sum(K, A[s], s, h, y, ytmp, dv)
        rhs(t + C[s] * h, ytmp, K[s], model, th, fc)
    gemv_t(K, s_n, B, dv)
    for i in range(n):
        y_new[i] = y[i] + h * dv[i]
    rhs(t + h, y_new, f_new, model, th, fc)
    for i in range(n):
        K[s_n, i] = f_new[i]

@jit
def error_norm(K, h, scale, e5, e3, tab):
    """The step's error estimate: DOP853's combined 5th/3rd-order one (``DOP853._estimate_error_norm``), or
    RK45's ``norm(np.dot(K.T, E) * h / scale)``."""
    n = scale.size
    s_n = tab.b.size
    if tab.kind == KIND_RK45:
        gemv_t(K, s_n + 1, tab.e, e5)
        for i in range(n):
            e5[i] = e5[i] * h / scale[i]
        return math.sqrt(dot_self(e5)) / n ** 0.5
    gemv_t(K, s_n + 1, tab.e, e5)
    gemv_t(K, s_n + 1, tab.e3, e3)
    for i in range(n):
        e5[i] = e5[i] / scale[i]
        e3[i] = e3[i] / scale[i]
    r5 = math.sqrt(dot_self(e5))
    r3 = math.sqrt(dot_self(e3))
    n5 = r5 * r5
    n3 = r3 * r3
    if n5 == 0.0 and n3 == 0.0:
        return 0.0
    denom = n5 + 0.01 * n3
    return abs(h) * n5 / math.sqrt(denom * n)

@jit
def dense_coefficients(t_old, h, y_old, y, f, K, F, ytmp, dv, DK, model, th, fc, tab):
    """The interpolant of the step just taken, into F: DOP853's three extra stages and its 7th-order
    coefficients (INTERPOLATOR_POWER x n), or RK45's Q = K.T P (stored as F[c, i]); the extra evaluations."""
    n = y.size
    s_n = tab.b.size
    Dm = tab.dense
    if tab.kind == KIND_RK45:
        for i in range(n):
            for c in range(Dm.shape[1]):
                acc = 0.0
                for j in range(s_n + 1):
                    acc += K[j, i] * Dm[j, c]
                F[c, i] = acc
        return 0
    a_extra, c_extra = tab.a_extra, tab.c_extra
    for k in range(a_extra.shape[0]):
        s = s_n + 1 + k
        _stage_sum(K, a_extra[k], s, h, y_old, ytmp, dv)
        rhs(t_old + c_extra[k] * h, ytmp, K[s], model, th, fc)
    gemm(Dm, K, DK)
    for i in range(n):
        dy = y[i] - y_old[i]
        f_old = K[0, i]
        F[0, i] = dy
        F[1, i] = h * f_old - dy
        F[2, i] = 2 * dy - h * (f[i] + f_old)
        for r in range(Dm.shape[0]):
            F[3 + r, i] = h * DK[r, i]
    return a_extra.shape[0]

@jit
def dense_eval(t, t_old, h, y_old, F, out, col, tab):
    """The interpolant at one time, into ``out[:, col]`` (``Dop853DenseOutput`` / ``RkDenseOutput``)."""
    x = (t - t_old) / h
    if tab.kind == KIND_RK45:
        x2 = x * x
        x3 = x2 * x
        x4 = x3 * x
        for i in range(y_old.size):
            out[i, col] = h * (F[0, i] * x + F[1, i] * x2 + F[2, i] * x3 + F[3, i] * x4) + y_old[i]
        return
    n_interp = F.shape[0]
    for i in range(y_old.size):
        v = 0.0
        for k in range(n_interp):
            v += F[n_interp - 1 - k, i]
            if k % 2 == 0:
                v *= x
            else:
                v *= 1 - x
        out[i, col] = v + y_old[i]

@jit_alloc
def rk_run(model, y0, t_eval, breaks, rtol, atol, max_nfev, watch_every, wpar, trace, tab):
    """The explicit Runge-Kutta driver: scipy's ``RungeKutta`` loop for the tableau ``tab`` (DOP853 or RK45,
    :data:`gearcli.engine.tableau.DOP853_TABLEAU`, a :class:`~gearcli.engine.tableau.Tableau`), step for step.

    Integrate from t0 = ``wpar[4]`` through the segments ending at ``breaks`` (the last is ``t_eval[-1]``),
    sampling at ``t_eval``; ``rtol`` and ``atol`` are per-state vectors. ``watch_every`` 0 switches the
    energy watch off; ``wpar``: see ``WP_*`` (5 entries: no priced work budget). The times of the first
    ``trace.size`` accepted steps are written to ``trace`` (tests; pass an empty array). Returns (samples,
    counters [nfev, steps, status, samples done], floats [t reached, energy created, energy scale], y)."""
    n = y0.size
    s_n = tab.b.size
    n_extra = tab.a_extra.shape[0]
    error_exponent = -1.0 / (tab.error_order + 1)
    nb = model.inertia.shape[0]
    nc = model.kind.shape[0]
    th = np.zeros(nb)
    fc = np.zeros(4 * nc)
    K = np.zeros((s_n + 1 + n_extra, n))
    n_dense = tab.dense.shape[0] + 3 if tab.kind != KIND_RK45 else tab.dense.shape[1]
    F = np.zeros((n_dense, n))
    y = y0.copy()
    f = np.empty(n)
    y_new = np.empty(n)
    f_new = np.empty(n)
    ytmp = np.empty(n)
    scale = np.empty(n)
    w1 = np.empty(n)
    w2 = np.empty(n)
    dv = np.empty(n)
    e3 = np.empty(n)
    DK = np.empty((tab.dense.shape[0], n))
    watched = np.array([0.0, wpar[WP_SCALE]])
    out, done = start(y0, t_eval, wpar)
    t = wpar[WP_T0]  # the run's start (a continuation starts later)
    max_step = wpar[WP_MAX_STEP] if wpar.size > WP_MAX_STEP else np.inf  # scipy's max_step
    nfev = 0
    steps = 0
    status = STATUS_FINISHED
    for seg in range(breaks.size):
        t_bound = breaks[seg]
        seg_nfev = 0
        rhs(t, y, f, model, th, fc)
        seg_nfev += 1
        h_abs = select_initial_step(t, y, t_bound, f, rtol, atol, model, th, fc, w1, w2, scale, ytmp, dv,
                                    -error_exponent, max_step)
        seg_nfev += 1
        while True:
            min_step = 10 * abs(np.nextafter(t, np.inf) - t)
            if h_abs > max_step:
                h_abs = max_step
            elif h_abs < min_step:
                h_abs = min_step
            accepted_step = False
            rejected = False
            h = 0.0
            t_new = t
            while not accepted_step:
                if h_abs < min_step:
                    break
                h = h_abs
                t_new = t + h
                if t_new - t_bound > 0:
                    t_new = t_bound
                h = t_new - t
                h_abs = abs(h)
                rk_step(t, y, f, h, K, y_new, f_new, ytmp, dv, model, th, fc, tab)
                seg_nfev += s_n
                for i in range(n):
                    a = abs(y[i])
                    b = abs(y_new[i])
                    scale[i] = atol[i] + (a if a > b or a != a else b) * rtol[i]  # np.maximum: NaN wins
                err = error_norm(K, h, scale, dv, e3, tab)
                if err < 1:
                    if err == 0:
                        factor = MAX_FACTOR
                    else:
                        factor = SAFETY * err ** error_exponent
                        if not factor < MAX_FACTOR:
                            factor = MAX_FACTOR
                    if rejected and not factor < 1.0:
                        factor = 1.0
                    h_abs *= factor
                    accepted_step = True
                else:
                    factor = SAFETY * err ** error_exponent
                    h_abs *= factor if factor > MIN_FACTOR else MIN_FACTOR
                    rejected = True
            if not accepted_step:
                status = STATUS_FAILED
                break
            t_old = t
            for i in range(n):
                ytmp[i] = y[i]  # y_old
                y[i] = y_new[i]
                f[i] = f_new[i]
            t = t_new
            finished = t - t_bound >= 0
            steps += 1
            status, upto = step_accepted(t, y, steps, trace, t_eval, done)
            if status != STATUS_FINISHED:
                break
            if upto > done:
                # y_old is kept in w1 for the interpolant: ytmp is the stage scratch
                for i in range(n):
                    w1[i] = ytmp[i]
                seg_nfev += dense_coefficients(t_old, h, w1, y, f, K, F, ytmp, dv, DK, model, th, fc, tab)
                hd = t - t_old
                for j in range(done, upto):
                    dense_eval(t_eval[j], t_old, hd, w1, F, out, j, tab)
                done = upto
            status = guards(t, y, nfev + seg_nfev, 0, 0, steps, finished, max_nfev, watch_every, wpar, model, watched)
            if status != STATUS_FINISHED or finished:
                break
        nfev += seg_nfev
        if status != STATUS_FINISHED:
            break
    counters = np.array([nfev, steps, status, done], dtype=np.int64)
    floats = np.array([t, watched[0], watched[1]])
    return out, counters, floats, y
