"""The compiled kernel (numba): the scene's right-hand side read from :class:`~gearcli.model.ModelArrays` and
scipy's integrators step for step, with output sampling and the run's guards inside; this module is its face (the
entries a run and the tests call), the kernel's parts are its neighbours:

- :mod:`gearcli.engine.laws`: the element laws, dispatched by kind (generated from the registry), and the drive's
  and the load's laws, compiled from their own modules;
- :mod:`gearcli.engine.assembly`: the scene's right-hand side (the generated Python's, term for term, in the same
  floating-point order) and its stored energy; :mod:`gearcli.engine.jacobian` its analytic Jacobian;
  :mod:`gearcli.engine.rhs` the two together for a state that carries the variational equations;
- :mod:`gearcli.engine.rk`: one explicit Runge-Kutta driver reading its method as data (DOP853 and RK45,
  :class:`gearcli.engine.tableau.Tableau`), scipy's steps bit for bit; :mod:`gearcli.engine.radau`: scipy's
  Radau IIA; :mod:`gearcli.engine.common` the initial step both share;
- :mod:`gearcli.engine.guards`: after every accepted step (trace, non-finite state, the samples due, the
  evaluation budget, the priced work budget with its projection, the energy watch, the stop flag);
- :mod:`gearcli.engine.linalg`: scipy's vector sums through the same BLAS, its norm, the LU of Radau;
- :mod:`gearcli.engine.window`: a run's window statistics, numpy's numbers in one pass (the results').

Imported only through :func:`gearcli.engine.load` (which points numba's cache at the user's cache directory first).
Nothing here closes over a scene: every function takes the model as arrays (:mod:`gearcli.engine.packing`), so one
compilation serves every design file and every sweep point. Functions that allocate no array are compiled without
numba's reference counting (:func:`gearcli.engine.numba_cache.jit`). Status codes: :mod:`gearcli.engine.status`.
"""

from __future__ import annotations

import numpy as np

from gearcli.engine import status as st
from gearcli.engine import tableau as tb
from gearcli.engine.assembly import stored_energy  # noqa: F401 - the energy watch's test reads it here
from gearcli.engine.jacobian import jacobian
from gearcli.engine.laws import (  # noqa: F401 - the laws one sample at a time: tests
    KINDS,
    conn_channel,
    conn_channels,
    conn_force,
    conn_forces,
    conn_n_channels,
    conn_potential,
)
from gearcli.engine.linalg import lu_factor, lu_solve  # noqa: F401 - the LU's tests call them here
from gearcli.engine.numba_cache import jit_alloc
from gearcli.engine.radau import radau  # noqa: F401 - an entry (gearcli.engine.loader.ENTRIES)
from gearcli.engine.rhs import rhs
from gearcli.engine.rk import rk_run
from gearcli.engine.window import window_statistics  # noqa: F401 - the results' window statistics

STATUS_FINISHED, STATUS_FAILED, STATUS_BUDGET = st.FINISHED, st.FAILED, st.BUDGET
STATUS_NONFINITE, STATUS_ENERGY, STATUS_PROJECTED = st.NONFINITE, st.ENERGY, st.PROJECTED
STATUS_INTERRUPTED = st.INTERRUPTED
DOP853_TABLEAU, RK45_TABLEAU = tb.DOP853_TABLEAU, tb.RK45_TABLEAU


def dop853(model, y0, t_eval, breaks, rtol, atol, max_nfev, watch_every, wpar, trace):
    """scipy's DOP853, step for step: :func:`~gearcli.engine.rk.rk_run` with DOP853's tableau."""
    return rk_run(model, y0, t_eval, breaks, rtol, atol, max_nfev, watch_every, wpar, trace, DOP853_TABLEAU)


def rk45(model, y0, t_eval, breaks, rtol, atol, max_nfev, watch_every, wpar, trace):
    """scipy's RK45 (Dormand-Prince 5(4), quartic dense output), step for step: :func:`~gearcli.engine.rk.rk_run`
    with its tableau; the samples agree to the last bits (the interpolant is summed in a loop, not by BLAS)."""
    return rk_run(model, y0, t_eval, breaks, rtol, atol, max_nfev, watch_every, wpar, trace, RK45_TABLEAU)


@jit_alloc
def evaluate(model, t, y):
    """One right-hand side evaluation (tests, benchmarks)."""
    dy = np.empty(y.size)
    rhs(t, y, dy, model, np.zeros(model.inertia.shape[0]), np.zeros(4 * model.kind.shape[0]))
    return dy

@jit_alloc
def evaluate_many(model, t, y, times):
    """``times`` evaluations at one point (the benchmark's cost of one compiled evaluation)."""
    dy = np.empty(y.size)
    th = np.zeros(model.inertia.shape[0])
    fc = np.zeros(4 * model.kind.shape[0])
    acc = 0.0
    for _ in range(times):
        rhs(t, y, dy, model, th, fc)
        acc += dy[0]
    return acc

@jit_alloc
def connector_series(kind, P, d, dd, phi, wphi, energy_from, channels):
    """Force, stored energy and the element's own output channels (its ``CHANNELS``, rows of ``ch``) of one
    connector at every sample (:func:`gearcli.model.outputs.connector_series`, through the same element laws); the
    stored energy from sample ``energy_from`` on, NaN before it, and the first ``channels`` channels alone, zeros in
    the rows after them (not evaluated: a caller that reads them from there, or not at all)."""
    n = d.size
    F = np.empty(n)
    U = np.empty(n)
    ch = np.zeros((conn_n_channels(kind), n))
    rows = min(channels, ch.shape[0])
    conn_forces(kind, P, d, dd, phi, wphi, F)  # the kind chosen once for all the samples (not at each)
    for j in range(n):
        U[j] = conn_potential(kind, P, d[j], phi[j]) if j >= energy_from else np.nan
    for i in range(rows):
        conn_channels(kind, P, i, d, phi, ch[i])
    return F, U, ch

@jit_alloc
def connectors_series(kind, param, bodies, levers, ppr, flags, rows, Y, omega, theta, energy_from, channels, width):
    """:func:`connector_series` of every connector at once, each one's law arguments made here as
    :func:`gearcli.model.outputs.connector_series` makes them (the same operations in the same order): the
    deflection ``Y[rows[c]]``, its rate sum_s lever_s omega[body_s] in slot order, the mesh phase
    ``ppr[c] theta[bodies[c, 0]]`` where ``flags[c] & 1`` (phased, else 0) and its rate ``ppr[c] omega[bodies[c, 0]]``
    where ``flags[c] & 2`` (excited, else 0). The samples of ``Y`` are evaluated; ``width`` columns are returned, the
    last evaluated one repeated after them (a state held constant from there on: the equilibrium's statistics
    period). Returns (force, stored energy, channels, deflection): connectors x samples, the channels connectors x
    channel x samples (``channels[c]`` of them evaluated, zeros after)."""
    nc = kind.shape[0]
    n = Y.shape[1]
    nch = 0
    for c in range(nc):
        nch = max(nch, conn_n_channels(kind[c]))
    F = np.empty((nc, width))
    U = np.empty((nc, width))
    D = np.empty((nc, width))
    ch = np.empty((nc, nch, width))  # every row written below: evaluated and repeated, or zeros
    dd_s, phi_s, wphi_s = np.empty(n), np.empty(n), np.empty(n)  # a connector's law arguments at the samples
    e0 = max(0, min(energy_from, n))  # the first sample whose stored energy is evaluated
    for c in range(nc):
        k = kind[c]
        P = param[c]
        m = min(channels[c], conn_n_channels(k))
        a = bodies[c, 0]
        r = rows[c]
        for j in range(n):
            dd = levers[c, 0] * omega[a, j]
            for s in range(1, bodies.shape[1]):
                b = bodies[c, s]
                if b < 0:
                    break
                dd = dd + levers[c, s] * omega[b, j]
            dd_s[j] = dd
            phi_s[j] = ppr[c] * theta[a, j] if flags[c] & 1 else 0.0
            wphi_s[j] = ppr[c] * omega[a, j] if flags[c] & 2 else 0.0
        # the forces and each channel in one call each (the kind chosen once for all the samples, not at each: the
        # same law, the same numbers), the stored energy sample by sample; each row's last evaluated sample then
        # repeated to ``width`` by a slice (a loop over one row at a time: numba fills it as a block)
        conn_forces(k, P, Y[r], dd_s, phi_s, wphi_s, F[c])
        for i in range(m):
            conn_channels(k, P, i, Y[r], phi_s, ch[c, i])
            ch[c, i, n:] = ch[c, i, n - 1]
        ch[c, m:] = 0.0
        D[c, :n] = Y[r]
        U[c, :e0] = np.nan
        for j in range(e0, n):
            U[c, j] = conn_potential(k, P, Y[r, j], phi_s[j])
        F[c, n:] = F[c, n - 1]
        U[c, n:] = U[c, n - 1]
        D[c, n:] = D[c, n - 1]
    return F, U, ch, D

@jit_alloc
def evaluate_jacobian(model, t, y):
    """One Jacobian evaluation (tests)."""
    n = y.size
    Jm = np.zeros((n, n))
    jacobian(t, y, Jm, model, np.zeros(model.inertia.shape[0]), np.zeros(n), np.zeros(n))
    return Jm
