"""A single spur mesh as a one-degree-of-freedom oscillator (the Kahraman & Singh 1990 model), built from
plain model parameters for the excitation tests: the pinion turns at a prescribed constant speed (an
infinitely heavy side), the gear is free and carries the load, so the dynamic transmission error
q = delta - e obeys

    m_e q'' + c q' + F_el(q) = F_s - m_e e'',   m_e = J_g / r_g^2,  F_s = T_L / r_g,

with F_el = k (q - b/2) on the drive flank, k (q + b/2) on the back flank, 0 in the gap (transverse =
normal: spur). Numbers: k = 2e8 N/m, r = 35 mm, z = 25, f_n = sqrt(k / m_e) / 2 pi = 1 kHz.
"""

from __future__ import annotations

import math

import numpy as np

from gearcli.model import DriveSpec, LoadSpec, MeshSpec, ModelSpec, TorsionalModel
from gearcli.model.outputs import sample
from gearcli.simulate.solver import integrate

K = 2e8  # N/m
R = 0.035  # m, both base radii
Z = 25  # pinion teeth: the mesh frequency is Z x the pinion speed
WN = 2 * math.pi * 1000.0  # rad/s
M_E = K / WN**2  # kg
J_G = M_E * R * R  # kg m^2
SAMPLES = 40  # per mesh period


def oscillator(r: float, *, te_m=(), te_phase_rad=(), ks=(), ks_phase_rad=(), zeta=0.05, backlash_m=0.0,
               p0_m=10e-6) -> TorsionalModel:
    """The oscillator at mesh frequency r x f_n, static deflection p0 (the load F_s = k p0)."""
    m = MeshSpec(base_radius_pinion_m=R, base_radius_gear_m=R, base_helix_angle_rad=0.0,
                 transverse_pressure_angle_rad=math.radians(20.0), helix_angle_rad=0.0, stiffness_N_m_e=K,
                 exponent=1.0, damping_Ns_m=0.0, full_damping_m=1e-4, backlash_m=backlash_m, pinion_teeth=Z,
                 damping_ratio=zeta, transmission_error_m=tuple(te_m), transmission_error_phase_rad=tuple(te_phase_rad),
                 stiffness_harmonics=tuple(ks), stiffness_harmonics_phase_rad=tuple(ks_phase_rad))
    return TorsionalModel(ModelSpec((m,), (1.0, J_G), DriveSpec("speed", r * WN / Z), LoadSpec(K * p0_m * R)))


def mesh_rad_s(model: TorsionalModel) -> float:
    return Z * model.spec.drive.speed_rad_s


def run(model: TorsionalModel, periods: int, *, q0: float, qd0: float = 0.0, rtol: float = 1e-9):
    """Integrate ``periods`` mesh periods from q = q0, q' = qd0; returns (t, q, integration, samples)."""
    t = np.linspace(0.0, periods * 2 * math.pi / mesh_rad_s(model), periods * SAMPLES + 1)
    y0 = model.initial_state()
    y0[0] = q0  # no TE at t = 0 when its amplitude is 0 there; see callers
    y0[1] -= qd0 / R  # delta' = R (w_p - w_g)
    it = integrate(model, t, "DOP853", rtol, y0=y0)
    assert it.status == 0, it.message
    s = sample(model.layout, t, it.y)
    return t, s.connectors[0].dte_m, it, s


def tail(x: np.ndarray, periods: int) -> np.ndarray:
    """The last ``periods`` whole mesh periods of a series sampled SAMPLES per period (one end point)."""
    return x[-(periods * SAMPLES + 1):-1]
