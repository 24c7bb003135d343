"""The tooth-root factors of ISO 6336-3:2006 (method B), one formula per function (docs/iso6336.md).

Lengths in mm, stresses in N/mm². Pure ``math``, like ``rating_factors`` (ISO 6336-1, -2, -5).
"""

from __future__ import annotations

import math

from gearcli.design.rating_factors import SURFACE_HARDENED


def _fillet_angle(g: float, z_n: float, h: float, iterations: int) -> float:
    """θ of ISO 6336-3 method B: the fixed point of θ = 2G/z_n tan θ − H, from π/6 (to 1e-13)."""
    theta = math.pi / 6.0
    for _ in range(iterations):
        new = 2.0 * g / z_n * math.tan(theta) - h
        if abs(new - theta) < 1e-13:
            return new
        theta = new
    return theta


def _bracketed_fillet_angle(g: float, z_n: float, h: float, fallback: float) -> float:
    """The root of 2G/z_n tan θ − H − θ = 0 in (0, π/2) nearest π/6, by bisection, where the fixed-point iteration
    of ISO 6336-3 diverges (the same equation, solved another way); ``fallback`` when the interval holds none."""
    def f(t: float) -> float:
        return 2.0 * g / z_n * math.tan(t) - h - t

    grid = [1e-6 + (0.5 * math.pi - 2e-6) * i / 400 for i in range(401)]
    brackets = [(a, b) for a, b in zip(grid, grid[1:], strict=False) if f(a) * f(b) <= 0.0]
    if not brackets:
        return fallback
    a, b = min(brackets, key=lambda ab: abs(0.5 * (ab[0] + ab[1]) - math.pi / 6.0))
    for _ in range(200):
        mid = 0.5 * (a + b)
        if f(a) * f(mid) <= 0.0:
            b = mid
        else:
            a = mid
    return 0.5 * (a + b)


FILLET_ANGLE_TOLERANCE = 1e-9  # rad: θ's fixed-point residual above which method B found no 30° tangent
VIRTUAL_TOOTH_COUNTS = ("iso", "cos3")  # [rating] virtual_tooth_count: z_n in the load angle γ_e


def load_angle_teeth(teeth: float, helix_rad: float, base_helix_rad: float, choice: str = "iso") -> float:
    """The virtual tooth count γ_e divides by: ISO 6336-3's z_n = z/(cos² β_b cos β) (``"iso"``), or the classical
    approximation z/cos³ β (``"cos3"``, which some commercial tools use there; docs/iso6336.md, "The virtual tooth
    count in the load angle"). Signed as ``teeth`` (an internal gear's z_n < 0)."""
    if choice == "cos3":
        return teeth / math.cos(helix_rad) ** 3
    if choice != "iso":
        raise ValueError(f"virtual_tooth_count {choice!r}: one of {VIRTUAL_TOOTH_COUNTS}")
    return teeth / (math.cos(base_helix_rad) ** 2 * math.cos(helix_rad))


def tooth_form(teeth: int, normal_module: float, normal_pressure_rad: float, helix_rad: float,
               base_helix_rad: float, profile_shift: float, tip_diameter: float, reference_diameter: float,
               eps_alpha: float, rack: tuple[float, float], *, virtual_tooth_count: str = "iso") -> dict[str, float]:
    """Y_F, Y_S and the root geometry by method B (ISO 6336-3:2006, 6.2 and 7.2) for an external gear cut by
    the basic rack (h_fP*, ρ_fP*) without protuberance: the 30° tangent to the root fillet, θ by iteration.
    ``virtual_tooth_count``: the z_n of the load angle γ_e (:func:`load_angle_teeth`; every other z_n is ISO's).

    Returns ``Y_F``, ``Y_S``, ``s_Fn``, ``h_Fe``, ``rho_F``, ``alpha_Fen`` (rad), ``q_s``, ``d_en`` and
    ``theta_residual`` (rad): θ's fixed-point residual, above ``FILLET_ANGLE_TOLERANCE`` where the iteration finds
    no 30° tangent (a small, far-shifted tooth at a low pressure angle): then no figure here is ISO's.
    """
    m, an = normal_module, normal_pressure_rad
    h_fp, rho_fp = rack[0] * m, rack[1] * m
    z_n = teeth / (math.cos(base_helix_rad) ** 2 * math.cos(helix_rad))
    e = math.pi / 4.0 * m - h_fp * math.tan(an) - (1.0 - math.sin(an)) * rho_fp / math.cos(an)
    g = rho_fp / m - h_fp / m + profile_shift
    h = 2.0 / z_n * (math.pi / 2.0 - e / m) - math.pi / 3.0
    theta = _fillet_angle(g, z_n, h, 1000)  # linear convergence, slow near the method's edge
    residual = 2.0 * g / z_n * math.tan(theta) - h - theta
    if abs(residual) > FILLET_ANGLE_TOLERANCE:  # the iteration diverges (|2G/z_n sec² θ| > 1): bracket the root
        theta = _bracketed_fillet_angle(g, z_n, h, theta)
        residual = 2.0 * g / z_n * math.tan(theta) - h - theta
    s_fn = m * (z_n * math.sin(math.pi / 3.0 - theta) + math.sqrt(3.0) * (g / math.cos(theta) - rho_fp / m))
    rho_f = m * (rho_fp / m + 2.0 * g * g / (math.cos(theta) * (z_n * math.cos(theta) ** 2 - 2.0 * g)))
    d_n = m * z_n
    d_bn = d_n * math.cos(an)
    d_an = d_n + tip_diameter - reference_diameter
    eps_an = eps_alpha / math.cos(base_helix_rad) ** 2
    p = math.pi * reference_diameter * math.cos(helix_rad) * math.cos(an) / teeth
    d_en = 2.0 * math.sqrt((math.sqrt((d_an / 2.0) ** 2 - (d_bn / 2.0) ** 2) - p * (eps_an - 1.0)) ** 2
                           + (d_bn / 2.0) ** 2)
    alpha_en = math.acos(d_bn / d_en)
    z_gamma = load_angle_teeth(teeth, helix_rad, base_helix_rad, virtual_tooth_count)
    gamma_e = (0.5 * math.pi + 2.0 * profile_shift * math.tan(an)) / z_gamma + (math.tan(an) - an) \
        - (math.tan(alpha_en) - alpha_en)
    alpha_fen = alpha_en - gamma_e
    h_fe = 0.5 * m * ((math.cos(gamma_e) - math.sin(gamma_e) * math.tan(alpha_fen)) * d_en / m
                      - z_n * math.cos(math.pi / 3.0 - theta) - g / math.cos(theta) + rho_fp / m)
    y_f = 6.0 * (h_fe / m) * math.cos(alpha_fen) / ((s_fn / m) ** 2 * math.cos(an))
    ell = s_fn / h_fe if h_fe != 0.0 else math.nan
    # a sharp root (ρ_F = 0: a rack without tip radius whose corner rolls on the reference line, G = 0): no notch
    # parameter, as on the internal gear below
    q_s = s_fn / (2.0 * rho_f) if rho_f > 0.0 else math.inf
    # no section (s_Fn, h_Fe or ρ_F ≤ 0, the caller's exit 2): Y_S is not defined there (a complex power)
    y_s = (1.2 + 0.13 * ell) * q_s ** (1.0 / (1.21 + 2.3 / ell)) if 0.0 < q_s < math.inf and ell > 0.0 else math.nan
    return {"Y_F": y_f, "Y_S": y_s, "s_Fn": s_fn, "h_Fe": h_fe, "rho_F": rho_f, "alpha_Fen": alpha_fen,
            "q_s": q_s, "d_en": d_en, "theta_residual": residual}


def helix_factor_bending(overlap_ratio: float, helix_deg: float) -> float:
    """Y_β = 1 − ε_β β/120° with ε_β ≤ 1 and β ≤ 30° (ISO 6336-3:2006, 9)."""
    return 1.0 - min(overlap_ratio, 1.0) * min(helix_deg, 30.0) / 120.0


RIM_RANGE = (0.5, 1.2)  # s_R/h_t where an external gear's Y_B formula holds, and from where Y_B = 1


def rim_factor(rim_thickness_mm: float | None, tooth_depth_mm: float) -> float:
    """Y_B = 1 for s_R/h_t ≥ 1.2 (or a solid blank), 1.6 ln(2.242 h_t/s_R) for 0.5 < s_R/h_t < 1.2 (ISO 6336-3:2006,
    10; below 0.5 the standard does not apply and the 0.5 value is used)."""
    if rim_thickness_mm is None:
        return 1.0
    ratio = max(rim_thickness_mm / tooth_depth_mm, RIM_RANGE[0])
    return 1.0 if ratio >= RIM_RANGE[1] else 1.6 * math.log(2.242 / ratio)


def deep_tooth_factor(eps_alpha: float, base_helix_rad: float, grade: int) -> float:
    """Y_DT (ISO 6336-3:2006, 11): with ε_αn = ε_α/cos² β_b, 1 unless grade ≤ 4 and ε_αn > 2.05, then
    −0.666 ε_αn + 2.366 up to 2.5 and 0.7 above."""
    eps_an = eps_alpha / math.cos(base_helix_rad) ** 2
    if grade > 4 or eps_an <= 2.05:
        return 1.0
    return -0.666 * eps_an + 2.366 if eps_an <= 2.5 else 0.7


# slip-layer thickness ρ′ (mm) of ISO 6336-3:2006, 12.3 (Table 5); where it depends on the yield strength,
# the value of a typical grade is taken (docs/iso6336.md says which)
_SLIP_LAYER_MM = {"case_carburized": 0.0030, "induction_hardened": 0.0030, "flame_hardened": 0.0030,
                  "nitrided": 0.1005, "nitrocarburized": 0.1005, "through_hardened": 0.0194,
                  "cast_steel": 0.0194, "nodular_iron": 0.0194, "structural_steel": 0.0445,
                  "grey_iron": 0.3095}


def relative_notch_sensitivity(treatment: str, q_s: float) -> float:
    """Y_δrelT = (1 + √(ρ′ χ*)) / (1 + √(ρ′ χ*_T)), χ* = (1 + 2 q_s)/5, χ*_T = 1.2 (ISO 6336-3:2006, 12.3)."""
    rho = _SLIP_LAYER_MM[treatment]
    return (1.0 + math.sqrt(rho * (1.0 + 2.0 * q_s) / 5.0)) / (1.0 + math.sqrt(rho * 1.2))


def relative_surface_factor(treatment: str, rz_um: float) -> float:
    """Y_RrelT (ISO 6336-3:2006, 13.3), 1 ≤ R_z ≤ 40 µm: 1.674 − 0.529 (R_z + 1)^0.1 (V, GGG, Eh, IF),
    5.306 − 4.203 (R_z + 1)^0.01 (St), 4.299 − 3.259 (R_z + 1)^0.0058 (GG, NT, NV); below 1 µm: 1.120, 1.070, 1.025."""
    if treatment == "structural_steel":
        a, b, p, smooth = 5.306, 4.203, 0.01, 1.070
    elif treatment in ("grey_iron", "nitrided", "nitrocarburized"):
        a, b, p, smooth = 4.299, 3.259, 0.0058, 1.025
    else:
        a, b, p, smooth = 1.674, 0.529, 0.1, 1.120
    if rz_um < 1.0:
        return smooth
    return a - b * (min(rz_um, 40.0) + 1.0) ** p


def size_factor_bending(treatment: str, normal_module_mm: float) -> float:
    """Y_X (ISO 6336-3:2006, 14, Table 6): 1 up to m_n = 5; St, V, GS, GGG (perl.): 1.03 − 0.006 m_n (≥ 0.85);
    Eh, IF, NT, NV: 1.05 − 0.01 m_n (≥ 0.8); GG, GGG (ferr.): 1.075 − 0.015 m_n (≥ 0.7)."""
    m = normal_module_mm
    if m <= 5.0:
        return 1.0
    if treatment in SURFACE_HARDENED:
        return max(1.05 - 0.01 * m, 0.8)
    if treatment == "grey_iron":
        return max(1.075 - 0.015 * m, 0.7)
    return max(1.03 - 0.006 * m, 0.85)


IDLER_MEAN_STRESS_FACTOR = 0.7  # Y_M of an idler's root (alternating bending), ISO 6336-3:2006, 5.3 / ISO 6336-5


def internal_tooth_form(teeth: int, normal_module: float, normal_pressure_rad: float, helix_rad: float,
                        base_helix_rad: float, profile_shift: float, tip_diameter: float, reference_diameter: float,
                        eps_alpha: float, rack: tuple[float, float],
                        cutter_teeth: float | None = None, *, virtual_tooth_count: str = "iso") -> dict[str, float]:
    """Y_F, Y_S and the root geometry of an internal gear by method B (ISO 6336-3:2006, 6.2 and 7.2).

    ``teeth``, ``tip_diameter`` and ``reference_diameter`` are given positive, ``profile_shift`` with the sign of
    ISO 21771 (a negative x moves the ring's tip outwards). The external gear's equations hold with the signed
    virtual number of teeth z_n < 0 and the critical section at the 60° tangent to the root fillet
    (H = 2/z_n (π/2 − E/m_n) − π/6; s_Fn = m_n [z_n sin(π/6 − θ) + (G/cos θ − ρ_fP/m_n)]); the load acts at the
    outer point of single tooth contact of the ring, whose roll length exceeds the tip's by p_bn (ε_αn − 1).
    The fillet radius is the one a pinion-type cutter of ``cutter_teeth`` z_0 generates, z_0 in place of z_n in
    ρ_F = ρ_fP + 2 G² m_n/(cos θ (z_0 cos² θ − 2 G)); without a cutter the substitute rack's (z_0 → ∞): ρ_F = ρ_fP.
    ``virtual_tooth_count``: the z_n of the load angle γ_e, as :func:`tooth_form`'s.

    Returns ``Y_F``, ``Y_S``, ``s_Fn``, ``h_Fe``, ``rho_F``, ``alpha_Fen`` (rad), ``q_s``, ``d_en`` and ``d_sFn``
    (positive, mm).
    """
    m, an = normal_module, normal_pressure_rad
    h_fp, rho_fp = rack[0] * m, rack[1] * m
    virtual = math.cos(base_helix_rad) ** 2 * math.cos(helix_rad)
    z_n = -teeth / virtual
    e = math.pi / 4.0 * m - h_fp * math.tan(an) - (1.0 - math.sin(an)) * rho_fp / math.cos(an)
    g = rho_fp / m - h_fp / m + profile_shift
    h = 2.0 / z_n * (math.pi / 2.0 - e / m) - math.pi / 6.0
    theta = _fillet_angle(g, z_n, h, 200)
    lever = g / math.cos(theta) - rho_fp / m
    s_fn = m * (z_n * math.sin(math.pi / 6.0 - theta) + lever)
    d_sfn = -m * (z_n * math.cos(math.pi / 6.0 - theta) + math.sqrt(3.0) * lever)
    rho_f = rho_fp
    if cutter_teeth is not None:
        z_0 = cutter_teeth / virtual
        rho_f = m * (rho_fp / m + 2.0 * g * g / (math.cos(theta) * (z_0 * math.cos(theta) ** 2 - 2.0 * g)))
    d_n = m * teeth / virtual  # magnitudes from here on
    d_bn = d_n * math.cos(an)
    d_an = d_n - (reference_diameter - tip_diameter)
    eps_an = eps_alpha / math.cos(base_helix_rad) ** 2
    p = math.pi * reference_diameter * math.cos(helix_rad) * math.cos(an) / teeth
    d_en = 2.0 * math.hypot(math.sqrt(max((d_an / 2.0) ** 2 - (d_bn / 2.0) ** 2, 0.0)) + p * (eps_an - 1.0),
                            d_bn / 2.0)
    alpha_en = math.acos(d_bn / d_en)
    z_gamma = load_angle_teeth(-teeth, helix_rad, base_helix_rad, virtual_tooth_count)
    gamma_e = (0.5 * math.pi + 2.0 * profile_shift * math.tan(an)) / z_gamma + (math.tan(an) - an) \
        - (math.tan(alpha_en) - alpha_en)  # negative: the ring's tooth thickens towards its root
    alpha_fen = alpha_en - gamma_e
    h_fe = 0.5 * (d_sfn - (math.cos(gamma_e) - math.sin(gamma_e) * math.tan(alpha_fen)) * d_en)
    y_f = 6.0 * (h_fe / m) * math.cos(alpha_fen) / ((s_fn / m) ** 2 * math.cos(an))
    ell = s_fn / h_fe if h_fe != 0.0 else math.nan
    q_s = s_fn / (2.0 * rho_f) if rho_f > 0.0 else math.inf  # a sharp root (ρ_F = 0): no notch parameter
    # Y_S only where the root has a section, a fillet and a lever (the caller refuses the rest, naming the key)
    y_s = (1.2 + 0.13 * ell) * q_s ** (1.0 / (1.21 + 2.3 / ell)) if 0.0 < q_s < math.inf and ell > 0.0 else math.nan
    return {"Y_F": y_f, "Y_S": y_s, "s_Fn": s_fn, "h_Fe": h_fe, "rho_F": rho_f, "alpha_Fen": alpha_fen,
            "q_s": q_s, "d_en": d_en, "d_sFn": d_sfn}


INTERNAL_RIM_RANGE = (1.75, 3.5)  # s_R/m_n where the internal gear's Y_B formula holds, and from where Y_B = 1


def internal_rim_factor(rim_thickness_mm: float | None, normal_module_mm: float) -> float:
    """Y_B of an internal gear (ISO 6336-3:2006, 10): 1 for s_R/m_n ≥ 3.5 (or no rim given),
    1.15 ln(8.324 m_n/s_R) for 1.75 < s_R/m_n < 3.5 (below 1.75 the standard does not apply and the 1.75 value
    is used). The internal gear's rim is measured in normal modules, not in tooth depths as an external gear's
    (s_R/h_t): before 2026-12-01 gearcli took s_R/h_t here, 2.25x too thin a rim for the ISO 53 rack (the NREL 5 MW
    ring, s_R = 157.5 mm = 3.5 m_n, Y_B 1.79 for 1.00)."""
    if rim_thickness_mm is None:
        return 1.0
    ratio = max(rim_thickness_mm / normal_module_mm, INTERNAL_RIM_RANGE[0])
    return 1.0 if ratio >= INTERNAL_RIM_RANGE[1] else 1.15 * math.log(8.324 / ratio)
