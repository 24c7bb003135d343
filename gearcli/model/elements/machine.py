"""The machines at either end of the train: an induction motor's torque-speed curve with its starting method,
and a load torque that depends on speed (docs/physics.md, "Motor and load characteristics").

Both are torques on an end body, in plain ``math`` on floats over a flat parameter row (numba compiles them
unchanged, like the connector laws); each returns the torque and its derivative by the body's speed (the
Jacobian's entry).

Motor row (:func:`motor_row`): the curve is either the extended Kloss form through the nameplate's rated,
breakdown and locked-rotor points,

    T(s) = 2 T_b (1 + a s_b) s s_b / (s^2 + s_b^2 + 2 a s_b^2 |s|),     s = (w_s - w) / w_s,

(``a = 0`` is Kloss's formula; the term ``2 a s_b^2 |s|`` lifts the low-speed part of the curve to the
locked-rotor torque while the maximum stays ``T_b`` at ``s_b``; odd in s, so above synchronous speed the
motor brakes as a generator), or a table (speed rad/s, torque N m) linear between its points, constant
below its first point and extrapolated along its last segment above the last one. Starting methods:

- direct: the curve;
- star-delta: ``T (1/3 + 2/3 S(w))``, S a smoothstep from 0 to 1 over ``[w_sw - dw, w_sw]``
  (``dw`` 1 % of the synchronous speed): star connection gives a third of the torque (voltage / sqrt 3);
- soft start: ``u(t)^2 T``, ``u = u_0 + (1 - u_0) STEP(t, 0, 0, t_r, 1)`` (torque ~ voltage squared);
- VFD: the synchronous speed follows ``w_s STEP(t, 0, 0, t_r, 1)``, and the curve moves with it at
  constant slip speed (constant V/f: the torque depends on ``w_s(t) - w``); above the base speed ``w_B`` (the
  nameplate's synchronous speed: rated voltage at rated frequency) the converter's voltage stays at its rating
  and the field weakens, the curve scaled by ``(w_B / w_s(t))^2`` (flux ~ V/f, torque ~ flux^2 at a given slip
  speed; the breakdown slip speed unchanged, stator resistance neglected); a torque limit ``L`` clamps
  it smoothly, ``(T + L - sqrt((T - L)^2 + (0.02 L)^2)) / 2`` (within 0.01 % of L of min(T, L) away
  from the corner).

Load row (:func:`load_row`): ``T_L = T_ref g(w)`` with ``g = 1`` (exponent 0), ``w / w_n`` (1),
``w |w| / w_n^2`` (2) — smooth through standstill as they stand, w_n the load body's nominal speed —
or a table ``T_table(|w|) tanh(w / w_e) / T_ref`` (``w_e`` 0.5 % of w_n: a breakaway torque at
standstill turns with the direction of rotation instead of jumping).
"""

from __future__ import annotations

import math

MAX_TABLE = 32  # points of a torque-speed table

# motor row
KLOSS, TABLE = 0.0, 1.0
DIRECT, STAR_DELTA, SOFT_START, VFD = 0.0, 1.0, 2.0, 3.0
STARTING = {"direct": DIRECT, "star_delta": STAR_DELTA, "soft_start": SOFT_START, "vfd": VFD}
(M_KIND, M_WS, M_TB, M_SB, M_A, M_START, M_P1, M_P2, M_N, M_WB) = range(10)
M_TAB = 10  # then N speeds (rad/s), then N torques (N m)
STAR_DELTA_WIDTH = 0.01  # of the synchronous speed
TORQUE_LIMIT_ROUNDING = 0.02  # of the limit

# load row
L_KIND, L_EXP, L_WN, L_WE, L_N = range(5)
L_TAB = 5
POWER_LAW = 0.0
LOAD_TABLE_WIDTH = 0.005  # of the nominal speed


def kloss_fit(rated_torque: float, breakdown_ratio: float, locked_ratio: float, rated_slip: float) -> tuple[float, float]:
    """(s_b, a) of the extended Kloss curve through T(s_r) = T_r, max T = T_b at s_b, T(1) = T_lr.

    For a given s_b the locked-rotor point fixes a (linear in a); the rated point then fixes s_b in
    (s_r, 1) by bisection (T(s_r) falls from T_b at s_b = s_r to 0 at s_b = 1). ValueError when the
    nameplate admits no such curve (locked-rotor torque at or above the breakdown torque)."""
    kb, kl, sr = breakdown_ratio, locked_ratio, rated_slip
    if not (kb > 1.0 and 0.0 < kl < kb and 0.0 < sr < 1.0):
        raise ValueError("the Kloss curve needs breakdown ratio > 1, 0 < locked-rotor ratio < breakdown ratio "
                         "and a rated slip between 0 and 1")

    def a_of(sb: float) -> float:
        return (2.0 * kb - kl * (1.0 / sb + sb)) / (2.0 * sb * (kl - kb))

    def excess(sb: float) -> float:
        a = a_of(sb)
        return kloss(sr, kb, sb, a) - 1.0

    lo, hi = sr * (1.0 + 1e-12), 1.0 - 1e-12
    if not (excess(lo) > 0.0 > excess(hi)):
        raise ValueError("no Kloss curve passes through these nameplate points")
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if excess(mid) > 0.0:
            lo = mid
        else:
            hi = mid
    sb = 0.5 * (lo + hi)
    a = a_of(sb)
    if 1.0 + a * sb <= 0.0:
        raise ValueError("no Kloss curve passes through these nameplate points")
    return sb, a


def kloss(s, tb, sb, a):
    """The extended Kloss torque at slip s (float), in units of ``tb``."""
    return 2.0 * tb * (1.0 + a * sb) * s * sb / (s * s + sb * sb + 2.0 * a * sb * sb * abs(s))


def _kloss_d(s, tb, sb, a):
    """(T, dT/ds) of the extended Kloss curve."""
    n = 2.0 * tb * (1.0 + a * sb) * sb
    sg = 1.0 if s >= 0.0 else -1.0
    den = s * s + sb * sb + 2.0 * a * sb * sb * abs(s)
    dden = 2.0 * s + 2.0 * a * sb * sb * sg
    return n * s / den, n * (den - s * dden) / (den * den)


def _table_d(R, start, n, x):
    """(y, dy/dx) of the table with n abscissae at R[start:] and ordinates at R[start + n:]: linear between
    points, constant below the first, the last segment extended above the last."""
    if x <= R[start]:
        return R[start + n], 0.0
    j = n - 2
    for i in range(n - 1):
        if x <= R[start + i + 1]:
            j = i
            break
    x0 = R[start + j]
    x1 = R[start + j + 1]
    y0 = R[start + n + j]
    y1 = R[start + n + j + 1]
    k = (y1 - y0) / (x1 - x0)
    return y0 + k * (x - x0), k


def _step01(t, T):
    """(STEP(t, 0, 0, T, 1)); 1 for T <= 0."""
    if T <= 0.0 or t >= T:
        return 1.0
    if t <= 0.0:
        return 0.0
    s = t / T
    return s * s * (3.0 - 2.0 * s)


def motor_curve(M, w, ws):
    """(T, dT/dw) of the bare curve at speed w with the synchronous speed ``ws`` (the VFD's momentary one); a
    Kloss curve above its base speed ``M[M_WB]`` in field weakening, scaled by (w_B / ws)^2."""
    if M[M_KIND] == KLOSS:
        w0 = M[M_WS]
        t, dts = _kloss_d((ws - w) / w0, M[M_TB], M[M_SB], M[M_A])
        k = field_weakening(M[M_WB], ws)
        return k * t, -k * dts / w0
    return _table_d(M, M_TAB, int(M[M_N]), w + (M[M_WS] - ws))


def field_weakening(wb, ws):
    """(w_B / ws)^2 above the base speed w_B, else 1 (w_B <= 0: none): a converter's voltage is capped at the
    motor's rating, so above its rated frequency the flux, V/f, falls as 1/f and the torque at a given slip speed
    as its square."""
    if wb > 0.0 and ws > wb:
        r = wb / ws
        return r * r
    return 1.0


def motor_torque(M, t, w):
    """(T_m, dT_m/dw) of the motor at time t and speed w, with its starting method."""
    start = M[M_START]
    ws = M[M_WS]
    if start == VFD:
        ws = M[M_WS] * _step01(t, M[M_P1])
    tq, dtq = motor_curve(M, w, ws)
    if start == STAR_DELTA:
        width = STAR_DELTA_WIDTH * M[M_WS]
        x = (w - (M[M_P1] - width)) / width
        if x <= 0.0:
            f, df = 1.0 / 3.0, 0.0
        elif x >= 1.0:
            f, df = 1.0, 0.0
        else:
            f = 1.0 / 3.0 + (2.0 / 3.0) * x * x * (3.0 - 2.0 * x)
            df = (2.0 / 3.0) * 6.0 * x * (1.0 - x) / width
        return tq * f, dtq * f + tq * df
    if start == SOFT_START:
        u = M[M_P2] + (1.0 - M[M_P2]) * _step01(t, M[M_P1])
        return u * u * tq, u * u * dtq
    if start == VFD and M[M_P2] > 0.0:
        lim = M[M_P2]
        eps = TORQUE_LIMIT_ROUNDING * lim
        r = math.sqrt((tq - lim) * (tq - lim) + eps * eps)
        return 0.5 * (tq + lim - r), 0.5 * (1.0 - (tq - lim) / r) * dtq
    return tq, dtq


def load_factor(L, w):
    """(g, dg/dw) of the load law: T_L = T_ref g(w)."""
    if L[L_KIND] == POWER_LAW:
        k = L[L_EXP]
        wn = L[L_WN]
        if k == 0.0:
            return 1.0, 0.0
        if k == 1.0:
            return w / wn, 1.0 / wn
        return w * abs(w) / (wn * wn), 2.0 * abs(w) / (wn * wn)
    n = int(L[L_N])
    aw = abs(w)
    y, dy = _table_d(L, L_TAB, n, aw)
    th = math.tanh(w / L[L_WE])
    sg = 1.0 if w >= 0.0 else -1.0
    return y * th, dy * sg * th + y * (1.0 - th * th) / L[L_WE]


# ------------------------------------------------------------------------------------------ rows (Python)
def motor_row(spec) -> tuple[float, ...]:
    """The flat row of a :class:`gearcli.model.spec.MotorSpec`."""
    head = [0.0] * M_TAB
    head[M_WS] = spec.synchronous_speed_rad_s
    head[M_START] = STARTING[spec.starting]
    head[M_P1], head[M_P2] = spec.start_parameters
    if spec.table:
        head[M_KIND] = TABLE
        head[M_N] = float(len(spec.table))
        return tuple(head) + tuple(float(w) for w, _ in spec.table) + tuple(float(t) for _, t in spec.table)
    head[M_KIND] = KLOSS
    head[M_TB], head[M_SB], head[M_A] = spec.breakdown_torque_Nm, spec.breakdown_slip, spec.kloss_a
    head[M_WB] = spec.base_speed_rad_s
    return tuple(head)


def load_row(exponent: int, nominal_speed_rad_s: float, table: tuple[tuple[float, float], ...],
             reference_torque_Nm: float) -> tuple[float, ...]:
    """The flat row of a speed-dependent load (empty for a constant one): a power law of the load body's
    speed, or a table (torques divided by ``reference_torque_Nm``, the scale T_ref)."""
    if table:
        head = (TABLE, 0.0, nominal_speed_rad_s, LOAD_TABLE_WIDTH * nominal_speed_rad_s, float(len(table)))
        return head + tuple(float(w) for w, _ in table) + tuple(float(t) / reference_torque_Nm for _, t in table)
    if exponent == 0:
        return ()
    return (POWER_LAW, float(exponent), nominal_speed_rad_s, 0.0, 0.0)
