"""The right-hand side the integrators call: the scene's own (:mod:`gearcli.engine.assembly`) and, for a state
augmented with the variational equations (:mod:`gearcli.simulate.shooting`), ``Phi' = J Phi``
(:mod:`gearcli.engine.jacobian`).
"""

from __future__ import annotations

import numpy as np

from gearcli.engine.assembly import n_dynamic, n_model_states, scene_rhs
from gearcli.engine.jacobian import jacobian
from gearcli.engine.numba_cache import jit, jit_alloc


@jit
def rhs(t, y, dy, model, th, fc):
    """dy = f(t, y) of the scene ``model``, the variational equations included when ``y`` carries them; ``th``
    (n_bodies) and ``fc`` (4 n_conn: assembly.scene_rhs) are scratch."""
    scene_rhs(t, y, dy, model, th, fc)
    if y.size > n_model_states(model):
        variational_rhs(t, y, dy, model, th)


@jit_alloc
def variational_rhs(t, y, dy, model, th):
    """The variational equations of an augmented state ``[y | Phi[:, 0] | ... | Phi[:, d-1]]``:
    ``Phi' = J Phi`` with the dynamic block of the analytic Jacobian at ``(t, y)`` (gearcli.simulate.shooting)."""
    ns = n_model_states(model)
    d = n_dynamic(model)
    Jm = np.zeros((ns, ns))
    g = np.zeros(ns)
    ag = np.zeros(ns)
    jacobian(t, y[:ns], Jm, model, th, g, ag)
    for k in range(d):
        s = ns + k * d
        for i in range(d):
            acc = 0.0
            for j in range(d):
                acc += Jm[i, j] * y[s + j]
            dy[s + i] = acc
