"""Result objects of ``gearcli life`` (JSON: docs/life.md, "Output")."""

from __future__ import annotations

from dataclasses import field

from gearcli.core.jsontypes import JsonObject
from gearcli.core.records import record
from gearcli.diagnostics import Diagnostic


@record
class Bin:
    """One load class of a member's spectrum: the tooth force it stands for, the stress it causes, the load
    cycles at it and the cycles the S–N curve allows (None: unbounded, below a flat endurance limit)."""

    point: str  # the duty point it belongs to
    force_N: float  # tangential force at the reference circle (as the rating takes it)
    stress_MPa: float
    cycles: float
    cycles_to_failure: float | None
    damage: float
    endurance_MPa: float  # the S–N curve's stress at its knee for this point (factor 1)


@record
class ModeLife:
    """Miner damage of one member and failure mode over the duty."""

    damage: float
    life_h: float | None  # duty hours / damage (None: no damage)
    safety: float | None  # load multiplier that makes D = 1 (None: none in 1e-3 .. 1e3)
    bins: tuple[Bin, ...]
    curve: str  # "Z_NT ISO 6336-2:2006 case_carburized" ...
    static_cycles: float  # the S–N curve's static node (a bin above it is beyond the static strength)
    knee_cycles: float
    sn: object = None  # the SNCurve of the duty's first point (for plots; not in JSON)
    planet: int | None = None  # dynamic route, a planet member: the planet (1-based) reported, the worst
    below_endurance: bool = False  # every class at or below the endurance limit (the knee): life_h None, infinite
    stress_safety: float | None = None  # the factor on stress to D = 1: √safety for pitting (σ_H ∝ √F), safety for
    # bending (σ_F ∝ F); ``safety`` is the load multiplier (JSON also ``load_multiplier``)


@record
class MemberLife:
    pitting: ModeLife
    bending: ModeLife


@record
class StageLife:
    """A stage's members. A planetary stage: ``pinion`` the sun and ``gear`` the planet in the sun–planet mesh;
    its planet–ring mesh adds ``ring``, ``planet_ring_side`` (the planet's flank and root in the ring mesh) and
    ``planet_root`` (the planet's root bending over both meshes, summed: docs/life.md)."""

    index: int  # 1-based
    pinion: MemberLife
    gear: MemberLife
    ring: MemberLife | None = None
    planet_ring_side: MemberLife | None = None
    planet_root: ModeLife | None = None  # bending only


#: a planetary stage's members in messages and tables: the sun–planet mesh's pinion is the sun, its gear the
#: planet's sun-mesh flank (the JSON keys stay the mesh's: docs/life.md)
PLANETARY_LABELS = {"pinion": "sun", "gear": "planet (sun mesh)", "planet_ring_side": "planet (ring mesh)",
                    "planet_root": "planet root (both meshes)"}


def member_label(st: StageLife, member: str) -> str:
    """``member`` (a StageLife key) of stage ``st`` as an engineer reads it: a planetary stage's pinion "sun", its
    gear "planet (sun mesh)"; a parallel stage's keys as they are."""
    return PLANETARY_LABELS.get(member, member) if st.ring is not None else member


def planet_flank(st: StageLife) -> tuple[str, str]:
    """A planetary stage's planet flank that its ``planet`` entry reports as pitting (DESIGN §10's member names):
    the more damaged over the duty of its sun-mesh side (``gear``) and its ring-mesh side (``planet_ring_side``),
    the sun side on a tie; (``flank``, the member key)."""
    assert st.planet_ring_side is not None
    ring_side = st.planet_ring_side.pitting.damage > st.gear.pitting.damage
    return ("ring_mesh", "planet_ring_side") if ring_side else ("sun_mesh", "gear")


@record
class BearingLife:
    """ISO 281 over the duty: the spectrum's equivalent load and the basic rating life it gives."""

    shaft: int
    position_mm: float
    kind: str
    dynamic_load_rating_kN: float
    equivalent_load_N: float
    revolutions: float  # over the duty's hours
    L10_Mrev: float | None
    L10_h: float | None
    loads_N: tuple[float, ...]  # the equivalent load P of each duty point
    planet_stage: int = 0  # a planet pin's bearing: its planetary stage, 1-based (shaft 0); 0 for a shaft's
    # ISO 76 over the duty and its starts (with C_0), ISO 281 modified life over the duty (with C_u):
    # docs/bearings.md; absent from JSON without their keys
    static_load_rating_kN: float | None = None
    static_equivalent_load_N: float | None = None  # the largest peak P_0
    static_safety: float | None = None  # its s_0
    static_safety_min: float | None = None  # the same s_0, under simulate's name for the smallest over a run
    fatigue_load_limit_kN: float | None = None
    pitch_diameter_mm: float | None = None
    reliability_percent: float | None = None
    kappa: float | None = None  # the lowest of the duty's load levels (its points' and its starts')
    a_ISO: float | None = None  # the duty's: L_nm / (a_1 L10)
    a_1: float | None = None
    L_nm_Mrev: float | None = None  # Palmgren–Miner over the points' L_nm
    L_nm_h: float | None = None
    kappa_points: tuple[float, ...] | None = None  # per duty point
    a_ISO_points: tuple[float | None, ...] | None = None  # None where the point leaves it unloaded


@record
class PointRun:
    """What one duty point was, and for the dynamic route how its simulation ran."""

    name: str
    hours: float
    torque_Nm: float
    speed_rpm: float
    K_v: tuple[float, ...]  # per stage: the rating's (static route) or the simulated max/static (dynamic)
    mesh_cycles: tuple[int, ...] = ()  # whole mesh cycles counted per stage (dynamic)
    peak_error: tuple[float, ...] = ()  # estimated relative error of the mesh-cycle peaks per stage (dynamic)
    solver: JsonObject | None = None  # method, engine, rtol, nfev, wall_s, steps, statistics_resolved
    settled: bool | None = None  # dynamic route: the window shown settled (gearcli.simulate.settle)
    start: JsonObject | None = None  # the point's starts (docs/life.md, "Starts"); None without


@record
class LifeResult:
    route: str  # "static" | "dynamic"
    miner: str  # the variant's name
    standard: str  # the rating's edition
    hours: float  # sum over the duty
    points: tuple[PointRun, ...]
    stages: tuple[StageLife, ...]
    bearings: tuple[BearingLife, ...]
    warnings: tuple[str, ...] = field(default_factory=tuple)
    diagnostics: tuple[Diagnostic, ...] = field(default_factory=tuple)  # the warnings' (code, data): the JSON's
    units: tuple[str, str] | None = None  # the design file's (speed, torque) key suffixes: the tables' torque unit
