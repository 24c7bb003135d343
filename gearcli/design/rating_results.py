"""ISO 6336:2006 method B's rated meshes (``gearcli.design.iso6336``): the factor names are ISO's, the JSON keys of
``stages[k].rating`` and ``meshes[1].rating`` (docs/output.md). They satisfy ``gearcli.results.RatedMesh``, which
is all the layers above read."""

from __future__ import annotations

from dataclasses import fields

from gearcli.core.records import record


@record
class MemberRating:
    """ISO 6336-2/-3 figures of one member (docs/iso6336.md, "Strength rating"); JSON ``rating.pinion|gear``."""

    load_cycles: float
    Z_BD: float  # Z_B of the smaller wheel, Z_D of the larger (ISO's pinion and wheel)
    sigma_H_MPa: float  # sigma_HB / sigma_HD
    Z_NT: float
    Z_X: float
    sigma_HG_MPa: float
    sigma_HP_MPa: float
    S_H: float
    Y_F: float
    Y_S: float
    Y_B: float
    Y_DT: float
    sigma_F0_MPa: float
    sigma_F_MPa: float
    Y_delta_rel_T: float
    Y_R_rel_T: float
    Y_X: float
    Y_NT: float
    sigma_FG_MPa: float
    sigma_FP_MPa: float
    S_F: float
    Y_M: float = 1.0  # mean stress factor in sigma_FG: 0.7 on a planet's root (an idler: alternating bending)

    def safety(self, mode: str) -> float:
        """S_H ("pitting") or S_F ("bending"): the generic rated member (:class:`gearcli.rating.RatedMember`)."""
        return self.S_H if mode == "pitting" else self.S_F

    def stress_MPa(self, mode: str) -> float:
        """σ_HB/σ_HD ("pitting") or σ_F ("bending") at the rating's operating point."""
        return self.sigma_H_MPa if mode == "pitting" else self.sigma_F_MPa


@record
class MeshRatingFactors:
    """The mesh-level figures of an ISO 6336:2006 method B rating (load factors, pitting factors, σ_H0, σ_H),
    shared by a gear pair's rating and the planet–ring mesh's."""

    standard: str
    K_A: float
    K_v: float
    K_v_source: str  # "iso" | "simulated" | "given"
    K_Hbeta: float
    K_Hbeta_source: str  # "given" | "estimated"
    K_Fbeta: float
    K_Halpha: float
    K_Falpha: float
    Z_H: float
    Z_E: float
    Z_eps: float
    Z_beta: float
    Z_L: float
    Z_V: float
    Z_R: float
    Z_W: float
    Y_beta: float
    sigma_H0_MPa: float
    sigma_H_MPa: float  # at the operating pitch point (Z_B = Z_D = 1)

    def factor_table(self) -> dict[str, float | str]:
        """The mesh-level factors by their ISO names (:class:`gearcli.rating.RatedMesh`), the JSON's keys."""
        return {f.name: getattr(self, f.name) for f in fields(self) if f.name not in ("pinion", "gear")}


@record
class RatingResult(MeshRatingFactors):
    """The strength rating of one stage, ISO 6336:2006 method B; JSON ``stages[k].rating``."""

    pinion: MemberRating
    gear: MemberRating
    K_gamma: float = 1.0  # load-sharing factor of a planetary stage (in σ_H, σ_F; not in the nominal σ_H0, σ_F0)


@record
class InternalRatingResult(MeshRatingFactors):
    """The planet–ring mesh's strength rating (ISO 6336:2006 method B); JSON ``meshes[1].rating``, the keys of a
    parallel stage's ``rating``: ``pinion`` is the planet, ``gear`` the ring (its root by ISO 6336-3's internal
    gear method; K_v from the internal mesh's own resonance)."""

    pinion: MemberRating
    gear: MemberRating
    K_gamma: float = 1.0  # load-sharing factor of a planetary stage (in σ_H, σ_F; not in the nominal σ_H0, σ_F0)
