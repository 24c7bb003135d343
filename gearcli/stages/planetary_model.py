"""A planetary stage's model (the model facet's :class:`~gearcli.stages.model.PlanetaryModelKind` builds it):
its spec in SI, placed by :func:`gearcli.model.planet_assembly.place_planetary`. Imported by the facet on first
use, so that a file without planetary stages creates none of its classes (start-up time of the one-shot run).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace
from typing import TYPE_CHECKING

from gearcli.core.records import record
from gearcli.design.planetary_balance import balance, willis_speeds
from gearcli.design.stiffness import (
    calibration_line_force_N,
    iso6336_normal_stiffness_N_mm,
    iso_reference_normal_force_N,
    law_coefficient_N_mm_e,
)
from gearcli.model.parts import Body, Connector
from gearcli.model.planet_assembly import place_planetary
from gearcli.model.planet_phasing import stage_contact_phase_cycles, sun_drives
from gearcli.model.planet_spec import PlanetarySpec
from gearcli.model.spec import MM, MeshSpec
from gearcli.results import StageResult

if TYPE_CHECKING:
    from gearcli.config.schema import DesignFile


@record
class PlanetaryModel(PlanetarySpec):
    """A planetary stage's model: its spec, placed by :func:`gearcli.model.planet_assembly.place_planetary`."""

    def place(self, k: int, bodies: list[Body], conns: list[Connector], body: Callable[..., None],
              out_inertia: float) -> None:
        place_planetary(self, k, bodies, conns, body, out_inertia)



def planetary_model(cfg: DesignFile, st: StageResult, k: int, sun_mesh: MeshSpec) -> PlanetaryModel:
    """A planetary stage's model (SI): levers from the base radii, the members' inertias, both mesh laws."""
    p = st.planetary
    assert p is not None
    law = cfg.contact_for(k)
    e = float(law.exponent)
    ring = p.planet_ring
    k_n = iso6336_normal_stiffness_N_mm(ring.iso6336_mesh_stiffness_N_mm_um, ring.face_width_mm,
                                        math.radians(st.base_helix_angle_deg))
    f_n0 = iso_reference_normal_force_N(ring.static_force_N.tangential, ring.face_width_mm,
                                        math.radians(st.normal_pressure_angle_deg), math.radians(st.helix_angle_deg))
    coefficient = law_coefficient_N_mm_e(law.stiffness, law.exponent, hertz=ring.hertz_stiffness_N_mm1_5,
                                         iso_normal_stiffness_N_mm=k_n, iso_reference_normal_force_N=f_n0)
    eta_m = p.mesh_efficiency  # each planet mesh loses in the carrier's frame (docs/planetary.md)
    sun_mesh = replace(sun_mesh, efficiency=eta_m)
    ring_mesh = replace(sun_mesh, stiffness_N_m_e=float(coefficient) * 1000.0**e,
                        contact_ratio=ring.contact_ratio_transverse, overlap_ratio=ring.overlap_ratio,
                        iso_normal_stiffness_N_m=k_n * 1000.0,
                        linearisation_line_force_N=calibration_line_force_N(
                            law.stiffness, ring.face_width_mm, math.radians(st.normal_pressure_angle_deg),
                            math.radians(st.helix_angle_deg), math.radians(st.base_helix_angle_deg)))
    r_bs, r_bp, r_br = (0.5 * MM * g.base_diameter_mm for g in (p.sun, p.planet, p.ring))
    unit = willis_speeds(p.sun.teeth, p.ring.teeth, p.fixed, p.input)
    third = next(m for m in ("sun", "carrier", "ring") if m not in (p.input, p.output))
    inertia = {"sun": p.sun.inertia_kg_m2, "ring": p.ring.inertia_kg_m2, "carrier": p.carrier.inertia_kg_m2}
    return PlanetaryModel(
        fixed=p.fixed, input=p.input, output=p.output, planets=p.planet_count, sun_teeth=p.sun.teeth,
        planet_teeth=p.planet.teeth, ring_teeth=p.ring.teeth, base_radius_sun_m=r_bs, base_radius_planet_m=r_bp,
        base_radius_ring_m=r_br, lever_sun_carrier_m=r_bs + r_bp, lever_ring_carrier_m=r_br - r_bp,
        third_inertia_kg_m2=inertia[third], planet_inertia_kg_m2=p.planet.inertia_kg_m2, sun_mesh=sun_mesh,
        ring_mesh=ring_mesh, unit_speeds=(unit["sun"], unit["carrier"], unit["ring"]),
        planet_offsets_m=tuple(e * 1e-6 for e in _planet_errors_um(cfg, k)),
        planet_angles_rad=_running_angles_rad(cfg, k, p.planet_angles_deg, p.planet_count),
        ring_contact_phase_cycles=_ring_contact_phase(st, unit),
        **_loss_factors(p, eta_m, -1.0 if (cfg.load.torque_Nm_value or 0.0) < 0.0 else 1.0))


def _running_angles_rad(cfg: DesignFile, k: int, angles_deg: tuple[float, ...] | list[float] | None,
                        planets: int) -> tuple[float, ...]:
    """Each planet's position from planet 1 in the stage's running direction, the sense of rotation its mesh phases
    follow (Parker & Lin; :meth:`PlanetarySpec.mesh_phase_cycles`): the planets sit at ``angles_deg`` (declared, or
    360 j / N) clockwise from the housing's y seen from the input end (the frame of ``[input] rotation`` and of the
    shaft statics, :mod:`gearcli.design.shafts`), so in a stage whose input member turns counter-clockwise planet j
    is ψ_1 − ψ_j ahead of planet 1, not ψ_j − ψ_1 (the mirror image of the clockwise train). Empty (2π j / N) for
    equally spaced planets turning clockwise, as before."""
    sense = _input_sense(cfg, k)
    if not _unequal(cfg, k):
        return () if sense > 0 else tuple(-2.0 * math.pi * j / planets for j in range(planets))
    assert angles_deg is not None
    return tuple(sense * math.radians(a - angles_deg[0]) for a in angles_deg)


def _input_sense(cfg: DesignFile, k: int) -> int:
    """The sense of rotation of stage k's input member, +1 clockwise seen from the input end (``[input] rotation``
    for the first stage): a parallel stage reverses it, a planetary one turns its output member as Willis says
    (the senses :func:`gearcli.design.shafts.layout` gives the shafts)."""
    sense = 1 if cfg.input.rotation == "cw" else -1
    for stage in cfg.stage[:k]:
        if getattr(stage, "type", "parallel") != "planetary":
            sense = -sense
            continue
        output = next(m for m in ("sun", "carrier", "ring") if m not in (stage.fixed, stage.input))  # type: ignore[union-attr]
        if willis_speeds(stage.sun.teeth, stage.ring.teeth, stage.fixed, stage.input)[output] < 0:  # type: ignore[union-attr]
            sense = -sense
    return sense


def _unequal(cfg: DesignFile, k: int) -> bool:
    """The stage declares its planets' positions (``planet.angles_deg``)."""
    planet = getattr(cfg.stage[k], "planet", None)
    return planet is not None and planet.angles_deg is not None


def _loss_factors(p, eta_m: float, load_sign: float) -> dict[str, float]:
    """The planet meshes' static (driving-side) forces over the lossless ones, in the power flow of the load's
    sign, and the stage's efficiencies (:mod:`gearcli.design.planetary_balance`)."""
    def factors(sign: float) -> tuple[float, float, float]:
        lossless = balance(p.sun.teeth, p.ring.teeth, p.fixed, p.input, 1.0, sign)
        lossy = balance(p.sun.teeth, p.ring.teeth, p.fixed, p.input, eta_m, sign)
        scale = abs(lossless.torques[p.output]) / abs(lossy.torques[p.output])  # |T_sun| lossy / lossless, same T_out
        return lossy.sun_mesh * scale, lossy.ring_mesh * scale, lossy.efficiency

    sun, ring, _ = factors(load_sign)
    other_sun, other_ring, _ = factors(-load_sign)
    # the efficiencies forward and back whatever the nominal load's sign (was the nominal flow's as "efficiency":
    # the reversed one under a reversed load, which a load law turning forward at its operating point then took)
    forward, back = (factors(sign)[2] for sign in (1.0, -1.0))
    return {"sun_force_factor": sun, "ring_force_factor": ring, "efficiency": forward, "reverse_efficiency": back,
            "other_sun_force_factor": other_sun, "other_ring_force_factor": other_ring}


def _ring_contact_phase(st: StageResult, unit: dict[str, float]) -> float:
    """Planet 1's ring-mesh contact-line phase against its sun mesh's (:mod:`gearcli.model.planet_phasing`)."""
    p = st.planetary
    assert p is not None
    return stage_contact_phase_cycles(st, sun_drives(unit, p.input, p.sun.teeth, p.ring.teeth))


def _planet_errors_um(cfg: DesignFile, k: int) -> list[float]:
    stage = cfg.stage[k]
    planet = getattr(stage, "planet", None)
    return list(planet.position_error_um or []) if planet is not None else []
