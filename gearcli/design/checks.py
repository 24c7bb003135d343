"""Design checks: the warnings that do not stop the design (docs/physics.md, "Design calculations"); the errors that
do are :mod:`gearcli.design.input_checks`.

Warnings are one line each, name the stage (1-based, as an engineer counts) and carry the numbers.

Choices where the contract is silent:

- Module, helix angle and pressure angle are stage-level keys in the design file, so a pinion and
  gear that disagree on them cannot be written down: there is nothing to check.
- β = 0 makes a spur pair whatever the hands say. Hands given on a spur pair are not an error (a sweep
  over β may pass through 0), but a warning asks whether ``helix_angle_deg`` was forgotten, since it
  defaults to 0. The result then reports hand "spur".
- Limits: undercut below z_min = 2 (h_FfP* − x) cos β / sin² α_t (h_FfP* = h_fP* − ρ_fP* (1 − sin α_n), the
  straight flank of the stage's basic rack; ≈ 1 for ISO 53 profile A at 20°; ISO 21771 / DIN 3960); tip
  interference where the mate's tip meets a flank below its involute form circle (or beyond its base tangent
  point when undercut: Shigley's interference condition), with the usable ε_α;
  ε_α < 1.2 (common design minimum) and ε_α < 1 (interrupted
  transverse contact) as separate messages; b/d1 outside 0.2 … 1.5 (Niemann/Winter, Maschinenelemente II:
  b/d1 ≲ 1.1–1.6 for straddle-mounted pinions depending on hardening, 1.5 taken as the upper end;
  below 0.2 the face is so narrow that the module, not the width, carries the load); normal tip
  thickness s_an < 0.2 m_n, 0.4 m_n on surface-hardened members (pointed teeth, Niemann/Winter's minima).
- An intermediate shaft whose gear and next pinion (both helical, parallel stages) have opposite hands: their axial
  forces add on its bearings (the countershaft rule says one hand on both, so they oppose): a warning.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from typing import TYPE_CHECKING

from gearcli.core.jsontypes import JsonObject
from gearcli.core.text import beside
from gearcli.design.drive_balance import load_table_beyond_warning, torque_drive_warning
from gearcli.design.geometry import (
    form_point_from_base_tangent_mm,
    hardened_tip_text,
    min_tip_thickness_per_module,
    normal_tip_thickness_mm,
    pointed_tip_diameter_mm,
    rack_form_height_factor,
    tip_reach_mm,
    undercut_limit_teeth,
    undercut_min_profile_shift,
)
from gearcli.design.input_checks import HANDS, OPPOSITE
from gearcli.design.resonance import MAIN_RESONANCE_UPPER, SUBHARMONICS, subharmonic_orders
from gearcli.design.stiffness import material_factor, smaller_wheel_first
from gearcli.design.target import target_speed_warning
from gearcli.diagnostics import DESIGN, STIFFNESS_NOT_ISO, warning
from gearcli.stages.design import design_kind, gear_pairs, member_name

if TYPE_CHECKING:
    from gearcli.config.schema import DesignFile, Stage
    from gearcli.diagnostics import Diagnostic
    from gearcli.results import GearResult, StageResult

MIN_CONTACT_RATIO = 1.2
FACE_RATIO_RANGE = (0.2, 1.5)  # b / d1


# ---------------------------------------------------------------------------------------- warnings
def design_diagnostics(cfg: DesignFile, stages: Iterable[StageResult], output_speed_rpm: float,
                       required_input_Nm: float, input_speed_rpm: float,
                       reflect: Callable[[float], float] | None = None) -> tuple[Diagnostic, ...]:
    """The design's warnings as diagnostics (code ``design``; ``check`` names the check, with its stage,
    member and numbers): train-level first, then stage by stage. ``required_input_Nm`` is the input torque the
    load needs at the nominal ``input_speed_rpm`` (for a torque drive's balance); ``reflect`` takes a load torque
    (N·m, at the output) to the input torque that balances it, with the losses in its power flow's direction."""
    found: list[tuple[str | None, JsonObject]] = []
    if cfg.target is not None:
        found.append((target_speed_warning(cfg, output_speed_rpm),
                      {"check": "target_speed", "output_speed_rpm": output_speed_rpm,
                       "target_rpm": cfg.target.output_speed_rpm_value,
                       "tolerance_percent": cfg.target.tolerance_percent}))
    found.append((massless_rotor_warning(cfg), {"check": "motor_rotor_inertia"}))
    found.append(load_table_beyond_warning(cfg, output_speed_rpm))
    found.append((torque_drive_warning(cfg, required_input_Nm, input_speed_rpm, output_speed_rpm, reflect),
                  {"check": "torque_drive_balance", "input_torque_Nm": cfg.input.torque_Nm_value,
                   "required_input_torque_Nm": required_input_Nm}))
    stages = tuple(stages)
    found += axial_hand_warnings(stages)
    # a check's data (its figures, some computed again) are built only where its warning is given: a diagnostic is
    # made of a warning's text and data, and the data of a check that gives none is dropped unread (the warnings and
    # their data in the same order, each as before; a sweep point designs every stage)
    for k, stage in gear_pairs(stages):
        stage_cfg = cfg.pair(k)
        at: JsonObject = {"stage": stage.index}
        # a helical pair gives no spur-hand warning, which alone reads the members' names
        if stage_cfg.helix_angle_deg == 0.0 and (w := spur_hand_warning(
                stage.index, stage_cfg, (_name(stage, stage.pinion), _name(stage, stage.gear)))):
            found.append((w, {"check": "spur_hand", **at}))
        for gear in (stage.pinion, stage.gear):
            if w := undercut_warning(stage, gear, stage_cfg):
                z_min, x_min = undercut_figures(stage, gear, stage_cfg)
                found.append((w, {"check": "undercut", **at, "member": _part(stage, gear), "teeth": gear.teeth,
                                  "profile_shift": gear.profile_shift, **_cut_shift_data(gear),
                                  "min_teeth": z_min, "min_profile_shift": x_min}))
        for gear in (stage.pinion, stage.gear):
            found.append(interference_warning(stage, stage_cfg, gear))
        if w := contact_ratio_warning(stage):
            found.append((w, {"check": "contact_ratio", **at, **mesh_data(stage), **{
                key: getattr(stage, key) for key in ("contact_ratio_transverse", "contact_ratio_total")}}))
        for gear in (stage.pinion, stage.gear):
            clearance = tip_clearance_with_allowances_mm(stage, stage_cfg, gear)
            if w := tip_clearance_warning(stage, gear, clearance, stage_cfg):
                found.append((w, {"check": "tip_clearance", **at, **mesh_data(stage), "member": _part(stage, gear),
                                  "tip_clearance_mm": clearance}))
        if w := contact_ratio_allowances_warning(stage):
            found.append((w, {"check": "contact_ratio_allowances", **at, **mesh_data(stage),
                              "contact_ratio_transverse_with_allowances":
                                  stage.contact_ratio_transverse_with_allowances}))
        if w := face_width_warning(stage):
            found.append((w, {"check": "face_width", **at,
                              "face_width_ratio": stage.face_width_mm / smaller_pitch_diameter_mm(stage)}))
        for gear in (stage.pinion, stage.gear):
            tip_allowance = getattr(stage_cfg, _part(stage, gear)).tip_diameter_allowance_mm
            tip_mm = tip_allowance[0] if tip_allowance else 0.0
            treatment = cfg.materials[getattr(stage_cfg, _part(stage, gear)).material].treatment
            if w := tip_thickness_warning(stage, gear, tip_mm, treatment):
                found.append((w, {"check": "tip_thickness", **at, "member": _part(stage, gear),
                                  "profile_shift": gear.profile_shift, **_cut_shift_data(gear),
                                  "tip_thickness_mm": tip_thickness_mm(stage, gear, tip_mm), "treatment": treatment,
                                  "min_tip_thickness_mm":
                                      min_tip_thickness_per_module(treatment) * stage.normal_module_mm}))
        found.append(steel_stiffness_warning(cfg, stage.index, "mesh" if stage.planetary is None else "sun_planet",
                                             (stage_cfg.pinion.material, stage_cfg.gear.material)))
        if w := static_approach_warning(stage):
            found.append((w, {"check": "static_approach", **at, **mesh_data(stage),
                              "static_approach_mm": stage.static_approach_mm,
                              "normal_module_mm": stage.normal_module_mm}))
        if w := resonance_warning(stage):
            found.append((w, {"check": "iso6336_resonance", **at, **mesh_data(stage),
                              **{key: getattr(stage, key) for key in ("resonance_ratio", "resonance_speed_rpm",
                                                                       "resonance_lower_limit", "resonance_range")}}))
    return tuple(warning(DESIGN, w, **data) for w, data in found if w)


#: a static approach beyond this fraction of the normal module: the contact law far outside its validity (the
#: simulation's penetration_over_module, gearcli.simulate.stats, warns at this fraction of the run's deepest
#: penetration)
STATIC_APPROACH_MODULE_FRACTION = 0.10


def static_approach_warning(stage: StageResult) -> str | None:
    """The mesh's static approach h0 = (|F_n| / K)^(1/e) beyond 10 % of the normal module: a real tooth pair
    deflects some micrometres at its rated load, so a load or a contact stiffness off by orders of magnitude
    (a unit mistake) shows here, before any simulation."""
    h0, m_n = stage.static_approach_mm, stage.normal_module_mm
    if not (h0 > STATIC_APPROACH_MODULE_FRACTION * m_n):
        return None
    return (f"{mesh_head(stage)}: the static approach of the mesh is {h0:.3g} mm at the design load, more than 10 % "
            f"of the normal module ({m_n:.3g} mm): the contact law is far outside its validity (a tooth pair "
            "deflects some micrometres at its rated load); check the load torque, [contact] stiffness and their units")


def steel_stiffness_warning(cfg: DesignFile, stage: int, mesh: str,
                            materials: tuple[str, str]) -> tuple[str | None, JsonObject]:
    """A mesh of a pairing other than steel on steel: ISO 6336-1's c′ (and so c_γα, the ``iso6336`` law, K_v and
    K_Hβ) is steel's in gearcli (the formula has no material term), where the standard scales it by E/E_st for
    other pairings: cast irons, bronzes, light alloys and polymers mesh softer than steel's c′ says."""
    mats = [cfg.materials[name] for name in materials]
    factor = material_factor(mats[0].youngs_modulus_MPa, mats[0].treatment, mats[1].youngs_modulus_MPa,
                             mats[1].treatment)
    data: JsonObject = {"check": "steel_stiffness", "stage": stage, "mesh": mesh, "modulus_ratio": factor}
    if factor == 1.0:
        return None, data
    where = f"stage {stage}" + ("" if mesh == "mesh" else f" {mesh.replace('_', '–')} mesh")
    return (f"{where}: the {materials[0]}/{materials[1]} pairing is not steel on steel, but c′ = c′_th C_M C_R C_B "
            "cos β is steel's (ISO 6336-1 measured c′_th on steel pairs and scales it by E/E_st for other pairings, "
            f"here {factor:.3g}: E = 2E1E2/(E1+E2), E_st = 206,000 N/mm²); the iso6336 mesh law, modes and the "
            "rating's K_v and K_Hβ take this mesh stiffer than the standard would; where that matters, give "
            "[contact] stiffness as a number"), data


def planet_ring_steel_warnings(cfg: DesignFile, stages: Iterable[StageResult]) -> tuple[Diagnostic, ...]:
    """:func:`steel_stiffness_warning` of every planetary stage's planet–ring mesh (``cfg`` the file, not the pair
    view: the ring is not a member of the sun–planet pair)."""
    found = (steel_stiffness_warning(cfg, st.index, "planet_ring", (cfg.stage[k].planet.material,  # type: ignore[union-attr]
                                                                   cfg.stage[k].ring.material))  # type: ignore[union-attr]
             for k, st in enumerate(stages) if getattr(st, "planetary", None) is not None)
    return tuple(warning(DESIGN, w, **data) for w, data in found if w)


def axial_hand_warnings(stages: tuple[StageResult, ...]) -> list[tuple[str | None, JsonObject]]:
    """An intermediate shaft between two helical parallel stages whose gear (driven) and pinion (driving) have
    opposite hands: their axial forces point the same way and add on the shaft's bearings, where one hand on both
    opposes them (the countershaft rule: a driven and a driving helical gear on one shaft push opposite ways when
    their hands are the same)."""
    found: list[tuple[str | None, JsonObject]] = []
    for prev, nxt in zip(stages, stages[1:], strict=False):
        if prev.type != "parallel" or nxt.type != "parallel":
            continue
        hands = (prev.gear.hand, nxt.pinion.hand)
        if hands[0] not in HANDS or hands[1] not in HANDS or hands[0] == hands[1]:
            continue
        forces = (abs(prev.static_force_N.axial), abs(nxt.static_force_N.axial))
        shaft = nxt.index
        message = (f"shaft {shaft}: the stage {prev.index} gear ({hands[0]}) and the stage {nxt.index} pinion "
                   f"({hands[1]}) on it have opposite hands, so their axial forces add: {forces[0]:.4g} + "
                   f"{forces[1]:.4g} = {sum(forces):.4g} N on the shaft's locating bearing; with the same hand on "
                   f'both (stage {nxt.index} pinion "{hands[0]}", its gear "{OPPOSITE[hands[0]]}") they oppose and '
                   f"leave {abs(forces[0] - forces[1]):.4g} N")
        found.append((message, {"check": "axial_forces_add", "shaft": shaft, "stage": nxt.index,
                                "axial_N": list(forces), "net_axial_N": sum(forces),
                                "opposed_axial_N": abs(forces[0] - forces[1])}))
    return found


def massless_rotor_warning(cfg: DesignFile) -> str | None:
    """A motor drive without the rotor's inertia: the motor torque then acts on the input pinion's inertia alone,
    and a start's time and peak tooth loads follow that (a 45 kW hoist: 0.06 s and 43 kN without its rotor's
    inertia, 0.17 s and 25 kN with it)."""
    if cfg.input.drive != "motor" or cfg.input.inertia_kg_m2 is not None:
        return None
    return ('input: drive = "motor" without input.inertia_kg_m2: the motor\'s rotor is taken as massless, so a '
            "start's acceleration, its time and its peak tooth loads follow the input pinion's inertia alone; give "
            "the rotor's inertia (the motor's catalogue) as input.inertia_kg_m2 with input.coupling_stiffness_Nm_rad")


def spur_hand_warning(index: int, stage_cfg: Stage, names: tuple[str, str] = ("pinion", "gear")) -> str | None:
    """Hands on a spur pair; ``names``: the pair's members as the file names them (a planetary: sun, planet)."""
    given = [f'{name} "{getattr(stage_cfg, part).hand}"' for part, name in zip(("pinion", "gear"), names, strict=True)
             if getattr(stage_cfg, part).hand in HANDS]
    return None if stage_cfg.helix_angle_deg != 0.0 or not given else (
        f"stage {index}: hand given ({', '.join(given)}) but helix_angle_deg = 0, a spur pair; the hands are ignored "
        "(forgot helix_angle_deg?)")


def _cut_shift(gear: GearResult) -> float:
    """The profile shift the thinnest tooth is cut at: x_E,i of the lower tooth-thickness allowance (ISO 21771),
    else x. Undercut and the tip thickness are properties of the cut tooth, so they are checked there."""
    return gear.profile_shift if gear.generating_profile_shift is None else gear.generating_profile_shift[1]


def _cut_shift_data(gear: GearResult) -> JsonObject:
    return {} if gear.generating_profile_shift is None else {"generating_profile_shift": _cut_shift(gear)}


def _shift_text(gear: GearResult) -> str:
    text = f"x = {gear.profile_shift:+.2f}"
    if gear.generating_profile_shift is not None and _cut_shift(gear) != gear.profile_shift:
        text += f", cut at x_E,i = {_cut_shift(gear):+.3f} by the lower tooth-thickness allowance"
    return text


def form_height_factor(stage: StageResult, stage_cfg: Stage) -> float:
    """h_FfP* of the stage's basic rack: the straight-flank height of the rack that generates its teeth."""
    rack = stage_cfg.basic_rack
    return rack_form_height_factor(rack.dedendum, rack.root_radius, math.radians(stage.normal_pressure_angle_deg))


def undercut_figures(stage: StageResult, gear: GearResult, stage_cfg: Stage) -> tuple[float, float]:
    """(z_min, x_min): the undercut limit z_min = 2 (h_FfP* − x) cos β / sin² α_t at the member's cut shift, and the
    profile shift x_min that just avoids undercut with its teeth, h_FfP* of the stage's basic rack (``basic_rack``)."""
    beta, alpha_t = math.radians(stage.helix_angle_deg), math.radians(stage.transverse_pressure_angle_deg)
    h_ff = form_height_factor(stage, stage_cfg)
    return (undercut_limit_teeth(_cut_shift(gear), beta, alpha_t, h_ff),
            undercut_min_profile_shift(gear.teeth, beta, alpha_t, h_ff))


def undercut_warning(stage: StageResult, gear: GearResult, stage_cfg: Stage) -> str | None:
    """z < z_min = 2 (h_FfP* − x) cos β / sin² α_t with h_FfP* of the stage's basic rack (``basic_rack``)."""
    z_min, x_needed = undercut_figures(stage, gear, stage_cfg)
    if gear.teeth >= z_min:
        return None
    what = "a profile shift" if gear.generating_profile_shift is None else "a generating profile shift x_E,i"
    return (f"stage {stage.index}: {_name(stage, gear)} z = {gear.teeth} < z_min = {beside(z_min, gear.teeth, '.1f')} "
            f"({_shift_text(gear)}, β = {stage.helix_angle_deg:g}°): undercut risk; "
            f"use {what} ≥ {math.ceil(100.0 * x_needed) / 100.0:+.2f} or more teeth")


#: contact may start this far (× m_n, along the line of action) below a form circle before it is called interference:
#: ISO 53 profile A's straight flank (0.99997 m_n at 20°) ends a hair below a rack mate's tip line (1 m_n)
INTERFERENCE_TOLERANCE_PER_MODULE = 1e-3


def interference_warning(stage: StageResult, stage_cfg: Stage,
                         gear: GearResult) -> tuple[str | None, JsonObject]:
    """The mate's tip reaches ``gear``'s flank below the lowest point of its involute (ISO 21771 meshing check).

    Along the transverse line of action T1T2 = a_w sin α_wt, the mate's tip circle starts contact at s = T1T2 −
    g_mate from ``gear``'s base tangent point T (g = √(r_a² − r_b²)); the involute the rack generated reaches down to
    q = r sin α_t − (h_FfP* − x) m_n / sin α_t from T (its form circle d_Ff = 2 √(r_b² + q²); undercut when q < 0,
    and then no lower than T). s < max(q, 0) is tip interference: the mate's tip runs into the root fillet (or the
    undercut), and ε_α, computed from the tips, counts a path that carries no involute contact. The data give the
    usable ε_α: the path between both members' lowest involute points and the tips, over p_bt.
    """
    mate = stage.gear if gear is stage.pinion else stage.pinion
    m_n, alpha_t = stage.normal_module_mm, math.radians(stage.transverse_pressure_angle_deg)
    h_ff = form_height_factor(stage, stage_cfg)
    line = stage.center_distance_mm * math.sin(math.radians(stage.working_pressure_angle_deg))

    def lowest(g: GearResult) -> float:  # the lowest involute point's distance from g's base tangent point
        return max(form_point_from_base_tangent_mm(g.pitch_diameter_mm, alpha_t, m_n, g.profile_shift, h_ff), 0.0)

    start = line - tip_reach_mm(mate.tip_diameter_mm, mate.base_diameter_mm)
    form = lowest(gear)
    if start >= form - INTERFERENCE_TOLERANCE_PER_MODULE * m_n:
        return None, {}  # no warning: its data unread (design_diagnostics keeps a check's data with its warning)
    data: JsonObject = {"check": "interference", "stage": stage.index, "member": _part(stage, gear), **mesh_data(stage)}
    # the usable path, measured from the pinion's T: from the higher of the gear's tip point and the pinion's lowest
    # involute point, to the lower of the pinion's tip point and the gear's lowest involute point
    p, g = stage.pinion, stage.gear
    usable = (min(tip_reach_mm(p.tip_diameter_mm, p.base_diameter_mm), line - lowest(g))
              - max(line - tip_reach_mm(g.tip_diameter_mm, g.base_diameter_mm), lowest(p)))
    eps = max(usable, 0.0) / stage.transverse_base_pitch_mm
    part, other = _name(stage, gear), _name(stage, mate)
    if form > 0.0:
        d_ff = 2.0 * math.hypot(0.5 * gear.base_diameter_mm, form)
        below = f"below its involute form circle d_Ff = {d_ff:.4g} mm, in its root fillet"
    else:
        d_ff = None
        below = (f"beyond its base tangent point (base circle d_b = {gear.base_diameter_mm:.4g} mm), in its undercut "
                 "root")
    depth = form - start
    data.update(form_diameter_mm=d_ff, depth_mm=depth, contact_ratio_transverse=stage.contact_ratio_transverse,
                contact_ratio_transverse_usable=eps)
    fix = (f"lower the {part}'s form circle (a smaller profile shift, or a basic rack whose straight flank reaches "
           f"deeper: a larger dedendum, a smaller root radius) or shorten the {other}'s tip" if form > 0.0 else
           f"give the {part} a larger profile shift (the {other} a smaller one) or more teeth")
    return (f"stage {stage.index}: tip interference: the {other}'s tip meets the {part} {depth:.3g} mm along the line "
            f"of action {below}; the usable transverse contact ratio is {eps:.3f}{usable_margin(eps)}, not ε_α = "
            f"{stage.contact_ratio_transverse:.3f} (which counts that path); {fix}"), data


def usable_margin(eps: float) -> str:
    """What a usable ε_α below the contact-ratio check's limits means (that check reads the nominal ε_α)."""
    if eps < 1.0:
        return " (< 1: contact is interrupted in every transverse section)"
    if eps < MIN_CONTACT_RATIO:
        return f" (< {MIN_CONTACT_RATIO}: little margin for tip relief, pitch and centre-distance errors)"
    return ""


def tip_clearance_with_allowances_mm(stage: StageResult, stage_cfg: Stage, gear: GearResult) -> float | None:
    """The smallest clearance between ``gear``'s tip and its mate's root with allowances: c = a_w + A_ai − (d_a +
    A_dae)/2 − d_f,e/2, the largest tip against the mate's highest root (its thickest tooth, x_E,e) at the smallest
    centre distance. None without allowances (the nominal clearance is the basic rack's, by the tip alteration)."""
    mate = stage.gear if gear is stage.pinion else stage.pinion
    if mate.manufactured_root_diameter_mm is None:
        return None
    tip = getattr(stage_cfg, _part(stage, gear)).tip_diameter_allowance_mm
    centre = stage_cfg.center_distance_allowance_mm
    return (stage.center_distance_mm + (centre[1] if centre else 0.0)
            - 0.5 * (gear.tip_diameter_mm + (tip[0] if tip else 0.0)) - 0.5 * mate.manufactured_root_diameter_mm[0])


def tip_clearance_warning(stage: StageResult, gear: GearResult, clearance: float | None,
                          stage_cfg: Stage | None = None) -> str | None:
    if clearance is None or clearance >= 0.0:
        return None
    return (f"stage {stage.index}: {_name(stage, gear)} tip clearance with allowances c = {clearance:.3g} mm < 0: at "
            "the upper tip allowance, the mate's upper tooth-thickness allowance and the smallest centre distance the "
            f"tip runs into the mate's root; narrow {_clearance_culprits(stage, gear, stage_cfg)}")


def _clearance_culprits(stage: StageResult, gear: GearResult, stage_cfg: Stage | None) -> str:
    """The allowances that take the clearance below the basic rack's: a positive upper tip allowance, a positive
    upper tooth-thickness allowance of the mate (its root raised), a negative lower centre-distance allowance."""
    if stage_cfg is None:
        return "the tip allowance (tip_diameter_allowance_mm)"
    own = getattr(stage_cfg, _part(stage, gear))
    mate = getattr(stage_cfg, _part(stage, stage.gear if gear is stage.pinion else stage.pinion))
    centre = stage_cfg.center_distance_allowance_mm
    named = [text for text, on in (
        (f"the {_name(stage, gear)}'s tip allowance (tip_diameter_allowance_mm)",
         bool(own.tip_diameter_allowance_mm and own.tip_diameter_allowance_mm[0] > 0.0)),
        ("the mate's upper tooth-thickness allowance (tooth_thickness_allowance_mm)",
         bool(mate.tooth_thickness_allowance_mm and mate.tooth_thickness_allowance_mm[0] > 0.0)),
        ("the centre distance's lower allowance (center_distance_allowance_mm)", bool(centre and centre[1] < 0.0)))
        if on]
    return " or ".join(named) if named else "the tip allowance (tip_diameter_allowance_mm)"


def contact_ratio_allowances_warning(stage: StageResult) -> str | None:
    """ε_α < 1 at a limit of the allowances (lower tips, largest centre distance) where the nominal ε_α ≥ 1 (the
    nominal case has its own warning)."""
    eps = stage.contact_ratio_transverse_with_allowances
    if eps is None or min(eps) >= 1.0 or stage.contact_ratio_transverse < 1.0:
        return None
    return (f"{mesh_head(stage)}: transverse contact ratio with allowances ε_α,i = {beside(min(eps), 1.0, '.3f')} < 1 (nominal "
            f"{stage.contact_ratio_transverse:.3f}): at the lower tip diameters and the largest centre distance "
            "contact is interrupted in every transverse section; narrow the tip or centre-distance allowances")


def contact_ratio_warning(stage: StageResult) -> str | None:
    return contact_ratio_text(mesh_head(stage), stage.contact_ratio_transverse, stage.contact_ratio_total)


def contact_ratio_text(head: str, eps: float, total: float) -> str | None:
    """ε_α below 1 (interrupted contact) or below MIN_CONTACT_RATIO, after ``head`` (the stage and its mesh)."""
    if eps < 1.0:
        overlap = "the motion is not continuous" if total < 1.0 else "only the overlap keeps the motion continuous"
        return (f"{head}: transverse contact ratio ε_α = {beside(eps, 1.0, '.3f')} < 1: contact is interrupted in "
                f"every transverse section; total ε_γ = {total:.3f}, {overlap}")
    if eps < MIN_CONTACT_RATIO:
        return (f"{head}: transverse contact ratio ε_α = {beside(eps, MIN_CONTACT_RATIO, '.3f')} < {MIN_CONTACT_RATIO}: little "
                "margin for tip relief, pitch and centre-distance errors")
    return None


def smaller_pitch_diameter_mm(stage: StageResult) -> float:
    """d1 of b/d1: ISO 6336's pinion is the wheel with fewer teeth, whichever member drives (a speed increaser's
    driving wheel is the larger one)."""
    return smaller_wheel_first((stage.pinion.teeth, stage.gear.teeth), (stage.pinion, stage.gear),
                               (stage.pinion.profile_shift, stage.gear.profile_shift))[0].pitch_diameter_mm


def face_width_warning(stage: StageResult) -> str | None:
    d1 = smaller_pitch_diameter_mm(stage)
    ratio = stage.face_width_mm / d1
    low, high = FACE_RATIO_RANGE
    if low <= ratio <= high:
        return None  # within the range: no warning, whose text alone names the members
    gear = _name(stage, stage.gear)  # a planetary's sun–planet pair: the planet
    which = _name(stage, stage.pinion) if d1 == stage.pinion.pitch_diameter_mm else \
        f"smaller wheel's (the {'driven gear' if gear == 'gear' else gear}'s)"
    if ratio > high:
        return (f"stage {stage.index}: face width / {which} pitch diameter b/d1 = {stage.face_width_mm:g}/"
                f"{d1:.4g} = {beside(ratio, high)} > {high}: the load concentrates along the "
                "face (misalignment, shaft bending); usual b/d1 ≤ 1.1–1.6")
    if ratio < low:
        return (f"stage {stage.index}: face width / {which} pitch diameter b/d1 = {stage.face_width_mm:g}/"
                f"{d1:.4g} = {beside(ratio, low)} < {low}: a very narrow face; a smaller "
                "pinion or a wider face would use the material better")
    return None


def tip_thickness_mm(stage: StageResult, gear: GearResult, tip_allowance_mm: float = 0.0) -> float:
    """s_an of the thinnest cut tooth (x_E,i, ``_cut_shift``) on the largest tip, d_a + A_dae."""
    return normal_tip_thickness_mm(gear.teeth, stage.normal_module_mm, _cut_shift(gear),
                                   math.radians(stage.helix_angle_deg), math.radians(stage.normal_pressure_angle_deg),
                                   gear.tip_diameter_mm + tip_allowance_mm)


def tip_thickness_warning(stage: StageResult, gear: GearResult, tip_allowance_mm: float = 0.0,
                          treatment: str | None = None) -> str | None:
    """s_an (``tip_thickness_mm``) below 0.2 m_n, 0.4 m_n on a surface-hardened member."""
    m_n, factor = stage.normal_module_mm, min_tip_thickness_per_module(treatment)
    tip = gear.tip_diameter_mm + tip_allowance_mm
    s_an = tip_thickness_mm(stage, gear, tip_allowance_mm)
    limit = factor * m_n
    if s_an >= limit:
        return None
    what = _pointed_text(stage, gear) if s_an <= 0 else "thin tooth tip"
    at_tip = f", d_a + A_dae = {tip:.4g} mm" if tip_allowance_mm else ""
    fix = "reduce the profile shift" if gear.generating_profile_shift is None else \
        "reduce the profile shift or the tooth-thickness / tip allowances"
    return (f"stage {stage.index}: {_name(stage, gear)} {what}, normal tip thickness s_an = {beside(s_an, limit)} mm "
            f"< {factor:g} m_n = {limit:.3g} mm{hardened_tip_text(treatment)} ({_shift_text(gear)}{at_tip}); {fix}")


def _pointed_text(stage: StageResult, gear: GearResult) -> str:
    """Where a pointed tooth's flanks meet (``pointed_tip_diameter_mm``, at the cut shift) and the transverse contact
    ratio with contact ending there (each member's tip taken at the lower of d_a and that diameter), not at d_a."""
    def point(g: GearResult) -> float:
        return pointed_tip_diameter_mm(g.teeth, stage.normal_module_mm, _cut_shift(g), math.radians(stage.helix_angle_deg),
                                       math.radians(stage.normal_pressure_angle_deg))
    reach = sum(tip_reach_mm(min(g.tip_diameter_mm, point(g)), g.base_diameter_mm) for g in (stage.pinion, stage.gear))
    eps = (reach - stage.center_distance_mm * math.sin(math.radians(stage.working_pressure_angle_deg))) \
        / stage.transverse_base_pitch_mm
    return (f"pointed tooth: the flanks meet at d = {point(gear):.4g} mm, below the tip circle, where contact ends: the "
            f"transverse contact ratio is {max(eps, 0.0):.3f}{usable_margin(eps)}, not ε_α = "
            f"{stage.contact_ratio_transverse:.3f}")


def resonance_warning(stage: StageResult) -> str | None:
    """ISO 6336-1 speed ranges: the main resonance N_S < N ≤ 1.15, and the subcritical resonances near
    N = 1/2 and 1/3 (the main range's band divided by 2 and 3; ISO names the points, gearcli the band)."""
    if stage.resonance_range != "main resonance" and not subharmonic_orders(stage.resonance_ratio,
                                                                            stage.resonance_lower_limit):
        return None  # what resonance_text says of it, without its head's figures (a sweep point's every stage)
    head = (f"{mesh_head(stage)}: resonance ratio N = n1/n_E1 = "
            f"{resonance_figure(stage.resonance_ratio, stage.resonance_lower_limit)} (n_E1 = "
            f"{stage.resonance_speed_rpm:.4g} rpm of the smaller wheel, ISO 6336-1)")
    return resonance_text(head, stage.resonance_ratio, stage.resonance_lower_limit, stage.resonance_range)


def resonance_figure(n: float, lower: float) -> str:
    """N to 3 decimals, or more where that would put it on or across the nearest edge of the ranges the warning
    names (N_S and 1.15, over 1, 2 and 3)."""
    edges = [edge / j for edge in (lower, MAIN_RESONANCE_UPPER) for j in (1, *SUBHARMONICS)]
    return beside(n, min(edges, key=lambda edge: abs(edge - n)), ".3f")


def resonance_text(head: str, n: float, lower: float, speed_range: str) -> str | None:
    """The verdict on a mesh's ISO 6336-1 resonance ratio N (``head`` names the mesh and N): main resonance, or
    near a subcritical resonance; None elsewhere."""
    if speed_range == "main resonance":
        return (f"{head} lies in the main resonance range {lower:.3f} < N ≤ {MAIN_RESONANCE_UPPER}: the mesh "
                "frequency meets the mesh's natural frequency; change the speed, the masses or the stiffness")
    orders = subharmonic_orders(n, lower)
    if not orders:
        return None
    near = " and ".join(f"N = 1/{j} ({lower / j:.3f} < N ≤ {MAIN_RESONANCE_UPPER / j:.3f})" for j in orders)
    which = " and ".join({2: "second", 3: "third"}.get(j, f"{j}th") for j in orders)
    return (f"{head} lies near {near} in the subcritical range: the mesh frequency's {which} "
            f"harmonic{'s' if len(orders) > 1 else ''} can excite the resonance")


def mesh_head(stage: StageResult) -> str:
    """A mesh warning's head: its stage, and which mesh on a planetary stage (the sun–planet; the planet–ring's own)."""
    return f"stage {stage.index}" + ("" if stage.planetary is None else " sun–planet mesh")


def mesh_data(stage: StageResult) -> JsonObject:
    return {} if stage.planetary is None else {"mesh": "sun_planet"}


def _part(stage: StageResult, gear: GearResult) -> str:
    return "pinion" if gear is stage.pinion else "gear"


def _name(stage: StageResult, gear: GearResult) -> str:
    """The member as the design file names it, for the messages (a planetary's sun–planet pair: sun, planet);
    the diagnostics' ``member`` stays the pair's (``_part``: pinion/gear, docs/output.md)."""
    return member_name(stage, _part(stage, gear))


#: |linearised / ISO - 1| beyond which a mesh law is warned about (DESIGN section 13)
STIFFNESS_NOT_ISO_TOLERANCE = 0.25


def stiffness_not_iso(stage: int, mesh: str, law, key: str = "stiffness") -> Diagnostic | None:
    """``stiffness_not_iso`` for a mesh whose law's linearised stiffness (``law``: a
    :class:`~gearcli.results.MeshStiffness`) departs from ISO 6336-1's k_n by more than 25 %; None otherwise.
    ``key``: the key that chose the law, as the message names it (``[stage.mesh] stiffness = 1e+05``)."""
    if law is None or law.departure is None or abs(law.departure) <= STIFFNESS_NOT_ISO_TOLERANCE:
        return None
    where = f"stage {stage}" + ("" if mesh == "mesh" else f" {mesh.replace('_', '–')} mesh")
    message = (f"{where}: the mesh law ({law.law}, e = {law.exponent:g}) has a linearised stiffness of "
               f"{law.linearised_N_mm:.4g} N/mm at the static load, {beside(100 * law.departure, math.copysign(100 * STIFFNESS_NOT_ISO_TOLERANCE, law.departure), '+.0f')} % from ISO 6336-1's "
               f"k_n = c_γα b / cos² β_b = {law.iso_N_mm:.4g} N/mm: natural frequencies and dynamic loads follow "
               f"the law, not ISO's mesh stiffness ({key}; the default stiffness = \"iso6336\" calibrates the law's "
               "tangent to k_n)")
    return warning(STIFFNESS_NOT_ISO, message, stage=stage, mesh=mesh, law=law.law, exponent=law.exponent,
                   linearised_N_mm=law.linearised_N_mm, iso_N_mm=law.iso_N_mm, departure=law.departure)


def stiffness_diagnostics(stages: Iterable[StageResult], keys: Sequence[str] = ()) -> tuple[Diagnostic, ...]:
    """``stiffness_not_iso`` of every mesh: a parallel stage's, a planetary stage's sun–planet and planet–ring;
    ``keys[k]``: the key that chose stage k+1's law (its ``[stage.mesh]`` one, or ``[contact]``'s)."""
    found = []
    for k, st in enumerate(stages):
        key = keys[k] if k < len(keys) else "stiffness"
        found += [stiffness_not_iso(st.index, name, law, key) for name, law in design_kind(st).meshes(st)]
    return tuple(d for d in found if d is not None)
