"""The design facet of a stage kind (the design layer): its kinematics, its stage result, the inertias it puts
on the chain's shafts, the further meshes it rates and its own warnings.

``compute_design`` asks :func:`design_kind` for each stage and never which kind it is. The parallel stage is a
pair; the planetary stage is designed as its sun–planet mesh (the pair's code, in the carrier's frame) with its
members and planet–ring mesh attached (``gearcli.design.planetary``).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace
from typing import TYPE_CHECKING, Protocol, cast

from gearcli.design import planetary as pl
from gearcli.diagnostics import DESIGN, Diagnostic, warning
from gearcli.results import InternalRatingResult, MeshStiffness, StageResult
from gearcli.stages import kinds

if TYPE_CHECKING:
    from gearcli.config.schema import DesignFile
    from gearcli.design.kinematics import Train

#: the pair's stage result: (the design file as pairs, stage index, train, meshes in parallel) -> StageResult
MeshResult = Callable[["DesignFile", int, "Train", int], StageResult]

UNRATED_MESH = "mesh_not_rated"


class DesignKind(Protocol):
    """What ``compute_design`` asks of a stage kind."""

    def reverse_efficiency(self, table: object, k: int) -> float | None:
        """The stage's efficiency with the power flowing back (None: its forward efficiency)."""

    def pair(self, table: object) -> object:
        """The stage as the pair the rating and the pair's code read (``cfg.pair(k)``): itself if it is one."""

    def result(self, cfg: DesignFile, pairs: DesignFile, k: int, kin: Train, mesh: MeshResult) -> StageResult:
        """The designed stage k (``mesh`` designs a pair)."""

    def inertia(self, result: StageResult, side: str) -> float:
        """The inertia the stage puts on its input (``side = "input"``) or output shaft, kg·m²."""

    def as_rated(self, result: StageResult) -> StageResult:
        """The stage as its mesh is rated (a planetary's: the most loaded planet's)."""

    def rate_more(self, cfg: DesignFile, k: int, result: StageResult) -> StageResult:
        """A rated stage with its further meshes rated and its nominal figures (after ``rating``)."""

    def rating_diagnostics(self, cfg: DesignFile, result: StageResult) -> tuple[Diagnostic, ...]:
        """The warnings of the further meshes' rating."""

    def diagnostics(self, result: StageResult) -> tuple[Diagnostic, ...]:
        """The stage's own design warnings."""

    def check_inputs(self, cfg: DesignFile, k: int) -> None:
        """Refuse what the pair checks do not see (``DesignError`` naming the key)."""

    def file_key(self, k: int, key: str) -> str:
        """A key of the stage's pair (``stage[k].pinion.x``) as the design file names it."""

    @property
    def shares_load(self) -> bool:
        """The stage's meshes share its load among planets (its rating has K_γ; load-sharing columns)."""

    def meshes(self, result: StageResult) -> list[tuple[str, MeshStiffness | None]]:
        """The stage's meshes by name (a pair's ``mesh``) with the contact law at the static load."""

    def further_ratings(self, result: StageResult) -> list[InternalRatingResult]:
        """The ratings of the stage's meshes beyond its first (a planetary's planet–ring mesh)."""

    def output_speed_deg_s(self, result: StageResult) -> float:
        """The speed of the stage's output member, °/s (magnitude where the model counts it so)."""

    @property
    def model_signs_forces(self) -> bool:
        """The model's static force of the stage's mesh may differ in sign from the design's (its flank)."""


def design_kind(stage: object) -> DesignKind:
    """The design facet of a stage table or stage result (by its ``type``)."""
    return cast(DesignKind, kinds.facet(kinds.kind_of(stage), "design"))


def pair_view(cfg: DesignFile) -> DesignFile:
    """``cfg`` with every stage seen as the pair its kind designs (the pair's code and the rating read it)."""
    stages = [design_kind(s).pair(s) for s in cfg.stage]
    if all(a is b for a, b in zip(stages, cfg.stage, strict=True)):
        return cfg
    return cfg.model_copy(update={"stage": stages})


def file_key(cfg: DesignFile, key: str | None) -> str | None:
    """A key of the pair view (``stage[k].pinion.x``) as the design file names it (a planetary's ``sun.x``)."""
    if key is None or not key.startswith("stage["):
        return key
    k = int(key[len("stage["):key.index("]")])
    return design_kind(cfg.stage[k]).file_key(k, key) if k < len(cfg.stage) else key


class ParallelDesign:
    """A parallel stage: one external pair (pinion on the input shaft, gear on the output shaft)."""

    def reverse_efficiency(self, table: object, k: int) -> float | None:
        return None

    def pair(self, table: object) -> object:
        return table

    def result(self, cfg: DesignFile, pairs: DesignFile, k: int, kin: Train, mesh: MeshResult) -> StageResult:
        return mesh(pairs, k, kin, 1)

    def inertia(self, result: StageResult, side: str) -> float:
        return (result.pinion if side == "input" else result.gear).inertia_kg_m2

    def as_rated(self, result: StageResult) -> StageResult:
        return result

    def rate_more(self, cfg: DesignFile, k: int, result: StageResult) -> StageResult:
        return result

    def rating_diagnostics(self, cfg: DesignFile, result: StageResult) -> tuple[Diagnostic, ...]:
        return ()

    def diagnostics(self, result: StageResult) -> tuple[Diagnostic, ...]:
        return ()

    def check_inputs(self, cfg: DesignFile, k: int) -> None:
        return None

    def file_key(self, k: int, key: str) -> str:
        return key

    shares_load = False

    def meshes(self, result: StageResult) -> list[tuple[str, MeshStiffness | None]]:
        return [("mesh", result.mesh_stiffness)]

    def further_ratings(self, result: StageResult) -> list[InternalRatingResult]:
        return []

    def output_speed_deg_s(self, result: StageResult) -> float:
        return result.gear.speed_deg_s

    model_signs_forces = False


class PlanetaryDesign:
    """A simple planetary stage (docs/planetary.md): its sun–planet mesh in the carrier's frame, per planet, with
    the members, the planet–ring mesh and the assembly checks attached."""

    def reverse_efficiency(self, table: object, k: int) -> float | None:
        return pl.reverse_efficiency(table, k)  # type: ignore[arg-type]  # the table of this kind

    def pair(self, table: object) -> object:
        return pl.sun_planet_stage(table)  # type: ignore[arg-type]

    def result(self, cfg: DesignFile, pairs: DesignFile, k: int, kin: Train, mesh: MeshResult) -> StageResult:
        stage = cfg.stage[k]
        count = stage.planet.count  # type: ignore[union-attr]
        sun_planet = mesh(pairs, k, pl.mesh_train(k, stage, kin), count)  # type: ignore[arg-type]
        return replace(pl.planetary_result(cfg, k, kin, sun_planet), type="planetary")

    def inertia(self, result: StageResult, side: str) -> float:
        p = result.planetary
        assert p is not None
        member = p.input if side == "input" else p.output
        return {"sun": p.sun.inertia_kg_m2, "ring": p.ring.inertia_kg_m2, "carrier": p.carrier.inertia_kg_m2}[member]

    def as_rated(self, result: StageResult) -> StageResult:
        return pl.with_load_sharing(result)

    def rate_more(self, cfg: DesignFile, k: int, result: StageResult) -> StageResult:
        return _nominal(_rate_planet_ring(cfg, k, result))

    def rating_diagnostics(self, cfg: DesignFile, result: StageResult) -> tuple[Diagnostic, ...]:
        from gearcli.design.rating_internal import planet_ring_safety_diagnostics  # only for a rated design

        out = tuple(planet_ring_safety_diagnostics(cfg, result))
        p = result.planetary
        if p is not None and result.rating is not None and p.planet_ring.rating is None:
            out += (_unrated_ring_mesh(cfg, result),)
        return out

    def diagnostics(self, result: StageResult) -> tuple[Diagnostic, ...]:
        return tuple(warning(DESIGN, w, check="planetary", stage=result.index) for w in pl.planetary_warnings(result))

    def check_inputs(self, cfg: DesignFile, k: int) -> None:
        pl.check_stage_inputs(cfg, k)

    def file_key(self, k: int, key: str) -> str:
        head = f"stage[{k}]."
        return key.replace(head + "pinion.", head + "sun.").replace(head + "gear.", head + "planet.")

    shares_load = True

    def meshes(self, result: StageResult) -> list[tuple[str, MeshStiffness | None]]:
        assert result.planetary is not None
        return [("sun_planet", result.mesh_stiffness), ("planet_ring", result.planetary.planet_ring.mesh_stiffness)]

    def further_ratings(self, result: StageResult) -> list[InternalRatingResult]:
        ring = None if result.planetary is None else result.planetary.planet_ring.rating
        return [] if ring is None else [ring]

    def output_speed_deg_s(self, result: StageResult) -> float:
        p = result.planetary
        assert p is not None
        return abs({"sun": p.sun.speed_deg_s, "ring": p.ring.speed_deg_s, "carrier": p.carrier.speed_deg_s}[p.output])

    model_signs_forces = True


def _rate_planet_ring(cfg: DesignFile, k: int, stage: StageResult) -> StageResult:
    """A rated planetary stage with its planet–ring mesh rated too (ISO 6336-2/-3, docs/iso6336.md)."""
    if stage.planetary is None or stage.rating is None:
        return stage
    from gearcli.design.rating_internal import rate_planet_ring  # only for a rated design

    ring_rating = rate_planet_ring(cfg, k, pl.with_load_sharing(stage))
    mesh = replace(stage.planetary.planet_ring, rating=ring_rating)
    return replace(stage, planetary=replace(stage.planetary, planet_ring=mesh))


def _unrated_ring_mesh(cfg: DesignFile, stage: StageResult) -> Diagnostic:
    """Which planet–ring mesh was not rated and the key it needs (never dropped without a word)."""
    k = stage.index - 1
    st = cfg.stage[k]
    ring, planet = st.ring, st.planet  # type: ignore[union-attr]  # a planetary stage's table
    ring_mat, planet_mat = cfg.materials[ring.material], cfg.materials[planet.material]
    if ring.flank_roughness_Rz_um is None:
        key = f"stage[{k}].ring.flank_roughness_Rz_um"
    else:
        missing = [(name, m) for name, m in ((ring.material, ring_mat), (planet.material, planet_mat))
                   if m.treatment is None or m.contact_fatigue_limit_MPa is None or m.bending_fatigue_limit_MPa is None]
        key = f"materials.{missing[0][0]}" if missing else "rating"
    return warning(UNRATED_MESH, f"stage {stage.index}: the planet–ring mesh is not rated (ISO 6336): it needs {key} "
                   "(the ring's flank roughness, and the ring's and planet's material treatment and fatigue limits); "
                   "the ring and the planet's ring side have no safeties", stage=stage.index, mesh="planet_ring",
                   key=key)


def _nominal(stage: StageResult) -> StageResult:
    """A planetary stage's ratings with ISO's nominal σ_H0, σ_F0 and K_gamma among the load factors (rated at
    K_gamma times the mean planet's force: ``pl.with_load_sharing``)."""
    p = stage.planetary
    if p is None or stage.rating is None:
        return stage
    k = p.load_sharing_factor
    ring = p.planet_ring
    if ring.rating is not None:
        p = replace(p, planet_ring=replace(ring, rating=pl.nominal_with_sharing(ring.rating, k)))
    return replace(stage, rating=pl.nominal_with_sharing(stage.rating, k), planetary=p)


kinds.provide(kinds.PARALLEL, "design", ParallelDesign())
kinds.provide("planetary", "design", PlanetaryDesign())
