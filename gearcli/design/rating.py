"""Strength rating of a stage: ISO 6336-2 (pitting) and ISO 6336-3 (tooth root), 2006 editions, method B,
with the load factors of ISO 6336-1 (docs/iso6336.md, "Strength rating").

Assembles the factors of ``rating_factors`` on a stage the design has computed: geometry, c′, c_γα, c_γβ,
N = n1/n_E1 and N_S come from the ``StageResult`` (ISO 6336-1 and ISO 21771 are not computed twice).

Choices where the contract is silent (docs/iso6336.md says each):

- ISO's pinion (index 1) is the wheel with fewer teeth whichever member drives; JSON ``pinion``/``gear`` are
  gearcli's members (driving/driven), and ``Z_BD`` is Z_B on the smaller wheel, Z_D on the larger.
- F_t is the nominal tangential force at the reference circle, floored at 1 N per mm of face width as the
  stiffness is (so an unloaded stage gets large, finite safeties rather than infinities).
- Pitch and profile deviations come from the stage's accuracy grade by ISO 1328-1:1995 at the range means;
  the larger of the two members counts. K_Hα uses max(f_pb, f_fα) − y_α, as the published KISSsoft
  report of the NREL 5 MW stage does (its K_Hα = 1.069 follows from f_fα, not from f_pb).
- Z_L, Z_V, Z_R take the lower σ_Hlim of the pair; Z_W acts on the through-hardened member of a pair with a
  surface-hardened mate (HB ≈ 0.95 HV from ``surface_hardness_HV``), 1 otherwise.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import TYPE_CHECKING

from gearcli.core.records import record
from gearcli.core.text import beside
from gearcli.design import rating_factors as rf
from gearcli.design import rating_root as rr
from gearcli.design.allowances import manufactured_tooth_depth_mm
from gearcli.design.checks import mesh_data
from gearcli.design.rating_load import LoadFactors, MeshLoad, resolve_load_factors
from gearcli.design.rating_results import MemberRating, RatingResult
from gearcli.design.stiffness import reference_tangential_force_N, smaller_wheel_first
from gearcli.diagnostics import Diagnostic, warning
from gearcli.errors import DesignError
from gearcli.rating.registry import ISO_TITLE
from gearcli.stages import kinds
from gearcli.stages.design import design_kind, gear_pairs, member_name

if TYPE_CHECKING:
    from gearcli.config.schema import DesignFile, Gear, Material
    from gearcli.core.jsontypes import JsonValue
    from gearcli.results import GearResult, StageResult

STANDARD = ISO_TITLE  # "ISO 6336:2006 method B": the rating registry keeps it from any other standard
STRESS_CORRECTION_TEST_GEAR = 2.0  # Y_ST (ISO 6336-3:2006)
HB_PER_HV = 0.95  # Brinell from Vickers for steels below ~450 HV (ISO 18265, approximately)
PITTING_LOW = "pitting_safety_low"
BENDING_LOW = "bending_safety_low"
OUT_OF_RANGE = "rating_out_of_range"
NOT_ISO = "rating_not_iso"  # a rating option that departs from the standard ([rating] virtual_tooth_count)
EPS_ALPHA_N_MAX = 2.5  # ISO 6336-2:2006 (Scope): teeth of other basic racks while ε_αn = ε_α/cos² β_b < 2.5
Q_S_RANGE = (1.0, 8.0)  # the notch parameter range of Y_S, method B (ISO 6336-3:2006, 7.2)
# the lowest modulus of ISO 6336's gear materials: its Z_E table's cast tin bronze (103,000 N/mm²) under grey cast
# iron's 118,000, steel's 206,000; ISO 6336-5's strength values are steels' and cast irons' (polymers: VDI 2736)
ISO_MATERIAL_MODULUS_MIN_MPa = 100_000.0


# ------------------------------------------------------------------------------ required inputs
def check_rating_inputs(cfg: DesignFile) -> None:
    """With ``[rating]`` present, every key the rating needs must be given (``DesignError`` naming it)."""
    if cfg.rating is None:
        return
    if cfg.lubricant is None or cfg.lubricant.viscosity_40C_mm2_s is None:
        raise DesignError("the strength rating ([rating]) needs the oil's viscosity at 40 °C (Z_L): add "
                          "[lubricant] viscosity_40C_mm2_s", key="lubricant.viscosity_40C_mm2_s")
    used: set[str] = set()
    for k, stage in gear_pairs(cfg.stage):  # a kind without a gear pair (a belt) is not rated
        if stage.accuracy_grade is None:
            raise DesignError("the strength rating ([rating]) needs the ISO 1328-1 accuracy grade of every stage "
                              "(K_v, K_Hα)", key=f"stage[{k}].accuracy_grade")
        for part in ("pinion", "gear"):
            gear: Gear = getattr(stage, part)
            for name, what in (("flank_roughness_Rz_um", "Z_R"), ("root_roughness_Rz_um", "Y_RrelT")):
                if getattr(gear, name) is None:
                    raise DesignError(f"the strength rating ([rating]) needs the roughness Rz of every member "
                                      f"({what})", key=f"stage[{k}].{part}.{name}")
            used.add(gear.material)
    for name in sorted(used):
        material = cfg.materials.get(name)
        if material is None:
            continue  # check_material names the unknown material
        for key in ("treatment", "contact_fatigue_limit_MPa", "bending_fatigue_limit_MPa"):
            if getattr(material, key) is None:
                raise DesignError(f"the strength rating ([rating]) needs {key} of every material a stage uses "
                                  "(ISO 6336-5)", key=f"materials.{name}.{key}")


# ---------------------------------------------------------------------------------- the rating
def rate_design(cfg: DesignFile, stages: tuple[StageResult, ...]) -> tuple[tuple[StageResult, ...], tuple]:
    """Every gear-pair stage with its ``rating`` (unchanged without ``[rating]``) and the safety warnings; a stage
    whose kind has no gear pair (a belt) as it is."""
    if cfg.rating is None:
        return stages, ()
    pairs = dict(gear_pairs(stages))
    rated = tuple(replace(st, rating=rate_stage(cfg, k, st)) if k in pairs else st for k, st in enumerate(stages))
    return rated, (*not_iso_diagnostics(cfg), *(d for k, st in enumerate(rated) if k in pairs
                                                 for d in range_diagnostics(cfg, k, st) + safety_diagnostics(cfg, st)),
                   *reversal_diagnostics(cfg, [st for k, st in enumerate(rated) if k in pairs]))


def reversal_diagnostics(cfg: DesignFile, stages: list[StageResult]) -> list[Diagnostic]:
    """Warnings (``rating_out_of_range``) where the rating's unidirectional load is not the load the teeth see:

    - a lossy parallel stage under load reversal (a negative load torque: the gear drives, the back flanks carry the
      load) is rated as ISO 6336-1 writes F_t, from the pinion's torque T_1, which the mesh's losses put η below the
      driving gear's torque over its radius: named with both forces (σ_H grows as √F_t, σ_F as F_t);
    - a load whose fluctuations (``[load] fluctuation``, or a torque drive's ``torque_ripple``) sum to more than 100 %
      of it changes sign: the teeth bend both ways, for which ISO 6336-5 takes 0.7 of σ_FE (the idler rule, Y_M
      = 0.7, as on a planet); this rating keeps Y_M = 1 on every member but an idler's."""
    out = []
    for st in stages:
        if kinds.kind_of(st) != "parallel" or not st.static_force_N.tangential < 0.0:
            continue
        rated = abs(st.static_force_N.tangential)
        driving = abs(st.gear.torque_Nmm) / (0.5 * st.gear.pitch_diameter_mm)
        if not driving > rated * (1.0 + 1e-9):  # a lossless mesh: the back flanks' force is the rated one
            continue
        out.append(warning(OUT_OF_RANGE, f"stage {st.index}: load reversal (negative load torque): the gear drives and "
                           "the back flanks carry the load, rated as the drive flanks (symmetric teeth) at ISO 6336-1's "
                           f"F_t = T_1 / r_1 = {rated:.5g} N from the pinion's torque; the driving gear's |T_2| / r_2 is "
                           f"{driving:.5g} N, {driving / rated:.4g}x it through the mesh's losses (σ_H "
                           f"{math.sqrt(driving / rated):.4g}x, σ_F {driving / rated:.4g}x at that force)",
                           stage=st.index, quantity="load_reversal", value=rated, driving_force_N=driving))
    fluctuating = [(f"[load] fluctuation amplitudes sum to {a:.4g} %", a)
                   for a in (sum(f.amplitude_percent for f in cfg.load.fluctuation),) if a > 100.0]
    if cfg.input.drive == "torque":
        fluctuating += [(f"[input] torque_ripple amplitudes sum to {a:.4g} %", a)
                        for a in (sum(r.amplitude_percent for r in cfg.input.torque_ripple),) if a > 100.0]
    out += [warning(OUT_OF_RANGE, f"{what} of the torque: the load changes sign and the teeth bend both ways; ISO 6336-5 "
                    "takes 0.7 of σ_FE for alternating bending (the idler rule, Y_M = 0.7), which this rating does not "
                    "apply but on an idler: S_F of every other member is up to 1/0.7 = 1.43x too high",
                    stage=None, quantity="alternating_load", value=a) for what, a in fluctuating]
    return out


def not_iso_diagnostics(cfg: DesignFile) -> list[Diagnostic]:
    """A warning where a ``[rating]`` option departs from ISO 6336: the tooth root's load angle γ_e with z/cos³ β
    (``virtual_tooth_count = "cos3"``, docs/iso6336.md), so no one signs the figures as ISO's."""
    if cfg.rating is None or cfg.rating.virtual_tooth_count == "iso":
        return []
    return [warning(NOT_ISO, "[rating] virtual_tooth_count = \"cos3\": the tooth root's load angle γ_e divides by "
                    "z/cos³ β, not by ISO 6336-3's z_n = z/(cos² β_b cos β); Y_F, Y_S, σ_F0, σ_F and S_F reproduce "
                    "reports of tools that use it and are not ISO 6336-3's", quantity="virtual_tooth_count",
                    value="cos3")]


def range_diagnostics(cfg: DesignFile, k: int, st: StageResult) -> list[Diagnostic]:
    """Warnings where the stage lies outside what method B covers: a nominal F_t below the 1 N/mm floor the rating
    then uses (an unloaded stage), ε_α < 1 (no continuous mesh), ε_αn ≥ 2.5 (ISO 6336-2's scope), a notch parameter
    q_s of the root outside 1 … 8 (Y_S's range) and a rim thinner than half the tooth depth (Y_B's range); on a
    planetary stage each carries ``mesh`` "sun_planet"."""
    out = []
    floor = reference_tangential_force_N(0.0, st.face_width_mm)
    if abs(st.static_force_N.tangential) < floor:
        out.append(warning(OUT_OF_RANGE, f"stage {st.index}: the nominal tangential force "
                           f"{abs(st.static_force_N.tangential):.3g} N is below 1 N per mm of face width: the strength "
                           f"rating is at F_t = {floor:.3g} N (that floor), a token load whose load factors (K_v, K_Hβ, "
                           "K_Hα) and safeties describe no operating point; rate the stage at its working torque",
                           stage=st.index, quantity="tangential_force_N", value=abs(st.static_force_N.tangential)))
    if st.contact_ratio_transverse < 1.0:
        out.append(warning(OUT_OF_RANGE, f"stage {st.index}: ε_α = {st.contact_ratio_transverse:.3g} < 1: ISO 6336 "
                           "assumes a continuous mesh (ε_α ≥ 1); the strength rating of this stage is not valid",
                           stage=st.index, quantity="contact_ratio_transverse", value=st.contact_ratio_transverse))
    out.extend(virtual_contact_ratio_diagnostics(st.index, st.contact_ratio_transverse, st.base_helix_angle_deg))
    stage = cfg.pair(k)
    assert cfg.rating is not None  # rate_design's caller
    for part in ("pinion", "gear"):
        g = getattr(st, part)
        # the root as the rating rates it: at x_E of the chosen allowance where the member has one
        form = rr.tooth_form(g.teeth, st.normal_module_mm, math.radians(st.normal_pressure_angle_deg),
                             math.radians(st.helix_angle_deg), math.radians(st.base_helix_angle_deg),
                             root_shift(g, cfg.rating.root_profile_shift), g.tip_diameter_mm, g.pitch_diameter_mm,
                             st.contact_ratio_transverse, (stage.basic_rack.dedendum, stage.basic_rack.root_radius),
                             virtual_tooth_count=cfg.rating.virtual_tooth_count)
        if not Q_S_RANGE[0] <= form["q_s"] < Q_S_RANGE[1]:
            out.append(warning(OUT_OF_RANGE, f"stage {st.index} {member_name(st, part)}: the root's notch parameter q_s = "
                               f"{form['q_s']:.3g} lies outside 1 … 8, where ISO 6336-3's Y_S (method B) holds",
                               stage=st.index, member=part, quantity="q_s", value=form["q_s"]))
        out.extend(_rim_range_diagnostics(st, part, getattr(stage, part).rim_thickness_mm, g))
        out.extend(_material_range_diagnostics(cfg, st, part, getattr(stage, part).material))
    tag = mesh_data(st)  # a planetary stage's sun–planet mesh: "sun_planet", as its planet–ring warnings say theirs
    return [replace(d, data={**d.data, **tag}) for d in out] + static_range_diagnostics(cfg, k, st)


def _material_range_diagnostics(cfg: DesignFile, st: StageResult, part: str, name: str) -> list[Diagnostic]:
    """A member softer than every ISO 6336 gear material (a polymer, a light alloy): its σ_Hlim, σ_FE and S-N curves
    are steel's or cast iron's (ISO 6336-5), so its safeties describe no real part."""
    modulus = cfg.materials[name].youngs_modulus_MPa
    if modulus >= ISO_MATERIAL_MODULUS_MIN_MPa:
        return []
    return [warning(OUT_OF_RANGE, f"stage {st.index} {member_name(st, part)}: its material {name!r} has E = {modulus:,.0f} N/mm², below "
                    f"every ISO 6336 gear material (from {ISO_MATERIAL_MODULUS_MIN_MPa:,.0f} N/mm²: bronzes, cast irons, "
                    "steels): ISO 6336-5's strength values and S-N curves are steels' and cast irons', so the "
                    "safeties of this member are not a rating of it (polymer gears: VDI 2736)",
                    stage=st.index, member=part, quantity="youngs_modulus_MPa", value=modulus)]


def _rim_range_diagnostics(st: StageResult, part: str, rim_mm: float | None, g: GearResult) -> list[Diagnostic]:
    """``rating_out_of_range`` for a rim thinner than half the tooth depth (s_R/h_t < 0.5), where ISO 6336-3's rim
    factor of an external gear no longer applies: Y_B is taken at 0.5 (``rating_root.rim_factor``)."""
    depth = 0.5 * (g.tip_diameter_mm - g.root_diameter_mm)  # h_t as the rating's Y_B reads it
    if rim_mm is None or rim_mm / depth >= rr.RIM_RANGE[0]:
        return []
    return [warning(OUT_OF_RANGE, f"stage {st.index} {member_name(st, part)}: rim s_R/h_t = {rim_mm / depth:.3g} below 0.5, where "
                    "ISO 6336-3's rim factor of an external gear ends; Y_B is taken at 0.5 "
                    f"({rr.rim_factor(rim_mm, depth):.3g}), a thinner rim needs a finite element check",
                    stage=st.index, member=part, quantity="rim_ratio", value=rim_mm / depth)]


def virtual_contact_ratio_diagnostics(stage: int, eps_alpha: float, base_helix_deg: float,
                                      **data: JsonValue) -> list[Diagnostic]:
    """``rating_out_of_range`` for a mesh whose virtual contact ratio ε_αn = ε_α / cos² β_b reaches 2.5: ISO
    6336-2:2006 (Scope) holds for teeth of other basic racks only while ε_αn < 2.5 (ISO 6336-3's Y_DT is its one
    factor beyond); ``data`` adds to the warning's data (``mesh`` of a planetary stage's planet–ring mesh)."""
    eps_an = eps_alpha / math.cos(math.radians(base_helix_deg)) ** 2
    if eps_an < EPS_ALPHA_N_MAX:
        return []
    where = f"stage {stage}" + (" planet–ring mesh" if data.get("mesh") == "planet_ring" else "")
    return [warning(OUT_OF_RANGE, f"{where}: the virtual contact ratio ε_αn = ε_α/cos² β_b = {eps_an:.3g} is not "
                    f"below {EPS_ALPHA_N_MAX:g}, where ISO 6336-2 (and its pitting factors Z_ε, Z_B, Z_D) holds; the "
                    "strength rating of this mesh is outside the standard's scope", stage=stage,
                    quantity="contact_ratio_virtual", value=eps_an, **data)]


def static_range_diagnostics(cfg: DesignFile, k: int, st: StageResult) -> list[Diagnostic]:
    """A warning for a member whose load cycles lie in the static range of its life factor (N_L at or below the first
    node of its Z_NT or Y_NT curve, ISO 6336-2 Table 2, ISO 6336-3 Table 3): the static proof takes its own
    (Z_L Z_V Z_R)_st, Y_δrelT,st, Y_RrelT,st, Y_X,st, which gearcli does not compute (docs/iso6336.md, "Not
    covered"); the rating keeps the endurance values of those factors with the static Z_NT, Y_NT."""
    r = st.rating
    if r is None:
        return []
    out = []
    stage = cfg.pair(k)
    for part in ("pinion", "gear"):
        out += static_cycles_diagnostics(st.index, part, str(cfg.materials[getattr(stage, part).material].treatment),
                                         getattr(r, part).load_cycles, label=member_name(st, part), **mesh_data(st))
    return out


def static_cycles_diagnostics(stage: int, member: str, treatment: str, cycles: float, *, label: str | None = None,
                              **data: JsonValue) -> list[Diagnostic]:
    """``rating_out_of_range`` (``quantity`` "load_cycles") for one member whose N_L lies at or below the first node of
    its Z_NT or Y_NT curve (:func:`static_range_diagnostics`); ``label`` names it in the message (the design file's
    name, a planetary's "sun"), ``data`` adds ``mesh`` on a planetary stage."""
    modes = (("Z_NT", rf.znt_curve(treatment)[0][0], "Z_L Z_V Z_R"),
             ("Y_NT", rf.ynt_curve(treatment)[0][0], "Y_δrelT, Y_RrelT, Y_X"))
    static = [(f"{name} (N_L ≤ {n:.0e})", factors) for name, n, factors in modes if cycles <= n]
    if not static:
        return []
    return [warning(OUT_OF_RANGE, f"stage {stage} {label or member}: N_L = {cycles:.3g} load cycles lie in the static range of "
                    f"{' and '.join(m for m, _ in static)}: ISO 6336's static proof takes static values of "
                    f"{'; '.join(f for _, f in static)}, which gearcli does not compute; this rating keeps their "
                    "endurance values beside the static life factors",
                    stage=stage, member=member, quantity="load_cycles", value=cycles, **data)]


@record
class _Mesh:
    """A stage as the rating sees it: ISO's index 1 (``small``) is the wheel with fewer teeth."""

    members: tuple[GearResult, GearResult]  # gearcli's pinion, gear
    parts: tuple[Gear, Gear]  # their design-file tables
    mats: tuple[Material, Material]
    treatments: tuple[str, str]
    hlim: tuple[float, float]  # σ_Hlim
    flim: tuple[float, float]  # σ_Flim
    small: int
    large: int
    f_t: float  # N, nominal, floored at 1 N/mm
    k_a: float
    speed_m_s: float  # pitch-line speed
    grade: int

    @property
    def g1(self) -> GearResult:
        return self.members[self.small]

    @property
    def g2(self) -> GearResult:
        return self.members[self.large]


def _mesh(cfg: DesignFile, k: int, st: StageResult) -> _Mesh:
    stage = cfg.pair(k)
    assert stage.accuracy_grade is not None  # check_rating_inputs requires it
    parts = (stage.pinion, stage.gear)
    mats = (cfg.materials[parts[0].material], cfg.materials[parts[1].material])
    small, large = smaller_wheel_first((st.pinion.teeth, st.gear.teeth), (0, 1),
                                       (st.pinion.profile_shift, st.gear.profile_shift))
    g1 = (st.pinion, st.gear)[small]
    return _Mesh(members=(st.pinion, st.gear), parts=parts, mats=mats,
                 treatments=(str(mats[0].treatment), str(mats[1].treatment)),
                 hlim=(float(mats[0].contact_fatigue_limit_MPa or 0.0), float(mats[1].contact_fatigue_limit_MPa or 0.0)),
                 flim=(float(mats[0].bending_fatigue_limit_MPa or 0.0), float(mats[1].bending_fatigue_limit_MPa or 0.0)),
                 small=small, large=large,
                 f_t=reference_tangential_force_N(st.static_force_N.tangential, st.face_width_mm),
                 k_a=cfg.load.application_factor,
                 speed_m_s=max(math.pi * g1.pitch_diameter_mm * abs(g1.speed_rpm) / 60000.0, 1e-9),
                 grade=stage.accuracy_grade)


def _load_factors(cfg: DesignFile, k: int, st: StageResult, mesh: _Mesh, simulated_k_v: float | None) -> LoadFactors:
    """ISO 6336-1's load factors of the pair (``rating_load``, the one K_v / K_Hβ resolution)."""
    stage = cfg.pair(k)
    assert cfg.rating is not None
    return resolve_load_factors(cfg.rating, MeshLoad(
        grade=mesh.grade, normal_module_mm=st.normal_module_mm,
        transverse_pressure_angle_rad=math.radians(st.transverse_pressure_angle_deg),
        pitch_diameters_mm=(mesh.members[0].pitch_diameter_mm, mesh.members[1].pitch_diameter_mm),
        treatments=mesh.treatments, hlim_MPa=mesh.hlim, small=mesh.small, speed_m_s=mesh.speed_m_s,
        line_load_N_mm=mesh.f_t * mesh.k_a / st.face_width_mm, face_width_mm=st.face_width_mm,
        resonance_ratio=st.resonance_ratio, resonance_lower_limit=st.resonance_lower_limit,
        contact_ratios=(st.contact_ratio_transverse, st.overlap_ratio, st.contact_ratio_total),
        single_pair_stiffness=st.iso6336_single_pair_stiffness_N_mm_um, mesh_stiffness=st.iso6336_mesh_stiffness_N_mm_um,
        mesh_stiffness_beta=st.iso6336_mesh_stiffness_beta_N_mm_um, tip_relief_um=stage.tip_relief_um or 0.0,
        tooth_depth_mm=_tooth_depth_mm(stage, st)), simulated_k_v)


def root_shift(g, choice: str) -> float:
    """The profile shift method B rates the root at: x, or x_E of the chosen allowance (docs/iso6336.md,
    "Allowances in the strength rating")."""
    x_e = g.generating_profile_shift
    if choice == "nominal" or x_e is None:
        return float(g.profile_shift)
    return {"upper": x_e[0], "lower": x_e[1], "mean": 0.5 * (x_e[0] + x_e[1])}[choice]


def member_tooth_depth_mm(g, tip_allowance_mm: list[float] | None) -> float:
    """A member's tooth depth for K_Fβ's b/h (ISO 6336-1:2006, 7.7): (d_a − d_f)/2, which a tip alteration k
    shortens, or with tooth-thickness allowances the deepest tooth cut, (d_a + A_dae − d_f,i)/2 (docs/iso6336.md,
    "Tooth-thickness allowances"). A [0, 0] allowance gives the nominal depth: the two paths meet."""
    roots = g.manufactured_root_diameter_mm
    if roots is None:
        return 0.5 * (g.tip_diameter_mm - g.root_diameter_mm)
    return manufactured_tooth_depth_mm(g.tip_diameter_mm, tip_allowance_mm, roots)


def _tooth_depth_mm(stage, st: StageResult) -> float:
    """h of K_Fβ's b/h: the deeper member's (:func:`member_tooth_depth_mm`; ISO's smaller b/h of the pair)."""
    return max(member_tooth_depth_mm(g, part.tip_diameter_allowance_mm)
               for g, part in ((st.pinion, stage.pinion), (st.gear, stage.gear)))


def rate_stage(cfg: DesignFile, k: int, st: StageResult, *, simulated_k_v: float | None = None) -> RatingResult:
    """The rating of stage ``k`` (0-based); ``simulated_k_v`` replaces K_v (``K_v_source = "simulated"``)."""
    assert cfg.rating is not None and cfg.lubricant is not None and cfg.lubricant.viscosity_40C_mm2_s is not None
    mesh = _mesh(cfg, k, st)
    lf = _load_factors(cfg, k, st, mesh, simulated_k_v)
    g1, g2, b = mesh.g1, mesh.g2, st.face_width_mm
    alpha_wt = math.radians(st.working_pressure_angle_deg)
    # ISO 6336-2: contact stress and the stage-level factors
    z_h = rf.zone_factor(math.radians(st.base_helix_angle_deg), math.radians(st.transverse_pressure_angle_deg),
                         alpha_wt)
    z_e = rf.elasticity_factor(mesh.mats[0].youngs_modulus_MPa, mesh.mats[0].poisson_ratio,
                               mesh.mats[1].youngs_modulus_MPa, mesh.mats[1].poisson_ratio)
    z_beta = rf.helix_factor_pitting(math.radians(st.helix_angle_deg))
    u = g2.teeth / g1.teeth
    sigma_h0 = z_h * z_e * lf.z_eps * z_beta * math.sqrt(mesh.f_t / (g1.pitch_diameter_mm * b) * (u + 1.0) / u)
    sigma_h = sigma_h0 * math.sqrt(mesh.k_a * lf.k_v * lf.k_hb * lf.k_ha)
    z_b, z_d = rf.single_pair_factors((g1.tip_diameter_mm, g2.tip_diameter_mm),
                                      (g1.base_diameter_mm, g2.base_diameter_mm), (g1.teeth, g2.teeth), alpha_wt,
                                      st.contact_ratio_transverse, st.overlap_ratio)
    low_hlim = min(mesh.hlim)
    rho = [0.5 * g.base_diameter_mm * math.tan(alpha_wt) for g in (g1, g2)]
    rz_flank = 0.5 * sum(float(g.flank_roughness_Rz_um or 0.0) for g in mesh.parts)
    soft, z_w = _work_hardening(mesh.mats, mesh.treatments)
    flank = _Flank(z_bd={mesh.small: z_b, mesh.large: z_d}, sigma_h=sigma_h,
                   z_l=rf.lubricant_factor(low_hlim, cfg.lubricant.viscosity_40C_mm2_s),
                   z_v=rf.velocity_factor(low_hlim, mesh.speed_m_s),
                   z_r=rf.roughness_factor(low_hlim, rz_flank, rho[0] * rho[1] / (rho[0] + rho[1])),
                   z_w={soft: z_w})
    y_beta = rr.helix_factor_bending(st.overlap_ratio, st.helix_angle_deg)
    return RatingResult(
        standard=STANDARD, K_A=mesh.k_a, K_v=lf.k_v, K_v_source=lf.k_v_source, K_Hbeta=lf.k_hb,
        K_Hbeta_source=lf.k_hb_source, K_Fbeta=lf.k_fb, K_Halpha=lf.k_ha, K_Falpha=lf.k_fa, Z_H=z_h, Z_E=z_e,
        Z_eps=lf.z_eps, Z_beta=z_beta, Z_L=flank.z_l, Z_V=flank.z_v, Z_R=flank.z_r, Z_W=z_w, Y_beta=y_beta,
        sigma_H0_MPa=sigma_h0, sigma_H_MPa=sigma_h,
        pinion=_member(cfg, k, st, mesh, lf, flank, y_beta, 0), gear=_member(cfg, k, st, mesh, lf, flank, y_beta, 1))


@record
class _Flank:
    """The pitting factors a member's figures need: Z_B/Z_D by member index, σ_H at the pitch point, Z_L, Z_V, Z_R,
    and Z_W by the index of the member it acts on."""

    z_bd: dict[int, float]
    sigma_h: float
    z_l: float
    z_v: float
    z_r: float
    z_w: dict[int, float]


def _member(cfg: DesignFile, k: int, st: StageResult, mesh: _Mesh, lf: LoadFactors, flank: _Flank, y_beta: float,
            i: int) -> MemberRating:
    """ISO 6336-2 and -3 figures of member ``i`` (0 pinion, 1 gear)."""
    rating, stage = cfg.rating, cfg.pair(k)
    assert rating is not None
    g, part, m_n = mesh.members[i], mesh.parts[i], st.normal_module_mm
    # contacts per turn as the stage's kind counts them (a planetary's sun, member 0 of its sun–planet mesh, meets
    # every planet once per turn relative to the carrier; a planet meets the sun once: its ring mesh is the other
    # flank, rated in rating_internal)
    kind = design_kind(st)
    meetings = kind.meetings(st, i)
    cycles = 60.0 * abs(g.speed_rpm) * rating.life_h * meetings
    z_nt = rf.life_factor_pitting(mesh.treatments[i], cycles, rating.material_quality)
    sig_h = flank.z_bd[i] * flank.sigma_h
    sig_hg = mesh.hlim[i] * z_nt * flank.z_l * flank.z_v * flank.z_r * flank.z_w.get(i, 1.0)  # Z_X = 1
    form = rr.tooth_form(g.teeth, m_n, math.radians(st.normal_pressure_angle_deg), math.radians(st.helix_angle_deg),
                         math.radians(st.base_helix_angle_deg), root_shift(g, rating.root_profile_shift),
                         g.tip_diameter_mm,
                         g.pitch_diameter_mm, st.contact_ratio_transverse,
                         (stage.basic_rack.dedendum, stage.basic_rack.root_radius),
                         virtual_tooth_count=rating.virtual_tooth_count)
    if abs(form["theta_residual"]) > rr.FILLET_ANGLE_TOLERANCE:
        raise DesignError(f"ISO 6336-3 (method B) finds no critical section on the root of this {g.teeth}-tooth "
                          "member: the 30° tangent's iteration θ = 2G/z_n tan θ − H has no solution (residual "
                          f"{form['theta_residual']:.2g} rad; a small, far-shifted tooth at a low pressure angle): "
                          "change the profile shift, the tooth count or the pressure angle to rate it",
                          key=f"stage[{k}].{('pinion', 'gear')[i]}.profile_shift")
    if form["rho_F"] == 0.0 and form["s_Fn"] > 0.0 and form["h_Fe"] > 0.0:
        raise DesignError(f"the root fillet of this {g.teeth}-tooth member has no radius (ρ_F = 0: the basic rack's "
                          "root_radius 0 with the tool's corner on the reference line, x = h_fP*): ISO 6336-3's notch "
                          "parameter q_s = s_Fn/(2 ρ_F) and Y_S are unbounded; give basic_rack.root_radius > 0 (ISO 53: "
                          "0.38) to rate it", key=f"stage[{k}].basic_rack.root_radius")
    if not (form["s_Fn"] > 0.0 and form["rho_F"] > 0.0 and form["h_Fe"] > 0.0):
        raise DesignError(f"the root of this {g.teeth}-tooth member is undercut so far that ISO 6336-3 (method B) "
                          f"finds no critical section (s_Fn = {form['s_Fn']:.3g} mm, ρ_F = {form['rho_F']:.3g} mm): "
                          "raise the profile shift or the tooth count to rate it",
                          key=f"stage[{k}].{('pinion', 'gear')[i]}.profile_shift")
    y_b = rr.rim_factor(part.rim_thickness_mm, 0.5 * (g.tip_diameter_mm - g.root_diameter_mm))
    y_dt = rr.deep_tooth_factor(st.contact_ratio_transverse, math.radians(st.base_helix_angle_deg), mesh.grade)
    b_f = min(g.face_width_mm, st.face_width_mm + 2.0 * m_n)
    sig_f0 = mesh.f_t / (b_f * m_n) * form["Y_F"] * form["Y_S"] * y_beta * y_b * y_dt
    sig_f = sig_f0 * mesh.k_a * lf.k_v * lf.k_fb * lf.k_fa
    y_d = rr.relative_notch_sensitivity(mesh.treatments[i], form["q_s"])
    y_r = rr.relative_surface_factor(mesh.treatments[i], float(part.root_roughness_Rz_um or 0.0))
    y_x = rr.size_factor_bending(mesh.treatments[i], m_n)
    y_nt = rf.life_factor_bending(mesh.treatments[i], cycles, rating.material_quality)
    # an idler's root bends both ways (Y_M): a planetary stage's planet, the sun–planet pair's gear
    y_m = rr.IDLER_MEAN_STRESS_FACTOR if kind.idler(st, i) else 1.0
    sig_fg = mesh.flim[i] * STRESS_CORRECTION_TEST_GEAR * y_nt * y_d * y_r * y_x * y_m
    return MemberRating(
        load_cycles=cycles, Z_BD=flank.z_bd[i], sigma_H_MPa=sig_h, Z_NT=z_nt, Z_X=1.0, sigma_HG_MPa=sig_hg,
        sigma_HP_MPa=sig_hg / rating.min_safety_pitting, S_H=sig_hg / sig_h, Y_F=form["Y_F"], Y_S=form["Y_S"],
        Y_B=y_b, Y_DT=y_dt, sigma_F0_MPa=sig_f0, sigma_F_MPa=sig_f, Y_delta_rel_T=y_d, Y_R_rel_T=y_r, Y_X=y_x,
        Y_NT=y_nt, sigma_FG_MPa=sig_fg, sigma_FP_MPa=sig_fg / rating.min_safety_bending, S_F=sig_fg / sig_f,
        Y_M=y_m)


def _work_hardening(mats: tuple[Material, ...], treatments: tuple[str, ...]) -> tuple[int, float]:
    """(index of the member Z_W acts on, Z_W): the through-hardened member of a pair whose mate is surface-
    hardened; (-1, 1.0) otherwise."""
    hard = [t in rf.SURFACE_HARDENED for t in treatments]
    if hard[0] == hard[1]:
        return -1, 1.0
    soft = 1 if hard[0] else 0
    hv = mats[soft].surface_hardness_HV
    return soft, rf.work_hardening_factor(None if hv is None else HB_PER_HV * hv)


# ------------------------------------------------------------------------------------ warnings
def safety_diagnostics(cfg: DesignFile, st: StageResult, *, source: str = "") -> list[Diagnostic]:
    """A warning for every safety below its minimum, naming stage, member and failure mode (a planetary stage's
    sun–planet mesh adds ``mesh`` "sun_planet", as its planet–ring mesh's warnings carry "planet_ring")."""
    r = st.rating
    if r is None or cfg.rating is None:
        return []
    out = []
    minima = {"pitting": cfg.rating.min_safety_pitting, "bending": cfg.rating.min_safety_bending}
    for part in ("pinion", "gear"):
        m: MemberRating = getattr(r, part)
        for mode, value, symbol, norm in (("pitting", m.S_H, "S_H", "ISO 6336-2"),
                                          ("bending", m.S_F, "S_F", "ISO 6336-3")):
            if value < minima[mode]:
                code = PITTING_LOW if mode == "pitting" else BENDING_LOW
                what = "pitting (flank)" if mode == "pitting" else "tooth-root bending"
                teeth = (st.pinion if part == "pinion" else st.gear).teeth
                message = (f"stage {st.index} {member_name(st, part)} (z = {teeth}): {what} safety {symbol} = {beside(value, minima[mode])} is below the minimum "
                           f"{minima[mode]:.3g} ({norm}, K_v = {r.K_v:.3g} {r.K_v_source}{source}); widen the face, "
                           "raise the module or choose a stronger material")
                out.append(warning(code, message, stage=st.index, member=part, mode=mode, S=value,
                                   S_min=minima[mode], **mesh_data(st)))
    return out
