"""Mesh stiffness: the seed's Hertz law, ISO 6336-1 method B, and the coefficient K of a contact law.

Units: lengths mm, moduli MPa (= N/mm²), forces N; ISO stiffnesses in N/(mm·µm) as the standard
writes them; K of the force law F = K h^e in N/mm^e.

Calibration. ``stiffness = "iso6336"`` chooses K so that the law's tangent at the static load is ISO's normal
mesh stiffness k_n = c_γα b / cos² β_b: e K h_0^(e−1) = k_n with F_n0 = K h_0^e, for any exponent e. Linearised
models then equal the linear ISO model at the operating point; the static approach is h_0 = e F_n0 / k_n, e
times ISO's F_n0 / k_n (the secant F/h of a law with e > 1 is k_n / e).

Zero load. ISO 6336-1's low-load factor (F_t K_A / b / 100)^0.25 vanishes with the load, and the
calibration of an ``iso6336`` law is undefined at F_n0 = 0. Both are evaluated at the
static tangential force floored at ``MIN_LINE_LOAD_N_mm`` = 1 N per mm of face width: the single-pair
stiffness then never drops below (K_A/100)^0.25 ≈ 0.32 of its full-load value, stays continuous in the
load, and the iso6336 coefficient is calibrated at the same (small) load the stiffness was evaluated at.
Hertz and numeric laws need no floor; for e > 1 an unloaded mesh has h_0 = 0 and k_lin = 0.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from gearcli.design.forces import normal_force_N
from gearcli.results import MeshStiffness

if TYPE_CHECKING:  # the design layer never imports the config package at run time
    from gearcli.config.schema import Contact
    from gearcli.results import MeshStiffness, StageResult

MIN_LINE_LOAD_N_mm = 1.0  # floor of |F_t| / b for the ISO 6336 evaluation (see the module docstring)
UM_PER_MM = 1000.0

# ISO 6336-1:2006, clause 9 (method B, basic formulas): q' = C1 + C2/zn1 + ... + C9 x2², mm·µm/N
ISO6336_C = (0.04723, 0.15551, 0.25791, -0.00635, -0.11654, -0.00193, -0.24188, 0.00529, 0.00182)
C_M = 0.8  # theoretical to measured stiffness, solid blanks (ISO 6336-1, clause 9)
C_R = 1.0  # gear blank factor, solid disc gears (ISO 6336-1, clause 9)
FULL_LOAD_LINE_LOAD_N_mm = 100.0  # above this F_t K_A / b, c' no longer depends on the load
C_GAMMA_BETA_PER_ALPHA = 0.85  # c_gamma_beta = 0.85 c_gamma_alpha (ISO 6336-1, clause 9)
WEB_RATIO_RANGE = (0.2, 1.2)  # b_s / b limits of the C_R formula (ISO 6336-1); values outside are clamped
MIN_RIM_PER_MODULE = 1.0  # s_R / m_n below this is taken as 1 (ISO 6336-1)
E_ST_MPa = 206_000.0  # the steel modulus ISO 6336-1 writes c'_th for
STEEL_MODULUS_RANGE_MPa = (190_000.0, 220_000.0)  # a member counts as steel (stainless 193-200, steels 200-215)
IRON_TREATMENTS = ("nodular_iron", "grey_iron")  # ISO 6336-5 material classes that are cast irons, not steels


# ------------------------------------------------------------------------ Hertz (seed section 3.3)
def equivalent_radius_mm(radius_1_mm: float, radius_2_mm: float) -> float:
    """1/R = 1/r1 + 1/r2 (pitch radii, as the seed paper takes them)."""
    return radius_1_mm * radius_2_mm / (radius_1_mm + radius_2_mm)


def effective_modulus_MPa(youngs_1_MPa: float, poisson_1: float, youngs_2_MPa: float, poisson_2: float) -> float:
    """1/E* = (1 − ν1²)/E1 + (1 − ν2²)/E2 (Hertz; the seed's 1.144e5 MPa is an erratum for 1.130e5)."""
    return 1.0 / ((1.0 - poisson_1 ** 2) / youngs_1_MPa + (1.0 - poisson_2 ** 2) / youngs_2_MPa)


def hertz_stiffness_N_mm1_5(equivalent_radius: float, effective_modulus: float) -> float:
    """K = 4/3 √R E* (sphere on plane, seed eq. in 3.3), N/mm^1.5 with R in mm and E* in MPa."""
    return 4.0 / 3.0 * math.sqrt(equivalent_radius) * effective_modulus


# ------------------------------------------------------------------- ISO 6336-1, method B (basic)
def virtual_teeth(teeth: int, helix_rad: float, base_helix_rad: float) -> float:
    """z_n = z / (cos² β_b cos β) (ISO 6336-1, virtual spur gear of the normal section)."""
    return teeth / (math.cos(base_helix_rad) ** 2 * math.cos(helix_rad))


def flexibility_q_prime(zn1: float, zn2: float, x1: float, x2: float) -> float:
    """q' = C1 + C2/zn1 + C3/zn2 + C4 x1 + C5 x1/zn1 + C6 x2 + C7 x2/zn2 + C8 x1² + C9 x2², mm·µm/N."""
    c1, c2, c3, c4, c5, c6, c7, c8, c9 = ISO6336_C
    return (c1 + c2 / zn1 + c3 / zn2 + c4 * x1 + c5 * x1 / zn1 + c6 * x2 + c7 * x2 / zn2
            + c8 * x1 ** 2 + c9 * x2 ** 2)


def counts_as_steel(youngs_modulus_MPa: float, treatment: str | None) -> bool:
    """A member whose modulus lies in :data:`STEEL_MODULUS_RANGE_MPa` and that is not an ISO 6336-5 cast iron."""
    low, high = STEEL_MODULUS_RANGE_MPa
    return low <= youngs_modulus_MPa <= high and treatment not in IRON_TREATMENTS


def material_factor(youngs_1_MPa: float, treatment_1: str | None, youngs_2_MPa: float,
                    treatment_2: str | None) -> float:
    """ISO 6336-1's E/E_st, E = 2 E1 E2 / (E1 + E2), of a pairing that is not steel on steel; 1 for steel on steel.

    ISO's c'_th is measured on steel pairs and the standard scales it by E/E_st (E_st = 206,000 N/mm²) for other
    pairings. gearcli's c' has no material term (the design contract's formula), so this factor only sets the
    design's ``steel_stiffness`` warning.
    """
    if counts_as_steel(youngs_1_MPa, treatment_1) and counts_as_steel(youngs_2_MPa, treatment_2):
        return 1.0
    return 2.0 * youngs_1_MPa * youngs_2_MPa / (youngs_1_MPa + youngs_2_MPa) / E_ST_MPa


def smaller_wheel_first(teeth: tuple[int, int], values: tuple, shifts: tuple[float, float] = (0.0, 0.0)) -> tuple:
    """``values`` (pinion, gear) reordered so that index 1 of ISO 6336-1 is the wheel with fewer teeth.

    ISO 6336-1 numbers the smaller wheel 1 whichever member drives; gearcli numbers the driving member
    (the pinion) first, so a speed-increasing stage (z_gear < z_pinion) swaps. Equal tooth counts, which
    the standard does not order, put the smaller profile shift first (the smaller wheel by tip diameter),
    so that the result never depends on which member drives.
    """
    gear_first = (teeth[1], shifts[1]) < (teeth[0], shifts[0])
    return (values[1], values[0]) if gear_first else values


def gear_blank_factor(web_thickness_mm: float, rim_thickness_mm: float, face_width_mm: float,
                      normal_module_mm: float) -> float:
    """C_R = 1 + ln(b_s/b) / (5 e^(s_R/(5 m_n))) for a webbed gear blank (ISO 6336-1, clause 9).

    b_s the web thickness, s_R the rim thickness, b the face width. The standard's limits are applied
    as it prescribes: b_s/b is clamped to [0.2, 1.2] and s_R/m_n is taken as at least 1.
    """
    low, high = WEB_RATIO_RANGE
    web_ratio = min(max(web_thickness_mm / face_width_mm, low), high)
    rim_ratio = max(rim_thickness_mm / normal_module_mm, MIN_RIM_PER_MODULE)
    return 1.0 + math.log(web_ratio) / (5.0 * math.exp(rim_ratio / 5.0))


def basic_rack_factor(normal_pressure_deg: float, dedendum_factor: float = 1.25) -> float:
    """C_B = [1 + 0.5 (1.2 − h_fP/m_n)] [1 − 0.02 (20° − α_n)] (ISO 6336-1, clause 9)."""
    return (1.0 + 0.5 * (1.2 - dedendum_factor)) * (1.0 - 0.02 * (20.0 - normal_pressure_deg))


def low_load_factor(line_load_N_mm: float) -> float:
    """(F_t K_A / b / 100)^0.25 below 100 N/mm, else 1 (ISO 6336-1, clause 9)."""
    return min(line_load_N_mm / FULL_LOAD_LINE_LOAD_N_mm, 1.0) ** 0.25


def reference_tangential_force_N(tangential_force_N: float, face_width_mm: float) -> float:
    """|F_t| floored at 1 N/mm of face width: the load the ISO stiffness is evaluated at."""
    return max(abs(tangential_force_N), MIN_LINE_LOAD_N_mm * face_width_mm)


def single_pair_stiffness_N_mm_um(zn1: float, zn2: float, x1: float, x2: float, helix_rad: float,
                                  normal_pressure_deg: float, line_load_N_mm: float, *,
                                  blank_factor: float = C_R, dedendum_factor: float = 1.25) -> float:
    """c' = c'_th C_M C_R C_B cos β × low-load factor, c'_th = 1/q' (ISO 6336-1, clause 9).

    Index 1 is the smaller wheel (``smaller_wheel_first``); ``blank_factor`` is C_R, ``dedendum_factor``
    the rack's h_fP* that sets C_B.
    """
    c_th = 1.0 / flexibility_q_prime(zn1, zn2, x1, x2)
    return (c_th * C_M * blank_factor * basic_rack_factor(normal_pressure_deg, dedendum_factor)
            * math.cos(helix_rad) * low_load_factor(line_load_N_mm))


def mesh_stiffness_N_mm_um(single_pair: float, contact_ratio_transverse: float) -> float:
    """c_γα = c' (0.75 ε_α + 0.25) (ISO 6336-1, clause 9), with no reduction below ε_α = 1.2.

    A published KISSsoft rating (ISO 6336:2006 method B, spur mesh at ε_α = 1.115) prints exactly this
    product; see docs/iso6336.md for why the 10 % reduction gearcli used to apply was dropped.
    """
    return single_pair * (0.75 * contact_ratio_transverse + 0.25)


def mesh_stiffness_beta_N_mm_um(mesh_stiffness: float) -> float:
    """c_γβ = 0.85 c_γα (ISO 6336-1, clause 9): the mesh stiffness used for the face load factors."""
    return C_GAMMA_BETA_PER_ALPHA * mesh_stiffness


def iso6336_normal_stiffness_N_mm(mesh_stiffness: float, face_width_mm: float, base_helix_rad: float) -> float:
    """k_n = k_t / cos² β_b with k_t = c_γα b (docs/physics.md, "Torsional model"); N/µm × 1000 = N/mm."""
    return mesh_stiffness * face_width_mm * UM_PER_MM / math.cos(base_helix_rad) ** 2


def iso6336_coefficient_N_mm_e(normal_stiffness_N_mm: float, normal_force_N: float, exponent: float) -> float:
    """K whose tangent at the static load equals ISO's mesh stiffness: e K h_0^(e−1) = k_n with K h_0^e = F_n0,
    i.e. h_0 = e F_n0 / k_n (e times ISO's deflection) and K = k_n^e / (e^e F_n0^(e−1)) (= k_n for e = 1)."""
    e = exponent
    return normal_stiffness_N_mm ** e / (e ** e * normal_force_N ** (e - 1.0))


# ---------------------------------------------------------------------------- the contact law's K
def law_coefficient_N_mm_e(stiffness: str | float, exponent: float, *, hertz: float,
                           iso_normal_stiffness_N_mm: float, iso_reference_normal_force_N: float) -> float:
    """K of F = K h^e for a law ``stiffness`` = "hertz" | "iso6336" | a number (N/mm^e)."""
    if stiffness == "hertz":
        return hertz  # 4/3 √R E*, used as-is whatever the exponent
    if stiffness == "iso6336":
        return iso6336_coefficient_N_mm_e(iso_normal_stiffness_N_mm, iso_reference_normal_force_N, exponent)
    return float(stiffness)


def iso_reference_normal_force_N(tangential_force_N: float, face_width_mm: float,
                                 normal_pressure_rad: float, helix_rad: float) -> float:
    """F_n0: the normal force behind F_t,ref = ``reference_tangential_force_N`` (|F_n| unless floored)."""
    return normal_force_N(reference_tangential_force_N(tangential_force_N, face_width_mm),
                          normal_pressure_rad, helix_rad)


def calibration_line_force_N(stiffness: str | float, face_width_mm: float, normal_pressure_rad: float,
                             helix_rad: float, base_helix_rad: float) -> float:
    """The transverse line force F_bt = F_n cos β_b of the floor an ``iso6336`` law is calibrated at when the load is
    below it (1 N/mm of face width: its tangent is k_n there, and its reported ``linearised_N_mm`` is taken there), so
    that a linearisation at a smaller load holds at it; 0 for the other laws (linearised at the load itself)."""
    if stiffness != "iso6336":
        return 0.0
    return normal_force_N(MIN_LINE_LOAD_N_mm * face_width_mm, normal_pressure_rad, helix_rad) * math.cos(base_helix_rad)


def law_tangential_force_N(tangential_N: float, efficiency: float) -> float:
    """The static transverse force a parallel mesh's law carries, from the design's F_t = T_pinion / r_pinion: F_t
    itself under a forward load (the pinion drives and the law's force is its side's), F_t / eta when the load
    drives back through a lossy mesh (the gear drives with the law's whole force f and the pinion gets eta f = F_t:
    docs/physics.md "Stage efficiency in the dynamics"). The run's static load, where an iso6336 law's tangent is
    k_n (DESIGN section 13)."""
    if tangential_N < 0.0 and 0.0 < efficiency < 1.0:
        return tangential_N / efficiency
    return tangential_N


def contact_stiffness_N_mm_e(stage: StageResult, contact: Contact) -> float:
    """The coefficient K (N/mm^e) mesh ``stage`` uses under ``contact`` (``cfg.contact_for(k)``).

    "hertz": the stage's 4/3 √R E*; a number: that number; "iso6336": K whose tangent e K h_0^(e−1) at the static
    load F_n0 is k_n = c_γα b / cos² β_b (docs/physics.md, "Torsional model"); F_n0 is floored at 1 N/mm of face
    width when the load is (near) zero (see the module docstring).
    """
    beta_b = math.radians(stage.base_helix_angle_deg)
    k_n = iso6336_normal_stiffness_N_mm(stage.iso6336_mesh_stiffness_N_mm_um, stage.face_width_mm, beta_b)
    f_t = stage.static_force_N.tangential
    if stage.planetary is None:  # a planetary's sun–planet force is its driving side's already (design.planetary)
        f_t = law_tangential_force_N(f_t, stage.efficiency)
    f_n0 = iso_reference_normal_force_N(f_t,
                                        stage.face_width_mm,
                                        math.radians(stage.normal_pressure_angle_deg),
                                        math.radians(stage.helix_angle_deg))
    return law_coefficient_N_mm_e(contact.stiffness, contact.exponent, hertz=stage.hertz_stiffness_N_mm1_5,
                                  iso_normal_stiffness_N_mm=k_n, iso_reference_normal_force_N=f_n0)


def static_approach_mm(normal_force_N: float, coefficient: float, exponent: float) -> float:
    """h_0 = (|F_n| / K)^(1/e): the normal approach under the static load."""
    return (abs(normal_force_N) / coefficient) ** (1.0 / exponent)


def linearised_stiffness_N_mm(coefficient: float, exponent: float, approach_mm: float) -> float:
    """k_lin = dF/dh = e K h_0^(e−1) (= K for e = 1, 0 for e > 1 at zero load)."""
    if exponent == 1.0:
        return coefficient
    return exponent * coefficient * approach_mm ** (exponent - 1.0)


def law_name(stiffness: str | float) -> str:
    """The ``mesh_stiffness.law`` of a ``stiffness`` key: "iso6336", "hertz", or "given" (a number)."""
    return stiffness if isinstance(stiffness, str) else "given"


def mesh_law_stiffness(stiffness: str | float, exponent: float, *, hertz: float, iso_normal_stiffness_N_mm: float,
                       tangential_force_N: float, face_width_mm: float, normal_pressure_rad: float,
                       helix_rad: float) -> MeshStiffness:
    """The law's K, its tangent at the static load and ISO's k_n beside it (``mesh_stiffness`` of design JSON).

    An ``iso6336`` law's tangent is taken at the static normal force floored as ISO's stiffness is (1 N/mm of face
    width): the load it is calibrated at, so its ``linearised_N_mm`` is ``iso_N_mm`` at any load (and the models
    linearise it there: :attr:`gearcli.model.spec.MeshSpec.linearisation_line_force_N`). A Hertz or numeric law
    needs no floor (module text): its tangent and static approach are at the static force itself, as ``simulate``
    reports them (0 for e > 1 unloaded)."""
    f_n0 = iso_reference_normal_force_N(tangential_force_N, face_width_mm, normal_pressure_rad, helix_rad)
    K = law_coefficient_N_mm_e(stiffness, exponent, hertz=hertz, iso_normal_stiffness_N_mm=iso_normal_stiffness_N_mm,
                               iso_reference_normal_force_N=f_n0)
    if stiffness != "iso6336":
        f_n0 = normal_force_N(abs(tangential_force_N), normal_pressure_rad, helix_rad)
    h0 = static_approach_mm(f_n0, K, exponent)
    return MeshStiffness(law_N_mm_e=K, exponent=exponent, linearised_N_mm=linearised_stiffness_N_mm(K, exponent, h0),
                         static_approach_mm=h0, law=law_name(stiffness), K=K, iso_N_mm=iso_normal_stiffness_N_mm)
