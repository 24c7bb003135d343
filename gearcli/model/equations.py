"""The torsional model of a reducer: state layout, equations of motion, Jacobian, scales, energies.

Equations (SI; docs/physics.md, "Torsional model"). Shaft i has inertia J_i and speed w_i; mesh k joins shaft k
(pinion, base radius r_bp,k) and shaft k+1 (gear, r_bg,k):

    delta_k' = r_bp,k w_k - r_bg,k w_{k+1}
    J_i w_i' = r_bg,i-1 F_bt,i-1 - r_bp,i F_bt,i  (+ T_in on shaft 1 of a torque drive, - T_L on the last)

with ``F_bt = +-cos(beta_b) F_n`` and the Adams IMPACT law ``F_n = K g p^e + STEP(p, 0, 0, d, C) p'``
(clamped >= 0) on the penetration ``p`` beyond the gap of the normal approach ``h = cos(beta_b) delta``.
``g = L(phi) / L_mean`` for time-varying stiffness, else 1.

Energy balance, integrated with the states (quadrature states; cheaper and more accurate than
integrating sampled output afterwards, and exact to the integrator's own accuracy):

    W_in - W_load - E_damp - dKE - dU_const - W_el,tv = 0

``W_in = int T_in w_1``, ``W_load = int T_L w_n``, ``E_damp = int (F_n - K g p^e) p'`` (the damping
force's work, including the part the clamp at F_n = 0 removes), ``U = sum K p^(e+1)/(e+1)`` for meshes of
constant K, and for time-varying meshes ``W_el,tv = int K g p^e p'`` — the work done on their springs,
which equals their potential change plus the parametric work ``-int (dg/dt) K p^(e+1)/(e+1)`` that the
varying stiffness exchanges with the drive. The quadrature states get a huge absolute tolerance so
they never steer the step size (they do dilute the RMS error norm by sqrt(n_dyn / n), a ~20 % looser
effective tolerance for three stages; the accuracy study measures the actual error).

Initial state: every mesh undeflected (delta = 0); speeds rigid-body consistent, at rest for a speed
drive with a ramp, at the nominal speed for a speed drive without a ramp and for a torque drive.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from gearcli.model.codegen import compile_functions
from gearcli.model.layout import Layout
from gearcli.model.linear import static_line_forces_N
from gearcli.model.spec import ModelSpec
from gearcli.model.step import ramp_motion

QUADRATURE_ATOL = 1e20  # J: excludes the energy quadratures from step-size control
MIN_DEFLECTION_SCALE_M = 1e-6  # atol floor for unloaded meshes: 1 um of deflection


@dataclass(frozen=True)
class Energy:
    input_work_J: float
    load_work_J: float
    damping_loss_J: float
    kinetic_change_J: float
    potential_change_J: float
    parametric_work_J: float
    kinetic_end_J: float

    @property
    def residual_J(self) -> float:
        return (self.input_work_J - self.load_work_J - self.damping_loss_J - self.kinetic_change_J
                - self.potential_change_J + self.parametric_work_J)

    @property
    def residual_relative(self) -> float:
        scale = max(abs(self.input_work_J), abs(self.load_work_J), abs(self.kinetic_end_J))
        return abs(self.residual_J) / scale if scale > 0 else 0.0


class TorsionalModel:
    """Compiled equations of one scene. ``rhs(t, y)`` and ``jac(t, y)`` are plain functions of the
    state layout documented in :mod:`gearcli.model.layout`; ``source`` is their generated code."""

    def __init__(self, spec: ModelSpec):
        self.spec = spec
        self.layout = Layout.of(spec)
        self.rhs: Callable[[float, np.ndarray], np.ndarray]
        self.jac: Callable[[float, np.ndarray], np.ndarray]
        self.rhs, self.jac, self.source = compile_functions(self.layout)

    @property
    def n_states(self) -> int:
        return self.layout.n_states

    # ------------------------------------------------------------------------------- start, scales
    def initial_state(self) -> np.ndarray:
        lay = self.layout
        y0 = np.zeros(lay.n_states)
        w_in = ramp_motion(0.0, lay.drive.ramp_s, lay.drive.speed_rad_s)[1] if lay.speed_drive \
            else lay.drive.speed_rad_s
        for i, rho in zip(lay.free_shafts, self.spec.speed_ratios[lay.free_shafts.start:]):
            y0[lay.i_omega(i)] = rho * w_in
        return y0

    def deflection_scales_m(self) -> np.ndarray:
        """Static deflection of each mesh at full load, floored (backlash half-gap, 1 um), m."""
        F = np.abs(static_line_forces_N(self.spec))
        out = np.empty(F.size)
        for k, m in enumerate(self.spec.meshes):
            cb = m.cos_beta_b
            p0 = (F[k] / cb / m.stiffness_N_m_e) ** (1.0 / m.exponent)
            out[k] = max(p0 / cb, 0.5 * m.backlash_m / cb, MIN_DEFLECTION_SCALE_M)
        return out

    def speed_scales_rad_s(self) -> np.ndarray:
        """Nominal speed of each free shaft, rad/s."""
        rho = self.spec.speed_ratios
        return np.array([rho[i] * self.spec.drive.speed_rad_s for i in self.layout.free_shafts])

    def atol(self, rtol: float) -> np.ndarray:
        """Per-state absolute tolerance: rtol x the state's natural scale."""
        lay = self.layout
        parts = [rtol * self.deflection_scales_m(), rtol * self.speed_scales_rad_s()]
        if lay.has_theta_state:
            parts.append(np.array([rtol * 2.0 * math.pi / max(m.pinion_teeth for m in lay.meshes)]))
        parts.append(np.full(lay.n_quad, QUADRATURE_ATOL))
        return np.concatenate(parts)

    # ------------------------------------------------------------------------------------ energy
    def energy(self, s, Y: np.ndarray) -> Energy:
        """Energy balance over the run from its samples ``s`` (``outputs.Sampled``) and states ``Y``."""
        from gearcli.model.outputs import kinetic_energy, potential_energy

        lay = self.layout
        q = lay.i_quad
        ke = kinetic_energy(lay, s.omega_rad_s[:, [0, -1]])
        u_const = potential_energy(lay, s, time_varying=False)
        u_tv = potential_energy(lay, s, time_varying=True)
        d_u_tv = float(u_tv[-1] - u_tv[0])
        w_el_tv = float(Y[q + 3, -1] - Y[q + 3, 0]) if lay.n_tv else 0.0
        return Energy(
            input_work_J=float(Y[q, -1] - Y[q, 0]),
            load_work_J=float(Y[q + 1, -1] - Y[q + 1, 0]),
            damping_loss_J=float(Y[q + 2, -1] - Y[q + 2, 0]),
            kinetic_change_J=float(ke[1] - ke[0]),
            potential_change_J=float(u_const[-1] - u_const[0]) + d_u_tv,
            parametric_work_J=d_u_tv - w_el_tv,
            kinetic_end_J=float(ke[1]),
        )
