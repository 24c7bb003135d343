"""The compiled kernel (numba): the scene's right-hand side read from :class:`~gearcli.model.ModelArrays`
and scipy's DOP853 loop, step for step, with output sampling and the run's guards inside.

Imported only through :func:`gearcli.engine.load` (which points numba's cache at the user's cache directory
first). Nothing here closes over a scene: every function takes the model as arrays, so one compilation
serves every design file and every sweep point.

Right-hand side. The same assembly as the generated Python source (:mod:`gearcli.model.codegen`), term for
term and in the same floating-point order, so both engines compute bit-identical derivatives: the speed
drive's exact STEP motion (or the ramped drive torque), the ramped load, the body angles a time-varying
mesh needs, each connector's force from its element law, the net torque on each free body, and the four
work quadratures. The element laws are those of :mod:`gearcli.model.elements`, compiled from their own
code (:func:`_jit_module`), never rewritten here.

Integrators. One explicit Runge-Kutta driver (:func:`rk_run`) reads its method as data, the tableau of
:mod:`gearcli.engine.tableau` (DOP853, RK45): ``scipy.integrate``'s ``RungeKutta`` loop transcribed: the initial
step of ``select_initial_step``, the stage sums, the error norm (DOP853's combined 5th/3rd-order one), SAFETY 0.9,
MIN_FACTOR 0.2, MAX_FACTOR 10, the rejected-step rule (no growth right after a rejection), the minimum step
``10 ulp(t)``, the clamp at ``t_bound``, and the dense output (DOP853's three extra stages, counted in nfev as
scipy counts them) at the requested samples. :func:`radau` is scipy's Radau IIA. The run is integrated in segments
between the ramp ends, with a fresh solver (and initial step) at each, as :mod:`gearcli.simulate.solver` does.
After every accepted step both drivers call the same helpers (:func:`step_accepted`, :func:`guards`): trace, non-finite
state, the samples due, the evaluation budget, the priced work budget with its projection (``RunTooLong``), the
energy watch. Status codes: :mod:`gearcli.engine.status`.
"""

from __future__ import annotations

import math
from typing import Any

import numba
import numpy as np

from gearcli.engine import blas as _blas
from gearcli.engine import dispatch as _dispatch
from gearcli.engine import status as st
from gearcli.engine import tableau as tb
from gearcli.engine.numba_cache import jit_alloc
from gearcli.model.elements import KIND_MESH, KIND_PLANET_MESH
from gearcli.model.elements import machine as _machine_mod
from gearcli.model.elements import mesh as _mesh_mod
from gearcli.model.elements import torque as _torque_mod

jit = _dispatch.jit  # cached in the checked directory (gearcli.engine.numba_cache); inf/NaN as IEEE, judged once per step
STATUS_FINISHED, STATUS_FAILED, STATUS_BUDGET = st.FINISHED, st.FAILED, st.BUDGET
STATUS_NONFINITE, STATUS_ENERGY, STATUS_PROJECTED = st.NONFINITE, st.ENERGY, st.PROJECTED
STATUS_INTERRUPTED = st.INTERRUPTED

# the element laws, dispatched by kind: generated from the registry (gearcli.engine.dispatch)
_D = _dispatch.build()  # into the checked cache directory this process loads from
KINDS = _D.KINDS
conn_force, conn_power_gradient, conn_potential = _D.conn_force, _D.conn_power_gradient, _D.conn_potential
conn_channel, conn_n_channels, conn_damped = _D.conn_channel, _D.conn_n_channels, _D.conn_damped
conn_tv, conn_phased, conn_excited = _D.conn_tv, _D.conn_phased, _D.conn_excited
conn_phase_per_rad = _D.conn_phase_per_rad
_TORQUE = _dispatch.jit_module(_torque_mod)
torque_ripple, torque_fluctuation = _TORQUE["ripple"], _TORQUE["fluctuation"]
_MACHINE = _dispatch.jit_module(_machine_mod)  # the motor's curve and start, the load's speed law
motor_torque, load_factor = _MACHINE["motor_torque"], _MACHINE["load_factor"]
mesh_loss_factors = _D._mesh_loss_factors  # a lossy mesh's two side forces (the registry compiled the mesh law)
I_ETA = _mesh_mod.I_ETA
I_LSA, I_LSB, I_LSC, I_LKA = _mesh_mod.I_LSA, _mesh_mod.I_LSB, _mesh_mod.I_LSC, _mesh_mod.I_LKA

# scipy's step-size control (rk.py, common.py); the tableaux are data (gearcli.engine.tableau, the driver's argument)
SAFETY, MIN_FACTOR, MAX_FACTOR = 0.9, 0.2, 10.0
DOP853_TABLEAU, RK45_TABLEAU = tb.DOP853_TABLEAU, tb.RK45_TABLEAU
# wpar layout: the energy watch (e0, w0, scale, margin), the run's start t0, then (optional: a run without them has
# no priced work budget) the budget (cap, project after, projection limit, check every) and the prices
# (eval, jac, lu, step) of gearcli.core.cost, and the span (t_start, t_end) the pace is projected over
WP_E0, WP_W0, WP_SCALE, WP_MARGIN, WP_T0 = 0, 1, 2, 3, 4
WP_CAP, WP_AFTER, WP_LIMIT, WP_EVERY, WP_P_EVAL, WP_P_JAC, WP_P_LU, WP_P_STEP, WP_SPAN0, WP_SPAN1 = range(5, 15)
N_WPAR = 15
WP_PROGRESS = st.WP_PROGRESS  # optional: the time reached, written at every budget check (a progress bar reads it)
WP_STOP = st.WP_STOP  # optional: the stop flag a signal handler sets (gearcli.core.signals), read after every step

# ipar / fpar layout (gearcli.engine.pack)
IP_DRIVE, IP_W0, IP_THETA, IP_QUAD, IP_LAST_ANGLE, IP_NTV = 0, 1, 2, 3, 4, 5
FP_DRIVE, FP_DRIVE_RAMP, FP_LOAD, FP_LOAD_RAMP, FP_ANGLE, FP_CLOCK = 0, 1, 2, 3, 4, 5
# the model tuple: (kind, bodies, levers, param, inertia, ipar, fpar, ripple row, fluctuation row, tree, ptr,
# pairs): bodies and signed levers by connector and slot (-1 / 0 padded; gearcli.model.ModelArrays), the rows
# the flat (amplitude, order) / (amplitude, frequency) pairs of gearcli.model.elements.torque, tree the
# connector that gives each body's angle, per body b its (connector, slot) pairs pairs[ptr[b]:ptr[b + 1]]
# in connector order (gearcli.engine.pack), then the motor's row and the load's speed law
# (gearcli.model.elements.machine; empty when there is none), and the angle rows of the bodies the tree does not
# reach (gearcli.model.Layout.angle_rows; (0, 0) for none)

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
def ramp(t, value, ramp_s):
    """``STEP(t, 0, 0, ramp_s, value)`` as the generated code writes it."""
    if ramp_s <= 0.0 or value == 0.0:
        return value
    if t < ramp_s:
        s = t * (1.0 / ramp_s)
        return value * s * s * (3.0 - 2.0 * s)
    return value


@jit
def input_motion(t, v, T, start):
    """(th0, w0, a0) of the speed drive's exact STEP profile from the start angle ``start``."""
    if T <= 0.0:
        th = v * t
    elif t < T:
        s = t * (1.0 / T)
        th = (v * T) * s * s * s * (1.0 - 0.5 * s)
        if start != 0.0:
            th = th + start
        return th, v * s * s * (3.0 - 2.0 * s), (6.0 * v / T) * s * (1.0 - s)
    else:
        th = v * (t - 0.5 * T)
    if start != 0.0:
        th = th + start
    return th, v, 0.0


@jit
def prologue(t, y, model, th):
    """(speed drive, w0, a0, Tin, dTin, load, TL, dTL/dw_N) at (t, y) and the body angles ``th`` the phased
    meshes need, as the generated prologue forms them; dTin is d/dth0 of a rippled drive torque, d/dw0 of a
    motor's."""
    lev, ipar, fpar, rip, flu, tree = model[2], model[5], model[6], model[7], model[8], model[9]
    mrow, lrow = model[12], model[13]
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
        nb = model[4].shape[0]
        g, dg = load_factor(lrow, body_speed(y, nb - 1, 1 if speed else 0, i_w0, w0))
        dtl = tl * dg
        tl = tl * g
    th[0] = th0
    for b in range(1, ipar[IP_LAST_ANGLE] + 1):  # theta_b = (r_a theta_a - delta_c) / r_b along the tree
        c = tree[b]
        if c >= 0:
            th[b] = (lev[c, 0] * th[model[1][c, 0]] - y[c]) * (1.0 / -lev[c, 1])
        elif c == -2:  # a body the kinematics fix through several connectors (Layout.angle_rows), as generated
            th[b] = angle_row(b, model, th, y)
    return speed, w0, a0, tin, dtin, load, tl, dtl


@jit
def angle_row(b, model, th, y):
    """theta_b from its row (Layout.angle_rows): body angles, then deflections, then the constant, summed in
    the generated expression's order."""
    M = model[14]
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
    if b < first:
        return w0
    return y[i_w0 + b - first]


@jit
def deflection_rate(c, y, model, first, i_w0, w0):
    """delta_c' = sum_j s_j r_j w_{bodies[j]}, in slot order."""
    bodies, lev = model[1], model[2]
    dd = lev[c, 0] * body_speed(y, bodies[c, 0], first, i_w0, w0)
    for s in range(1, bodies.shape[1]):
        if bodies[c, s] >= 0:
            dd = dd + lev[c, s] * body_speed(y, bodies[c, s], first, i_w0, w0)
    return dd


@jit
def lossy(kind, P):
    """A mesh that loses (1 - eta) of the power it transmits (a pair's, or a planet's sun or ring mesh)."""
    return (kind == KIND_MESH or kind == KIND_PLANET_MESH) and 0.0 < P[I_ETA] < 1.0


@jit
def side_losses(c, f, y, model, first, i_w0, w0):
    """A lossy mesh's forces on its pinion and gear side and their partials (mesh.loss_factors), from
    v_a = r_a w_a and v_b = r_b w_b (levers (r_a, -r_b)); a planet mesh's from its relative pitch-line speeds
    v_a = l_a w_a + kappa_a l_c w_c, v_b = -(l_b w_b + kappa_b l_c w_c) (mesh.planet_loss_slots)."""
    bodies, lev = model[1], model[2]
    P = model[3][c]
    if P[I_LSB] > 0.0:
        sa, sb, sc, ka = int(P[I_LSA]), int(P[I_LSB]), int(P[I_LSC]), P[I_LKA]
        vb = (-lev[c, sb]) * body_speed(y, bodies[c, sb], first, i_w0, w0)
        va = 0.0
        if sa >= 0:
            va = lev[c, sa] * body_speed(y, bodies[c, sa], first, i_w0, w0)
        if sc >= 0:
            wc = body_speed(y, bodies[c, sc], first, i_w0, w0)
            va = va + (ka * lev[c, sc]) * wc if sa >= 0 else (ka * lev[c, sc]) * wc
            vb = vb + (-(1.0 - ka) * lev[c, sc]) * wc
    else:
        va = lev[c, 0] * body_speed(y, bodies[c, 0], first, i_w0, w0)
        vb = -lev[c, 1] * body_speed(y, bodies[c, 1], first, i_w0, w0)
    fa, fb, aa, ba, ab, bb = mesh_loss_factors(P, f, va, vb)
    return va, vb, fa, fb, aa, ba, ab, bb


@jit
def side_of(c, s, model):
    """Which side force a lossy mesh puts on its slot s: 0 (f_a), 1 (f_b), 2 (a planet mesh's carrier:
    kappa_a f_a + kappa_b f_b), -1 (the law's f)."""
    P = model[3][c]
    if P[I_LSB] > 0.0:
        if s == int(P[I_LSA]):
            return 0
        if s == int(P[I_LSB]):
            return 1
        if s == int(P[I_LSC]):
            return 2
        return -1
    return s if s < 2 else -1


@jit
def body_torque(i, model, fc, y, first, i_w0, w0):
    """The connectors' torque on body i, -s_j r_j F_c summed in connector order (scatter by index, through
    the body's list of (connector, slot) pairs); a lossy mesh puts f_a on its pinion and f_b on its gear (a
    planet mesh: by its slots, the carrier's share of both on the carrier)."""
    lev, ptr, pairs = model[2], model[10], model[11]
    x = 0.0
    for k in range(ptr[i], ptr[i + 1]):
        c = pairs[k, 0]
        s = pairs[k, 1]
        f = fc[c]
        if lossy(model[0][c], model[3][c]):
            side = side_of(c, s, model)
            if side >= 0:
                _, _, fa, fb, _, _, _, _ = side_losses(c, f, y, model, first, i_w0, w0)
                if side == 0:
                    f = fa
                elif side == 1:
                    f = fb
                else:
                    ka = model[3][c][I_LKA]
                    f = ka * fa + (1.0 - ka) * fb
        term = -lev[c, s] * f
        x = x + term if k > ptr[i] else term
    return x


@jit
def rhs(t, y, dy, model, th, fc):
    """dy = f(t, y) of the scene ``model``; ``th`` (n_bodies) and ``fc`` (2 n_conn: forces, then the
    transmission errors' powers) are scratch."""
    kind, bodies, param, inertia, ipar = model[0], model[1], model[3], model[4], model[5]
    nc = kind.shape[0]
    nb = inertia.shape[0]
    i_w0 = ipar[IP_W0]
    i_th = ipar[IP_THETA]
    iq = ipar[IP_QUAD]
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
    for c in range(nc):  # the meshes' losses, after the damping (the generated sum's order)
        if lossy(kind[c], param[c]):
            va, vb, fa, fb, _, _, _, _ = side_losses(c, fc[c], y, model, first, i_w0, w0)
            ql = va * (fa - fc[c]) - vb * (fb - fc[c])
            damp = damp + ql if have_damp else ql
            have_damp = True
    for i in range(first, nb):
        x = body_torque(i, model, fc, y, first, i_w0, w0)
        if i == 0 and not speed:
            x = x + tin
        if i == nb - 1 and load:
            x = x - tl
        dy[i_w0 + i - first] = x * (1.0 / inertia[i])
    if i_th >= 0:
        dy[i_th] = w0
    if speed:
        p_in = (-body_torque(0, model, fc, y, first, i_w0, w0) + inertia[0] * a0) * w0
    else:
        p_in = tin * w0
    for c in range(nc):  # + the transmission errors' work, connector by connector (the generated sum's order)
        if conn_excited(kind[c], param[c]):
            p_in = p_in + fc[nc + c]
    dy[iq] = p_in
    dy[iq + 1] = tl * body_speed(y, nb - 1, first, i_w0, w0) if load else 0.0
    dy[iq + 2] = damp
    if ipar[IP_NTV] > 0:
        dy[iq + 3] = tvp
    if y.size > iq + 3 + (1 if ipar[IP_NTV] > 0 else 0):
        variational_rhs(t, y, dy, model, th)


@jit
def n_model_states(model):
    """The scene's own state count (an augmented state carries the variational equations after it)."""
    ipar = model[5]
    return ipar[IP_QUAD] + 3 + (1 if ipar[IP_NTV] > 0 else 0)


@jit
def n_dynamic(model):
    """The dynamic states (deflections, free speeds) whose variational equations an augmented state carries."""
    ipar = model[5]
    return ipar[IP_THETA] if ipar[IP_THETA] >= 0 else ipar[IP_QUAD]


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


@jit_alloc
def stored_energy(t, y, model):
    """Kinetic energy + elastic energy of the constant-stiffness connectors + work on time-varying
    springs (the energy watch's ``_stored``)."""
    kind, bodies, param, inertia, ipar = model[0], model[1], model[3], model[4], model[5]
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
    if ipar[IP_NTV] > 0:
        total += y[ipar[IP_QUAD] + 3]
    return total


@jit
def _rms(x, scale, tmp):
    """scipy's ``norm(x / scale)``: ``sqrt((x/scale) . (x/scale)) / sqrt(n)``."""
    for i in range(x.size):
        tmp[i] = x[i] / scale[i]
    return math.sqrt(dot_self(tmp)) / x.size ** 0.5


@jit
def select_initial_step(t0, y0, t_bound, f0, rtol, atol, model, th, fc, y1, f1, scale, diff, tmp, exponent):
    """scipy's ``select_initial_step`` (max_step = inf, forward direction; ``exponent`` 1 / (error order + 1))."""
    n = y0.size
    interval = abs(t_bound - t0)
    if interval == 0.0:
        return 0.0
    for i in range(n):
        scale[i] = atol[i] + abs(y0[i]) * rtol[i]
    d0 = _rms(y0, scale, tmp)
    d1 = _rms(f0, scale, tmp)
    if d0 < 1e-5 or d1 < 1e-5:
        h0 = 1e-6
    else:
        h0 = 0.01 * d0 / d1
    h0 = min(h0, interval)
    for i in range(n):
        y1[i] = y0[i] + h0 * f0[i]
    rhs(t0 + h0, y1, f1, model, th, fc)
    for i in range(n):
        diff[i] = f1[i] - f0[i]
    d2 = _rms(diff, scale, tmp) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** exponent
    return min(100 * h0, h1, interval)


@jit
def _stage_sum(K, a, s, h, y, dst, dv):
    """dst = y + (K[:s].T @ a[:s]) * h."""
    gemv_t(K, s, a, dv)
    for i in range(y.size):
        dst[i] = y[i] + dv[i] * h


# ------------------------------------------------------------------------------- after a step
# What every driver does after an accepted step (the explicit Runge-Kutta one and Radau), in the Python solver
# loop's order (gearcli.simulate.solver._segment): count and trace the step, stop on a non-finite state, sample
# (the driver's own interpolant, at the samples :func:`samples_due` names), then :func:`guards`.
@jit
def step_accepted(t, y, steps, trace, t_eval, done):
    """The step count is ``steps`` (this step included): trace it, check the state; (status, samples due up to)."""
    if steps <= trace.size:
        trace[steps - 1] = t
    total = 0.0
    for i in range(y.size):
        total += y[i]
    if not np.isfinite(total):
        return STATUS_NONFINITE, done
    return STATUS_FINISHED, samples_due(t_eval, done, t)


@jit
def samples_due(t_eval, done, t):
    """The index past the last sample at or before ``t``, from ``done`` on."""
    upto = done
    while upto < t_eval.size and t_eval[upto] <= t:
        upto += 1
    return upto


@jit
def priced_work(nfev, njev, nlu, steps, wpar):
    """:func:`gearcli.core.cost.priced_work_s` with the prices in ``wpar``."""
    return nfev * wpar[WP_P_EVAL] + njev * wpar[WP_P_JAC] + nlu * wpar[WP_P_LU] + steps * wpar[WP_P_STEP]


@jit
def guards(t, y, nfev, njev, nlu, steps, finished, max_nfev, watch_every, wpar, model, watched):
    """The evaluation budget, the priced work budget (spent, or a pace projected over its limit: as
    :func:`gearcli.simulate.guards.over_budget`, checked every ``wpar[WP_EVERY]`` steps) and the energy watch
    every ``watch_every`` steps; ``watched`` receives (energy created, energy scale). At each budget check the
    time reached goes to ``wpar[WP_PROGRESS]`` when ``wpar`` has that entry (a progress bar). A raised stop flag
    (``wpar[WP_STOP]``, when present) ends the run at once. Returns a status."""
    if wpar.size > WP_STOP and wpar[WP_STOP] != 0.0:
        return STATUS_INTERRUPTED
    if nfev > max_nfev:
        return STATUS_BUDGET
    if wpar.size >= N_WPAR and steps % np.int64(wpar[WP_EVERY]) == 0:
        if wpar.size > WP_PROGRESS:
            wpar[WP_PROGRESS] = t
        work = priced_work(nfev, njev, nlu, steps, wpar)
        if work > wpar[WP_CAP]:
            return STATUS_BUDGET
        if work > wpar[WP_AFTER]:
            span = wpar[WP_SPAN1] - wpar[WP_SPAN0]
            frac = (t - wpar[WP_SPAN0]) / span if span > 0 else 1.0
            if frac <= 0 or work / frac > wpar[WP_LIMIT] * wpar[WP_CAP]:
                return STATUS_PROJECTED
    if watch_every > 0 and (steps % watch_every == 0 or finished):
        q = ipar_quad(model)
        work = y[q] - y[q + 1]
        watched[0] = (stored_energy(t, y, model) - wpar[WP_E0]) - (work - wpar[WP_W0])
        watched[1] = max(wpar[WP_SCALE], abs(work - wpar[WP_W0]))
        if watched[0] > wpar[WP_MARGIN] * watched[1]:
            return STATUS_ENERGY
    return STATUS_FINISHED


@jit_alloc
def _start(y0, t_eval, wpar):
    """The output array with the samples at or before the run's start filled; (out, samples done)."""
    n = y0.size
    m = t_eval.size
    out = np.full((n, m), np.nan)
    done = 0
    while done < m and t_eval[done] <= wpar[WP_T0]:
        out[:, done] = y0
        done += 1
    for j in range(done, m):
        if t_eval[j] <= wpar[WP_T0]:
            out[:, j] = y0
    return out, done


# ---------------------------------------------------------------------------- explicit Runge-Kutta
@jit
def rk_step(t, y, f, h, K, y_new, f_new, ytmp, dv, model, th, fc, tab):
    """scipy's ``rk_step``: the stages of the tableau ``tab``, then ``f(t + h, y_new)``."""
    C, A, B = tab[1], tab[2], tab[3]
    s_n = B.size
    n = y.size
    for i in range(n):
        K[0, i] = f[i]
    for s in range(1, s_n):
        _stage_sum(K, A[s], s, h, y, ytmp, dv)
        rhs(t + C[s] * h, ytmp, K[s], model, th, fc)
    gemv_t(K, s_n, B, dv)
    for i in range(n):
        y_new[i] = y[i] + h * dv[i]
    rhs(t + h, y_new, f_new, model, th, fc)
    for i in range(n):
        K[s_n, i] = f_new[i]


@jit
def error_norm(K, h, scale, e5, e3, tab):
    """The step's error estimate: DOP853's combined 5th/3rd-order one (``DOP853._estimate_error_norm``), or
    RK45's ``norm(np.dot(K.T, E) * h / scale)``."""
    n = scale.size
    s_n = tab[3].size
    if tab[0][0] == tb.KIND_RK45:
        gemv_t(K, s_n + 1, tab[4], e5)
        for i in range(n):
            e5[i] = e5[i] * h / scale[i]
        return math.sqrt(dot_self(e5)) / n ** 0.5
    gemv_t(K, s_n + 1, tab[4], e5)
    gemv_t(K, s_n + 1, tab[5], e3)
    for i in range(n):
        e5[i] = e5[i] / scale[i]
        e3[i] = e3[i] / scale[i]
    r5 = math.sqrt(dot_self(e5))
    r3 = math.sqrt(dot_self(e3))
    n5 = r5 * r5
    n3 = r3 * r3
    if n5 == 0.0 and n3 == 0.0:
        return 0.0
    denom = n5 + 0.01 * n3
    return abs(h) * n5 / math.sqrt(denom * n)


@jit
def dense_coefficients(t_old, h, y_old, y, f, K, F, ytmp, dv, DK, model, th, fc, tab):
    """The interpolant of the step just taken, into F: DOP853's three extra stages and its 7th-order
    coefficients (INTERPOLATOR_POWER x n), or RK45's Q = K.T P (stored as F[c, i]); the extra evaluations."""
    n = y.size
    s_n = tab[3].size
    Dm = tab[8]
    if tab[0][0] == tb.KIND_RK45:
        for i in range(n):
            for c in range(Dm.shape[1]):
                acc = 0.0
                for j in range(s_n + 1):
                    acc += K[j, i] * Dm[j, c]
                F[c, i] = acc
        return 0
    a_extra, c_extra = tab[6], tab[7]
    for k in range(a_extra.shape[0]):
        s = s_n + 1 + k
        _stage_sum(K, a_extra[k], s, h, y_old, ytmp, dv)
        rhs(t_old + c_extra[k] * h, ytmp, K[s], model, th, fc)
    gemm(Dm, K, DK)
    for i in range(n):
        dy = y[i] - y_old[i]
        f_old = K[0, i]
        F[0, i] = dy
        F[1, i] = h * f_old - dy
        F[2, i] = 2 * dy - h * (f[i] + f_old)
        for r in range(Dm.shape[0]):
            F[3 + r, i] = h * DK[r, i]
    return a_extra.shape[0]


@jit
def dense_eval(t, t_old, h, y_old, F, out, col, tab):
    """The interpolant at one time, into ``out[:, col]`` (``Dop853DenseOutput`` / ``RkDenseOutput``)."""
    x = (t - t_old) / h
    if tab[0][0] == tb.KIND_RK45:
        x2 = x * x
        x3 = x2 * x
        x4 = x3 * x
        for i in range(y_old.size):
            out[i, col] = h * (F[0, i] * x + F[1, i] * x2 + F[2, i] * x3 + F[3, i] * x4) + y_old[i]
        return
    n_interp = F.shape[0]
    for i in range(y_old.size):
        v = 0.0
        for k in range(n_interp):
            v += F[n_interp - 1 - k, i]
            if k % 2 == 0:
                v *= x
            else:
                v *= 1 - x
        out[i, col] = v + y_old[i]


@jit_alloc
def rk_run(model, y0, t_eval, breaks, rtol, atol, max_nfev, watch_every, wpar, trace, tab):
    """The explicit Runge-Kutta driver: scipy's ``RungeKutta`` loop for the tableau ``tab`` (DOP853 or RK45,
    :data:`gearcli.engine.tableau.DOP853_TABLEAU`), step for step.

    Integrate from t0 = ``wpar[4]`` through the segments ending at ``breaks`` (the last is ``t_eval[-1]``),
    sampling at ``t_eval``; ``rtol`` and ``atol`` are per-state vectors. ``watch_every`` 0 switches the
    energy watch off; ``wpar``: see ``WP_*`` (5 entries: no priced work budget). The times of the first
    ``trace.size`` accepted steps are written to ``trace`` (tests; pass an empty array). Returns (samples,
    counters [nfev, steps, status, samples done], floats [t reached, energy created, energy scale], y)."""
    n = y0.size
    s_n = tab[3].size
    n_extra = tab[6].shape[0]
    error_exponent = -1.0 / (tab[0][1] + 1)
    nb = model[4].shape[0]
    nc = model[0].shape[0]
    th = np.zeros(nb)
    fc = np.zeros(2 * nc)
    K = np.zeros((s_n + 1 + n_extra, n))
    n_dense = tab[8].shape[0] + 3 if tab[0][0] == tb.KIND_DOP853 else tab[8].shape[1]
    F = np.zeros((n_dense, n))
    y = y0.copy()
    f = np.empty(n)
    y_new = np.empty(n)
    f_new = np.empty(n)
    ytmp = np.empty(n)
    scale = np.empty(n)
    w1 = np.empty(n)
    w2 = np.empty(n)
    dv = np.empty(n)
    e3 = np.empty(n)
    DK = np.empty((tab[8].shape[0], n))
    watched = np.array([0.0, wpar[WP_SCALE]])
    out, done = _start(y0, t_eval, wpar)
    t = wpar[WP_T0]  # the run's start (a continuation starts later)
    nfev = 0
    steps = 0
    status = STATUS_FINISHED
    for seg in range(breaks.size):
        t_bound = breaks[seg]
        seg_nfev = 0
        rhs(t, y, f, model, th, fc)
        seg_nfev += 1
        h_abs = select_initial_step(t, y, t_bound, f, rtol, atol, model, th, fc, w1, w2, scale, ytmp, dv,
                                    -error_exponent)
        seg_nfev += 1
        while True:
            min_step = 10 * abs(np.nextafter(t, np.inf) - t)
            if h_abs < min_step:
                h_abs = min_step
            accepted_step = False
            rejected = False
            h = 0.0
            t_new = t
            while not accepted_step:
                if h_abs < min_step:
                    break
                h = h_abs
                t_new = t + h
                if t_new - t_bound > 0:
                    t_new = t_bound
                h = t_new - t
                h_abs = abs(h)
                rk_step(t, y, f, h, K, y_new, f_new, ytmp, dv, model, th, fc, tab)
                seg_nfev += s_n
                for i in range(n):
                    a = abs(y[i])
                    b = abs(y_new[i])
                    scale[i] = atol[i] + (a if a > b or a != a else b) * rtol[i]  # np.maximum: NaN wins
                err = error_norm(K, h, scale, dv, e3, tab)
                if err < 1:
                    if err == 0:
                        factor = MAX_FACTOR
                    else:
                        factor = SAFETY * err ** error_exponent
                        if not factor < MAX_FACTOR:
                            factor = MAX_FACTOR
                    if rejected and not factor < 1.0:
                        factor = 1.0
                    h_abs *= factor
                    accepted_step = True
                else:
                    factor = SAFETY * err ** error_exponent
                    h_abs *= factor if factor > MIN_FACTOR else MIN_FACTOR
                    rejected = True
            if not accepted_step:
                status = STATUS_FAILED
                break
            t_old = t
            for i in range(n):
                ytmp[i] = y[i]  # y_old
                y[i] = y_new[i]
                f[i] = f_new[i]
            t = t_new
            finished = t - t_bound >= 0
            steps += 1
            status, upto = step_accepted(t, y, steps, trace, t_eval, done)
            if status != STATUS_FINISHED:
                break
            if upto > done:
                # y_old is kept in w1 for the interpolant: ytmp is the stage scratch
                for i in range(n):
                    w1[i] = ytmp[i]
                seg_nfev += dense_coefficients(t_old, h, w1, y, f, K, F, ytmp, dv, DK, model, th, fc, tab)
                hd = t - t_old
                for j in range(done, upto):
                    dense_eval(t_eval[j], t_old, hd, w1, F, out, j, tab)
                done = upto
            status = guards(t, y, nfev + seg_nfev, 0, 0, steps, finished, max_nfev, watch_every, wpar, model, watched)
            if status != STATUS_FINISHED or finished:
                break
        nfev += seg_nfev
        if status != STATUS_FINISHED:
            break
    counters = np.array([nfev, steps, status, done], dtype=np.int64)
    floats = np.array([t, watched[0], watched[1]])
    return out, counters, floats, y


def dop853(model, y0, t_eval, breaks, rtol, atol, max_nfev, watch_every, wpar, trace):
    """scipy's DOP853, step for step: :func:`rk_run` with DOP853's tableau."""
    return rk_run(model, y0, t_eval, breaks, rtol, atol, max_nfev, watch_every, wpar, trace, DOP853_TABLEAU)


def rk45(model, y0, t_eval, breaks, rtol, atol, max_nfev, watch_every, wpar, trace):
    """scipy's RK45 (Dormand-Prince 5(4), quartic dense output), step for step: :func:`rk_run` with its tableau;
    the samples agree to the last bits (the interpolant is summed in a loop, not by BLAS)."""
    return rk_run(model, y0, t_eval, breaks, rtol, atol, max_nfev, watch_every, wpar, trace, RK45_TABLEAU)


@jit
def ipar_quad(model):
    return model[5][IP_QUAD]


@jit_alloc
def evaluate(model, t, y):
    """One right-hand side evaluation (tests, benchmarks)."""
    dy = np.empty(y.size)
    rhs(t, y, dy, model, np.zeros(model[4].shape[0]), np.zeros(2 * model[0].shape[0]))
    return dy


@jit_alloc
def evaluate_many(model, t, y, times):
    """``times`` evaluations at one point (the benchmark's cost of one compiled evaluation)."""
    dy = np.empty(y.size)
    th = np.zeros(model[4].shape[0])
    fc = np.zeros(2 * model[0].shape[0])
    acc = 0.0
    for _ in range(times):
        rhs(t, y, dy, model, th, fc)
        acc += dy[0]
    return acc


@jit_alloc
def connector_series(kind, P, d, dd, phi, wphi):
    """Force, stored energy and the element's own output channels (its ``CHANNELS``, rows of ``ch``) of one
    connector at every sample (:func:`gearcli.model.outputs.connector_series`, through the same element laws)."""
    n = d.size
    F = np.empty(n)
    U = np.empty(n)
    ch = np.zeros((conn_n_channels(kind), n))
    for j in range(n):
        F[j] = conn_force(kind, P, d[j], dd[j], phi[j], wphi[j])[0]
        U[j] = conn_potential(kind, P, d[j], phi[j])
        for i in range(ch.shape[0]):
            ch[i, j] = conn_channel(kind, P, i, d[j], phi[j])
    return F, U, ch


# ------------------------------------------------------------------------------------ Jacobian
@jit
def _angle_gradient(body, model, ag):
    """ag = d(theta_body)/dy: theta_b = (r_a theta_a - delta_c) / r_b along the tree from theta_0 (a state of
    a torque drive; a function of t alone for a speed drive), through a row body's row (Layout.angle_rows)
    where the path meets one."""
    bodies, lev, tree = model[1], model[2], model[9]
    i_th = model[5][IP_THETA]
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
    bodies, lev, tree, M = model[1], model[2], model[9], model[14]
    i_th = model[5][IP_THETA]
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
    kind, bodies, lev, param = model[0], model[1], model[2], model[3]
    i_w0 = model[5][IP_W0]
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
    kind, bodies, lev, param, inertia, ipar = model[0], model[1], model[2], model[3], model[4], model[5]
    nc = kind.shape[0]
    nb = inertia.shape[0]
    n = y.size
    i_w0 = ipar[IP_W0]
    i_th = ipar[IP_THETA]
    iq = ipar[IP_QUAD]
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
        loses = lossy(kind[c], P)
        va = vb = fa = fb = aa = ba = ab = bb = 0.0
        if loses:
            f = conn_force(kind[c], P, y[c], dd, phi, wphi)[0]
            va, vb, fa, fb, aa, ba, ab, bb = side_losses(c, f, y, model, first, i_w0, w0)
        for s in range(bodies.shape[1]):  # body j takes -s_j r_j F: scattered by index
            b = bodies[c, s]
            side = side_of(c, s, model) if loses else -1  # a lossy mesh's side: A dF/dy + B dv/dy
            if b >= first:
                k = -lev[c, s] / inertia[b]
                for j in range(n):
                    Jm[i_w0 + b - first, j] += k * (_slot_row(c, side, j, g[j], aa, ba, ab, bb, model, first, i_w0)
                                                    if side >= 0 else g[j])
            elif b == 0 and speed:  # the drive's power: its reaction on body 0, times w0
                k = lev[c, s] * w0
                for j in range(n):
                    Jm[iq, j] += k * (_slot_row(c, side, j, g[j], aa, ba, ab, bb, model, first, i_w0)
                                      if side >= 0 else g[j])
        if loses:  # the loss power va (fa - f) - vb (fb - f): lf dF/dy + lv dv/dy + (fa - f) r_a, -(fb - f) r_b
            f = conn_force(kind[c], P, y[c], dd, phi, wphi)[0]
            lf = va * (aa - 1.0) - vb * (ab - 1.0)
            lv = va * ba - vb * bb
            for j in range(n):
                Jm[iq + 2, j] += _loss_row(c, j, g[j], lf, lv, fa - f, fb - f, model, first, i_w0)
        if conn_damped(kind[c], P) or tv or ex:
            qd, qv, qt, qw, ud, uv, ut, uw, ed, ev, et, ew = conn_power_gradient(kind[c], P, y[c], dd, phi, wphi)
            if conn_damped(kind[c], P):
                _gradient(c, qd, qv, qt, qw, model, first, g, ag)
                for j in range(n):
                    Jm[iq + 2, j] += g[j]
            if tv:
                _gradient(c, ud, uv, ut, uw, model, first, g, ag)
                for j in range(n):
                    Jm[iq + 3, j] += g[j]
            if ex:  # the transmission error's power is part of the input work
                _gradient(c, ed, ev, et, ew, model, first, g, ag)
                for j in range(n):
                    Jm[iq, j] += g[j]
    if i_th >= 0:
        Jm[i_th, i_w0] = 1.0
    if ipar[IP_DRIVE] == 2:  # a motor: P_in = T_m(w0) w0, T_m'(w0) on body 0
        Jm[iq, i_w0] += tin + dtin * w0
        Jm[i_w0, i_w0] += (1.0 / inertia[0]) * dtin
    elif not speed:
        Jm[iq, i_w0] += tin
        if dtin != 0.0 and i_th >= 0:  # a rippled drive torque depends on the input angle
            Jm[i_w0, i_th] += dtin * (1.0 / inertia[0])
            Jm[iq, i_th] += dtin * w0
    if load:
        last = i_w0 + nb - 1 - first
        if model[13].size > 0:  # a speed-dependent load
            Jm[iq + 1, last] = tl + dtl * body_speed(y, nb - 1, first, i_w0, w0)
            Jm[last, last] += (-1.0 / inertia[nb - 1]) * dtl
        else:
            Jm[iq + 1, last] = tl
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
    """d v/dy_j of a mesh's mean pitch-line speed v = (r_a w_a + r_b w_b) / 2 (a planet mesh's (v_a + v_b) / 2)
    (0: y_j is no speed of its bodies)."""
    bodies, lev = model[1], model[2]
    P = model[3][c]
    out = 0.0
    hit = False
    if P[I_LSB] > 0.0:
        for s in range(bodies.shape[1]):
            b = bodies[c, s]
            if b >= first and j == i_w0 + b - first:
                r = _planet_va(c, s, model) + _planet_vb(c, s, model)
                out = out + 0.5 * r if hit else 0.5 * r
                hit = True
        return out, hit
    for s in range(2):
        b = bodies[c, s]
        if b >= first and j == i_w0 + b - first:
            r = lev[c, s] if s == 0 else -lev[c, s]
            out = out + 0.5 * r if hit else 0.5 * r
            hit = True
    return out, hit


@jit
def _planet_va(c, s, model):
    """d v_a / d w of a planet mesh's slot s (module text of side_losses)."""
    P, lev = model[3][c], model[2]
    if s == int(P[I_LSA]):
        return lev[c, s]
    if s == int(P[I_LSC]):
        return P[I_LKA] * lev[c, s]
    return 0.0


@jit
def _planet_vb(c, s, model):
    """d v_b / d w of a planet mesh's slot s."""
    P, lev = model[3][c], model[2]
    if s == int(P[I_LSB]):
        return -lev[c, s]
    if s == int(P[I_LSC]):
        return -(1.0 - P[I_LKA]) * lev[c, s]
    return 0.0


@jit
def _side_row(c, s, j, gj, a_coef, b_coef, model, first, i_w0):
    """d(f_side)/dy_j = A dF/dy_j + B dv/dy_j, in the generated expression's order."""
    dv, hit = _speed_column(c, j, model, first, i_w0)
    x = a_coef * gj
    return x + dv * b_coef if hit else x


@jit
def _slot_row(c, side, j, gj, aa, ba, ab, bb, model, first, i_w0):
    """d/dy_j of the side force ``side`` (side_of) of a lossy mesh: f_a's, f_b's, or the carrier's share of both."""
    if side == 0:
        return _side_row(c, 0, j, gj, aa, ba, model, first, i_w0)
    if side == 1:
        return _side_row(c, 1, j, gj, ab, bb, model, first, i_w0)
    ka = model[3][c][I_LKA]
    return ka * _side_row(c, 0, j, gj, aa, ba, model, first, i_w0) + (1.0 - ka) * _side_row(
        c, 1, j, gj, ab, bb, model, first, i_w0)


@jit
def _loss_row(c, j, gj, lf, lv, da, db, model, first, i_w0):
    """d(loss power)/dy_j: lf dF/dy_j + lv dv/dy_j + (f_a - f) dv_a/dy_j - (f_b - f) dv_b/dy_j (a pair:
    (f_a - f) r_a [y_j = w_a] - (f_b - f) r_b [y_j = w_b])."""
    bodies, lev = model[1], model[2]
    dv, hit = _speed_column(c, j, model, first, i_w0)
    x = lf * gj
    if hit:
        x = x + dv * lv
    if model[3][c][I_LSB] > 0.0:
        for s in range(bodies.shape[1]):
            b = bodies[c, s]
            if b >= first and j == i_w0 + b - first:
                x = x + _planet_va(c, s, model) * da - _planet_vb(c, s, model) * db
        return x
    if bodies[c, 0] >= first and j == i_w0 + bodies[c, 0] - first:
        x = x + lev[c, 0] * da
    if bodies[c, 1] >= first and j == i_w0 + bodies[c, 1] - first:
        x = x + lev[c, 1] * db  # -(f_b - f) r_b, lever -r_b
    return x


@jit_alloc
def evaluate_jacobian(model, t, y):
    """One Jacobian evaluation (tests)."""
    n = y.size
    Jm = np.zeros((n, n))
    jacobian(t, y, Jm, model, np.zeros(model[4].shape[0]), np.zeros(n), np.zeros(n))
    return Jm


# ------------------------------------------------------------------------------------- Radau IIA
# scipy/integrate/_ivp/radau.py: the method's constants (Hairer & Wanner, "Solving ODEs II", Sec. IV.8)
S6 = 6 ** 0.5
RC = np.array([(4 - S6) / 10, (4 + S6) / 10, 1])
RE = np.array([-13 - 7 * S6, -13 + 7 * S6, -1]) / 3
MU_REAL = 3 + 3 ** (2 / 3) - 3 ** (1 / 3)
MU_COMPLEX = (3 + 0.5 * (3 ** (1 / 3) - 3 ** (2 / 3)) - 0.5j * (3 ** (5 / 6) + 3 ** (7 / 6)))
RT = np.array([[0.09443876248897524, -0.14125529502095421, 0.03002919410514742],
               [0.25021312296533332, 0.20412935229379994, -0.38294211275726192],
               [1.0, 1.0, 0.0]])
RTI = np.array([[4.17871859155190428, 0.32768282076106237, 0.52337644549944951],
                [-4.17871859155190428, -0.32768282076106237, 0.47662355450055044],
                [0.50287263494578682, -2.57192694985560522, 0.59603920482822492]])
RP = np.array([[13 / 3 + 7 * S6 / 3, -23 / 3 - 22 * S6 / 3, 10 / 3 + 5 * S6],
               [13 / 3 - 7 * S6 / 3, -23 / 3 + 22 * S6 / 3, 10 / 3 - 5 * S6],
               [1 / 3, -8 / 3, 10 / 3]])
NEWTON_MAXITER = 6
EPS = float(np.finfo(float).eps)


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
def _factor(Jm, h, LUr, pr, LUc, pc):
    n = Jm.shape[0]
    mr = MU_REAL / h
    mc = MU_COMPLEX / h
    for i in range(n):
        for j in range(n):
            LUr[i, j] = -Jm[i, j]
            LUc[i, j] = -Jm[i, j]
        LUr[i, i] += mr
        LUc[i, i] += mc
    lu_factor(LUr, pr)
    lu_factor(LUc, pc)


@jit
def collocation(t, y, h, Z0, scale, tol, LUr, pr, LUc, pc, Z, W, F, dW, br, bc, ytmp, model, th, fc):
    """scipy's ``solve_collocation_system``: (converged, iterations, rate, evaluations); Z holds the result."""
    n = y.size
    mr = MU_REAL / h
    mc = MU_COMPLEX / h
    for r in range(3):
        for i in range(n):
            W[r, i] = RTI[r, 0] * Z0[0, i] + RTI[r, 1] * Z0[1, i] + RTI[r, 2] * Z0[2, i]
            Z[r, i] = Z0[r, i]
    dw_old = -1.0
    rate = -1.0
    converged = False
    nfev = 0
    k = 0
    for k in range(NEWTON_MAXITER):
        finite = True
        for r in range(3):
            for i in range(n):
                ytmp[i] = y[i] + Z[r, i]
            rhs(t + h * RC[r], ytmp, F[r], model, th, fc)
            nfev += 1
            for i in range(n):
                if not np.isfinite(F[r, i]):
                    finite = False
        if not finite:
            break
        for i in range(n):
            br[i] = F[0, i] * RTI[0, 0] + F[1, i] * RTI[0, 1] + F[2, i] * RTI[0, 2] - mr * W[0, i]
            fcx = (F[0, i] * (RTI[1, 0] + 1j * RTI[2, 0]) + F[1, i] * (RTI[1, 1] + 1j * RTI[2, 1])
                   + F[2, i] * (RTI[1, 2] + 1j * RTI[2, 2]))
            bc[i] = fcx - mc * (W[1, i] + 1j * W[2, i])
        lu_solve(LUr, pr, br)
        lu_solve(LUc, pc, bc)
        for i in range(n):
            dW[0, i] = br[i]
            dW[1, i] = bc[i].real
            dW[2, i] = bc[i].imag
        dw = _rms_matrix(dW, scale)
        if dw_old >= 0.0:
            rate = dw / dw_old
        if rate >= 0.0 and (rate >= 1 or rate ** (NEWTON_MAXITER - k) / (1 - rate) * dw > tol):
            break
        for r in range(3):
            for i in range(n):
                W[r, i] += dW[r, i]
        for r in range(3):
            for i in range(n):
                Z[r, i] = RT[r, 0] * W[0, i] + RT[r, 1] * W[1, i] + RT[r, 2] * W[2, i]
        if dw == 0 or (rate >= 0.0 and rate / (1 - rate) * dw < tol):
            converged = True
            break
        dw_old = dw
    return converged, k + 1, rate, nfev


@jit
def predict_factor(h_abs, h_abs_old, err, err_old):
    """scipy's ``predict_factor`` (old values < 0 stand for None)."""
    if err_old < 0 or h_abs_old < 0 or err == 0:
        multiplier = 1.0
    else:
        multiplier = h_abs / h_abs_old * (err_old / err) ** 0.25
    m = multiplier if multiplier < 1 else 1.0
    if err == 0:
        return np.inf
    return m * err ** -0.25


@jit_alloc
def radau(model, y0, t_eval, breaks, rtol, atol, max_nfev, watch_every, wpar, trace):
    """Radau IIA (order 5) as scipy's ``Radau`` with the analytic Jacobian: the same Newton iteration, LU
    reuse, error estimate (refined after a rejection), step-size prediction and dense output; segments,
    sampling, guards and returns as :func:`rk_run` (the same after-step helpers; counters add njev and nlu).
    rtol enters the Newton tolerance through its smallest component."""
    n = y0.size
    nb = model[4].shape[0]
    nc = model[0].shape[0]
    th = np.zeros(nb)
    fc = np.zeros(2 * nc)
    y = y0.copy()
    f = np.empty(n)
    f_new = np.empty(n)
    y_new = np.empty(n)
    ytmp = np.empty(n)
    scale = np.empty(n)
    w1 = np.empty(n)
    w2 = np.empty(n)
    w3 = np.empty(n)
    w4 = np.empty(n)
    err_v = np.empty(n)
    ze = np.empty(n)
    Jm = np.zeros((n, n))
    g = np.zeros(n)
    ag = np.zeros(n)
    LUr = np.zeros((n, n))
    LUc = np.zeros((n, n), dtype=np.complex128)
    pr = np.zeros(3 * n, dtype=np.int64)  # pivots and the factors' row spans (lu_factor)
    pc = np.zeros(3 * n, dtype=np.int64)
    Z = np.zeros((3, n))
    Z0 = np.zeros((3, n))
    W = np.zeros((3, n))
    F = np.zeros((3, n))
    dW = np.zeros((3, n))
    br = np.zeros(n)
    bc = np.zeros(n, dtype=np.complex128)
    Q = np.zeros((n, 3))
    y_old = np.empty(n)
    rmin = rtol[0]
    for i in range(n):
        if rtol[i] < rmin:
            rmin = rtol[i]
    newton_tol = max(10 * EPS / rmin, min(0.03, rmin ** 0.5))
    watched = np.array([0.0, wpar[WP_SCALE]])
    out, done = _start(y0, t_eval, wpar)
    t = wpar[WP_T0]  # the run's start (a continuation starts later)
    nfev = 0
    njev = 0
    nlu = 0
    steps = 0
    status = STATUS_FINISHED
    for seg in range(breaks.size):
        t_bound = breaks[seg]
        seg_nfev = 0
        rhs(t, y, f, model, th, fc)
        seg_nfev += 1
        h_self = select_initial_step(t, y, t_bound, f, rtol, atol, model, th, fc, w1, w2, scale, w3, w4, 0.25)
        seg_nfev += 1
        h_abs_old_self = -1.0
        err_old_self = -1.0
        have_sol = False
        sol_t_old = 0.0
        sol_h = 1.0
        jacobian(t, y, Jm, model, th, g, ag)
        njev += 1
        current_jac = True
        lu_ok = False
        while True:
            min_step = 10 * abs(np.nextafter(t, np.inf) - t)
            if h_self < min_step:
                h_abs = min_step
                h_abs_old = -1.0
                err_old = -1.0
            else:
                h_abs = h_self
                h_abs_old = h_abs_old_self
                err_old = err_old_self
            rejected = False
            accepted = False
            failed = False
            h = 0.0
            t_new = t
            n_iter = 0
            rate = -1.0
            err = 0.0
            safety = 0.9
            while not accepted:
                if h_abs < min_step:
                    failed = True
                    break
                h = h_abs
                t_new = t + h
                if t_new - t_bound > 0:
                    t_new = t_bound
                h = t_new - t
                h_abs = abs(h)
                for r in range(3):
                    if have_sol:
                        x = (t + h * RC[r] - sol_t_old) / sol_h
                        for i in range(n):
                            Z0[r, i] = (Q[i, 0] * x + Q[i, 1] * x * x + Q[i, 2] * x * x * x + y_old[i]) - y[i]
                    else:
                        for i in range(n):
                            Z0[r, i] = 0.0
                for i in range(n):
                    scale[i] = atol[i] + abs(y[i]) * rtol[i]
                converged = False
                while not converged:
                    if not lu_ok:
                        _factor(Jm, h, LUr, pr, LUc, pc)
                        nlu += 2
                        lu_ok = True
                    converged, n_iter, rate, ne = collocation(t, y, h, Z0, scale, newton_tol, LUr, pr, LUc, pc, Z, W,
                                                              F, dW, br, bc, ytmp, model, th, fc)
                    seg_nfev += ne
                    if not converged:
                        if current_jac:
                            break
                        jacobian(t, y, Jm, model, th, g, ag)
                        njev += 1
                        current_jac = True
                        lu_ok = False
                if not converged:
                    h_abs *= 0.5
                    lu_ok = False
                    continue
                for i in range(n):
                    y_new[i] = y[i] + Z[2, i]
                    ze[i] = (Z[0, i] * RE[0] + Z[1, i] * RE[1] + Z[2, i] * RE[2]) / h
                    err_v[i] = f[i] + ze[i]
                lu_solve(LUr, pr, err_v)
                for i in range(n):
                    a = abs(y[i])
                    b = abs(y_new[i])
                    scale[i] = atol[i] + (a if a > b or a != a else b) * rtol[i]
                err = _rms(err_v, scale, w1)
                safety = 0.9 * (2 * NEWTON_MAXITER + 1) / (2 * NEWTON_MAXITER + n_iter)
                if rejected and err > 1:
                    for i in range(n):
                        ytmp[i] = y[i] + err_v[i]
                    rhs(t, ytmp, w2, model, th, fc)
                    seg_nfev += 1
                    for i in range(n):
                        err_v[i] = w2[i] + ze[i]
                    lu_solve(LUr, pr, err_v)
                    err = _rms(err_v, scale, w1)
                if err > 1:
                    factor = predict_factor(h_abs, h_abs_old, err, err_old)
                    sf = safety * factor
                    h_abs *= sf if sf > MIN_FACTOR else MIN_FACTOR
                    lu_ok = False
                    rejected = True
                else:
                    accepted = True
            if failed:
                status = STATUS_FAILED
                break
            recompute_jac = n_iter > 2 and rate > 1e-3
            factor = predict_factor(h_abs, h_abs_old, err, err_old)
            factor = safety * factor
            if not factor < MAX_FACTOR:
                factor = MAX_FACTOR
            if not recompute_jac and factor < 1.2:
                factor = 1.0
            else:
                lu_ok = False
            rhs(t_new, y_new, f_new, model, th, fc)
            seg_nfev += 1
            if recompute_jac:
                jacobian(t_new, y_new, Jm, model, th, g, ag)
                njev += 1
                current_jac = True
            else:
                current_jac = False
            h_abs_old_self = h_self
            err_old_self = err
            h_self = h_abs * factor
            for i in range(n):
                y_old[i] = y[i]
                y[i] = y_new[i]
                f[i] = f_new[i]
                for k in range(3):
                    Q[i, k] = Z[0, i] * RP[0, k] + Z[1, i] * RP[1, k] + Z[2, i] * RP[2, k]
            sol_t_old = t
            t = t_new
            sol_h = t - sol_t_old
            have_sol = True
            finished = t - t_bound >= 0
            steps += 1
            status, upto = step_accepted(t, y, steps, trace, t_eval, done)
            if status != STATUS_FINISHED:
                break
            for j in range(done, upto):
                x = (t_eval[j] - sol_t_old) / sol_h
                for i in range(n):
                    out[i, j] = Q[i, 0] * x + Q[i, 1] * x * x + Q[i, 2] * x * x * x + y_old[i]
            done = upto
            status = guards(t, y, nfev + seg_nfev, njev, nlu, steps, finished, max_nfev, watch_every, wpar, model,
                            watched)
            if status != STATUS_FINISHED or finished:
                break
        nfev += seg_nfev
        if status != STATUS_FINISHED:
            break
    counters = np.array([nfev, steps, status, done, njev, nlu], dtype=np.int64)
    floats = np.array([t, watched[0], watched[1]])
    return out, counters, floats, y
