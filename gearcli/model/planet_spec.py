"""A planetary stage in the model (SI): :class:`PlanetarySpec`, which a planetary stage's model
(:mod:`gearcli.stages.planetary_model`) is. Apart from :mod:`gearcli.model.spec` (which re-exports it by name) so
that a scene without planetary stages does not create the class (24 fields: about 1 ms on Python 3.11).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from gearcli.core.records import record

if TYPE_CHECKING:
    from gearcli.model.spec import MeshSpec

MEMBERS = ("sun", "carrier", "ring")


@record
class PlanetarySpec:
    """A planetary stage in the model (SI). The stage's input member is the chain's body before it (its inertia
    is the reducer shaft's), its output member the body after it; the third member is a body unless it is
    ``fixed``; every planet is a body. Each planet has a sun mesh and a ring mesh (``MeshSpec`` laws; their
    base radii are not used, the levers below are): along the sun mesh's line of action
    ``delta = r_bp theta_p + r_bs theta_s - lever_sun_carrier theta_c``, along the ring mesh's
    ``delta = -r_bp theta_p + r_br theta_r - lever_ring_carrier theta_c`` (absolute angles, one sense of
    rotation for the whole stage; :mod:`gearcli.model.elements.planet_mesh`). ``unit_speeds``: each member's
    speed for a unit speed of the input member (Willis)."""

    fixed: str
    input: str
    output: str
    planets: int
    sun_teeth: int
    planet_teeth: int
    ring_teeth: int
    base_radius_sun_m: float
    base_radius_planet_m: float
    base_radius_ring_m: float
    lever_sun_carrier_m: float  # r_c cos(alpha_wt,sp) = r_bs + r_bp
    lever_ring_carrier_m: float  # r_c cos(alpha_wt,rp) = r_br - r_bp
    third_inertia_kg_m2: float  # the member neither driven nor output (unused when it is the held one)
    planet_inertia_kg_m2: float
    sun_mesh: MeshSpec
    ring_mesh: MeshSpec
    unit_speeds: tuple[float, float, float]  # sun, carrier, ring
    planet_angles_rad: tuple[float, ...] = ()  # per planet, its position psi_j on the carrier; empty: 2 pi j / N
    planet_offsets_m: tuple[float, ...] = ()  # per planet, a position error along its sun mesh (a constant TE)
    ring_contact_phase_cycles: float = 0.0  # planet 1's ring mesh contact-line phase against its sun mesh's
    # (time-varying stiffness; gearcli.model.planet_phasing)
    # losses (docs/planetary.md): each planet mesh loses in the carrier's frame with its law's efficiency eta_m;
    # the static (driving-side) force of a sun and of a ring mesh over the lossless one, and the stage's power
    # efficiency forward and with the load reversed
    sun_force_factor: float = 1.0
    ring_force_factor: float = 1.0
    efficiency: float = 1.0
    reverse_efficiency: float = 1.0
    # the two force factors in the other power flow, of the other load sign (a load law whose torque turns sign
    # at the operating point: gearcli.model.linear.operating_line_forces_N)
    other_sun_force_factor: float = 1.0
    other_ring_force_factor: float = 1.0

    def mesh_phase_cycles(self, j: int, gear: str) -> float:
        """Planet j's mesh phase against planet 1's, in mesh cycles (Parker & Lin 2004): z_s psi_j / 2 pi for
        its sun mesh, -z_r psi_j / 2 pi for its ring mesh."""
        psi = self.planet_angles_rad[j] if self.planet_angles_rad else 2.0 * math.pi * j / self.planets
        return (self.sun_teeth if gear == "sun" else -self.ring_teeth) * psi / (2.0 * math.pi)

    def unit_speed(self, member: str) -> float:
        return self.unit_speeds[MEMBERS.index(member)]

    @property
    def third(self) -> str:
        return next(m for m in MEMBERS if m not in (self.input, self.output))

    @property
    def planet_unit_speed(self) -> float:
        """The planets' absolute speed for a unit input speed: r_bp w_p = r_c cos(a_sp) w_c - r_bs w_s."""
        w_s, w_c = self.unit_speed("sun"), self.unit_speed("carrier")
        return (self.lever_sun_carrier_m * w_c - self.base_radius_sun_m * w_s) / self.base_radius_planet_m
