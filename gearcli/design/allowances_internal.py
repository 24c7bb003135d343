"""Tooth-thickness allowances of a planetary stage's planet–ring (internal) mesh (ISO 21771:2007; docs/planetary.md,
"Tooth-thickness allowances").

Sign conventions (ISO 21771, as gearcli's ring): the ring's teeth z_r and diameters are given positive, its profile
shift x_r with ISO's sign, under which the tooth thickness on the reference circle is s_n = m_n (π/2 + 2 x tan α_n)
for the planet and the ring alike. A tooth-thickness allowance A_sn < 0 thins either tooth, so the generating
profile shift x_E = x + A_sn / (2 m_n tan α_n) holds for the ring too, and its root, cut deeper into the rim, is
d_f = d_r + 2 (h_fP − x_E m_n).

The planet sits on the carrier's radius a′ (the sun–planet working centre distance). On the working circles
d_w = d cos α_t / cos α′ (cos α′ = (d_br − d_bp) / (2 a′)) the circumferential backlash is the ring's space width
less the planet's tooth thickness, s_wp = d_wp (s_tp/d_p + inv α_t − inv α′), e_wr = p_w − s_wr,
s_wr = d_wr (s_tr/d_r − inv α_t + inv α′) (an internal tooth thickens outwards), which adds up to

    j_t = m_t cos α_t / cos α′ · [(z_r − z_p)(inv α_t − inv α′) − 2 (x_Ep + x_Er) tan α_n]

(zero at inv α′ = inv α_t + 2 tan α_n (x_Ep + x_Er)/(z_p − z_r), ISO 21771's internal zero-backlash condition).
Unlike an external pair's, it falls as the centre distance grows. j_n = j_t cos α′ cos β_b. Lengths in mm.
"""

from __future__ import annotations

import math

from gearcli.core.records import record
from gearcli.design.allowances import generating_profile_shift
from gearcli.design.geometry import involute

Pair = tuple[float, float]  # [upper, lower]


@record
class InternalMesh:
    """What the internal mesh's allowances need: the teeth, module, angles and the planet's and ring's circles."""

    normal_module_mm: float
    normal_pressure_rad: float
    transverse_pressure_rad: float
    base_helix_rad: float
    transverse_module_mm: float
    teeth: tuple[int, int]  # (planet, ring), both positive
    base_diameter_mm: tuple[float, float]  # (planet, ring)
    center_distance_mm: float  # the carrier's radius a′


@record
class InternalAllowances:
    ring_generating_profile_shift: Pair  # [x_E,e, x_E,i]
    ring_manufactured_root_diameter_mm: Pair  # [d_f,e, d_f,i]
    backlash_circumferential_mm: Pair  # [max, min]
    backlash_normal_mm: Pair  # [max, min]
    contact_ratio_transverse_with_allowances: tuple[float, float, float]  # [e, m, i]


def working_pressure_rad(mesh: InternalMesh) -> float:
    """α′ of the planet on the carrier's radius: cos α′ = (d_br − d_bp) / (2 a′)."""
    d_bp, d_br = mesh.base_diameter_mm
    return math.acos((d_br - d_bp) / (2.0 * mesh.center_distance_mm))


def circumferential_backlash_mm(mesh: InternalMesh, x_planet: float, x_ring: float) -> float:
    """j_t on the working circles at the carrier's radius of teeth cut at x_Ep, x_Er (module docstring)."""
    alpha = working_pressure_rad(mesh)
    z_p, z_r = mesh.teeth
    a_t = mesh.transverse_pressure_rad
    return (mesh.transverse_module_mm * math.cos(a_t) / math.cos(alpha)
            * ((z_r - z_p) * (involute(a_t) - involute(alpha))
               - 2.0 * (x_planet + x_ring) * math.tan(mesh.normal_pressure_rad)))


def contact_ratio(mesh: InternalMesh, planet_tip_mm: float, ring_tip_mm: float) -> float:
    """ε_α = [√(r_ap² − r_bp²) − √(r_ar² − r_br²) + a′ sin α′] / p_bt at the carrier's radius."""
    alpha = working_pressure_rad(mesh)
    d_bp, d_br = mesh.base_diameter_mm
    p_bt = math.pi * mesh.transverse_module_mm * math.cos(mesh.transverse_pressure_rad)
    path = (math.sqrt(max(0.25 * (planet_tip_mm ** 2 - d_bp ** 2), 0.0))
            - math.sqrt(0.25 * (ring_tip_mm ** 2 - d_br ** 2)) + mesh.center_distance_mm * math.sin(alpha))
    return path / p_bt


def internal_allowances(mesh: InternalMesh, shifts: Pair, planet_cut: Pair, ring_thickness: Pair,
                        planet_tips: Pair, ring_tip_mm: float, ring_pitch_mm: float,
                        dedendum_factor: float) -> InternalAllowances:
    """The ring's x_E and manufactured root, and the planet–ring backlash [max, min] and ε_α [e, m, i]. ``shifts``:
    (x_p, x_r) nominal; ``planet_cut``: the planet's [x_E,e, x_E,i] (its own allowance, or x twice);
    ``ring_thickness``: the ring's [A_sne, A_sni]; ``planet_tips``: the planet's [d_a + A_dae, d_a + A_dai]."""
    m_n, a_n = mesh.normal_module_mm, mesh.normal_pressure_rad
    ring_cut = (generating_profile_shift(shifts[1], ring_thickness[0], m_n, a_n),
                generating_profile_shift(shifts[1], ring_thickness[1], m_n, a_n))
    roots = (ring_pitch_mm + 2.0 * m_n * (dedendum_factor - ring_cut[0]),
             ring_pitch_mm + 2.0 * m_n * (dedendum_factor - ring_cut[1]))
    j_max = circumferential_backlash_mm(mesh, planet_cut[1], ring_cut[1])  # the thinnest teeth
    j_min = circumferential_backlash_mm(mesh, planet_cut[0], ring_cut[0])  # the thickest
    to_normal = math.cos(working_pressure_rad(mesh)) * math.cos(mesh.base_helix_rad)
    mean_tip = 0.5 * (planet_tips[0] + planet_tips[1])
    eps = (contact_ratio(mesh, planet_tips[0], ring_tip_mm), contact_ratio(mesh, mean_tip, ring_tip_mm),
           contact_ratio(mesh, planet_tips[1], ring_tip_mm))
    return InternalAllowances(ring_cut, roots, (j_max, j_min), (j_max * to_normal, j_min * to_normal), eps)


def internal_normal_tip_thickness_mm(teeth: int, normal_module_mm: float, profile_shift: float, helix_rad: float,
                                     normal_pressure_rad: float, tip_diameter: float) -> float:
    """Normal tooth thickness of an internal gear at its tip circle (the inner one), s_an = s_at cos β_a: with
    s_t = m_t (π/2 + 2 x tan α_n) on the reference circle (ISO 21771's sign of x), an internal tooth thins inwards,
    s_at = d_a (s_t/d − inv α_t + inv α_at), cos α_at = d_b/d_a, tan β_a = tan β d_a/d. Negative: pointed."""
    m_t = normal_module_mm / math.cos(helix_rad)
    alpha_t = math.atan(math.tan(normal_pressure_rad) / math.cos(helix_rad))
    d = teeth * m_t
    alpha_at = math.acos(min(d * math.cos(alpha_t) / tip_diameter, 1.0))
    s_t = m_t * (0.5 * math.pi + 2.0 * profile_shift * math.tan(normal_pressure_rad))
    s_at = tip_diameter * (s_t / d - involute(alpha_t) + involute(alpha_at))
    return s_at * math.cos(math.atan(math.tan(helix_rad) * tip_diameter / d))
