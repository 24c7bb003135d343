"""Strength rating of a planetary stage's planet–ring (internal) mesh: ISO 6336-2 (pitting) and ISO 6336-3
(tooth root of planet and ring), 2006 editions, method B (docs/iso6336.md, "The planet–ring mesh").

Reuses the external-gear factors of ``rating_factors`` and ``rating_root`` wherever the standard's formula is the
same; what differs for the internal pair:

- σ_H0 with u = z_r/z_p taken negative: (u + 1)/u becomes (|u| − 1)/|u|; Z_H at the internal mesh's α_wt;
  Z_ε and the load factors from the internal mesh's ε_α, c′, c_γα, c_γβ.
- Z_D = 1 for the internal gear (ISO 6336-2); Z_B of the planet from the relative curvature at its inner point of
  single contact B against the concave ring flank, M_1 = √((1/ρ_1B − 1/ρ_2B)/(1/ρ_1C − 1/ρ_2C)), ρ_2 = ρ_1 + a_w sin α_wt.
- ρ_red = ρ_1 ρ_2/(ρ_2 − ρ_1) for Z_R.
- K_v: ``dynamic_factor`` when given as a number, else ISO 6336-1 method B from the internal mesh's own resonance
  ratio (m_red = the planet's m*, the ring taken infinitely heavy; c′, c_γα, ε_γ of the internal mesh).
- Load cycles: the planet 60 n_p,rel H (one mesh per relative turn), the ring 60 N |n_r − n_c| H (N planets).
- The ring's root: ``rating_root.internal_tooth_form`` (60° tangent, the substitute rack's fillet ρ_F = ρ_fP),
  Y_B of an internal gear from ``ring.rim_thickness_mm`` over m_n; the planet's root carries Y_M = 0.7 (an idler).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, cast

from gearcli.core.text import beside
from gearcli.design import rating_factors as rf
from gearcli.design import rating_root as rr
from gearcli.design import resonance as res
from gearcli.design.rating import (
    BENDING_LOW,
    HB_PER_HV,
    OUT_OF_RANGE,
    PITTING_LOW,
    Q_S_RANGE,
    STANDARD,
    STRESS_CORRECTION_TEST_GEAR,
    member_tooth_depth_mm,
    root_shift,
    static_cycles_diagnostics,
    virtual_contact_ratio_diagnostics,
)
from gearcli.design.rating_load import MeshLoad, resolve_load_factors
from gearcli.design.rating_results import InternalRatingResult, MemberRating
from gearcli.design.stiffness import reference_tangential_force_N
from gearcli.diagnostics import Diagnostic, warning
from gearcli.errors import DesignError

if TYPE_CHECKING:
    from gearcli.config.schema import DesignFile, Material, PlanetaryStage
    from gearcli.results import StageResult


def _tooth_depth_mm(stage, planet, ring) -> float:
    """h of K_Fβ's b/h on the planet–ring mesh (ISO 6336-1:2006, 7.7): the deeper tooth of the pair, the planet's
    as an external member's (:func:`gearcli.design.rating.member_tooth_depth_mm`) and the ring's (d_f − d_a)/2, at
    its deepest cut where it has a tooth-thickness allowance."""
    ring_root = max(ring.manufactured_root_diameter_mm or (ring.root_diameter_mm,))
    return max(member_tooth_depth_mm(planet, stage.planet.tip_diameter_allowance_mm),
               0.5 * (ring_root - ring.tip_diameter_mm))


def _complete(mat: Material, ring_rz: float | None) -> bool:
    return (mat.treatment is not None and mat.contact_fatigue_limit_MPa is not None
            and mat.bending_fatigue_limit_MPa is not None and ring_rz is not None)


def planet_single_contact_factor(tip_p: float, base_p: float, working_rad: float, a_w: float, p_bt: float,
                                 eps_beta: float) -> float:
    """Z_B of the planet against the concave ring flank (ISO 6336-2, 6.2, with the internal pair's curvatures)."""
    rho1_c = 0.5 * base_p * math.tan(working_rad)
    shift = a_w * math.sin(working_rad)  # T1T2: the ring's tangency lies beyond the planet's by a_w sin α_wt
    rho1_b = math.sqrt(max(0.25 * (tip_p ** 2 - base_p ** 2), 0.0)) - p_bt
    if eps_beta >= 1.0 or rho1_b <= 0.0:
        return 1.0
    curv_c = 1.0 / rho1_c - 1.0 / (rho1_c + shift)
    curv_b = 1.0 / rho1_b - 1.0 / (rho1_b + shift)
    m = math.sqrt(curv_b / curv_c)
    return max(1.0, m - eps_beta * (m - 1.0))


def rate_planet_ring(cfg: DesignFile, k: int, st: StageResult,
                     simulated_k_v: float | None = None) -> InternalRatingResult | None:
    """The planet–ring rating of planetary stage ``k`` (``st`` with K_γ applied to its force); ``None`` when the
    ring's material or flank roughness lacks what the rating needs. ``simulated_k_v`` replaces K_v
    (``K_v_source = "simulated"``)."""
    stage, rating, lub, p = cast("PlanetaryStage", cfg.stage[k]), cfg.rating, cfg.lubricant, st.planetary
    assert p is not None  # a planetary stage's result (ISO rates its planet–ring mesh: design/iso6336.py)
    if rating is None or lub is None or lub.viscosity_40C_mm2_s is None or stage.accuracy_grade is None:
        return None
    mats = (cfg.materials[stage.planet.material], cfg.materials[stage.ring.material])
    if (not _complete(mats[1], stage.ring.flank_roughness_Rz_um) or not _complete(mats[0], 0.0)
            or stage.ring.root_roughness_Rz_um is None):  # Y_RrelT of the ring's root, never a polished default
        return None
    mesh, planet, ring = p.planet_ring, p.planet, p.ring
    treat = (str(mats[0].treatment), str(mats[1].treatment))
    hlim = (float(mats[0].contact_fatigue_limit_MPa or 0.0), float(mats[1].contact_fatigue_limit_MPa or 0.0))
    grade, m_n, b = stage.accuracy_grade, st.normal_module_mm, mesh.face_width_mm
    alpha_t, alpha_wt = math.radians(st.transverse_pressure_angle_deg), math.radians(mesh.working_pressure_angle_deg)
    beta, beta_b = math.radians(st.helix_angle_deg), math.radians(st.base_helix_angle_deg)
    eps_a, eps_b, eps_g = mesh.contact_ratio_transverse, mesh.overlap_ratio, mesh.contact_ratio_total
    # the planet–ring mesh's own force (η_m off the sun–planet mesh's with losses) times K_γ
    f_t = reference_tangential_force_N(mesh.static_force_N.tangential * p.load_sharing_factor, b)
    k_a = cfg.load.application_factor
    speed = max(math.pi * planet.pitch_diameter_mm * abs(st.gear.speed_rpm) / 60000.0, 1e-9)  # carrier frame
    # ISO 6336-1: K_v (the internal mesh's own N = n_p/n_E1, design.planetary; N_S from this rating's line load),
    # K_Hβ, K_Fβ, K_Hα, K_Fα: the one resolution of every mesh (rating_load)
    line_load = f_t * k_a / b
    lf = resolve_load_factors(rating, MeshLoad(
        grade=grade, normal_module_mm=m_n, transverse_pressure_angle_rad=alpha_t,
        pitch_diameters_mm=(planet.pitch_diameter_mm, ring.pitch_diameter_mm), treatments=treat, hlim_MPa=hlim,
        small=0, speed_m_s=speed, line_load_N_mm=line_load, face_width_mm=b, resonance_ratio=mesh.resonance_ratio,
        resonance_lower_limit=res.lower_main_resonance_limit(line_load), contact_ratios=(eps_a, eps_b, eps_g),
        single_pair_stiffness=mesh.iso6336_single_pair_stiffness_N_mm_um,
        mesh_stiffness=mesh.iso6336_mesh_stiffness_N_mm_um, mesh_stiffness_beta=mesh.iso6336_mesh_stiffness_beta_N_mm_um,
        tip_relief_um=stage.tip_relief_um or 0.0,
        tooth_depth_mm=_tooth_depth_mm(stage, planet, ring)), simulated_k_v)
    k_v, k_hb, k_fb, k_ha, k_fa, z_eps = lf.k_v, lf.k_hb, lf.k_fb, lf.k_ha, lf.k_fa, lf.z_eps
    # ISO 6336-2: pitting
    z_h = rf.zone_factor(beta_b, alpha_t, alpha_wt)
    z_e = rf.elasticity_factor(mats[0].youngs_modulus_MPa, mats[0].poisson_ratio, mats[1].youngs_modulus_MPa,
                               mats[1].poisson_ratio)
    z_beta = rf.helix_factor_pitting(beta)
    u = ring.teeth / planet.teeth  # |u|; the internal pair's u is negative
    sigma_h0 = z_h * z_e * z_eps * z_beta * math.sqrt(f_t / (planet.pitch_diameter_mm * b) * (u - 1.0) / u)
    sigma_h = sigma_h0 * math.sqrt(k_a * k_v * k_hb * k_ha)
    z_b = planet_single_contact_factor(planet.tip_diameter_mm, planet.base_diameter_mm, alpha_wt,
                                       mesh.center_distance_mm, mesh.transverse_base_pitch_mm, eps_b)
    low = min(hlim)
    rho1 = 0.5 * planet.base_diameter_mm * math.tan(alpha_wt)
    rho2 = 0.5 * ring.base_diameter_mm * math.tan(alpha_wt)
    rz = 0.5 * (float(stage.planet.flank_roughness_Rz_um or 0.0) + float(stage.ring.flank_roughness_Rz_um or 0.0))
    z_l = rf.lubricant_factor(low, lub.viscosity_40C_mm2_s)
    z_v = rf.velocity_factor(low, speed)
    z_r = rf.roughness_factor(low, rz, rho1 * rho2 / (rho2 - rho1))
    hard = [t in rf.SURFACE_HARDENED for t in treat]
    soft, z_w = -1, 1.0
    if hard[0] != hard[1]:
        soft = 1 if hard[0] else 0
        hv = mats[soft].surface_hardness_HV
        z_w = rf.work_hardening_factor(None if hv is None else HB_PER_HV * hv)
    cycles = (60.0 * abs(st.gear.speed_rpm) * rating.life_h,
              60.0 * p.planet_count * abs(ring.speed_rpm - p.carrier.speed_rpm) * rating.life_h)
    z_nt = tuple(rf.life_factor_pitting(treat[i], cycles[i], rating.material_quality) for i in (0, 1))
    sig_hg = tuple(hlim[i] * z_nt[i] * z_l * z_v * z_r * (z_w if i == soft else 1.0) for i in (0, 1))
    sig_hb = (z_b * sigma_h, sigma_h)  # Z_D = 1 for the internal gear
    # ISO 6336-3: the planet's root on its ring side (an external gear cut by the rack; an idler: Y_M = 0.7)
    rack = (stage.basic_rack.dedendum, stage.basic_rack.root_radius)
    an = math.radians(st.normal_pressure_angle_deg)
    z_gamma = rating.virtual_tooth_count
    # the planet's and the ring's roots at x, or at x_E of their tooth-thickness allowances (``[rating]
    # root_profile_shift``; the planet's as in its sun mesh)
    forms = (rr.tooth_form(planet.teeth, m_n, an, beta, beta_b, root_shift(planet, rating.root_profile_shift),
                           planet.tip_diameter_mm, planet.pitch_diameter_mm, eps_a, rack,
                           virtual_tooth_count=z_gamma),
             rr.internal_tooth_form(ring.teeth, m_n, an, beta, beta_b, root_shift(ring, rating.root_profile_shift),
                                    ring.tip_diameter_mm, ring.pitch_diameter_mm, eps_a, rack,
                                    cutter_teeth=stage.ring.cutter_teeth,
                                    virtual_tooth_count=z_gamma))
    _check_ring_root(forms[1], k, stage)
    y_beta = rr.helix_factor_bending(eps_b, st.helix_angle_deg)
    y_bs = (rr.rim_factor(stage.planet.rim_thickness_mm, 0.5 * (planet.tip_diameter_mm - planet.root_diameter_mm)),
            rr.internal_rim_factor(stage.ring.rim_thickness_mm, m_n))
    y_dt = rr.deep_tooth_factor(eps_a, beta_b, grade)
    parts, members = (stage.planet, stage.ring), (planet, ring)
    y_m = (rr.IDLER_MEAN_STRESS_FACTOR, 1.0)
    rated = []
    for i in (0, 1):
        form = forms[i]
        b_f = min(members[i].face_width_mm, b + 2.0 * m_n)
        sig_f0 = f_t / (b_f * m_n) * form["Y_F"] * form["Y_S"] * y_beta * y_bs[i] * y_dt
        sig_f = sig_f0 * k_a * k_v * k_fb * k_fa
        y_d = rr.relative_notch_sensitivity(treat[i], form["q_s"])
        y_r = rr.relative_surface_factor(treat[i], float(parts[i].root_roughness_Rz_um or 0.0))
        y_x = rr.size_factor_bending(treat[i], m_n)
        y_nt = rf.life_factor_bending(treat[i], cycles[i], rating.material_quality)
        sig_fg = (float(mats[i].bending_fatigue_limit_MPa or 0.0) * STRESS_CORRECTION_TEST_GEAR * y_nt * y_d * y_r
                  * y_x * y_m[i])
        rated.append(MemberRating(
            load_cycles=cycles[i], Z_BD=(z_b, 1.0)[i], sigma_H_MPa=sig_hb[i], Z_NT=z_nt[i], Z_X=1.0,
            sigma_HG_MPa=sig_hg[i], sigma_HP_MPa=sig_hg[i] / rating.min_safety_pitting, S_H=sig_hg[i] / sig_hb[i],
            Y_F=form["Y_F"], Y_S=form["Y_S"], Y_B=y_bs[i], Y_DT=y_dt, sigma_F0_MPa=sig_f0, sigma_F_MPa=sig_f,
            Y_delta_rel_T=y_d, Y_R_rel_T=y_r, Y_X=y_x, Y_NT=y_nt, sigma_FG_MPa=sig_fg,
            sigma_FP_MPa=sig_fg / rating.min_safety_bending, S_F=sig_fg / sig_f, Y_M=y_m[i]))
    return InternalRatingResult(
        standard=STANDARD, K_A=k_a, K_v=k_v, K_v_source=lf.k_v_source, K_Hbeta=k_hb, K_Hbeta_source=lf.k_hb_source,
        K_Fbeta=k_fb, K_Halpha=k_ha, K_Falpha=k_fa, Z_H=z_h, Z_E=z_e, Z_eps=z_eps, Z_beta=z_beta, Z_L=z_l, Z_V=z_v,
        Z_R=z_r, Z_W=z_w, Y_beta=y_beta, sigma_H0_MPa=sigma_h0, sigma_H_MPa=sigma_h, pinion=rated[0],
        gear=rated[1])


def _check_ring_root(form: dict[str, float], k: int, stage: PlanetaryStage) -> None:
    """Refuse (``DesignError`` naming the key) a ring whose root ISO 6336-3 cannot rate: no fillet (ρ_F ≤ 0: a sharp
    rack root, ``basic_rack.root_radius = 0``, without a pinion-type cutter, or a cutter that generates none), where the
    notch parameter q_s = s_Fn/(2 ρ_F) and with it Y_S are unbounded; or no critical section (s_Fn or h_Fe ≤ 0)."""
    if not form["rho_F"] > 0.0:
        cutter = stage.ring.cutter_teeth
        raise DesignError(
            f"the ring's root fillet has no radius (ρ_F = {form['rho_F']:.3g} mm"
            + (f", generated by a {cutter}-tooth cutter" if cutter is not None else
               ", a sharp rack root without a pinion-type cutter") + "): ISO 6336-3's notch parameter q_s = s_Fn/(2 ρ_F) "
            "and Y_S are unbounded; give basic_rack.root_radius > 0 (ISO 53: 0.38) or the ring's cutter_teeth to rate "
            "it", key=f"stage[{k}]." + ("ring.cutter_teeth" if cutter is not None else "basic_rack.root_radius"))
    if not (form["s_Fn"] > 0.0 and form["h_Fe"] > 0.0):
        raise DesignError(f"ISO 6336-3 (method B) finds no critical section on the ring's root (s_Fn = "
                          f"{form['s_Fn']:.3g} mm, h_Fe = {form['h_Fe']:.3g} mm): change the ring's profile shift or "
                          "the basic rack to rate it", key=f"stage[{k}].ring.profile_shift")


def _ring_range_diagnostics(cfg: DesignFile, st: StageResult) -> list[Diagnostic]:
    """``rating_out_of_range`` where the ring's root lies outside what ISO 6336-3 covers: its notch parameter q_s
    outside 1 … 8 (Y_S), its rim thinner than 1.75 normal modules (the internal gear's Y_B, held at that value), its
    load cycles in the static range of its Z_NT or Y_NT curve; and where the planet–ring mesh's ε_αn reaches 2.5
    (ISO 6336-2's scope)."""
    stage, p = cast("PlanetaryStage", cfg.stage[st.index - 1]), st.planetary
    assert p is not None  # a planetary stage's result
    ring, mesh = p.ring, p.planet_ring
    form = rr.internal_tooth_form(ring.teeth, st.normal_module_mm, math.radians(st.normal_pressure_angle_deg),
                                  math.radians(st.helix_angle_deg), math.radians(st.base_helix_angle_deg),
                                  root_shift(ring, cfg.rating.root_profile_shift if cfg.rating is not None
                                             else "nominal"), ring.tip_diameter_mm, ring.pitch_diameter_mm,
                                  mesh.contact_ratio_transverse,
                                  (stage.basic_rack.dedendum, stage.basic_rack.root_radius),
                                  cutter_teeth=stage.ring.cutter_teeth)
    out = []
    if not Q_S_RANGE[0] <= form["q_s"] < Q_S_RANGE[1]:
        out.append(warning(OUT_OF_RANGE, f"stage {st.index} ring: the root's notch parameter q_s = {form['q_s']:.3g} "
                           "lies outside 1 … 8, where ISO 6336-3's Y_S (method B) holds", stage=st.index,
                           member="ring", quantity="q_s", value=form["q_s"], mesh="planet_ring"))
    out.extend(virtual_contact_ratio_diagnostics(st.index, mesh.contact_ratio_transverse, st.base_helix_angle_deg,
                                                 mesh="planet_ring"))
    m_n = st.normal_module_mm  # an internal gear's rim is measured in normal modules (ISO 6336-3:2006, 10)
    rim = stage.ring.rim_thickness_mm
    if rim is not None and rim / m_n < rr.INTERNAL_RIM_RANGE[0]:
        out.append(warning(OUT_OF_RANGE, f"stage {st.index} ring: rim s_R/m_n = {rim / m_n:.3g} below 1.75, where "
                           "ISO 6336-3's rim factor of an internal gear ends; Y_B is taken at 1.75 "
                           f"({rr.internal_rim_factor(rim, m_n):.3g}), a thinner rim needs a finite element check",
                           stage=st.index, member="ring", quantity="rim_ratio", value=rim / m_n,
                           mesh="planet_ring"))
    rated = mesh.rating
    if rated is not None:  # the ring's own N_L (the planet's ring side counts the cycles its sun side warns of)
        out += static_cycles_diagnostics(st.index, "ring", str(cfg.materials[stage.ring.material].treatment),
                                         rated.gear.load_cycles, mesh="planet_ring")
    return out


def planet_ring_safety_diagnostics(cfg: DesignFile, st: StageResult) -> list[Diagnostic]:
    """A warning for every safety of the planet–ring mesh below its minimum (the codes of the external pairs',
    ``member`` "planet" or "ring", ``mesh`` "planet_ring"), and where the ring's root lies outside the method's
    range (``rating_out_of_range``)."""
    p = st.planetary
    r = None if p is None else p.planet_ring.rating
    if r is None or p is None or cfg.rating is None:
        return []
    minima = {"pitting": cfg.rating.min_safety_pitting, "bending": cfg.rating.min_safety_bending}
    out = _ring_range_diagnostics(cfg, st)
    for member, m, teeth in (("planet", r.pinion, p.planet.teeth), ("ring", r.gear, p.ring.teeth)):
        for mode, value, symbol in (("pitting", m.safety("pitting"), "S_H"), ("bending", m.safety("bending"), "S_F")):
            if value is None or value >= minima[mode]:
                continue
            what = "pitting (flank)" if mode == "pitting" else "tooth-root bending"
            norm = "ISO 6336-2" if mode == "pitting" else "ISO 6336-3"  # as the external pairs' warnings name it
            out.append(warning(PITTING_LOW if mode == "pitting" else BENDING_LOW,
                               f"stage {st.index} planet–ring mesh, {member} (z = {teeth}): {what} safety {symbol} = "
                               f"{beside(value, minima[mode])} is below the minimum {minima[mode]:.3g} ({norm}, K_v = {r.K_v:.3g} "
                               f"{r.K_v_source}); widen the face, raise the module or choose a stronger material",
                               stage=st.index, member=member, mode=mode, S=value, S_min=minima[mode],
                               mesh="planet_ring"))
    return out
