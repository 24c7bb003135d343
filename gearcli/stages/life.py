"""The life facet of a stage kind (the life layer): the stage's members and the rating each is rated by, the
design-file member that gives its material, the contacts per turn and the speed that load its teeth, the
tooth-force classes each member meets, the planets' own force channels, and the stage's life record.

``gearcli.life`` asks :func:`life_kind` and never which kind a stage is. A parallel stage has a pinion and a
gear; a planetary stage's sun–planet mesh is its pinion (sun) and gear (planet), and its planet–ring mesh adds
the ring, the planet's ring side and the planet's root over both meshes (docs/life.md, "Planetary stages").
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from typing import TYPE_CHECKING, Protocol, cast

import numpy as np

from gearcli.core.channels import Channel
from gearcli.errors import ConfigError, DesignError
from gearcli.life import spectra
from gearcli.life.result import MemberLife, ModeLife, StageLife
from gearcli.life.spectra import StageLoads
from gearcli.results import RatedMember, StageResult
from gearcli.stages import kinds

if TYPE_CHECKING:
    from gearcli.config import DesignFile

#: a member's life over the duty (both modes), of planet ``planet`` (1-based) where the kind has planets
MemberLives = Callable[..., MemberLife]
#: the planet's root life over both its meshes (bending), of planet ``planet``
RootLives = Callable[..., ModeLife]


class LifeKind(Protocol):
    """What ``gearcli.life`` asks of a stage kind."""

    def require_rated(self, cfg: DesignFile, st: StageResult, source: str | None) -> None:
        """Refuse (``ConfigError`` naming the key) a stage whose members life rates lack a rating."""

    def k_gamma(self, st: StageResult) -> float:
        """The design's load-sharing factor K_γ (1 where nothing shares the load)."""

    def planet_forces(self, st: StageResult, series: Mapping[Channel, np.ndarray]) -> list[np.ndarray]:
        """The tangential force series of each planet's sun mesh (empty for a kind without planets)."""

    def member_rating(self, st: StageResult, member: str) -> RatedMember:
        """The rating ``member`` is rated by."""

    def material_member(self, member: str) -> str:
        """The design-file member (table key) whose material ``member`` is made of."""

    def contacts_per_turn(self, st: StageResult, member: str) -> int:
        """Load cycles of one tooth of ``member`` per revolution."""

    def member_speed_rpm(self, st: StageResult, member: str) -> float:
        """The speed that loads ``member``'s teeth, rpm."""

    def member_loads(self, loads: StageLoads, st: StageResult, member: str, planet: int | None) -> StageLoads:
        """The tooth-force classes ``member`` meets, from the stage's loads of a point."""

    def dynamic_loads(self, t: np.ndarray, series: Mapping[Channel, np.ndarray], st: StageResult,
                      k: int) -> StageLoads:
        """The stage's tooth-force classes over the window samples ``t`` of a simulation."""

    def stage_life(self, k: int, st: StageResult, loads: StageLoads, member_life: MemberLives,
                   root_life: RootLives) -> StageLife:
        """The stage's life record from its members' lives (``loads``: its tooth-force classes, the first
        point's: a planetary's are per planet on the dynamic route)."""


def life_kind(stage: object) -> LifeKind:
    """The life facet of a stage table or stage result (by its ``type``); a kind without one (a belt: no teeth to
    count) is refused by name (exit 2)."""
    kind = kinds.kind_of(stage)
    if kind not in kinds.kinds("life"):
        index = getattr(stage, "index", None)
        raise ConfigError(f'gearcli life rates gear teeth, and a stage of type "{kind}" has none to rate (no life '
                          "model of its kind): run gearcli design or simulate on this file",
                          key=None if index is None else f"stage[{index - 1}].type")
    return cast(LifeKind, kinds.facet(kind, "life"))


def _rating_of(st: StageResult):
    if st.rating is None:
        raise DesignError(f"stage {st.index}: no ISO 6336 rating; gearcli life needs a [rating] table")
    return st.rating


class ParallelLife:
    """A gear pair: the pinion and the gear, one contact per turn, the pair's own mesh-cycle peaks."""

    def require_rated(self, cfg: DesignFile, st: StageResult, source: str | None) -> None:
        return None

    def k_gamma(self, st: StageResult) -> float:
        return 1.0

    def planet_forces(self, st: StageResult, series: Mapping[Channel, np.ndarray]) -> list[np.ndarray]:
        return []

    def member_rating(self, st: StageResult, member: str) -> RatedMember:
        return cast(RatedMember, getattr(_rating_of(st), member))

    def material_member(self, member: str) -> str:
        return member

    def contacts_per_turn(self, st: StageResult, member: str) -> int:
        return 1

    def member_speed_rpm(self, st: StageResult, member: str) -> float:
        return abs(getattr(st, member).speed_rpm)

    def member_loads(self, loads: StageLoads, st: StageResult, member: str, planet: int | None) -> StageLoads:
        return loads

    def dynamic_loads(self, t: np.ndarray, series: Mapping[Channel, np.ndarray], st: StageResult,
                      k: int) -> StageLoads:
        return spectra.pair_loads(t, series, st, k)

    def stage_life(self, k: int, st: StageResult, loads: StageLoads, member_life: MemberLives,
                   root_life: RootLives) -> StageLife:
        return StageLife(k + 1, member_life("pinion"), member_life("gear"))


# A planetary stage's planet–ring mesh (static route): output key -> the member of its rating (InternalRatingResult:
# pinion = planet, gear = ring) and the stage's member that gives the material
RING_MEMBERS = {"ring": ("gear", "ring"), "planet_ring_side": ("pinion", "planet")}
SUN_PLANET_MEMBERS = {"pinion": "sun", "gear": "planet"}  # its sun–planet mesh's members in the design file


class PlanetaryLife:
    """A planetary stage: the sun (``pinion``) and the planets (``gear``) of its sun–planet mesh, and of its
    planet–ring mesh the ring and the planets' ring side; the sun and the ring meet N planets per turn relative
    to the carrier; on the dynamic route every planet's own spectra."""

    def require_rated(self, cfg: DesignFile, st: StageResult, source: str | None) -> None:
        """The planet–ring mesh must be rated: its ring and the planet's ring side are members."""
        if st.planetary is None or st.planetary.planet_ring.rating is not None:
            return
        standard = "iso6336" if cfg.rating is None else cfg.rating.standard
        if standard != "iso6336":  # the keys below are ISO's; another standard may rate sun–planet meshes only
            raise ConfigError(f'stage {st.index}: gearcli life rates the planet–ring mesh too (the ring is often the '
                              f'weakest member), and the rating standard "{standard}" leaves it unrated: choose a '
                              "standard that rates it", source=source, key="rating.standard")
        ring = cfg.stage[st.index - 1].ring  # type: ignore[union-attr]  # a planetary stage's table
        key = (f"stage[{st.index - 1}].ring.flank_roughness_Rz_um" if ring.flank_roughness_Rz_um is None
               else f"materials.{ring.material}")
        raise ConfigError(f"stage {st.index}: gearcli life rates the planet–ring mesh too (the ring is often the "
                          "weakest member): the ring needs flank_roughness_Rz_um and its material a treatment "
                          "and fatigue limits", source=source, key=key)

    def k_gamma(self, st: StageResult) -> float:
        assert st.planetary is not None
        return st.planetary.load_sharing_factor

    def planet_forces(self, st: StageResult, series: Mapping[Channel, np.ndarray]) -> list[np.ndarray]:
        assert st.planetary is not None
        return [series[Channel("tangential_force", f"stage{st.index}_planet{j}_sun")]
                for j in range(1, st.planetary.planet_count + 1)]

    def member_rating(self, st: StageResult, member: str) -> RatedMember:
        if member in RING_MEMBERS:
            assert st.planetary is not None and st.planetary.planet_ring.rating is not None
            return cast(RatedMember, getattr(st.planetary.planet_ring.rating, RING_MEMBERS[member][0]))
        return cast(RatedMember, getattr(_rating_of(st), member))

    def material_member(self, member: str) -> str:
        return RING_MEMBERS[member][1] if member in RING_MEMBERS else SUN_PLANET_MEMBERS[member]

    def contacts_per_turn(self, st: StageResult, member: str) -> int:
        """The sun (and the ring) meets its N planets per turn relative to the carrier; a planet's tooth meets the
        sun once on one flank, the ring once on the other."""
        assert st.planetary is not None
        return int(st.planetary.planet_count) if member in ("pinion", "ring") else 1

    def member_speed_rpm(self, st: StageResult, member: str) -> float:
        """Relative to the carrier (the sun–planet mesh's speeds are already)."""
        if member == "ring":
            assert st.planetary is not None
            return abs(st.planetary.ring.speed_rpm - st.planetary.carrier.speed_rpm)
        if member == "planet_ring_side":
            return abs(st.gear.speed_rpm)  # the planet's speed relative to the carrier
        return abs(getattr(st, member).speed_rpm)

    def member_loads(self, loads: StageLoads, st: StageResult, member: str, planet: int | None) -> StageLoads:
        """On the dynamic route: the sun's and the ring's of all N meshes, a planet's (``gear``,
        ``planet_ring_side``) of planet ``planet``'s (1-based) own mesh; on the static route a ring-mesh
        member's are the planet–ring mesh's static force."""
        dyn = loads.planetary
        if dyn is not None:
            if member in ("gear", "planet_ring_side"):
                assert planet is not None
                return (dyn.planet_sun if member == "gear" else dyn.planet_ring)[planet - 1]
            return dyn.ring if member == "ring" else dyn.sun
        if member in RING_MEMBERS:
            assert st.planetary is not None
            return spectra.static_loads(st.planetary.planet_ring.static_force_N.tangential)
        return loads

    def dynamic_loads(self, t: np.ndarray, series: Mapping[Channel, np.ndarray], st: StageResult,
                      k: int) -> StageLoads:
        return spectra.planetary_loads(t, series, st)

    def stage_life(self, k: int, st: StageResult, loads: StageLoads, member_life: MemberLives,
                   root_life: RootLives) -> StageLife:
        if loads.planetary is None:  # static route: the most loaded planet is the rating's (K_gamma)
            return StageLife(k + 1, member_life("pinion"), member_life("gear"), ring=member_life("ring"),
                             planet_ring_side=member_life("planet_ring_side"), planet_root=root_life())
        # dynamic route: every planet's own spectra; each planet member reports its worst planet
        assert st.planetary is not None
        planets = range(1, st.planetary.planet_count + 1)
        return StageLife(k + 1, member_life("pinion"), _worst([member_life("gear", j) for j in planets]),
                         ring=member_life("ring"),
                         planet_ring_side=_worst([member_life("planet_ring_side", j) for j in planets]),
                         planet_root=_worst_mode([root_life(j) for j in planets]))


def _severity(ml: ModeLife) -> tuple[float, float]:
    """Order of severity: the smaller spectrum safety (load multiplier to D = 1; none found: infinite), then the
    larger damage."""
    return (math.inf if ml.safety is None else ml.safety, -ml.damage)


def _first_of_worst(severity: Sequence[tuple[float, float]]) -> int:
    """Index of the most severe entry; of entries equal to it within 1e-9 (identical planets, whose simulated
    forces differ by round-off), the first."""
    worst = min(severity)

    def close(a: float, b: float) -> bool:
        return a == b or abs(a - b) <= 1e-9 * max(abs(a), abs(b))

    return next(i for i, s in enumerate(severity) if close(s[0], worst[0]) and close(s[1], worst[1]))


def _worst_mode(lives: Sequence[ModeLife]) -> ModeLife:
    """The most severe of the planets' lives."""
    return lives[_first_of_worst([_severity(ml) for ml in lives])]


def _worst(lives: Sequence[MemberLife]) -> MemberLife:
    """The planet whose member is most severely loaded: the more severe of its two modes decides (pitting and
    bending of one planet reported together)."""
    return lives[_first_of_worst([min(_severity(m.pitting), _severity(m.bending)) for m in lives])]


kinds.provide(kinds.PARALLEL, "life", ParallelLife())
kinds.provide("planetary", "life", PlanetaryLife())
