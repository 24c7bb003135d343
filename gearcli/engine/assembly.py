"""The scene's right-hand side read from the model (:class:`gearcli.engine.packing.Model`).

The same assembly as the generated Python source (:mod:`gearcli.model.codegen`), term for term and in the same
floating-point order, so both engines compute bit-identical derivatives: the speed drive's exact STEP motion (or
the ramped drive torque), the ramped load, the body angles a time-varying mesh needs, each connector's force from
its element law (:mod:`gearcli.engine.laws`), the net torque on each free body, and the four work quadratures; and
the stored energy the energy watch compares with the work done.
"""

from __future__ import annotations

import numpy as np

from gearcli.engine.laws import (
    conn_damped,
    conn_excited,
    conn_force,
    conn_loss_factors,
    conn_lossy,
    conn_phase_per_rad,
    conn_phased,
    conn_potential,
    conn_tv,
    input_motion,
    load_factor,
    motor_torque,
    ramp,
    speed_drive_power,
    torque_fluctuation,
    torque_power,
    torque_ripple,
)
from gearcli.engine.numba_cache import jit, jit_alloc
from gearcli.engine.packing import (
    FP_ANGLE,
    FP_CLOCK,
    FP_DRIVE,
    FP_DRIVE_RAMP,
    FP_LOAD,
    FP_LOAD_RAMP,
    IP_DRIVE,
    IP_LAST_ANGLE,
    IP_N_STATES,
    IP_Q_DAMPING,
    IP_Q_INPUT,
    IP_Q_LOAD,
    IP_Q_TV,
    IP_QUAD,
    IP_THETA,
    IP_W0,
)


@jit
def prologue(t, y, model, th):
    """(speed drive, w0, a0, Tin, dTin, load, TL, dTL/dw_N) at (t, y) and the body angles ``th`` the phased
    meshes need, as the generated prologue forms them; dTin is d/dth0 of a rippled drive torque, d/dw0 of a
    motor's."""
    lev, ipar, fpar, rip, flu, tree = model.levers, model.ipar, model.fpar, model.ripple, model.fluct, model.tree
    mrow, lrow = model.motor, model.load_law
    speed = ipar[IP_DRIVE] == 0
    i_w0 = ipar[IP_W0]
    i_th = ipar[IP_THETA]
    a0 = 0.0
    tin = 0.0
    dtin = 0.0
    if speed:
        th0, w0, a0 = input_motion(t, fpar[FP_DRIVE], fpar[FP_DRIVE_RAMP], fpar[FP_ANGLE])
    elif ipar[IP_DRIVE] == 2:  # an induction motor at its speed
        w0 = y[i_w0]
        th0 = y[i_th] if i_th >= 0 else 0.0
        tin, dtin = motor_torque(mrow, t, w0)
    else:
        tin = ramp(t, fpar[FP_DRIVE], fpar[FP_DRIVE_RAMP])
        w0 = y[i_w0]
        th0 = y[i_th] if i_th >= 0 else 0.0
        if rip.size > 0:
            r, dr = torque_ripple(rip, th0)
            dtin = tin * dr
            tin = tin * r
    load = fpar[FP_LOAD] != 0.0
    tl = 0.0
    if load:
        tl = ramp(t, fpar[FP_LOAD], fpar[FP_LOAD_RAMP])
        if flu.size > 0:
            tl = tl * torque_fluctuation(flu, t + fpar[FP_CLOCK] if fpar[FP_CLOCK] != 0.0 else t)
    dtl = 0.0
    if load and lrow.size > 0:  # T_L g(w_N)
        nb = model.inertia.shape[0]
        g, dg = load_factor(lrow, body_speed(y, nb - 1, 1 if speed else 0, i_w0, w0))
        dtl = tl * dg
        tl = tl * g
    th[0] = th0
    for b in range(1, ipar[IP_LAST_ANGLE] + 1):  # theta_b = (r_a theta_a - delta_c) / r_b along the tree
        c = tree[b]
        if c >= 0:
            th[b] = (lev[c, 0] * th[model.bodies[c, 0]] - y[c]) * (1.0 / -lev[c, 1])
        elif c == -2:  # a body the kinematics fix through several connectors (Layout.angle_rows), as generated
            th[b] = angle_row(b, model, th, y)
    return speed, w0, a0, tin, dtin, load, tl, dtl

@jit
def angle_row(b, model, th, y):
    """theta_b from its row (Layout.angle_rows): body angles, then deflections, then the constant, summed in
    the generated expression's order."""
    M = model.angle_rows
    nb = M.shape[0]
    x = 0.0
    have = False
    for j in range(b):
        if M[b, j] != 0.0:
            x = x + M[b, j] * th[j] if have else M[b, j] * th[j]
            have = True
    for c in range(M.shape[1] - nb - 1):
        if M[b, nb + c] != 0.0:
            x = x + M[b, nb + c] * y[c] if have else M[b, nb + c] * y[c]
            have = True
    return x + M[b, M.shape[1] - 1]

@jit
def body_speed(y, b, first, i_w0, w0):
    """Body b's speed: the prescribed w0 below ``first``, else its state; the free bodies' speeds are one
    contiguous slice from ``i_w0`` (gearcli.model.layout.StateLayout.speeds and .omega: ``n_conn + b -
    first_free``)."""
    if b < first:
        return w0
    return y[i_w0 + b - first]

@jit
def deflection_rate(c, y, model, first, i_w0, w0):
    """delta_c' = sum_j s_j r_j w_{bodies[j]}, in slot order."""
    bodies, lev = model.bodies, model.levers
    dd = lev[c, 0] * body_speed(y, bodies[c, 0], first, i_w0, w0)
    for s in range(1, bodies.shape[1]):
        if bodies[c, s] >= 0:
            dd = dd + lev[c, s] * body_speed(y, bodies[c, s], first, i_w0, w0)
    return dd

@jit
def loss_speeds(c, y, model, first, i_w0, w0):
    """A lossy element's pitch-line speeds (v_a, v_b), each ``sum k w_body`` over its side's terms in their order
    (its loss hook's geometry, packed: gearcli.model.parts.Connector.loss_speeds; a side without terms: 0)."""
    lb, lk = model.loss_body, model.loss_coef
    m = lb.shape[1] // 2
    va = 0.0
    vb = 0.0
    for side in range(2):
        v = 0.0
        have = False
        for k in range(side * m, side * m + m):
            b = lb[c, k]
            if b >= 0:
                term = lk[c, k] * body_speed(y, b, first, i_w0, w0)
                v = v + term if have else term
                have = True
        if side == 0:
            va = v
        else:
            vb = v
    return va, vb

@jit
def side_losses(c, f, y, model, first, i_w0, w0):
    """A lossy element's pitch-line speeds, its forces on its two sides and their partials (its loss hook's
    ``loss_factors``, dispatched by kind)."""
    va, vb = loss_speeds(c, y, model, first, i_w0, w0)
    fa, fb, aa, ba, ab, bb = conn_loss_factors(model.kind[c], model.param[c], f, va, vb)
    return va, vb, fa, fb, aa, ba, ab, bb

@jit
def sided(c, s, model):
    """Whether a lossy element puts a side force on its slot s (a share of f_a or f_b; packed from
    gearcli.model.parts.Connector.loss_share, (0, 0) for every slot of a lossless element)."""
    i = model.loss_body.shape[1] + 2 * s
    return model.loss_coef[c, i] != 0.0 or model.loss_coef[c, i + 1] != 0.0

@jit
def side_force(c, s, fa, fb, model):
    """The side force a lossy element puts on its slot s, as the generated Python forms it: f_a (a share of side a
    alone), f_b (of side b alone), or ``share_a f_a + share_b f_b`` (a slot on both sides: a planet mesh's
    carrier)."""
    i = model.loss_body.shape[1] + 2 * s
    sa = model.loss_coef[c, i]
    sb = model.loss_coef[c, i + 1]
    if sa != 0.0 and sb != 0.0:
        return sa * fa + sb * fb
    return fa if sa != 0.0 else fb

@jit
def body_torque(i, model, fc):
    """The connectors' torque on body i, -s_j r_j F_c summed in connector order (scatter by index, through
    the body's list of (connector, slot) pairs); a lossy element puts its side force on the slots of its sides
    (a mesh: f_a on its pinion, f_b on its gear; a planet mesh the carrier's share of both on the carrier)."""
    lev, ptr, pairs = model.levers, model.ptr, model.pairs
    nc = model.kind.shape[0]
    x = 0.0
    for k in range(ptr[i], ptr[i + 1]):
        c = pairs[k, 0]
        s = pairs[k, 1]
        f = fc[c]
        if pairs[k, 2] != 0:  # a lossy element's side force (sided), from its f_a and f_b (scene_rhs's loss loop)
            f = side_force(c, s, fc[2 * nc + c], fc[3 * nc + c], model)
        term = -lev[c, s] * f
        x = x + term if k > ptr[i] else term
    return x

@jit
def scene_rhs(t, y, dy, model, th, fc):
    """dy = f(t, y) of the scene ``model`` (its own states: :func:`gearcli.engine.rhs.rhs` adds the variational
    equations of an augmented state); ``th`` (n_bodies) and ``fc`` (4 n_conn: forces, the transmission errors'
    powers, a lossy element's f_a, its f_b) are scratch."""
    kind, bodies, param, inertia, ipar = model.kind, model.bodies, model.param, model.inertia, model.ipar
    nc = kind.shape[0]
    nb = inertia.shape[0]
    i_w0 = ipar[IP_W0]
    i_th = ipar[IP_THETA]
    speed, w0, a0, tin, _, load, tl, _ = prologue(t, y, model, th)
    first = 1 if speed else 0
    damp = 0.0
    tvp = 0.0
    have_damp = False
    have_tv = False
    for c in range(nc):
        a = bodies[c, 0]
        P = param[c]
        dd = deflection_rate(c, y, model, first, i_w0, w0)
        tv = conn_tv(kind[c], P)
        phi = conn_phase_per_rad(kind[c], P) * th[a] if conn_phased(kind[c], P) else 0.0
        wphi = conn_phase_per_rad(kind[c], P) * body_speed(y, a, first, i_w0, w0) if conn_excited(kind[c], P) else 0.0
        f, _, _, _, _, q, u, te = conn_force(kind[c], P, y[c], dd, phi, wphi)
        fc[c] = f
        fc[nc + c] = te
        dy[c] = dd
        if conn_damped(kind[c], P):
            damp = damp + q if have_damp else q
            have_damp = True
        if tv:
            tvp = tvp + u if have_tv else u
            have_tv = True
    for c in range(nc):  # the elements' losses, after the damping (the generated sum's order)
        if conn_lossy(kind[c], param[c]):
            va, vb, fa, fb, _, _, _, _ = side_losses(c, fc[c], y, model, first, i_w0, w0)
            fc[2 * nc + c] = fa  # the side forces body_torque puts on its slots
            fc[3 * nc + c] = fb
            ql = va * (fa - fc[c]) - vb * (fb - fc[c])
            damp = damp + ql if have_damp else ql
            have_damp = True
    for i in range(first, nb):
        x = body_torque(i, model, fc)
        if i == 0 and not speed:
            x = x + tin
        if i == nb - 1 and load:
            x = x - tl
        dy[i_w0 + i - first] = x * (1.0 / inertia[i])
    if i_th >= 0:
        dy[i_th] = w0
    if speed:
        p_in = speed_drive_power(-body_torque(0, model, fc), inertia[0], a0, w0)
    else:
        p_in = torque_power(tin, w0)
    for c in range(nc):  # + the transmission errors' work, connector by connector (the generated sum's order)
        if conn_excited(kind[c], param[c]):
            p_in = p_in + fc[nc + c]
    dy[ipar[IP_Q_INPUT]] = p_in
    dy[ipar[IP_Q_LOAD]] = torque_power(tl, body_speed(y, nb - 1, first, i_w0, w0)) if load else 0.0
    dy[ipar[IP_Q_DAMPING]] = damp
    if ipar[IP_Q_TV] >= 0:
        dy[ipar[IP_Q_TV]] = tvp

@jit
def n_model_states(model):
    """The scene's own state count (an augmented state carries the variational equations after it)."""
    return model.ipar[IP_N_STATES]

@jit
def n_dynamic(model):
    """The dynamic states (deflections, free speeds) whose variational equations an augmented state carries."""
    ipar = model.ipar
    return ipar[IP_THETA] if ipar[IP_THETA] >= 0 else ipar[IP_QUAD]

@jit
def quadrature(model, ip):
    """The state of the quadrature whose ``ipar`` entry is ``ip`` (``IP_Q_*``; -1: none)."""
    return model.ipar[ip]

@jit_alloc
def stored_energy(t, y, model):
    """Kinetic energy + elastic energy of the constant-stiffness connectors + work on time-varying
    springs (the energy watch's ``_stored``)."""
    kind, bodies, param, inertia, ipar = model.kind, model.bodies, model.param, model.inertia, model.ipar
    th = np.zeros(inertia.shape[0])
    speed, w0, _, _, _, _, _, _ = prologue(t, y, model, th)
    first = 1 if speed else 0
    ke = 0.0
    for i in range(inertia.shape[0]):
        w = body_speed(y, i, first, ipar[IP_W0], w0)
        ke += inertia[i] * (w * w)
    total = 0.5 * ke
    for c in range(kind.shape[0]):
        if not conn_tv(kind[c], param[c]):  # a transmission error's mesh at its phase
            phi = conn_phase_per_rad(kind[c], param[c]) * th[bodies[c, 0]] if conn_phased(kind[c], param[c]) else 0.0
            total += conn_potential(kind[c], param[c], y[c], phi)
    if ipar[IP_Q_TV] >= 0:
        total += y[ipar[IP_Q_TV]]
    return total
