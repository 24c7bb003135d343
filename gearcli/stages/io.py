"""The output facet of a stage kind (the io layer): its rows in the design tables, its own tables, its JSON
stage; registered when ``gearcli.io`` is imported (``gearcli/io/__init__.py``).

``gearcli.io.tables``, and ``serialize`` ask the kind (their own protocols of what they read,
looked up in :mod:`gearcli.stages.kinds`) and never which kind a stage is.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from gearcli.core.jsontypes import JsonObject
from gearcli.core.records import record
from gearcli.stages import kinds

if TYPE_CHECKING:  # the tables' modules (rich) are imported by the table builders below, only when tables are made
    from rich.console import RenderableType

    from gearcli.io.units import OutputUnits
    from gearcli.results import DesignResult, RatedMesh, StageResult
    from gearcli.simulate.results import SimulationResult, StageDynamics

_Doc = dict[str, Any]

#: the stage keys a planetary stage's JSON keeps before its members (the rest is its sun–planet mesh's)
_STAGE_KEYS = ("index", "ratio", "efficiency", "normal_module_mm", "transverse_module_mm", "normal_pressure_angle_deg",
               "transverse_pressure_angle_deg", "helix_angle_deg", "base_helix_angle_deg")


class ParallelOutput:
    """A parallel stage: pinion and gear in the common tables, today's JSON keys (no ``type``)."""

    pair_members = True
    pair_names: tuple[str, str] | None = None
    load_sharing = False

    def design_tables(self, r: DesignResult, stages: list[StageResult]) -> list[RenderableType]:
        return []

    def simulation_tables(self, r: SimulationResult, stages: list[StageDynamics]) -> list[RenderableType]:
        return []

    def json_stage(self, stage: _Doc) -> _Doc:
        stage.pop("type", None)  # a parallel stage's JSON has no type (today's keys)
        stage.pop("planetary", None)
        if isinstance(stage.get("rating"), dict):  # K_gamma belongs to planetary stages (a parallel rating: today's keys)
            stage["rating"].pop("K_gamma", None)
        return stage

    def json_simulated_stage(self, stage: JsonObject) -> JsonObject:
        return stage


class PlanetaryOutput:
    """A planetary stage: its members and planet–ring mesh in a table of their own, its JSON with ``type``,
    the members and the two meshes per planet."""

    pair_members = False
    pair_names = ("sun", "planet")
    load_sharing = True

    def design_tables(self, r: DesignResult, stages: list[StageResult]) -> list[RenderableType]:
        from gearcli.io.units import of_result  # lazy: the io layer's units, only when tables are made

        return [*_planetary_design(stages, of_result(r)), *_planet_ring_rating(stages)]

    def simulation_tables(self, r: SimulationResult, stages: list[StageDynamics]) -> list[RenderableType]:
        return []  # its planets' tables are the run's (``io.tables``), in today's place

    def json_stage(self, stage: _Doc) -> _Doc:
        """A planetary stage's JSON: type, members (sun, planet, ring, carrier), ratio and the two meshes per planet."""
        p = stage.pop("planetary")
        stage.pop("type")
        head = {k: stage.pop(k) for k in _STAGE_KEYS}
        stage.pop("pinion")
        stage.pop("gear")
        ring_mesh = p.pop("planet_ring")
        ring_mesh.pop("tip_clearance_with_allowances_mm", None)  # the warning's data only (docs/planetary.md)
        ring_mesh.pop("planet_form_from_tangent_mm", None)  # as the tip clearances: the interference warning's data
        p.pop("ring_treatment", None)  # the ring's tip_thickness warning's (its material's, in the file)
        ring_mesh = {"backlash_mm": stage.get("backlash_mm"), **ring_mesh}  # the stage's, which the model gives both
        planet = {**p.pop("planet"), "count": p["planet_count"], "mass_kg": p.pop("planet_mass_kg")}
        return {**head, "type": "planetary", "ratio": p.pop("ratio"), "sun": p.pop("sun"), "planet": planet,
                "ring": p.pop("ring"), "carrier": p.pop("carrier"), **p,
                "meshes": [{"name": "sun_planet", **stage}, {"name": "planet_ring", **ring_mesh}]}

    def json_simulated_stage(self, stage: JsonObject) -> JsonObject:
        return stage


@record
class _RatedMesh:
    """A planet–ring mesh as ``rating_table`` reads a stage: its stage's index and its rating."""

    index: int
    rating: RatedMesh


def _planet_ring_rating(stages: list[StageResult]) -> list[RenderableType]:
    """The planet–ring meshes' rating (``meshes[1].rating``), below the planetary stages' table."""
    from gearcli.io.tables import rating_table  # lazy: rich, only when tables are made (JSON and CSV need none)

    meshes = [_RatedMesh(st.index, st.planetary.planet_ring.rating) for st in stages
              if st.planetary is not None and st.planetary.planet_ring.rating is not None]
    if not meshes:
        return []
    return [rating_table(meshes, "planet–ring mesh strength rating, {standard} (p planet, g ring)")]


def _planetary_design(stages: list[StageResult], u: OutputUnits) -> list[RenderableType]:
    """The planetary stages (their columns above are the sun–planet mesh): members and the planet–ring mesh; speeds
    and torques in the design file's units ``u`` (DESIGN §12)."""
    from gearcli.io.table_kit import _g, _quantity_table  # lazy: rich, only when tables are made

    speed, torque = u.speed_label, u.torque_label

    s = [st for st in stages if st.planetary is not None]
    ps = [st.planetary for st in stages if st.planetary is not None]
    if not ps:
        return []
    rows = [
        ("held / driven / output", [f"{p.fixed} / {p.input} / {p.output}" for p in ps]),
        ("teeth sun / planet / ring, planets", [f"{p.sun.teeth} / {p.planet.teeth} / {p.ring.teeth}, "
                                                f"{p.planet_count}" for p in ps]),
        ("ratio |ω_in/ω_out|", [_g(p.ratio, 6) for p in ps]),
        *(_member_row(m, ps, u) for m in ("sun", "carrier", "ring")),
        (f"moment balance T_sun + T_carrier + T_ring [{torque}]", [_balance(p, u) for p in ps]),
        ("efficiency stage η / carrier-held η_0 / per mesh η_m",
         [f"{_g(p.stage_efficiency, 4)} / {_g(p.basic_efficiency, 5)} / {_g(p.mesh_efficiency, 5)}"
          for p in _efficiencies(s)]),
        (f"planet speed relative to the carrier [{speed}]", [_g(u.speed_from_deg_s(p.planet.speed_deg_s)) for p in ps]),
        (f"per planet, carrier frame: sun-side / planet torque [{torque}]",  # each the member's own (after its losses)
         [f"{_g(u.torque_from_Nm(math.copysign(p.sun.torque_Nm / p.planet_count, st.pinion.torque_Nm)))} / "
          f"{_g(u.torque_from_Nm(p.planet.torque_Nm))}" for st, p in zip(s, ps, strict=True)]),
        ("per planet, carrier frame: rolling power [kW]", [_g(abs(st.pinion.power_kW)) for st in s]),
        ("ring d / d_a / d_f [mm]", [f"{_g(p.ring.pitch_diameter_mm)} / {_g(p.ring.tip_diameter_mm)} / "
                                     f"{_g(p.ring.root_diameter_mm)}" for p in ps]),
        ("planet–ring α_wt [°]", [_g(p.planet_ring.working_pressure_angle_deg) for p in ps]),
        ("planet–ring ε_α", [_g(p.planet_ring.contact_ratio_transverse, 4) for p in ps]),
        ("planet–ring c′ / c_γα [N/(mm·µm)]", [f"{_g(p.planet_ring.iso6336_single_pair_stiffness_N_mm_um)} / "
                                              f"{_g(p.planet_ring.iso6336_mesh_stiffness_N_mm_um)}" for p in ps]),
        ("planet–ring law K [N/mm^e] / tangent / ISO k_n [N/mm]", [_ring_law(p.planet_ring.mesh_stiffness) for p in ps]),
        ("F_t per planet: sun–planet / planet–ring [N]", [f"{_g(st.static_force_N.tangential)} / "
                                                        f"{_g(p.planet_ring.static_force_N.tangential)}"
                                                        for st, p in zip(s, ps, strict=True)]),
        ("carrier inertia (own + planets) [kg·m²]", [_g(p.carrier.inertia_kg_m2) for p in ps]),
        ("planets at [°], load-sharing K_γ", [f"{', '.join(_g(a, 5) for a in p.planet_angles_deg)}, "
                                             f"{_g(p.load_sharing_factor, 4)}" for p in ps]),
        *_ring_allowance_rows(ps),
    ]
    return [_quantity_table("planetary stages (the columns above: their sun–planet mesh, z1 sun, z2 planet)",
                            [f"stage {st.index}" for st in s], rows)]


def _ring_allowance_rows(ps) -> list[tuple[str, list[str]]]:
    """The planet–ring mesh's tooth-thickness allowances (docs/planetary.md), where any stage has them."""
    if all(p.planet_ring.backlash_circumferential_mm is None for p in ps):
        return []
    from gearcli.io.table_kit import limits  # lazy: rich, only when tables are made

    return [("ring x_E e / i", [limits(p.ring.generating_profile_shift, 4) for p in ps]),
            ("ring d_f e / i [mm]", [limits(p.ring.manufactured_root_diameter_mm, 3) for p in ps]),
            ("planet–ring backlash j_t max / min [mm]", [limits(p.planet_ring.backlash_circumferential_mm, 3)
                                                         for p in ps]),
            ("planet–ring backlash j_n max / min [mm]", [limits(p.planet_ring.backlash_normal_mm, 3) for p in ps]),
            ("planet–ring ε_α e / m / i", [limits(p.planet_ring.contact_ratio_transverse_with_allowances, 3)
                                           for p in ps])]


def _ring_law(law) -> str:
    """The planet–ring mesh's law (its ``mesh_stiffness``, DESIGN section 13; the stage's law, named in the loads table)
    as the loads table gives the sun–planet mesh's: K, its tangent where the models linearise it, ISO's k_n beside it."""
    from gearcli.io.table_kit import _g  # lazy: rich, only when tables are made

    if law is None:
        return "—"
    return f"{_g(law.K, 4)} / {_g(law.linearised_N_mm, 4)} / {_g(law.iso_N_mm, 4)}"


def _member_row(member: str, ps, u: OutputUnits) -> tuple[str, list[str]]:
    """A member's own speed, torque (its magnitude) and power, in the housing's frame and the file's units."""
    from gearcli.io.table_kit import _g  # lazy: rich, only when tables are made

    def cell(g) -> str:
        return (f"{_g(u.speed_from_deg_s(g.speed_deg_s))} / {_g(u.torque_from_Nmm(g.torque_Nmm))} / "
                f"{_g(abs(g.power_kW))}")

    return (f"{member}: speed [{u.speed_label}] / torque [{u.torque_label}] / power [kW]",
            [cell(getattr(p, member)) for p in ps])


def _balance(p, u: OutputUnits) -> str:
    """The signed external torques (positive in the input member's sense) and their sum."""
    from gearcli.io.table_kit import _g  # lazy: rich, only when tables are made

    m = p.moment_balance_Nm
    if not m:
        return "—"
    terms = [u.torque_from_Nm(m[k]) for k in ("sun", "carrier", "ring")]
    text_ = _g(terms[0]) + "".join(f" {'-' if v < 0 else '+'} {_g(abs(v))}" for v in terms[1:])
    return f"{text_} = {_g(sum(terms), 2)}"


@record
class _Efficiencies:
    """A stage's efficiencies as its table prints them: the stage's, the basic and the mesh's."""

    stage_efficiency: float
    basic_efficiency: float
    mesh_efficiency: float


def _efficiencies(stages) -> list[_Efficiencies]:
    return [_Efficiencies(st.efficiency, st.planetary.basic_efficiency, st.planetary.mesh_efficiency) for st in stages]


kinds.provide(kinds.PARALLEL, "io", ParallelOutput())
kinds.provide("planetary", "io", PlanetaryOutput())
