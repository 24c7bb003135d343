"""Output channels and energies from sampled states (SI), through the elements' own force laws.

Every connector quantity is the element's :func:`force` (and :func:`potential`) evaluated at each
sample — the same function the right-hand side calls, so the channels cannot drift from the dynamics.
Reported tooth forces (DESIGN contract, docs/tour.md "The model, in one paragraph"): ``F_t = F_bt cos(alpha_t)``,
``F_r = F_t tan(alpha_t)``, ``F_a = F_t tan(beta)`` — signed like the design's static forces (negative
on the back flank). An element's own channels are its ``CHANNELS`` (:mod:`gearcli.model.elements`): a
mesh's ``penetration_m`` is the signed penetration beyond the gap, its ``dte_m`` the dynamic transmission
error ``q = delta - e(phi)`` (:func:`gearcli.model.elements.mesh.dynamic_transmission_error`; the deflection
when the mesh has no transmission error). Speeds and forces go to and from bodies by index (the connector's
bodies and levers, :class:`gearcli.model.assembly.Connector`).
"""

from __future__ import annotations

import math
from contextlib import nullcontext
from dataclasses import fields

import numpy as np

from gearcli.core import signals
from gearcli.core.records import record
from gearcli.model import elements
from gearcli.model.assembly import Layout, ModelArrays
from gearcli.model.elements import machine, torque
from gearcli.model.step import ramp, ramp_motion, ramp_rates


@record
class ConnectorSeries:
    """One connector's sampled force, deflection, penetration, stored energy and DTE."""

    force: np.ndarray  # F_bt (N) of a mesh, torque (N m) of a spring; signed
    deflection: np.ndarray  # delta (m or rad)
    penetration_m: np.ndarray  # mesh: signed penetration beyond the gap; spring: zeros
    potential_J: np.ndarray  # stored elastic energy
    dte_m: np.ndarray  # mesh: dynamic transmission error q = delta - e(phi) (m); spring: the deflection

    @property
    def line_force_N(self) -> np.ndarray:
        return self.force

    def tail(self, start: int) -> ConnectorSeries:
        """The samples from ``start`` on."""
        return ConnectorSeries(self.force[start:], self.deflection[start:], self.penetration_m[start:],
                               self.potential_J[start:], self.dte_m[start:])


@record
class Sampled:
    """A run's samples: body speeds (and angles), drive and load torques, every connector's series."""

    time_s: np.ndarray
    omega_rad_s: np.ndarray  # (n_bodies, T)
    theta_rad: np.ndarray | None  # (n_bodies, T), only when the scene needs angles
    input_torque_Nm: np.ndarray
    load_torque_Nm: np.ndarray
    connectors: tuple[ConnectorSeries, ...]
    layout: Layout

    @property
    def meshes(self) -> tuple[ConnectorSeries, ...]:
        """The mesh connectors, in stage order."""
        return tuple(self.connectors[c] for c in self.layout.stage_conn)

    def tail(self, start: int) -> Sampled:
        """The samples from ``start`` on: every channel is a function of its own sample, so these are the numbers
        :func:`sample` gives for those samples alone."""
        return Sampled(self.time_s[start:], self.omega_rad_s[:, start:],
                       None if self.theta_rad is None else self.theta_rad[:, start:],
                       np.broadcast_to(self.input_torque_Nm, self.time_s.shape)[start:],
                       np.broadcast_to(self.load_torque_Nm, self.time_s.shape)[start:],
                       tuple(c.tail(start) for c in self.connectors), self.layout)


def body_motion(lay: Layout, t: np.ndarray, Y: np.ndarray) -> tuple[np.ndarray, np.ndarray | None, np.ndarray]:
    """Speeds of all bodies, their angles (if needed) and the input body's acceleration."""
    if lay.speed_drive and lay.needs_angles:
        th0, w0, a0 = ramp_motion(t, lay.drive.ramp_s, lay.drive.speed_rad_s)
        if lay.drive.angle_rad != 0.0:  # a continued sweep point's start angle
            th0 = th0 + lay.drive.angle_rad
    elif lay.speed_drive:  # (no angle read)
        th0, (w0, a0) = None, ramp_rates(t, lay.drive.ramp_s, lay.drive.speed_rad_s)
    else:
        th0 = Y[lay.state.i_theta] if lay.state.i_theta is not None else None
        w0, a0 = None, np.zeros_like(t)  # a torque drive's input torque is prescribed
    omega = lay.body_speeds(Y, w0)
    theta = None
    if lay.needs_angles:
        theta = np.empty((lay.n_bodies, t.size))
        theta[0] = th0
        rows = lay.angle_rows
        for b, c in enumerate(lay.tree):  # theta_b = (r_a theta_a - delta_c) / r_b, a < b
            if c >= 0:
                x = lay.connectors[c]
                theta[b] = (x.ra * theta[x.a] - Y[lay.state.delta(c)]) / x.rb
            elif b in rows:  # the kinematics fix it through several connectors (Layout.angle_rows)
                row = rows[b]
                theta[b] = row.constant
                for j, k in row.bodies:
                    theta[b] = theta[b] + k * theta[j]
                for cc, k in row.deflections:
                    theta[b] = theta[b] + k * Y[lay.state.delta(cc)]
            elif b > 0:
                theta[b] = np.nan  # no two-body connector reaches it: no element reads its angle
    return omega, theta, np.asarray(a0)


def _law_arguments(lay: Layout, c: int, Y: np.ndarray, omega: np.ndarray, theta):
    """Connector c's law arguments at every sample: deflection, its rate, mesh phase and phase rate."""
    x = lay.connectors[c]
    el, P = x.element, x.params
    d = Y[lay.state.delta(c)]
    dd = None
    for lever, b in zip(x.levers, x.bodies, strict=True):  # delta' = sum_j s_j r_j w_j, in slot order
        dd = lever * omega[b] if dd is None else dd + lever * omega[b]
    assert dd is not None
    phi = el.phase_per_rad(P) * theta[x.a] if x.phased else np.zeros_like(d)
    wphi = el.phase_per_rad(P) * omega[x.a] if x.excited else np.zeros_like(d)
    return d, dd, phi, wphi


def connector_series(lay: Layout, c: int, Y: np.ndarray, omega: np.ndarray, theta) -> ConnectorSeries:
    """Force, penetration and stored energy of connector c at every sample (the element's own law)."""
    kernel = _loaded_kernel()
    if kernel is None:
        return _connector_series(lay, c, Y, omega, theta, None)
    with signals.deferred():  # a signal acted on in plain Python after the call, never inside numba's dispatcher
        return _connector_series(lay, c, Y, omega, theta, kernel)


def _connector_series(lay: Layout, c: int, Y: np.ndarray, omega: np.ndarray, theta, kernel,
                      energy_from: int = 0) -> ConnectorSeries:
    """:func:`connector_series` with the compiled engine's ``kernel`` (None: the scalar laws), called with the
    signals held back by the caller (:func:`gearcli.core.signals.deferred`, once for all of a sample's
    connectors); the stored energy from sample ``energy_from`` on (NaN before it: :func:`sample`). The compiled
    laws never evaluate an unexcited mesh's DTE channel (its ``dte_m`` is the deflection)."""
    x = lay.connectors[c]
    el, P = x.element, x.params
    d, dd, phi, wphi = _law_arguments(lay, c, Y, omega, theta)
    n = d.size
    if kernel is not None and x.kind in kernel.KINDS:  # the same laws, compiled (gearcli.engine): ~100x faster
        F, U, ch = kernel.connector_series(x.kind, *_compiled_arguments(P, d, dd, phi, wphi), energy_from,
                                           _evaluated_channels(x))
        channels = {name: ch[i] for i, name in enumerate(el.CHANNELS)}
    elif (vectorised := elements.series_of(el, P, d, dd, phi, wphi)) is not None:  # the same values at once
        F, U, ch = vectorised
        if energy_from > 0:
            U = np.array(U, dtype=float)
            U[:energy_from] = np.nan
        channels = dict(zip(el.CHANNELS, ch, strict=True))
    else:  # the scalar laws on Python floats (tolist: the values of float(d[j]), without numpy's per-item cost)
        potential, channel = el.potential, el.channel
        ds, phs = d.tolist(), phi.tolist()
        F = _scalar_forces(el, P, d, dd, phi, wphi)
        U = np.array([potential(P, dj, phj) if j >= energy_from else math.nan
                      for j, (dj, phj) in enumerate(zip(ds, phs, strict=True))], dtype=float).reshape(n)
        channels = {name: np.array([channel(P, i, dj, phj) for dj, phj in zip(ds, phs, strict=True)],
                                   dtype=float).reshape(n) for i, name in enumerate(el.CHANNELS)}
    pen = channels["penetration_m"] if "penetration_m" in channels else np.zeros(n)
    q = channels["dte_m"] if x.excited and "dte_m" in channels else d.copy()  # without a transmission error q = delta
    return ConnectorSeries(F, d.copy(), pen, U, q)


def _evaluated_channels(x) -> int:
    """How many of connector ``x``'s leading channels the compiled laws evaluate: all of them but an unexcited
    mesh's DTE (its last channel; its ``dte_m`` is the deflection)."""
    names = x.element.CHANNELS
    return len(names) - 1 if names and names[-1] == "dte_m" and not x.excited else len(names)


def _compiled_arguments(P, d, dd, phi, wphi) -> tuple[np.ndarray, ...]:
    """The compiled ``connector_series``'s arguments after the kind: the parameter row and the law arguments as
    contiguous float arrays."""
    return (np.asarray(P, dtype=float), np.ascontiguousarray(d, dtype=float), np.ascontiguousarray(dd, dtype=float),
            np.ascontiguousarray(phi, dtype=float), np.ascontiguousarray(wphi, dtype=float))


def _connector_force(lay: Layout, c: int, Y: np.ndarray, omega: np.ndarray, theta) -> np.ndarray:
    """``connector_series(...).force`` alone: the law's force at every sample, without the energy and channels the
    series also evaluates (the compiled call told to evaluate neither: the series' force, the same numbers)."""
    x = lay.connectors[c]
    kernel = _loaded_kernel()
    d, dd, phi, wphi = _law_arguments(lay, c, Y, omega, theta)
    if kernel is not None and x.kind in kernel.KINDS:  # the compiled laws' force, no energy nor channel evaluated
        with signals.deferred():
            return kernel.connector_series(x.kind, *_compiled_arguments(x.params, d, dd, phi, wphi), d.size, 0)[0]
    vectorised = elements.series_of(x.element, x.params, d, dd, phi, wphi)
    return vectorised[0] if vectorised is not None else _scalar_forces(x.element, x.params, d, dd, phi, wphi)


def _scalar_forces(el, P, d: np.ndarray, dd: np.ndarray, phi: np.ndarray, wphi: np.ndarray) -> np.ndarray:
    """The element's scalar force law at every sample, on Python floats (tolist: the values of float(d[j]), without
    numpy's per-item cost)."""
    force = el.force
    return np.array([force(P, dj, ddj, phj, wj)[0] for dj, ddj, phj, wj in
                     zip(d.tolist(), dd.tolist(), phi.tolist(), wphi.tolist(), strict=True)], dtype=float).reshape(d.size)


def mesh_line_forces(lay: Layout, t: np.ndarray, Y: np.ndarray) -> list[np.ndarray]:
    """The meshes' line forces F_bt (N) at the sample times ``t``, in stage order: ``[m.line_force_N for m in
    sample(lay, t, Y).meshes]`` (the same numbers), without the channels and energies a check pass never reads."""
    omega, theta, _ = body_motion(lay, np.asarray(t, dtype=float), Y)
    return [_connector_force(lay, c, Y, omega, theta) for c in lay.stage_conn]


def planet_sun_connectors(lay: Layout, gear: str = "sun") -> dict[int, list[int]]:
    """Stage (0-based) -> its planets' sun-mesh connectors in planet order (planetary stages only): the meshes whose
    largest force is the stage's dynamic and run-up factor (:mod:`gearcli.simulate.planet_stats`); ``gear = "ring"``:
    their planet-ring meshes instead."""
    out: dict[int, list[tuple[int, int]]] = {}
    for c, x in enumerate(lay.connectors):
        if x.load_body >= 0 and x.gear == gear:
            out.setdefault(x.index, []).append((x.planet, c))
    return {k: [c for _, c in sorted(v)] for k, v in out.items()}


def connector_line_forces(lay: Layout, t: np.ndarray, Y: np.ndarray, connectors: list[int]) -> list[np.ndarray]:
    """The line forces (N) of ``connectors`` at the sample times ``t``, as :func:`mesh_line_forces` gives the stages'."""
    omega, theta, _ = body_motion(lay, np.asarray(t, dtype=float), Y)
    return [_connector_force(lay, c, Y, omega, theta) for c in connectors]


def stored_energy(lay: Layout, t: float, y: np.ndarray) -> float:
    """Kinetic energy plus the elastic energy of the constant-stiffness connectors at one state ``y`` at time
    ``t``: what ``kinetic_energy`` and ``potential_energy(time_varying=False)`` of ``sample`` at that one state
    give (the same laws, the same sum), without the forces and channels (an energy watch asks every ~500 steps)."""
    tt, Y = np.array([t]), y[:, None]
    omega, theta, _ = body_motion(lay, tt, Y)
    elastic = np.zeros_like(tt)
    kernel = _loaded_kernel()
    with signals.deferred() if kernel is not None else nullcontext():  # once for the connectors' compiled calls
        for c, x in enumerate(lay.connectors):
            if not x.time_varying:  # the connector's own law at the one sample
                elastic += _potential(lay, c, Y, omega, theta, kernel)
    return float(kinetic_energy(lay, omega)[0]) + float(elastic[0])


def _potential(lay: Layout, c: int, Y: np.ndarray, omega: np.ndarray, theta, kernel) -> np.ndarray:
    """Connector c's stored energy at the samples: the compiled laws' series where the ``kernel`` is loaded, else the
    element's scalar ``potential`` sample by sample, which its vectorised hook gives value for value
    (:data:`~gearcli.model.elements.SERIES_HOOK`): at the energy watch's one sample, without the numpy calls the
    hook's forces and channels cost."""
    x = lay.connectors[c]
    if kernel is not None and x.kind in kernel.KINDS:  # the series' own call (its potential), without its channels
        args = _compiled_arguments(x.params, *_law_arguments(lay, c, Y, omega, theta))
        return kernel.connector_series(x.kind, *args, 0, 0)[1]
    d, _, phi, _ = _law_arguments(lay, c, Y, omega, theta)
    potential, P = x.element.potential, x.params
    return np.array([potential(P, dj, phj) for dj, phj in zip(d.tolist(), phi.tolist(), strict=True)], dtype=float)


_compiled: list = []  # the compiled engine's kernel once gearcli.engine has loaded it (use_compiled)


def use_compiled(kernel) -> None:
    """The compiled engine (the layer above, ``gearcli.engine.load``) hands its kernel down when it has loaded
    it: ``connector_series`` then runs the same element laws compiled. The model never imports the engine."""
    _compiled[:] = [kernel]


def _loaded_kernel():
    """The compiled engine's kernel if this process loaded it (never imports numba itself)."""
    return _compiled[0] if _compiled else None


def sample(lay: Layout, t: np.ndarray, Y: np.ndarray, *, torques: bool = True, energy_from: int = 0,
           constant_from: int | None = None, arrays: ModelArrays | None = None) -> Sampled:
    """Everything the channels and the energy balance need, at the sample times ``t``. ``torques=False``: without
    the input and load torques (empty arrays; a caller that reads only the speeds, connector forces and energies:
    the energy watch, the settle test, the check pass). ``energy_from``: the connectors' stored energy
    (``potential_J``) from this sample on, NaN before it (not evaluated: an energy balance that starts there,
    :func:`gearcli.simulate.equilibrium.sampled`; every other channel is sampled whole). ``constant_from``: the
    state is constant from this sample on and so is every channel (the caller's word: a speed drive past its ramps,
    no angle read, ``Y``'s dynamic states equal from there): the samples up to it are evaluated, its own repeated
    after it (the same numbers as evaluating each). ``arrays``: the layout's ``Layout.arrays`` where the caller
    has them (its model's, :attr:`gearcli.model.TorsionalModel.arrays`): the compiled call's connector rows read
    from them (:func:`_series_rows`), not built again."""
    t = np.asarray(t, dtype=float)
    kernel = _loaded_kernel()
    if constant_from is not None:  # the samples from there on are that sample's state: evaluated once, repeated
        if kernel is None or not _compiled_all(lay, kernel):
            return _held(sample(lay, t[:constant_from + 1], Y[:, :constant_from + 1], torques=torques,
                                energy_from=energy_from), t, torques)
        head = t[:constant_from + 1]
        omega, theta, a0 = body_motion(lay, head, Y[:, :constant_from + 1])
        with signals.deferred():  # a signal acted on after the compiled call
            conns = _all_series(lay, Y[:, :constant_from + 1], omega, theta, kernel, energy_from, t.size, arrays)
        omega = _widened(omega, t.size)
        if not torques:
            return Sampled(t, omega, None, np.empty(0), np.empty(0), conns, lay)
        t_in, t_load = _torques(lay, head, omega[:, :head.size], theta, a0, conns, head.size)
        return Sampled(t, omega, None, _widened(t_in, t.size), _widened(t_load, t.size), conns, lay)
    omega, theta, a0 = body_motion(lay, t, Y)
    if kernel is None:
        conns = tuple(_connector_series(lay, c, Y, omega, theta, None, energy_from) for c in range(lay.n_conn))
    else:
        with signals.deferred():  # once for every connector (a signal acted on after the compiled calls)
            conns = _all_series(lay, Y, omega, theta, kernel, energy_from, t.size, arrays) \
                if _compiled_all(lay, kernel) \
                else tuple(_connector_series(lay, c, Y, omega, theta, kernel, energy_from) for c in range(lay.n_conn))
    if not torques:
        return Sampled(t, omega, theta, np.empty(0), np.empty(0), conns, lay)
    t_in, t_load = _torques(lay, t, omega, theta, a0, conns, t.size)
    return Sampled(t, omega, theta, t_in, t_load, conns, lay)


def _torques(lay: Layout, t: np.ndarray, omega: np.ndarray, theta, a0, conns: tuple[ConnectorSeries, ...],
             n: int) -> tuple[np.ndarray, np.ndarray]:
    """The drive's input torque and the load's torque at the samples ``t`` (the first ``n`` of the connectors'
    series)."""
    if lay.speed_drive:  # what the drive puts into body 0: its connectors' reactions and its inertia
        t_in = None
        for c, j in lay.acting_on(0):
            term = _side_force(lay, c, j, conns[c].force[:n], omega) * lay.connectors[c].levers[j]
            t_in = term if t_in is None else t_in + term
        t_in = (0.0 if t_in is None else t_in) + lay.inertias[0] * a0
    elif lay.motor_drive:
        row = lay.motor_row
        t_in = np.array([machine.motor_torque(row, tj, wj)[0] for tj, wj in zip(t.tolist(), omega[0].tolist(),
                                                                                 strict=True)])
    else:
        t_in = np.asarray(ramp(t, lay.drive.ramp_s, lay.drive.torque_Nm)) * np.ones_like(t)
        if lay.ripple:
            assert theta is not None  # a ripple needs the input angle
            t_in = t_in * np.array([torque.ripple(lay.ripple, float(th))[0] for th in theta[0]])
    t_load = np.asarray(ramp(t, lay.load.ramp_s, lay.load.torque_Nm)) * np.ones_like(t)
    if lay.fluctuation:
        t_load = t_load * np.array([torque.fluctuation(lay.fluctuation, float(tj) + lay.load.clock_s) for tj in t])
    if lay.load_law:
        t_load = t_load * np.array([machine.load_factor(lay.load_law, w)[0] for w in omega[-1].tolist()])
    return t_in, t_load


def _compiled_all(lay: Layout, kernel) -> bool:
    """Every connector's kind is one the compiled laws have (their series in one call, :func:`_all_series`)."""
    return all(x.kind in kernel.KINDS for x in lay.connectors)


def _series_rows(lay: Layout, arrays: ModelArrays | None = None) -> tuple[np.ndarray, ...]:
    """The compiled ``connectors_series``' description of the layout's connectors (its own, kept with it): kinds,
    parameter rows, bodies and levers by slot (-1 / 0 padded), phase per radian, flags (1 phased, 2 excited), the
    deflection's state row, how many leading channels are evaluated (:func:`_evaluated_channels`). ``arrays``: the
    layout's :meth:`~gearcli.model.assembly.Layout.arrays` where the caller has them (a run's model built them for
    its integration): their kinds, parameter rows, bodies and levers are those rows, built once (the parameter rows
    zero-padded to ``N_PARAM``, as the integration reads them: the laws read their parameters by position)."""
    kept = lay.__dict__.get("_series_rows")
    if kept is None:
        conns = lay.connectors
        nc = len(conns)
        if arrays is not None:
            kind, param, bodies, levers = arrays.conn_kind, arrays.conn_param, arrays.conn_bodies, arrays.conn_levers
        else:
            width = max((len(x.params) for x in conns), default=0)
            kind = np.array([x.kind for x in conns], dtype=np.int64)
            param = np.zeros((nc, width))
            bodies = np.full((nc, elements.MAX_BODIES), -1, dtype=np.int64)
            levers = np.zeros((nc, elements.MAX_BODIES))
            for c, x in enumerate(conns):
                param[c, :len(x.params)] = x.params
                bodies[c, :len(x.bodies)] = x.bodies
                levers[c, :len(x.levers)] = x.levers
        ppr = np.zeros(nc)
        for c, x in enumerate(conns):
            if x.phased or x.excited:
                ppr[c] = x.element.phase_per_rad(x.params)
        kept = (kind, param, bodies, levers, ppr,
                np.array([int(x.phased) + 2 * int(x.excited) for x in conns], dtype=np.int64),
                np.array([lay.state.delta(c) for c in range(nc)], dtype=np.int64),
                np.array([_evaluated_channels(x) for x in conns], dtype=np.int64))
        lay.__dict__["_series_rows"] = kept
    return kept


def _all_series(lay: Layout, Y: np.ndarray, omega: np.ndarray, theta, kernel, energy_from: int,
                width: int, arrays: ModelArrays | None = None) -> tuple[ConnectorSeries, ...]:
    """Every connector's :func:`_connector_series` (the same numbers) in one compiled call, its law arguments made
    there; ``width`` samples, the last of ``Y``'s repeated after them (:func:`sample`'s ``constant_from``). Called
    with the signals held back; ``arrays``: :func:`_series_rows`'."""
    kind, param, bodies, levers, ppr, flags, rows, channels = _series_rows(lay, arrays)
    if theta is None and any(x.phased for x in lay.connectors):  # the kernel would read past its dummy angles
        raise ValueError("a phased connector's mesh phase needs the bodies' angles (Layout.needs_angles)")
    F, U, ch, D = kernel.connectors_series(kind, param, bodies, levers, ppr, flags, rows,
                                           np.ascontiguousarray(Y, dtype=float), np.ascontiguousarray(omega),
                                           _NO_ANGLES if theta is None else np.ascontiguousarray(theta),
                                           energy_from, channels, width)
    out = []
    for c, x in enumerate(lay.connectors):
        names = x.element.CHANNELS
        pen = ch[c, names.index("penetration_m")] if "penetration_m" in names else np.zeros(width)
        q = ch[c, names.index("dte_m")] if x.excited and "dte_m" in names else D[c].copy()
        out.append(ConnectorSeries(F[c], D[c], pen, U[c], q))
    return tuple(out)


_NO_ANGLES = np.zeros((1, 1))  # theta where the scene reads no angle (no connector is phased)


def _widened(x: np.ndarray, width: int) -> np.ndarray:
    """``x`` (its samples along the last axis; a constant broadcast) with its last sample repeated to ``width``."""
    x = np.asarray(x, dtype=float)
    out = np.empty((*x.shape[:-1], width) if x.ndim else (width,))
    if x.ndim == 0:
        out.fill(float(x))
        return out
    n = x.shape[-1]
    out[..., :n] = x
    out[..., n:] = x[..., n - 1:n]
    return out


def _held(head: Sampled, t: np.ndarray, torques: bool) -> Sampled:
    """``head``'s samples with the last repeated to ``t``'s (:func:`sample`'s ``constant_from``, the laws in Python)."""
    width = t.size
    conns = tuple(ConnectorSeries(*(_widened(getattr(c, name), width) for name in _FIELDS)) for c in head.connectors)
    return Sampled(t, _widened(head.omega_rad_s, width), None,
                   _widened(head.input_torque_Nm, width) if torques else head.input_torque_Nm,
                   _widened(head.load_torque_Nm, width) if torques else head.load_torque_Nm, conns, head.layout)


_FIELDS = tuple(f.name for f in fields(ConnectorSeries))  # a connector's series, in ConnectorSeries' field order


def _side_force(lay: Layout, c: int, j: int, force: np.ndarray, omega: np.ndarray) -> np.ndarray:
    """The force connector c puts on its body j: the law's, or a lossy element's side force on that slot (its
    loss hook: ``loss_factors`` on the pitch-line speeds of ``loss_sides``; a slot with a share of both sides,
    a planet mesh's carrier, takes that share of each)."""
    x = lay.connectors[c]
    share_a, share_b = x.loss_share(j)
    if share_a == 0.0 and share_b == 0.0:
        return force
    va, vb = (_pitch_line_speed(terms, omega, force.shape) for terms in x.loss_speeds)
    law = x.element.loss_factors
    sides = np.array([law(x.params, f, a, b)[:2] for f, a, b in
                      zip(force.tolist(), va.tolist(), vb.tolist(), strict=True)]).reshape(-1, 2)
    if share_b == 0.0 and share_a == 1.0:
        return sides[:, 0]
    if share_a == 0.0 and share_b == 1.0:
        return sides[:, 1]
    return share_a * sides[:, 0] + share_b * sides[:, 1]


def _pitch_line_speed(terms: list[tuple[int, float]], omega: np.ndarray, shape: tuple[int, ...]) -> np.ndarray:
    """sum k w_body over a loss side's (body, k) terms, at every sample (0 for no term: a held member)."""
    v = None
    for body, k in terms:
        v = k * omega[body] if v is None else v + k * omega[body]
    return np.broadcast_to(0.0 if v is None else v, shape)


def tooth_forces(lay: Layout, k: int, line_force_N: np.ndarray,
                 out: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Stage k: F_t = F_bt cos(alpha_t), F_r = F_t tan(alpha_t), F_a = F_t tan(beta), N; ``out``: three rows the
    three are written into (the same multiplications), returned. A spur stage's F_a is zero, never the negative
    zero a reversed F_t times tan 0 would give (printed "-0" in CSV and reports)."""
    m = lay.spec.meshes[k]
    cos_a, tan_a, tan_b = (math.cos(m.transverse_pressure_angle_rad), math.tan(m.transverse_pressure_angle_rad),
                           math.tan(m.helix_angle_rad))
    if out is None:
        ft = line_force_N * cos_a
        return ft, ft * tan_a, ft * tan_b if tan_b else np.zeros_like(ft)
    ft = np.multiply(line_force_N, cos_a, out=out[0])
    if not tan_b:
        out[2].fill(0.0)
        return ft, np.multiply(ft, tan_a, out=out[1]), out[2]
    return ft, np.multiply(ft, tan_a, out=out[1]), np.multiply(ft, tan_b, out=out[2])


def stage_rows(lay: Layout, meshes: tuple[ConnectorSeries, ...]) -> np.ndarray:
    """Every stage's F_t, F_r, F_a (N), penetration (mm) and DTE (um) at the samples of its mesh's series
    ``meshes`` (stage order), five rows a stage of one array: :func:`tooth_forces` and the units' scalings, each
    written in its row."""
    rows = np.empty((5 * len(meshes), meshes[0].force.size if meshes else 0))
    for k, ms in enumerate(meshes):
        tooth_forces(lay, k, ms.line_force_N, out=rows[5 * k:5 * k + 3])
        np.multiply(ms.penetration_m, 1e3, out=rows[5 * k + 3])
        np.multiply(ms.dte_m, 1e6, out=rows[5 * k + 4])
    return rows


def tangential_force_N(lay: Layout, k: int, line_force_N: float) -> float:
    """Stage k's F_t of one line force F_bt (N): :func:`tooth_forces`' F_t on a float, the same multiplication."""
    return float(line_force_N) * math.cos(lay.spec.meshes[k].transverse_pressure_angle_rad)


def kinetic_energy(lay: Layout, omega: np.ndarray) -> np.ndarray:
    """0.5 sum J_i w_i^2 over all bodies, J."""
    return 0.5 * np.asarray(lay.inertias) @ (omega * omega)


def potential_energy(lay: Layout, s: Sampled, *, time_varying: bool, at: list[int] | None = None) -> np.ndarray:
    """Stored energy of the connectors with constant (``time_varying=False``) or time-varying stiffness, J; at the
    samples ``at`` alone (indices; default: every sample), each the same sum."""
    total = np.zeros_like(s.time_s) if at is None else np.zeros(len(at))
    for x, cs in zip(lay.connectors, s.connectors, strict=True):
        if x.time_varying == time_varying:
            total += cs.potential_J if at is None else cs.potential_J[at]
    return total
