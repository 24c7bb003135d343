"""The model facet of a stage kind (the model layer, beside ``gearcli.scene``): the stage's mesh law as the
model signs it and its own model (bodies and connectors), or none where the stage is the chain's pair.

``gearcli.scene`` asks :func:`model_kind` for each designed stage; ``gearcli.model.assembly`` places a stage
model it is given (``ModelSpec.stage_models``) through its ``place``, and never asks which kind it is.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Protocol, cast

from gearcli.core import plugins
from gearcli.design.planetary_balance import balance, willis_speeds
from gearcli.design.stiffness import (
    calibration_line_force_N,
    iso6336_normal_stiffness_N_mm,
    iso_reference_normal_force_N,
    law_coefficient_N_mm_e,
)
from gearcli.errors import GearcliError, PluginError
from gearcli.model.parts import Body, Connector
from gearcli.model.planet_assembly import place_planetary
from gearcli.model.planet_phasing import stage_contact_phase_cycles, sun_drives
from gearcli.model.spec import MM, MeshSpec, PlanetarySpec, StageModel
from gearcli.results import StageResult
from gearcli.stages import kinds

if TYPE_CHECKING:
    from gearcli.config.schema import DesignFile


#: the design -> model adapter's mesh law of a gear pair: (design file, stage result, k) -> MeshSpec
PairMesh = Callable[["DesignFile", StageResult, int], MeshSpec]


class ModelKind(Protocol):
    """What the design -> model adapter (``gearcli.scene``) asks of a stage kind."""

    def line(self, cfg: DesignFile, st: StageResult, k: int, pair_mesh: PairMesh) -> MeshSpec:
        """The stage's line of action as the model reads it (``ModelSpec.meshes[k]``: its levers, its angles, its
        static force signed as the model's): a gear pair's mesh law (``pair_mesh``), a belt's span."""

    def stage_model(self, cfg: DesignFile, st: StageResult, k: int, mesh: MeshSpec) -> StageModel | None:
        """The stage's own model (SI), or None: the chain's pair of ``mesh``."""


def model_kind(stage: object) -> ModelKind:
    """The model facet of a stage table or stage result (by its ``type``)."""
    return cast(ModelKind, kinds.facet(kinds.kind_of(stage), "model"))


def checked_losses(st: StageResult, k: int, own: StageModel | None) -> StageModel | None:
    """A plug-in's stage model ``own`` of stage ``st`` (0-based ``k``) whose losses are its design's, or a
    :class:`~gearcli.errors.PluginError` naming the kind. The dynamics lose only what a connector's element loses
    (a lossy element: the built-in ``mesh`` with ``MeshSpec.efficiency``); a stage model's own ``efficiency`` acts
    only through a planetary's planet meshes (connectors with a ``load_body``), and the steady-state and rigid-start
    estimates read it (:meth:`gearcli.model.assembly.Layout.train_efficiency`). So a stage model that places no
    planet mesh must give ``efficiency`` and ``reverse_efficiency`` 1, and its connectors must lose the design's
    (1 - eta): else the simulated forces before the stage are eta x the design's (docs/plugins.md)."""
    if own is None or plugins.origin(own).split(".")[0] == "gearcli":
        return own
    where = f'stage type "{kinds.kind_of(st)}" ({plugins.origin(own)}): its stage model'
    bodies: list[Body] = [Body(1.0, "input", 1.0)]
    conns: list[Connector] = []

    def body(inertia: float, label: str, ratio: float = 1.0) -> None:
        bodies.append(Body(float(inertia), label, ratio))

    try:
        own.place(k, bodies, conns, body, 1.0)
        if any(c.load_body >= 0 for c in conns):
            return own
        eta = math.prod(c.efficiency for c in conns if c.lossy)
        given = {n: float(getattr(own, n)) for n in ("efficiency", "reverse_efficiency")}
    except GearcliError:
        raise
    except Exception as exc:  # third-party code: named, with what it raised
        raise PluginError(f"{where}'s place raised {type(exc).__name__}: {' '.join(str(exc).split())[:300]}") \
            from exc
    design_eta = float(getattr(st, "efficiency", 1.0))
    for name, value in given.items():
        if value != 1.0:
            raise PluginError(f"{where} gives {name} = {value:.6g}, which no element of it loses: the dynamics "
                              "lose only what its connectors' elements lose; give the model 1 and place a lossy "
                              "element (the built-in mesh with MeshSpec.efficiency; docs/plugins.md)")
    if not math.isclose(eta, design_eta, rel_tol=1e-9, abs_tol=1e-12):
        raise PluginError(f"{where}'s connectors lose {1.0 - eta:.6g} of the power, its design {1.0 - design_eta:.6g} "
                          f"(efficiency {design_eta:.6g}): the simulated forces before stage {k + 1} would be "
                          f"{eta / design_eta:.6g} x the design's; place a lossy element of the design's efficiency "
                          "(the built-in mesh with MeshSpec.efficiency; docs/plugins.md)")
    return own


class ParallelModel:
    """A parallel stage is the chain's pair: its mesh between its input and output shafts' bodies."""

    def line(self, cfg: DesignFile, st: StageResult, k: int, pair_mesh: PairMesh) -> MeshSpec:
        return pair_mesh(cfg, st, k)

    def stage_model(self, cfg: DesignFile, st: StageResult, k: int, mesh: MeshSpec) -> StageModel | None:
        return None


@dataclass(frozen=True)
class PlanetaryModel(PlanetarySpec):
    """A planetary stage's model: its spec, placed by :func:`gearcli.model.planet_assembly.place_planetary`."""

    def place(self, k: int, bodies: list[Body], conns: list[Connector], body: Callable[..., None],
              out_inertia: float) -> None:
        place_planetary(self, k, bodies, conns, body, out_inertia)


class PlanetaryModelKind:
    """A planetary stage: the sun–planet mesh law signed by the output member's moment balance, and its
    :class:`PlanetaryModel` (levers from the base radii, the members' inertias, both mesh laws)."""

    def line(self, cfg: DesignFile, st: StageResult, k: int, pair_mesh: PairMesh) -> MeshSpec:
        """The sun–planet mesh law with a planet mesh's static F_t signed as its deflection is in the model: the
        moment balance of the output member, N c_out F = T_out sign(w_out), c_out = -r_bs (sun), r_bs + r_br
        (carrier), -r_br (ring) (:func:`gearcli.model.planet_assembly.place_planetary`)."""
        mesh = pair_mesh(cfg, st, k)
        p = st.planetary
        assert p is not None
        sign_out = 1.0 if willis_speeds(p.sun.teeth, p.ring.teeth, p.fixed, p.input)[p.output] >= 0 else -1.0
        sign = sign_out * (1.0 if p.output == "carrier" else -1.0)
        return replace(mesh, static_tangential_N=sign * mesh.static_tangential_N)

    def stage_model(self, cfg: DesignFile, st: StageResult, k: int, mesh: MeshSpec) -> StageModel | None:
        return _planetary(cfg, st, k, mesh)


def _planetary(cfg: DesignFile, st: StageResult, k: int, sun_mesh: MeshSpec) -> PlanetaryModel:
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
        planet_angles_rad=tuple(math.radians(a - p.planet_angles_deg[0]) for a in p.planet_angles_deg)
        if _unequal(cfg, k) else (),
        ring_contact_phase_cycles=_ring_contact_phase(st, unit),
        **_loss_factors(p, eta_m, -1.0 if (cfg.load.torque_Nm_value or 0.0) < 0.0 else 1.0))


def _unequal(cfg: DesignFile, k: int) -> bool:
    """The stage declares its planets' positions (``planet.angles_deg``)."""
    planet = getattr(cfg.stage[k], "planet", None)
    return planet is not None and planet.angles_deg is not None


def _loss_factors(p, eta_m: float, load_sign: float) -> dict[str, float]:
    """The planet meshes' static (driving-side) forces over the lossless ones, in the power flow of the load's
    sign, and the stage's efficiencies (:mod:`gearcli.design.planetary_balance`)."""
    lossless = balance(p.sun.teeth, p.ring.teeth, p.fixed, p.input, 1.0, load_sign)
    lossy = balance(p.sun.teeth, p.ring.teeth, p.fixed, p.input, eta_m, load_sign)
    scale = abs(lossless.torques[p.output]) / abs(lossy.torques[p.output])  # |T_sun| lossy / lossless, same T_out
    back = balance(p.sun.teeth, p.ring.teeth, p.fixed, p.input, eta_m, -1.0)
    return {"sun_force_factor": lossy.sun_mesh * scale, "ring_force_factor": lossy.ring_mesh * scale,
            "efficiency": lossy.efficiency, "reverse_efficiency": back.efficiency}


def _ring_contact_phase(st: StageResult, unit: dict[str, float]) -> float:
    """Planet 1's ring-mesh contact-line phase against its sun mesh's (:mod:`gearcli.model.planet_phasing`)."""
    p = st.planetary
    assert p is not None
    return stage_contact_phase_cycles(st, sun_drives(unit, p.input, p.sun.teeth, p.ring.teeth))


def _planet_errors_um(cfg: DesignFile, k: int) -> list[float]:
    stage = cfg.stage[k]
    planet = getattr(stage, "planet", None)
    return list(planet.position_error_um or []) if planet is not None else []


kinds.provide(kinds.PARALLEL, "model", ParallelModel())
kinds.provide("planetary", "model", PlanetaryModelKind())
