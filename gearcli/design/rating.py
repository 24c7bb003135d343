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

from gearcli.design import rating_factors as rf
from gearcli.design import rating_root as rr
from gearcli.design.stiffness import reference_tangential_force_N, smaller_wheel_first
from gearcli.diagnostics import Diagnostic, warning
from gearcli.errors import DesignError
from gearcli.results import MemberRating, RatingResult

if TYPE_CHECKING:
    from gearcli.config.schema import DesignFile, Gear, Material
    from gearcli.results import StageResult

STANDARD = "ISO 6336:2006 method B"
STRESS_CORRECTION_TEST_GEAR = 2.0  # Y_ST (ISO 6336-3:2006)
HB_PER_HV = 0.95  # Brinell from Vickers for steels below ~450 HV (ISO 18265, approximately)
PITTING_LOW = "pitting_safety_low"
BENDING_LOW = "bending_safety_low"
OUT_OF_RANGE = "rating_out_of_range"
Q_S_RANGE = (1.0, 8.0)  # the notch parameter range of Y_S, method B (ISO 6336-3:2006, 7.2)


# ------------------------------------------------------------------------------ required inputs
def check_rating_inputs(cfg: DesignFile) -> None:
    """With ``[rating]`` present, every key the rating needs must be given (``DesignError`` naming it)."""
    if cfg.rating is None:
        return
    if cfg.lubricant is None or cfg.lubricant.viscosity_40C_mm2_s is None:
        raise DesignError("the strength rating ([rating]) needs the oil's viscosity at 40 °C (Z_L): add "
                          "[lubricant] viscosity_40C_mm2_s", key="lubricant.viscosity_40C_mm2_s")
    used: set[str] = set()
    for k, stage in enumerate(cfg.stage):
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
    """Every stage with its ``rating`` (unchanged without ``[rating]``) and the safety warnings."""
    if cfg.rating is None:
        return stages, ()
    rated = tuple(replace(st, rating=rate_stage(cfg, k, st)) for k, st in enumerate(stages))
    return rated, tuple(d for k, st in enumerate(rated) for d in range_diagnostics(cfg, k, st)
                        + safety_diagnostics(cfg, st))


def range_diagnostics(cfg: DesignFile, k: int, st: StageResult) -> list[Diagnostic]:
    """Warnings where the stage lies outside what method B covers: ε_α < 1 (no continuous mesh), and a
    notch parameter q_s of the root outside 1 … 8 (Y_S's range)."""
    out = []
    if st.contact_ratio_transverse < 1.0:
        out.append(warning(OUT_OF_RANGE, f"stage {st.index}: ε_α = {st.contact_ratio_transverse:.3g} < 1: ISO 6336 "
                           "assumes a continuous mesh (ε_α ≥ 1); the strength rating of this stage is not valid",
                           stage=st.index, quantity="contact_ratio_transverse", value=st.contact_ratio_transverse))
    stage = cfg.stage[k]
    for part in ("pinion", "gear"):
        g = getattr(st, part)
        form = rr.tooth_form(g.teeth, st.normal_module_mm, math.radians(st.normal_pressure_angle_deg),
                             math.radians(st.helix_angle_deg), math.radians(st.base_helix_angle_deg), g.profile_shift,
                             g.tip_diameter_mm, g.pitch_diameter_mm, st.contact_ratio_transverse,
                             (stage.basic_rack.dedendum, stage.basic_rack.root_radius))
        if not Q_S_RANGE[0] <= form["q_s"] < Q_S_RANGE[1]:
            out.append(warning(OUT_OF_RANGE, f"stage {st.index} {part}: the root's notch parameter q_s = "
                               f"{form['q_s']:.3g} lies outside 1 … 8, where ISO 6336-3's Y_S (method B) holds",
                               stage=st.index, member=part, quantity="q_s", value=form["q_s"]))
    return out


def rate_stage(cfg: DesignFile, k: int, st: StageResult, *, simulated_k_v: float | None = None) -> RatingResult:
    """The rating of stage ``k`` (0-based); ``simulated_k_v`` replaces K_v (``K_v_source = "simulated"``)."""
    rating, stage = cfg.rating, cfg.stage[k]
    assert rating is not None and stage.accuracy_grade is not None and cfg.lubricant is not None
    assert cfg.lubricant.viscosity_40C_mm2_s is not None
    cfg_members = (stage.pinion, stage.gear)
    members = (st.pinion, st.gear)
    mats = tuple(cfg.materials[g.material] for g in cfg_members)
    small, large = smaller_wheel_first((st.pinion.teeth, st.gear.teeth), (0, 1),
                                       (st.pinion.profile_shift, st.gear.profile_shift))
    g1, g2 = members[small], members[large]
    grade = stage.accuracy_grade
    beta, beta_b = math.radians(st.helix_angle_deg), math.radians(st.base_helix_angle_deg)
    alpha_n, alpha_t = math.radians(st.normal_pressure_angle_deg), math.radians(st.transverse_pressure_angle_deg)
    alpha_wt = math.radians(st.working_pressure_angle_deg)
    b, m_n = st.face_width_mm, st.normal_module_mm
    u = g2.teeth / g1.teeth
    f_t = reference_tangential_force_N(st.static_force_N.tangential, b)
    k_a = cfg.load.application_factor
    speed_m_s = max(math.pi * g1.pitch_diameter_mm * abs(g1.speed_rpm) / 60000.0, 1e-9)
    eps_a, eps_b, eps_g = st.contact_ratio_transverse, st.overlap_ratio, st.contact_ratio_total
    treatments = tuple(str(m.treatment) for m in mats)
    hlim = tuple(float(m.contact_fatigue_limit_MPa or 0.0) for m in mats)
    flim = tuple(float(m.bending_fatigue_limit_MPa or 0.0) for m in mats)

    # ISO 6336-1: deviations of the grade, running-in, K_v, K_Hβ, K_Fβ, K_Hα, K_Fα
    f_pb = max(rf.single_pitch_tolerance_um(g.pitch_diameter_mm, m_n, grade) for g in members) * math.cos(alpha_t)
    f_fa = max(rf.profile_form_tolerance_um(g.pitch_diameter_mm, m_n, grade) for g in members)
    y_a = 0.5 * sum(rf.running_in_um(t, h, f_pb, speed_m_s) for t, h in zip(treatments, hlim, strict=True))
    y_f = 0.5 * sum(rf.running_in_um(t, h, f_fa, speed_m_s) for t, h in zip(treatments, hlim, strict=True))
    tip_relief = stage.tip_relief_um or 0.0  # C_a; running-in is in f_pb,eff and f_fα,eff, not here
    line_load = f_t * k_a / b
    if simulated_k_v is not None:
        k_v, k_v_source = max(1.0, simulated_k_v), "simulated"
    elif isinstance(rating.dynamic_factor, float):
        k_v, k_v_source = rating.dynamic_factor, "given"
    else:
        k_v = rf.dynamic_factor(st.resonance_ratio, st.resonance_lower_limit, eps_g,
                                st.iso6336_single_pair_stiffness_N_mm_um, line_load, f_pb - y_a, f_fa - y_f,
                                tip_relief)
        k_v_source = "iso"
    if rating.face_load_factor is not None:
        k_hb, k_hb_source = rating.face_load_factor, "given"
    else:
        f_hb = rf.helix_slope_tolerance_um(g1.pitch_diameter_mm, b, grade)
        k_hb = rf.face_load_factor_estimate(st.iso6336_mesh_stiffness_beta_N_mm_um, line_load * k_v, f_hb,
                                            b / g1.pitch_diameter_mm, (treatments[small], hlim[small], speed_m_s))
        k_hb_source = "estimated"
    depth = (stage.basic_rack.addendum + stage.basic_rack.dedendum) * m_n  # h of b/h: the rack's depth
    k_fb = rf.face_load_factor_root(k_hb, b, depth)
    z_eps = rf.contact_ratio_factor(eps_a, eps_b)
    k_ha, k_fa = rf.transverse_load_factors(eps_a, eps_g, z_eps, st.iso6336_mesh_stiffness_N_mm_um,
                                            max(f_pb, f_fa) - y_a, line_load * k_v * k_hb)

    # ISO 6336-2: contact stress and the stage-level factors
    z_h = rf.zone_factor(beta_b, alpha_t, alpha_wt)
    z_e = rf.elasticity_factor(mats[0].youngs_modulus_MPa, mats[0].poisson_ratio,
                               mats[1].youngs_modulus_MPa, mats[1].poisson_ratio)
    z_beta = rf.helix_factor_pitting(beta)
    sigma_h0 = z_h * z_e * z_eps * z_beta * math.sqrt(f_t / (g1.pitch_diameter_mm * b) * (u + 1.0) / u)
    sigma_h = sigma_h0 * math.sqrt(k_a * k_v * k_hb * k_ha)
    z_b, z_d = rf.single_pair_factors((g1.tip_diameter_mm, g2.tip_diameter_mm),
                                      (g1.base_diameter_mm, g2.base_diameter_mm), (g1.teeth, g2.teeth),
                                      alpha_wt, eps_a, eps_b)
    z_bd = {small: z_b, large: z_d}
    low_hlim = min(hlim)
    z_l = rf.lubricant_factor(low_hlim, cfg.lubricant.viscosity_40C_mm2_s)
    z_v = rf.velocity_factor(low_hlim, speed_m_s)
    rho = [0.5 * g.base_diameter_mm * math.tan(alpha_wt) for g in (g1, g2)]
    rz_flank = 0.5 * sum(float(g.flank_roughness_Rz_um or 0.0) for g in cfg_members)
    z_r = rf.roughness_factor(low_hlim, rz_flank, rho[0] * rho[1] / (rho[0] + rho[1]))
    soft, z_w = _work_hardening(mats, treatments)
    y_beta = rr.helix_factor_bending(eps_b, st.helix_angle_deg)

    def member(i: int) -> MemberRating:
        g, gear_cfg = members[i], cfg_members[i]
        cycles = 60.0 * abs(g.speed_rpm) * rating.required_life_h
        z_nt = rf.life_factor_pitting(treatments[i], cycles, rating.material_quality)
        z_x = 1.0
        sig_h = z_bd[i] * sigma_h
        sig_hg = hlim[i] * z_nt * z_l * z_v * z_r * (z_w if i == soft else 1.0) * z_x
        form = rr.tooth_form(g.teeth, m_n, alpha_n, beta, beta_b, g.profile_shift, g.tip_diameter_mm,
                             g.pitch_diameter_mm, eps_a, (stage.basic_rack.dedendum, stage.basic_rack.root_radius))
        if not (form["s_Fn"] > 0.0 and form["rho_F"] > 0.0 and form["h_Fe"] > 0.0):
            part = "pinion" if i == 0 else "gear"
            raise DesignError(f"the root of this {g.teeth}-tooth member is undercut so far that ISO 6336-3 (method B) "
                              f"finds no critical section (s_Fn = {form['s_Fn']:.3g} mm, ρ_F = {form['rho_F']:.3g} mm): "
                              "raise the profile shift or the tooth count to rate it",
                              key=f"stage[{k}].{part}.profile_shift")
        y_b = rr.rim_factor(gear_cfg.rim_thickness_mm, 0.5 * (g.tip_diameter_mm - g.root_diameter_mm))
        y_dt = rr.deep_tooth_factor(eps_a, beta_b, grade)
        b_f = min(g.face_width_mm, b + 2.0 * m_n)
        sig_f0 = f_t / (b_f * m_n) * form["Y_F"] * form["Y_S"] * y_beta * y_b * y_dt
        sig_f = sig_f0 * k_a * k_v * k_fb * k_fa
        y_d = rr.relative_notch_sensitivity(treatments[i], form["q_s"])
        y_r = rr.relative_surface_factor(treatments[i], float(gear_cfg.root_roughness_Rz_um or 0.0))
        y_x = rr.size_factor_bending(treatments[i], m_n)
        y_nt = rf.life_factor_bending(treatments[i], cycles, rating.material_quality)
        sig_fg = flim[i] * STRESS_CORRECTION_TEST_GEAR * y_nt * y_d * y_r * y_x
        return MemberRating(
            load_cycles=cycles, Z_BD=z_bd[i], sigma_H_MPa=sig_h, Z_NT=z_nt, Z_X=z_x, sigma_HG_MPa=sig_hg,
            sigma_HP_MPa=sig_hg / rating.min_safety_pitting, S_H=sig_hg / sig_h, Y_F=form["Y_F"], Y_S=form["Y_S"],
            Y_B=y_b, Y_DT=y_dt, sigma_F0_MPa=sig_f0, sigma_F_MPa=sig_f, Y_delta_rel_T=y_d, Y_R_rel_T=y_r, Y_X=y_x,
            Y_NT=y_nt, sigma_FG_MPa=sig_fg, sigma_FP_MPa=sig_fg / rating.min_safety_bending, S_F=sig_fg / sig_f)

    return RatingResult(
        standard=STANDARD, K_A=k_a, K_v=k_v, K_v_source=k_v_source, K_Hbeta=k_hb, K_Hbeta_source=k_hb_source,
        K_Fbeta=k_fb, K_Halpha=k_ha, K_Falpha=k_fa, Z_H=z_h, Z_E=z_e, Z_eps=z_eps, Z_beta=z_beta, Z_L=z_l,
        Z_V=z_v, Z_R=z_r, Z_W=z_w, Y_beta=y_beta, sigma_H0_MPa=sigma_h0, sigma_H_MPa=sigma_h,
        pinion=member(0), gear=member(1))


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
    """A warning for every safety below its minimum, naming stage, member and failure mode."""
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
                message = (f"stage {st.index} {part} (z = {teeth}): {what} safety {symbol} = {value:.3g} is below the minimum "
                           f"{minima[mode]:.3g} ({norm}, K_v = {r.K_v:.3g} {r.K_v_source}{source}); widen the face, "
                           "raise the module or choose a stronger material")
                out.append(warning(code, message, stage=st.index, member=part, mode=mode, S=value,
                                   S_min=minima[mode]))
    return out


# ------------------------------------------------------------------------- the simulated K_v
def simulated_dynamic_factor(tangential_N, static_tangential_N: float) -> float:
    """K_v from a run: max(1, steady-window max |F_t| / |static F_t|), ``tangential_N`` the window's statistics
    (min, max) of F_t; 1 when the static force is 0 (no load to amplify)."""
    if static_tangential_N == 0.0:
        return 1.0
    peak = max(abs(tangential_N.max), abs(tangential_N.min))
    return max(1.0, peak / abs(static_tangential_N))


def simulated_ratings(cfg: DesignFile, design, stages) -> tuple[tuple, list[Diagnostic]]:
    """With ``[rating] dynamic_factor = "simulated"``: simulate's stage summaries (``StageDynamics``) each with
    its ``rating`` at the simulated K_v, and the safety warnings of that rating; unchanged otherwise."""
    if cfg.rating is None or cfg.rating.dynamic_factor != "simulated":
        return tuple(stages), []
    out, diags = [], []
    for k, sd in enumerate(stages):
        k_v = simulated_dynamic_factor(sd.tangential_N, sd.static_tangential_N)
        rated = replace(design.stages[k], rating=rate_stage(cfg, k, design.stages[k], simulated_k_v=k_v))
        diags += safety_diagnostics(cfg, rated)
        out.append(replace(sd, rating=rated.rating))
    return tuple(out), diags
