"""Static tooth forces on the pinion's reference (pitch) circle (docs/physics.md, "Design calculations", seed section 4.2)."""

from __future__ import annotations

import math

from gearcli.results import StaticForces


def static_forces(pinion_torque_Nmm: float, pinion_pitch_radius_mm: float, normal_pressure_rad: float,
                  transverse_pressure_rad: float, helix_rad: float) -> StaticForces:
    """F_t = T_1 / r_1, F_r = F_t tan α_t (= F_t tan α_n / cos β), F_a = F_t tan β,
    F_n = F_t / (cos α_n cos β), in N; signed with the torque (negative under load reversal).

    These are the ISO 6336-1 nominal forces at the reference circle; with profile shift the working
    pitch circle differs slightly, which this convention ignores on purpose.
    """
    f_t = pinion_torque_Nmm / pinion_pitch_radius_mm
    return StaticForces(
        tangential=f_t,
        radial=f_t * math.tan(transverse_pressure_rad),
        axial=f_t * math.tan(helix_rad),
        normal=normal_force_N(f_t, normal_pressure_rad, helix_rad),
    )


def normal_force_N(tangential_force_N: float, normal_pressure_rad: float, helix_rad: float) -> float:
    """F_n = F_t / (cos α_n cos β): the tooth normal force behind a tangential force."""
    return tangential_force_N / (math.cos(normal_pressure_rad) * math.cos(helix_rad))
