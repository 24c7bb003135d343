"""ISO 6336:2006 method B as a rating standard (``[rating] standard = "iso6336"``, the default; ``gearcli.rating``).

The formulas stay where they were (``rating``: a gear pair, ``rating_internal``: a planetary stage's planet–ring
mesh, ``rating_factors`` and ``rating_root``: the factors); this module is the standard's face to the layers above:
what it rates in a design (every mesh of every stage, a planetary stage's at K_γ with ISO's nominal σ_H0, σ_F0),
its re-rating at a run's simulated K_v, its S–N curves (the life factors Z_NT, Y_NT) and its table rows. Above
``rating`` and ``rating_internal`` (the design layer's inner contract, ARCHITECTURE.md), so neither imports the
other; a run's stage summaries (``gearcli.simulate.results``, a layer above) are read by their fields.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import replace
from typing import TYPE_CHECKING, TypeVar, cast

from gearcli.design import planetary as pl
from gearcli.design import rating as iso
from gearcli.design import rating_factors as rf
from gearcli.design import resonance as res
from gearcli.design import stiffness as stf
from gearcli.design.rating_internal import planet_ring_safety_diagnostics, rate_planet_ring
from gearcli.diagnostics import LOAD_SHARING, Diagnostic, warning
from gearcli.rating import register
from gearcli.rating.dynamic import ring_simulated_k_v, stage_simulated_k_v
from gearcli.rating.sn import SNCurve
from gearcli.stages.design import design_kind, pair_view

if TYPE_CHECKING:
    from gearcli.config.schema import DesignFile, PlanetaryStage
    from gearcli.design.rating_results import InternalRatingResult, RatingResult
    from gearcli.optional_results import InternalMeshResult
    from gearcli.rating.standard import RatedMember, RatedMesh
    from gearcli.results import DesignResult, StageResult

S = TypeVar("S")  # a run's stage summary (``gearcli.simulate.results.StageDynamics``), read by its fields

UNRATED_MESH = "mesh_not_rated"


class Iso6336:
    """ISO 6336-1, -2, -3 (2006, method B) and the life factors of ISO 6336-2/-3 for ISO 6336-6's Miner sum."""

    name = "iso6336"
    title = iso.STANDARD

    def check_inputs(self, cfg: DesignFile) -> None:
        iso.check_rating_inputs(pair_view(cfg))

    def rate_design(self, cfg: DesignFile, stages: tuple[StageResult, ...]
                    ) -> tuple[tuple[StageResult, ...], tuple[Diagnostic, ...]]:
        """Every gear pair (a stage that shares its load among planets: at K_γ times the mean planet's force, its
        planet–ring mesh too, with ISO's nominal σ_H0, σ_F0); a stage without a gear pair (a belt) as it is."""
        rated, diags = iso.rate_design(pair_view(cfg), tuple(_shared(cfg, s) for s in stages))
        out = tuple(replace(s, rating=r.rating) if design_kind(s).gear_pair else s
                    for s, r in zip(stages, rated, strict=True))
        out = tuple(_nominal(_rate_planet_ring(cfg, k, s)) if _planets(s) else s for k, s in enumerate(out))
        diags += tuple(d for s in out if _planets(s) for d in planet_ring_safety_diagnostics(cfg, s))
        diags += tuple(_unrated_ring_mesh(cfg, s) for s in out if _planets(s) and _ring_unrated(s))
        return out, diags

    def rate_simulation(self, cfg: DesignFile, design: DesignResult, stages: Sequence[S]
                        ) -> tuple[tuple[S, ...], list[Diagnostic]]:
        return simulated_ratings(cfg, design, stages)

    def sn_curve(self, cfg: DesignFile, member: RatedMember, treatment: str, mode: str, variant: str) -> SNCurve:
        """σ(N) = σ_∞ Z_NT(N): the life factor's curve of the material group times the rating's limit stress
        divided by its own life factor (every other factor as the rating computed it)."""
        assert cfg.rating is not None
        m = member  # an ISO MemberRating: its limit stresses and life factors
        optimum = cfg.rating.material_quality == "optimum"
        if mode == "pitting":
            return SNCurve(rf.znt_curve(treatment), m.sigma_HG_MPa / m.Z_NT, variant, optimum)  # type: ignore[attr-defined]
        return SNCurve(rf.ynt_curve(treatment), m.sigma_FG_MPa / m.Y_NT, variant, optimum)  # type: ignore[attr-defined]

    def rate_at_force(self, cfg: DesignFile, stage: StageResult, force_ratio: float) -> RatedMesh | None:
        """A gear pair's rating with its tooth forces ``force_ratio`` times the design's (a load class of the life):
        every load-dependent factor of ISO 6336-1 at that load, as ``gearcli design`` at the scaled torque rates it
        (K_Hβ, K_Hα, K_Fβ, K_Fα from the line load; c′, c_γα, c_γβ with their low-load factor, N and N_S; ISO
        6336-6: each load class at its own load, as its Annex C gives K_Hβ per bin). None for a stage this does not cover (a
        stage that shares its load among planets: its two meshes are re-rated together, :meth:`rate_stage_at_force`)."""
        if _planets(stage):
            return None
        rated = self.rate_stage_at_force(cfg, stage, force_ratio)
        return None if rated is None else rated.rating

    def rate_stage_at_force(self, cfg: DesignFile, stage: StageResult, force_ratio: float) -> StageResult | None:
        """The stage rated with its tooth forces ``force_ratio`` times the design's, as ``gearcli design`` at the
        scaled torque rates it: a gear pair's rating (:meth:`rate_at_force`); a stage that shares its load among
        planets with both its meshes' (the sun–planet and the planet–ring mesh, each at K_γ times its mean planet's
        scaled force, ISO's nominal σ_H0, σ_F0), as ISO 6336-6 rates each load level with its own factors. None for
        a stage without a gear pair or a rating."""
        if not design_kind(stage).gear_pair or stage.rating is None:
            return None
        k = stage.index - 1
        scaled = at_force(cfg, stage, force_ratio)
        if not _planets(stage):
            return replace(scaled, rating=iso.rate_stage(pair_view(cfg), k, scaled))
        p = scaled.planetary
        assert p is not None  # a stage with planets (``_planets``)
        ring = p.planet_ring
        f = ring.static_force_N
        ring = replace(_stiffness_at(cfg, ring, force_ratio), static_force_N=replace(
            f, tangential=f.tangential * force_ratio, radial=f.radial * force_ratio, axial=f.axial * force_ratio,
            normal=f.normal * force_ratio))
        scaled = replace(scaled, planetary=replace(p, planet_ring=ring))
        rated = replace(scaled, rating=iso.rate_stage(pair_view(cfg), k, _shared(cfg, scaled)))
        return _nominal(_rate_planet_ring(cfg, k, rated))

    def curve_name(self, mode: str) -> str:
        return "Z_NT (ISO 6336-2:2006)" if mode == "pitting" else "Y_NT (ISO 6336-3:2006)"

    def table_rows(self, ratings: Sequence[RatedMesh], *, shared: bool) -> list[tuple[str, list[str]]]:
        return table_rows(ratings, shared=shared)


def _g(v: float | None, digits: int = 5) -> str:
    """A number to ``digits`` significant digits (as io's tables print them)."""
    return "—" if v is None else f"{v + 0.0:.{digits}g}"


def table_rows(ratings: Sequence, *, shared: bool) -> list[tuple[str, list[str]]]:
    """ISO's factors, stresses, permissible stresses and safeties per member, in the order of a KISSsoft report
    (general factors, tooth root, flank); per-member cells read "pinion / gear"."""
    def one(label: str, fn: Callable, digits: int = 4) -> tuple[str, list[str]]:
        return label, [_g(fn(r), digits) for r in ratings]

    def two(label: str, name: str, digits: int = 4) -> tuple[str, list[str]]:
        return label, [f"{_g(getattr(r.pinion, name), digits)} / {_g(getattr(r.gear, name), digits)}"
                       for r in ratings]

    return [
        one("application factor K_A", lambda r: r.K_A),
        *([one("load-sharing factor K_γ", lambda r: r.K_gamma)] if shared else []),
        ("dynamic factor K_v", [f"{r.K_v:.4g} ({r.K_v_source})" for r in ratings]),
        ("face load factor K_Hβ", [f"{r.K_Hbeta:.4g} ({r.K_Hbeta_source})" for r in ratings]),
        one("face load factor K_Fβ", lambda r: r.K_Fbeta),
        one("transverse load factor K_Hα", lambda r: r.K_Halpha),
        one("transverse load factor K_Fα", lambda r: r.K_Falpha),
        two("load cycles N_L p / g", "load_cycles"),
        two("tooth form Y_F p / g", "Y_F"),
        two("stress correction Y_S p / g", "Y_S"),
        one("helix factor Y_β", lambda r: r.Y_beta),
        two("rim factor Y_B p / g", "Y_B"),
        two("deep tooth Y_DT p / g", "Y_DT"),
        two("nominal root σ_F0 [MPa] p / g", "sigma_F0_MPa"),
        two("root stress σ_F [MPa] p / g", "sigma_F_MPa"),
        two("notch Y_δrelT p / g", "Y_delta_rel_T"),
        two("surface Y_RrelT p / g", "Y_R_rel_T"),
        two("size Y_X p / g", "Y_X"),
        two("life Y_NT p / g", "Y_NT"),
        two("mean stress Y_M p / g", "Y_M"),
        two("root limit σ_FG [MPa] p / g", "sigma_FG_MPa"),
        two("permissible σ_FP [MPa] p / g", "sigma_FP_MPa"),
        two("root safety S_F p / g", "S_F", 3),
        one("zone factor Z_H", lambda r: r.Z_H),
        one("elasticity Z_E [√MPa]", lambda r: r.Z_E),
        one("contact ratio Z_ε", lambda r: r.Z_eps),
        one("helix factor Z_β", lambda r: r.Z_beta),
        one("nominal contact σ_H0 [MPa]", lambda r: r.sigma_H0_MPa),
        one("contact σ_H (pitch) [MPa]", lambda r: r.sigma_H_MPa),
        two("single pair Z_B,D p / g", "Z_BD"),  # Z_B on the wheel with fewer teeth, either member
        two("contact σ_HB,D [MPa] p / g", "sigma_H_MPa"),
        one("lubricant Z_L", lambda r: r.Z_L),
        one("velocity Z_V", lambda r: r.Z_V),
        one("roughness Z_R", lambda r: r.Z_R),
        one("work hardening Z_W", lambda r: r.Z_W),
        two("life Z_NT p / g", "Z_NT"),
        two("size Z_X p / g", "Z_X"),
        two("pitting limit σ_HG [MPa] p / g", "sigma_HG_MPa"),
        two("permissible σ_HP [MPa] p / g", "sigma_HP_MPa"),
        two("flank safety S_H p / g", "S_H", 3),
    ]


# ------------------------------------------------------------------------- the simulated K_v
def simulated_ratings(cfg: DesignFile, design, stages) -> tuple[tuple, list[Diagnostic]]:
    """With ``[rating] dynamic_factor = "simulated"``: simulate's stage summaries (``StageDynamics``) each with
    its ``rating`` at the simulated K_v, and the safety warnings of that rating; unchanged otherwise. A
    planetary stage's planet–ring mesh is rated too, at its own meshes' simulated K_v (``planet_ring_rating``)."""
    if cfg.rating is None or cfg.rating.dynamic_factor != "simulated":
        return tuple(stages), []
    pairs = pair_view(cfg)  # a planetary stage is rated as its sun–planet mesh, its most loaded planet's
    out, diags = [], []
    own_sharing = simulates_sharing(cfg, design.stages)
    for k, sd in enumerate(stages):
        stage = design.stages[k]
        if not design_kind(stage).gear_pair:  # no gear mesh to rate (a belt)
            out.append(sd)
            continue
        k_v = stage_simulated_k_v(sd)
        if own_sharing and _planets(stage) and pl.load_sharing_of(stage) != 1.0:
            # the simulated K_v is the most loaded planet's (its position errors' share times its dynamics) over the
            # mean planet's static force: K_gamma on top of it would count the unequal sharing twice
            diags.append(warning(LOAD_SHARING, f"stage {k + 1}: [rating] dynamic_factor = \"simulated\" takes the "
                                 "planets' load sharing from the simulation (stage"
                                 f"[{k}].planet.position_error_um: K_v {k_v:.4g} is the most loaded planet's); "
                                 f"[rating] load_sharing_factor = {pl.load_sharing_of(stage):g} is not applied",
                                 stage=k + 1, load_sharing_factor=pl.load_sharing_of(stage)))
            stage = pl.without_load_sharing(stage)
        shared = _shared(cfg, stage)
        rating = iso.rate_stage(pairs, k, shared, simulated_k_v=k_v)
        if _planets(shared):  # ISO's nominal σ_H0, σ_F0; K_gamma among the load factors
            rating = pl.nominal_with_sharing(rating, pl.load_sharing_of(shared))
        rated = replace(stage, rating=rating)
        diags += iso.safety_diagnostics(pairs, rated)
        ring = None
        if _planets(rated) and sd.planets:
            ring = rate_planet_ring(cfg, k, shared,
                                    simulated_k_v=ring_simulated_k_v(sd, design.stages[k]))
            if ring is not None:  # ISO's nominal σ_H0, σ_F0 and K_gamma listed, as the design's ring rating
                ring = pl.nominal_with_sharing(ring, pl.load_sharing_of(shared))
                mesh = replace(rated.planetary.planet_ring, rating=ring)
                diags += planet_ring_safety_diagnostics(cfg, replace(rated, planetary=replace(rated.planetary,
                                                                                               planet_ring=mesh)))
        out.append(replace(sd, rating=rated.rating, planet_ring_rating=ring))
    return tuple(out), diags


def at_force(cfg: DesignFile, stage: StageResult, force_ratio: float) -> StageResult:
    """A parallel stage as the design computes it at ``force_ratio`` times its static tooth forces: the forces
    scaled, and ISO 6336-1's load-dependent stiffness and resonance figures at the new line load
    (:func:`_stiffness_at`)."""
    f = stage.static_force_N
    forces = replace(f, tangential=f.tangential * force_ratio, radial=f.radial * force_ratio,
                     axial=f.axial * force_ratio, normal=f.normal * force_ratio)
    return replace(_stiffness_at(cfg, stage, force_ratio), static_force_N=forces)


M = TypeVar("M", "StageResult", "InternalMeshResult")  # a mesh's record: a stage's (its pair) or a planet–ring mesh


def _stiffness_at(cfg: DesignFile, mesh: M, force_ratio: float) -> M:
    """``mesh`` with ISO 6336-1's load-dependent figures at ``force_ratio`` times its static tangential force (its
    forces as they are): c′ × (F_t K_A / b / 100)^0.25 below 100 N/mm, so c_γα and c_γβ with it, n_E1 ∝ √c_γα and
    N = n1/n_E1, and the lower resonance limit N_S and the range at the new line load."""
    f_t, b, k_a = mesh.static_force_N.tangential, mesh.face_width_mm, cfg.load.application_factor
    old, new = (stf.reference_tangential_force_N(ft, b) * k_a / b for ft in (f_t, f_t * force_ratio))
    c = stf.low_load_factor(new) / stf.low_load_factor(old)
    stiffness = mesh.iso6336_mesh_stiffness_N_mm_um * c
    ratio = mesh.resonance_ratio / math.sqrt(c)
    lower = res.lower_main_resonance_limit(new)
    return replace(mesh, iso6336_single_pair_stiffness_N_mm_um=mesh.iso6336_single_pair_stiffness_N_mm_um * c,
                   iso6336_mesh_stiffness_N_mm_um=stiffness,
                   iso6336_mesh_stiffness_beta_N_mm_um=stf.mesh_stiffness_beta_N_mm_um(stiffness),
                   resonance_speed_rpm=mesh.resonance_speed_rpm * math.sqrt(c), resonance_ratio=ratio,
                   resonance_lower_limit=lower, resonance_range=res.resonance_range(ratio, lower))


# ------------------------------------------------------------------ a planetary stage's planet–ring mesh
def simulates_sharing(cfg: DesignFile, stages: Sequence[StageResult]) -> bool:
    """Whether a run shares its planets' load itself: every stage with planets gives ``planet.position_error_um``
    (then [rating] K_γ, ISO's allowance for the sharing a model of identical planets does not see, is 1 in a rating
    from the run: the dynamic life's rule, docs/life.md "Load sharing", and the simulated K_v's)."""
    sharing = [k for k, st in enumerate(stages) if _planets(st)]
    return bool(sharing) and all(getattr(cfg.stage[k], "planet").position_error_um is not None  # noqa: B009
                                 for k in sharing)


def _planets(stage: StageResult) -> bool:
    """The stage's kind shares its load among planets (``gearcli.stages``): rated at K_γ, with its planet–ring
    mesh (``rating_internal``)."""
    return design_kind(stage).shares_load


def _ring_unrated(stage: StageResult) -> bool:
    """A rated stage with planets whose planet–ring mesh is not rated (a key it needs is missing)."""
    p = stage.planetary
    assert p is not None  # a stage with planets (``_planets``)
    return stage.rating is not None and p.planet_ring.rating is None


def _shared(cfg: DesignFile, stage: StageResult) -> StageResult:
    """The stage as ISO rates it: a planetary stage's most loaded planet, K_γ times the mean planet's force
    (``pl.with_load_sharing``), and both its meshes' load-dependent ISO 6336-1 figures (c′, c_γα, c_γβ, N, N_S) at
    that planet's load, as every other load factor of its rating reads it (the design's are the mean planet's)."""
    if not _planets(stage):
        return stage
    k = pl.load_sharing_of(stage)
    if k == 1.0:
        return stage
    p = stage.planetary
    assert p is not None  # a stage with planets (``_planets``)
    loaded = pl.with_load_sharing(_stiffness_at(cfg, stage, k))
    return replace(loaded, planetary=replace(p, planet_ring=_stiffness_at(cfg, p.planet_ring, k)))


def _rate_planet_ring(cfg: DesignFile, k: int, stage: StageResult) -> StageResult:
    """A rated planetary stage with its planet–ring mesh rated too (ISO 6336-2/-3, docs/iso6336.md)."""
    if stage.rating is None:
        return stage
    assert stage.planetary is not None  # a stage with planets (``_planets``)
    ring_rating = rate_planet_ring(cfg, k, _shared(cfg, stage))
    mesh = replace(stage.planetary.planet_ring, rating=ring_rating)
    return replace(stage, planetary=replace(stage.planetary, planet_ring=mesh))


def _unrated_ring_mesh(cfg: DesignFile, stage: StageResult) -> Diagnostic:
    """Which planet–ring mesh was not rated and the key it needs (never dropped without a word)."""
    k = stage.index - 1
    st = cast("PlanetaryStage", cfg.stage[k])  # a stage with planets (``_planets``): the planetary kind's table
    ring_mat, planet_mat = cfg.materials[st.ring.material], cfg.materials[st.planet.material]
    if st.ring.flank_roughness_Rz_um is None:
        key = f"stage[{k}].ring.flank_roughness_Rz_um"
    elif st.ring.root_roughness_Rz_um is None:
        key = f"stage[{k}].ring.root_roughness_Rz_um"
    else:
        missing = [(name, m) for name, m in ((st.ring.material, ring_mat), (st.planet.material, planet_mat))
                   if m.treatment is None or m.contact_fatigue_limit_MPa is None or m.bending_fatigue_limit_MPa is None]
        key = f"materials.{missing[0][0]}" if missing else "rating"
    return warning(UNRATED_MESH, f"stage {stage.index}: the planet–ring mesh is not rated (ISO 6336): it needs {key} "
                   "(the ring's flank and root roughness, and the ring's and planet's material treatment and fatigue "
                   "limits); the ring and the planet's ring side have no safeties", stage=stage.index, mesh="planet_ring",
                   key=key)


def _nominal(stage: StageResult) -> StageResult:
    """A planetary stage's ratings with ISO's nominal σ_H0, σ_F0 and K_gamma among the load factors (rated at
    K_gamma times the mean planet's force: ``pl.with_load_sharing``)."""
    p = stage.planetary
    if stage.rating is None:
        return stage
    assert p is not None  # a stage with planets (``_planets``)
    k = p.load_sharing_factor
    ring = p.planet_ring
    if ring.rating is not None:
        ring_rating = cast("InternalRatingResult", ring.rating)  # ISO's own (rate_planet_ring)
        p = replace(p, planet_ring=replace(ring, rating=pl.nominal_with_sharing(ring_rating, k)))
    return replace(stage, rating=pl.nominal_with_sharing(cast("RatingResult", stage.rating), k), planetary=p)


ISO6336 = register(Iso6336())
