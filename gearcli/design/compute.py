"""``compute_design``: the design file in, a ``DesignResult`` out (docs/physics.md, "Design calculations").

This module only assembles: every formula lives, with its source, in ``geometry`` (ISO 21771),
``kinematics``, ``forces``, ``stiffness`` (Hertz, ISO 6336-1), ``inertia`` and ``checks``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import fields, is_dataclass, replace
from operator import itemgetter
from typing import TYPE_CHECKING

from gearcli.core.records import fields_getter, record
from gearcli.design import resonance as res
from gearcli.design import stiffness as stf
from gearcli.design.checks import (
    design_diagnostics,
    mesh_data,
    mesh_head,
    planet_ring_steel_warnings,
    stiffness_diagnostics,
)
from gearcli.design.forces import static_forces
from gearcli.design.geometry import BasicRackFactors, InfeasibleGeometry, PairGeometry, pair_geometry
from gearcli.design.inertia import (
    annulus_inertia_kg_m2,
    body_inertia_kg_m2,
    gear_inertia_kg_m2,
    mean_body_diameter_mm,
    shaft_inertias_kg_m2,
)
from gearcli.design.inputs import check_inputs
from gearcli.design.kinematics import Train, mesh_frequency_Hz, power_kW, speed_deg_s, speed_rpm, train_from_ratios
from gearcli.design.standards import standard_of
from gearcli.diagnostics import DESIGN, Diagnostic, warning
from gearcli.errors import DesignError, PluginError
from gearcli.results import (
    DesignResult,
    GearResult,
    Iso6336Factors,
    MeshStiffness,
    ShaftResult,
    StageResult,
    StaticForces,
)
from gearcli.stages import gear_design as _gear_design  # noqa: F401  # registers the built-in kinds' design facets
from gearcli.stages import kinds
from gearcli.stages.design import (
    checked_diagnostics,
    checked_figures,
    checked_result,
    design_kind,
    file_key,
    gear_pairs,
    pair_view,
)

if TYPE_CHECKING:
    from gearcli.config.schema import DesignFile, Gear, Material, Stage
    from gearcli.optional_results import BearingResult


def compute_design(cfg: DesignFile) -> DesignResult:
    """Ratios, speeds, torques, geometry, contact ratios, stiffness, static forces and warnings.

    Raises ``DesignError`` (with a 0-based key path) for an infeasible design: an unknown material,
    a helical pair without opposite hands, or a pair whose teeth cannot mesh.
    """
    kind = tuple(design_kind(s) for s in cfg.stage)
    pairs = pair_view(cfg)
    check_inputs(cfg)
    figures = tuple(checked_figures(s, k) for k, s in enumerate(cfg.stage))
    efficiencies, back = tuple(f[1] for f in figures), tuple(kind[k].reverse_efficiency(s, k) for k, s in enumerate(cfg.stage))
    kin = train_from_ratios(tuple(f[0] for f in figures), efficiencies, cfg.input.speed_rad_s_value,
                            cfg.load.torque_Nm_value * 1000.0, back)
    try:  # a key of the pair view (stage[k].pinion.x) named as the file names it (a planetary's sun.x)
        stages = tuple(checked_result(cfg.stage[k], k, kind[k].result(cfg, pairs, k, kin, _stage_result))
                       for k in range(len(cfg.stage)))
        rating_diagnostics: tuple = ()
        if cfg.rating is not None:  # the [rating] standard's (gearcli.rating; ISO 6336 by default, docs/iso6336.md)
            stages, rating_diagnostics = standard_of(cfg).rate_design(cfg, stages)
            rating_diagnostics += tuple(_not_rated(st) for st in stages if not design_kind(st).gear_pair)
            rating_diagnostics += _left_unrated(cfg.rating.standard, stages, rating_diagnostics)
    except DesignError as exc:
        raise DesignError(exc.message, key=file_key(cfg, exc.key), source=exc.source) from None
    for k, stage in enumerate(stages):
        _require_finite(stage, f"stage[{k}]", kinds.kind_of(stage), getattr(kind[k], "origin", None))
    out = kin.shaft_speeds_rad_s[-1]
    own = tuple(d for k, st in enumerate(stages) for d in checked_diagnostics(st, kind[k].diagnostics(st)))
    jammed = tuple(warning(DESIGN, f"{mesh_head(st)}: the minimum circumferential backlash is "
                           f"{st.backlash_circumferential_mm[1]:.4g} mm (< 0): at the upper tooth-thickness "
                           "allowances " + ("and the smallest centre distance" if st.planetary is None else
                                            "of sun and planet, on the carrier's radius,") + " the teeth jam"
                           + (f" (the maximum, {st.backlash_circumferential_mm[0]:.4g} mm, too: every pair within the "
                              "tolerances jams)" if st.backlash_circumferential_mm[0] < 0.0 else "")
                           + ("; thin the teeth (tooth_thickness_allowance_mm) or widen the centre distance"
                              if st.planetary is None else
                              "; thin the teeth (tooth_thickness_allowance_mm of the sun or the planet)"),
                           check="backlash_negative", stage=st.index, **mesh_data(st),
                           backlash_min_mm=st.backlash_circumferential_mm[1],
                           backlash_max_mm=st.backlash_circumferential_mm[0])
                   for _, st in gear_pairs(stages) if st.backlash_circumferential_mm is not None
                   and st.backlash_circumferential_mm[1] < 0.0)
    pins, bearings = _bearings(cfg, stages, kin)

    ignored = cfg.input.ignored_keys
    drive_notes = (warning(DESIGN, f"[input] {', '.join(ignored)}: {'keys' if len(ignored) > 1 else 'a key'} of "
                           f"drive = \"motor\"; drive = \"{cfg.input.drive}\" ignores "
                           f"{'it' if len(ignored) == 1 else 'them'}", check="drive", keys=list(ignored)),) \
        if ignored else ()
    reverse_notes = _reverse_efficiency_notes(cfg, kind, kin)

    def reflect(load_Nm: float) -> float:  # a load torque at the input, the losses in its power flow's direction
        return train_from_ratios(kin.ratios, efficiencies, 0.0, load_Nm * 1000.0, back).shaft_torque_Nmm(0) / 1000.0

    diagnostics = (*design_diagnostics(pairs, stages, speed_rpm(out), kin.shaft_torque_Nmm(0) / 1000.0,
                                       speed_rpm(kin.shaft_speeds_rad_s[0]), reflect), *own, *pins, *jammed,
                   *planet_ring_steel_warnings(cfg, stages), *stiffness_diagnostics(stages, _law_keys(cfg)), *_damping_notes(cfg),
                   *rating_diagnostics, *_bearing_diagnostics(cfg, bearings), *drive_notes, *reverse_notes)
    return DesignResult(
        title=cfg.title,
        stages=stages,
        shafts=_shaft_results(stages, kin),
        total_ratio=kin.total_ratio,
        input_speed_deg_s=speed_deg_s(kin.shaft_speeds_rad_s[0]),
        output_speed_deg_s=speed_deg_s(out),
        output_speed_rpm=speed_rpm(out),
        input_torque_Nmm=kin.shaft_torque_Nmm(0),
        output_torque_Nmm=kin.load_torque_Nmm,
        warnings=tuple(d.message for d in diagnostics),
        input_power_kW=power_kW(kin.shaft_torque_Nmm(0), kin.shaft_speeds_rad_s[0]),
        output_power_kW=power_kW(kin.load_torque_Nmm, out),
        bearings=bearings,
        diagnostics=diagnostics,
    )


def _law_keys(cfg: DesignFile) -> list[str]:
    """Per stage, the key that chose its mesh law, as ``stiffness_not_iso`` names it: ``[stage.mesh] stiffness =
    …`` where the stage overrides it, else ``[contact] stiffness = …`` (or its default)."""
    def text(value) -> str:
        return f'"{value}"' if isinstance(value, str) else f"{value:g}"

    return [f"[stage.mesh] stiffness = {text(st.mesh.stiffness)}"
            if st.mesh is not None and st.mesh.stiffness is not None else
            f"[contact] stiffness = {text(cfg.contact.stiffness)}" for st in cfg.stage]


def _damping_notes(cfg: DesignFile) -> tuple[Diagnostic, ...]:
    """IMPACT damping keys a ``damping_ratio`` overrides (DESIGN section 13: viscous damping wherever a ratio
    applies): said, never dropped without a word. ``[contact]``'s beside its own ratio, a ``[stage.mesh]``'s beside
    a ratio there or in ``[contact]`` (which then applies to every mesh, so no stage can ask for the ramp)."""
    tables = [(0, None), *((k + 1, st.mesh) for k, st in enumerate(cfg.stage) if st.mesh is not None)]
    found = []
    for stage, mesh in tables:
        keys, where = cfg.contact.ignored_impact_keys(mesh)
        if not keys:
            continue
        zeta = mesh.damping_ratio if where == "[stage.mesh]" and mesh is not None else cfg.contact.damping_ratio
        given = ", ".join(f"{name} = {value:g}" for name, value in keys.items())
        one = len(keys) == 1
        fix = ("remove damping_ratio for the IMPACT ramp, or the IMPACT keys" if where == "[stage.mesh]"
               or mesh is None else "for the ramp on this mesh, give damping_ratio in the other stages' "
               "[stage.mesh] instead of in [contact]")
        found.append(warning(DESIGN, f"{'[contact]' if mesh is None else f'stage {stage}: [stage.mesh]'} {given} "
                             f"{'has' if one else 'have'} no effect: {'it sets' if one else 'they set'} the IMPACT "
                             f"damping ramp, and damping_ratio = {zeta:g} given in {where} damps "
                             f"{'every mesh' if mesh is None else 'this mesh'} viscously instead; {fix}",
                             check="damping_ignored", keys=list(keys), damping_ratio=zeta,
                             damping_ratio_given_in=where, **({"stage": stage} if stage else {})))
    return tuple(found)


def _not_rated(st: StageResult) -> Diagnostic:
    """A stage whose kind has no gear mesh (a belt) is not rated: said, never dropped without a word."""
    kind = kinds.kind_of(st)
    return warning(DESIGN, f"stage {st.index}: a {kind} stage has no gear mesh to rate: [rating] leaves it unrated",
                   check="not_rated", stage=st.index, type=kind)


def _reverse_efficiency_notes(cfg: DesignFile, kind: tuple, kin: Train) -> tuple[Diagnostic, ...]:
    """A plug-in stage whose reverse efficiency differs from its forward one (a worm's), under a reversed load
    (power from the load back through the train): the design takes its reverse efficiency, the dynamics its forward
    one (a lossy element loses one efficiency whichever way the power flows, docs/plugins.md "Losses"), so the
    simulated torques and forces before it are eta / eta_r x the design's: said, with the factor."""
    out = []
    for k, table in enumerate(cfg.stage):
        back, eta = kind[k].reverse_efficiency(table, k), float(table.efficiency)
        name = kinds.kind_of(table)
        if (back is None or kin.stage_torques_Nmm[k][1] >= 0.0 or math.isclose(back, eta, rel_tol=1e-9)
                or name in kinds.BUILT_IN):  # gearcli's own kinds model theirs (a planetary's planet meshes)
            continue
        out.append(warning(DESIGN, f"stage {k + 1}: a reversed load: the design takes this {name} stage's reverse "
                           f"efficiency {back:.4g} (T_in = T_out eta_r / i), the dynamics its efficiency {eta:.4g} "
                           "(its element loses one efficiency whichever way the power flows): simulate's torques "
                           f"and forces before it are {eta / back:.4g}x the design's", check="reverse_efficiency",
                           stage=k + 1, type=name, reverse_efficiency=back, efficiency=eta, factor=eta / back))
    return tuple(out)


def _left_unrated(standard: str, stages: tuple[StageResult, ...],
                  said: tuple[Diagnostic, ...]) -> tuple[Diagnostic, ...]:
    """A gear stage, or a planetary stage's planet–ring mesh, that the ``[rating]`` standard returned unrated (a
    plug-in standard may rate some kinds only): said, naming the standard, never a stage silently without
    safeties. A planet–ring mesh the standard's own warnings already name (ISO 6336's ``mesh_not_rated``, which says
    which key is missing) is not said twice."""
    out = []
    for st in stages:
        if not design_kind(st).gear_pair:
            continue
        kind = kinds.kind_of(st)
        if st.rating is None:
            out.append(warning(DESIGN, f'stage {st.index}: the rating standard "{standard}" left this {kind} stage '
                               "unrated: it has no safeties", check="not_rated", stage=st.index, type=kind,
                               standard=standard))
        elif st.planetary is not None and st.planetary.planet_ring.rating is None and not any(
                d.data.get("stage") == st.index and d.data.get("mesh") == "planet_ring" for d in said):
            out.append(warning(DESIGN, f'stage {st.index}: the rating standard "{standard}" left the planet–ring '
                               "mesh unrated: the ring and the planet's ring side have no safeties",
                               check="not_rated", stage=st.index, type=kind, mesh="planet_ring", standard=standard))
    return tuple(out)


def _require_finite(obj, key: str, kind: str = kinds.PARALLEL, origin: str | None = None) -> None:
    """Every number of a stage result must be finite; a value in range that still overflows (a huge
    module with a huge density) is a bad design file, not a result (exit 2, never inf in the output). A plug-in
    kind's result (``origin`` its module) that holds one is the plug-in's fault (exit 1 naming it): its table's
    bounds are its own, and the design file has no module or density to check."""
    found = _non_finite(obj)
    if found is None:
        return
    name, value = found
    if origin is not None and origin.split(".")[0] != "gearcli":
        raise PluginError(f'stage type "{kind}" ({origin}): its design facet\'s result for stage {obj.index} has a non-finite '
                          f'{name} ({value}) (docs/plugins.md, "A stage kind")')
    raise DesignError(f"the design gives a non-finite {name} ({value}): check the magnitudes of "
                      "module, face width, density, speed and torque", key=key)


def _non_finite(obj) -> tuple[str, float] | None:
    """The first float field of ``obj`` (a dataclass, nested ones searched) that is not finite, with its value."""
    names, values = _dataclass_fields(type(obj)) or ((), _NO_FIELDS)
    row = values(obj)
    floats, nested = _plan(tuple(map(type, row)))
    if all(map(math.isfinite, floats(row))):  # its own floats finite (a design's every result): the first
        for i in nested:  # non-finite number, if any, is in a dataclass it holds, in their order
            if (found := _non_finite(row[i])) is not None:
                return found
        return None
    for name, value in zip(names, row, strict=True):
        if isinstance(value, float):
            if not math.isfinite(value):
                return name, value
        elif value.__class__ in _FIELDS and _FIELDS[value.__class__] is None:
            continue  # a class known not to be a dataclass (a str, an int, a tuple, None)
        elif _dataclass_fields(type(value)) is not None and (found := _non_finite(value)) is not None:
            return found
    return None


_NO_FIELDS = fields_getter(())
_FIELDS: dict[type, tuple[tuple[str, ...], Callable[[object], tuple]] | None] = {}


#: by the types of a row of field values: (its floats' getter, the indices of its dataclasses), at most
#: _PLANS_MAX (a result class's rows take a few: an optional field None or a number); a type held alive as a key
_PLANS: dict[tuple[type, ...], tuple[Callable[[tuple], tuple], tuple[int, ...]]] = {}
_PLANS_MAX = 256


def _plan(types: tuple[type, ...]) -> tuple[Callable[[tuple], tuple], tuple[int, ...]]:
    """Where a row of values of these types holds floats (read by one getter) and dataclasses (as the loop of
    :func:`_non_finite` tells them: a float first, then a dataclass), once per row of types."""
    plan = _PLANS.get(types)
    if plan is None:
        if len(_PLANS) >= _PLANS_MAX:
            _PLANS.clear()
        at = [i for i, t in enumerate(types) if issubclass(t, float)]
        floats = itemgetter(*at) if len(at) > 1 else (lambda row: (row[at[0]],)) if at else (lambda row: ())
        plan = _PLANS[types] = (floats, tuple(i for i, t in enumerate(types)
                                              if not issubclass(t, float) and _dataclass_fields(t) is not None))
    return plan


def _dataclass_fields(cls: type) -> tuple[tuple[str, ...], Callable[[object], tuple]] | None:
    """The field names of a dataclass and the function that reads their values (None: no dataclass), once per
    class: every sweep point checks the same result classes."""
    if cls not in _FIELDS:
        names = tuple(f.name for f in fields(cls)) if is_dataclass(cls) else None
        _FIELDS[cls] = None if names is None else (names, fields_getter(names))
    return _FIELDS[cls]


def _geometry(stage: Stage, k: int) -> PairGeometry:
    try:
        geo = pair_geometry(stage.normal_module_mm, stage.normal_pressure_angle_deg, stage.helix_angle_deg,
                             (stage.pinion.teeth, stage.gear.teeth),
                             (stage.pinion.profile_shift, stage.gear.profile_shift),
                             (stage.pinion.face_width_mm, stage.gear.face_width_mm),
                             BasicRackFactors(stage.basic_rack.addendum, stage.basic_rack.dedendum,
                                              stage.basic_rack.root_radius))
    except InfeasibleGeometry as exc:
        key = f"stage[{k}]" + (f".{exc.part}.{exc.field}" if exc.part else "")
        raise DesignError(exc.message, key=key) from None
    _require_tooth_left(stage.backlash_mm, geo, k)
    return geo


def _require_tooth_left(backlash_mm: float, geo: PairGeometry, k: int) -> None:
    """The normal backlash is the normal base pitch p_bn = π m_n cos α_n less both teeth's normal base thicknesses:
    one at or beyond p_bn leaves the teeth no thickness (the torsional model would turn the gap past a pitch)."""
    p_bn = geo.transverse_base_pitch_mm * math.cos(geo.base_helix_rad)
    if backlash_mm >= p_bn:
        raise DesignError(f"the normal backlash {backlash_mm:g} mm is not less than the normal base pitch "
                          f"p_bn = π m_n cos α_n = {p_bn:.4g} mm, which it shares with the two teeth: no tooth "
                          "thickness is left (backlash is normal, along the line of action)", key=f"stage[{k}].backlash_mm")


@record
class _Stiffness:
    """A stage's Hertz line contact and ISO 6336-1 mesh stiffness."""

    equivalent_radius_mm: float
    effective_modulus_MPa: float
    hertz_N_mm1_5: float
    single_pair_N_mm_um: float
    mesh_N_mm_um: float
    approach_mm: float
    linearised_N_mm: float
    factors: Iso6336Factors
    line_load_N_mm: float  # F_t K_A / b at which c' was evaluated
    law: MeshStiffness  # the contact law at the static load beside ISO's k_n


def _blank_factor(gear: Gear, normal_module_mm: float) -> float:
    """C_R of one member: ISO 6336-1's webbed-blank formula, or 1 for a solid disc."""
    if gear.web_thickness_mm is None or gear.rim_thickness_mm is None:
        return stf.C_R
    return stf.gear_blank_factor(gear.web_thickness_mm, gear.rim_thickness_mm, gear.face_width_mm, normal_module_mm)


def _iso_factors(stage: Stage) -> Iso6336Factors:
    """C_M, C_R (mean of the two members, as ISO 6336-1 takes it for blanks of different design), C_B."""
    c_r = 0.5 * (_blank_factor(stage.pinion, stage.normal_module_mm) + _blank_factor(stage.gear, stage.normal_module_mm))
    return Iso6336Factors(C_M=stf.C_M, C_R=c_r,
                          C_B=stf.basic_rack_factor(stage.normal_pressure_angle_deg, stage.basic_rack.dedendum))


def _stiffness(cfg: DesignFile, k: int, geo: PairGeometry, forces: StaticForces,
               materials: tuple[Material, Material], driving_side: bool = False) -> _Stiffness:
    """Hertz (seed 3.3), ISO 6336-1 c' and c_γα, and the static point of the stage's own contact law (at the
    law's force: ``forces`` as they are where they are the driving side's, ``MeshResult``)."""
    stage, law = cfg.pair(k), cfg.contact_for(k)
    radius = stf.equivalent_radius_mm(0.5 * geo.pitch_diameter_mm[0], 0.5 * geo.pitch_diameter_mm[1])
    modulus = stf.effective_modulus_MPa(materials[0].youngs_modulus_MPa, materials[0].poisson_ratio,
                                        materials[1].youngs_modulus_MPa, materials[1].poisson_ratio)
    hertz = stf.hertz_stiffness_N_mm1_5(radius, modulus)
    teeth, shifts = (stage.pinion.teeth, stage.gear.teeth), (stage.pinion.profile_shift, stage.gear.profile_shift)
    zn = stf.smaller_wheel_first(teeth, tuple(stf.virtual_teeth(z, geo.helix_rad, geo.base_helix_rad) for z in teeth),
                                 shifts)
    x = stf.smaller_wheel_first(teeth, shifts, shifts)
    f_t_ref = stf.reference_tangential_force_N(forces.tangential, geo.face_width_mm)
    line_load = f_t_ref * cfg.load.application_factor / geo.face_width_mm
    factors = _iso_factors(stage)
    c_single = stf.single_pair_stiffness_N_mm_um(zn[0], zn[1], x[0], x[1], geo.helix_rad,
                                                 stage.normal_pressure_angle_deg, line_load,
                                                 blank_factor=factors.C_R, dedendum_factor=stage.basic_rack.dedendum)
    c_mesh = stf.mesh_stiffness_N_mm_um(c_single, geo.contact_ratio_transverse)
    law_force = forces.tangential if driving_side else \
        stf.law_tangential_force_N(forces.tangential, stage.efficiency)  # the run's static load
    at_load = stf.mesh_law_stiffness(
        law.stiffness, law.exponent, hertz=hertz,
        iso_normal_stiffness_N_mm=stf.iso6336_normal_stiffness_N_mm(c_mesh, geo.face_width_mm, geo.base_helix_rad),
        tangential_force_N=law_force, face_width_mm=geo.face_width_mm,
        normal_pressure_rad=geo.normal_pressure_rad, helix_rad=geo.helix_rad)
    coefficient = at_load.K
    h0 = stf.static_approach_mm(forces.normal * (law_force / forces.tangential if forces.tangential else 1.0),
                                coefficient, law.exponent)
    return _Stiffness(radius, modulus, hertz, c_single, c_mesh, h0,
                      stf.linearised_stiffness_N_mm(coefficient, law.exponent, h0), factors, line_load, at_load)


def _check_bore(gear: Gear, root_diameter_mm: float, key: str) -> None:
    """A bore must leave material under the tooth roots (else the body's inertia is zero or negative)."""
    bore = gear.bore_diameter_mm
    if bore is not None and gear.inertia_kg_m2 is None and bore >= root_diameter_mm:
        raise DesignError(f"the bore ({bore:g} mm) must be smaller than the root diameter d_f = "
                          f"{root_diameter_mm:.4g} mm of this gear", key=key)


def _gear_result(gear: Gear, i: int, geo: PairGeometry, helical: bool, density_kg_m3: float,
                 speed_rad_s: float, torque_Nmm: float) -> GearResult:
    d = geo.pitch_diameter_mm[i]
    d_m = mean_body_diameter_mm(geo.tip_diameter_mm[i], geo.root_diameter_mm[i])
    body = body_inertia_kg_m2(gear.inertia_kg_m2, density_kg_m3, gear.face_width_mm, d_m, gear.bore_diameter_mm)
    return GearResult(
        teeth=gear.teeth,
        hand=(gear.hand or "spur") if helical else "spur",
        profile_shift=gear.profile_shift,
        face_width_mm=gear.face_width_mm,
        pitch_diameter_mm=d,
        base_diameter_mm=geo.base_diameter_mm[i],
        tip_diameter_mm=geo.tip_diameter_mm[i],
        root_diameter_mm=geo.root_diameter_mm[i],
        speed_deg_s=speed_deg_s(speed_rad_s),
        speed_rpm=speed_rpm(speed_rad_s),
        torque_Nmm=torque_Nmm,
        inertia_kg_m2=_model_inertia_kg_m2(gear, density_kg_m3, d, d_m),
        inertia_given=gear.inertia_kg_m2 is not None,
        body_inertia_kg_m2=body,
        bore_diameter_mm=gear.bore_diameter_mm,
        gear_blank_factor=_blank_factor(gear, geo.normal_module_mm),
        torque_Nm=torque_Nmm / 1000.0,
        power_kW=power_kW(torque_Nmm, speed_rad_s),
    )


def _model_inertia_kg_m2(gear: Gear, density_kg_m3: float, pitch_mm: float, mean_mm: float) -> float:
    """The inertia the torsional model uses: given; else ISO's body (d_m, bore) when the design file describes
    the body (bore/rim/web); else, as before these keys existed, a solid disc of pitch diameter."""
    if gear.inertia_kg_m2 is not None or not gear.body_given:
        return gear_inertia_kg_m2(gear.inertia_kg_m2, density_kg_m3, gear.face_width_mm, pitch_mm)
    return annulus_inertia_kg_m2(density_kg_m3, gear.face_width_mm, mean_mm, gear.bore_diameter_mm or 0.0)


@record
class _Resonance:
    """A stage's ISO 6336-1 resonance figures: reduced mass, resonance speed and ratio."""

    reduced_mass_kg_mm: float
    speed_rpm: float
    ratio: float
    lower_limit: float
    range: str


def _resonance(pinion: GearResult, gear: GearResult, mesh_N_mm_um: float, line_load_N_mm: float,
               planets: int = 1) -> _Resonance:
    """m_red, n_E1 and N of ISO 6336-1 with index 1 the smaller wheel (m_red is symmetric anyway). ``planets``: a
    planetary stage's sun (the pinion) meets that many planets (the gear), so each mesh moves 1/N of the sun:
    m_red = m*_s m*_p / (m*_s + N m*_p) (ISO 6336-1's planetary form; N = 1 is the pair's)."""
    masses = [res.body_mass_per_width_kg_mm(g.body_inertia_kg_m2, g.face_width_mm, g.base_diameter_mm)
              for g in (pinion, gear)]
    m_red = res.reduced_mass_kg_mm(masses[0] / planets, masses[1])
    # n_E1 in the smaller wheel's speed; a planetary sun–planet mesh's in the sun's (relative to the carrier), as
    # ISO 6336-1's planetary clause and the reference report state it (N, the ratio, is the same either way)
    small = pinion if planets > 1 else stf.smaller_wheel_first((pinion.teeth, gear.teeth), (pinion, gear),
                                                                (pinion.profile_shift, gear.profile_shift))[0]
    n_e1 = res.resonance_speed_rpm(small.teeth, mesh_N_mm_um, m_red)
    ratio = abs(small.speed_rpm) / n_e1
    lower = res.lower_main_resonance_limit(line_load_N_mm)
    return _Resonance(m_red, n_e1, ratio, lower, res.resonance_range(ratio, lower))


def _bearings(cfg: DesignFile, stages: tuple[StageResult, ...],
              kin: Train) -> tuple[tuple[Diagnostic, ...], tuple[BearingResult, ...]]:
    """The ``[[bearing]]`` tables' position warnings and results at the design's load; none without tables (the
    shaft statics and ISO 281 are imported only then: a one-shot run without bearings never loads them)."""
    if not cfg.bearing:
        return (), ()
    from gearcli.design.shafts import bearing_results, pin_bearing_warnings  # lazy: start-up time without bearings

    pins = tuple(warning(DESIGN, m, check="bearing_position", **data) for m, data in pin_bearing_warnings(cfg, stages))
    return pins, bearing_results(cfg, stages, [speed_rpm(w) for w in kin.shaft_speeds_rad_s])


def _bearing_diagnostics(cfg: DesignFile, bearings: tuple[BearingResult, ...]) -> list[Diagnostic]:
    """The bearings' warnings (:func:`gearcli.design.bearing_life.bearing_diagnostics`); none without bearings."""
    if not bearings:
        return []
    from gearcli.design.bearing_life import bearing_diagnostics  # lazy: start-up time of a file without bearings

    return bearing_diagnostics(cfg, bearings)


def _stage_result(cfg: DesignFile, k: int, kin: Train, planets: int = 1, /, *,
                  driving_side: bool = False) -> StageResult:
    """A parallel stage, or a planetary stage's sun–planet mesh (``planets``: its planet count, for m_red;
    ``driving_side``: ``kin`` gives the mesh's driving-side force, :class:`gearcli.stages.design.MeshResult`)."""
    stage = cfg.pair(k)
    geo = _geometry(stage, k)
    materials = (cfg.materials[stage.pinion.material], cfg.materials[stage.gear.material])
    t_pinion, t_gear = kin.stage_torques_Nmm[k]
    forces = static_forces(t_pinion, 0.5 * geo.pitch_diameter_mm[0], geo.normal_pressure_rad,
                           geo.transverse_pressure_rad, geo.helix_rad)
    s = _stiffness(cfg, k, geo, forces, materials, driving_side)
    w_p, w_g, helical = kin.shaft_speeds_rad_s[k], kin.shaft_speeds_rad_s[k + 1], stage.helix_angle_deg > 0
    for i, part in enumerate(("pinion", "gear")):
        _check_bore(getattr(stage, part), geo.root_diameter_mm[i], f"stage[{k}].{part}.bore_diameter_mm")
    pinion = _gear_result(stage.pinion, 0, geo, helical, materials[0].density_kg_m3, w_p, t_pinion)
    gear = _gear_result(stage.gear, 1, geo, helical, materials[1].density_kg_m3, w_g, t_gear)
    r = _resonance(pinion, gear, s.mesh_N_mm_um, s.line_load_N_mm, planets)
    result = StageResult(
        index=k + 1, ratio=kin.ratios[k], efficiency=stage.efficiency,
        normal_module_mm=stage.normal_module_mm, transverse_module_mm=geo.transverse_module_mm,
        normal_pressure_angle_deg=stage.normal_pressure_angle_deg,
        transverse_pressure_angle_deg=math.degrees(geo.transverse_pressure_rad),
        working_pressure_angle_deg=math.degrees(geo.working_pressure_rad),
        helix_angle_deg=stage.helix_angle_deg, base_helix_angle_deg=math.degrees(geo.base_helix_rad),
        center_distance_mm=geo.center_distance_mm, transverse_base_pitch_mm=geo.transverse_base_pitch_mm,
        face_width_mm=geo.face_width_mm, contact_ratio_transverse=geo.contact_ratio_transverse,
        overlap_ratio=geo.overlap_ratio, contact_ratio_total=geo.contact_ratio_transverse + geo.overlap_ratio,
        mesh_frequency_Hz=mesh_frequency_Hz(stage.pinion.teeth, w_p),
        equivalent_radius_mm=s.equivalent_radius_mm, effective_modulus_MPa=s.effective_modulus_MPa,
        hertz_stiffness_N_mm1_5=s.hertz_N_mm1_5, static_approach_mm=s.approach_mm,
        linearised_stiffness_N_mm=s.linearised_N_mm, static_force_N=forces,
        iso6336_single_pair_stiffness_N_mm_um=s.single_pair_N_mm_um, iso6336_mesh_stiffness_N_mm_um=s.mesh_N_mm_um,
        backlash_mm=stage.backlash_mm, pinion=pinion, gear=gear,
        tip_alteration_coefficient=geo.tip_alteration_coefficient,
        iso6336_mesh_stiffness_beta_N_mm_um=stf.mesh_stiffness_beta_N_mm_um(s.mesh_N_mm_um),
        iso6336_factors=s.factors, reduced_mass_kg_mm=r.reduced_mass_kg_mm, resonance_speed_rpm=r.speed_rpm,
        resonance_ratio=r.ratio, resonance_lower_limit=r.lower_limit, resonance_range=r.range,
        mesh_stiffness=s.law,
    )
    return _with_allowances(result, stage, geo, k) if stage.has_allowances else result


def _with_allowances(result: StageResult, stage: Stage, geo: PairGeometry, k: int) -> StageResult:
    """The stage with its allowances' figures (ISO 21771, docs/iso6336.md "Tooth-thickness allowances")."""
    from gearcli.design.allowances import NO_ALLOWANCE, AllowanceInfeasible, pair_allowances  # lazy: with them only

    def pair(value: list[float] | None) -> tuple[float, float]:
        return NO_ALLOWANCE if value is None else (value[0], value[1])

    members = (stage.pinion, stage.gear)
    try:
        a = pair_allowances(geo, (stage.pinion.teeth, stage.gear.teeth),
                            (stage.pinion.profile_shift, stage.gear.profile_shift),
                            (pair(members[0].tooth_thickness_allowance_mm),
                             pair(members[1].tooth_thickness_allowance_mm)),
                            (pair(members[0].tip_diameter_allowance_mm), pair(members[1].tip_diameter_allowance_mm)),
                            pair(stage.center_distance_allowance_mm), stage.basic_rack.dedendum)
    except AllowanceInfeasible as e:  # no involute mesh, or no contact, at these limits: the key to blame
        raise DesignError(e.message, key=f"stage[{k}]." + (f"{e.part}." if e.part else "") + e.field) from None
    except ValueError:  # InfeasibleGeometry, or a limit the checks above do not foresee
        raise DesignError("the allowances leave no involute mesh (the teeth at their limits cannot mesh at the "
                          "centre distance's limits): check their magnitudes against the module", key=f"stage[{k}]") from None
    gears = tuple(replace(g, generating_profile_shift=a.generating_profile_shift[i],
                          manufactured_root_diameter_mm=a.manufactured_root_diameter_mm[i])
                  for i, g in enumerate((result.pinion, result.gear)))
    return replace(result, pinion=gears[0], gear=gears[1], backlash_circumferential_mm=a.backlash_circumferential_mm,
                   backlash_normal_mm=a.backlash_normal_mm,
                   contact_ratio_transverse_with_allowances=a.contact_ratio_transverse_with_allowances)


def _shaft_results(stages: tuple[StageResult, ...], kin: Train) -> tuple[ShaftResult, ...]:
    inertias = shaft_inertias_kg_m2(tuple(design_kind(s).inertia(s, "input") for s in stages),
                                    tuple(design_kind(s).inertia(s, "output") for s in stages))
    return tuple(
        ShaftResult(index=j + 1, speed_deg_s=speed_deg_s(w), speed_rpm=speed_rpm(w),
                    torque_Nmm=kin.shaft_torque_Nmm(j), inertia_kg_m2=inertias[j],
                    torque_Nm=kin.shaft_torque_Nmm(j) / 1000.0, power_kW=power_kW(kin.shaft_torque_Nmm(j), w))
        for j, w in enumerate(kin.shaft_speeds_rad_s)
    )
