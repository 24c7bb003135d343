"""The contact-line phase of a planet's ring mesh against its sun mesh, from the tooth geometry.

Time-varying contact-line stiffness counts its phase ``x`` in base pitches from the start of the active path
of contact (:mod:`gearcli.model.contact_lines`). Between planets the phases follow from their positions
(Parker & Lin, J. Mech. Des. 126, 2004; :meth:`gearcli.model.spec.PlanetarySpec.mesh_phase_cycles`); within
one planet, the ring mesh's phase against the sun mesh's follows from where the planet's teeth stand.

In the carrier's frame, with the sun–planet pitch point P_s on the side of the sun (polar angle pi about the
planet's centre) and the planet–ring pitch point P_r opposite (angle 0), the mesh forces on the planet are
parallel (its moment balance), so one flank family of the planet meets the sun and the other the ring (the
planet is an idler). A tooth's flank stands at the polar angle ``theta_k +- psi(r)`` on the radius r, with
``psi(r) = psi_b - inv(alpha(r))`` half the tooth's angular thickness (``psi_b = (pi/2 + 2 x tan alpha_n)/z_p
+ inv(alpha_t)``). A flank passes P_s at ``phi_s = pi - psi_b + inv(alpha_w,sp)`` and the other flank passes
P_r at ``phi_r = psi_b - inv(alpha_w,rp)`` (mod one angular pitch 2 pi / z_p), so between the two pitch-point
contacts the planet turns

    Delta = z_p (phi_r - phi_s) / 2 pi = z_p (2 psi_b - inv(alpha_w,sp) - inv(alpha_w,rp)) / 2 pi - z_p / 2

mesh cycles (mod 1; the z_p / 2 term is Parker & Lin's parity: an even planet puts a tooth opposite a tooth, an
odd one a tooth opposite a space). The sense: with the sun driving the planet in the carrier's frame (power
from the sun side), the planet turns with the sun's pull, the ring mesh's pitch-point contact follows the sun
mesh's by Delta; with the ring side driving, it leads by Delta. Each mesh's path starts at the tip of the
member it drives: a contact at the pitch point is ``g_approach / p_bt`` into the path. So

    x_ring - x_sun = s Delta + (g_approach,ring - g_approach,sun) / p_bt     (mod 1),  s = +-1 as above,

with, for the sun mesh, ``g_planet = sqrt(r_ap^2 - r_bp^2) - r_w,p sin alpha_w,sp`` and ``g_sun`` alike, and
for the ring mesh ``g_planet = sqrt(r_ap^2 - r_bp^2) - r_w,p sin alpha_w,rp``, ``g_ring = r_w,r sin alpha_w,rp -
sqrt(r_ar^2 - r_br^2)`` (the internal gear's tip circle is inside its pitch circle). A transverse section is
taken (the helical contact lines cross the face alike on both meshes).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from gearcli.results import StageResult


def involute(alpha: float) -> float:
    return math.tan(alpha) - alpha


def sun_ring_contact_phase_cycles(*, planet_teeth: int, planet_profile_shift: float, normal_pressure_angle_rad: float,
                                  transverse_pressure_angle_rad: float, alpha_w_sun_rad: float,
                                  alpha_w_ring_rad: float, r_b_sun: float, r_b_planet: float, r_b_ring: float,
                                  r_a_sun: float, r_a_planet: float, r_a_ring: float, base_pitch: float,
                                  sun_drives: bool) -> float:
    """Planet 1's ring-mesh contact-line phase minus its sun mesh's, in mesh cycles in [0, 1) (module text).
    Lengths in one unit (any), angles in radians; ``r_a_ring`` the internal gear's tip radius (inner)."""
    z_p = planet_teeth
    psi_b = (0.5 * math.pi + 2.0 * planet_profile_shift * math.tan(normal_pressure_angle_rad)) / z_p \
        + involute(transverse_pressure_angle_rad)
    delta = z_p * (2.0 * psi_b - involute(alpha_w_sun_rad) - involute(alpha_w_ring_rad)) / (2.0 * math.pi) - 0.5 * z_p
    # tip parts of each path of contact, from the pitch point
    rw_p_sun = r_b_planet / math.cos(alpha_w_sun_rad)
    rw_s = r_b_sun / math.cos(alpha_w_sun_rad)
    rw_p_ring = r_b_planet / math.cos(alpha_w_ring_rad)
    rw_r = r_b_ring / math.cos(alpha_w_ring_rad)
    sun_planet_tip = math.sqrt(r_a_planet**2 - r_b_planet**2) - rw_p_sun * math.sin(alpha_w_sun_rad)
    sun_sun_tip = math.sqrt(r_a_sun**2 - r_b_sun**2) - rw_s * math.sin(alpha_w_sun_rad)
    ring_planet_tip = math.sqrt(r_a_planet**2 - r_b_planet**2) - rw_p_ring * math.sin(alpha_w_ring_rad)
    ring_ring_tip = rw_r * math.sin(alpha_w_ring_rad) - math.sqrt(r_a_ring**2 - r_b_ring**2)
    if sun_drives:  # sun -> planet -> ring: each path starts at the driven member's tip
        approach_sun, approach_ring, sense = sun_planet_tip, ring_ring_tip, 1.0
    else:  # ring -> planet -> sun
        approach_sun, approach_ring, sense = sun_sun_tip, ring_planet_tip, -1.0
    return (sense * delta + (approach_ring - approach_sun) / base_pitch) % 1.0


def sun_drives(unit_speeds: dict[str, float], driven: str, z_sun: int, z_ring: int) -> bool:
    """Whether the sun side drives the planets in the carrier's frame: the sun's torque times its speed relative
    to the carrier is positive. The members' torques stand as sun 1 : ring z_r/z_s : carrier -(1 + z_r/z_s), and
    the driven member's torque has the sign of its (unit, positive) speed."""
    u = z_ring / z_sun
    share = {"sun": 1.0, "ring": u, "carrier": -(1.0 + u)}[driven]
    return share * (unit_speeds["sun"] - unit_speeds["carrier"]) > 0.0


def stage_contact_phase_cycles(st: StageResult, sun_drives: bool) -> float:
    """:func:`sun_ring_contact_phase_cycles` of a designed planetary stage (planet 1's ring mesh against its sun
    mesh), from its design result."""
    p = st.planetary
    assert p is not None
    return sun_ring_contact_phase_cycles(
        planet_teeth=p.planet.teeth, planet_profile_shift=p.planet.profile_shift,
        normal_pressure_angle_rad=math.radians(st.normal_pressure_angle_deg),
        transverse_pressure_angle_rad=math.radians(st.transverse_pressure_angle_deg),
        alpha_w_sun_rad=math.radians(st.working_pressure_angle_deg),
        alpha_w_ring_rad=math.radians(p.planet_ring.working_pressure_angle_deg),
        r_b_sun=0.5 * p.sun.base_diameter_mm, r_b_planet=0.5 * p.planet.base_diameter_mm,
        r_b_ring=0.5 * p.ring.base_diameter_mm, r_a_sun=0.5 * p.sun.tip_diameter_mm,
        r_a_planet=0.5 * p.planet.tip_diameter_mm, r_a_ring=0.5 * p.ring.tip_diameter_mm,
        base_pitch=st.transverse_base_pitch_mm, sun_drives=sun_drives)
