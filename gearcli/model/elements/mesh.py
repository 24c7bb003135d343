"""Gear mesh along its transverse line of action: the MSC Adams IMPACT law, or viscous damping, with
mesh excitation (docs: docs/tour.md "The model", docs/elements.md "Excitation").

Deflection ``delta = r_bp theta_p - r_bg theta_g`` (m). The mesh acts on the dynamic transmission error
``q = delta - e(phi)`` (Kahraman & Singh, J. Sound Vib. 142(1), 1990): ``e`` is the static transmission
error prescribed along the transverse line of action as harmonics of the mesh phase,

    e(phi) = sum_j e_j cos(2 pi j phi + psi_j),   q' = delta' - e'(phi) phi',   phi' = z_p w_p / 2 pi,

``phi = z_p theta_p / 2 pi`` the pinion's mesh phase in mesh cycles (:func:`phase_per_rad`; DESIGN's
radians are 2 pi phi). Normal approach ``h = cos(beta_b) q``. Backlash j opens a gap of j/2 on each
flank: drive-flank contact when ``h > j/2``, back-flank contact when ``h < -j/2``, no elastic force
between. On the penetration ``p`` beyond the gap

    IMPACT:   F_n = K g(phi) p^e + STEP(p, 0, 0, d, C) p'   clamped at 0 (never tensile),
              F   = F_bt = +-cos(beta_b) F_n               (negative on the back flank),
    viscous:  F   = +-cos(beta_b) K g(phi) p^e + c q'      (``damping_ratio``: c q' at all times, also in
              the gap; c = 2 zeta sqrt(k_lin m_e), k_lin the linearised dF/d delta at the static load, m_e
              the equivalent mass; both computed by :mod:`gearcli.model.assembly`),

``g(phi) = L(phi + phi_c) / L_mean`` (total contact-line length over its mean;
:mod:`gearcli.model.contact_lines`; ``phi_c`` a planet mesh's contact-line phase, 0 otherwise) for a
time-varying mesh, else 1, times the stiffness harmonics
``1 - sum_j s_j cos(2 pi j phi + chi_j)``. The damping dissipates ``(F_n - K g p^e) p'`` (IMPACT,
including the part the clamp removes) or ``c q'^2``; the work into a time-varying spring is
``K g p^e p'``; the transmission error does ``-F e'(phi) phi'`` on the bodies.

Parameter row (:data:`PARAMS`, then the harmonics): ``N_HARM`` TE amplitudes (m) from :data:`I_TE`,
their phases (rad) from :data:`I_TEP`, the stiffness harmonics from :data:`I_KS`, their phases from
:data:`I_KSP`; unused entries 0.
"""
from __future__ import annotations

import math

import numpy as np

from gearcli.model.contact_lines import SPUR_OVERLAP, contact_length_range
from gearcli.model.elements import N_HARM, N_PARAM

NAME = "mesh"
SIGNS = (1.0, -1.0)  # delta = r_bp theta_p - r_bg theta_g
CHANNELS = ("penetration_m", "dte_m")  # signed penetration beyond the gap, dynamic transmission error
MIN_APPROACH_M = 1e-6  # an unloaded Hertzian mesh's k_lin: at a 1 um approach (as the cost estimate)
ROW_WIDTH = N_PARAM  # the law reads the whole row: PARAMS, then the harmonics
PARAMS = ("cos_beta_b", "cos2_beta_b", "stiffness_N_m_e", "exponent", "damping_Ns_m", "inv_full_damping_1_m",
          "damping_slope", "half_gap_m", "time_varying", "contact_ratio", "overlap_ratio", "pinion_teeth",
          "full_damping_m", "viscous", "viscous_damping_Ns_m", "damping_ratio", "k_lin_N_m", "m_e_kg",
          "n_te", "n_ks", "efficiency", "loss_width_W", "contact_phase_cycles",
          "loss_slot_a", "loss_slot_b", "loss_slot_c", "loss_carrier_share_a")
(I_CB, I_CB2, I_K, I_E, I_C, I_INVD, I_DC, I_HALF, I_TV, I_EA, I_EB, I_Z, I_D,
 I_VIS, I_CV, I_ZETA, I_KLIN, I_ME, I_NTE, I_NKS, I_ETA, I_LW, I_CPH,
 I_LSA, I_LSB, I_LSC, I_LKA) = range(len(PARAMS))
LOSS_WIDTH = 1e-3  # the power-flow sign's tanh width: 1e-3 of the static force times the nominal pitch-line speed
I_TE = len(PARAMS)  # TE amplitudes, m
I_TEP = I_TE + N_HARM  # TE phases, rad
I_KS = I_TEP + N_HARM  # stiffness harmonics s_j (fractions of K)
I_KSP = I_KS + N_HARM  # their phases, rad
TWO_PI = 2.0 * math.pi


def phase_per_rad(P) -> float:
    """Mesh cycles per radian of the pinion: phi = (z_p / 2 pi) theta_p."""
    return P[I_Z] / (2.0 * math.pi)


def pack(spec) -> np.ndarray:
    """The parameter row of a :class:`gearcli.model.spec.MeshSpec` (SI)."""
    cb = math.cos(spec.base_helix_angle_rad)
    d = spec.full_damping_m
    row = np.zeros(N_PARAM)
    te, ks = spec.transmission_error_m, spec.stiffness_harmonics
    row[:I_VIS] = (cb, cb * cb, spec.stiffness_N_m_e, spec.exponent, spec.damping_Ns_m, 1.0 / d,
                   6.0 * spec.damping_Ns_m / d, 0.5 * spec.backlash_m, float(spec.time_varying),
                   spec.contact_ratio, spec.overlap_ratio, float(spec.pinion_teeth), d)
    if spec.damping_ratio is not None:  # c, k_lin, m_e: filled by the assembly (with_viscous)
        row[I_VIS], row[I_ZETA] = 1.0, spec.damping_ratio
    if len(te) > N_HARM or len(ks) > N_HARM:
        raise ValueError(f"at most {N_HARM} transmission-error and stiffness harmonics")
    row[I_NTE], row[I_NKS] = len(te), len(ks)
    row[I_ETA] = spec.efficiency  # the loss's width is filled by the assembly (with_loss_width)
    row[I_CPH] = spec.contact_phase_cycles  # a planet mesh's contact-line phase against the stage's phase
    row[I_TE:I_TE + len(te)] = te
    row[I_TEP:I_TEP + len(spec.transmission_error_phase_rad)] = spec.transmission_error_phase_rad
    row[I_KS:I_KS + len(ks)] = ks
    row[I_KSP:I_KSP + len(spec.stiffness_harmonics_phase_rad)] = spec.stiffness_harmonics_phase_rad
    return row


def with_viscous(P, k_lin, m_e):
    """The row with the viscous damping c = 2 zeta sqrt(k_lin m_e) of a ``damping_ratio`` mesh."""
    Q = np.array(P, dtype=float)
    Q[I_KLIN], Q[I_ME] = k_lin, m_e
    Q[I_CV] = 2.0 * Q[I_ZETA] * math.sqrt(k_lin * m_e)
    return Q


def with_loss_width(P, width_W):
    """The row with the power scale of the power-flow sign (:func:`loss_factors`)."""
    Q = np.array(P, dtype=float)
    Q[I_LW] = width_W
    return Q


def lossy(P) -> bool:
    """The mesh loses (1 - eta) of the power it transmits (0 < eta < 1)."""
    return bool(0.0 < P[I_ETA] < 1.0)


def with_planet_loss(P, slot_a, slot_b, slot_c, share_a):
    """The row of a planet mesh that loses in the carrier's frame (:func:`planet_loss_slots`): the connector's
    slots of its sun or ring (``slot_a``), its planet (``slot_b``, > 0) and its carrier (-1 where that member
    is held), and the carrier's share ``kappa_a = l_a / (l_a + l_b)`` of the sun's (ring's) side force."""
    Q = np.array(P, dtype=float)
    Q[I_LSA], Q[I_LSB], Q[I_LSC], Q[I_LKA] = slot_a, slot_b, slot_c, share_a
    return Q


def planet_loss(P) -> bool:
    """A planet mesh's loss geometry (slots in the row) rather than a pair's (pinion slot 0, gear slot 1)."""
    return bool(P[I_LSB] > 0.0)


def efficiency(P):
    """The loss hook: the power efficiency of the mesh in its power-flow direction (1: no loss)."""
    return P[I_ETA]


def loss_sides(P):
    """The loss hook's geometry: for the side that drives forward (a) and the driven side (b), the slots whose
    speeds make that side's pitch-line speed and that take its side force, with their shares: ``((slot, share),
    ...)`` each. ``v_a = sum_a share_j lever_j w_j``, ``v_b = -sum_b share_j lever_j w_j``; slot j takes
    ``share_a,j f_a + share_b,j f_b`` (:func:`loss_factors`), a slot on neither side the law's ``f``. A pair
    mesh: its pinion (slot 0) and its gear (slot 1); a planet mesh in the carrier's frame
    (:func:`planet_loss_slots`): its sun or ring and the carrier's share kappa_a, its planet and the carrier's
    share kappa_b = 1 - kappa_a."""
    if not planet_loss(P):
        return ((0, 1.0),), ((1, 1.0),)
    sa, sb, sc, ka = planet_loss_slots(P)
    side_a = [(sa, 1.0)] if sa >= 0 else []
    side_b = [(sb, 1.0)]
    if sc >= 0:
        side_a.append((sc, ka))
        side_b.append((sc, 1.0 - ka))
    return tuple(side_a), tuple(side_b)


def planet_loss_slots(P):
    """(slot a, slot b, slot c, kappa_a) of a planet mesh's loss: a planet mesh's deflection is
    ``delta = l_a (theta_a - theta_c) + l_b (theta_b - theta_c)`` (a: the sun or the ring, b: the planet, c: the
    carrier); it loses in the carrier's frame, on the relative pitch-line speeds ``v_a = l_a (w_a - w_c)``,
    ``v_b = -l_b (w_b - w_c)``: body a takes ``-l_a f_a``, body b ``-l_b f_b`` and the carrier, whose lever is
    ``l_c = -(l_a + l_b)``, ``-l_c (kappa_a f_a + kappa_b f_b)`` (= l_a f_a + l_b f_b: the friction forces are
    internal, the moments about the central axis balance). A held member has slot -1 (no speed, no body)."""
    return int(P[I_LSA]), int(P[I_LSB]), int(P[I_LSC]), P[I_LKA]


def loss_factors(P, f, va, vb):
    """The forces the mesh puts on its two bodies when it loses (1 - eta) of the power it transmits, and their
    partials: (f_a, f_b, df_a/df, df_a/dv, df_b/df, df_b/dv), ``f`` the line force of the law, ``va = r_a w_a``
    and ``vb = r_b w_b`` the pitch-line speeds of the pinion and the gear, ``v = (va + vb) / 2``.

    The driven side gets eta f, the driving side f: ``f_a = f (1 - c (1 - s))``, ``f_b = f (1 - c (1 + s))``,
    ``c = (1 - eta) / 2``, ``s = tanh(f v / W)`` the power-flow sign regularised over the power W
    (``loss_width_W``): power from pinion to gear (s = 1) loses on the gear side, from gear to pinion
    (s = -1, a reversed load or an overrunning gear) on the pinion side. The loss power
    ``va (f_a - f) - vb (f_b - f)`` is (1 - eta) f v s >= 0 up to the deflection rate's share."""
    v = 0.5 * (va + vb)
    w = P[I_LW]
    s = math.tanh(f * v / w)
    c = 0.5 * (1.0 - P[I_ETA])
    ga = 1.0 - c * (1.0 - s)
    gb = 1.0 - c * (1.0 + s)
    gx = c * (1.0 - s * s) / w
    return f * ga, f * gb, ga + f * gx * v, f * f * gx, gb - f * gx * v, -f * f * gx


def linear_stiffness(P, F, floor_m):
    """The linearised mesh stiffness of the viscous damping law, dF_n/dh = e K p0^(e-1) at the line force F
    on the drive flank at mean stiffness (K itself for e = 1; the normal slope, as design's linearised
    stiffness); an unloaded mesh with e > 1 at the penetration ``floor_m`` instead (it would have none)."""
    e = P[I_E]
    p0 = static_penetration(P, F)
    if e != 1.0 and p0 <= 0.0:
        p0 = floor_m
    return e * P[I_K] * p0 ** (e - 1.0)


def transmission_error(P, phi):
    """(e, de/dphi, d2e/dphi2) at the mesh phase phi (cycles): e = sum_j e_j cos(2 pi j phi + psi_j), m."""
    e = e1 = e2 = 0.0
    for j in range(int(P[I_NTE])):
        w = TWO_PI * (j + 1)
        a = P[I_TE + j]
        arg = w * phi + P[I_TEP + j]
        c = math.cos(arg)
        s = math.sin(arg)
        e += a * c
        e1 -= a * w * s
        e2 -= a * w * w * c
    return e, e1, e2


def harmonic_factor(P, phi):
    """(1 - sum_j s_j cos(2 pi j phi + chi_j), its d/dphi): the stiffness harmonics' factor on K."""
    h = 1.0
    dh = 0.0
    for j in range(int(P[I_NKS])):
        w = TWO_PI * (j + 1)
        arg = w * phi + P[I_KSP + j]
        h -= P[I_KS + j] * math.cos(arg)
        dh += P[I_KS + j] * w * math.sin(arg)
    return h, dh


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
        x = phi + P[I_CPH] if P[I_CPH] != 0.0 else phi
        kph = P[I_K] * contact_slope(x, P[I_EA], P[I_EB])
        kk = P[I_K] * contact_factor(x, P[I_EA], P[I_EB])
    if P[I_NKS] != 0.0:
        h, dh = harmonic_factor(P, phi)
        kph = kph * h + kk * dh
        kk = kk * h
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


def law(P, q, qd, phi, wphi=0.0):
    """The force law on the dynamic transmission error: (F_bt, dF/dq, dF/dq', dF/dphi at fixed q, 0,
    damping power, power into a time-varying spring, 0). It is :func:`force` itself for a mesh without
    transmission error (q = delta; the generated code calls it directly there, one call fewer).

    The flank test (:func:`_contact`), the damping ramp (:func:`_damping`) and, for the default Hertzian law
    (e = 1.5) at a constant stiffness, the elastic term (:func:`_elastic`) are written out here, the same
    operations in the same order: the Python right-hand side calls this law ~30,000 times in a one-shot run, and
    the first two calls were a fifth of its cost, the third a sixth of what was left."""
    cb = P[I_CB]
    half = P[I_HALF]
    h = cb * q
    if h > half:  # the drive flank
        p, pd, sc = h - half, cb * qd, cb
    elif h < -half:  # the back flank
        p, pd, sc = -h - half, -cb * qd, -cb
    elif P[I_VIS] != 0.0:  # in the gap: the viscous damper alone
        cv = P[I_CV]
        return cv * qd, 0.0, cv, 0.0, 0.0, cv * qd * qd, 0.0, 0.0
    else:
        return 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    if P[I_E] == 1.5 and P[I_TV] == 0.0 and P[I_NKS] == 0.0:  # Hertz at the mean stiffness: _elastic written out
        kk = P[I_K]
        rp = math.sqrt(p)
        fe, ke, fph, u = kk * p * rp, 1.5 * kk * rp, 0.0 * (p * rp), 0.0
    else:
        fe, ke, fph, _ = _elastic(P, p, phi)
        u = fe * pd if (P[I_TV] != 0.0 or P[I_NKS] != 0.0) else 0.0
    if P[I_VIS] != 0.0:
        cv = P[I_CV]
        return sc * fe + cv * qd, P[I_CB2] * ke, cv, sc * fph, 0.0, cv * qd * qd, u, 0.0
    c = P[I_C]
    if c > 0.0:
        dc = 0.0
        s = p * P[I_INVD]
        if s < 1.0:  # STEP(p, 0, 0, d, C) below the full damping depth
            c, dc = c * s * s * (3.0 - 2.0 * s), P[I_DC] * s * (1.0 - s)
        fn = fe + c * pd
        if fn > 0.0:
            return sc * fn, P[I_CB2] * (ke + dc * pd), P[I_CB2] * c, sc * fph, 0.0, (fn - fe) * pd, u, 0.0
        return 0.0, 0.0, 0.0, 0.0, 0.0, (0.0 - fe) * pd, u, 0.0  # clamped: the damper cancels the spring
    return sc * fe, P[I_CB2] * ke, 0.0, sc * fph, 0.0, 0.0, u, 0.0


def rhs_force(P, d, dd):
    """The optional hook of the Python right-hand side (:data:`gearcli.model.elements.RHS_HOOK`): ``(F_bt, damping
    power)`` of a row whose force depends on no phase (:func:`phased` false), value for value :func:`law`'s first
    and sixth numbers; the generated ``rhs`` reads no other of a phase-free mesh, and this skips the six it would
    drop (the partials, the 8-tuple): ~40 % of :func:`law`'s time, ~7 % of a one-shot seed ``simulate``'s
    integrations. The flank test by the sign of ``h``: the penetration on that side, ``h - g/2`` or ``-h - g/2``
    as the law's, is positive exactly where the law's ``h > g/2`` or ``h < -g/2`` holds."""
    cb = P[I_CB]
    h = cb * d
    if h > 0.0:  # the drive flank's side
        p, sc = h - P[I_HALF], cb
    else:
        p, sc = -h - P[I_HALF], -cb
    if not p > 0.0:  # in the backlash: the viscous damper alone, if any
        return (P[I_CV] * dd, P[I_CV] * dd * dd) if P[I_VIS] != 0.0 else (0.0, 0.0)
    pd = sc * dd
    fe = P[I_K] * p * math.sqrt(p) if P[I_E] == 1.5 else _elastic(P, p, 0.0)[0]
    if P[I_VIS] != 0.0:
        return sc * fe + P[I_CV] * dd, P[I_CV] * dd * dd
    c = P[I_C]
    if c <= 0.0:
        return sc * fe, 0.0
    s = p * P[I_INVD]
    if s < 1.0:  # STEP(p, 0, 0, d, C) below the full damping depth
        c = c * s * s * (3.0 - 2.0 * s)
    fn = fe + c * pd
    return (sc * fn, (fn - fe) * pd) if fn > 0.0 else (0.0, (0.0 - fe) * pd)


def _law_power_gradient(P, q, qd, phi):
    """Partials of (damping power, time-varying spring power) by (q, q', phi at fixed q)."""
    touching, p, pd, sc = _contact(P, q, qd)
    qd_ = qv = qt = ud = uv = ut = 0.0
    if P[I_VIS] != 0.0:
        qv = 2.0 * P[I_CV] * qd
        if not touching:
            return qd_, qv, qt, ud, uv, ut
    elif not touching:
        return qd_, qv, qt, ud, uv, ut
    fe, ke, fph, _ = _elastic(P, p, phi)
    if P[I_VIS] == 0.0 and P[I_C] > 0.0:
        c, dc = _damping(P, p)
        if fe + c * pd > 0.0:
            qd_, qv = sc * dc * pd * pd, 2.0 * sc * c * pd
        else:
            qd_, qv, qt = -sc * ke * pd, -sc * fe, -fph * pd
    if time_varying(P):
        ud, uv, ut = sc * ke * pd, sc * fe, fph * pd
    return qd_, qv, qt, ud, uv, ut


def _excited(P, d, dd, phi, wphi):
    """(q, q', e', e'') of a mesh with a transmission error."""
    e, e1, e2 = transmission_error(P, phi)
    return d - e, dd - e1 * wphi, e1, e2


def force(P, d, dd, phi, wphi):
    """(F_bt, dF/d delta, dF/d delta', dF/d phi, dF/d phi', damping power, power into a time-varying
    spring, power of the transmission error on the bodies)."""
    if P[I_NTE] == 0.0:
        return law(P, d, dd, phi)
    q, qd, e1, e2 = _excited(P, d, dd, phi, wphi)
    f, kd, kv, kt, _, pq, pu, _ = law(P, q, qd, phi)
    return f, kd, kv, kt - kd * e1 - kv * e2 * wphi, -kv * e1, pq, pu, -f * e1 * wphi


def power_gradient(P, d, dd, phi, wphi):
    """Partials of (damping power, time-varying spring power, transmission-error power) by
    (delta, delta', phi, phi'): twelve numbers, power by power."""
    if P[I_NTE] == 0.0:
        a, b, c, x, y, z = _law_power_gradient(P, d, dd, phi)
        return a, b, c, 0.0, x, y, z, 0.0, 0.0, 0.0, 0.0, 0.0
    q, qd, e1, e2 = _excited(P, d, dd, phi, wphi)
    a, b, c, x, y, z = _law_power_gradient(P, q, qd, phi)
    f, kd, kv, kt, kw, _, _, _ = force(P, d, dd, phi, wphi)
    return (a, b, c - a * e1 - b * e2 * wphi, -b * e1, x, y, z - x * e1 - y * e2 * wphi, -y * e1,
            -kd * e1 * wphi, -kv * e1 * wphi, -(kt * e1 + f * e2) * wphi, -(kw * wphi + f) * e1)


def dynamic_transmission_error(P, d, phi):
    """The mesh's dynamic transmission error q = delta - e(phi) along the transverse line of action (m): the
    deflection the teeth actually take up (backlash gap included)."""
    return d - transmission_error(P, phi)[0] if P[I_NTE] != 0.0 else d


def penetration(P, d, phi=0.0):
    """Signed penetration beyond the gap (m): + drive flank, - back flank, 0 inside the backlash."""
    touching, p, _, sc = _contact(P, dynamic_transmission_error(P, d, phi), 0.0)
    return (p if sc > 0.0 else -p) if touching else 0.0


def potential(P, d, phi):
    """Elastic energy K g p^(e+1) / (e+1) stored in the mesh, J."""
    touching, p, _, _ = _contact(P, dynamic_transmission_error(P, d, phi), 0.0)
    if not touching:
        return 0.0
    x = phi + P[I_CPH] if P[I_CPH] != 0.0 else phi
    kk = P[I_K] * contact_factor(x, P[I_EA], P[I_EB]) if P[I_TV] != 0.0 else P[I_K]
    if P[I_NKS] != 0.0:
        kk *= harmonic_factor(P, phi)[0]
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
    """The parameter row of the mesh frozen at ``factor`` x its mean stiffness, without gap and without
    excitation (linearisation)."""
    Q = np.array(P, dtype=float)
    Q[I_K] *= factor
    Q[I_TV] = 0.0
    Q[I_HALF] = 0.0
    Q[I_NTE] = Q[I_NKS] = 0.0
    return Q


def channel(P, i, d, phi):
    """Output channel ``CHANNELS[i]``: the signed penetration, or the dynamic transmission error."""
    return penetration(P, d, phi) if i == 0 else dynamic_transmission_error(P, d, phi)


def tangent(P, F, stiffest_phase=False):
    """(k, c, static penetration) at the line force |F|, on the drive flank without the gap at the mean
    stiffness (``stiffest_phase``: the largest contact-line factor of a time-varying mesh); unloaded, a
    linear mesh keeps K, a Hertzian one has no stiffness."""
    factor = contact_length_range(P[I_EA], P[I_EB])[1] if stiffest_phase and time_varying(P) else 1.0
    Q = linear_row(P, factor)
    p0 = static_penetration(Q, F)
    if p0 == 0.0 and Q[I_E] != 1.0:
        return 0.0, 0.0, 0.0
    _, k, cd, _, _, _, _, _ = force(Q, max(p0, 1e-300) / Q[I_CB], 0.0, 0.0, 0.0)
    return k, cd, p0


def assembled(P, F, m_e):
    """A ``damping_ratio`` mesh's row with its viscous damping c = 2 zeta sqrt(k_lin m_e) (module text), from
    the static line force F and the equivalent mass m_e of the bodies it joins; other meshes unchanged."""
    if P[I_VIS] == 0.0:
        return P
    return with_viscous(P, linear_stiffness(P, F, MIN_APPROACH_M), m_e)


def cycle_period_s(P, w):
    """One mesh cycle at the pinion speed w: 2 pi / (z_p w_p) = 60 / (z_p n_p) s."""
    return 2.0 * math.pi / (P[I_Z] * abs(w))


def makes_excitation(P) -> bool:
    """Time-varying stiffness, or any transmission-error or stiffness harmonic: once per mesh cycle."""
    return bool(time_varying(P) or any(P[I_TE + j] != 0.0 for j in range(N_HARM))
                or any(P[I_KS + j] != 0.0 for j in range(N_HARM)))


def self_exciting(P) -> bool:
    """The law makes its own harmonics: Hertzian, contact-line time variation, or backlash."""
    return bool(P[I_E] != 1.0 or P[I_TV] != 0.0 or P[I_HALF] > 0.0)


def damped(P) -> bool:
    return bool(P[I_CV] > 0.0) if P[I_VIS] != 0.0 else bool(P[I_C] > 0.0)


def time_varying(P) -> bool:
    """The stiffness depends on the mesh phase (contact lines or stiffness harmonics)."""
    return bool(P[I_TV] != 0.0 or P[I_NKS] != 0.0)


def phased(P) -> bool:
    """The force depends on the mesh phase (time-varying stiffness or a transmission error)."""
    return bool(P[I_TV] != 0.0 or P[I_NKS] != 0.0 or P[I_NTE] != 0.0)


def excited(P) -> bool:
    """A transmission error: the force depends on the phase rate too, and the TE does work."""
    return bool(P[I_NTE] != 0.0)


def _pow(p, e):
    """``p ** e`` element by element with the C library's ``pow``, as the scalar laws and the compiled kernel take it
    (numpy's own power may round the last bit otherwise)."""
    return np.array([x ** e for x in p.tolist()], dtype=float).reshape(p.shape)


def series(P, d, dd, phi, wphi):
    """The optional vectorised hook (:data:`gearcli.model.elements.SERIES_HOOK`): ``(F, stored energy, (penetration,
    dte))`` at every sample of the float arrays ``d``, ``dd``, value for value what :func:`force`, :func:`potential`
    and :func:`channel` give there: their operations in their order on IEEE doubles, ``pow`` the C library's as
    theirs (:func:`_pow`), so the same doubles. None for a phase-dependent row (time-varying stiffness, stiffness
    harmonics or a transmission error), which the caller evaluates sample by sample."""
    if phased(P):
        return None
    cb, half, kk, e = P[I_CB], P[I_HALF], P[I_K], P[I_E]
    h = cb * d
    drive, back = h > half, h < -half
    touching = drive | back
    p = np.where(drive, h - half, np.where(back, -h - half, 0.0))  # _contact
    pd = np.where(drive, cb * dd, np.where(back, -cb * dd, 0.0))
    sc = np.where(drive, cb, np.where(back, -cb, 0.0))
    if e == 1.0:  # _elastic at mean stiffness
        fe = kk * p
    elif e == 1.5:
        fe = kk * p * np.sqrt(p)
    elif e == 2.0:
        fe = kk * p * p
    else:
        fe = kk * _pow(p, e)
    if P[I_VIS] != 0.0:
        cv = P[I_CV]
        F = np.where(touching, sc * fe + cv * dd, cv * dd)
    elif P[I_C] > 0.0:
        s = p * P[I_INVD]  # _damping
        c = np.where(s < 1.0, P[I_C] * s * s * (3.0 - 2.0 * s), P[I_C])
        fn = fe + c * pd
        F = np.where(touching & (fn > 0.0), sc * fn, 0.0)
    else:
        F = np.where(touching, sc * fe, 0.0)
    U = np.where(touching, kk * _pow(p, e + 1.0) / (e + 1.0), 0.0)
    penetration_m = np.where(touching, np.where(sc > 0.0, p, -p), 0.0)
    return F, U, (penetration_m, np.array(d, dtype=float))
