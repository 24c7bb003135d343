"""The analytic Jacobian df/dy of :func:`gearcli.engine.assembly.scene_rhs`, from the elements' own partials (as
the generated ``jac``): what Radau's Newton iteration and the variational equations use.
"""

from __future__ import annotations

import numpy as np

from gearcli.engine.assembly import (
    body_speed,
    deflection_rate,
    n_dynamic,
    n_model_states,
    prologue,
    side_losses,
    sided,
)
from gearcli.engine.laws import (
    conn_damped,
    conn_excited,
    conn_force,
    conn_lossy,
    conn_phase_per_rad,
    conn_phased,
    conn_power_gradient,
    conn_tv,
)
from gearcli.engine.numba_cache import jit, jit_alloc
from gearcli.engine.packing import IP_DRIVE, IP_Q_DAMPING, IP_Q_INPUT, IP_Q_LOAD, IP_Q_TV, IP_THETA, IP_W0


@jit
def _angle_gradient(body, model, ag):
    """ag = d(theta_body)/dy: theta_b = (r_a theta_a - delta_c) / r_b along the tree from theta_0 (a state of
    a torque drive; a function of t alone for a speed drive), through a row body's row (Layout.angle_rows)
    where the path meets one."""
    bodies, lev, tree = model.bodies, model.levers, model.tree
    i_th = model.ipar[IP_THETA]
    ag[:] = 0.0
    depth = 0  # the path from its root (body 0 or a row body), walked from the root end
    b = body
    while b > 0 and tree[b] >= 0:
        depth += 1
        b = bodies[tree[b], 0]
    if b > 0:  # a row body: its gradient from the earlier bodies' (a table, each row built as the path's steps)
        _row_gradient(b, model, ag)
    elif i_th >= 0:
        ag[i_th] = 1.0
    for k in range(depth, 0, -1):
        b = body
        for _ in range(k - 1):
            b = bodies[tree[b], 0]
        c = tree[b]
        for j in range(ag.size):
            ag[j] *= lev[c, 0] / -lev[c, 1]
        ag[c] -= 1.0 / -lev[c, 1]

@jit_alloc
def _row_gradient(body, model, ag):
    """ag = d(theta_body)/dy of a row body: the gradients of all bodies up to it, in index order (tree bodies as
    :func:`_angle_gradient` forms them, row bodies from their rows), in a table."""
    bodies, lev, tree, M = model.bodies, model.levers, model.tree, model.angle_rows
    i_th = model.ipar[IP_THETA]
    nb = M.shape[0]
    G = np.zeros((body + 1, ag.size))
    if i_th >= 0:
        G[0, i_th] = 1.0
    for b in range(1, body + 1):
        c = tree[b]
        if c >= 0:
            a = bodies[c, 0]
            for j in range(ag.size):
                G[b, j] = G[a, j] * (lev[c, 0] / -lev[c, 1])
            G[b, c] -= 1.0 / -lev[c, 1]
        elif c == -2:
            for i in range(b):
                if M[b, i] != 0.0:
                    for j in range(ag.size):
                        G[b, j] += M[b, i] * G[i, j]
            for k in range(M.shape[1] - nb - 1):
                G[b, k] += M[b, nb + k]
    for j in range(ag.size):
        ag[j] = G[body, j]

@jit
def _gradient(c, xd, xv, xt, xw, model, first, g, ag):
    """g = d(x_c)/dy of a connector quantity with partials xd (deflection), xv (rate), xt (mesh phase),
    xw (phase rate)."""
    kind, bodies, lev, param = model.kind, model.bodies, model.levers, model.param
    i_w0 = model.ipar[IP_W0]
    a = bodies[c, 0]
    g[:] = 0.0
    g[c] = xd
    for s in range(bodies.shape[1]):
        b = bodies[c, s]
        if b >= first:
            g[i_w0 + b - first] += lev[c, s] * xv
    if conn_phased(kind[c], param[c]) and xt != 0.0:
        _angle_gradient(a, model, ag)
        k = conn_phase_per_rad(kind[c], param[c]) * xt
        for j in range(g.size):
            g[j] += ag[j] * k
    if conn_excited(kind[c], param[c]) and a >= first:
        g[i_w0 + a - first] += conn_phase_per_rad(kind[c], param[c]) * xw

@jit
def jacobian(t, y, Jm, model, th, g, ag):
    """Jm = df/dy of :func:`rhs`, from the elements' own partials (as the generated ``jac``)."""
    kind, bodies, lev, param, inertia, ipar = model.kind, model.bodies, model.levers, model.param, model.inertia, model.ipar
    nc = kind.shape[0]
    nb = inertia.shape[0]
    n = y.size
    i_w0 = ipar[IP_W0]
    i_th = ipar[IP_THETA]
    q_in, q_load, q_damp, q_tv = ipar[IP_Q_INPUT], ipar[IP_Q_LOAD], ipar[IP_Q_DAMPING], ipar[IP_Q_TV]
    speed, w0, a0, tin, dtin, load, tl, dtl = prologue(t, y, model, th)
    first = 1 if speed else 0
    Jm[:, :] = 0.0
    for c in range(nc):
        a = bodies[c, 0]
        P = param[c]
        dd = deflection_rate(c, y, model, first, i_w0, w0)
        tv = conn_tv(kind[c], P)
        ex = conn_excited(kind[c], P)
        phi = conn_phase_per_rad(kind[c], P) * th[a] if conn_phased(kind[c], P) else 0.0
        wphi = conn_phase_per_rad(kind[c], P) * body_speed(y, a, first, i_w0, w0) if ex else 0.0
        _, kd, kv, kt, kw, _, _, _ = conn_force(kind[c], P, y[c], dd, phi, wphi)
        for s in range(bodies.shape[1]):
            if bodies[c, s] >= first:
                Jm[c, i_w0 + bodies[c, s] - first] = lev[c, s]
        _gradient(c, kd, kv, kt, kw, model, first, g, ag)
        loses = conn_lossy(kind[c], P)
        va = vb = fa = fb = aa = ba = ab = bb = 0.0
        if loses:
            f = conn_force(kind[c], P, y[c], dd, phi, wphi)[0]
            va, vb, fa, fb, aa, ba, ab, bb = side_losses(c, f, y, model, first, i_w0, w0)
        for s in range(bodies.shape[1]):  # body j takes -s_j r_j F: scattered by index
            b = bodies[c, s]
            side = loses and sided(c, s, model)  # a lossy element's side force: A dF/dy + B dv/dy
            if b >= first:
                k = -lev[c, s] / inertia[b]
                for j in range(n):
                    Jm[i_w0 + b - first, j] += k * (_slot_row(c, s, j, g[j], aa, ba, ab, bb, model, first, i_w0)
                                                    if side else g[j])
            elif b == 0 and speed:  # the drive's power: its reaction on body 0, times w0
                k = lev[c, s] * w0
                for j in range(n):
                    Jm[q_in, j] += k * (_slot_row(c, s, j, g[j], aa, ba, ab, bb, model, first, i_w0)
                                        if side else g[j])
        if loses:  # the loss power va (fa - f) - vb (fb - f): lf dF/dy + lv dv/dy + (fa - f) r_a, -(fb - f) r_b
            f = conn_force(kind[c], P, y[c], dd, phi, wphi)[0]
            lf = va * (aa - 1.0) - vb * (ab - 1.0)
            lv = va * ba - vb * bb
            for j in range(n):
                Jm[q_damp, j] += _loss_row(c, j, g[j], lf, lv, fa - f, fb - f, model, first, i_w0)
        if conn_damped(kind[c], P) or tv or ex:
            qd, qv, qt, qw, ud, uv, ut, uw, ed, ev, et, ew = conn_power_gradient(kind[c], P, y[c], dd, phi, wphi)
            if conn_damped(kind[c], P):
                _gradient(c, qd, qv, qt, qw, model, first, g, ag)
                for j in range(n):
                    Jm[q_damp, j] += g[j]
            if tv:
                _gradient(c, ud, uv, ut, uw, model, first, g, ag)
                for j in range(n):
                    Jm[q_tv, j] += g[j]
            if ex:  # the transmission error's power is part of the input work
                _gradient(c, ed, ev, et, ew, model, first, g, ag)
                for j in range(n):
                    Jm[q_in, j] += g[j]
    if i_th >= 0:
        Jm[i_th, i_w0] = 1.0
    if ipar[IP_DRIVE] == 2:  # a motor: P_in = T_m(w0) w0, T_m'(w0) on body 0
        Jm[q_in, i_w0] += tin + dtin * w0
        Jm[i_w0, i_w0] += (1.0 / inertia[0]) * dtin
    elif not speed:
        Jm[q_in, i_w0] += tin
        if dtin != 0.0 and i_th >= 0:  # a rippled drive torque depends on the input angle
            Jm[i_w0, i_th] += dtin * (1.0 / inertia[0])
            Jm[q_in, i_th] += dtin * w0
    if load:
        last = i_w0 + nb - 1 - first  # its speed (the speeds: StateLayout's one contiguous slice)
        if model.load_law.size > 0:  # a speed-dependent load
            Jm[q_load, last] = tl + dtl * body_speed(y, nb - 1, first, i_w0, w0)
            Jm[last, last] += (-1.0 / inertia[nb - 1]) * dtl
        else:
            Jm[q_load, last] = tl
    ns = n_model_states(model)
    if n > ns:  # an augmented state: the variational equations' blocks (block diagonal, see variational_rhs)
        d = n_dynamic(model)
        for k in range(d):
            s = ns + k * d
            for i in range(d):
                for j in range(d):
                    Jm[s + i, s + j] = Jm[i, j]

@jit
def _speed_column(c, j, model, first, i_w0):
    """d v/dy_j of a lossy element's mean pitch-line speed v = (v_a + v_b) / 2: 0.5 k summed over the terms of both
    sides whose body's speed is y_j (a first, then b, as the generated Python; ``hit`` False: none is)."""
    lb, lk = model.loss_body, model.loss_coef
    out = 0.0
    hit = False
    for k in range(lb.shape[1]):  # side a's terms, then side b's
        b = lb[c, k]
        if b >= first and j == i_w0 + b - first:
            out = out + 0.5 * lk[c, k] if hit else 0.5 * lk[c, k]
            hit = True
    return out, hit

@jit
def _side_row(c, j, gj, a_coef, b_coef, model, first, i_w0):
    """d(f_side)/dy_j = A dF/dy_j + B dv/dy_j, in the generated expression's order."""
    dv, hit = _speed_column(c, j, model, first, i_w0)
    x = a_coef * gj
    return x + dv * b_coef if hit else x

@jit
def _slot_row(c, s, j, gj, aa, ba, ab, bb, model, first, i_w0):
    """d/dy_j of the side force a lossy element puts on its slot s (assembly.side_force): f_a's, f_b's, or the
    shares of both."""
    i = model.loss_body.shape[1] + 2 * s
    sa = model.loss_coef[c, i]
    sb = model.loss_coef[c, i + 1]
    if sa != 0.0 and sb != 0.0:
        return sa * _side_row(c, j, gj, aa, ba, model, first, i_w0) + sb * _side_row(c, j, gj, ab, bb, model, first,
                                                                                   i_w0)
    if sa != 0.0:
        return _side_row(c, j, gj, aa, ba, model, first, i_w0)
    return _side_row(c, j, gj, ab, bb, model, first, i_w0)

@jit
def _loss_row(c, j, gj, lf, lv, da, db, model, first, i_w0):
    """d(loss power)/dy_j: lf dF/dy_j + lv dv/dy_j + (f_a - f) dv_a/dy_j - (f_b - f) dv_b/dy_j, the sides' terms
    in their order (a pair mesh: (f_a - f) r_a [y_j = w_a] - (f_b - f) r_b [y_j = w_b])."""
    lb, lk = model.loss_body, model.loss_coef
    m = lb.shape[1] // 2
    dv, hit = _speed_column(c, j, model, first, i_w0)
    x = lf * gj
    if hit:
        x = x + dv * lv
    for k in range(m):
        b = lb[c, k]
        if b >= first and j == i_w0 + b - first:
            x = x + lk[c, k] * da
    for k in range(m, 2 * m):
        b = lb[c, k]
        if b >= first and j == i_w0 + b - first:
            x = x - lk[c, k] * db
    return x
