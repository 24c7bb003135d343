"""Tooth-thickness, tip-diameter and centre-distance allowances of an external pair (ISO 21771:2007, clauses on
tooth thickness and backlash; docs/iso6336.md, "Tooth-thickness allowances").

Every pair of limits is [upper, lower] as the allowances are written: A_sne ≥ A_sni (tooth thickness, normal
section, at the reference circle), A_dae ≥ A_dai (tip diameter), A_ae ≥ A_ai (working centre distance). The
"e" (upper) side of a pair is the tight mesh (thickest teeth, largest tips, smallest centre distance), the "i"
(lower) side the loose one. Angles in radians, lengths in mm. Pure ``math``.
"""

from __future__ import annotations

import math

from gearcli.core.records import record
from gearcli.design.geometry import PairGeometry, involute, transverse_contact_ratio, working_pressure_angle_rad

Pair = tuple[float, float]  # [upper, lower]
NO_ALLOWANCE: Pair = (0.0, 0.0)


def generating_profile_shift(profile_shift: float, thickness_allowance_mm: float, normal_module_mm: float,
                             normal_pressure_rad: float) -> float:
    """x_E = x + A_sn / (2 m_n tan α_n): the tool's position that cuts the tooth thinner by A_sn (normal
    section) than the nominal tooth of x (ISO 21771, generating profile shift coefficient)."""
    return profile_shift + thickness_allowance_mm / (2.0 * normal_module_mm * math.tan(normal_pressure_rad))


def manufactured_root_diameter_mm(pitch_diameter: float, normal_module_mm: float, generating_shift: float,
                                  dedendum_factor: float) -> float:
    """d_f = d + 2 (x_E m_n − h_fP): the root the basic rack (tool addendum h_fP = h_fP* m_n) cuts at x_E."""
    return pitch_diameter + 2.0 * normal_module_mm * (generating_shift - dedendum_factor)


def manufactured_tooth_depth_mm(tip_diameter: float, tip_allowance: list[float] | None, roots: Pair) -> float:
    """The deepest tooth cut: (d_a + A_dae − d_f,i)/2, the upper tip over the root of the lower thickness limit."""
    return 0.5 * (tip_diameter + (tip_allowance[0] if tip_allowance else 0.0) - roots[1])


def backlash_free_pressure_angle_rad(geo: PairGeometry, teeth: tuple[int, int], generating_shifts: Pair) -> float:
    """α_wt of the backlash-free mesh of the teeth cut at x_E1, x_E2: inv α = inv α_t + 2 tan α_n Σx_E / Σz."""
    return working_pressure_angle_rad(geo.transverse_pressure_rad, geo.normal_pressure_rad,
                                      generating_shifts[0] + generating_shifts[1], teeth[0] + teeth[1])


def reference_center_distance_mm(geo: PairGeometry) -> float:
    return 0.5 * (geo.pitch_diameter_mm[0] + geo.pitch_diameter_mm[1])


def pressure_angle_at_rad(geo: PairGeometry, center_distance: float) -> float:
    """The transverse working pressure angle at centre distance a': a cos α_t = a' cos α'."""
    return math.acos(reference_center_distance_mm(geo) * math.cos(geo.transverse_pressure_rad) / center_distance)


def circumferential_backlash_mm(geo: PairGeometry, teeth: tuple[int, int], generating_shifts: Pair,
                                center_distance: float) -> float:
    """j_t on the working pitch circle at centre distance a' of teeth cut at x_E1, x_E2: the pitch there less both
    tooth thicknesses, j_t = m_t cos α_t / cos α' · (z1 + z2) (inv α' − inv α_wE) (ISO 21771's zero-backlash
    condition with the thicknesses of x_E). Negative: the teeth jam."""
    alpha = pressure_angle_at_rad(geo, center_distance)
    alpha_free = backlash_free_pressure_angle_rad(geo, teeth, generating_shifts)
    return (geo.transverse_module_mm * math.cos(geo.transverse_pressure_rad) / math.cos(alpha)
            * (teeth[0] + teeth[1]) * (involute(alpha) - involute(alpha_free)))


def normal_backlash_mm(geo: PairGeometry, circumferential_mm: float, center_distance: float) -> float:
    """j_n = j_t cos α' cos β_b: the shortest distance between the idle flanks (along the line of action, in the
    normal plane) at centre distance a'."""
    return circumferential_mm * math.cos(pressure_angle_at_rad(geo, center_distance)) * math.cos(geo.base_helix_rad)


def contact_ratio_at(geo: PairGeometry, tips: Pair, center_distance: float) -> float:
    """ε_α with tip diameters ``tips`` at centre distance a' (the tooth thickness does not move the path of
    contact: it sets which flank pair touches, not where)."""
    alpha = pressure_angle_at_rad(geo, center_distance)
    return transverse_contact_ratio(tips[0], geo.base_diameter_mm[0], tips[1], geo.base_diameter_mm[1],
                                    center_distance, alpha, geo.transverse_base_pitch_mm)


@record
class PairAllowances:
    """What the allowances of one pair give; per member tuples are (pinion, gear), every pair [upper, lower]."""

    generating_profile_shift: tuple[Pair, Pair]  # [x_E,e, x_E,i]
    manufactured_root_diameter_mm: tuple[Pair, Pair]  # [d_f,e, d_f,i]
    backlash_free_center_distance_mm: Pair  # a of zero backlash, thickest [e] and thinnest [i] teeth
    backlash_circumferential_mm: Pair  # [max, min]
    backlash_normal_mm: Pair  # [max, min]
    contact_ratio_transverse_with_allowances: tuple[float, float, float]  # [e, m, i]


class AllowanceInfeasible(ValueError):
    """Allowances that leave no mesh. ``part`` ("pinion", "gear", or None for the stage) and ``field`` name the
    design-file key to blame."""

    def __init__(self, message: str, part: str | None, field: str):
        super().__init__(message)
        self.message, self.part, self.field = message, part, field


PARTS = ("pinion", "gear")


def _require_involute_limits(geo: PairGeometry, teeth: tuple[int, int], shifts: Pair,
                             thickness: tuple[Pair, Pair], tips: tuple[Pair, Pair], center: Pair) -> None:
    """Each limit must leave an involute mesh: the smallest centre distance above r_b1 + r_b2 (else no line of
    action), every lower tip above its base circle, and the thinnest teeth a backlash-free mesh (inv α_wE > 0)."""
    base_sum = reference_center_distance_mm(geo) * math.cos(geo.transverse_pressure_rad)  # (d_b1 + d_b2)/2
    tight = geo.center_distance_mm + center[1]
    if tight <= base_sum:
        raise AllowanceInfeasible(f"the smallest centre distance a_w + A_ai = {tight:.4g} mm is not above (d_b1 + "
                                  f"d_b2)/2 = {base_sum:.4g} mm: no line of action is left", None,
                                  "center_distance_allowance_mm")
    for i, part in enumerate(PARTS):
        tip, base = geo.tip_diameter_mm[i] + tips[i][1], geo.base_diameter_mm[i]
        if tip <= base:
            raise AllowanceInfeasible(f"the lower tip diameter d_a + A_dai = {tip:.4g} mm is not above the base "
                                      f"circle d_b = {base:.4g} mm: no involute flank is left", part,
                                      "tip_diameter_allowance_mm")
    m_n, a_n = geo.normal_module_mm, geo.normal_pressure_rad
    thin = sum(generating_profile_shift(shifts[i], thickness[i][1], m_n, a_n) for i in (0, 1))
    try:
        working_pressure_angle_rad(geo.transverse_pressure_rad, a_n, thin, teeth[0] + teeth[1])
    except ValueError:
        part = PARTS[0] if thickness[0][1] <= thickness[1][1] else PARTS[1]
        raise AllowanceInfeasible(f"the lower tooth-thickness allowances leave x_E1 + x_E2 = {thin:.3f}, too "
                                  f"negative for z1 + z2 = {teeth[0] + teeth[1]}: the thinned teeth have no "
                                  "backlash-free mesh (inv α_wE ≤ 0); check their magnitudes against the module",
                                  part, "tooth_thickness_allowance_mm") from None


def _require_roots(geo: PairGeometry, tips: tuple[Pair, Pair], roots: tuple[Pair, Pair]) -> None:
    """Every manufactured root above 0 and below the lower tip: the thickest tooth must keep some depth."""
    for i, part in enumerate(PARTS):
        lowest, highest, tip = min(roots[i]), max(roots[i]), geo.tip_diameter_mm[i] + tips[i][1]
        if lowest <= 0.0:
            raise AllowanceInfeasible(f"the tooth thickness allowance leaves no root: manufactured d_f = "
                                      f"{lowest:.4g} mm ≤ 0", part, "tooth_thickness_allowance_mm")
        if highest >= tip:
            raise AllowanceInfeasible(f"the upper tooth-thickness allowance cuts the root at d_f = {highest:.4g} mm, "
                                      f"not below the lower tip d_a + A_dai = {tip:.4g} mm: no tooth depth is left",
                                      part, "tooth_thickness_allowance_mm")


def _require_contact(geo: PairGeometry, tips: tuple[Pair, Pair], center: Pair, eps: tuple[float, ...]) -> None:
    """ε_α ≤ 0 at a limit: the tips do not reach the line of action there, the teeth lose contact. Blamed on the
    centre distance when the nominal tips lose contact at its largest value, else on the lower tip allowance."""
    if min(eps) > 0.0:
        return
    loose = geo.center_distance_mm + center[0]
    if center != NO_ALLOWANCE and contact_ratio_at(geo, geo.tip_diameter_mm, loose) <= 0.0:
        part, field = None, "center_distance_allowance_mm"
    else:
        part, field = PARTS[0] if tips[0][1] <= tips[1][1] else PARTS[1], "tip_diameter_allowance_mm"
    raise AllowanceInfeasible(f"the contact ratio with allowances ε_α = {min(eps):.3f} ≤ 0: at the lower tips and "
                              f"the largest centre distance a_w + A_ae = {loose:.4g} mm the tips do not reach the "
                              "line of action, the teeth lose contact", part, field)


def pair_allowances(geo: PairGeometry, teeth: tuple[int, int], shifts: Pair, thickness: tuple[Pair, Pair],
                    tips: tuple[Pair, Pair], center: Pair, dedendum_factor: float) -> PairAllowances:
    """Generating shifts, manufactured roots, backlash [max, min] and ε_α [e, m, i] of one external pair. Limits
    that leave no mesh raise ``AllowanceInfeasible`` naming the key."""
    _require_involute_limits(geo, teeth, shifts, thickness, tips, center)
    m_n, a_n = geo.normal_module_mm, geo.normal_pressure_rad
    x_e = tuple(tuple(generating_profile_shift(shifts[i], a, m_n, a_n) for a in thickness[i]) for i in (0, 1))
    d_f = tuple(tuple(manufactured_root_diameter_mm(geo.pitch_diameter_mm[i], m_n, x, dedendum_factor)
                      for x in x_e[i]) for i in (0, 1))
    _require_roots(geo, tips, d_f)  # type: ignore[arg-type]
    thick, thin = (x_e[0][0], x_e[1][0]), (x_e[0][1], x_e[1][1])
    a_w = geo.center_distance_mm
    a_free = tuple(reference_center_distance_mm(geo) * math.cos(geo.transverse_pressure_rad)
                   / math.cos(backlash_free_pressure_angle_rad(geo, teeth, xs)) for xs in (thick, thin))
    loose, tight = a_w + center[0], a_w + center[1]
    j_max = circumferential_backlash_mm(geo, teeth, thin, loose)
    j_min = circumferential_backlash_mm(geo, teeth, thick, tight)
    d_a = geo.tip_diameter_mm
    mean = (0.5 * (tips[0][0] + tips[0][1]), 0.5 * (tips[1][0] + tips[1][1]))
    eps = (contact_ratio_at(geo, (d_a[0] + tips[0][0], d_a[1] + tips[1][0]), tight),
           contact_ratio_at(geo, (d_a[0] + mean[0], d_a[1] + mean[1]), a_w + 0.5 * (center[0] + center[1])),
           contact_ratio_at(geo, (d_a[0] + tips[0][1], d_a[1] + tips[1][1]), loose))
    _require_contact(geo, tips, center, eps)
    return PairAllowances(
        generating_profile_shift=(x_e[0], x_e[1]),  # type: ignore[arg-type]
        manufactured_root_diameter_mm=(d_f[0], d_f[1]),  # type: ignore[arg-type]
        backlash_free_center_distance_mm=(a_free[0], a_free[1]),
        backlash_circumferential_mm=(j_max, j_min),
        backlash_normal_mm=(normal_backlash_mm(geo, j_max, loose), normal_backlash_mm(geo, j_min, tight)),
        contact_ratio_transverse_with_allowances=eps,
    )
