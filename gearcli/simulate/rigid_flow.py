"""The rigid start's lossy meshes where their power flow turns against the load's (docs/physics.md, "Rigid-body
start"): :mod:`gearcli.simulate.rigid_start` counts every lossy mesh's loss on the side the load's sign sets (the
whole start forward for a driving load, backward for an overhauling one), while the simulation's meshes lose on
the side their instantaneous power flow sets, sigma = tanh(f v / W) (:func:`gearcli.model.elements.mesh.loss_factors`).
They part where a mesh's power flow reverses during the start: a soft or star start rolled back by its load (the
load drives the train backwards, so the power flows from the load), an overhauling load whose inertia the motor
still accelerates. There a chain of two-body connectors (the parallel stages, couplings and flexible shafts) is
walked from the load to the input with each lossy element's own loss law at the rigid state: body i turning at
rho_i w needs J_i rho_i dw/dt plus what it passes on, the connector that drives it carries f_b = that / r_b on its
driven side and its law's f (the reported line force) with f_b(f) = f_b, so its driving side f_a(f). The drive
torque then sets dw/dt (``required_torque`` is increasing in it). A layout with planet meshes or further elements
keeps the fixed direction.

The rigid start takes this walk only at states the fixed direction does not describe (``needs_walk``): a lossy
element whose power-flow sign at the fixed direction's forces is not that direction's to ``SATURATED`` (tanh(10):
4e-9); elsewhere both are the same force to that, and the fixed direction's closed form stays (a start from rest
walks its first instants, where the pitch-line speed is within the sign's width: its peaks move by ~1e-11)."""

from __future__ import annotations

import math

import numpy as np

from gearcli.core.memo import remember
from gearcli.core.records import record
from gearcli.model.assembly import Layout

SATURATED = 10.0  # |f v / W| beyond which the power-flow sign is that direction's (1 - tanh(10) = 4e-9)
NEWTON_STEPS = 30


@record
class Plan:
    """What the walk and its test need of a layout, once (:func:`plan`): per connector its pitch-line speed per unit
    input speed (v = (v_a + v_b) / 2 = speed w) and, per lossy one, the fixed direction's force per unit
    acceleration and per unit load torque and the power scale W of its sign; the direction (the load's sign)."""

    lay: Layout
    speed: tuple[float, ...]
    lossy: tuple[tuple[int, float, float, float], ...]  # (connector, force per dw/dt, force per T_L, W)
    forward: bool


def plan(lay: Layout, coefficients: tuple) -> Plan | None:
    """The layout's :class:`Plan` where the walk applies (a chain of two-body connectors, connector c joining bodies
    (c', c' + 1) in order, with a lossy one), else None; kept per layout (its id, the layout held)."""
    found = _PLANS.get(id(lay))
    if found is not None and found[0] is lay:
        return found[1]
    conns = lay.connectors
    ok = any(x.lossy for x in conns) and all(
        x.load_body < 0 and len(x.bodies) == 2 and x.bodies == (c, c + 1) for c, x in enumerate(conns))
    out = None
    if ok:
        rho, J, f = coefficients[0], coefficients[1], coefficients[2]
        ratio = [b.ratio for b in lay.bodies]
        speed, lossy = [], []
        for c, x in enumerate(conns):
            side_a, side_b = x.loss_speeds if x.lossy else ([], [])
            speed.append(0.5 * (sum(k * ratio[j] for j, k in side_a) + sum(k * ratio[j] for j, k in side_b)))
            if x.lossy:
                b = x.b
                per_accel = float(f[c]) * (float(J[b:] @ rho[b:] ** 2) / float(rho[b])) / x.rb
                per_load = float(f[c]) * (float(rho[-1]) / float(rho[b])) / x.rb
                lossy.append((c, per_accel, per_load, float(x.params[x.element.I_LW])))
        out = Plan(lay, tuple(speed), tuple(lossy), lay.load.torque_Nm >= 0)
    remember(_PLANS, id(lay), (lay, out), cap=4)
    return out


_PLANS: dict[int, tuple[Layout, Plan | None]] = {}


def needs_walk(p: Plan, w: float, a: float, load_Nm: float) -> bool:
    """Whether a lossy connector's power-flow sign at the fixed direction's force is not that direction's to
    ``SATURATED`` (module text); the same operations as :func:`needs_walk_mask`, so the same verdict."""
    for c, per_accel, per_load, width in p.lossy:
        arg = (per_accel * a + per_load * load_Nm) * (p.speed[c] * w) / width
        if (arg if p.forward else -arg) < SATURATED:
            return True
    return False


def needs_walk_mask(p: Plan, w: np.ndarray, a: np.ndarray, load_Nm: np.ndarray) -> np.ndarray:
    """:func:`needs_walk` at every state of the arrays."""
    out = np.zeros(w.shape, bool)
    for c, per_accel, per_load, width in p.lossy:
        arg = (per_accel * a + per_load * load_Nm) * (p.speed[c] * w) / width
        out |= (arg if p.forward else -arg) < SATURATED
    return out


def _law_force(p: Plan, c: int, fb: float, w: float) -> tuple[float, float]:
    """(f, f_a) of lossy connector c whose driven side must carry ``fb``: f_b(f) = fb by Newton's method from the
    saturated guess (f_b is increasing in f: df_b/df >= eta - (1 - eta)/2 > 0 for eta > 1/3)."""
    x = p.lay.connectors[c]
    v = p.speed[c] * w
    law = x.element.loss_factors
    f = fb / x.efficiency if fb * w >= 0.0 else fb
    for _ in range(NEWTON_STEPS):
        _, f_b, _, _, dfb, _ = law(x.params, f, v, v)
        step = (f_b - fb) / dfb
        f -= step
        if abs(step) <= 1e-15 * max(abs(f), 1e-300):
            break
    return f, law(x.params, f, v, v)[0]


def walk(p: Plan, w: float, a: float, load_Nm: float) -> tuple[float, list[float]]:
    """(the torque the input body needs, every connector's law force) at the rigid state w, dw/dt = a with the
    load torque ``load_Nm`` on the last body (module text)."""
    bodies, conns = p.lay.bodies, p.lay.connectors
    need = bodies[-1].inertia * bodies[-1].ratio * a + load_Nm
    forces = [0.0] * len(conns)
    for c in range(len(conns) - 1, -1, -1):
        x = conns[c]
        fb = need / x.rb
        f, fa = _law_force(p, c, fb, w) if x.lossy else (fb, fb)
        forces[c] = f
        need = bodies[x.a].inertia * bodies[x.a].ratio * a + x.ra * fa
    return need, forces


def acceleration(p: Plan, w: float, drive_Nm: float, load_Nm: float, guess: float) -> float:
    """dw/dt where the drive torque meets the torque the walked train needs (increasing in dw/dt), bracketed from
    ``guess`` (the fixed direction's) outwards."""
    from scipy.optimize import brentq  # lazy: scipy, start-up time

    def gap(a: float) -> float:
        return walk(p, w, a, load_Nm)[0] - drive_Nm

    g0 = gap(guess)
    if g0 == 0.0:
        return guess
    step = max(abs(guess), 1.0) * 0.05
    lo = hi = guess
    for _ in range(200):
        if g0 > 0.0:
            lo = hi - step
            if gap(lo) <= 0.0:
                break
            hi = lo
        else:
            hi = lo + step
            if gap(hi) >= 0.0:
                break
            lo = hi
        step *= 2.0
    else:
        return guess
    return float(brentq(gap, lo, hi, xtol=1e-12 * max(abs(guess), 1.0), rtol=4 * math.ulp(1.0)))
