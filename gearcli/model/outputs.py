"""Output channels and energies from sampled states, vectorised with numpy (SI).

This is a second, independent implementation of the mesh force law of :mod:`gearcli.model.codegen`
(array code instead of generated scalar code); ``tests/unit/test_model_equations.py`` holds the two
together. Reported tooth forces (docs/physics.md, "Torsional model"): ``F_t = F_bt cos(alpha_t)``,
``F_r = F_t tan(alpha_t)``, ``F_a = F_t tan(beta)`` — signed like the design's static forces (negative
on the back flank, i.e. under load reversal). The penetration channel is the signed penetration
beyond the gap: positive on the drive flank, negative on the back flank, 0 inside the backlash.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearcli.model.contact_lines import contact_length_factor
from gearcli.model.layout import Layout
from gearcli.model.step import ramp, ramp_motion


@dataclass(frozen=True)
class MeshSeries:
    penetration_m: np.ndarray  # signed, beyond the gap
    normal_force_N: np.ndarray  # F_n >= 0
    line_force_N: np.ndarray  # F_bt, signed
    elastic_force_N: np.ndarray  # K g p^e >= 0 (no damping part)
    stiffness_factor: np.ndarray  # g = L / L_mean (1 for constant stiffness)


@dataclass(frozen=True)
class Sampled:
    time_s: np.ndarray
    omega_rad_s: np.ndarray  # (n_shafts, T)
    theta_rad: np.ndarray | None  # (n_shafts, T), only when the scene needs angles
    input_torque_Nm: np.ndarray
    load_torque_Nm: np.ndarray
    meshes: tuple[MeshSeries, ...]


def shaft_speeds(lay: Layout, t: np.ndarray, Y: np.ndarray) -> tuple[np.ndarray, np.ndarray | None, np.ndarray]:
    """Speeds of all shafts, their angles (if needed) and the input shaft's acceleration."""
    n0 = lay.n_meshes
    if lay.speed_drive:
        th0, w0, a0 = ramp_motion(t, lay.drive.ramp_s, lay.drive.speed_rad_s)
        omega = np.vstack([w0[None, :], Y[n0:n0 + lay.n_shafts - 1]])
    else:
        th0 = Y[lay.i_theta] if lay.has_theta_state else None
        a0 = np.zeros_like(t)  # not needed: the torque drive's input torque is prescribed
        omega = Y[n0:n0 + lay.n_shafts]
    theta = None
    if lay.needs_angles:
        theta = np.empty((lay.n_shafts, t.size))
        theta[0] = th0
        for k, m in enumerate(lay.meshes):
            theta[k + 1] = (m.base_radius_pinion_m * theta[k] - Y[k]) / m.base_radius_gear_m
    return omega, theta, np.asarray(a0)


def mesh_series(lay: Layout, k: int, Y: np.ndarray, omega: np.ndarray, theta: np.ndarray | None) -> MeshSeries:
    """The Adams IMPACT force of mesh k at every sample (see :mod:`gearcli.model.codegen`)."""
    m = lay.meshes[k]
    cb = m.cos_beta_b
    h = cb * Y[k]
    hd = cb * (m.base_radius_pinion_m * omega[k] - m.base_radius_gear_m * omega[k + 1])
    half = 0.5 * m.backlash_m
    drive, back = h > half, h < -half
    sign = np.where(back, -1.0, 1.0)
    p = np.where(drive, h - half, np.where(back, -h - half, 0.0))
    pd = sign * hd
    g = np.ones_like(h)
    if m.time_varying:
        g = contact_length_factor(m.pinion_teeth * theta[k] / (2.0 * math.pi), m.contact_ratio, m.overlap_ratio)
    fe = m.stiffness_N_m_e * g * p ** m.exponent
    fn = fe
    if m.damping_Ns_m > 0:
        s = np.clip(p / m.full_damping_m, 0.0, 1.0)
        fn = np.maximum(fe + m.damping_Ns_m * s * s * (3.0 - 2.0 * s) * pd, 0.0)
    fn = np.where(drive | back, fn, 0.0)
    return MeshSeries(sign * np.where(drive | back, p, 0.0), fn, sign * cb * fn, np.where(drive | back, fe, 0.0), g)


def sample(lay: Layout, t: np.ndarray, Y: np.ndarray) -> Sampled:
    """Everything the channels and the energy balance need, at the sample times ``t``."""
    t = np.asarray(t, dtype=float)
    omega, theta, a0 = shaft_speeds(lay, t, Y)
    meshes = tuple(mesh_series(lay, k, Y, omega, theta) for k in range(lay.n_meshes))
    if lay.speed_drive:
        t_in = meshes[0].line_force_N * lay.meshes[0].base_radius_pinion_m + lay.inertias[0] * a0
    else:
        t_in = np.asarray(ramp(t, lay.drive.ramp_s, lay.drive.torque_Nm)) * np.ones_like(t)
    t_load = np.asarray(ramp(t, lay.load.ramp_s, lay.load.torque_Nm)) * np.ones_like(t)
    return Sampled(t, omega, theta, t_in, t_load, meshes)


def tooth_forces(lay: Layout, k: int, line_force_N: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """F_t = F_bt cos(alpha_t), F_r = F_t tan(alpha_t), F_a = F_t tan(beta), N."""
    m = lay.meshes[k]
    ft = line_force_N * math.cos(m.transverse_pressure_angle_rad)
    return ft, ft * math.tan(m.transverse_pressure_angle_rad), ft * math.tan(m.helix_angle_rad)


def kinetic_energy(lay: Layout, omega: np.ndarray) -> np.ndarray:
    """0.5 sum J_i w_i^2, J."""
    return 0.5 * np.asarray(lay.inertias) @ (omega * omega)


def potential_energy(lay: Layout, s: Sampled, *, time_varying: bool) -> np.ndarray:
    """sum K g p^(e+1)/(e+1) over the meshes with constant (``time_varying=False``) or time-varying K, J."""
    total = np.zeros_like(s.time_s)
    for m, ms in zip(lay.meshes, s.meshes):
        if m.time_varying == time_varying:
            p = np.abs(ms.penetration_m)
            total += m.stiffness_N_m_e * ms.stiffness_factor * p ** (m.exponent + 1) / (m.exponent + 1)
    return total
