"""Straight-line Python source for the right-hand side and the Jacobian of one scene's assembly.

Why generate code: the model has a handful of states, where numpy's per-call overhead on tiny arrays
costs more than the arithmetic, and every term a scene does not need (a free input body, a load, a
time-varying stiffness) is time spent on every one of the ~10^4 evaluations of a run. The generator
writes the ASSEMBLY only — topology and constants inlined as literals, ``y.tolist()`` unpacking the state
in one call — and calls each connector's element force law (:mod:`gearcli.model.elements`) for its force;
no formula of an element is spelt here. ``gearcli simulate --dump-model`` prints that source. What is
compiled is its structure: the float literals become names bound as closure constants (the same values,
so the same results), so the points of a sweep that differ only in numbers share one compilation per
process (:func:`compile_function`; ``jac`` only for a method that takes it). The compiled module is registered with :mod:`linecache` under a
file name of its own, so tracebacks and debuggers show its lines.

Notation (SI): ``d{c}``/``dd{c}`` deflection of connector c and its rate, ``w{b}``/``a{b}``/``th{b}``
speed, acceleration, angle of body b, ``f{c}`` the connector's force (N along a mesh's line of action,
N m for a spring), ``q{c}``/``u{c}`` its damping power and the power into a time-varying spring, ``TL``
the load torque, ``Tin`` the drive torque of a torque drive (``dTin`` its d/d th0 with a ripple);
``kd``/``kv``/``kt``/``kw`` the force's partials by deflection, rate, mesh phase and phase rate,
``te{c}`` the power of a transmission error on the bodies, ``qd``... ``ew`` the partials of the three powers.
"""

from __future__ import annotations

import hashlib
import linecache
import math
import re
from collections.abc import Callable
from functools import lru_cache

import numpy as np

from gearcli.model import elements
from gearcli.model.assembly import Layout
from gearcli.model.elements import energy, machine, profile, torque
from gearcli.model.layout import QUADRATURES
from gearcli.model.parts import Connector


def lit(x: float) -> str:
    """A float literal that round-trips exactly."""
    return repr(float(x))


def _ramp_lines(name: str, value: float, ramp_s: float, indent: str = "    ") -> list[str]:
    """``name = STEP(t, 0, 0, ramp_s, value)`` (:func:`gearcli.model.elements.profile.ramp`, the kernel's too), or
    the constant when there is no ramp."""
    if ramp_s <= 0.0 or value == 0.0:
        return [f"{indent}{name} = {lit(value)}"]
    return [f"{indent}{name} = _ramp(t, {lit(value)}, {lit(ramp_s)})"]


def _input_motion_lines(lay: Layout) -> list[str]:
    """Speed drive: th0 (if needed), w0, a0 of the exact STEP speed profile of body 0 from the drive's start angle
    (:func:`gearcli.model.elements.profile.input_motion`, the kernel's too)."""
    v, T = lay.drive.speed_rad_s, lay.drive.ramp_s
    angle = "th0" if lay.needs_angles else "_"
    return [f"    {angle}, w0, a0 = _motion(t, {lit(v)}, {lit(T)}, {lit(lay.drive.angle_rad)})"]


def _prologue(lay: Layout) -> list[str]:
    # the state and the time as Python floats: scipy's stages pass t as a numpy scalar, and everything computed from
    # it (the drive's motion, the deflection rates, every law they feed) ran on numpy scalars, a few times slower
    # than on floats (the same IEEE operations, so the same doubles)
    lines = [f"    {', '.join(lay.state.names)}, = y.tolist()", "    t = float(t)"]
    if lay.speed_drive:
        lines += _input_motion_lines(lay)
    elif lay.motor_drive:  # the motor's torque at its speed (gearcli.model.elements.machine), dTw = dTin/dw0
        lines.append("    Tin, dTw = _motor(_MOT, t, w0)")
    else:
        lines += _ramp_lines("Tin", lay.drive.torque_Nm, lay.drive.ramp_s)
        if lay.ripple:  # T_in x (1 + sum a cos(n th0)) (gearcli.model.elements.torque)
            lines += ["    rip, drip = _ripple(_RIP, th0)", "    dTin = Tin * drip", "    Tin = Tin * rip"]
    if lay.load.torque_Nm != 0.0:
        lines += _ramp_lines("TL", lay.load.torque_Nm, lay.load.ramp_s)
        if lay.fluctuation:
            clock = f"t + {lit(lay.load.clock_s)}" if lay.load.clock_s != 0.0 else "t"
            lines.append(f"    TL = TL * _fluct(_FLU, {clock})")
        if lay.load_law:  # T_L g(w_N): dTL = dT_L/dw_N
            lines += [f"    gL, dgL = _load(_LOD, w{lay.n_bodies - 1})", "    dTL = TL * dgL", "    TL = TL * gL"]
    tree, rows = lay.tree, lay.angle_rows
    for b in range(1, lay.last_angle_body + 1):  # theta_b = (r_a theta_a - delta_c) / r_b along the tree
        c = tree[b]
        if c >= 0:
            x = lay.connectors[c]
            lines.append(f"    th{b} = ({lit(x.ra)} * th{x.a} - d{c}) * {lit(1.0 / x.rb)}")
        elif b in rows:  # a body the kinematics fix through several connectors (Layout.angle_rows)
            row = rows[b]
            terms = [f"{lit(k)} * th{j}" for j, k in row.bodies] + [f"{lit(k)} * d{c}" for c, k in row.deflections]
            lines.append(f"    th{b} = {' + '.join(terms)} + {lit(row.constant)}")
    return lines


def _scaled(r: float, name: str) -> str:
    return name if r == 1.0 else f"{lit(r)} * {name}"


def _phase(x: Connector) -> str:
    """The mesh phase phi = z_p theta_p / 2 pi (cycles) of a phase-dependent mesh; 0.0 otherwise."""
    if not x.phased:
        return "0.0"
    return f"{lit(x.element.phase_per_rad(x.params))} * th{x.a}"


def _phase_rate(x: Connector) -> str:
    """phi' = z_p w_p / 2 pi of a mesh with a transmission error; 0.0 otherwise."""
    if not x.excited:
        return "0.0"
    return f"{lit(x.element.phase_per_rad(x.params))} * w{x.a}"


def _force_only(x: Connector) -> bool:
    """The rhs calls the element's force-only hook (:data:`gearcli.model.elements.RHS_HOOK`) for the connector: it
    has one and its row depends on no phase (so neither its time-varying spring's power nor a transmission error's,
    the two other numbers the rhs may read, exists)."""
    return not x.phased and hasattr(x.element, elements.RHS_HOOK)


def _connector_lines(lay: Layout, c: int, jacobian: bool) -> list[str]:
    x = lay.connectors[c]
    args = f"(_P{c}, d{c}, dd{c}, {_phase(x)}, {_phase_rate(x)})"
    rate = ""
    for j, (body, r, s) in enumerate(zip(x.bodies, x.radii, x.element.SIGNS, strict=True)):
        sign = ("-" if s < 0 else "") if j == 0 else (" - " if s < 0 else " + ")
        rate += sign + _scaled(r, f"w{body}")  # delta' = sum_j s_j r_j w_j
    out = [f"    dd{c} = {rate}"]
    if not jacobian and _force_only(x):  # the force and the damping power: all the rhs reads of the row
        return out + [f"    f{c}, q{c} = _rhs{c}(_P{c}, d{c}, dd{c})  # {x.label}"] + _loss_lines(lay, c)
    if not jacobian:
        return out + [f"    f{c}, _, _, _, _, q{c}, u{c}, te{c} = _force{c}{args}  # {x.label}"] + _loss_lines(lay, c)
    out.append(f"    f{c}, kd{c}, kv{c}, kt{c}, kw{c}, q{c}, u{c}, te{c} = _force{c}{args}  # {x.label}")
    out += _loss_lines(lay, c, jacobian=True)
    if x.damped or x.time_varying or x.excited:
        out.append(f"    qd{c}, qv{c}, qt{c}, qw{c}, ud{c}, uv{c}, ut{c}, uw{c}, ed{c}, ev{c}, et{c}, ew{c} = "
                   f"_power{c}{args}")
    return out


def _loss_lines(lay: Layout, c: int, jacobian: bool = False) -> list[str]:
    """A lossy element (its loss hook, :data:`gearcli.model.elements.LOSS_HOOK`): the forces on its two sides
    (fa, fb) and the loss power ql (the hook's ``loss_factors``, called as ``_loss{c}``); with the Jacobian,
    their partials by f and v, and the loss power's (lf by f, lv by v). A slot that takes a share of both sides
    (a planet mesh's carrier) its side force fc."""
    x = lay.connectors[c]
    if not x.lossy:
        return []
    va, vb = (" + ".join(_scaled(k, f"w{b}") for b, k in terms) or "0.0" for terms in x.loss_speeds)
    out = [f"    va{c} = {va}", f"    vb{c} = {vb}"]
    parts = f"Aa{c}, Ba{c}, Ab{c}, Bb{c}" if jacobian else "_, _, _, _"
    out.append(f"    fa{c}, fb{c}, {parts} = _loss{c}(_P{c}, f{c}, va{c}, vb{c})")
    out.append(f"    ql{c} = va{c} * (fa{c} - f{c}) - vb{c} * (fb{c} - f{c})")
    mixed = _mixed_share(x)
    if mixed is not None:
        out.append(f"    fc{c} = {lit(mixed[0])} * fa{c} + {lit(mixed[1])} * fb{c}")
    if jacobian:
        out += [f"    lf{c} = va{c} * (Aa{c} - 1.0) - vb{c} * (Ab{c} - 1.0)",
                f"    lv{c} = va{c} * Ba{c} - vb{c} * Bb{c}"]
    return out


def _mixed_share(x: Connector) -> tuple[float, float] | None:
    """The shares (of f_a, of f_b) of the one slot of a lossy element that takes a share of both sides (a planet
    mesh's carrier: its side force fc); None where no slot does."""
    shares = [x.loss_share(j) for j in range(len(x.bodies))]
    mixed = [s for s in shares if s[0] != 0.0 and s[1] != 0.0]
    assert len(mixed) <= 1, "a loss hook gives at most one slot a share of both sides"
    return mixed[0] if mixed else None


def _side_name(x: Connector, j: int) -> str:
    """Which force connector x puts on its slot j: "a" (f_a), "b" (f_b), "c" (a share of both) or "" (the law's f)."""
    share_a, share_b = x.loss_share(j)
    if share_a == 0.0 and share_b == 0.0:
        return ""
    return "c" if share_a != 0.0 and share_b != 0.0 else "a" if share_b == 0.0 else "b"


def _side(lay: Layout, c: int, j: int) -> str:
    """The force connector c puts on its body j: f, or a lossy element's side force by its slot (f_a, f_b, or
    the share of both f_c, :func:`_side_name`)."""
    return f"f{_side_name(lay.connectors[c], j)}{c}"


def _side_grad(lay: Layout, grads, grads_side, c: int, j: int) -> dict[int, str]:
    """d/dy of the force connector c puts on its body j (:func:`_side`)."""
    x = lay.connectors[c]
    side = _side_name(x, j)
    if side == "c":
        share_a, share_b = x.loss_share(j)
        out: dict[int, list[str]] = {}
        _add(out, grads_side[c][0], lit(share_a))
        _add(out, grads_side[c][1], lit(share_b))
        return {col: " + ".join(v) for col, v in out.items()}
    return grads_side[c]["ab".index(side)] if side else grads[c]


def _body_torque(lay: Layout, i: int) -> str:
    """Net torque on body i from its connectors (-s_j r_j F each, scattered by index), the drive and the load."""
    terms = []
    for c, j in lay.acting_on(i):
        x = lay.connectors[c]
        terms.append(f"{'+' if x.element.SIGNS[j] < 0 else '-'} {lit(x.radii[j])} * {_side(lay, c, j)}")
    if i == 0 and not lay.speed_drive:
        terms.append("+ Tin")
    if i == lay.n_bodies - 1 and lay.load.torque_Nm != 0.0:
        terms.append("- TL")
    text = " ".join(terms).lstrip("+ ")
    return text if not text.startswith("- ") else "-" + text[2:]


def _quadrature_exprs(lay: Layout) -> list[str]:
    """Input power, load power, damping power, power into time-varying springs (the drive's and the load's through
    :mod:`gearcli.model.elements.energy`, the kernel's too)."""
    if lay.speed_drive:
        reaction = " + ".join(f"{lit(lay.connectors[c].levers[j])} * {_side(lay, c, j)}" for c, j in lay.acting_on(0))
        p_in = f"_drive_power({reaction}, {lit(lay.inertias[0])}, a0, w0)"
    else:
        p_in = "_torque_power(Tin, w0)"
    p_in += "".join(f" + te{c}" for c, x in enumerate(lay.connectors) if x.excited)  # the TE's work
    p_load = f"_torque_power(TL, w{lay.n_bodies - 1})" if lay.load.torque_Nm != 0.0 else "0.0"
    damped = [f"q{c}" for c, x in enumerate(lay.connectors) if x.damped]
    damped += [f"ql{c}" for c, x in enumerate(lay.connectors) if x.lossy]  # mesh losses count as dissipation
    out = [p_in, p_load, " + ".join(damped) if damped else "0.0"]
    if lay.n_tv:
        out.append(" + ".join(f"u{c}" for c, x in enumerate(lay.connectors) if x.time_varying))
    return out


def rhs_source(lay: Layout) -> str:
    lines = ["def rhs(t, y):"] + _prologue(lay)
    for c in range(lay.n_conn):
        lines += _connector_lines(lay, c, jacobian=False)
    st = lay.state
    out = [""] * st.n_states
    for c in range(lay.n_conn):
        out[st.delta(c)] = f"dd{c}"
    for i in lay.free_bodies:
        out[_omega(lay, i)] = f"({_body_torque(lay, i)}) * {lit(1.0 / lay.inertias[i])}"
    if st.i_theta is not None:
        out[st.i_theta] = "w0"
    for name, expr in zip(QUADRATURES, _quadrature_exprs(lay), strict=False):
        out[_quad(lay, name)] = expr
    lines.append("    return _array([" + ", ".join(out) + "])")
    return "\n".join(lines) + "\n"


# ------------------------------------------------------------------------------------------ Jacobian
def _gradient(lay: Layout, c: int, name: str) -> dict[int, str]:
    """Column -> d(name_c)/dy of a connector quantity whose partials the generated code holds as
    ``{name}d{c}`` (deflection), ``{name}v{c}`` (deflection rate), ``{name}t{c}`` (mesh phase) and
    ``{name}w{c}`` (phase rate): the force (name "k") or a power (q: damping, u: time-varying spring,
    e: transmission error). Speeds enter through the deflection rate and the phase rate z_p w_p of a
    mesh with a transmission error, body angles through the mesh phase z_p theta_p."""
    x = lay.connectors[c]
    g = {lay.state.delta(c): f"{name}d{c}"}
    for body, r in zip(x.bodies, x.levers, strict=True):
        col = lay.state.omega(body)
        if col is not None:
            g[col] = f"{lit(r)} * {name}v{c}"
    per_rad = x.element.phase_per_rad(x.params)
    if x.phased:
        for col, coef in lay.angle_gradient(x.a).items():
            g[col] = (g[col] + " + " if col in g else "") + f"{lit(coef * per_rad)} * {name}t{c}"
    col = lay.state.omega(x.a)
    if x.excited and col is not None:
        g[col] = g[col] + f" + {lit(per_rad)} * {name}w{c}"
    return g


def _add(row: dict[int, list[str]], grad: dict[int, str], coef: str) -> None:
    for col, expr in grad.items():
        row.setdefault(col, []).append(f"{coef} * ({expr})")


def _omega(lay: Layout, body: int) -> int:
    col = lay.state.omega(body)
    assert col is not None, "a prescribed body has no speed state"
    return col


def _quad(lay: Layout, name: str) -> int:
    i = lay.state.quadrature(name)
    assert i is not None, f"this scene has no {name} quadrature"
    return i


def _speed_gradient(lay: Layout, c: int) -> dict[int, float]:
    """d v/dy of a mesh's mean pitch-line speed v = (r_a w_a + r_b w_b) / 2 (a planet mesh's: (v_a + v_b) / 2)."""
    terms = [t for ts in lay.connectors[c].loss_speeds for t in ts]
    g: dict[int, float] = {}
    for body, r in terms:
        col = lay.state.omega(body)
        if col is not None:
            g[col] = g.get(col, 0.0) + 0.5 * r
    return g


def _side_gradient(lay: Layout, c: int, grad: dict[int, str], side: str) -> dict[int, str]:
    """d(f_side)/dy of a lossy mesh: A d f/dy + B dv/dy (``grad`` is df/dy); the force's own otherwise."""
    if not lay.connectors[c].lossy:
        return grad
    out = {col: f"A{side}{c} * ({expr})" for col, expr in grad.items()}
    for col, coef in _speed_gradient(lay, c).items():
        out[col] = (out[col] + " + " if col in out else "") + f"{lit(coef)} * B{side}{c}"
    return out


def _loss_gradient(lay: Layout, c: int, grad: dict[int, str]) -> dict[int, str]:
    """d(ql)/dy of a lossy mesh: lf df/dy + lv dv/dy + (fa - f) r_a at w_a - (fb - f) r_b at w_b."""
    x = lay.connectors[c]
    out = {col: f"lf{c} * ({expr})" for col, expr in grad.items()}
    terms = {col: [f"{lit(coef)} * lv{c}"] for col, coef in _speed_gradient(lay, c).items()}
    va, vb = x.loss_speeds  # (fa - f) dva/dy - (fb - f) dvb/dy
    sides = [(body, k, "a", "") for body, k in va] + [(body, k, "b", "-") for body, k in vb]
    for body, r, side, sign in sides:
        col = lay.state.omega(body)
        if col is not None:
            terms.setdefault(col, []).append(f"{sign}{lit(r)} * (f{side}{c} - f{c})")
    for col, ts in terms.items():
        out[col] = " + ".join(([out[col]] if col in out else []) + ts)
    return out


def _jac_rows(lay: Layout) -> dict[int, dict[int, list[str]]]:
    rows: dict[int, dict[int, list[str]]] = {}
    grads = [_gradient(lay, c, "k") for c in range(lay.n_conn)]
    grads_side = [[_side_gradient(lay, c, g, side) for side in ("a", "b")] for c, g in enumerate(grads)]
    for c, x in enumerate(lay.connectors):  # d(delta_c)/dt = sum_j s_j r_j w_j
        row = rows.setdefault(lay.state.delta(c), {})
        for body, r in zip(x.bodies, x.levers, strict=True):
            col = lay.state.omega(body)
            if col is not None:
                row[col] = [lit(r)]
    for i in lay.free_bodies:  # J_i w_i' = sum over its connectors of -s_j r_j f_c (+ Tin - TL)
        row = rows.setdefault(_omega(lay, i), {})
        for c, j in lay.acting_on(i):
            _add(row, _side_grad(lay, grads, grads_side, c, j), lit(-lay.connectors[c].levers[j] / lay.inertias[i]))
    if lay.state.i_theta is not None:
        rows[lay.state.i_theta] = {_omega(lay, 0): ["1.0"]}
    q0, q_load, q_damp = (_quad(lay, n) for n in ("input_work_J", "load_work_J", "damping_loss_J"))
    if lay.speed_drive:  # P_in = (sum s_j r_j f_c over body 0's connectors + J0 a0) w0, w0 prescribed
        for c, j in lay.acting_on(0):
            _add(rows.setdefault(q0, {}), _side_grad(lay, grads, grads_side, c, j),
                 f"{lit(lay.connectors[c].levers[j])} * w0")
    elif lay.motor_drive:  # P_in = T_m(w0) w0
        rows.setdefault(q0, {})[_omega(lay, 0)] = ["Tin + dTw * w0"]
        rows[_omega(lay, 0)].setdefault(_omega(lay, 0), []).append(f"{lit(1.0 / lay.inertias[0])} * dTw")
    else:
        rows.setdefault(q0, {})[_omega(lay, 0)] = ["Tin"]
    if lay.ripple and lay.state.i_theta is not None:  # T_in depends on th0
        rows[_omega(lay, 0)].setdefault(lay.state.i_theta, []).append(f"{lit(1.0 / lay.inertias[0])} * dTin")
        rows[q0].setdefault(lay.state.i_theta, []).append("dTin * w0")
    for c, x in enumerate(lay.connectors):
        if x.excited:  # + the transmission error's power
            _add(rows.setdefault(q0, {}), _gradient(lay, c, "e"), "1.0")
    if lay.load.torque_Nm != 0.0:
        last = _omega(lay, lay.n_bodies - 1)
        rows.setdefault(q_load, {})[last] = ["TL + dTL * w" + str(lay.n_bodies - 1)] if lay.load_law else ["TL"]
        if lay.load_law:
            rows[last].setdefault(last, []).append(f"{lit(-1.0 / lay.inertias[-1])} * dTL")
    for c, x in enumerate(lay.connectors):
        if x.damped:
            _add(rows.setdefault(q_damp, {}), _gradient(lay, c, "q"), "1.0")
        if x.lossy:
            _add(rows.setdefault(q_damp, {}), _loss_gradient(lay, c, grads[c]), "1.0")
        if x.time_varying:
            _add(rows.setdefault(_quad(lay, "elastic_work_tv_J"), {}), _gradient(lay, c, "u"), "1.0")
    return rows


def jac_source(lay: Layout) -> str:
    lines = ["def jac(t, y):"] + _prologue(lay)
    for c in range(lay.n_conn):
        lines += _connector_lines(lay, c, jacobian=True)
    lines.append(f"    J = _zeros(({lay.state.n_states}, {lay.state.n_states}))")
    rows = _jac_rows(lay)
    for r in sorted(rows):
        for col in sorted(rows[r]):
            lines.append(f"    J[{r}, {col}] = " + " + ".join(rows[r][col]))
    lines.append("    return J")
    return "\n".join(lines) + "\n"


def _header(lay: Layout) -> str:
    bodies = ", ".join(f"{i}: {b.label} (J = {b.inertia:.6g} kg m^2)" for i, b in enumerate(lay.bodies))
    conns = ", ".join(f"{c}: {x.label} ({'-'.join(map(str, x.bodies))})" for c, x in enumerate(lay.connectors))
    return (f"# generated by gearcli.model.codegen\n# bodies: {bodies}\n# connectors: {conns}\n"
            f"# state: {', '.join(lay.state.names)}\n\n")


def source_of(lay: Layout) -> str:
    """The scene's generated module source: a comment header, ``rhs`` and ``jac``."""
    return _header(lay) + rhs_source(lay) + "\n\n" + jac_source(lay)


#: a number (the forms ``lit`` and the generator write: ``12``, ``0.5``, ``1e-06``, ``2.5e+20``), after what a number
#: cannot begin inside: a name (``d0``, ``_k1``), a comment. One scan finds the literals Python's tokenizer finds in
#: the generated source, without the tokenizer's token objects and its full pattern (compiled on first use, as ``re``
#: caches this one).
_LITERALS = r"[A-Za-z_]\w*|#[^\n]*|(?P<number>(?:[0-9]+\.[0-9]*|\.[0-9]+|[0-9]+)(?:[eE][-+]?[0-9]+)?)"


def _template(source: str) -> tuple[str, tuple[float, ...]]:
    """The source with every float literal replaced by a name ``_k{i}`` (what stays is the model's
    structure), and the literals' values in order. Integers (array shapes and indices) stay: they are
    structure. A name is an atom like a literal, so every expression keeps its meaning and its value."""
    values: list[float] = []
    parts: list[str] = []
    end = 0
    for m in re.finditer(_LITERALS, source):
        text = m.group("number")
        if text is None or text.isdigit():
            continue
        parts += [source[end:m.start()], f"_k{len(values)}"]
        values.append(float(text))
        end = m.end()
    return "".join(parts) + source[end:], tuple(values)


@lru_cache(maxsize=64)
def _compiled(template: str, n_constants: int, name: str):
    """The code of a module defining ``_make(_k0, ..., _kN)`` that returns the function ``name`` (``rhs`` or
    ``jac``) of a model structure as a closure over its constants: compiled once per structure, function and
    process (a sweep's points differ only in the constants)."""
    params = ", ".join(f"_k{i}" for i in range(n_constants))
    body = "".join("    " + line if line.strip() else line for line in template.splitlines(True))
    module = f"def _make({params}):\n{body}\n    return {name}\n"
    digest = hashlib.sha1(module.encode()).hexdigest()[:12]
    filename = f"gearcli/model/_generated_{digest}.py"
    linecache.cache[filename] = (len(module), None, module.splitlines(True), filename)
    return compile(module, filename, "exec")


#: what the generated functions are written for, by the name they call it
GENERATED = {"rhs": rhs_source, "jac": jac_source}


def compile_function(lay: Layout, name: str) -> Callable:
    """The scene's generated ``rhs(t, y)`` or ``jac(t, y)`` (``name``), each made on first use: a method without
    a Jacobian (DOP853, RK45) never generates nor compiles ``jac``.

    Its source is the scene's own, with its constants as literals (:func:`source_of`, ``--dump-model``). What runs
    is its structure (:func:`_template`), compiled once per process (:func:`_compiled`) and bound to this scene's
    constants and element parameters; the compiled module is registered with linecache, so a traceback
    through the generated code shows its lines."""
    namespace: dict = {"_drive_power": energy.speed_drive_power, "_torque_power": energy.torque_power,
                       "_ramp": profile.ramp, "_motion": profile.input_motion, "_array": np.array, "_zeros": np.zeros, "_sqrt": math.sqrt, "_ripple": torque.ripple,
                       "_fluct": torque.fluctuation, "_RIP": lay.ripple, "_FLU": lay.fluctuation,
                       "_motor": machine.motor_torque, "_MOT": lay.motor_row, "_load": machine.load_factor,
                       "_LOD": lay.load_law}
    for c, x in enumerate(lay.connectors):
        namespace[f"_P{c}"] = x.params
        if x.lossy:  # the element's loss hook
            namespace[f"_loss{c}"] = x.element.loss_factors
        namespace[f"_force{c}"] = x.element.force if x.excited else getattr(x.element, "law", x.element.force)
        if _force_only(x):
            namespace[f"_rhs{c}"] = getattr(x.element, elements.RHS_HOOK)
        namespace[f"_power{c}"] = x.element.power_gradient
    template, constants = _template(_header(lay) + GENERATED[name](lay))
    exec(_compiled(template, len(constants), name), namespace)  # noqa: S102 - our own generated source
    return namespace["_make"](*constants)
