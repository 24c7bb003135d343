"""Planetary stages: internal-gear geometry (ISO 21771), Willis kinematics, assembly and adjacency checks,
per-planet forces with the load-sharing factor K_gamma, ISO 6336-1 stiffness of the planet–ring mesh
(docs/physics.md, "Planetary stages").

A planetary stage is designed as its sun–planet mesh (an external pair, computed by the parallel-stage
code in the carrier's frame: the sun drives the planet at the relative speed ω_s − ω_c with a third, a
N-th, of the sun torque) plus what this module adds: the members' absolute speeds and torques, the
carrier, and the planet–ring internal mesh.

Internal gear conventions (ISO 21771:2007): the ring's teeth are given positive in the design file and
its profile shift with the sign ISO 21771 and the commercial reports print (a negative x_r moves the ring's
tip circle outwards, away from the planets). With signed
tooth numbers z_r < 0 every external formula holds; written with |z_r|:

- d_r = |z_r| m_t, d_br = d_r cos α_t, d_ar = d_r − 2 m_n (h_aP* + x_r), d_fr = d_r + 2 m_n (h_fP* − x_r)
  (no tip alteration on the ring);
- inv α_wt = inv α_t + 2 tan α_n (x_p + x_r) / (z_p − |z_r|);  a_w = (|z_r| − z_p) m_t cos α_t / (2 cos α_wt);
- ε_α = [√(r_ap² − r_bp²) − √(r_ar² − r_br²) + a_w sin α_wt] / p_bt.

ISO 6336-1's single stiffness q' of an internal mesh is evaluated with z_n2 = ∞ (the internal gear's
terms C3/z_n2 and C7 x2/z_n2 vanish) and x2 = x_r; C_R is the mean of the planet's and the ring's
blank factors, as for any pair of different blanks.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import TYPE_CHECKING, TypeVar, cast

from gearcli.core.jsontypes import JsonObject
from gearcli.core.records import record
from gearcli.design import allowances_internal as ia
from gearcli.design import planetary_balance as bal
from gearcli.design import resonance as res
from gearcli.design import stiffness as stf
from gearcli.design.checks import (
    INTERFERENCE_TOLERANCE_PER_MODULE,
    contact_ratio_text,
    resonance_figure,
    resonance_text,
    usable_margin,
)
from gearcli.design.geometry import (
    base_diameter_mm,
    base_helix_angle_rad,
    form_point_from_base_tangent_mm,
    inverse_involute,
    involute,
    overlap_ratio,
    pitch_diameter_mm,
    rack_form_height_factor,
    tip_reach_mm,
    transverse_base_pitch_mm,
    transverse_module_mm,
    transverse_pressure_angle_rad,
)
from gearcli.design.inertia import annulus_inertia_kg_m2, mean_body_diameter_mm
from gearcli.design.input_checks import check_material
from gearcli.design.kinematics import Train, power_kW, speed_deg_s, speed_rpm
from gearcli.design.rating_results import InternalRatingResult, RatingResult
from gearcli.errors import DesignError
from gearcli.optional_results import CarrierResult, InternalMeshResult, PlanetaryResult
from gearcli.results import GearResult, Iso6336Factors, StageResult, StaticForces

if TYPE_CHECKING:
    from gearcli.config.schema import DesignFile, Gear, Material, PlanetaryStage, Stage

MEMBERS = ("sun", "carrier", "ring")
R = TypeVar("R", RatingResult, InternalRatingResult)
DEFAULT_RING_RIM_MODULES = 3.0  # ring body below the root, in modules, when no rim thickness is given


# ------------------------------------------------------------------------------ kinematics
def member_speeds(z_sun: int, z_ring: int, fixed: str, driven: str) -> dict[str, float]:
    """Signed member speeds for a unit speed of ``driven`` with ``fixed`` at rest (Willis; no negative zero)."""
    return bal.willis(z_sun, z_ring, fixed, driven)


def stage_mesh_efficiency(stage: PlanetaryStage, k: int) -> float:
    """η_m of every planet mesh of the stage (:mod:`gearcli.design.planetary_balance`)."""
    return bal.mesh_efficiency(stage.sun.teeth, stage.ring.teeth, stage.fixed, stage.input, stage.efficiency,
                               key=f"stage[{k}].efficiency")


def reverse_efficiency(stage: PlanetaryStage, k: int) -> float:
    """The stage's power efficiency when the load reverses (power from the output member): its meshes' η_m in
    the other power flow."""
    eta_m = stage_mesh_efficiency(stage, k)
    return bal.balance(stage.sun.teeth, stage.ring.teeth, stage.fixed, stage.input, eta_m, -1.0).efficiency


def stage_balance(stage: PlanetaryStage, k: int, output_torque_Nmm: float) -> tuple[bal.Balance, float]:
    """The stage's moment balance with losses and |T_sun| (N·mm) for the output member's torque."""
    eta_m = stage_mesh_efficiency(stage, k)
    b = bal.balance(stage.sun.teeth, stage.ring.teeth, stage.fixed, stage.input, eta_m,
                    1.0 if output_torque_Nmm >= 0.0 else -1.0)
    return b, abs(output_torque_Nmm) / abs(b.torques[stage.output])


# --------------------------------------------------------------------------- equivalent pair
def sun_planet_stage(stage: PlanetaryStage) -> Stage:
    """The sun–planet mesh as a parallel stage (pinion = sun, gear = planet), for the external-pair code."""
    from gearcli.config.schema import PairGear, Stage  # lazy: config (pydantic) stays out of design's import

    planet = PairGear.model_validate(stage.planet.model_dump(exclude={"count", "mass_kg", "position_error_um", "angles_deg"}))
    return Stage.model_validate({
        "normal_module_mm": stage.normal_module_mm, "normal_pressure_angle_deg": stage.normal_pressure_angle_deg,
        "helix_angle_deg": stage.helix_angle_deg, "pinion": stage.sun.model_dump(), "gear": planet.model_dump(),
        "backlash_mm": stage.backlash_mm, "efficiency": stage.efficiency,
        "mesh": None if stage.mesh is None else stage.mesh.model_dump(),
        "basic_rack": stage.basic_rack.model_dump(), "accuracy_grade": stage.accuracy_grade,
        "tip_relief_um": stage.tip_relief_um})


def mesh_train(k: int, stage: PlanetaryStage, kin: Train) -> Train:
    """A train whose stage k is the sun–planet mesh in the carrier's frame: sun at |ω_s − ω_c|, the mesh's
    (driving-side) force on the sun's lever (a 1/N of the sun torque, over η_m where the planet drives the sun),
    the planet at |ω_s − ω_c| z_s/z_p."""
    w_in = kin.shaft_speeds_rad_s[k]
    w = member_speeds(stage.sun.teeth, stage.ring.teeth, stage.fixed, stage.input)
    relative = abs(w["sun"] - w["carrier"]) * w_in
    t_out = kin.stage_torques_Nmm[k][1]
    b, t_sun_abs = stage_balance(stage, k, t_out)
    # the sun–planet mesh's (driving-side) force on the sun's lever, per planet, with the load's sign
    t_sun = math.copysign(t_sun_abs * b.sun_mesh, t_out) / stage.planet.count
    ratio = stage.planet.teeth / stage.sun.teeth
    # the planet's torque: its side's force on its lever, the driven side's eta_m F where the sun drives (as a lossy
    # pair's gear torque; equal to the ring mesh's planet-side force times r_p either way)
    planet_side = stage_mesh_efficiency(stage, k) if b.sun_drives else 1.0
    pad = k * (1.0,)
    return Train(ratios=(*pad, ratio), shaft_speeds_rad_s=(*(k * (0.0,)), relative, relative / ratio),
                 stage_torques_Nmm=(*(k * ((0.0, 0.0),)), (t_sun, t_sun * ratio * planet_side)),
                 load_torque_Nmm=kin.load_torque_Nmm)


# ------------------------------------------------------------------------- internal geometry
@record
class InternalGeometry:
    pitch_diameter_mm: float
    base_diameter_mm: float
    tip_diameter_mm: float
    root_diameter_mm: float
    working_pressure_rad: float
    center_distance_mm: float
    transverse_base_pitch_mm: float
    contact_ratio_transverse: float
    overlap_ratio: float
    face_width_mm: float


def ring_geometry(normal_module: float, normal_pressure_deg: float, helix_deg: float, z_planet: int,
                  x_planet: float, planet_tip_mm: float, z_ring: int, x_ring: float, face_width_mm: float,
                  addendum: float = 1.0, dedendum: float = 1.25) -> InternalGeometry:
    """The ring's diameters and the planet–ring mesh (ISO 21771, internal gear; module docstring)."""
    alpha_n, beta = math.radians(normal_pressure_deg), math.radians(helix_deg)
    m_t = transverse_module_mm(normal_module, beta)
    alpha_t = transverse_pressure_angle_rad(alpha_n, beta)
    d_r, d_p = pitch_diameter_mm(z_ring, m_t), pitch_diameter_mm(z_planet, m_t)
    db_r, db_p = base_diameter_mm(d_r, alpha_t), base_diameter_mm(d_p, alpha_t)
    da_r = d_r - 2.0 * normal_module * (addendum + x_ring)
    df_r = d_r + 2.0 * normal_module * (dedendum - x_ring)
    inv_wt = involute(alpha_t) + 2.0 * math.tan(alpha_n) * (x_planet + x_ring) / (z_planet - z_ring)
    if inv_wt <= 0.0:
        raise ValueError("the profile shifts leave no working pressure angle for the planet–ring mesh")
    alpha_wt = inverse_involute(inv_wt)
    a_w = 0.5 * (z_ring - z_planet) * m_t * math.cos(alpha_t) / math.cos(alpha_wt)
    p_bt = transverse_base_pitch_mm(m_t, alpha_t)
    if da_r <= db_r:
        raise ValueError(f"the ring's tip circle (d_a = {da_r:.4g} mm) lies inside its base circle "
                         f"(d_b = {db_r:.4g} mm): a smaller (more negative) ring profile shift is needed")
    g_alpha = (math.sqrt(max(0.25 * (planet_tip_mm ** 2 - db_p ** 2), 0.0))
               - math.sqrt(0.25 * (da_r ** 2 - db_r ** 2)) + a_w * math.sin(alpha_wt))
    return InternalGeometry(d_r, db_r, da_r, df_r, alpha_wt, a_w, p_bt, g_alpha / p_bt,
                            overlap_ratio(face_width_mm, beta, normal_module), face_width_mm)


# ------------------------------------------------------------------------------ the stage
def _blank(gear: Gear, normal_module: float) -> float:
    if gear.web_thickness_mm is None or gear.rim_thickness_mm is None:
        return stf.C_R
    return stf.gear_blank_factor(gear.web_thickness_mm, gear.rim_thickness_mm, gear.face_width_mm, normal_module)


def _ring_inertia_kg_m2(ring: Gear, normal_module: float, geo: InternalGeometry, density: float) -> float:
    if ring.inertia_kg_m2 is not None:
        return ring.inertia_kg_m2
    rim = ring.rim_thickness_mm if ring.rim_thickness_mm is not None else DEFAULT_RING_RIM_MODULES * normal_module
    return annulus_inertia_kg_m2(density, ring.face_width_mm, geo.root_diameter_mm + 2.0 * rim, geo.tip_diameter_mm)


def planet_mass_kg(planet_cfg, planet: GearResult, density: float) -> float:
    """Given ``mass_kg``, else the mass of the body whose inertia the model takes (:mod:`gearcli.design.compute`):
    ISO's body, a disc of d_m = (d_a + d_f)/2 with the bore, where the file describes it (bore, rim or web), else
    a solid disc of pitch diameter; face width b."""
    if planet_cfg.mass_kg is not None:
        return float(planet_cfg.mass_kg)
    if planet_cfg.body_given:
        outer, bore = mean_body_diameter_mm(planet.tip_diameter_mm, planet.root_diameter_mm), planet.bore_diameter_mm
    else:
        outer, bore = planet.pitch_diameter_mm, None
    return density * math.pi / 4.0 * (outer ** 2 - (bore or 0.0) ** 2) * planet.face_width_mm * 1e-9


def _member(g: GearResult, speed_rad_s: float, torque_Nmm: float) -> GearResult:
    return replace(g, speed_deg_s=speed_deg_s(speed_rad_s), speed_rpm=speed_rpm(speed_rad_s), torque_Nmm=torque_Nmm,
                   torque_Nm=torque_Nmm / 1000.0, power_kW=power_kW(torque_Nmm, speed_rad_s))


def planetary_result(cfg: DesignFile, k: int, kin: Train, mesh: StageResult) -> StageResult:
    """The planetary stage k: its sun–planet ``mesh`` (computed in the carrier's frame) with the members,
    the carrier and the planet–ring mesh attached."""
    stage = cast("PlanetaryStage", cfg.stage[k])  # this kind's table (its design facet calls this)
    n, z_s, z_p, z_r = stage.planet.count, stage.sun.teeth, stage.planet.teeth, stage.ring.teeth
    ring_mat: Material = cfg.materials[stage.ring.material]
    planet_mat: Material = cfg.materials[stage.planet.material]
    try:
        geo = ring_geometry(stage.normal_module_mm, stage.normal_pressure_angle_deg, stage.helix_angle_deg, z_p,
                            stage.planet.profile_shift, mesh.gear.tip_diameter_mm, z_r, stage.ring.profile_shift,
                            min(stage.planet.face_width_mm, stage.ring.face_width_mm), stage.basic_rack.addendum,
                            stage.basic_rack.dedendum)
    except ValueError as exc:
        raise DesignError(str(exc), key=f"stage[{k}].ring.profile_shift") from None
    w_in = kin.shaft_speeds_rad_s[k]
    unit = member_speeds(z_s, z_r, stage.fixed, stage.input)
    speeds = {m: unit[m] * w_in for m in MEMBERS}
    t_out = kin.stage_torques_Nmm[k][1]
    books, t_sun = stage_balance(stage, k, t_out)
    eta_m = stage_mesh_efficiency(stage, k)
    moments = {m: books.torques[m] * t_sun + 0.0 for m in MEMBERS}  # signed, N·mm: they sum to zero
    torques = {m: abs(v) for m, v in moments.items()}
    # the members
    sun = _member(mesh.pinion, speeds["sun"], torques["sun"])
    m_t = transverse_module_mm(stage.normal_module_mm, math.radians(stage.helix_angle_deg))
    ring_body = _ring_inertia_kg_m2(stage.ring, stage.normal_module_mm, geo, ring_mat.density_kg_m3)
    ring = GearResult(
        teeth=z_r, hand=(stage.ring.hand or stage.planet.hand or "spur") if stage.helix_angle_deg > 0 else "spur",
        profile_shift=stage.ring.profile_shift, face_width_mm=stage.ring.face_width_mm,
        pitch_diameter_mm=geo.pitch_diameter_mm, base_diameter_mm=geo.base_diameter_mm,
        tip_diameter_mm=geo.tip_diameter_mm, root_diameter_mm=geo.root_diameter_mm,
        speed_deg_s=speed_deg_s(speeds["ring"]), speed_rpm=speed_rpm(speeds["ring"]), torque_Nmm=torques["ring"],
        inertia_kg_m2=ring_body, inertia_given=stage.ring.inertia_kg_m2 is not None, body_inertia_kg_m2=ring_body,
        bore_diameter_mm=None, gear_blank_factor=_blank(stage.ring, stage.normal_module_mm),
        torque_Nm=torques["ring"] / 1000.0, power_kW=power_kW(torques["ring"], speeds["ring"]))
    planet = mesh.gear
    m_p = planet_mass_kg(stage.planet, planet, planet_mat.density_kg_m3)
    r_c = mesh.center_distance_mm
    own = stage.carrier.inertia_kg_m2 or 0.0
    translational = n * m_p * (r_c * 1e-3) ** 2
    carrier = CarrierResult(
        radius_mm=r_c, speed_deg_s=speed_deg_s(speeds["carrier"]), speed_rpm=speed_rpm(speeds["carrier"]),
        torque_Nmm=torques["carrier"], torque_Nm=torques["carrier"] / 1000.0,
        power_kW=power_kW(torques["carrier"], speeds["carrier"]), own_inertia_kg_m2=own,
        planets_translational_inertia_kg_m2=translational, inertia_kg_m2=own + translational)
    bal.check_assembly(k, z_s, z_r, n, stage.planet.angles_deg, r_c, geo.center_distance_mm,
                       planet.tip_diameter_mm, stage.normal_module_mm)
    # the planet–ring mesh: its (driving-side) force against the sun–planet mesh's
    ring_mesh = _ring_mesh(cfg, k, stage, geo, mesh, planet_mat, ring_mat, m_t, books.ring_mesh / books.sun_mesh)
    ring, ring_mesh = _with_ring_allowances(k, stage, geo, mesh, ring, ring_mesh)
    k_gamma = cfg.rating.load_sharing_factor if cfg.rating is not None and cfg.rating.load_sharing_factor else 1.0
    angles = bal.planet_angles_deg(n, stage.planet.angles_deg, 360.0 / (z_s + z_r))
    order = sorted(a % 360.0 for a in angles)
    gaps = [((b - a) % 360.0 or 360.0) for a, b in zip(order, order[1:] + order[:1], strict=True)]
    gap = min(gaps)
    # the planets as they sit (declared angles may space them unequally even where (z_s + z_r)/N is whole)
    equal = all(abs(g - 360.0 / n) <= bal.ANGLE_TOLERANCE_DEG for g in gaps)
    adjacency = 2.0 * r_c * math.sin(math.radians(gap) / 2.0) - planet.tip_diameter_mm if n > 1 else math.inf
    result = PlanetaryResult(
        fixed=stage.fixed, input=stage.input, output=stage.output, planet_count=n, ratio=kin.ratios[k],
        willis_ratio=-z_r / z_s, sun=sun, planet=planet, ring=ring, carrier=carrier, planet_mass_kg=m_p,
        planet_ring=ring_mesh, load_sharing_factor=k_gamma, equal_spacing=equal,
        tip_clearance_between_planets_mm=adjacency if math.isfinite(adjacency) else None,  # one planet: no neighbour
        concentricity_mm=geo.center_distance_mm - r_c, mesh_efficiency=eta_m,
        basic_efficiency=eta_m ** 2, moment_balance_Nm={m: v / 1000.0 for m, v in moments.items()},
        planet_angles_deg=tuple(angles), ring_treatment=ring_mat.treatment)
    return replace(mesh, ratio=kin.ratios[k], planetary=result, type="planetary")


def _ring_mesh(cfg: DesignFile, k: int, stage: PlanetaryStage, geo: InternalGeometry, mesh: StageResult,
               planet_mat: Material, ring_mat: Material, m_t: float, force_ratio: float) -> InternalMeshResult:
    """Forces, Hertz and ISO 6336-1 stiffness of one planet–ring mesh (its force ``force_ratio`` times the
    sun–planet mesh's: η_m or 1/η_m with losses, 1 without)."""
    beta = math.radians(stage.helix_angle_deg)
    alpha_t = transverse_pressure_angle_rad(math.radians(stage.normal_pressure_angle_deg), beta)
    beta_b = base_helix_angle_rad(beta, alpha_t)
    f = mesh.static_force_N  # lossless: F_t = T_s/(N r_s) = T_r/(N r_r), the same on the planet's both flanks
    forces = StaticForces(f.tangential * force_ratio, f.radial * force_ratio, f.axial * force_ratio,
                          f.normal * force_ratio)
    r_p, r_r = 0.5 * mesh.gear.pitch_diameter_mm, 0.5 * geo.pitch_diameter_mm
    radius = r_p * r_r / (r_r - r_p)
    modulus = stf.effective_modulus_MPa(planet_mat.youngs_modulus_MPa, planet_mat.poisson_ratio,
                                        ring_mat.youngs_modulus_MPa, ring_mat.poisson_ratio)
    zn_p = stf.virtual_teeth(stage.planet.teeth, beta, beta_b)
    c_r = 0.5 * (_blank(stage.planet, stage.normal_module_mm) + _blank(stage.ring, stage.normal_module_mm))
    factors = Iso6336Factors(C_M=stf.C_M, C_R=c_r,
                             C_B=stf.basic_rack_factor(stage.normal_pressure_angle_deg, stage.basic_rack.dedendum))
    f_t_ref = stf.reference_tangential_force_N(forces.tangential, geo.face_width_mm)
    line_load = f_t_ref * cfg.load.application_factor / geo.face_width_mm
    c_single = stf.single_pair_stiffness_N_mm_um(zn_p, math.inf, stage.planet.profile_shift, stage.ring.profile_shift,
                                                 beta, stage.normal_pressure_angle_deg, line_load, blank_factor=c_r,
                                                 dedendum_factor=stage.basic_rack.dedendum)
    c_mesh = stf.mesh_stiffness_N_mm_um(c_single, geo.contact_ratio_transverse)
    w_rel = abs(mesh.gear.speed_deg_s) * math.pi / 180.0
    # ISO 6336-1 resonance of the internal mesh: the ring taken infinitely heavy (held, or a rim far heavier
    # than a planet), so m_red is the planet's own m* = J*_p / r_bp²; n_E1 in the planet's rpm relative to the
    # carrier, the speed its mesh frequency is counted in
    planet = mesh.gear
    m_red = res.body_mass_per_width_kg_mm(planet.body_inertia_kg_m2, planet.face_width_mm, planet.base_diameter_mm)
    n_e1 = res.resonance_speed_rpm(stage.planet.teeth, c_mesh, m_red)
    law = cfg.contact_for(k)
    at_load = stf.mesh_law_stiffness(
        law.stiffness, law.exponent, hertz=stf.hertz_stiffness_N_mm1_5(radius, modulus),
        iso_normal_stiffness_N_mm=stf.iso6336_normal_stiffness_N_mm(c_mesh, geo.face_width_mm, beta_b),
        tangential_force_N=forces.tangential, face_width_mm=geo.face_width_mm,
        normal_pressure_rad=math.radians(stage.normal_pressure_angle_deg), helix_rad=beta)
    return InternalMeshResult(
        working_pressure_angle_deg=math.degrees(geo.working_pressure_rad), center_distance_mm=geo.center_distance_mm,
        transverse_base_pitch_mm=geo.transverse_base_pitch_mm, face_width_mm=geo.face_width_mm,
        contact_ratio_transverse=geo.contact_ratio_transverse, overlap_ratio=geo.overlap_ratio,
        contact_ratio_total=geo.contact_ratio_transverse + geo.overlap_ratio,
        static_force_N=StaticForces(forces.tangential, forces.tangential * math.tan(alpha_t), forces.axial,
                                    forces.normal),
        equivalent_radius_mm=radius, effective_modulus_MPa=modulus,
        hertz_stiffness_N_mm1_5=stf.hertz_stiffness_N_mm1_5(radius, modulus),
        iso6336_single_pair_stiffness_N_mm_um=c_single, iso6336_mesh_stiffness_N_mm_um=c_mesh,
        iso6336_mesh_stiffness_beta_N_mm_um=stf.mesh_stiffness_beta_N_mm_um(c_mesh), iso6336_factors=factors,
        mesh_frequency_Hz=stage.planet.teeth * w_rel / (2.0 * math.pi), reduced_mass_kg_mm=m_red,
        resonance_speed_rpm=n_e1, resonance_ratio=abs(planet.speed_rpm) / n_e1,
        resonance_lower_limit=res.lower_main_resonance_limit(line_load),
        resonance_range=res.resonance_range(abs(planet.speed_rpm) / n_e1, res.lower_main_resonance_limit(line_load)),
        mesh_stiffness=at_load, static_approach_mm=at_load.static_approach_mm,
        linearised_stiffness_N_mm=at_load.linearised_N_mm,
        planet_form_from_tangent_mm=max(form_point_from_base_tangent_mm(
            planet.pitch_diameter_mm, alpha_t, stage.normal_module_mm, stage.planet.profile_shift,
            rack_form_height_factor(stage.basic_rack.dedendum, stage.basic_rack.root_radius,
                                    math.radians(stage.normal_pressure_angle_deg))), 0.0))


def _with_ring_allowances(k: int, stage: PlanetaryStage, geo: InternalGeometry, mesh: StageResult, ring: GearResult,
                          ring_mesh: InternalMeshResult) -> tuple[GearResult, InternalMeshResult]:
    """The ring's x_E and manufactured root, the planet–ring backlash and ε_α with allowances (design.allowances_
    internal) where the planet or the ring has allowance keys; unchanged otherwise."""
    planet_cfg, ring_cfg = stage.planet, stage.ring
    if (planet_cfg.tooth_thickness_allowance_mm is None and planet_cfg.tip_diameter_allowance_mm is None
            and ring_cfg.tooth_thickness_allowance_mm is None):
        return ring, ring_mesh
    beta = math.radians(stage.helix_angle_deg)
    alpha_t = transverse_pressure_angle_rad(math.radians(stage.normal_pressure_angle_deg), beta)
    planet = mesh.gear
    internal = ia.InternalMesh(
        normal_module_mm=stage.normal_module_mm, normal_pressure_rad=math.radians(stage.normal_pressure_angle_deg),
        transverse_pressure_rad=alpha_t, base_helix_rad=base_helix_angle_rad(beta, alpha_t),
        transverse_module_mm=transverse_module_mm(stage.normal_module_mm, beta), teeth=(planet_cfg.teeth, ring_cfg.teeth),
        base_diameter_mm=(planet.base_diameter_mm, geo.base_diameter_mm), center_distance_mm=mesh.center_distance_mm)
    x_p = planet.generating_profile_shift or (planet_cfg.profile_shift, planet_cfg.profile_shift)
    thickness = ring_cfg.tooth_thickness_allowance_mm or (0.0, 0.0)
    tips = planet_cfg.tip_diameter_allowance_mm or (0.0, 0.0)
    a = ia.internal_allowances(internal, (planet_cfg.profile_shift, ring_cfg.profile_shift), (x_p[0], x_p[1]),
                               (thickness[0], thickness[1]),
                               (planet.tip_diameter_mm + tips[0], planet.tip_diameter_mm + tips[1]),
                               geo.tip_diameter_mm, geo.pitch_diameter_mm, stage.basic_rack.dedendum)
    if a.ring_manufactured_root_diameter_mm[0] <= geo.tip_diameter_mm:
        raise DesignError(f"the ring's upper tooth-thickness allowance cuts its root at d_f = "
                          f"{a.ring_manufactured_root_diameter_mm[0]:.4g} mm, not outside its tip circle d_a = "
                          f"{geo.tip_diameter_mm:.4g} mm: no tooth depth is left",
                          key=f"stage[{k}].ring.tooth_thickness_allowance_mm")
    if min(a.contact_ratio_transverse_with_allowances) <= 0.0:
        raise DesignError(f"the planet–ring contact ratio with allowances ε_α = "
                          f"{min(a.contact_ratio_transverse_with_allowances):.3f} ≤ 0: at the planet's lower tip the "
                          "tips do not reach the line of action, the teeth lose contact",
                          key=f"stage[{k}].planet.tip_diameter_allowance_mm")
    ring = replace(ring, generating_profile_shift=a.ring_generating_profile_shift,
                   manufactured_root_diameter_mm=a.ring_manufactured_root_diameter_mm)
    # tip clearances at the limits: the planet's largest tip on the ring's shallowest root (its thickest tooth), the
    # ring's tip on the planet's highest root (its thickest tooth, x_E,e)
    planet_root = planet.manufactured_root_diameter_mm or (planet.root_diameter_mm, planet.root_diameter_mm)
    clearance = (0.5 * (a.ring_manufactured_root_diameter_mm[0] - planet.tip_diameter_mm - tips[0])
                 - mesh.center_distance_mm,
                 0.5 * (geo.tip_diameter_mm - planet_root[0]) - mesh.center_distance_mm)
    return ring, replace(ring_mesh, backlash_circumferential_mm=a.backlash_circumferential_mm,
                         backlash_normal_mm=a.backlash_normal_mm,
                         contact_ratio_transverse_with_allowances=a.contact_ratio_transverse_with_allowances,
                         tip_clearance_with_allowances_mm=clearance)


# ---------------------------------------------------------------------------------- warnings
def planetary_warnings(stage_result: StageResult) -> list[tuple[str, JsonObject]]:
    """The ring mesh's contact ratio and its interference with the planet's flank (spacing, concentricity and
    adjacency are errors: :func:`gearcli.design.planetary_balance.check_assembly`), each with its check's data."""
    p = stage_result.planetary
    if p is None:
        return []
    out: list[tuple[str, JsonObject]] = []
    eps, total = p.planet_ring.contact_ratio_transverse, p.planet_ring.contact_ratio_total
    text = contact_ratio_text(f"stage {stage_result.index} planet–ring mesh", eps, total)
    if text:
        out.append((text, {"check": "contact_ratio", "mesh": "planet_ring", "contact_ratio_transverse": eps,
                           "contact_ratio_total": total}))
    interference = ring_interference_warning(stage_result)
    return out + ([interference] if interference else [])


def ring_resonance_warning(stage_result: StageResult) -> str | None:
    """ISO 6336-1's speed ranges for the planet–ring mesh (its own N = n_p/n_E1, the planet's speed relative to the
    carrier, the ring taken infinitely heavy), as for any mesh (:func:`gearcli.design.checks.resonance_warning`)."""
    p = stage_result.planetary
    assert p is not None  # a planetary stage's result
    m = p.planet_ring
    n = resonance_figure(m.resonance_ratio, m.resonance_lower_limit)
    head = (f"stage {stage_result.index}: planet–ring mesh resonance ratio N = n_p/n_E1 = {n} "
            f"(n_E1 = {m.resonance_speed_rpm:.4g} rpm of the planet relative to the carrier, ISO 6336-1)")
    return resonance_text(head, m.resonance_ratio, m.resonance_lower_limit, m.resonance_range)


def ring_tip_minimum_mm(ring_base_mm: float, center_distance_mm: float, working_pressure_deg: float,
                        planet_form_mm: float = 0.0) -> float:
    """The smallest tip diameter of an internal gear free of interference: its tip meets the line of action no
    nearer its own tangent point T2 than the pinion's lowest involute point, ``planet_form_mm`` (q ≥ 0) beyond the
    pinion's tangent point T1 (T2T1 = a_w sin α_wt), so d_a2,min = √(d_b2² + (2 (a_w sin α_wt + q))²); q = 0 is
    DIN 3960 / ISO 21771's involute interference limit (the tip inside the pinion's base circle)."""
    reach = center_distance_mm * math.sin(math.radians(working_pressure_deg)) + planet_form_mm
    return math.hypot(ring_base_mm, 2.0 * reach)


def ring_interference_warning(stage_result: StageResult) -> tuple[str, JsonObject] | None:
    """The ring's tip meeting the planet's flank below the planet's lowest involute point, as an external pair's
    ``interference`` (:func:`gearcli.design.checks.interference_warning`): along the line of action the ring's tip
    point lies g_r = √(r_ar² − r_br²) from the ring's tangent point T2, i.e. g_r − a_w sin α_wt beyond the planet's
    tangent point T1; the planet's rack-cut involute reaches down to q = r_p sin α_t − (h_FfP* − x_p) m_n / sin α_t
    from T1 (its root form circle d_Ff). A tip point inside T1 is involute interference (the tip meets the planet
    inside its base circle), one between T1 and q meets the planet's root fillet (DIN 3960: d_Nf < d_Ff); either
    way ε_α counts a path that carries no involute contact, and the data give the usable one."""
    p = stage_result.planetary
    assert p is not None  # a planetary stage's result
    mesh, ring, planet = p.planet_ring, p.ring, p.planet
    m_n = stage_result.normal_module_mm
    line = mesh.center_distance_mm * math.sin(math.radians(mesh.working_pressure_angle_deg))
    start = tip_reach_mm(ring.tip_diameter_mm, ring.base_diameter_mm) - line  # from T1, towards the pitch point
    form = mesh.planet_form_from_tangent_mm
    if start >= form - INTERFERENCE_TOLERANCE_PER_MODULE * m_n:
        return None
    usable = tip_reach_mm(planet.tip_diameter_mm, planet.base_diameter_mm) - max(start, form)
    eps = max(usable, 0.0) / mesh.transverse_base_pitch_mm
    d_min = ring_tip_minimum_mm(ring.base_diameter_mm, mesh.center_distance_mm, mesh.working_pressure_angle_deg, form)
    d_ff = 2.0 * math.hypot(0.5 * planet.base_diameter_mm, form) if form > 0.0 else None
    fillet = "" if d_ff is None else f" (its involute form circle d_Ff = {d_ff:.4g} mm)"
    if start < 0.0:
        d_base = ring_tip_minimum_mm(ring.base_diameter_mm, mesh.center_distance_mm, mesh.working_pressure_angle_deg)
        head = (f"stage {stage_result.index}: planet–ring involute interference: the ring's tip diameter d_a = "
                f"{ring.tip_diameter_mm:.4g} mm is below d_a,min = √(d_b² + (2 a_w sin α_wt)²) = {d_base:.4g} mm, so "
                "its tip meets the planet's flank inside the planet's base circle"
                + ("" if d_ff is None else f"; clear of the planet's root fillet{fillet} it needs d_a ≥ {d_min:.4g} mm"))
    else:
        head = (f"stage {stage_result.index}: planet–ring tip interference: the ring's tip meets the planet "
                f"{form - start:.3g} mm along the line of action below its involute form circle d_Ff = {d_ff:.4g} mm, "
                f"in its root fillet: the ring's tip diameter d_a = {ring.tip_diameter_mm:.4g} mm is below d_a,min = "
                f"√(d_b² + (2 (a_w sin α_wt + q))²) = {d_min:.4g} mm")
    message = (f"{head}; the usable transverse contact ratio is {eps:.3f}{usable_margin(eps)}, not ε_α = "
               f"{mesh.contact_ratio_transverse:.3f} (which counts that path); give the ring a more negative profile "
               "shift (a larger tip circle; with the planet's and sun's to stay concentric) or fewer planet teeth")
    return message, {"check": "interference", "mesh": "planet_ring", "member": "planet", "form_diameter_mm": d_ff,
                     "depth_mm": form - start, "tip_diameter_mm": ring.tip_diameter_mm, "min_tip_diameter_mm": d_min,
                     "contact_ratio_transverse": mesh.contact_ratio_transverse,
                     "contact_ratio_transverse_usable": eps}


def check_stage_inputs(cfg: DesignFile, k: int) -> None:
    """The ring's material must be defined, a helical ring has the planet's hand, ``planet.angles_deg`` one
    angle per planet (the sun and planet are checked as the sun–planet pair)."""
    stage = cast("PlanetaryStage", cfg.stage[k])  # this kind's table (its design facet calls this)
    check_material(stage.ring.material, cfg.materials, f"stage[{k}].ring.material")
    ring_hand, planet_hand = stage.ring.hand, stage.planet.hand
    if stage.helix_angle_deg > 0 and ring_hand is not None and ring_hand != planet_hand:
        raise DesignError(f'ring.hand = "{ring_hand}": an internal helical pair has the same hand on both gears, '
                          f'so the ring needs the planet\'s hand "{planet_hand}" (the sun\'s opposite)',
                          key=f"stage[{k}].ring.hand")
    angles = stage.planet.angles_deg
    if angles is not None and len(angles) != stage.planet.count:
        raise DesignError(f"planet.angles_deg needs one angle per planet ({stage.planet.count}), got "
                          f"{len(angles)}", key=f"stage[{k}].planet.angles_deg")


def load_sharing_of(stage: StageResult) -> float:
    """K_γ of a planetary stage's design (its planets' load-sharing factor)."""
    assert stage.planetary is not None  # a planetary stage's result
    return stage.planetary.load_sharing_factor


def with_load_sharing(stage: StageResult) -> StageResult:
    """A planetary stage's sun–planet mesh as rated: the most loaded planet's, K_gamma times the mean."""
    k = load_sharing_of(stage)
    if k == 1.0:
        return stage
    f = stage.static_force_N
    return replace(stage, static_force_N=StaticForces(k * f.tangential, k * f.radial, k * f.axial, k * f.normal),
                   pinion=replace(stage.pinion, torque_Nmm=k * stage.pinion.torque_Nmm,
                                  torque_Nm=k * stage.pinion.torque_Nm),
                   gear=replace(stage.gear, torque_Nmm=k * stage.gear.torque_Nmm, torque_Nm=k * stage.gear.torque_Nm))


def without_load_sharing(stage: StageResult) -> StageResult:
    """A planetary stage's design with K_gamma = 1: a run whose planets' position errors share the load itself."""
    assert stage.planetary is not None  # a planetary stage's result
    return replace(stage, planetary=replace(stage.planetary, load_sharing_factor=1.0))


def nominal_with_sharing(rating: R, k_gamma: float) -> R:
    """A rating made at K_gamma times the mean planet's force, with ISO's nominal stresses: σ_H0 and σ_F0 of the
    nominal (mean planet's) force, K_gamma listed as a load factor (σ_H = σ_H0 √(K_A K_gamma K_v K_Hβ K_Hα) and
    σ_F = σ_F0 K_A K_gamma K_v K_Fβ K_Fα are unchanged)."""
    if k_gamma == 1.0:
        return rating
    return replace(rating, K_gamma=k_gamma, sigma_H0_MPa=rating.sigma_H0_MPa / math.sqrt(k_gamma),
                   pinion=replace(rating.pinion, sigma_F0_MPa=rating.pinion.sigma_F0_MPa / k_gamma),
                   gear=replace(rating.gear, sigma_F0_MPa=rating.gear.sigma_F0_MPa / k_gamma))
