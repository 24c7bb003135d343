"""Cylindrical involute gear geometry, ISO 21771 notation (docs/physics.md, "Design calculations").

Angles are in radians, lengths in mm (the unit of the design file's keys), every name says which.
Each function is one formula of ISO 21771:2007; ``pair_geometry`` strings them together for one
external gear pair and refuses geometry that cannot mesh (``InfeasibleGeometry``).

Conventions where the standard leaves a choice:

- The basic rack (ISO 53) is given per stage as multiples of m_n: addendum h_aP*, dedendum h_fP*,
  root radius ρ_fP* (default profile A: 1.0, 1.25, 0.38).
- Centre distance is the working one, a_w, from the sum of profile shifts (no backlash allowance).
- Tips are shortened by the tip alteration k m_n = a_w − a − (x1 + x2) m_n (ISO 21771, k ≤ 0), so that
  the bottom clearance at a_w stays the rack's h_fP* − h_aP*: d_a = d + 2 m_n (h_aP* + x + k). k = 0
  exactly when x1 + x2 = 0.
"""

from __future__ import annotations

import math

from gearcli.core.records import record

HALF_PI = 0.5 * math.pi


class InfeasibleGeometry(ValueError):
    """A pair that cannot mesh. ``part`` ("pinion", "gear" or None) and ``field`` name the key to blame."""

    def __init__(self, message: str, part: str | None = None, field: str | None = None):
        super().__init__(message)
        self.message = message
        self.part = part
        self.field = field


# --------------------------------------------------------------------------------------- involute
def involute(alpha_rad: float) -> float:
    """inv α = tan α − α (ISO 21771, 4.3.2)."""
    return math.tan(alpha_rad) - alpha_rad


#: below this angle inv α is summed from its series (tan α − α cancels there: 1e-12 relative at 0.01 rad)
_SERIES_BELOW_RAD = 0.02
_INV_SERIES = (1.0 / 3.0, 2.0 / 15.0, 17.0 / 315.0, 62.0 / 2835.0, 1382.0 / 155925.0)  # α³, α⁵, ..., α¹¹


def _involute_accurate(alpha_rad: float) -> float:
    """inv α to full relative precision: the Taylor series of tan α − α below 0.02 rad (next term < 1e-19
    relative), tan α − α above."""
    if alpha_rad >= _SERIES_BELOW_RAD:
        return involute(alpha_rad)
    a2 = alpha_rad * alpha_rad
    return alpha_rad * a2 * sum(c * a2 ** j for j, c in enumerate(_INV_SERIES))


def inverse_involute(value: float, *, tol_rad: float = 1e-15, max_iter: int = 60) -> float:
    """The angle α in (0, π/2) with inv α = ``value`` > 0, by Newton's method.

    inv is convex and increasing on (0, π/2) with d(inv)/dα = tan² α. The start α0 = (3 v)^(1/3)
    (from inv α = α³/3 + 2α⁵/15 + ... ≥ α³/3) lies at or right of the root, so the iterates
    decrease monotonically onto it; a handful of steps reach machine precision. At small angles tan α − α
    cancels (its rounding over tan² α put a noise floor on the step above ``tol_rad``, and Newton never met the
    tolerance below α ≈ 4.7°), so the residual takes inv α from its series there (``_involute_accurate``); as a
    guard the iteration also ends once a step below 1e-9 α fails to halve the one before.
    """
    if not value > 0.0:
        raise ValueError(f"inverse involute needs a positive value, got {value!r}")
    alpha = min((3.0 * value) ** (1.0 / 3.0), HALF_PI - 1e-9)
    last = math.inf
    for _ in range(max_iter):
        step = (_involute_accurate(alpha) - value) / math.tan(alpha) ** 2
        if abs(step) <= 1e-9 * alpha and abs(step) > 0.5 * last:  # the noise floor of inv α
            return alpha
        alpha -= step
        if abs(step) <= tol_rad * max(1.0, alpha):
            return alpha
        last = abs(step)
    raise ValueError(f"inverse involute did not converge for {value!r}")


# ------------------------------------------------------------------------------ one gear (ISO 21771)
def transverse_module_mm(normal_module_mm: float, helix_rad: float) -> float:
    """m_t = m_n / cos β."""
    return normal_module_mm / math.cos(helix_rad)


def transverse_pressure_angle_rad(normal_pressure_rad: float, helix_rad: float) -> float:
    """α_t = atan(tan α_n / cos β)."""
    return math.atan(math.tan(normal_pressure_rad) / math.cos(helix_rad))


def base_helix_angle_rad(helix_rad: float, transverse_pressure_rad: float) -> float:
    """β_b = atan(tan β cos α_t)."""
    return math.atan(math.tan(helix_rad) * math.cos(transverse_pressure_rad))


def pitch_diameter_mm(teeth: int, transverse_module: float) -> float:
    """Reference (pitch) diameter d = z m_t."""
    return teeth * transverse_module


def base_diameter_mm(pitch_diameter: float, transverse_pressure_rad: float) -> float:
    """d_b = d cos α_t."""
    return pitch_diameter * math.cos(transverse_pressure_rad)


def tip_diameter_mm(pitch_diameter: float, normal_module_mm: float, profile_shift: float,
                    addendum_factor: float = 1.0, tip_alteration: float = 0.0) -> float:
    """d_a = d + 2 m_n (h_aP* + x + k) (ISO 21771; h_aP* = 1 and k = 0 by default)."""
    return pitch_diameter + 2.0 * normal_module_mm * (addendum_factor + profile_shift + tip_alteration)


def root_diameter_mm(pitch_diameter: float, normal_module_mm: float, profile_shift: float,
                     dedendum_factor: float = 1.25) -> float:
    """d_f = d − 2 m_n (h_fP* − x) (ISO 21771; h_fP* = 1.25 by default)."""
    return pitch_diameter - 2.0 * normal_module_mm * (dedendum_factor - profile_shift)


def transverse_base_pitch_mm(transverse_module: float, transverse_pressure_rad: float) -> float:
    """p_bt = π m_t cos α_t."""
    return math.pi * transverse_module * math.cos(transverse_pressure_rad)


# ------------------------------------------------------------------------------------- the pair
def working_pressure_angle_rad(transverse_pressure_rad: float, normal_pressure_rad: float,
                               shift_sum: float, teeth_sum: int) -> float:
    """α_wt from inv α_wt = inv α_t + 2 tan α_n (x1 + x2)/(z1 + z2) (ISO 21771, eq. for zero backlash).

    x1 + x2 = 0 returns α_t itself (not a Newton solve of its involute), so that a_w = a and k = 0 exactly.
    """
    if shift_sum == 0.0:
        return transverse_pressure_rad
    value = involute(transverse_pressure_rad) + 2.0 * math.tan(normal_pressure_rad) * shift_sum / teeth_sum
    if value <= 0.0:
        raise InfeasibleGeometry(
            f"the sum of profile shifts x1 + x2 = {shift_sum:.3f} is too negative for "
            f"z1 + z2 = {teeth_sum}: inv α_wt = {value:.3g} ≤ 0, the pair cannot mesh", "pinion", "profile_shift")
    return inverse_involute(value)


def center_distance_mm(pitch_diameter_1: float, pitch_diameter_2: float,
                       transverse_pressure_rad: float, working_pressure_rad: float) -> float:
    """Working centre distance a_w = a cos α_t / cos α_wt with a = (d1 + d2)/2."""
    reference = 0.5 * (pitch_diameter_1 + pitch_diameter_2)
    return reference * math.cos(transverse_pressure_rad) / math.cos(working_pressure_rad)


def tip_alteration_coefficient(center_distance: float, reference_center_distance: float, shift_sum: float,
                               normal_module_mm: float) -> float:
    """k = (a_w − a)/m_n − (x1 + x2) (ISO 21771, tip alteration coefficient; ≤ 0 because inv is convex):
    the tips are shortened by k m_n so that the bottom clearance at a_w is that of the basic rack."""
    return (center_distance - reference_center_distance) / normal_module_mm - shift_sum


def transverse_contact_ratio(tip_1: float, base_1: float, tip_2: float, base_2: float,
                             center_distance: float, working_pressure_rad: float, base_pitch: float) -> float:
    """ε_α = (√(r_a1² − r_b1²) + √(r_a2² − r_b2²) − a_w sin α_wt) / p_bt (ISO 21771)."""
    approach = math.sqrt(max(0.25 * (tip_1 ** 2 - base_1 ** 2), 0.0))
    recess = math.sqrt(max(0.25 * (tip_2 ** 2 - base_2 ** 2), 0.0))
    return (approach + recess - center_distance * math.sin(working_pressure_rad)) / base_pitch


def overlap_ratio(face_width: float, helix_rad: float, normal_module_mm: float) -> float:
    """ε_β = b sin β / (π m_n), b the common (smaller) face width."""
    return face_width * math.sin(helix_rad) / (math.pi * normal_module_mm)


# ---------------------------------------------------------------------------- design-rule checks
def rack_form_height_factor(dedendum_factor: float, root_radius_factor: float, normal_pressure_rad: float) -> float:
    """h_FfP* = h_fP* − ρ_fP* (1 − sin α_n): the height of the straight flank of the generating rack (the tool's
    addendum h_aP0 = h_fP less its tip rounding ρ_aP0 = ρ_fP), in multiples of m_n (ISO 21771 / DIN 3960).

    The straight flank generates the involute; where it ends the tip rounding cuts the root fillet. ISO 53
    profile A (1.25, 0.38) at α_n = 20° gives 0.99997, the familiar h_a = m_n of the undercut rule z_min = 17.1.
    """
    return dedendum_factor - root_radius_factor * (1.0 - math.sin(normal_pressure_rad))


def undercut_limit_teeth(profile_shift: float, helix_rad: float, transverse_pressure_rad: float,
                         form_height_factor: float = 1.0) -> float:
    """Theoretical undercut limit z_min = 2 (h_FfP* − x) cos β / sin² α_t (rack-generated teeth).

    h_FfP* is the straight-flank height of the generating rack (``rack_form_height_factor``; ≈ 1 for
    ISO 53 profile A at 20°, the practical DIN 3960 / ISO 21771 value; the tool tip radius lets a few teeth
    fewer pass in practice, so this limit errs on the safe side). Spur 20°: z_min = 17.1.
    """
    return 2.0 * (form_height_factor - profile_shift) * math.cos(helix_rad) / math.sin(transverse_pressure_rad) ** 2


def undercut_min_profile_shift(teeth: int, helix_rad: float, transverse_pressure_rad: float,
                               form_height_factor: float = 1.0) -> float:
    """The profile shift that just avoids undercut: ``undercut_limit_teeth`` solved for x,
    x_min = h_FfP* − z sin² α_t / (2 cos β)."""
    return form_height_factor - teeth * math.sin(transverse_pressure_rad) ** 2 / (2.0 * math.cos(helix_rad))


def form_point_from_base_tangent_mm(pitch_diameter: float, transverse_pressure_rad: float, normal_module_mm: float,
                                    profile_shift: float, form_height_factor: float) -> float:
    """q = r sin α_t − (h_FfP* − x) m_n / sin α_t: how far from the member's base tangent point T, along the
    transverse line of action of its generation by the rack, the rack's straight flank ends: the lowest point
    of the generated involute, on the root form circle d_Ff = 2 √(r_b² + q²) (ISO 21771). q < 0 is undercut
    (the same condition as ``undercut_limit_teeth``): the involute then ends above T, higher than this formula
    can say."""
    return (0.5 * pitch_diameter * math.sin(transverse_pressure_rad)
            - (form_height_factor - profile_shift) * normal_module_mm / math.sin(transverse_pressure_rad))


def pointed_tip_diameter_mm(teeth: int, normal_module_mm: float, profile_shift: float, helix_rad: float,
                            normal_pressure_rad: float) -> float:
    """The diameter where the tooth's flanks meet, s_t = 0 (ISO 21771, 5.4): inv α_p = s_t/d + inv α_t with s_t =
    m_t (π/2 + 2 x tan α_n) at the reference circle, d_p = d_b / cos α_p. A tip circle above it carries no tooth."""
    m_t = transverse_module_mm(normal_module_mm, helix_rad)
    alpha_t = transverse_pressure_angle_rad(normal_pressure_rad, helix_rad)
    d = pitch_diameter_mm(teeth, m_t)
    value = (HALF_PI + 2.0 * profile_shift * math.tan(normal_pressure_rad)) / teeth + involute(alpha_t)
    return base_diameter_mm(d, alpha_t) / math.cos(inverse_involute(value)) if value > 0.0 else 0.0


def tip_reach_mm(tip_diameter: float, base_diameter: float) -> float:
    """g = √(r_a² − r_b²): from a member's base tangent point to where its tip circle crosses the line of action."""
    return math.sqrt(max(0.25 * (tip_diameter ** 2 - base_diameter ** 2), 0.0))


#: the smallest normal tip thickness s_an / m_n (Niemann/Winter, Maschinenelemente II; KISSsoft's defaults): 0.2 for
#: through-hardened and softer members, 0.4 for surface-hardened ones (the hard case would run through a thinner tip and
#: leave it brittle); ISO 6336-5's groups by the material's ``treatment``
MIN_TIP_THICKNESS_PER_MODULE = 0.2
SURFACE_HARDENED = ("case_carburized", "nitrided", "nitrocarburized", "induction_hardened", "flame_hardened")


def min_tip_thickness_per_module(treatment: str | None) -> float:
    return 2.0 * MIN_TIP_THICKNESS_PER_MODULE if treatment in SURFACE_HARDENED else MIN_TIP_THICKNESS_PER_MODULE


def hardened_tip_text(treatment: str | None) -> str:
    return f" ({treatment}: a surface-hardened tip needs 0.4 m_n)" if treatment in SURFACE_HARDENED else ""


def normal_tip_thickness_mm(teeth: int, normal_module_mm: float, profile_shift: float, helix_rad: float,
                            normal_pressure_rad: float, tip_diameter: float) -> float:
    """Normal tooth thickness at the tip circle, s_an = s_at cos β_a (ISO 21771, 5.4).

    s_t = m_t (π/2 + 2 x tan α_n) at the reference circle; s_at = d_a (s_t/d + inv α_t − inv α_at)
    with cos α_at = d_b/d_a; tan β_a = tan β d_a/d. Negative when the tooth comes to a point early.
    """
    m_t = transverse_module_mm(normal_module_mm, helix_rad)
    alpha_t = transverse_pressure_angle_rad(normal_pressure_rad, helix_rad)
    d = pitch_diameter_mm(teeth, m_t)
    alpha_at = math.acos(min(base_diameter_mm(d, alpha_t) / tip_diameter, 1.0))
    s_t = m_t * (HALF_PI + 2.0 * profile_shift * math.tan(normal_pressure_rad))
    s_at = tip_diameter * (s_t / d + involute(alpha_t) - involute(alpha_at))
    beta_a = math.atan(math.tan(helix_rad) * tip_diameter / d)
    return s_at * math.cos(beta_a)


# ------------------------------------------------------------------------------- assembled pair
@record
class PairGeometry:
    """Everything ISO 21771 gives for one external pair; angles in rad, lengths in mm."""

    normal_module_mm: float
    transverse_module_mm: float
    normal_pressure_rad: float
    transverse_pressure_rad: float
    working_pressure_rad: float
    helix_rad: float
    base_helix_rad: float
    pitch_diameter_mm: tuple[float, float]  # (pinion, gear)
    base_diameter_mm: tuple[float, float]
    tip_diameter_mm: tuple[float, float]
    root_diameter_mm: tuple[float, float]
    center_distance_mm: float  # working
    transverse_base_pitch_mm: float
    face_width_mm: float  # the smaller one
    contact_ratio_transverse: float
    overlap_ratio: float
    tip_alteration_coefficient: float = 0.0  # k (ISO 21771), tips shortened by k m_n (k <= 0)


@record
class BasicRackFactors:
    """The basic rack (ISO 53) in multiples of m_n; the default is profile A."""

    addendum: float = 1.0  # h_aP*
    dedendum: float = 1.25  # h_fP*
    root_radius: float = 0.38  # rho_fP*


def pair_geometry(normal_module: float, normal_pressure_deg: float, helix_deg: float,
                  teeth: tuple[int, int], shifts: tuple[float, float], widths_mm: tuple[float, float],
                  rack: BasicRackFactors = BasicRackFactors()) -> PairGeometry:
    """The geometry of one external pair (pinion, gear); raises ``InfeasibleGeometry`` if it cannot mesh."""
    a_n, beta = math.radians(normal_pressure_deg), math.radians(helix_deg)
    m_t = transverse_module_mm(normal_module, beta)
    a_t = transverse_pressure_angle_rad(a_n, beta)
    a_wt = working_pressure_angle_rad(a_t, a_n, shifts[0] + shifts[1], teeth[0] + teeth[1])
    d = (pitch_diameter_mm(teeth[0], m_t), pitch_diameter_mm(teeth[1], m_t))
    d_b = (base_diameter_mm(d[0], a_t), base_diameter_mm(d[1], a_t))
    a_w = center_distance_mm(d[0], d[1], a_t, a_wt)
    k = tip_alteration_coefficient(a_w, 0.5 * (d[0] + d[1]), shifts[0] + shifts[1], normal_module)
    d_a = (tip_diameter_mm(d[0], normal_module, shifts[0], rack.addendum, k),
           tip_diameter_mm(d[1], normal_module, shifts[1], rack.addendum, k))
    d_f = (root_diameter_mm(d[0], normal_module, shifts[0], rack.dedendum),
           root_diameter_mm(d[1], normal_module, shifts[1], rack.dedendum))
    _require_sound_blanks(d_b, d_a, d_f)
    p_bt = transverse_base_pitch_mm(m_t, a_t)
    eps_a = transverse_contact_ratio(d_a[0], d_b[0], d_a[1], d_b[1], a_w, a_wt, p_bt)
    if eps_a <= 0.0:
        raise InfeasibleGeometry(f"the tips do not reach the line of action (ε_α = {eps_a:.3f} ≤ 0): "
                                 "the teeth never mesh; raise the profile shifts or the tooth counts",
                                 "pinion", "profile_shift")
    b = min(widths_mm)
    return PairGeometry(normal_module, m_t, a_n, a_t, a_wt, beta, base_helix_angle_rad(beta, a_t), d, d_b, d_a,
                        d_f, a_w, p_bt, b, eps_a, overlap_ratio(b, beta, normal_module), k)


def _require_sound_blanks(d_b: tuple, d_a: tuple, d_f: tuple) -> None:
    for part, base, tip, root in zip(("pinion", "gear"), d_b, d_a, d_f, strict=True):
        if root <= 0.0:
            raise InfeasibleGeometry(f"root diameter d_f = {root:.4g} mm ≤ 0: too few teeth for this "
                                     "negative profile shift", part, "profile_shift")
        if tip <= base:
            raise InfeasibleGeometry(f"tip diameter d_a = {tip:.4g} mm does not exceed the base diameter "
                                     f"d_b = {base:.4g} mm: no involute flank; raise the profile shift",
                                     part, "profile_shift")
