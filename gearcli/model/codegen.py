"""Straight-line Python source for the right-hand side and the Jacobian of one scene.

Why generate code: the model has a handful of states, where numpy's per-call overhead on tiny
arrays costs more than the arithmetic, and every branch a scene does not need (backlash, damping,
time-varying stiffness, a free input shaft) is time spent on every one of the ~10^4 evaluations of a
run. The generator writes scalar float code with every constant inlined as a literal and only the
terms the scene uses (docs/physics.md, "Torsional model": "scenes leave out what they do not use"); ``y.tolist()``
unpacks the state in one call. The source is kept on the model (``TorsionalModel.source``) for
reading and debugging. The vectorised channels in :mod:`gearcli.model.outputs` are an independent
numpy implementation of the same force law; a unit test holds the two together.

Notation of the generated code (SI): ``d{k}`` mesh deflection delta_k (m) and ``dd{k}`` its rate,
``w{i}``/``a{i}`` shaft speed/acceleration, ``th{i}`` shaft angle (only for time-varying meshes),
``f{k}`` the transverse line-of-action force F_bt (N, signed: negative on the back flank), ``TL`` the
load torque, ``Tin`` the input torque of a torque drive. Mesh force (Adams IMPACT) on the penetration
``p`` beyond the gap: ``F_n = K g p^e + STEP(p, 0, 0, d, C) p'`` clamped at 0, ``F_bt = +-cos(beta_b) F_n``.
"""

from __future__ import annotations

import math
from typing import Callable

import numpy as np

from gearcli.model.contact_lines import contact_length_slope, scalar_factor
from gearcli.model.layout import Layout


def lit(x: float) -> str:
    """A float literal that round-trips exactly."""
    return repr(float(x))


def _power(base: str, e: float) -> str:
    if e == 1.0:
        return base
    if e == 1.5:
        return f"{base} * _sqrt({base})"
    if e == 2.0:
        return f"{base} * {base}"
    return f"{base} ** {lit(e)}"


def _power_minus_one(base: str, e: float) -> str:
    """p^(e-1), written so that e = 1 gives the literal 1."""
    if e == 1.0:
        return "1.0"
    if e == 1.5:
        return f"_sqrt({base})"
    if e == 2.0:
        return base
    return f"{base} ** {lit(e - 1.0)}"


def _ramp_lines(name: str, value: float, ramp_s: float, indent: str = "    ") -> list[str]:
    """``name = STEP(t, 0, 0, ramp_s, value)``, or the constant when there is no ramp."""
    if ramp_s <= 0.0 or value == 0.0:
        return [f"{indent}{name} = {lit(value)}"]
    return [f"{indent}if t < {lit(ramp_s)}:",
            f"{indent}    s = t * {lit(1.0 / ramp_s)}",
            f"{indent}    {name} = {lit(value)} * s * s * (3.0 - 2.0 * s)",
            f"{indent}else:",
            f"{indent}    {name} = {lit(value)}"]


def _input_motion_lines(lay: Layout) -> list[str]:
    """Speed drive: th0 (if needed), w0, a0 of the exact STEP speed profile."""
    v, T = lay.drive.speed_rad_s, lay.drive.ramp_s
    out = []
    if T <= 0.0:
        out += [f"    w0 = {lit(v)}", "    a0 = 0.0"]
        if lay.needs_angles:
            out.append(f"    th0 = {lit(v)} * t")
        return out
    out += [f"    if t < {lit(T)}:",
            f"        s = t * {lit(1.0 / T)}",
            f"        w0 = {lit(v)} * s * s * (3.0 - 2.0 * s)",
            f"        a0 = {lit(6.0 * v / T)} * s * (1.0 - s)"]
    if lay.needs_angles:
        out.append(f"        th0 = {lit(v * T)} * s * s * s * (1.0 - 0.5 * s)")
    out += ["    else:", f"        w0 = {lit(v)}", "        a0 = 0.0"]
    if lay.needs_angles:
        out.append(f"        th0 = {lit(v)} * (t - {lit(0.5 * T)})")
    return out


def _prologue(lay: Layout) -> list[str]:
    lines = [f"    {', '.join(lay.state_names)}, = y.tolist()"]
    if lay.speed_drive:
        lines += _input_motion_lines(lay)
    else:
        lines += _ramp_lines("Tin", lay.drive.torque_Nm, lay.drive.ramp_s)
    if lay.load.torque_Nm != 0.0:
        lines += _ramp_lines("TL", lay.load.torque_Nm, lay.load.ramp_s)
    if lay.needs_angles:  # theta_{k+1} = (r_bp,k theta_k - delta_k) / r_bg,k, up to the last pinion needed
        for k in range(lay.last_tv_mesh):
            m = lay.meshes[k]
            lines.append(f"    th{k + 1} = ({lit(m.base_radius_pinion_m)} * th{k} - d{k}) * "
                         f"{lit(1.0 / m.base_radius_gear_m)}")
    return lines


def _contact_blocks(lay: Layout, k: int, body: Callable[[str], list[str]], off: list[str]) -> list[str]:
    """``if`` blocks over the flanks of mesh k; ``body(sign)`` is the in-contact code with ``p``, ``pd``.

    Drive flank when ``h > j/2``, back flank when ``h < -j/2`` (docs/physics.md, "Torsional model"). Without backlash
    (j = 0) both flanks touch at h = 0, as in a tight mesh: a reversed load is carried by the back
    flank, and the gap offset is left out of the code.
    """
    m = lay.meshes[k]
    cb = lit(m.cos_beta_b)
    out = [f"    dd{k} = {lit(m.base_radius_pinion_m)} * w{k} - {lit(m.base_radius_gear_m)} * w{k + 1}",
           f"    h = {cb} * d{k}"]
    half = 0.5 * m.backlash_m
    gap = f" - {lit(half)}" if half > 0.0 else ""  # no backlash: both flanks touch at h = 0
    out += [f"    if h > {lit(half)}:", f"        p = h{gap}", f"        pd = {cb} * dd{k}"]
    out += body("")
    out += [f"    elif h < {lit(-half)}:", f"        p = -h{gap}", f"        pd = -{cb} * dd{k}"]
    out += body("-")
    out += ["    else:"] + [f"        {line}" for line in off]
    return out


def _stiffness_lines(lay: Layout, k: int) -> list[str]:
    m = lay.meshes[k]
    if not m.time_varying:
        return [f"        kk = {lit(m.stiffness_N_m_e)}"]
    return [f"        ph = {lit(m.pinion_teeth / (2.0 * math.pi))} * th{k}",
            f"        kk = {lit(m.stiffness_N_m_e)} * _g{k}(ph)"]


def _damping_lines(lay: Layout, k: int, with_slope: bool) -> list[str]:
    """c = STEP(p, 0, 0, d, C) (and its slope dc/dp for the Jacobian)."""
    m = lay.meshes[k]
    C, d = m.damping_Ns_m, m.full_damping_m
    out = [f"        s = p * {lit(1.0 / d)}",
           "        if s < 1.0:",
           f"            c = {lit(C)} * s * s * (3.0 - 2.0 * s)"]
    if with_slope:
        out += [f"            dc = {lit(6.0 * C / d)} * s * (1.0 - s)",
                "        else:", f"            c = {lit(C)}", "            dc = 0.0"]
    else:
        out += ["        else:", f"            c = {lit(C)}"]
    return out


def _rhs_mesh(lay: Layout, k: int) -> list[str]:
    m = lay.meshes[k]
    cb = lit(m.cos_beta_b)
    damped = m.damping_Ns_m > 0.0

    def body(sign: str) -> list[str]:
        out = _stiffness_lines(lay, k) + [f"        fe = kk * {_power('p', m.exponent)}"]
        if damped:
            out += _damping_lines(lay, k, with_slope=False)
            out += ["        fn = fe + c * pd", "        if fn < 0.0:", "            fn = 0.0",
                    f"        q{k} = (fn - fe) * pd"]
        else:
            out += ["        fn = fe"]
        if m.time_varying:
            out += [f"        u{k} = fe * pd"]
        return out + [f"        f{k} = {sign}{cb} * fn"]

    off = [f"f{k} = 0.0"] + ([f"q{k} = 0.0"] if damped else []) + ([f"u{k} = 0.0"] if m.time_varying else [])
    return _contact_blocks(lay, k, body, off)


def _shaft_torque(lay: Layout, i: int) -> str:
    """Net torque on shaft i from its meshes, the input and the load."""
    terms = []
    if i > 0:
        terms.append(f"{lit(lay.meshes[i - 1].base_radius_gear_m)} * f{i - 1}")
    if i < lay.n_meshes:
        terms.append(f"- {lit(lay.meshes[i].base_radius_pinion_m)} * f{i}")
    if i == 0 and not lay.speed_drive:
        terms.append("+ Tin")
    if i == lay.n_shafts - 1 and lay.load.torque_Nm != 0.0:
        terms.append("- TL")
    text = " ".join(terms).lstrip("+ ")
    return text if not text.startswith("- ") else "-" + text[2:]


def _quadrature_exprs(lay: Layout) -> list[str]:
    """Input power, load power, damping power, elastic power into time-varying springs."""
    if lay.speed_drive:
        m0 = lay.meshes[0]
        p_in = f"({lit(m0.base_radius_pinion_m)} * f0 + {lit(lay.inertias[0])} * a0) * w0"
    else:
        p_in = "Tin * w0"
    p_load = f"TL * w{lay.n_shafts - 1}" if lay.load.torque_Nm != 0.0 else "0.0"
    damped = [f"q{k}" for k, m in enumerate(lay.meshes) if m.damping_Ns_m > 0.0]
    out = [p_in, p_load, " + ".join(damped) if damped else "0.0"]
    if lay.n_tv:
        out.append(" + ".join(f"u{k}" for k, m in enumerate(lay.meshes) if m.time_varying))
    return out


def rhs_source(lay: Layout) -> str:
    lines = ["def rhs(t, y):"] + _prologue(lay)
    for k in range(lay.n_meshes):
        lines += _rhs_mesh(lay, k)
    out = [f"dd{k}" for k in range(lay.n_meshes)]
    out += [f"({_shaft_torque(lay, i)}) * {lit(1.0 / lay.inertias[i])}" for i in lay.free_shafts]
    if lay.has_theta_state:
        out.append("w0")
    out += _quadrature_exprs(lay)
    lines.append("    return _array([" + ", ".join(out) + "])")
    return "\n".join(lines) + "\n"


# ------------------------------------------------------------------------------------------ Jacobian
def _jac_mesh(lay: Layout, k: int) -> list[str]:
    """Partials of mesh k: kd = dF_bt/d delta, kv = dF_bt/d delta', kt = dF_bt/d theta_pinion, and of the
    quadrature integrands q (damping power) and u (elastic power): qd, qv, qt, ud, uv, ut."""
    m = lay.meshes[k]
    e = m.exponent
    cb = m.cos_beta_b
    damped, tv = m.damping_Ns_m > 0.0, m.time_varying
    names = ["kd", "kv"] + (["kt"] if tv else []) + ((["qd", "qv"] + (["qt"] if tv else [])) if damped else []) \
        + (["ud", "uv", "ut"] if tv else [])

    def body(sign: str) -> list[str]:
        s = -1.0 if sign else 1.0  # flank sign: dp/d delta = s cos(beta_b)
        out = _stiffness_lines(lay, k)
        out += [f"        fe = kk * {_power('p', e)}",
                f"        ke = {lit(e)} * kk * {_power_minus_one('p', e)}"]  # dfe/dp
        if tv:
            out += [f"        kth = {lit(m.stiffness_N_m_e * m.pinion_teeth / (2.0 * math.pi))} * "
                    f"_dg{k}(ph) * {_power('p', e)}"]  # dfe/dtheta_p
        if damped:
            out += _damping_lines(lay, k, with_slope=True)
            out += ["        if fe + c * pd > 0.0:",
                    f"            kd{k} = {lit(cb * cb)} * (ke + dc * pd)",
                    f"            kv{k} = {lit(cb * cb)} * c",
                    f"            qd{k} = {lit(s * cb)} * dc * pd * pd",
                    f"            qv{k} = {lit(2.0 * s * cb)} * c * pd"]
            if tv:
                out += [f"            kt{k} = {lit(s * cb)} * kth", f"            qt{k} = 0.0"]
            out += ["        else:", f"            kd{k} = 0.0", f"            kv{k} = 0.0",
                    f"            qd{k} = {lit(-s * cb)} * ke * pd",
                    f"            qv{k} = {lit(-s * cb)} * fe"]
            if tv:
                out += [f"            kt{k} = 0.0", f"            qt{k} = -kth * pd"]
        else:
            out += [f"        kd{k} = {lit(cb * cb)} * ke", f"        kv{k} = 0.0"]
            if tv:
                out += [f"        kt{k} = {lit(s * cb)} * kth"]
        if tv:
            out += [f"        ud{k} = {lit(s * cb)} * ke * pd", f"        uv{k} = {lit(s * cb)} * fe",
                    f"        ut{k} = kth * pd"]
        return out

    return _contact_blocks(lay, k, body, [f"{n}{k} = 0.0" for n in names])


def _gradient(lay: Layout, k: int, name: str) -> dict[int, str]:
    """Column -> d(name_k)/dy of a mesh-k quantity whose partials the generated code holds as
    ``{name}d{k}`` (delta_k), ``{name}v{k}`` (deflection rate) and ``{name}t{k}`` (mesh phase): the force
    F_bt,k (name "k") or a quadrature integrand (q: damping power, u: elastic power). The speeds enter
    through the deflection rate, the shaft angles through theta_pinion when the stiffness varies."""
    m = lay.meshes[k]
    g = {lay.i_delta(k): f"{name}d{k}"}
    for shaft, r in ((k, m.base_radius_pinion_m), (k + 1, -m.base_radius_gear_m)):
        col = lay.i_omega(shaft)
        if col is not None:
            g[col] = f"{lit(r)} * {name}v{k}"
    if m.time_varying:
        for col, coef in lay.angle_gradient(k).items():
            g[col] = (g[col] + " + " if col in g else "") + f"{lit(coef)} * {name}t{k}"
    return g


def _add(row: dict[int, list[str]], grad: dict[int, str], coef: str) -> None:
    for col, expr in grad.items():
        row.setdefault(col, []).append(f"{coef} * ({expr})")


def jac_source(lay: Layout) -> str:
    lines = ["def jac(t, y):"] + _prologue(lay)
    for k in range(lay.n_meshes):
        lines += _jac_mesh(lay, k)
    lines.append(f"    J = _zeros(({lay.n_states}, {lay.n_states}))")
    rows: dict[int, dict[int, list[str]]] = {}
    grads = [_gradient(lay, k, "k") for k in range(lay.n_meshes)]
    for k, m in enumerate(lay.meshes):  # d(delta_k)/dt = r_bp w_k - r_bg w_{k+1}
        row = rows.setdefault(lay.i_delta(k), {})
        for shaft, r in ((k, m.base_radius_pinion_m), (k + 1, -m.base_radius_gear_m)):
            col = lay.i_omega(shaft)
            if col is not None:
                row[col] = [lit(r)]
    for i in lay.free_shafts:  # J_i w_i' = r_bg,i-1 f_{i-1} - r_bp,i f_i (+ Tin - TL)
        row = rows.setdefault(lay.i_omega(i), {})
        if i > 0:
            _add(row, grads[i - 1], lit(lay.meshes[i - 1].base_radius_gear_m / lay.inertias[i]))
        if i < lay.n_meshes:
            _add(row, grads[i], lit(-lay.meshes[i].base_radius_pinion_m / lay.inertias[i]))
    if lay.has_theta_state:
        rows[lay.i_theta] = {lay.i_omega(0): ["1.0"]}
    q0 = lay.i_quad
    if lay.speed_drive:  # P_in = (r_bp0 f0 + J0 a0) w0, w0 prescribed
        _add(rows.setdefault(q0, {}), grads[0], f"{lit(lay.meshes[0].base_radius_pinion_m)} * w0")
    else:
        rows.setdefault(q0, {})[lay.i_omega(0)] = ["Tin"]
    if lay.load.torque_Nm != 0.0:
        rows.setdefault(q0 + 1, {})[lay.i_omega(lay.n_shafts - 1)] = ["TL"]
    for k, m in enumerate(lay.meshes):
        if m.damping_Ns_m > 0.0:
            _add(rows.setdefault(q0 + 2, {}), _gradient(lay, k, "q"), "1.0")
        if m.time_varying:
            _add(rows.setdefault(q0 + 3, {}), _gradient(lay, k, "u"), "1.0")
    for r in sorted(rows):
        for c in sorted(rows[r]):
            lines.append(f"    J[{r}, {c}] = " + " + ".join(rows[r][c]))
    lines.append("    return J")
    return "\n".join(lines) + "\n"


def compile_functions(lay: Layout) -> tuple[Callable, Callable, str]:
    """Compile the scene's ``rhs(t, y)`` and ``jac(t, y)``; returns them and their source."""
    namespace: dict = {"_array": np.array, "_zeros": np.zeros, "_sqrt": math.sqrt}
    for k, m in enumerate(lay.meshes):
        if m.time_varying:
            ea, eb = m.contact_ratio, m.overlap_ratio
            namespace[f"_g{k}"] = scalar_factor(ea, eb)
            namespace[f"_dg{k}"] = lambda ph, ea=ea, eb=eb: contact_length_slope(ph, ea, eb)
    source = rhs_source(lay) + "\n\n" + jac_source(lay)
    exec(compile(source, "<gearcli-model>", "exec"), namespace)  # noqa: S102 - our own generated source
    return namespace["rhs"], namespace["jac"], source
