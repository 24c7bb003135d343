"""Gear mesh along its transverse line of action: the MSC Adams IMPACT law (docs: README "Model").

Deflection ``delta = r_bp theta_p - r_bg theta_g`` (m), normal approach ``h = cos(beta_b) delta``.
Backlash j opens a gap of j/2 on each flank: drive-flank contact when ``h > j/2``, back-flank contact
when ``h < -j/2``, no force between. On the penetration ``p`` beyond the gap

    F_n = K g(phi) p^e + STEP(p, 0, 0, d, C) p'   clamped at 0 (never tensile),
    F   = F_bt = +-cos(beta_b) F_n               (negative on the back flank),

``g = L(phi) / L_mean`` (total contact-line length over its mean; :mod:`gearcli.model.contact_lines`)
for a time-varying mesh, else 1; ``phi = z_p theta_p / 2 pi`` the pinion's mesh phase in mesh cycles
(:func:`phase_per_rad`). The damping
dissipates ``(F_n - K g p^e) p'`` (including the part the clamp removes); the work into a time-varying
spring is ``K g p^e p'``.
"""

from __future__ import annotations

import math

import numpy as np

from gearcli.model.contact_lines import SPUR_OVERLAP
from gearcli.model.elements import N_PARAM

PARAMS = ("cos_beta_b", "cos2_beta_b", "stiffness_N_m_e", "exponent", "damping_Ns_m", "inv_full_damping_1_m",
          "damping_slope", "half_gap_m", "time_varying", "contact_ratio", "overlap_ratio", "pinion_teeth",
          "full_damping_m")
(I_CB, I_CB2, I_K, I_E, I_C, I_INVD, I_DC, I_HALF, I_TV, I_EA, I_EB, I_Z, I_D) = range(len(PARAMS))


def phase_per_rad(P) -> float:
    """Mesh cycles per radian of the pinion: phi = (z_p / 2 pi) theta_p."""
    return P[I_Z] / (2.0 * math.pi)


def pack(spec) -> np.ndarray:
    """The parameter row of a :class:`gearcli.model.spec.MeshSpec` (SI)."""
    cb = math.cos(spec.base_helix_angle_rad)
    d = spec.full_damping_m
    row = np.zeros(N_PARAM)
    row[:len(PARAMS)] = (cb, cb * cb, spec.stiffness_N_m_e, spec.exponent, spec.damping_Ns_m, 1.0 / d,
                         6.0 * spec.damping_Ns_m / d, 0.5 * spec.backlash_m, float(spec.time_varying),
                         spec.contact_ratio, spec.overlap_ratio, float(spec.pinion_teeth), d)
    return row


def contact_factor(x, ea, eb):
    """``L / L_mean`` at the mesh phase ``x`` in mesh cycles (plain-float form of
    :func:`gearcli.model.contact_lines.contact_length_factor`)."""
    x = x % 1.0
    lo_j = -int(math.floor(eb)) - 1
    hi_j = int(math.ceil(ea)) + 1
    if eb < SPUR_OVERLAP:
        n = 0.0
        for j in range(lo_j, hi_j):
            if 0.0 <= x + j <= ea:
                n += 1.0
        return n * (1.0 / ea)
    total = 0.0
    for j in range(lo_j, hi_j):
        lo = x + j
        hi = lo + eb
        o = (hi if hi < ea else ea) - (lo if lo > 0.0 else 0.0)
        if o > 0.0:
            total += o
    return total * (1.0 / (ea * eb))


def contact_slope(x, ea, eb):
    """d(L / L_mean)/dx, x in mesh cycles; 0 for spur gears (steps carry no derivative)."""
    if eb < SPUR_OVERLAP:
        return 0.0
    x = x % 1.0
    slope = 0.0
    for j in range(-int(math.floor(eb)) - 1, int(math.ceil(ea)) + 1):
        lo = x + j
        hi = lo + eb
        if min(hi, ea) > max(lo, 0.0):
            slope += (1.0 if hi < ea else 0.0) - (1.0 if lo > 0.0 else 0.0)
    return slope / (ea * eb)


def _contact(P, d, dd):
    """(in contact, p, p', signed cos(beta_b)) on the flank that touches."""
    cb = P[I_CB]
    half = P[I_HALF]
    h = cb * d
    if h > half:
        return True, h - half, cb * dd, cb
    if h < -half:
        return True, -h - half, -cb * dd, -cb
    return False, 0.0, 0.0, 0.0


def _elastic(P, p, phi):
    """(K g p^e, d/dp of it, d/dphi of it, K g)."""
    kk = P[I_K]
    kph = 0.0
    e = P[I_E]
    if P[I_TV] != 0.0:
        kph = P[I_K] * contact_slope(phi, P[I_EA], P[I_EB])
        kk = P[I_K] * contact_factor(phi, P[I_EA], P[I_EB])
    if e == 1.0:
        fe, ke, pe = kk * p, kk, p
    elif e == 1.5:
        rp = math.sqrt(p)
        fe, ke, pe = kk * p * rp, 1.5 * kk * rp, p * rp
    elif e == 2.0:
        fe, ke, pe = kk * p * p, 2.0 * kk * p, p * p
    else:
        fe, ke, pe = kk * p ** e, e * kk * p ** (e - 1.0), p ** e
    return fe, ke, kph * pe, kk


def _damping(P, p):
    """(c, dc/dp) of the STEP ramp c = STEP(p, 0, 0, d, C)."""
    s = p * P[I_INVD]
    if s < 1.0:
        return P[I_C] * s * s * (3.0 - 2.0 * s), P[I_DC] * s * (1.0 - s)
    return P[I_C], 0.0


def force(P, d, dd, phi):
    """(F_bt, dF/d delta, dF/d delta', dF/d phi, damping power, power into a time-varying spring)."""
    touching, p, pd, sc = _contact(P, d, dd)
    if not touching:
        return 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    fe, ke, fph, _ = _elastic(P, p, phi)
    u = fe * pd if P[I_TV] != 0.0 else 0.0
    if P[I_C] > 0.0:
        c, dc = _damping(P, p)
        fn = fe + c * pd
        if fn > 0.0:
            return sc * fn, P[I_CB2] * (ke + dc * pd), P[I_CB2] * c, sc * fph, (fn - fe) * pd, u
        return 0.0, 0.0, 0.0, 0.0, (0.0 - fe) * pd, u  # clamped: the damper cancels the spring
    return sc * fe, P[I_CB2] * ke, 0.0, sc * fph, 0.0, u


def power_gradient(P, d, dd, phi):
    """Partials of (damping power, time-varying spring power) by (delta, delta', phi)."""
    touching, p, pd, sc = _contact(P, d, dd)
    if not touching:
        return 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    fe, ke, fph, _ = _elastic(P, p, phi)
    qd = qv = qt = ud = uv = ut = 0.0
    if P[I_C] > 0.0:
        c, dc = _damping(P, p)
        if fe + c * pd > 0.0:
            qd, qv = sc * dc * pd * pd, 2.0 * sc * c * pd
        else:
            qd, qv, qt = -sc * ke * pd, -sc * fe, -fph * pd
    if P[I_TV] != 0.0:
        ud, uv, ut = sc * ke * pd, sc * fe, fph * pd
    return qd, qv, qt, ud, uv, ut


def transmission_error(P, phi):
    """Static transmission error e(phi) along the transverse line of action (m) at the mesh phase ``phi``
    (mesh cycles). None modelled yet: 0. The excitation (transmission-error harmonics) replaces this body;
    the dynamic transmission error, the DTE channel and its statistics follow through
    :func:`dynamic_transmission_error`."""
    return 0.0


def dynamic_transmission_error(P, d, phi):
    """The mesh's dynamic transmission error q = delta - e(phi) along the transverse line of action (m):
    the deflection the teeth actually take up (backlash gap included)."""
    return d - transmission_error(P, phi)


def penetration(P, d):
    """Signed penetration beyond the gap (m): + drive flank, - back flank, 0 inside the backlash."""
    touching, p, _, sc = _contact(P, d, 0.0)
    return (p if sc > 0.0 else -p) if touching else 0.0


def potential(P, d, phi):
    """Elastic energy K g p^(e+1) / (e+1) stored in the mesh, J."""
    touching, p, _, _ = _contact(P, d, 0.0)
    if not touching:
        return 0.0
    kk = P[I_K] * contact_factor(phi, P[I_EA], P[I_EB]) if P[I_TV] != 0.0 else P[I_K]
    e = P[I_E]
    return kk * p ** (e + 1.0) / (e + 1.0)


def static_penetration(P, F):
    """Penetration p0 = (|F| / cos(beta_b) / K)^(1/e) that carries the line force F at mean stiffness."""
    return (abs(F) / P[I_CB] / P[I_K]) ** (1.0 / P[I_E])


def static_deflection(P, F):
    """Deflection that carries the line force F (signed) at mean stiffness, gap included."""
    return math.copysign((static_penetration(P, F) + P[I_HALF]) / P[I_CB], F)


def deflection_scale(P, F, floor):
    """Scale of the deflection for the absolute tolerance: static one, half-gap, floor."""
    return max(static_penetration(P, F) / P[I_CB], P[I_HALF] / P[I_CB], floor)


def linear_row(P, factor):
    """The parameter row of the mesh frozen at ``factor`` x its mean stiffness, without gap (linearisation)."""
    Q = np.array(P, dtype=float)
    Q[I_K] *= factor
    Q[I_TV] = 0.0
    Q[I_HALF] = 0.0
    return Q


def damped(P) -> bool:
    return bool(P[I_C] > 0.0)


def time_varying(P) -> bool:
    return bool(P[I_TV] != 0.0)
