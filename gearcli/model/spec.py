"""Plain SI parameters of the torsional model, and their assembly from a design file and its design.

Shaft 1 carries pinion 1; shaft k+1 carries gear k and pinion k+1; the last shaft carries the last
gear. Mesh k joins shaft k (its pinion drives) and shaft k+1 (its gear is driven). Everything here is
SI (m, N, rad, s, kg m^2); the design file's engineering units are converted once, in
:func:`spec_from_design`: ``K`` in N/mm^e becomes N/m^e by ``K 1000^e``, damping N s/mm becomes N s/m
by ``x 1000``, lengths mm become m by ``/ 1000``.

Stage efficiency is not modelled in the dynamics (lossless meshes): a loss that depends on the
direction of power flow is not a smooth force law, and the seed paper's model has none. A stage with
``efficiency < 1`` gets a warning from the simulation.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

MM = 1e-3  # m per mm


@dataclass(frozen=True)
class MeshSpec:
    """One mesh along its transverse line of action (all SI)."""

    base_radius_pinion_m: float
    base_radius_gear_m: float
    base_helix_angle_rad: float
    transverse_pressure_angle_rad: float  # F_r = F_t tan(alpha_t), as the design's static forces
    helix_angle_rad: float  # F_a = F_t tan(beta)
    stiffness_N_m_e: float  # K in N/m^e
    exponent: float
    damping_Ns_m: float  # C, reached at the full-damping penetration
    full_damping_m: float  # d
    backlash_m: float = 0.0  # normal backlash j (gap of j/2 on each side)
    time_varying: bool = False
    contact_ratio: float = 1.5  # eps_alpha (used by time-varying stiffness)
    overlap_ratio: float = 0.0  # eps_beta
    pinion_teeth: int = 20  # mesh phase z_p theta_p / 2 pi
    normal_module_m: float = 0.0  # for the "penetration > 10 % of the module" warning (0: no check)
    static_tangential_N: float = 0.0  # design's F_t at full load (signed)
    efficiency: float = 1.0  # reported only; not in the dynamics

    @property
    def cos_beta_b(self) -> float:
        return math.cos(self.base_helix_angle_rad)


@dataclass(frozen=True)
class DriveSpec:
    """``kind = "speed"``: shaft 1 follows ``ramp(t, ramp_s, speed_rad_s)`` exactly (no DOF).
    ``kind = "torque"``: shaft 1 is free, driven by ``ramp(t, ramp_s, torque_Nm)``; every shaft starts
    at its nominal speed (rigid-body consistent), so the run begins in motion, not at rest."""

    kind: Literal["speed", "torque"]
    speed_rad_s: float
    ramp_s: float = 0.0
    torque_Nm: float = 0.0


@dataclass(frozen=True)
class LoadSpec:
    """Torque resisting the last shaft's rotation, ``ramp(t, ramp_s, torque_Nm)`` (negative: reversal)."""

    torque_Nm: float
    ramp_s: float = 0.0


@dataclass(frozen=True)
class ModelSpec:
    meshes: tuple[MeshSpec, ...]
    inertias_kg_m2: tuple[float, ...]  # one per shaft: len(meshes) + 1
    drive: DriveSpec
    load: LoadSpec

    def __post_init__(self) -> None:
        if len(self.inertias_kg_m2) != len(self.meshes) + 1:
            raise ValueError("need one inertia per shaft: len(meshes) + 1")
        if not all(j > 0 and math.isfinite(j) for j in self.inertias_kg_m2):
            raise ValueError("shaft inertias must be positive and finite")

    @property
    def speed_ratios(self) -> tuple[float, ...]:
        """Nominal speed of each shaft over the input speed (rigid kinematics on base radii)."""
        out = [1.0]
        for m in self.meshes:
            out.append(out[-1] * m.base_radius_pinion_m / m.base_radius_gear_m)
        return tuple(out)


def spec_from_design(cfg, design) -> ModelSpec:
    """Assemble the model parameters from a validated ``DesignFile`` and its ``DesignResult``."""
    from gearcli.design import contact_stiffness_N_mm_e

    meshes = []
    for k, st in enumerate(design.stages):
        law = cfg.contact_for(k)
        e = float(law.exponent)
        meshes.append(MeshSpec(
            base_radius_pinion_m=st.pinion.base_diameter_mm * MM / 2,
            base_radius_gear_m=st.gear.base_diameter_mm * MM / 2,
            base_helix_angle_rad=math.radians(st.base_helix_angle_deg),
            transverse_pressure_angle_rad=math.radians(st.transverse_pressure_angle_deg),
            helix_angle_rad=math.radians(st.helix_angle_deg),
            stiffness_N_m_e=float(contact_stiffness_N_mm_e(st, law)) * 1000.0**e,
            exponent=e,
            damping_Ns_m=law.damping_Ns_mm * 1000.0,
            full_damping_m=law.full_damping_penetration_mm * MM,
            backlash_m=st.backlash_mm * MM,
            time_varying=bool(law.time_varying),
            contact_ratio=st.contact_ratio_transverse,
            overlap_ratio=st.overlap_ratio,
            pinion_teeth=st.pinion.teeth,
            normal_module_m=st.normal_module_mm * MM,
            static_tangential_N=st.static_force_N.tangential,
            efficiency=st.efficiency,
        ))
    inp = cfg.input
    drive = DriveSpec(kind=inp.drive, speed_rad_s=inp.speed_rad_s_value, ramp_s=inp.ramp_s,
                      torque_Nm=inp.torque_Nm_value or 0.0)
    load = LoadSpec(torque_Nm=cfg.load.torque_Nm_value, ramp_s=cfg.load.ramp_s)
    return ModelSpec(tuple(meshes), tuple(s.inertia_kg_m2 for s in design.shafts), drive, load)
