"""The design facets of the built-in gear stages: a parallel stage (one external pair) and a simple planetary stage
(its sun–planet mesh designed by the pair's code in the carrier's frame, with its members and planet–ring mesh
attached, ``gearcli.design.planetary``).

Registered when ``gearcli.design.compute`` imports this module (every import of ``gearcli.design`` does). It
imports ``design.planetary`` (when a planetary stage is designed: a file of parallel stages never loads it), so only the modules above it in the design layer's inner contract (``inputs``,
``compute``) import it; the others ask :func:`gearcli.stages.design.design_kind`.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from gearcli.diagnostics import DESIGN, Diagnostic, warning
from gearcli.results import MeshStiffness, RatedMesh, StageResult
from gearcli.stages import kinds

if TYPE_CHECKING:
    from gearcli.config.schema import DesignFile
    from gearcli.design.kinematics import Train
    from gearcli.stages.design import MeshResult


def _planet_ring_allowance_diagnostics(result: StageResult) -> tuple[Diagnostic, ...]:
    """The planet–ring mesh's allowances: a negative minimum backlash (``backlash_negative``) and ε_α,i < 1 where
    the nominal ε_α ≥ 1 (``contact_ratio_allowances``), ``mesh`` "planet_ring"."""
    mesh = result.planetary.planet_ring  # type: ignore[union-attr]  # a planetary stage's result
    j, eps = mesh.backlash_circumferential_mm, mesh.contact_ratio_transverse_with_allowances
    out: list[Diagnostic] = []
    if j is not None and j[1] < 0.0:
        out.append(warning(
            DESIGN, f"stage {result.index} planet–ring mesh: the minimum circumferential backlash is {j[1]:.4g} mm "
            "(< 0): at the upper tooth-thickness allowances of planet and ring, on the carrier's radius, the teeth jam"
            + (f" (the maximum, {j[0]:.4g} mm, too: every pair within the tolerances jams)" if j[0] < 0.0 else "")
            + "; thin the teeth (tooth_thickness_allowance_mm of the planet or the ring)",
            check="backlash_negative", stage=result.index, mesh="planet_ring", backlash_min_mm=j[1],
            backlash_max_mm=j[0]))
    if eps is not None and min(eps) < 1.0 <= mesh.contact_ratio_transverse:
        out.append(warning(
            DESIGN, f"stage {result.index} planet–ring mesh: transverse contact ratio with allowances ε_α,i = "
            f"{min(eps):.3f} < 1 (nominal {mesh.contact_ratio_transverse:.3f}): at the planet's lower tip contact is "
            "interrupted in every transverse section; narrow the planet's tip allowance",
            check="contact_ratio_allowances", stage=result.index, mesh="planet_ring",
            contact_ratio_transverse_with_allowances=list(eps)))
    clearances = mesh.tip_clearance_with_allowances_mm
    for member, mate, c in zip(("planet", "ring"), ("ring", "planet"), clearances or (0.0, 0.0), strict=True):
        if c < 0.0:
            out.append(warning(
                DESIGN, f"stage {result.index} planet–ring mesh: {member} tip clearance with allowances c = {c:.3g} mm "
                f"< 0: at the upper tip and the {mate}'s upper tooth-thickness allowance the tip runs into the {mate}'s "
                f"root; narrow the {mate}'s positive tooth-thickness allowance"
                + (" or the planet's tip allowance (tip_diameter_allowance_mm)" if member == "planet" else ""),
                check="tip_clearance", stage=result.index, mesh="planet_ring", member=member, tip_clearance_mm=c))
    return (*out, *_ring_tip_thickness_diagnostics(result))


def _ring_tip_thickness_diagnostics(result: StageResult) -> tuple[Diagnostic, ...]:
    """``tip_thickness`` of the ring: its normal tip thickness at the thinnest cut tooth (x_E,i of its allowance, or
    x) below 0.2 m_n, 0.4 m_n when surface-hardened (pointed at ≤ 0), as an external member's."""
    from gearcli.design.allowances_internal import internal_normal_tip_thickness_mm  # lazy: planetary files only
    from gearcli.design.geometry import hardened_tip_text, min_tip_thickness_per_module  # lazy: as above

    p = result.planetary
    assert p is not None  # a planetary stage's result
    ring, m_n = p.ring, result.normal_module_mm
    cut = ring.profile_shift if ring.generating_profile_shift is None else ring.generating_profile_shift[1]
    s_an = internal_normal_tip_thickness_mm(ring.teeth, m_n, cut, math.radians(result.helix_angle_deg),
                                            math.radians(result.normal_pressure_angle_deg), ring.tip_diameter_mm)
    factor = min_tip_thickness_per_module(p.ring_treatment)
    limit = factor * m_n
    if s_an >= limit:
        return ()
    what = "pointed tooth: the flanks meet before the tip circle" if s_an <= 0 else "thin tooth tip"
    shift = f"x = {ring.profile_shift:+.3f}" + (f", cut at x_E,i = {cut:+.3f} by the lower tooth-thickness allowance"
                                                if cut != ring.profile_shift else "")
    return (warning(DESIGN, f"stage {result.index}: ring {what}, normal tip thickness s_an = {s_an:.3g} mm < "
                    f"{factor:g} m_n = {limit:.3g} mm{hardened_tip_text(p.ring_treatment)} ({shift}); narrow the ring's "
                    "tooth-thickness allowance or shorten its teeth (basic_rack addendum)", check="tip_thickness",
                    stage=result.index,
                    member="ring", profile_shift=ring.profile_shift, tip_thickness_mm=s_an, min_tip_thickness_mm=limit,
                    treatment=p.ring_treatment,
                    **({} if ring.generating_profile_shift is None else {"generating_profile_shift": cut})),)


class ParallelDesign:
    """A parallel stage: one external pair (pinion on the input shaft, gear on the output shaft)."""

    def reverse_efficiency(self, table: object, k: int) -> float | None:
        return None

    def pair(self, table: object) -> object | None:
        return table

    gear_pair = True

    def result(self, cfg: DesignFile, pairs: DesignFile, k: int, kin: Train, mesh: MeshResult) -> StageResult:
        return mesh(pairs, k, kin, 1)

    def inertia(self, result: StageResult, side: str) -> float:
        return (result.pinion if side == "input" else result.gear).inertia_kg_m2

    def diagnostics(self, result: StageResult) -> tuple[Diagnostic, ...]:
        return ()

    def check_inputs(self, cfg: DesignFile, k: int) -> None:
        return None

    def file_key(self, k: int, key: str) -> str:
        return key

    shares_load = False

    def meshes(self, result: StageResult) -> list[tuple[str, MeshStiffness | None]]:
        return [("mesh", result.mesh_stiffness)]

    def meetings(self, result: StageResult, member: int) -> int:
        return 1

    def idler(self, result: StageResult, member: int) -> bool:
        return False

    def further_ratings(self, result: StageResult) -> list[RatedMesh]:
        return []

    def output_speed_deg_s(self, result: StageResult) -> float:
        return result.gear.speed_deg_s

    model_signs_forces = False

    def fastest_rad_s(self, cfg: DesignFile, result: StageResult, k: int, inertia_in: float,
                      inertia_out: float) -> float:
        return pair_fastest_rad_s(cfg, result, k, inertia_in, inertia_out)


class PlanetaryDesign:
    """A simple planetary stage (docs/planetary.md): its sun–planet mesh in the carrier's frame, per planet, with
    the members, the planet–ring mesh and the assembly checks attached."""

    def reverse_efficiency(self, table: object, k: int) -> float | None:
        from gearcli.design import planetary as pl  # lazy: a file without planetary stages never loads it

        return pl.reverse_efficiency(table, k)  # type: ignore[arg-type]  # the table of this kind

    def pair(self, table: object) -> object | None:
        from gearcli.design import planetary as pl  # lazy: a file without planetary stages never loads it

        return pl.sun_planet_stage(table)  # type: ignore[arg-type]

    gear_pair = True

    def result(self, cfg: DesignFile, pairs: DesignFile, k: int, kin: Train, mesh: MeshResult) -> StageResult:
        from gearcli.design import planetary as pl  # lazy: a file without planetary stages never loads it

        stage = cfg.stage[k]
        count = stage.planet.count  # type: ignore[union-attr]
        sun_planet = mesh(pairs, k, pl.mesh_train(k, stage, kin), count, driving_side=True)  # type: ignore[arg-type]
        return pl.planetary_result(cfg, k, kin, sun_planet)

    def inertia(self, result: StageResult, side: str) -> float:
        p = result.planetary
        assert p is not None
        member = p.input if side == "input" else p.output
        return {"sun": p.sun.inertia_kg_m2, "ring": p.ring.inertia_kg_m2, "carrier": p.carrier.inertia_kg_m2}[member]

    def diagnostics(self, result: StageResult) -> tuple[Diagnostic, ...]:
        from gearcli.design import planetary as pl  # lazy: a file without planetary stages never loads it

        found = tuple(warning(DESIGN, w, stage=result.index, **data) for w, data in pl.planetary_warnings(result))
        found += _planet_ring_allowance_diagnostics(result)
        ring = pl.ring_resonance_warning(result)
        if ring is None:
            return found
        mesh = result.planetary.planet_ring  # type: ignore[union-attr]  # a planetary stage's result
        return (*found, warning(DESIGN, ring, check="iso6336_resonance", stage=result.index, mesh="planet_ring",
                                resonance_ratio=mesh.resonance_ratio, resonance_speed_rpm=mesh.resonance_speed_rpm,
                                resonance_lower_limit=mesh.resonance_lower_limit, resonance_range=mesh.resonance_range))

    def check_inputs(self, cfg: DesignFile, k: int) -> None:
        from gearcli.design import planetary as pl  # lazy: a file without planetary stages never loads it

        pl.check_stage_inputs(cfg, k)

    def file_key(self, k: int, key: str) -> str:
        head = f"stage[{k}]."
        return key.replace(head + "pinion.", head + "sun.").replace(head + "gear.", head + "planet.")

    shares_load = True

    def meshes(self, result: StageResult) -> list[tuple[str, MeshStiffness | None]]:
        assert result.planetary is not None
        return [("sun_planet", result.mesh_stiffness), ("planet_ring", result.planetary.planet_ring.mesh_stiffness)]

    def meetings(self, result: StageResult, member: int) -> int:
        assert result.planetary is not None
        return result.planetary.planet_count if member == 0 else 1  # the sun meets every planet

    def idler(self, result: StageResult, member: int) -> bool:
        return member == 1  # the planet: its sun and ring meshes load its teeth from both sides

    def further_ratings(self, result: StageResult) -> list[RatedMesh]:
        ring = None if result.planetary is None else result.planetary.planet_ring.rating
        return [] if ring is None else [ring]

    def output_speed_deg_s(self, result: StageResult) -> float:
        p = result.planetary
        assert p is not None
        return abs({"sun": p.sun.speed_deg_s, "ring": p.ring.speed_deg_s, "carrier": p.carrier.speed_deg_s}[p.output])

    model_signs_forces = True

    def fastest_rad_s(self, cfg: DesignFile, result: StageResult, k: int, inertia_in: float,
                      inertia_out: float) -> float:
        return pair_fastest_rad_s(cfg, result, k, inertia_in, inertia_out)  # its sun–planet mesh


MIN_APPROACH_M = 1e-6  # the static approach a run's budget assumes at least (an unloaded mesh's law is stiff)


def pair_fastest_rad_s(cfg: DesignFile, st: StageResult, k: int, inertia_in: float, inertia_out: float) -> float:
    """A gear pair's fastest angular frequency: its mesh's tangent stiffness at the static approach (at least
    ``MIN_APPROACH_M``; ISO's k_n where the law is ISO's) on the two shafts' inertias through the base radii, and
    its mesh frequency times its excitation harmonics."""
    law = cfg.contact_for(k)
    e = law.exponent
    K = st.hertz_stiffness_N_mm1_5 * 1e3 ** e  # N/m^e (K was N/mm^e)
    h = max(st.static_approach_mm * 1e-3, MIN_APPROACH_M)
    k_lin = e * K * h ** (e - 1.0) if law.stiffness == "hertz" else st.linearised_stiffness_N_mm * 1e3
    if law.stiffness == "iso6336":  # its tangent is ISO's k_n at the (floored) static load, loaded or not
        k_lin = max(k_lin, st.mesh_stiffness.iso_N_mm * 1e3 if st.mesh_stiffness is not None else 0.0)
    rb1, rb2 = st.pinion.base_diameter_mm / 2e3, st.gear.base_diameter_mm / 2e3
    mobility = rb1**2 / inertia_in + rb2**2 / inertia_out
    harmonics = max(len(law.transmission_error_um), len(law.stiffness_harmonics), int(law.time_varying))
    return max(math.sqrt(max(k_lin, 0.0) * mobility), 2 * math.pi * st.mesh_frequency_Hz * harmonics)


kinds.provide(kinds.PARALLEL, "design", ParallelDesign())
kinds.provide("planetary", "design", PlanetaryDesign())
