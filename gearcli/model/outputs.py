"""Output channels and energies from sampled states (SI), through the elements' own force laws.

Every connector quantity is the element's :func:`force` (and :func:`potential`) evaluated at each
sample — the same function the right-hand side calls, so the channels cannot drift from the dynamics.
Reported tooth forces (DESIGN contract, README "Model"): ``F_t = F_bt cos(alpha_t)``,
``F_r = F_t tan(alpha_t)``, ``F_a = F_t tan(beta)`` — signed like the design's static forces (negative
on the back flank). A mesh's penetration channel is the signed penetration beyond the gap; its dynamic
transmission error ``q = delta - e(phi)`` (:func:`gearcli.model.elements.mesh.dynamic_transmission_error`;
the deflection when the mesh has no transmission error).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearcli.model.assembly import Layout
from gearcli.model.elements import KIND_MESH, machine, torque
from gearcli.model.elements.mesh import dynamic_transmission_error, penetration, phase_per_rad
from gearcli.model.step import ramp, ramp_motion


@dataclass(frozen=True)
class ConnectorSeries:
    force: np.ndarray  # F_bt (N) of a mesh, torque (N m) of a spring; signed
    deflection: np.ndarray  # delta (m or rad)
    penetration_m: np.ndarray  # mesh: signed penetration beyond the gap; spring: zeros
    potential_J: np.ndarray  # stored elastic energy
    dte_m: np.ndarray  # mesh: dynamic transmission error q = delta - e(phi) (m); spring: the deflection

    @property
    def line_force_N(self) -> np.ndarray:
        return self.force


@dataclass(frozen=True)
class Sampled:
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

    @property
    def shaft_omega_rad_s(self) -> np.ndarray:
        """Speeds of the reducer shafts (a flexible shaft: its gear end), (n_shafts, T)."""
        return self.omega_rad_s[list(self.layout.shaft_body)]


def body_motion(lay: Layout, t: np.ndarray, Y: np.ndarray) -> tuple[np.ndarray, np.ndarray | None, np.ndarray]:
    """Speeds of all bodies, their angles (if needed) and the input body's acceleration."""
    if lay.speed_drive:
        th0, w0, a0 = ramp_motion(t, lay.drive.ramp_s, lay.drive.speed_rad_s)
        if lay.drive.angle_rad != 0.0:  # a continued sweep point's start angle
            th0 = th0 + lay.drive.angle_rad
    else:
        th0 = Y[lay.i_theta] if lay.i_theta is not None else None
        w0, a0 = None, np.zeros_like(t)  # a torque drive's input torque is prescribed
    omega = lay.body_speeds(Y, w0)
    theta = None
    if lay.needs_angles:
        theta = np.empty((lay.n_bodies, t.size))
        theta[0] = th0
        for c, x in enumerate(lay.connectors):
            theta[c + 1] = (x.ra * theta[c] - Y[c]) / x.rb
    return omega, theta, np.asarray(a0)


def connector_series(lay: Layout, c: int, Y: np.ndarray, omega: np.ndarray, theta) -> ConnectorSeries:
    """Force, penetration and stored energy of connector c at every sample (the element's own law)."""
    x = lay.connectors[c]
    el, P = x.element, x.params
    d = Y[c]
    dd = x.ra * omega[x.a] - x.rb * omega[x.b]
    phi = phase_per_rad(P) * theta[x.a] if x.phased else np.zeros_like(d)
    wphi = phase_per_rad(P) * omega[x.a] if x.excited else np.zeros_like(d)
    n = d.size
    kernel = _loaded_kernel()
    if kernel is not None:  # the same element laws, compiled (gearcli.engine): identical numbers, ~100x faster
        F, U, pen, q = kernel.connector_series(x.kind, np.asarray(P, dtype=float), np.ascontiguousarray(d, dtype=float),
                                               np.ascontiguousarray(dd, dtype=float),
                                               np.ascontiguousarray(phi, dtype=float),
                                               np.ascontiguousarray(wphi, dtype=float))
        return ConnectorSeries(F, d.copy(), pen, U, q)
    # the scalar laws on Python floats (tolist: the same values as float(d[j]), without numpy's per-item cost)
    force, potential = el.force, el.potential
    ds, dds, phs, wphs = d.tolist(), dd.tolist(), phi.tolist(), wphi.tolist()
    F = np.array([force(P, dj, ddj, phj, wj)[0] for dj, ddj, phj, wj in zip(ds, dds, phs, wphs, strict=True)],
                 dtype=float).reshape(n)
    U = np.array([potential(P, dj, phj) for dj, phj in zip(ds, phs, strict=True)], dtype=float).reshape(n)
    if x.kind == KIND_MESH:
        pen = np.array([penetration(P, dj, phj) for dj, phj in zip(ds, phs, strict=True)], dtype=float).reshape(n)
        q = np.array([dynamic_transmission_error(P, dj, phj) for dj, phj in zip(ds, phs, strict=True)],
                     dtype=float).reshape(n) if x.excited else d.copy()  # without a transmission error q = delta
    else:
        pen, q = np.zeros(n), d.copy()
    return ConnectorSeries(F, d.copy(), pen, U, q)


def _loaded_kernel():
    """The compiled engine's kernel if this process loaded it (never imports numba itself)."""
    import sys

    engine = sys.modules.get("gearcli.engine")
    return engine.loaded_kernel() if engine is not None else None


def sample(lay: Layout, t: np.ndarray, Y: np.ndarray) -> Sampled:
    """Everything the channels and the energy balance need, at the sample times ``t``."""
    t = np.asarray(t, dtype=float)
    omega, theta, a0 = body_motion(lay, t, Y)
    conns = tuple(connector_series(lay, c, Y, omega, theta) for c in range(lay.n_conn))
    if lay.speed_drive:
        f0 = conns[0].force
        if lay.connectors[0].lossy:  # the pinion side of a lossy first mesh
            x = lay.connectors[0]
            f0 = np.array([machine_side(x.params, f, x.ra * wa, x.rb * wb) for f, wa, wb in
                           zip(f0.tolist(), omega[x.a].tolist(), omega[x.b].tolist(), strict=True)])
        t_in = f0 * lay.connectors[0].ra + lay.inertias[0] * a0
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
    return Sampled(t, omega, theta, t_in, t_load, conns, lay)


def machine_side(P, f: float, va: float, vb: float) -> float:
    """The pinion-side force of a lossy mesh (:func:`gearcli.model.elements.mesh.loss_factors`)."""
    from gearcli.model.elements.mesh import loss_factors

    return loss_factors(P, f, va, vb)[0]


def tooth_forces(lay: Layout, k: int, line_force_N: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Stage k: F_t = F_bt cos(alpha_t), F_r = F_t tan(alpha_t), F_a = F_t tan(beta), N."""
    m = lay.spec.meshes[k]
    ft = line_force_N * math.cos(m.transverse_pressure_angle_rad)
    return ft, ft * math.tan(m.transverse_pressure_angle_rad), ft * math.tan(m.helix_angle_rad)


def kinetic_energy(lay: Layout, omega: np.ndarray) -> np.ndarray:
    """0.5 sum J_i w_i^2 over all bodies, J."""
    return 0.5 * np.asarray(lay.inertias) @ (omega * omega)


def potential_energy(lay: Layout, s: Sampled, *, time_varying: bool) -> np.ndarray:
    """Stored energy of the connectors with constant (``time_varying=False``) or time-varying stiffness, J."""
    total = np.zeros_like(s.time_s)
    for x, cs in zip(lay.connectors, s.connectors, strict=True):
        if x.time_varying == time_varying:
            total += cs.potential_J
    return total
