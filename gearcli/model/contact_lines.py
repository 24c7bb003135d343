"""Total length of the contact lines of a helical mesh against its mesh phase (time-varying stiffness).

The plane of action is a rectangle: ``g_alpha = eps_alpha p_bt`` along the transverse path of contact by
``b`` across the face. Contact lines cross it inclined at ``beta_b`` to the face-width direction and
``p_bt`` apart along the path; as the pinion turns by one base pitch (mesh phase ``phi`` from 0 to 1)
every line advances by ``p_bt``. In units of ``p_bt`` a line whose foot (at one face end) lies at
``x`` covers ``[x, x + eps_beta]`` of the path (``eps_beta = b tan(beta_b) / p_bt``, the overlap
ratio), so its length inside the rectangle is ``p_bt o(x) / sin(beta_b)`` with the clipped overlap

    o(x) = max(0, min(x + eps_beta, eps_alpha) - max(x, 0)),

and the total over the lines ``x = phi + j`` (j integer) divided by the mean ``b eps_alpha / cos(beta_b)``
is

    L(phi) / L_mean = sum_j o(phi + j) / (eps_alpha eps_beta)          (helical, eps_beta > 0)
    L(phi) / L_mean = #{j : 0 <= phi + j <= eps_alpha} / eps_alpha     (spur, eps_beta = 0)

The helical form is continuous and piecewise linear in ``phi`` (its derivative is piecewise constant);
the spur form is the rectangular wave between floor(eps_alpha) and ceil(eps_alpha) pairs. When
``eps_beta`` is an integer the sum is constant (= 1). Sources: ISO 21771 (plane of action), e.g.
Maatar & Velex (1996) for the contact-line model.
"""

from __future__ import annotations

import math

import numpy as np

SPUR_OVERLAP = 1e-9  # below this overlap ratio the helical form is evaluated as its spur limit


def _line_offsets(eps_alpha: float, eps_beta: float) -> range:
    """Integers j for which a line at phi + j (phi in [0, 1)) can meet the rectangle."""
    return range(-int(math.floor(eps_beta)) - 1, int(math.ceil(eps_alpha)) + 1)


def shortest_stretch(eps_alpha: float, eps_beta: float) -> float:
    """The shortest stretch of mesh phase (in mesh cycles) between two kinks of ``L(phi)`` (spur: its steps),
    where a line's clipped overlap ``o(phi + j)`` changes slope: phi = 0, -eps_alpha, eps_beta and eps_beta -
    eps_alpha (mod 1); 1.0 where ``L`` is constant (an integer overlap ratio) or has one kink a cycle."""
    if eps_beta >= SPUR_OVERLAP and abs(eps_beta - round(eps_beta)) < 1e-9:
        return 1.0
    kinks = [0.0, -eps_alpha] + ([eps_beta, eps_beta - eps_alpha] if eps_beta >= SPUR_OVERLAP else [])
    at = sorted({round(k % 1.0, 12) % 1.0 for k in kinks})
    gaps = [b - a for a, b in zip(at, [*at[1:], at[0] + 1.0], strict=True)]
    return min((g for g in gaps if g > 1e-9), default=1.0)


def contact_length_factor(phi, eps_alpha: float, eps_beta: float):
    """``L(phi) / L_mean`` for a float or an array of mesh phases (any real; the fractional part is used)."""
    if eps_alpha <= 0:
        raise ValueError("the transverse contact ratio must be positive")
    x = np.asarray(phi, dtype=float) % 1.0
    eps_beta = eps_beta if eps_beta >= SPUR_OVERLAP else 0.0  # o(x)/eps_beta -> indicator as eps_beta -> 0
    total = np.zeros_like(x)
    for j in _line_offsets(eps_alpha, eps_beta):
        xj = x + j
        if eps_beta > 0:
            total += np.maximum(0.0, np.minimum(xj + eps_beta, eps_alpha) - np.maximum(xj, 0.0))
        else:
            total += (xj >= 0.0) & (xj <= eps_alpha)
    out = total / (eps_alpha * eps_beta) if eps_beta > 0 else total / eps_alpha
    return float(out) if out.ndim == 0 else out


def scalar_factor(eps_alpha: float, eps_beta: float):
    """A fast pure-float ``phi -> L(phi) / L_mean`` for the right-hand side (same formula as
    :func:`contact_length_factor`; numpy on one float costs ~10x more)."""
    offsets = tuple(float(j) for j in _line_offsets(eps_alpha, eps_beta))
    if eps_beta < SPUR_OVERLAP:
        inv = 1.0 / eps_alpha

        def spur(phi: float) -> float:
            x = phi % 1.0
            return sum(1.0 for j in offsets if 0.0 <= x + j <= eps_alpha) * inv

        return spur
    inv = 1.0 / (eps_alpha * eps_beta)

    def helical(phi: float) -> float:
        x = phi % 1.0
        total = 0.0
        for j in offsets:
            lo = x + j
            hi = lo + eps_beta
            o = (hi if hi < eps_alpha else eps_alpha) - (lo if lo > 0.0 else 0.0)
            if o > 0.0:
                total += o
        return total * inv

    return helical


def contact_length_slope(phi: float, eps_alpha: float, eps_beta: float) -> float:
    """``d(L/L_mean)/d(phi)`` of the helical form (piecewise constant); 0 for spur gears, whose
    steps carry no derivative (the Jacobian then leaves the phase dependence out)."""
    if eps_beta < SPUR_OVERLAP:
        return 0.0
    x = phi % 1.0
    slope = 0.0
    for j in _line_offsets(eps_alpha, eps_beta):
        lo, hi = x + j, x + j + eps_beta
        if min(hi, eps_alpha) > max(lo, 0.0):  # the line meets the rectangle
            slope += (1.0 if hi < eps_alpha else 0.0) - (1.0 if lo > 0.0 else 0.0)
    return slope / (eps_alpha * eps_beta)


def contact_length_range(eps_alpha: float, eps_beta: float, samples: int = 4096) -> tuple[float, float]:
    """Smallest and largest ``L / L_mean`` over a mesh period (on a fine grid plus the kinks)."""
    kinks = np.concatenate([np.array([eps_alpha, eps_alpha - eps_beta, -eps_beta]) % 1.0, [0.0]])
    phi = np.concatenate([np.linspace(0.0, 1.0, samples, endpoint=False), kinks, kinks + 1e-12, kinks - 1e-12])
    f = contact_length_factor(phi, eps_alpha, eps_beta)
    return float(f.min()), float(f.max())
