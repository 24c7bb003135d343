"""The kernel's linear algebra: the vector sums scipy forms with ``np.dot`` (the same BLAS with the same arguments,
:mod:`gearcli.engine.blas`, so the sums are scipy's to the bit), scipy's RMS norm, and the LU factorisation and
solve of Radau's Newton matrices.
"""

from __future__ import annotations

import math
from typing import Any

import numba
import numpy as np

from gearcli.engine import blas as _blas
from gearcli.engine.numba_cache import jit


# ----------------------------------------------------------------------------------- vector sums
# scipy forms these with np.dot; the kernel calls the same BLAS with the same arguments (gearcli.engine.blas)
@jit
def _gemv_t_loop(K, s, a, out):
    """out = K[:s].T @ a[:s]."""
    for i in range(K.shape[1]):
        acc = 0.0
        for j in range(s):
            acc += K[j, i] * a[j]
        out[i] = acc


@jit
def _dot_loop(x):
    acc = 0.0
    for i in range(x.size):
        acc += x[i] * x[i]
    return acc


@jit
def _gemm_loop(Dm, K, out):
    """out = Dm @ K."""
    for r in range(Dm.shape[0]):
        for i in range(K.shape[1]):
            acc = 0.0
            for j in range(Dm.shape[1]):
                acc += Dm[r, j] * K[j, i]
            out[r, i] = acc


HAVE_BLAS = not getattr(numba.config, "DISABLE_JIT", 0) and _blas.register()  # NUMBA_DISABLE_JIT: the loops (Python cannot call BLAS by address)
if HAVE_BLAS:
    assert _blas.FOUND is not None
    _PATTERN, _WIDTH = _blas.FOUND[1], _blas.FOUND[2]
    _nt = numba.types
    _I = _nt.int64 if _WIDTH == 64 else _nt.int32
    _ci = np.int64 if _WIDTH == 64 else np.int32
    _E = _nt.int32  # CBLAS enums
    _U = _nt.uintp  # pointers, passed as addresses
    _F = _nt.float64
    _dgemv: Any = _nt.ExternalFunction(_PATTERN.format("dgemv"), _nt.void(_E, _E, _I, _I, _F, _U, _I, _U, _I, _F, _U, _I))
    _dgemm: Any = _nt.ExternalFunction(_PATTERN.format("dgemm"),
                                  _nt.void(_E, _E, _E, _I, _I, _I, _F, _U, _I, _U, _I, _F, _U, _I))
    _ddot: Any = _nt.ExternalFunction(_PATTERN.format("ddot"), _F(_I, _U, _I, _U, _I))

    @jit
    def _gemv_t_blas(K, s, a, out):
        n = K.shape[1]
        _dgemv(np.int32(102), np.int32(111), _ci(n), _ci(s), 1.0, K.ctypes.data, _ci(n), a.ctypes.data, _ci(1),
               0.0, out.ctypes.data, _ci(1))

    @jit
    def _dot_blas(x):
        return _ddot(_ci(x.size), x.ctypes.data, _ci(1), x.ctypes.data, _ci(1))

    @jit
    def _gemm_blas(Dm, K, out):
        m, k = Dm.shape
        n = K.shape[1]
        _dgemm(np.int32(101), np.int32(111), np.int32(111), _ci(m), _ci(n), _ci(k), 1.0, Dm.ctypes.data, _ci(k),
               K.ctypes.data, _ci(n), 0.0, out.ctypes.data, _ci(n))

    gemv_t, dot_self, gemm = _gemv_t_blas, _dot_blas, _gemm_blas
else:  # pragma: no cover - a numpy without a findable BLAS
    gemv_t, dot_self, gemm = _gemv_t_loop, _dot_loop, _gemm_loop


@jit
def _rms(x, scale, tmp):
    """scipy's ``norm(x / scale)``: ``sqrt((x/scale) . (x/scale)) / sqrt(n)``."""
    for i in range(x.size):
        tmp[i] = x[i] / scale[i]
    return math.sqrt(dot_self(tmp)) / x.size ** 0.5

@jit
def _rms_matrix(X, scale):
    """scipy's ``norm(X / scale)`` of a (3, n) array."""
    s = 0.0
    for r in range(X.shape[0]):
        for i in range(X.shape[1]):
            v = X[r, i] / scale[i]
            s += v * v
    return math.sqrt(s) / X.size ** 0.5

@jit
def lu_factor(A, piv):
    """In-place LU with partial pivoting (real or complex), as LAPACK getrf. A ``piv`` of 3 n entries also
    receives each row's nonzero span of the factors (``piv[n + i]`` the first column of L's row i,
    ``piv[2 n + i]`` one past the last column of U's row i) for :func:`lu_solve` to skip exact zeros: a block
    diagonal matrix (the variational equations' augmented Jacobian) factors and solves block by block. The
    skipped terms are exact zeros, so the numbers are those of the dense loops."""
    n = A.shape[0]
    spans = piv.size >= 3 * n
    for k in range(n):
        p = k
        best = abs(A[k, k])
        for i in range(k + 1, n):
            v = abs(A[i, k])
            if v > best:
                best = v
                p = i
        piv[k] = p
        if p != k:
            for j in range(n):
                tmp = A[k, j]
                A[k, j] = A[p, j]
                A[p, j] = tmp
        if A[k, k] == 0:
            continue
        end = n
        if spans:  # the pivot row's last nonzero: the update of the rows below stops there
            while end > k + 1 and A[k, end - 1] == 0:
                end -= 1
        inv = 1.0 / A[k, k]
        for i in range(k + 1, n):
            A[i, k] *= inv
            m = A[i, k]
            if m != 0:
                for j in range(k + 1, end):
                    A[i, j] -= m * A[k, j]
    if spans:
        for i in range(n):
            lo = 0
            while lo < i and A[i, lo] == 0:
                lo += 1
            hi = n
            while hi > i + 1 and A[i, hi - 1] == 0:
                hi -= 1
            piv[n + i] = lo
            piv[2 * n + i] = hi

@jit
def lu_solve(LU, piv, b):
    """Solve in place LU x = b (b overwritten with x); with the row spans of :func:`lu_factor` in ``piv``,
    over each row's nonzeros only."""
    n = LU.shape[0]
    spans = piv.size >= 3 * n
    for k in range(n):
        p = piv[k]
        if p != k:
            tmp = b[k]
            b[k] = b[p]
            b[p] = tmp
    for i in range(n):
        acc = b[i]
        for j in range(piv[n + i] if spans else 0, i):
            acc -= LU[i, j] * b[j]
        b[i] = acc
    for i in range(n - 1, -1, -1):
        acc = b[i]
        for j in range(i + 1, piv[2 * n + i] if spans else n):
            acc -= LU[i, j] * b[j]
        b[i] = acc / LU[i, i]
