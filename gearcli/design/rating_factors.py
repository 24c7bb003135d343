"""The factors of ISO 6336-1, -2 and -5 (2006 editions, method B), one formula per function; the tooth root's
(ISO 6336-3) are in ``rating_root``.

Units as the standards write them: lengths mm, stresses N/mm² (MPa), deviations µm, speeds m/s, line loads
N/mm. docs/iso6336.md lists every factor with its clause, formula and validity range. Index 1 is the smaller
wheel (ISO's pinion) wherever the standard orders the pair.

Pure ``math``: ``gearcli design`` never imports numpy or scipy for the rating.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

# ------------------------------------------------------------------- ISO 6336-5 material groups
# treatment -> the letters of ISO 6336 tables: St structural, V through-hardened, GS cast steel, GGG nodular,
# GG grey iron, Eh case-carburized, IF induction/flame hardened, NT/NV nitrided, NV(nitrocar.) nitrocarburized
TREATMENTS = ("case_carburized", "nitrided", "nitrocarburized", "induction_hardened", "flame_hardened",
              "through_hardened", "structural_steel", "cast_steel", "nodular_iron", "grey_iron")
SURFACE_HARDENED = frozenset({"case_carburized", "nitrided", "nitrocarburized", "induction_hardened",
                              "flame_hardened"})

# Life factor curves as nodes (N_L, factor): a power law between nodes, constant before the first; the
# last node (1e10) is the "normal" material quality's end value; "optimum" keeps 1.0 past the knee.
# ISO 6336-2:2006 Table 2 (Z_NT, no pitting permitted) and ISO 6336-3:2006 Table 3 (Y_NT).
_ZNT_NODES = {
    "steel": ((1e5, 1.6), (5e7, 1.0), (1e10, 0.85)),  # St, V, GS, GGG (perl./bai.), Eh, IF
    "nitrided": ((1e5, 1.3), (2e6, 1.0), (1e10, 0.85)),  # GG, GGG (ferr.), NT, NV (nitrided)
    "nitrocarburized": ((1e5, 1.1), (2e6, 1.0), (1e10, 0.85)),  # NV (nitrocarburized)
}
_YNT_NODES = {
    "through": ((1e4, 2.5), (3e6, 1.0), (1e10, 0.85)),  # St, V, GS, GGG (perl./bai.)
    "surface": ((1e3, 2.5), (3e6, 1.0), (1e10, 0.85)),  # Eh, IF (root)
    "nitrided": ((1e3, 1.6), (3e6, 1.0), (1e10, 0.85)),  # GG, GGG (ferr.), NT, NV (nitrided)
    "nitrocarburized": ((1e3, 1.1), (3e6, 1.0), (1e10, 0.85)),  # NV (nitrocarburized)
}


def znt_curve(treatment: str) -> tuple:
    if treatment in ("nitrided", "grey_iron"):
        return _ZNT_NODES["nitrided"]
    if treatment == "nitrocarburized":
        return _ZNT_NODES["nitrocarburized"]
    return _ZNT_NODES["steel"]


def ynt_curve(treatment: str) -> tuple:
    if treatment in ("case_carburized", "induction_hardened", "flame_hardened"):
        return _YNT_NODES["surface"]
    if treatment in ("nitrided", "grey_iron"):
        return _YNT_NODES["nitrided"]
    if treatment == "nitrocarburized":
        return _YNT_NODES["nitrocarburized"]
    return _YNT_NODES["through"]


def _life_factor(nodes: Sequence[tuple[float, float]], cycles: float, optimum: bool) -> float:
    """Power law (straight in log–log) between the nodes; the first node's value below it."""
    if cycles <= nodes[0][0]:
        return nodes[0][1]
    knee = nodes[-2][0]
    if optimum and cycles >= knee:
        return 1.0
    for (n_a, y_a), (n_b, y_b) in zip(nodes, nodes[1:], strict=False):
        if cycles <= n_b:
            return y_a * (cycles / n_a) ** (math.log(y_b / y_a) / math.log(n_b / n_a))
    return nodes[-1][1]  # beyond 1e10: the normal quality's end value (KISSsoft prints 0.850 at 1.2e10)


def life_factor_pitting(treatment: str, cycles: float, quality: str) -> float:
    """Z_NT (ISO 6336-2:2006, Table 2; no pitting permitted): 5e7 < N_L ≤ 1e10 gives (5e7/N_L)^0.0307."""
    return _life_factor(znt_curve(treatment), cycles, quality == "optimum")


def life_factor_bending(treatment: str, cycles: float, quality: str) -> float:
    """Y_NT (ISO 6336-3:2006, Table 3): 3e6 < N_L ≤ 1e10 gives (3e6/N_L)^0.02."""
    return _life_factor(ynt_curve(treatment), cycles, quality == "optimum")


# ------------------------------------------------------------ ISO 1328-1:1995 tolerances of a grade
_D_LIMITS = (5, 20, 50, 125, 280, 560, 1000, 1600, 2500, 4000, 6000, 8000, 10000)  # reference diameter, mm
_M_LIMITS = (0.5, 2, 3.5, 6, 10, 16, 25, 40, 70)  # normal module, mm
_B_LIMITS = (4, 10, 20, 40, 80, 160, 250, 400, 650, 1000)  # face width, mm


def _range_mean(value: float, limits: Sequence[float]) -> float:
    """The geometric mean of the ISO 1328 range that holds ``value`` (clamped to the first/last range)."""
    for lo, hi in zip(limits, limits[1:], strict=False):
        if value <= hi:
            return math.sqrt(lo * hi)
    return math.sqrt(limits[-2] * limits[-1])


def _grade_value(class5_um: float, grade: int) -> float:
    """Scale a class-5 value by 2^((Q − 5)/2) and round as ISO 1328-1:1995 does (> 10 µm to 1 µm,
    5 … 10 µm to 0.5 µm, below to 0.1 µm)."""
    value = class5_um * 2.0 ** (0.5 * (grade - 5))
    if value > 10.0:
        return float(round(value))
    if value >= 5.0:
        return round(2.0 * value) / 2.0
    return round(value, 1)


def single_pitch_tolerance_um(reference_diameter_mm: float, normal_module_mm: float, grade: int) -> float:
    """f_pt = 0.3 (m + 0.4 √d) + 4 for class 5 (ISO 1328-1:1995), at the range means of d and m."""
    d, m = _range_mean(reference_diameter_mm, _D_LIMITS), _range_mean(normal_module_mm, _M_LIMITS)
    return _grade_value(0.3 * (m + 0.4 * math.sqrt(d)) + 4.0, grade)


def profile_form_tolerance_um(reference_diameter_mm: float, normal_module_mm: float, grade: int) -> float:
    """f_fα = 2.5 √m + 0.17 √d + 0.5 for class 5 (ISO 1328-1:1995)."""
    d, m = _range_mean(reference_diameter_mm, _D_LIMITS), _range_mean(normal_module_mm, _M_LIMITS)
    return _grade_value(2.5 * math.sqrt(m) + 0.17 * math.sqrt(d) + 0.5, grade)


def helix_slope_tolerance_um(reference_diameter_mm: float, face_width_mm: float, grade: int) -> float:
    """f_Hβ = 0.07 √d + 0.45 √b + 3 for class 5 (ISO 1328-1:1995)."""
    d, b = _range_mean(reference_diameter_mm, _D_LIMITS), _range_mean(face_width_mm, _B_LIMITS)
    return _grade_value(0.07 * math.sqrt(d) + 0.45 * math.sqrt(b) + 3.0, grade)


# ------------------------------------------------------------------ ISO 6336-1: running-in, K_v
def running_in_um(treatment: str, sigma_hlim: float, deviation_um: float, speed_m_s: float) -> float:
    """y_α of one member from a deviation (f_pb, or f_fα for y_f) (ISO 6336-1:2006, 8.3.5 table):
    St, V, GS, GGG: 160/σ_Hlim · f (≤ 12800/σ_Hlim for 5 < v ≤ 10, ≤ 6400/σ_Hlim above 10 m/s);
    GG: 0.275 f (≤ 22 and ≤ 11 µm); surface-hardened: 0.075 f (≤ 3 µm at any speed)."""
    if treatment in SURFACE_HARDENED:
        return min(0.075 * deviation_um, 3.0)
    if treatment == "grey_iron":
        y, cap = 0.275 * deviation_um, (math.inf if speed_m_s <= 5 else 22.0 if speed_m_s <= 10 else 11.0)
        return min(y, cap)
    y = 160.0 / sigma_hlim * deviation_um
    cap = math.inf if speed_m_s <= 5 else (12800.0 if speed_m_s <= 10 else 6400.0) / sigma_hlim
    return min(y, cap)


def dynamic_coefficients(eps_gamma: float) -> tuple[float, ...]:
    """C_v1 … C_v7 of ISO 6336-1:2006, 6.5.9 (Table 8) for a total contact ratio ε_γ."""
    if eps_gamma <= 2.0:
        cv2, cv3, cv4, cv6 = 0.34, 0.23, 0.90, 0.47
    else:
        cv2 = 0.57 / (eps_gamma - 0.3)
        cv3 = 0.096 / (eps_gamma - 1.56)
        # Table 8's C_v4 turns negative beyond eps_gamma = 11.4 (outside any real mesh; the table was fitted far
        # below it) and would take K_v in the main resonance range below 0: held at 0 there
        cv4 = max((0.57 - 0.05 * eps_gamma) / (eps_gamma - 1.44), 0.0)
        cv6 = 0.12 / (eps_gamma - 1.74)
    if eps_gamma <= 1.5:
        cv7 = 0.75
    elif eps_gamma <= 2.5:
        cv7 = 0.125 * math.sin(math.pi * (eps_gamma - 2.0)) + 0.875
    else:
        cv7 = 1.0
    return 0.32, cv2, cv3, cv4, 0.47, cv6, cv7


def dynamic_factor(ratio: float, lower_limit: float, eps_gamma: float, single_pair: float, line_load: float,
                   pitch_eff_um: float, profile_eff_um: float, tip_relief_um: float) -> float:
    """K_v of ISO 6336-1:2006, method B (6.5.4–6.5.9) from N = n1/n_E1 and its range.

    B_p = c′ f_pb,eff/(K_A F_t/b), B_f = c′ f_fα,eff/(K_A F_t/b), B_k = |1 − c′ C_a/(K_A F_t/b)|;
    subcritical (N ≤ N_S) K_v = N (C_v1 B_p + C_v2 B_f + C_v3 B_k) + 1; main resonance (N_S < N ≤ 1.15)
    K_v = C_v1 B_p + C_v2 B_f + C_v4 B_k + 1; supercritical (N ≥ 1.5) K_v = C_v5 B_p + C_v6 B_f + C_v7;
    intermediate: linear in N between the values at 1.15 and 1.5.
    """
    cv1, cv2, cv3, cv4, cv5, cv6, cv7 = dynamic_coefficients(eps_gamma)
    b_p = single_pair * max(pitch_eff_um, 0.0) / line_load
    b_f = single_pair * max(profile_eff_um, 0.0) / line_load
    b_k = abs(1.0 - single_pair * tip_relief_um / line_load)
    if ratio <= lower_limit:
        return ratio * (cv1 * b_p + cv2 * b_f + cv3 * b_k) + 1.0
    main = cv1 * b_p + cv2 * b_f + cv4 * b_k + 1.0
    if ratio <= 1.15:
        return main
    supercritical = cv5 * b_p + cv6 * b_f + cv7
    if ratio >= 1.5:
        return supercritical
    return supercritical + (main - supercritical) * (1.5 - ratio) / 0.35


# -------------------------------------------------------------- ISO 6336-1: K_Hβ, K_Fβ, K_Hα, K_Fα
def face_running_in_um(treatment: str, sigma_hlim: float, misalignment_um: float, speed_m_s: float) -> float:
    """y_β of ISO 6336-1:2006, 7.6 (table): Eh, IF, NT, NV 0.15 F_βx (≤ 6 µm); St, V, GS, GGG 320/σ_Hlim F_βx
    (≤ 25 600/σ_Hlim at 5 < v ≤ 10 m/s, ≤ 12 800/σ_Hlim above); GG 0.55 F_βx (≤ 45 µm, ≤ 22 µm)."""
    if treatment in SURFACE_HARDENED:
        return min(0.15 * misalignment_um, 6.0)
    if treatment == "grey_iron":
        cap = math.inf if speed_m_s <= 5 else 45.0 if speed_m_s <= 10 else 22.0
        return min(0.55 * misalignment_um, cap)
    cap = math.inf if speed_m_s <= 5 else (25600.0 if speed_m_s <= 10 else 12800.0) / sigma_hlim
    return min(320.0 / sigma_hlim * misalignment_um, cap)


def face_load_factor_estimate(mesh_beta: float, line_load_m: float, helix_slope_um: float, width_ratio: float,
                              running_in: tuple[tuple[str, float], tuple[str, float], float]) -> float:
    """K_Hβ, method C of ISO 6336-1:2006 (7.6) for a pinion centred between its bearings, without lead
    correction: F_βx = 1.33 f_sh + f_ma, f_sh = 0.023 F_m/b (b/d1)² µm, f_ma = f_Hβ; F_βx ≥ max(0.005 F_m/b,
    0.5 f_Hβ); F_βy = F_βx − y_β, y_β = (y_β1 + y_β2)/2 the mean of the two members (``running_in`` = (treatment,
    σ_Hlim) of each member and v, for ``face_running_in_um``; ISO's rule for a pinion and wheel of different
    materials, as for y_α); K_Hβ = 1 + c_γβ F_βy/(2 F_m/b), or √(2 c_γβ F_βy/(F_m/b)) above 2.
    ``line_load_m`` = F_m/b = F_t K_A K_v/b."""
    f_sh = 0.023 * line_load_m * width_ratio ** 2
    f_bx = max(1.33 * f_sh + helix_slope_um, 0.005 * line_load_m, 0.5 * helix_slope_um)
    (t1, h1), (t2, h2), speed = running_in
    y_b = 0.5 * (face_running_in_um(t1, h1, f_bx, speed) + face_running_in_um(t2, h2, f_bx, speed))
    f_by = max(f_bx - y_b, 0.0)
    k = 1.0 + mesh_beta * f_by / (2.0 * line_load_m)
    return k if k <= 2.0 else math.sqrt(2.0 * mesh_beta * f_by / line_load_m)


def face_load_factor_root(k_hbeta: float, face_width_mm: float, tooth_depth_mm: float) -> float:
    """K_Fβ = K_Hβ^N_F, N_F = (b/h)²/(1 + b/h + (b/h)²), b/h ≥ 3 (ISO 6336-1:2006, 7.7)."""
    bh = max(face_width_mm / tooth_depth_mm, 3.0)
    return k_hbeta ** (bh * bh / (1.0 + bh + bh * bh))


def transverse_load_factors(eps_alpha: float, eps_gamma: float, z_eps: float, mesh_alpha: float,
                            deviation_eff_um: float, line_load_h: float) -> tuple[float, float]:
    """K_Hα, K_Fα of ISO 6336-1:2006, 8.3.2 (method B), ``line_load_h`` = F_tH/b = F_t K_A K_v K_Hβ/b:
    K = ε_γ/2 (0.9 + 0.4 c_γα f_eff/(F_tH/b)) for ε_γ ≤ 2, else 0.9 + 0.4 √(2(ε_γ − 1)/ε_γ) c_γα f_eff/(F_tH/b);
    K_Hα in [1, ε_γ/(ε_α Z_ε²)], K_Fα in [1, ε_γ/(0.25 ε_α + 0.75)]."""
    term = mesh_alpha * max(deviation_eff_um, 0.0) / line_load_h
    if eps_gamma <= 2.0:
        k = 0.5 * eps_gamma * (0.9 + 0.4 * term)
    else:
        k = 0.9 + 0.4 * math.sqrt(2.0 * (eps_gamma - 1.0) / eps_gamma) * term
    k_h = max(min(k, eps_gamma / (eps_alpha * z_eps ** 2)), 1.0)  # the limits fall below 1 only for ε_α < 1
    k_f = max(min(k, eps_gamma / (0.25 * eps_alpha + 0.75)), 1.0)
    return k_h, k_f


# ------------------------------------------------------------------------------ ISO 6336-2
def zone_factor(base_helix_rad: float, transverse_rad: float, working_rad: float) -> float:
    """Z_H = √(2 cos β_b cos α_wt / (cos² α_t sin α_wt)) (ISO 6336-2:2006, 6.1)."""
    return math.sqrt(2.0 * math.cos(base_helix_rad) * math.cos(working_rad)
                     / (math.cos(transverse_rad) ** 2 * math.sin(working_rad)))


def elasticity_factor(e1: float, nu1: float, e2: float, nu2: float) -> float:
    """Z_E = √(1 / (π ((1 − ν1²)/E1 + (1 − ν2²)/E2))) (ISO 6336-2:2006, 7)."""
    return math.sqrt(1.0 / (math.pi * ((1.0 - nu1 ** 2) / e1 + (1.0 - nu2 ** 2) / e2)))


def contact_ratio_factor(eps_alpha: float, eps_beta: float) -> float:
    """Z_ε (ISO 6336-2:2006, 8): √((4 − ε_α)/3 (1 − ε_β) + ε_β/ε_α) for ε_β < 1, √(1/ε_α) for ε_β ≥ 1; beyond
    ε_α = 3 never below √(1/ε_α), the load shared equally by ε_α pairs (the standard's own value for ε_β ≥ 1).

    The floor acts only beyond ε_α = 3, where (4 − ε_α)/3 crosses 1/ε_α: ISO 6336-2's scope ends before that
    (ε_αn < 2.5, the ``contact_ratio_virtual`` warning), and the spur term falls to 0 at ε_α = 4 and below 0 after
    it (Z_ε 0.065 at ε_α 3.99, σ_H an eighth of the stress; a math domain error at 4). Up to ε_α = 3 every Z_ε is
    the standard's (between 1 and 3 the ε_β < 1 form, a weighted mean of (4 − ε_α)/3 and 1/ε_α, is at least 1/ε_α;
    below 1, a warned discontinuous mesh, 1/ε_α lies above it and the standard's value stands).
    """
    if eps_beta >= 1.0:
        return math.sqrt(1.0 / eps_alpha)
    value = (4.0 - eps_alpha) / 3.0 * (1.0 - eps_beta) + eps_beta / eps_alpha
    return math.sqrt(max(value, 1.0 / eps_alpha) if eps_alpha > 3.0 else value)


def helix_factor_pitting(helix_rad: float) -> float:
    """Z_β = 1/√cos β (ISO 6336-2:2006 with Technical Corrigendum 1:2008)."""
    return 1.0 / math.sqrt(math.cos(helix_rad))


def single_pair_factors(tips: tuple[float, float], bases: tuple[float, float], teeth: tuple[int, int],
                        working_rad: float, eps_alpha: float, eps_beta: float) -> tuple[float, float]:
    """Z_B (smaller wheel, index 1) and Z_D (larger) of ISO 6336-2:2006, 6.2, from M_1 and M_2:
    M_1 = tan α_wt / √((√(d_a1²/d_b1² − 1) − 2π/z1)(√(d_a2²/d_b2² − 1) − (ε_α − 1) 2π/z2)), M_2 likewise;
    spur: max(1, M); ε_β ≥ 1: 1; else M − ε_β (M − 1), at least 1."""
    roll = [math.sqrt((tips[i] / bases[i]) ** 2 - 1.0) for i in (0, 1)]
    out = []
    for i, j in ((0, 1), (1, 0)):
        radicand = (roll[i] - 2.0 * math.pi / teeth[i]) * (roll[j] - (eps_alpha - 1.0) * 2.0 * math.pi / teeth[j])
        if eps_beta >= 1.0 or radicand <= 0.0:  # no single-pair zone on this flank (ε_α ≤ 1: outside the method)
            out.append(1.0)
            continue
        m = math.tan(working_rad) / math.sqrt(radicand)
        out.append(max(1.0, m - eps_beta * (m - 1.0)))
    return out[0], out[1]


def _c_zl(sigma_hlim: float) -> float:
    """C_ZL of ISO 6336-2:2006, 11: 0.83 below 850, σ_Hlim/4375 + 0.6357 up to 1200, 0.91 above (MPa)."""
    return 0.83 if sigma_hlim < 850 else (sigma_hlim / 4375.0 + 0.6357 if sigma_hlim <= 1200 else 0.91)


def lubricant_factor(sigma_hlim: float, viscosity_40: float) -> float:
    """Z_L = C_ZL + 4 (1 − C_ZL)/(1.2 + 134/ν40)² (ISO 6336-2:2006, 11), σ_Hlim the lower of the pair."""
    c = _c_zl(sigma_hlim)
    return c + 4.0 * (1.0 - c) / (1.2 + 134.0 / viscosity_40) ** 2


def velocity_factor(sigma_hlim: float, speed_m_s: float) -> float:
    """Z_V = C_ZV + 2 (1 − C_ZV)/√(0.8 + 32/v), C_ZV = C_ZL + 0.02 (ISO 6336-2:2006, 11)."""
    c = _c_zl(sigma_hlim) + 0.02
    return c + 2.0 * (1.0 - c) / math.sqrt(0.8 + 32.0 / speed_m_s)


def roughness_factor(sigma_hlim: float, rz_mean_um: float, rho_red_mm: float) -> float:
    """Z_R = (3/R_z10)^C_ZR, R_z10 = R_z (10/ρ_red)^(1/3), C_ZR = 0.15 below 850, 0.32 − 0.0002 σ_Hlim up to
    1200, 0.08 above (ISO 6336-2:2006, 11)."""
    c = 0.15 if sigma_hlim < 850 else (0.32 - 0.0002 * sigma_hlim if sigma_hlim <= 1200 else 0.08)
    return (3.0 / (rz_mean_um * (10.0 / rho_red_mm) ** (1.0 / 3.0))) ** c


def work_hardening_factor(soft_hardness_hb: float | None) -> float:
    """Z_W = 1.2 − (HB − 130)/1700 of a through-hardened wheel run with a surface-hardened pinion, HB clamped to
    130 … 470 (ISO 6336-2:2006, 13); 1 when the wheel's hardness is not given."""
    if soft_hardness_hb is None:
        return 1.0
    return 1.2 - (min(max(soft_hardness_hb, 130.0), 470.0) - 130.0) / 1700.0
