"""Radau IIA (order 5) as scipy's ``Radau`` with the analytic Jacobian (:func:`radau`): the same Newton iteration,
LU reuse, error estimate (refined after a rejection), step-size prediction and dense output; segments, sampling,
guards and returns as :func:`gearcli.engine.rk.rk_run`. Its results agree with scipy's to the tolerance: the LU is
not LAPACK's to the last bit.
"""

from __future__ import annotations

import numpy as np

from gearcli.engine.common import select_initial_step
from gearcli.engine.guards import STATUS_FINISHED, WP_MAX_STEP, WP_SCALE, WP_T0, guards, start, step_accepted
from gearcli.engine.jacobian import jacobian
from gearcli.engine.linalg import _rms, _rms_matrix, lu_factor, lu_solve
from gearcli.engine.numba_cache import jit, jit_alloc
from gearcli.engine.rhs import rhs
from gearcli.engine.rk import MAX_FACTOR, MIN_FACTOR
from gearcli.engine.status import FAILED as STATUS_FAILED

# scipy/integrate/_ivp/radau.py: the method's constants (Hairer & Wanner, "Solving ODEs II", Sec. IV.8)
S6 = 6 ** 0.5
RC = np.array([(4 - S6) / 10, (4 + S6) / 10, 1])
RE = np.array([-13 - 7 * S6, -13 + 7 * S6, -1]) / 3
MU_REAL = 3 + 3 ** (2 / 3) - 3 ** (1 / 3)
MU_COMPLEX = (3 + 0.5 * (3 ** (1 / 3) - 3 ** (2 / 3)) - 0.5j * (3 ** (5 / 6) + 3 ** (7 / 6)))
RT = np.array([[0.09443876248897524, -0.14125529502095421, 0.03002919410514742],
               [0.25021312296533332, 0.20412935229379994, -0.38294211275726192],
               [1.0, 1.0, 0.0]])
RTI = np.array([[4.17871859155190428, 0.32768282076106237, 0.52337644549944951],
                [-4.17871859155190428, -0.32768282076106237, 0.47662355450055044],
                [0.50287263494578682, -2.57192694985560522, 0.59603920482822492]])
RP = np.array([[13 / 3 + 7 * S6 / 3, -23 / 3 - 22 * S6 / 3, 10 / 3 + 5 * S6],
               [13 / 3 - 7 * S6 / 3, -23 / 3 + 22 * S6 / 3, 10 / 3 - 5 * S6],
               [1 / 3, -8 / 3, 10 / 3]])
NEWTON_MAXITER = 6
EPS = float(np.finfo(float).eps)


@jit
def _factor(Jm, h, LUr, pr, LUc, pc):
    n = Jm.shape[0]
    mr = MU_REAL / h
    mc = MU_COMPLEX / h
    for i in range(n):
        for j in range(n):
            LUr[i, j] = -Jm[i, j]
            LUc[i, j] = -Jm[i, j]
        LUr[i, i] += mr
        LUc[i, i] += mc
    lu_factor(LUr, pr)
    lu_factor(LUc, pc)

@jit
def collocation(t, y, h, Z0, scale, tol, LUr, pr, LUc, pc, Z, W, F, dW, br, bc, ytmp, model, th, fc):
    """scipy's ``solve_collocation_system``: (converged, iterations, rate, evaluations); Z holds the result."""
    n = y.size
    mr = MU_REAL / h
    mc = MU_COMPLEX / h
    for r in range(3):
        for i in range(n):
            W[r, i] = RTI[r, 0] * Z0[0, i] + RTI[r, 1] * Z0[1, i] + RTI[r, 2] * Z0[2, i]
            Z[r, i] = Z0[r, i]
    dw_old = -1.0
    rate = -1.0
    converged = False
    nfev = 0
    k = 0
    for k in range(NEWTON_MAXITER):
        finite = True
        for r in range(3):
            for i in range(n):
                ytmp[i] = y[i] + Z[r, i]
            rhs(t + h * RC[r], ytmp, F[r], model, th, fc)
            nfev += 1
            for i in range(n):
                if not np.isfinite(F[r, i]):
                    finite = False
        if not finite:
            break
        for i in range(n):
            br[i] = F[0, i] * RTI[0, 0] + F[1, i] * RTI[0, 1] + F[2, i] * RTI[0, 2] - mr * W[0, i]
            fcx = (F[0, i] * (RTI[1, 0] + 1j * RTI[2, 0]) + F[1, i] * (RTI[1, 1] + 1j * RTI[2, 1])
                   + F[2, i] * (RTI[1, 2] + 1j * RTI[2, 2]))
            bc[i] = fcx - mc * (W[1, i] + 1j * W[2, i])
        lu_solve(LUr, pr, br)
        lu_solve(LUc, pc, bc)
        for i in range(n):
            dW[0, i] = br[i]
            dW[1, i] = bc[i].real
            dW[2, i] = bc[i].imag
        dw = _rms_matrix(dW, scale)
        if dw_old >= 0.0:
            rate = dw / dw_old
        if rate >= 0.0 and (rate >= 1 or rate ** (NEWTON_MAXITER - k) / (1 - rate) * dw > tol):
            break
        for r in range(3):
            for i in range(n):
                W[r, i] += dW[r, i]
        for r in range(3):
            for i in range(n):
                Z[r, i] = RT[r, 0] * W[0, i] + RT[r, 1] * W[1, i] + RT[r, 2] * W[2, i]
        if dw == 0 or (rate >= 0.0 and rate / (1 - rate) * dw < tol):
            converged = True
            break
        dw_old = dw
    return converged, k + 1, rate, nfev

@jit
def predict_factor(h_abs, h_abs_old, err, err_old):
    """scipy's ``predict_factor`` (old values < 0 stand for None)."""
    if err_old < 0 or h_abs_old < 0 or err == 0:
        multiplier = 1.0
    else:
        multiplier = h_abs / h_abs_old * (err_old / err) ** 0.25
    m = multiplier if multiplier < 1 else 1.0
    if err == 0:
        return np.inf
    return m * err ** -0.25

@jit_alloc
def radau(model, y0, t_eval, breaks, rtol, atol, max_nfev, watch_every, wpar, trace):
    """Radau IIA (order 5) as scipy's ``Radau`` with the analytic Jacobian: the same Newton iteration, LU
    reuse, error estimate (refined after a rejection), step-size prediction and dense output; segments,
    sampling, guards and returns as :func:`rk_run` (the same after-step helpers; counters add njev and nlu).
    rtol enters the Newton tolerance through its smallest component."""
    n = y0.size
    nb = model.inertia.shape[0]
    nc = model.kind.shape[0]
    th = np.zeros(nb)
    fc = np.zeros(4 * nc)
    y = y0.copy()
    f = np.empty(n)
    f_new = np.empty(n)
    y_new = np.empty(n)
    ytmp = np.empty(n)
    scale = np.empty(n)
    w1 = np.empty(n)
    w2 = np.empty(n)
    w3 = np.empty(n)
    w4 = np.empty(n)
    err_v = np.empty(n)
    ze = np.empty(n)
    Jm = np.zeros((n, n))
    g = np.zeros(n)
    ag = np.zeros(n)
    LUr = np.zeros((n, n))
    LUc = np.zeros((n, n), dtype=np.complex128)
    pr = np.zeros(3 * n, dtype=np.int64)  # pivots and the factors' row spans (lu_factor)
    pc = np.zeros(3 * n, dtype=np.int64)
    Z = np.zeros((3, n))
    Z0 = np.zeros((3, n))
    W = np.zeros((3, n))
    F = np.zeros((3, n))
    dW = np.zeros((3, n))
    br = np.zeros(n)
    bc = np.zeros(n, dtype=np.complex128)
    Q = np.zeros((n, 3))
    y_old = np.empty(n)
    rmin = rtol[0]
    for i in range(n):
        if rtol[i] < rmin:
            rmin = rtol[i]
    newton_tol = max(10 * EPS / rmin, min(0.03, rmin ** 0.5))
    watched = np.array([0.0, wpar[WP_SCALE]])
    out, done = start(y0, t_eval, wpar)
    t = wpar[WP_T0]  # the run's start (a continuation starts later)
    max_step = wpar[WP_MAX_STEP] if wpar.size > WP_MAX_STEP else np.inf  # scipy's max_step
    nfev = 0
    njev = 0
    nlu = 0
    steps = 0
    status = STATUS_FINISHED
    for seg in range(breaks.size):
        t_bound = breaks[seg]
        seg_nfev = 0
        rhs(t, y, f, model, th, fc)
        seg_nfev += 1
        h_self = select_initial_step(t, y, t_bound, f, rtol, atol, model, th, fc, w1, w2, scale, w3, w4, 0.25,
                                     max_step)
        seg_nfev += 1
        h_abs_old_self = -1.0
        err_old_self = -1.0
        have_sol = False
        sol_t_old = 0.0
        sol_h = 1.0
        jacobian(t, y, Jm, model, th, g, ag)
        njev += 1
        current_jac = True
        lu_ok = False
        while True:
            min_step = 10 * abs(np.nextafter(t, np.inf) - t)
            if h_self > max_step:  # scipy's order: the ceiling first, then the floor
                h_abs = max_step
                h_abs_old = -1.0
                err_old = -1.0
            elif h_self < min_step:
                h_abs = min_step
                h_abs_old = -1.0
                err_old = -1.0
            else:
                h_abs = h_self
                h_abs_old = h_abs_old_self
                err_old = err_old_self
            rejected = False
            accepted = False
            failed = False
            h = 0.0
            t_new = t
            n_iter = 0
            rate = -1.0
            err = 0.0
            safety = 0.9
            while not accepted:
                if h_abs < min_step:
                    failed = True
                    break
                h = h_abs
                t_new = t + h
                if t_new - t_bound > 0:
                    t_new = t_bound
                h = t_new - t
                h_abs = abs(h)
                for r in range(3):
                    if have_sol:
                        x = (t + h * RC[r] - sol_t_old) / sol_h
                        for i in range(n):
                            Z0[r, i] = (Q[i, 0] * x + Q[i, 1] * x * x + Q[i, 2] * x * x * x + y_old[i]) - y[i]
                    else:
                        for i in range(n):
                            Z0[r, i] = 0.0
                for i in range(n):
                    scale[i] = atol[i] + abs(y[i]) * rtol[i]
                converged = False
                while not converged:
                    if not lu_ok:
                        _factor(Jm, h, LUr, pr, LUc, pc)
                        nlu += 2
                        lu_ok = True
                    converged, n_iter, rate, ne = collocation(t, y, h, Z0, scale, newton_tol, LUr, pr, LUc, pc, Z, W,
                                                              F, dW, br, bc, ytmp, model, th, fc)
                    seg_nfev += ne
                    if not converged:
                        if current_jac:
                            break
                        jacobian(t, y, Jm, model, th, g, ag)
                        njev += 1
                        current_jac = True
                        lu_ok = False
                if not converged:
                    h_abs *= 0.5
                    lu_ok = False
                    continue
                for i in range(n):
                    y_new[i] = y[i] + Z[2, i]
                    ze[i] = (Z[0, i] * RE[0] + Z[1, i] * RE[1] + Z[2, i] * RE[2]) / h
                    err_v[i] = f[i] + ze[i]
                lu_solve(LUr, pr, err_v)
                for i in range(n):
                    a = abs(y[i])
                    b = abs(y_new[i])
                    scale[i] = atol[i] + (a if a > b or a != a else b) * rtol[i]
                err = _rms(err_v, scale, w1)
                safety = 0.9 * (2 * NEWTON_MAXITER + 1) / (2 * NEWTON_MAXITER + n_iter)
                if rejected and err > 1:
                    for i in range(n):
                        ytmp[i] = y[i] + err_v[i]
                    rhs(t, ytmp, w2, model, th, fc)
                    seg_nfev += 1
                    for i in range(n):
                        err_v[i] = w2[i] + ze[i]
                    lu_solve(LUr, pr, err_v)
                    err = _rms(err_v, scale, w1)
                if err > 1:
                    factor = predict_factor(h_abs, h_abs_old, err, err_old)
                    sf = safety * factor
                    h_abs *= sf if sf > MIN_FACTOR else MIN_FACTOR
                    lu_ok = False
                    rejected = True
                else:
                    accepted = True
            if failed:
                status = STATUS_FAILED
                break
            recompute_jac = n_iter > 2 and rate > 1e-3
            factor = predict_factor(h_abs, h_abs_old, err, err_old)
            factor = safety * factor
            if not factor < MAX_FACTOR:
                factor = MAX_FACTOR
            if not recompute_jac and factor < 1.2:
                factor = 1.0
            else:
                lu_ok = False
            rhs(t_new, y_new, f_new, model, th, fc)
            seg_nfev += 1
            if recompute_jac:
                jacobian(t_new, y_new, Jm, model, th, g, ag)
                njev += 1
                current_jac = True
            else:
                current_jac = False
            h_abs_old_self = h_self
            err_old_self = err
            h_self = h_abs * factor
            for i in range(n):
                y_old[i] = y[i]
                y[i] = y_new[i]
                f[i] = f_new[i]
                for k in range(3):
                    Q[i, k] = Z[0, i] * RP[0, k] + Z[1, i] * RP[1, k] + Z[2, i] * RP[2, k]
            sol_t_old = t
            t = t_new
            sol_h = t - sol_t_old
            have_sol = True
            finished = t - t_bound >= 0
            steps += 1
            status, upto = step_accepted(t, y, steps, trace, t_eval, done)
            if status != STATUS_FINISHED:
                break
            for j in range(done, upto):
                x = (t_eval[j] - sol_t_old) / sol_h
                for i in range(n):
                    out[i, j] = Q[i, 0] * x + Q[i, 1] * x * x + Q[i, 2] * x * x * x + y_old[i]
            done = upto
            status = guards(t, y, nfev + seg_nfev, njev, nlu, steps, finished, max_nfev, watch_every, wpar, model,
                            watched)
            if status != STATUS_FINISHED or finished:
                break
        nfev += seg_nfev
        if status != STATUS_FINISHED:
            break
    counters = np.array([nfev, steps, status, done, njev, nlu], dtype=np.int64)
    floats = np.array([t, watched[0], watched[1]])
    return out, counters, floats, y
