"""``gearcli life``: duty points -> load spectra -> Miner damage, life and spectrum safety per member and
failure mode (ISO 6336-6), and ISO 281 bearing lives over the duty (docs/life.md).

Every duty point is a variant of the base design file made by ``--set`` overrides. This module neither
loads, designs nor simulates a point itself: the caller (:func:`gearcli.api.life`) injects how a point is
designed (``design_case``) and simulated (``evaluate``), the sweep's point evaluation. The dynamic route
simulates the points inside one ``engine.batch`` so that ``engine = "auto"`` takes the compiled engine for
them.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from contextlib import suppress
from dataclasses import replace
from typing import cast

from gearcli import engine
from gearcli.config import DesignFile
from gearcli.config.bounds import check_memory
from gearcli.config.overrides import SOURCE, blames_key
from gearcli.core.jsontypes import JsonObject
from gearcli.core.memo import remember
from gearcli.core.records import record
from gearcli.design.bearing_life import AXIAL_NOT_RATED, KAPPA_OUT_OF_RANGE
from gearcli.design.standards import standard_of
from gearcli.design.stiffness import MIN_LINE_LOAD_N_mm
from gearcli.diagnostics import (
    BEARING_LIFE_SHORT,
    BEYOND_STATIC_STRENGTH,
    DUTY,
    LOAD_SHARING,
    MOTOR_SPEED_MISMATCH,
    PEAK_OVER_RIGID,
    PEAK_UNDERSAMPLED,
    PEAK_UNRESOLVED,
    PEAKS_UNRESOLVED,
    STARTS_NOT_COUNTED,
    Diagnostic,
    carrying,
    messages,
    warning,
)
from gearcli.errors import ConfigError, DesignError, GearcliError, ResourceError, SimulationError
from gearcli.life import point_loads, spectra, verdicts
from gearcli.life.bearings import PointBearings, StartBearings, bearing_lives, bearing_warnings
from gearcli.life.duty import DutyPoint
from gearcli.life.miner import SNCurve, spectrum_safety
from gearcli.life.result import (
    BearingLife,
    Bin,
    LifeResult,
    MemberLife,
    ModeLife,
    PointRun,
    StageLife,
    member_label,
    planet_flank,
)
from gearcli.life.spectra import StageLoads
from gearcli.life.starts import StartData, label, member_start_cycles
from gearcli.model.motor_start import vfd_off_speed
from gearcli.rating.registry import DEFAULT as DEFAULT_STANDARD
from gearcli.rating.sn import miner_name
from gearcli.results import DesignResult, RatedMember, RatedMesh, StageResult
from gearcli.stages import kinds
from gearcli.stages.design import design_kind
from gearcli.stages.life import LifeKind, life_kind
from gearcli.sweep.worker import Case, CaseDesigner, PointEvaluator, Scene

MODES = ("pitting", "bending")
PEAK_TOLERANCE = 1e-3  # relative error of the mesh-cycle peaks (from the output sampling) without a warning
MEMBERS = ("pinion", "gear")
# a point's design warnings the duty says once per bearing over all its points (_point_design_warnings)
_DUTY_WORDS = frozenset({AXIAL_NOT_RATED, KAPPA_OUT_OF_RANGE, BEARING_LIFE_SHORT})


@record
class _PointData:
    """What the damage sums need of one evaluated point."""

    point: DutyPoint
    design: DesignResult  # with ratings (K_A = 1)
    cfg: DesignFile
    loads: list[StageLoads]  # per stage
    bearings: PointBearings  # each bearing's ISO 281 equivalent load and peak ISO 76 P_0 at this point
    run: PointRun
    start: StartData | None = None  # the point's start from rest, counted ``starts`` times (dynamic route)
    reference: Case | None = None  # an idle point's design at REFERENCE_NM: its classes' ratings scale from it


def _named(scene: Scene, point: DutyPoint, exc: ConfigError | DesignError) -> ConfigError | DesignError:
    """A point's bad value or infeasible design, naming the duty point (a key of its own ``set`` table by its
    path there)."""
    if isinstance(exc, ConfigError):
        own = [t.partition("=")[0].strip() for t in point.sets]
        if exc.key in own:  # a key of the point's own set table
            return ConfigError(exc.message, source=scene.source, key=f"{point.key}.set.{exc.key}")
        source = SOURCE if blames_key(exc.key, scene.sets) else scene.source
        return ConfigError(f"{point.key} ({point.name}): {exc.message}", source=source, key=exc.key)
    return DesignError(f"{point.key} ({point.name}): {exc.message}", source=scene.source, key=exc.key)


def _point_design(scene: Scene, point: DutyPoint, design_case: CaseDesigner,
                  extra: tuple[str, ...] = ()) -> Case:
    """The validated DesignFile and design of a point; errors name the duty point."""
    try:
        case = design_case(scene, (*point.overrides(), *extra))
    except (ConfigError, DesignError) as exc:
        raise _named(scene, point, exc) from None
    _require_rating(case.cfg, scene)
    return case


def _lengthened(exc: SimulationError | ResourceError, duration_s: float,
                design: DesignResult) -> SimulationError | ResourceError:
    """A point's run that failed (over its budget) at the duration the life route chose, not the file's: the
    run's own advice to shorten simulation.duration_s would not help, the route lengthens it again."""
    f_min = min(abs(st.mesh_frequency_Hz) for st in design.stages)
    return type(exc)(f"{exc}. The run's duration is the life route's: it runs each point until its steady window "
                     f"holds {spectra.MIN_WINDOW_MESH_CYCLES} whole mesh cycles of the slowest mesh ({f_min:.3g} Hz "
                     f"here), {duration_s:.4g} s, whatever simulation.duration_s says; rate this duty with --static")


def _require_rating(cfg: DesignFile, scene: Scene) -> None:
    if cfg.rating is None:
        raise ConfigError("gearcli life rates every member by ISO 6336-2/-3: add a [rating] table (with the "
                          "materials' treatment and fatigue limits, accuracy grades, roughness and [lubricant])",
                          source=scene.source, key="rating")


def _rating(stage: StageResult) -> RatedMesh:
    """A stage's rating (every life point has one: :func:`_require_rating`)."""
    if stage.rating is None:
        raise DesignError(f"stage {stage.index}: no ISO 6336 rating; gearcli life needs a [rating] table")
    return stage.rating


def _require_ring_rating(cfg: DesignFile, design: DesignResult, scene: Scene) -> None:
    """Every member life rates has its rating (a planetary stage's planet–ring mesh too: its kind says); a stage
    the file's standard left unrated (a plug-in standard that rates some kinds only) names the standard."""
    for st, kind in zip(design.stages, _life_kinds(design, scene), strict=True):
        if st.rating is None and cfg.rating is not None:
            raise ConfigError(f'stage {st.index}: the rating standard "{cfg.rating.standard}" leaves this '
                              f"{kinds.kind_of(st)} stage unrated, and gearcli life rates every gear stage's members:"
                              " choose a standard that rates it", source=scene.source, key="rating.standard")
        kind.require_rated(cfg, st, scene.source)


def _life_kinds(design: DesignResult, scene: Scene) -> list[LifeKind]:
    """Each stage's life facet; a stage of a kind without one (no teeth to count: a belt) is exit 2 naming it."""
    try:
        return [life_kind(st) for st in design.stages]
    except ConfigError as exc:
        raise ConfigError(exc.message, source=scene.source, key=exc.key) from None


def _static_point(scene: Scene, point: DutyPoint, design_case: CaseDesigner) -> _PointData:
    cfg, design = _point_design(scene, point, design_case)
    _require_ring_rating(cfg, design, scene)
    loads = [spectra.static_loads(st.static_force_N.tangential) for st in design.stages]
    k_v = tuple(_rating(st).K_v for st in design.stages)
    bearings = PointBearings(tuple(b.equivalent_load_N for b in design.bearings),
                             tuple(b.static_equivalent_load_N or 0.0 for b in design.bearings))
    return _PointData(point, design, cfg, loads, bearings, PointRun(point.name, point.hours, point.torque_Nm, point.speed_rpm, k_v))


def _dynamic_point(scene: Scene, point: DutyPoint, design_case: CaseDesigner,
                   evaluate: PointEvaluator) -> tuple[_PointData, tuple[Diagnostic, ...], tuple[Diagnostic, ...]]:
    """The point simulated and its spectra; its warnings, and notes that hold for every point (said once)."""
    extra: tuple[str, ...] = ("rating.dynamic_factor=1.0",)  # the spectrum replaces K_v
    cfg, design = _point_design(scene, point, design_case, extra)
    _require_ring_rating(cfg, design, scene)  # before its run: every member rated, as on the static route
    notes: list[Diagnostic] = []
    sharing = [st for st in design.stages if design_kind(st).shares_load]  # planets sharing the load
    given = cfg.rating is not None and cfg.rating.load_sharing_factor not in (None, 1.0)
    if sharing and given:
        errors = [getattr(cfg.stage[st.index - 1], "planet").position_error_um for st in sharing]  # noqa: B009
        if all(e is not None for e in errors):
            # the simulated planets share the load themselves (their position errors): K_gamma = 1 in the rating
            extra += ("rating.load_sharing_factor=1.0",)
            notes += [warning(LOAD_SHARING, f"stage {st.index}: the dynamic route takes the planets' load sharing from the simulation "
                      f"(stage[{st.index - 1}].planet.position_error_um); [rating] load_sharing_factor = "
                      f"{point_loads.k_gamma(st):g} is not applied", stage=st.index, load_sharing_factor=point_loads.k_gamma(st))
                      for st in sharing]
        else:
            # identical planets share equally in the model: the ISO allowance for unequal sharing stays
            notes += [warning(LOAD_SHARING, f"stage {st.index}: the simulated planets are identical (no planet.position_error_um), so "
                      f"[rating] load_sharing_factor = {point_loads.k_gamma(st):g} stays on the planet meshes' stresses and the "
                      "planet pins' loads; give the planets' position errors to simulate the sharing instead",
                              stage=st.index, load_sharing_factor=point_loads.k_gamma(st)) for st in sharing]
    if cfg.simulation.engine == "auto" and engine.available():
        # a duty is a batch of long runs: the compiled engine (DOP853 takes scipy's steps bit for bit) pays off
        extra += ("simulation.engine=compiled",)
    duration = spectra.duration_for(cfg, design)
    steps = spectra.steps_for(design, duration, cfg.simulation.steps)
    check_memory(cfg, fmt="json", series=False, source=scene.source, steps=steps)  # the point's run, in memory
    extra += (f"simulation.steps={steps}", f"simulation.duration_s={duration!r}")
    from_rest = cfg.simulation.steady == "window" or point.starts > 0
    run_notes: list[Diagnostic] = []
    if cfg.simulation.steady != "window" and point.starts > 0:
        # the periodic state keeps no run from rest: a point whose starts are counted runs from rest with its window
        # settled (the window route), or its start was empty (exit 2: "no whole mesh cycle")
        extra += ("simulation.steady=window",)
        run_notes.append(warning(DUTY, f"its {point.starts} starts are counted on the run from rest, so its spectrum is "
                                 "that run's settled window, not [simulation] steady = \"periodic\"'s periodic state "
                                 "(which keeps no start)", starts=point.starts))
    try:
        # a settled window of the run from rest (its start is counted); the periodic state would skip the start
        settle = "window" if from_rest else True
        (cfg, design), result, _ = evaluate(scene, (*point.overrides(), *extra), None, series=True, check=None,
                                            settle=settle)
    except (ConfigError, DesignError) as exc:
        raise _named(scene, point, exc) from None
    except (SimulationError, ResourceError) as exc:  # over its budget, or refused up front for its cost
        if duration <= cfg.simulation.duration_s:
            raise
        raise _lengthened(exc, duration, design) from None
    _require_rating(cfg, scene)
    loads = point_loads.window_loads(design, result)  # a periodic state: repeated; a stalled motor: refused
    loads = [spectra.referred(ld, spectra.resolved_force_N(result, k)) for k, ld in enumerate(loads)]
    bearing_loads = point_loads.dynamic_bearing_loads(cfg, design, result)
    start = point_loads.start_of(point, cfg, design, result) if point.starts else None
    sv = result.solver
    # the solver's and the output sampling's estimates (K_v is the window max over the static force: its sampling
    # error is the max's, over the static force)
    unresolved = [s.index for s in result.stages if (s.error_estimate is not None and not s.error_estimate.resolved)
                  or (s.sampling_error is not None and not s.sampling_error.resolved)]
    k_v_sampling = [None if s.sampling_error is None or not s.static_tangential_N or s.sampling_error.aliased else
                    s.sampling_error.max_N / abs(s.simulated_static_tangential_N or s.static_tangential_N)
                    for s in result.stages]
    solver: JsonObject = {"method": sv.method, "engine": sv.engine, "engine_reason": sv.engine_reason, "rtol": sv.rtol, "nfev": sv.nfev, "steps": sv.steps,
              "wall_s": sv.wall_s, "compile_s": sv.compile_s, "duration_s": result.final_time_s or duration, "output_samples": int(result.time_s.size), "window_s": list(result.window_s),
              "runs": sv.runs, "total_nfev": sv.total_nfev, "total_wall_s": sv.total_wall_s,  # every run: spent.py
              "statistics_resolved": not unresolved, "unresolved_stages": unresolved,
              "k_v_sampling_error": k_v_sampling,
              "energy_residual": sv.energy_residual}
    k_v = point_loads.k_v_factors(result, loads)  # over the static force of the load the run applies
    settled = result.steady.settled if result.steady is not None else None
    run = PointRun(point.name, point.hours, point.torque_Nm, point.speed_rpm, k_v,
                   mesh_cycles=tuple(ld.mesh_cycles for ld in loads), solver=solver,
                   peak_error=tuple(ld.peak_error for ld in loads), settled=settled)
    # the point's rating at K_v = 1: superseded
    warnings = [d for d in carrying(result.warnings, result.diagnostics) if d.message not in design.warnings
                and (point.starts or d.code not in RUN_UP_ONLY)]
    if cfg.input.drive == "motor" and result.extra and "motor" in result.extra:
        running = result.extra["motor"].get("operating_speed_rpm")
        said = any(d.code == MOTOR_SPEED_MISMATCH for d in warnings)  # the run's own, on its load
        if running and not said and abs(running - point.speed_rpm) > 0.02 * point.speed_rpm:
            warnings.append(warning(
                MOTOR_SPEED_MISMATCH, f"the motor (starting = \"{cfg.input.starting}\") runs at {running:.5g} rpm, not "
                f"the point's speed_rpm = {point.speed_rpm:.5g} its design and cycle counts assume: "
                + (vfd_off_speed(cfg.input.motor is not None and cfg.input.motor.torque_speed is not None)
                   if cfg.input.starting == "vfd" else
                   "give the speed the motor runs at, or starting = \"vfd\" (the supply follows the point's speed)"),
                operating_speed_rpm=running, speed_rpm=point.speed_rpm))
    warnings += run_notes
    for k, ld in enumerate(loads):
        if ld.peak_error > PEAK_TOLERANCE:
            warnings.append(warning(
                PEAKS_UNRESOLVED, f"stage {k + 1}: the mesh-cycle peaks are resolved to about {ld.peak_error:.1e} of "
                f"the force only (target {PEAK_TOLERANCE:g}; the damage goes with a high power of it); "
                f"sample finer: --set simulation.steps={4 * steps}", stage=k + 1, relative_error=ld.peak_error,
                target_relative=PEAK_TOLERANCE, steps=4 * steps))
    ref = None  # an idle point: its classes are rated from its design at a reference load (where that designs)
    if not all(st.static_force_N.tangential for st in design.stages):
        with suppress(ConfigError, DesignError):
            ref = _point_design(scene, replace(point, torque_Nm=REFERENCE_NM, sets=tuple(
                t for t in point.sets if not t.startswith("input.torque_Nm="))), design_case, extra)
    return _PointData(point, design, cfg, loads, bearing_loads, run, start, ref), tuple(warnings), tuple(notes)


#: warnings of a point's run that concern its run-up peak alone: a point without starts counts the settled window,
#: never the run from rest that reaches it, so they change no figure of the life ("give ramp_s > 0", "sample finer
#: for the run's peak") and are dropped there; a point with starts counts the run-up and keeps them
RUN_UP_ONLY = (PEAK_OVER_RIGID, PEAK_UNDERSAMPLED, PEAK_UNRESOLVED)


# ------------------------------------------------------------------------------------- damage
# A planetary stage's planet–ring mesh (static route): output key -> the member of its rating (InternalRatingResult:
# pinion = planet, gear = ring) and the stage's member that gives the material
RING_MEMBERS = {"ring": ("gear", "ring"), "planet_ring_side": ("pinion", "planet")}


def _member_rating(st: StageResult, member: str) -> RatedMember:
    """The rating of ``member`` (its stage kind's: a planetary's ring-mesh members the planet–ring mesh's)."""
    _rating(st)
    return life_kind(st).member_rating(st, member)


def _curve(cfg, design, k: int, member: str, mode: str, variant: str) -> SNCurve:
    """The S–N curve of ``member`` in ``mode`` as the file's rating standard gives it (``gearcli.rating``)."""
    stage = cfg.stage[k]
    own = life_kind(stage).material_member(member)
    treatment = str(cfg.materials[getattr(stage, own).material].treatment)
    return standard_of(cfg).sn_curve(cfg, _member_rating(design.stages[k], member), treatment, mode, variant)


def _contacts_per_turn(st, member: str) -> int:
    """Load cycles of one tooth per revolution (its stage kind's: a planetary's sun and ring meet N planets)."""
    return life_kind(st).contacts_per_turn(st, member)


def _member_speed_rpm(st: StageResult, member: str) -> float:
    """The member's speed in rpm that loads its teeth (a planetary stage's relative to the carrier)."""
    return life_kind(st).member_speed_rpm(st, member)


def _member_loads(pd: _PointData, k: int, member: str, planet: int | None = None) -> StageLoads:
    """The tooth-force classes the member meets (its stage kind's: a planetary's per planet on the dynamic route)."""
    st = pd.design.stages[k]
    return life_kind(st).member_loads(pd.loads[k], st, member, planet)


def _stress(pd: _PointData, k: int, member: str, mode: str, force_N: float, static_N: float) -> float:
    """The stress of a load class of ``force_N``: the point's rating at that force, every load-dependent factor at
    the class's own load where the standard re-rates the stage (ISO 6336-6: a start's peak many times an idle
    point's load does not carry the idle load's K_Hβ, K_Hα); else the point's stress scaled from its static force
    (σ_H ∝ √F_t, σ_F ∝ F_t)."""
    st = pd.design.stages[k]
    if not static_N and pd.reference is not None and force_N >= MIN_LINE_LOAD_N_mm * st.face_width_mm:
        pd = replace(pd, cfg=pd.reference.cfg, design=pd.reference.design)  # an idle point's start: its own load
        st = pd.design.stages[k]
        static_N = life_kind(st).member_loads(spectra.static_loads(st.static_force_N.tangential), st, member, None).static_N
    ratio = force_N / abs(static_N) if static_N else 0.0
    rated = _rated_at(pd, k, ratio) if ratio > 0.0 and ratio != 1.0 else None
    if rated is not None:
        return _member_rating(rated, member).stress_MPa(mode)
    m = _member_rating(st, member)
    return m.stress_MPa(mode) * (math.sqrt(ratio) if mode == "pitting" else ratio)


REFERENCE_NM = 1000.0  # an idle point's reference torque (any load: the class's factors are evaluated at its own force)
_RATED_AT: dict[tuple[int, int, float], tuple[DesignResult, StageResult | None]] = {}  # rated classes of the points lately rated
_RATED_AT_SIZE = 4096


def _rated_at(pd: _PointData, k: int, ratio: float) -> StageResult | None:
    """Stage ``k`` of the point rated at ``ratio`` times its static force by the file's standard (None where it
    does not re-rate): the whole stage where the standard re-rates it (``rate_stage_at_force``: a planetary stage's
    two meshes), else the gear pair's rating (``rate_at_force``); kept for the point's other members and modes."""
    key = (id(pd.design), k, ratio)
    found = _RATED_AT.get(key)
    if found is not None and found[0] is pd.design:
        return found[1]
    std, st = standard_of(pd.cfg), pd.design.stages[k]
    whole = getattr(std, "rate_stage_at_force", None)
    if whole is not None:
        rated = whole(pd.cfg, st, ratio)
    else:
        rerate = getattr(std, "rate_at_force", None)
        mesh = rerate(pd.cfg, st, ratio) if rerate is not None else None
        rated = None if mesh is None else replace(st, rating=mesh)
    return remember(_RATED_AT, key, (pd.design, rated), cap=_RATED_AT_SIZE)[1]


_Raw = tuple[str, float, float, float, SNCurve]  # (point, force, stress, cycles, curve)


def _raw_bins(points: Sequence[_PointData], k: int, member: str, mode: str, variant: str,
              planet: int | None = None) -> list[_Raw]:
    raw: list[_Raw] = []
    for pd in points:
        st = pd.design.stages[k]
        total = pd.point.hours * 60.0 * _member_speed_rpm(st, member) * _contacts_per_turn(st, member)
        curve = _curve(pd.cfg, pd.design, k, member, mode, variant)
        ld = _member_loads(pd, k, member, planet)
        for force, share in zip(ld.forces_N, ld.shares, strict=True):
            raw.append((pd.point.name, force, _stress(pd, k, member, mode, force, ld.static_N),
                        total * share, curve))
        if pd.start is not None and pd.start.count:  # the point's starts: classes of their own
            n = member_start_cycles(pd.start, pd.point.speed_rpm, _member_speed_rpm(st, member),
                                    _contacts_per_turn(st, member))
            sl = _member_loads(replace(pd, loads=pd.start.loads), k, member, planet)
            for force, share in zip(sl.forces_N, sl.shares, strict=True):
                raw.append((label(pd.point.name), force, _stress(pd, k, member, mode, force, sl.static_N),
                            n * share, curve))
    return raw


def _mode_life(points: Sequence[_PointData], k: int, member: str, mode: str, variant: str,
               hours: float, planet: int | None = None) -> ModeLife:
    ml = _from_raw(_raw_bins(points, k, member, mode, variant, planet), mode, hours, _curve_name(points, mode))
    return ml if planet is None else replace(ml, planet=planet)


def _curve_name(points: Sequence[_PointData], mode: str) -> str:
    return standard_of(points[0].cfg).curve_name(mode)


def _from_raw(raw: Sequence[_Raw], mode: str, hours: float, curve_name: str = "") -> ModeLife:
    """Miner damage and life of the bins ``raw`` in ``mode``; ``curve_name``: the standard's name of the curve."""
    exponent = 0.5 if mode == "pitting" else 1.0

    def damage_at(scale: float) -> float:
        return sum(n / c.cycles_to_failure(s * scale**exponent) for _, _, s, n, c in raw)

    bins = []
    for name, force, stress, n, c in raw:
        nf = c.cycles_to_failure(stress)
        bins.append(Bin(name, force, stress, n, None if math.isinf(nf) else nf, 0.0 if math.isinf(nf) else n / nf,
                        c.endurance_MPa))
    d = sum(b.damage for b in bins)
    first = raw[0][4]
    below = all(s < c.endurance_limit_MPa for _, _, s, _, c in raw)  # below the curve's endurance limit: infinite life
    load = spectrum_safety(damage_at)
    return ModeLife(d, hours / d if d > 0 and not below else None, load, tuple(bins),
                    curve_name,
                    first.static_cycles, first.knee[0], first, below_endurance=below,
                    stress_safety=None if load is None else load**exponent)


def _stage_life(points: Sequence[_PointData], k: int, variant: str, hours: float) -> StageLife:
    """A stage's members, as its kind names them (a planetary stage adds its planet–ring mesh: the ring, the
    planet's ring side, and the planet's root over both meshes; docs/life.md, "Planetary stages")."""
    def member_life(member: str, planet: int | None = None) -> MemberLife:
        return MemberLife(*(_mode_life(points, k, member, mode, variant, hours, planet) for mode in MODES))

    def root_life(planet: int | None = None) -> ModeLife:
        ml = _from_raw([*_raw_bins(points, k, "gear", "bending", variant, planet),
                        *_raw_bins(points, k, "planet_ring_side", "bending", variant, planet)], "bending", hours,
                      _curve_name(points, "bending"))
        return ml if planet is None else replace(ml, planet=planet)

    st = points[0].design.stages[k]
    return life_kind(st).stage_life(k, st, points[0].loads[k], member_life, root_life)


def _no_progress(label: str, done: int, total: int) -> None:
    pass


def _point_design_warnings(scene: Scene, point: DutyPoint, design_case: CaseDesigner,
                           base_warnings: Sequence[str], design: DesignResult | None = None) -> list[Diagnostic]:
    """What ``gearcli design`` says of the point (its torque, speed and ``set``: undercut, S_H below the
    minimum ...) beyond what it says of the base file, each naming the point. A bearing's axial force that its
    equivalent loads ignore is the duty's word, said once per bearing (a reversed point's F_a/F_r differs: the axial
    force's moment loads the other bearing; it repeated per point), as are a kappa below ISO 281's range (naming
    the points) and a life shorter than the required one (the duty's verdict, over all the points)."""
    if design is None:
        design = _point_design(scene, point, design_case).design
    return _of_point(point, [d for d in carrying(design.warnings, design.diagnostics)
                             if d.message not in base_warnings and d.code not in _DUTY_WORDS])


def _of_point(point: DutyPoint, diags: Sequence[Diagnostic]) -> list[Diagnostic]:
    """A duty point's own warnings: each message names the point, its data carries it as ``point``; the code and
    the rest of the data stay the diagnostic's."""
    return [replace(d, message=f"duty point {point.name}: {d.message}", data={**d.data, "point": point.name})
            for d in diags]


def compute_life(scene: Scene, points: Sequence[DutyPoint], *, design_case: CaseDesigner, evaluate: PointEvaluator,
                 route: str = "dynamic", variant: str = "iso",
                 progress: Callable[[str, int, int], None] | None = None, notes: Sequence[str | Diagnostic] = (),
                 base_warnings: Sequence[str] = (), held: Sequence[DutyPoint] = ()) -> LifeResult:
    """The life of every member and bearing over the duty ``points`` of the design file ``scene``; each point
    designed by ``design_case`` (the static route) or simulated by ``evaluate`` (the dynamic route). ``notes``
    (about the duty) lead the warnings; a point's design warnings beyond ``base_warnings`` (the base file's)
    follow, naming the point. ``held``: torques held at standstill (a history's zero-speed rows), designed for
    their static bearing loads alone (the bearings' s_0; no revolutions, no damage)."""
    progress = progress or _no_progress
    if not points:
        raise ConfigError("no duty points: add [[duty]] tables (name, hours, torque_Nm, speed_rpm) or give "
                          "--series FILE.csv", source=scene.source, key="duty")
    evaluated: list[_PointData] = []
    warnings: list[Diagnostic] = [n if isinstance(n, Diagnostic) else warning(DUTY, n) for n in notes]
    if route == "static":
        for i, p in enumerate(points):
            progress(p.name, i, len(points))
            evaluated.append(_static_point(scene, p, design_case))
            warnings += _point_design_warnings(scene, p, design_case, base_warnings, evaluated[-1].design)
    else:
        with engine.batch(len(points)):
            for i, p in enumerate(points):
                progress(p.name, i, len(points))
                try:
                    pd, run_warnings, point_notes = _dynamic_point(scene, p, design_case, evaluate)
                except GearcliError as exc:
                    if isinstance(exc, (ConfigError, DesignError)):
                        if exc.source is None:  # a rule of the run's own (its window too short): the point named
                            raise _named(scene, p, exc) from None
                        raise
                    own = str(exc).removeprefix(f"{scene.source}: ")  # a refusal that names the file already
                    raise type(exc)(f"{scene.source}: duty point {p.name}: {own}") from None
                evaluated.append(pd)
                warnings += _point_design_warnings(scene, p, design_case, base_warnings)
                warnings += [n for n in point_notes if n.message not in messages(warnings)]
                warnings += _of_point(p, run_warnings)
                warnings += verdicts.starts_warning(p, pd.start)
                if route != "static":
                    warnings += verdicts.starts_from_rest_warning(p, pd.cfg.input.drive, pd.cfg.input.ramp_s)
    if route != "static":
        warnings += verdicts.unexcited_warning([pd.point.name for pd in evaluated if _unexcited(pd.loads)])
    hours = sum(p.hours for p in points)
    first = evaluated[0].design
    stages = tuple(_stage_life(evaluated, k, variant, hours) for k in range(len(first.stages)))
    warnings += _static_warnings(stages)
    if route == "static" and any(p.starts for p in points):
        warnings.append(warning(STARTS_NOT_COUNTED, "the duty's starts ([[duty]] starts) are counted on the dynamic "
                                "route only (each point's start simulated from rest); --static rates the steady "
                                "points alone", points=[p.name for p in points if p.starts],
                                starts=sum(p.starts for p in points)))
    held_peaks = [tuple(b.static_equivalent_load_N or 0.0 for b in _point_design(scene, p, design_case).design.bearings)
                  for p in held]
    bearings = bearing_lives(evaluated, start_bearings(evaluated), held_peaks)
    warnings += bearing_warnings(evaluated, bearings, base_warnings)
    from_series = {p.key for p in points if not p.key.startswith("duty[")}  # a history's classes carry its name
    warnings += _verdicts(evaluated[0].cfg, stages, bearings, hours, next(iter(from_series), None))
    runs = tuple(replace(pd.run, start=start_record(pd, stages)) if pd.start is not None else pd.run
                 for pd in evaluated)
    miner = miner_name(variant, iso_curves=standard_of(evaluated[0].cfg).name == DEFAULT_STANDARD)
    return LifeResult(route, miner, _rating(first.stages[0]).standard, hours,
                      runs, stages, bearings, messages(warnings), tuple(warnings))


def _unexcited(loads: Sequence[StageLoads]) -> bool:
    """Whether every loaded stage met one force at every engagement of its window: its classes spread by no more
    than ``verdicts.UNEXCITED_K_V`` of the largest (a quiet window's are one class), no dynamic increment."""
    loaded = [ld for ld in loads if ld.static_N and ld.forces_N]
    return bool(loaded) and all(max(ld.forces_N) - min(ld.forces_N) <= verdicts.UNEXCITED_K_V * max(ld.forces_N)
                                for ld in loaded)


def _verdicts(cfg: DesignFile, stages: Sequence[StageLife], bearings: Sequence[BearingLife], hours: float,
              series: str | None) -> list[Diagnostic]:
    """The duty's verdicts (:mod:`gearcli.life.verdicts`): hours not the required life, spectrum safeties below the
    minimum, bearings outlived by the duty (``series``: the history file the points were classed from)."""
    rating = cfg.rating
    assert rating is not None  # every life point is rated (_require_rating)
    return [*verdicts.hours_warning(hours, rating.required_life_h, series),
            *verdicts.gear_warnings(stages, rating.min_safety_pitting, rating.min_safety_bending, hours,
                                    rating.required_life_h),
            *verdicts.bearing_life_warnings(bearings, hours, rating.required_life_h)]


def start_bearings(points: Sequence[_PointData]) -> list[StartBearings]:
    """The bearings' share of the duty points' starts (``[[duty]] starts = N``), one :class:`StartBearings` per
    point with starts: per bearing its revolutions over all the starts, the ISO 281 equivalent load of a start,
    its mean speed during a start and the start's peak ISO 76 P_0 (docs/life.md, "Starts"; docs/bearings.md)."""
    out = []
    for i, pd in enumerate(points):
        st = pd.start
        if st is None or not st.count or not st.bearing_loads_N:
            continue
        minutes = max(st.span_s[1] - st.span_s[0], 1e-12) / 60.0
        revs = tuple(member_start_cycles(st, pd.point.speed_rpm, b.speed_rpm, 1) for b in pd.design.bearings)
        out.append(StartBearings(i, revs, tuple(st.bearing_loads_N), tuple(r / st.count / minutes for r in revs),
                                 tuple(st.bearing_peak_static_N) or tuple(0.0 for _ in revs)))
    return out


def start_record(pd: _PointData, stages: Sequence[StageLife]) -> JsonObject:
    """``points[i].start``: the count, the start's peak |F_t| per stage, its damage per member and mode (the sum
    of its own classes' n/N), and per bearing its peak reactions and ISO 281 equivalent load."""
    assert pd.start is not None
    name = label(pd.point.name)
    damage: list[JsonObject] = []
    for st in stages:
        doc: dict[str, dict[str, float]] = {}
        members = [m for m in (*MEMBERS, *RING_MEMBERS) if getattr(st, m, None) is not None]
        for member in (*members, *(("planet_root",) if st.planet_root is not None else ())):
            ml = getattr(st, member) if member != "planet_root" else None
            modes = {"bending": st.planet_root} if ml is None else {m: getattr(ml, m) for m in MODES}
            doc[member] = {m: sum(b.damage for b in x.bins if b.point == name) for m, x in modes.items()
                           if x is not None}
        if st.planet_ring_side is not None and st.planet_root is not None:  # DESIGN §10's sun, planet (as stages[k])
            doc.update(sun=doc["pinion"], planet={"pitting": doc[planet_flank(st)[1]]["pitting"],
                                                  "bending": doc["planet_root"]["bending"]})
        damage.append(cast(JsonObject, doc))
    bearings: list[JsonObject] = []
    for j, b in enumerate(pd.design.bearings):
        if j < len(pd.start.bearing_peaks):
            bearings.append({"shaft": b.shaft, **({"planet_stage": b.planet_stage} if b.planet_stage else {}),
                             "position_mm": b.position_mm, **pd.start.bearing_peaks[j],
                             "equivalent_load_N": pd.start.bearing_loads_N[j]})
    return {"count": pd.start.count, "span_s": list(pd.start.span_s),
            "input_revolutions": pd.start.input_revolutions,
            "peak_tangential_N": list(pd.start.peak_tangential_N), "damage": damage, "bearings": bearings}


def _static_warnings(stages: Sequence[StageLife]) -> list[Diagnostic]:
    out = []
    for st in stages:
        for member in (*MEMBERS, *RING_MEMBERS):
            if getattr(st, member, None) is None:
                continue
            for mode in MODES:
                ml: ModeLife = getattr(getattr(st, member), mode)
                over = [b for b in ml.bins if b.cycles_to_failure is not None and b.cycles_to_failure < ml.static_cycles]
                if over:
                    out.append(warning(
                        BEYOND_STATIC_STRENGTH, f"stage {st.index} {member_label(st, member)} {mode}: {len(over)} load class(es) beyond "
                        f"the static strength (fewer than {ml.static_cycles:.3g} cycles to failure), e.g. at point "
                        f"{over[0].point}: the finite-life slope is extrapolated there", stage=st.index, member=member,
                        mode=mode, classes=len(over), static_cycles=ml.static_cycles, point=over[0].point))
    return out
