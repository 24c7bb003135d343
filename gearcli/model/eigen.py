"""Eigenpairs of the linearised chain's mass-normalised stiffness J^-1/2 K J^-1/2 (:mod:`gearcli.model.modes`):
the soft modes of a chain with extreme stiffness ratios from its compliance side, a lossy chain's non-symmetric
eigenproblem with real pairs, and repeated eigenvalues with an orthonormal basis."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from gearcli.model.assembly import Layout


def soft_modes_refined(R: np.ndarray, k: np.ndarray, J: np.ndarray, w2: np.ndarray, u: np.ndarray,
                        L: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The eigenpairs of J^-1/2 K J^-1/2 with its soft modes from the compliance side.

    An eigensolver resolves omega^2 to eps x the largest: a chain with stiffness ratios of 1e12 (a 1 N m/rad coupling
    beside a 1e12 N/mm mesh) loses the digits of its slowest modes (one came out at twice its frequency). In
    connector forces f (``delta = f / k``) the elastic modes solve ``diag(1/k) f = mu M f``, ``M = R J^-1 L^T``
    (``L`` the levers times the loss factors; ``R`` without losses), ``mu = 1 / omega^2``: the compliances are exact
    and the soft modes are this pencil's largest eigenvalues, resolved to eps x themselves. Each elastic mode below
    the geometric mean of the extreme omega^2 (where the compliance side's error eps omega^4 / omega_min^2 is the
    smaller) takes the pencil's, with its shape J^-1 L^T f (mass-weighted, unit). Only where every connector is an
    independent spring (R of full row rank; a planetary's closed loops are not); else the eigenpairs unchanged."""
    n_el = R.shape[0]
    if n_el == 0 or n_el > R.shape[1] or np.any(k <= 0.0) or np.linalg.matrix_rank(R) < n_el:
        return w2, u
    D = np.diag(1.0 / k)
    try:
        if L is None:  # Cholesky M = C C^T: C^-1 D C^-T y = mu y, f = C^-T y (numpy only: design never loads scipy)
            chol = np.linalg.cholesky(R @ (R.T / J[:, None]))
            half = np.linalg.solve(chol, D)
            mu, y = np.linalg.eigh(np.linalg.solve(chol, half.T).T)
            f = np.linalg.solve(chol.T, y)
        else:  # real: the lossy chain is a lossless one up to a diagonal similarity (real_eigenpairs)
            mu_c, f_c = np.linalg.eig(np.linalg.solve(R @ (L.T / J[:, None]), D))
            mu = np.where(np.isfinite(mu_c), np.real(mu_c), -np.inf)
            f = np.real(f_c * np.exp(-1j * np.angle(f_c[np.argmax(np.abs(f_c), axis=0), np.arange(f_c.shape[1])]))[None, :])
    except np.linalg.LinAlgError:
        return w2, u
    by_softness = np.argsort(-mu)  # mu = 1 / omega^2, largest first (a stiff mode's tiny mu may round below 0)
    order = np.argsort(w2)
    elastic = order[order.size - n_el:]  # the n_el largest: the rigid modes are the others
    if mu[by_softness[0]] <= 0.0:
        return w2, u
    split = math.sqrt(float(w2[elastic[-1]]) / float(mu[by_softness[0]]))
    lt = R if L is None else L
    w2, u = w2.copy(), u.copy()
    for rank, i in enumerate(by_softness):
        if mu[i] <= 0.0 or 1.0 / mu[i] >= split:
            break
        v = np.sqrt(J) * ((lt.T @ f[:, i]) / J)  # the body angles J^-1 L^T f, mass-weighted
        j = elastic[rank]
        w2[j], u[:, j] = 1.0 / mu[i], v / np.linalg.norm(v)
    return w2, u


def real_eigenpairs(a: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Eigenvalues and unit eigenvectors of J^-1/2 K J^-1/2 for a lossy chain's non-symmetric K. Its eigenvalues are
    real (the lossy chain is the lossless one with each body's inertia over the efficiencies between it and the
    drive, up to a diagonal similarity): the real parts are kept, each vector turned real by the phase of its
    largest entry."""
    w2, u = np.linalg.eig(a)
    big = np.argmax(np.abs(u), axis=0)
    u = np.real(u * np.exp(-1j * np.angle(u[big, np.arange(u.shape[1])]))[None, :])
    return orthonormal_clusters(np.real(w2), u / np.linalg.norm(u, axis=0))


DEGENERATE = 1e-9  # eigenvalues closer than this fraction of the largest span one eigenspace


def orthonormal_clusters(w2: np.ndarray, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``u`` with each repeated eigenvalue's vectors made orthonormal (mass-orthogonal shapes). A lossy planetary's
    N - 1 planet modes share one eigenvalue; the non-symmetric solver returns any basis of that eigenspace (four
    planets: shapes 60 degrees apart in the mass metric), where the lossless solver and the modal analysis take an
    orthogonal one. Any combination within an eigenspace is an eigenvector, so the frequencies stay."""
    order = np.argsort(w2)
    tol = DEGENERATE * max(float(np.max(np.abs(w2))), 1e-300)
    u = u.copy()
    start = 0
    for stop in range(1, order.size + 1):
        if stop < order.size and w2[order[stop]] - w2[order[stop - 1]] <= tol:
            continue
        group = order[start:stop]
        if group.size > 1:
            u[:, group] = np.linalg.qr(u[:, group])[0]
        start = stop
    return w2, u


def rigid_mode_count(lay: Layout, k: np.ndarray, clamped: int = 0) -> int:
    """Rigid-body modes of the chain: its connected groups of bodies (joined by connectors of non-zero
    stiffness) that hold none of the ``clamped`` first bodies. Counted on the graph, so a badly scaled
    eigenproblem (1e-9 and 1e6 kg m^2 in one chain) cannot turn a slow elastic mode into a rigid one."""
    parent = list(range(lay.n_bodies))

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for c, x in enumerate(lay.connectors):
        joined = [b for b, r in zip(x.bodies, x.radii, strict=True) if r != 0.0]  # a planet mesh joins three
        if k[c] > 0.0:
            for b in joined[1:]:
                parent[root(b)] = root(joined[0])
    grounded = {root(i) for i in range(clamped)}
    return len({root(i) for i in range(clamped, lay.n_bodies)} - grounded)

