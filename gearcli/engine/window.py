"""The window statistics of a run's stages in one compiled pass (:func:`gearcli.simulate.stats.stages_dynamics`'s
numbers): every row's window mean, min, max and standard deviation, each stage's run-up peak and its contact
fractions, without the temporary arrays numpy's reductions build.

The same numbers as numpy's, bit for bit: a sum is numpy's pairwise summation (:func:`pairwise_sum`: eight
accumulators over blocks of at most 128 elements, halves above, added to the reduction's identity 0.0, as
``np.add.reduce`` sums a contiguous row), and every element that is summed is formed in numpy's operation order
(the trapezoid's ``0.5 * (x[i + 1] + x[i]) * (t[i + 1] - t[i])``, the deviation's ``(x - mean) * (x - mean)``); a
minimum, maximum or first maximum's index does not depend on the order. A constant row (an equilibrium's window:
one state repeated, :func:`gearcli.simulate.equilibrium.sampled`) is reduced without its samples: its sums are the
pairwise sums of copies of one value (:func:`constant_sum`: the same additions, each equal half once), its min and
max that value, the same numbers. tests/engine/test_window_statistics.py checks the pass against closed forms and
against numpy's reductions.
"""

from __future__ import annotations

import math

import numpy as np

from gearcli.engine.numba_cache import jit, jit_alloc

BLOCK = 128  # numpy's PW_BLOCKSIZE: the longest run summed with eight accumulators, not halved


DEPTH = 64  # the halvings' stack: ample (a sum of 2**64 elements)


@jit
def _block(a, lo, n):
    """numpy's sum of a block (``n`` <= :data:`BLOCK`): a plain loop below eight elements, else eight accumulators
    and the rest added in order."""
    if n < 8:
        res = 0.0
        for i in range(lo, lo + n):
            res += a[i]
        return res
    r0, r1, r2, r3 = a[lo], a[lo + 1], a[lo + 2], a[lo + 3]
    r4, r5, r6, r7 = a[lo + 4], a[lo + 5], a[lo + 6], a[lo + 7]
    i = 8
    whole = n - n % 8
    while i < whole:
        j = lo + i
        r0 += a[j]
        r1 += a[j + 1]
        r2 += a[j + 2]
        r3 += a[j + 3]
        r4 += a[j + 4]
        r5 += a[j + 5]
        r6 += a[j + 6]
        r7 += a[j + 7]
        i += 8
    res = ((r0 + r1) + (r2 + r3)) + ((r4 + r5) + (r6 + r7))
    while i < n:
        res += a[lo + i]
        i += 1
    return res


@jit
def pairwise_sum(a, lo, n, span, left):
    """numpy's pairwise sum of ``a[lo:lo + n]`` (loops_utils.h's ``pairwise_sum``), without the identity: a block
    of at most :data:`BLOCK` elements summed whole, a longer run split at half its length rounded down to a multiple
    of eight and the halves' sums added. The recursion walked with a stack (``span``: (DEPTH, 3) int64 scratch of
    each pending run's start, length and progress; ``left``: DEPTH floats, its left half's sum)."""
    if n <= BLOCK:
        return _block(a, lo, n)
    top = 0
    span[0, 0], span[0, 1], span[0, 2] = lo, n, 0
    done = 0.0  # the sum of the run last finished
    while top >= 0:
        start, size, step = span[top, 0], span[top, 1], span[top, 2]
        if size <= BLOCK:
            done = _block(a, start, size)
            top -= 1
            continue
        half = size // 2
        half -= half % 8
        if step == 0:  # its left half first
            span[top, 2] = 1
            top += 1
            span[top, 0], span[top, 1], span[top, 2] = start, half, 0
        elif step == 1:  # the left half's sum kept, the right half next
            left[top] = done
            span[top, 2] = 2
            top += 1
            span[top, 0], span[top, 1], span[top, 2] = start + half, size - half, 0
        else:
            done = left[top] + done
            top -= 1
    return done


@jit
def _block_constant(c, n):
    """:func:`_block` of ``n`` copies of ``c``, the same additions: its eight accumulators are equal, one is summed."""
    if n < 8:
        res = 0.0
        for _ in range(n):
            res += c
        return res
    whole = n - n % 8
    r = c
    for _ in range(whole // 8 - 1):
        r += c
    res = ((r + r) + (r + r)) + ((r + r) + (r + r))
    for _ in range(n - whole):
        res += c
    return res


@jit
def constant_sum(c, n):
    """:func:`pairwise_sum` of ``n`` copies of ``c``, the same additions in the same order (its splits depend on the
    lengths alone, and equal halves have equal sums: each is worked out once), in a few dozen additions."""
    if n <= BLOCK:
        return _block_constant(c, n)
    half = n // 2
    half -= half % 8
    lhs = constant_sum(c, half)
    return lhs + (lhs if n - half == half else constant_sum(c, n - half))


@jit
def constant(x):
    """Whether every value of ``x`` (at least one) is its first, bit for bit but for a NaN's payload (a NaN: no)."""
    c = x[0]
    if c != c:
        return False
    zero = c == 0.0
    sign = math.copysign(1.0, c)
    for j in range(1, x.size):
        if x[j] != c or (zero and math.copysign(1.0, x[j]) != sign):
            return False
    return True


@jit
def _window_mean(x, t, buf, plain, periodic, span, left):
    """The window mean of the row ``x`` sampled at ``t`` (:func:`gearcli.simulate.stats.window_means`): the trapezoid
    rule over the window's length; for whole periods (or fewer than two samples, or a window of no length) the
    samples' plain mean ``plain``. ``buf``: scratch of ``x.size`` values."""
    m = x.size
    if periodic or m < 2 or t[m - 1] <= t[0]:
        return plain
    for j in range(m - 1):
        buf[j] = 0.5 * (x[j + 1] + x[j]) * (t[j + 1] - t[j])
    return (0.0 + pairwise_sum(buf, 0, m - 1, span, left)) / (t[m - 1] - t[0])


@jit
def _extremes(x):
    """min and max of ``x`` (at least one value), four lanes at a time (the order does not change them)."""
    m = x.size
    a0 = a1 = a2 = a3 = b0 = b1 = b2 = b3 = x[0]
    j = 0
    end = m - m % 4
    while j < end:
        a0, b0 = min(a0, x[j]), max(b0, x[j])
        a1, b1 = min(a1, x[j + 1]), max(b1, x[j + 1])
        a2, b2 = min(a2, x[j + 2]), max(b2, x[j + 2])
        a3, b3 = min(a3, x[j + 3]), max(b3, x[j + 3])
        j += 4
    while j < m:
        a0, b0 = min(a0, x[j]), max(b0, x[j])
        j += 1
    return min(min(a0, a1), min(a2, a3)), max(max(b0, b1), max(b2, b3))


@jit
def _first_abs_max(x):
    """The index of the first largest |x| (numpy's ``argmax(abs(x))``)."""
    best = abs(x[0])
    at = 0
    for i in range(1, x.size):
        v = abs(x[i])
        if v > best:
            best = v
            at = i
    return at


@jit_alloc
def window_statistics(W, whole, t, periodic, loaded):
    """The window statistics of a run's stages (:func:`gearcli.simulate.stats.stages_dynamics`). ``W``: the window's
    samples (at least one, at the times ``t``), five rows a stage (F_t, F_r, F_a, penetration, DTE); ``whole``: each
    stage's F_t over the whole run; ``loaded``: each stage's loaded flank, the sign (+1 or -1) of its static F_t.

    Returns ``stats`` (a row of ``W`` a row: its window mean, min, max, standard deviation about the samples' mean
    and that plain mean), ``peak_at`` (a stage's index of its first largest |F_t| in ``whole``) and per stage, columns (no contact,
    back flank), the window's ``fractions`` of time (:func:`gearcli.simulate.stats.time_fraction`) and ``flags``
    (1.0: some sample is so) of no contact (F_t or the penetration exactly 0) and of the back flank (a penetration
    of the other sign than the loaded flank's)."""
    rows, m = W.shape
    stages = rows // 5
    stats = np.empty((rows, 5))
    peak_at = np.zeros(stages, dtype=np.int64)
    fractions = np.empty((stages, 2))
    flags = np.zeros((stages, 2))
    buf = np.empty(m)
    lost = np.empty(m)
    back = np.empty(m)
    span = np.empty((DEPTH, 3), dtype=np.int64)  # the pairwise sums' scratch
    left = np.empty(DEPTH)
    same = np.zeros(rows, dtype=np.bool_)  # a constant row (an equilibrium's window): its sums of copies, once
    for r in range(rows):
        x = W[r]
        same[r] = constant(x)
        if same[r]:  # the same numbers: every summed element is the same copy (constant_sum), min = max = it
            plain = (0.0 + constant_sum(x[0], m)) / m
            stats[r, 1], stats[r, 2] = x[0], x[0]
            d = x[0] - plain
            deviations = constant_sum(d * d, m)
        else:
            plain = (0.0 + pairwise_sum(x, 0, m, span, left)) / m  # numpy's mean, and its std's centre
            stats[r, 1], stats[r, 2] = _extremes(x)
            for j in range(m):
                d = x[j] - plain
                buf[j] = d * d
            deviations = pairwise_sum(buf, 0, m, span, left)
        stats[r, 0] = _window_mean(x, t, buf, plain, periodic, span, left)
        stats[r, 4] = plain
        stats[r, 3] = np.sqrt((0.0 + deviations) / m)
    plainly = periodic or m < 2 or t[m - 1] <= t[0]  # a window mean that is the plain mean
    for k in range(stages):
        peak_at[k] = _first_abs_max(whole[k])
        f = W[5 * k]
        p = W[5 * k + 3]
        if plainly and same[5 * k] and same[5 * k + 3]:  # constant flags: their plain means of copies
            for c, v in enumerate((1.0 if f[0] == 0.0 or p[0] == 0.0 else 0.0,
                                   1.0 if loaded[k] * p[0] < 0.0 else 0.0)):
                plain = (0.0 + constant_sum(v, m)) / m
                fractions[k, c] = plain
                flags[k, c] = 1.0 if plain > 0.0 else 0.0
            continue
        for j in range(m):
            lost[j] = 1.0 if f[j] == 0.0 or p[j] == 0.0 else 0.0
            back[j] = 1.0 if loaded[k] * p[j] < 0.0 else 0.0
        for c, flag in enumerate((lost, back)):
            plain = (0.0 + pairwise_sum(flag, 0, m, span, left)) / m
            fractions[k, c] = _window_mean(flag, t, buf, plain, periodic, span, left)
            flags[k, c] = 1.0 if plain > 0.0 else 0.0
    return stats, peak_at, fractions, flags
