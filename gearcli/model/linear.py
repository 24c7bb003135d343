"""Rigid-body loads and the linearised model: natural frequencies and the stiffness of the ODE.

Rigid body (no mesh compliance): shaft speeds are ``rho_i w_1`` with ``rho_i`` the product of the base
radius ratios up to shaft i. The gear of mesh k accelerates everything after it and carries the load:

    F_bt,k r_bg,k = sum_{i > k} J_i alpha_i rho_i / rho_{k+1} + T_L rho_n / rho_{k+1},   alpha_i = rho_i alpha_1,

with ``alpha_1`` the STEP profile's acceleration (speed drive) or ``(T_in - rho_n T_L) / J_eff``,
``J_eff = sum J_i rho_i^2`` (torque drive).

Linearised about mesh forces F_bt,k (deflection coordinates, see :mod:`gearcli.model.layout`): the
penetration is ``p0 = (F_n / K)^(1/e)``, ``F_n = |F_bt| / cos(beta_b)``, the normal stiffness
``k_n = e K p0^(e-1)`` and damping ``c(p0) = STEP(p0, 0, 0, d, C)``; along the line of action
``k_d = cos^2(beta_b) k_n``, ``c_d = cos^2(beta_b) c(p0)``. With ``R`` the map from free shaft speeds to
deflection rates (``delta' = R w``) the deflections obey

    delta'' = -M (K_d delta + C_d delta'),   M = R J^-1 R^T,

so the oscillating modes live in the m-dimensional deflection space (a torque drive's rigid-body mode
has no deflection). The first-order matrix ``[[0, I], [-M K_d, -M C_d]]`` gives the eigenvalues used for
the method choice; the undamped natural frequencies are ``sqrt(eig(M K_d)) / 2 pi``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearcli.model.contact_lines import contact_length_range
from gearcli.model.spec import ModelSpec
from gearcli.model.step import ramp, ramp_motion


def static_line_forces_N(spec: ModelSpec) -> np.ndarray:
    """F_bt of every mesh at full load in steady state (lossless), N (signed)."""
    rho = np.asarray(spec.speed_ratios)
    r_bg = np.array([m.base_radius_gear_m for m in spec.meshes])
    return spec.load.torque_Nm * rho[-1] / rho[1:] / r_bg


def rigid_line_forces_N(spec: ModelSpec, t: np.ndarray) -> np.ndarray:
    """F_bt,k(t) of the rigid train, shape (meshes, len(t)), N."""
    t = np.asarray(t, dtype=float)
    rho = np.asarray(spec.speed_ratios)
    J = np.asarray(spec.inertias_kg_m2)
    t_load = np.asarray(ramp(t, spec.load.ramp_s, spec.load.torque_Nm)) * np.ones_like(t)
    if spec.drive.kind == "speed":
        alpha1 = ramp_motion(t, spec.drive.ramp_s, spec.drive.speed_rad_s)[2] * np.ones_like(t)
    else:
        t_in = np.asarray(ramp(t, spec.drive.ramp_s, spec.drive.torque_Nm)) * np.ones_like(t)
        alpha1 = (t_in - rho[-1] * t_load) / float(J @ rho**2)
    out = np.empty((len(spec.meshes), t.size))
    for k, m in enumerate(spec.meshes):
        downstream = float(J[k + 1:] @ rho[k + 1:] ** 2) / rho[k + 1]
        out[k] = (downstream * alpha1 + t_load * rho[-1] / rho[k + 1]) / m.base_radius_gear_m
    return out


def rigid_input_torque_Nm(spec: ModelSpec, t: np.ndarray) -> np.ndarray:
    """Input torque of the rigid train under a speed drive: J_eff alpha_1 + rho_n T_L."""
    rho = np.asarray(spec.speed_ratios)
    alpha1 = ramp_motion(np.asarray(t, float), spec.drive.ramp_s, spec.drive.speed_rad_s)[2]
    t_load = ramp(np.asarray(t, float), spec.load.ramp_s, spec.load.torque_Nm)
    return float(np.asarray(spec.inertias_kg_m2) @ rho**2) * alpha1 + rho[-1] * t_load


def peak_rigid_line_forces_N(spec: ModelSpec, duration_s: float, samples: int = 801) -> np.ndarray:
    """Largest |F_bt,k| of the rigid train over [0, duration] (run-up inertia plus load)."""
    end = min(duration_s, max(spec.drive.ramp_s, spec.load.ramp_s, 0.0)) or duration_s
    t = np.linspace(0.0, end, samples)
    return np.max(np.abs(rigid_line_forces_N(spec, t)), axis=1)


@dataclass(frozen=True)
class Linearisation:
    line_forces_N: np.ndarray  # the operating point, F_bt per mesh
    penetration_m: np.ndarray  # p0 per mesh at that point
    stiffness_N_m: np.ndarray  # k_d along the line of action
    damping_Ns_m: np.ndarray  # c_d along the line of action
    eigenvalues: np.ndarray  # of the first-order deflection system (2m)
    natural_frequencies_Hz: np.ndarray  # undamped, ascending

    @property
    def max_abs_eigenvalue(self) -> float:
        return float(np.max(np.abs(self.eigenvalues))) if self.eigenvalues.size else 0.0

    @property
    def min_abs_eigenvalue(self) -> float:
        nz = np.abs(self.eigenvalues)[np.abs(self.eigenvalues) > 0]
        return float(nz.min()) if nz.size else 0.0


def _speed_map(spec: ModelSpec) -> np.ndarray:
    """R with delta' = R w over the free shafts."""
    m = len(spec.meshes)
    first = 1 if spec.drive.kind == "speed" else 0
    R = np.zeros((m, m + 1))
    for k, mesh in enumerate(spec.meshes):
        R[k, k], R[k, k + 1] = mesh.base_radius_pinion_m, -mesh.base_radius_gear_m
    return R[:, first:]


def linearise(spec: ModelSpec, line_forces_N, *, stiffest_phase: bool = False) -> Linearisation:
    """Linearise about the given mesh forces; ``stiffest_phase``: time-varying K at its largest factor."""
    F = np.abs(np.asarray(line_forces_N, dtype=float))
    kd, cd, pen = np.empty(F.size), np.empty(F.size), np.empty(F.size)
    for k, m in enumerate(spec.meshes):
        cb, e = m.cos_beta_b, m.exponent
        K = m.stiffness_N_m_e
        if m.time_varying and stiffest_phase:
            K *= contact_length_range(m.contact_ratio, m.overlap_ratio)[1]
        p0 = pen[k] = (F[k] / cb / K) ** (1.0 / e)
        kn = K if e == 1.0 else e * K * p0 ** (e - 1.0)
        s = min(p0 / m.full_damping_m, 1.0)
        kd[k], cd[k] = cb * cb * kn, cb * cb * m.damping_Ns_m * s * s * (3.0 - 2.0 * s)
    R = _speed_map(spec)
    first = 1 if spec.drive.kind == "speed" else 0
    M = R @ np.diag(1.0 / np.asarray(spec.inertias_kg_m2[first:])) @ R.T
    n = F.size
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-M * kd[None, :], -M * cd[None, :]]])
    sq = np.sqrt(kd)
    omega2 = np.linalg.eigvalsh(sq[:, None] * M * sq[None, :])
    freqs = np.sqrt(np.clip(omega2, 0.0, None)) / (2.0 * math.pi)
    return Linearisation(F, pen, kd, cd, np.linalg.eigvals(A), np.sort(freqs))
