"""A planetary stage's bodies and connectors in the scene (:mod:`gearcli.model.assembly` calls it while it
numbers the chain): the third member, the planets, the output member's body, and each planet's sun and ring
mesh with its levers, its phase and (with losses) its loss geometry (docs/physics.md, "Planetary stages";
docs/planetary.md, "Losses and the moment balance")."""

from __future__ import annotations

import math
from dataclasses import replace

from gearcli.model.elements import kind_of, law_of, mesh
from gearcli.model.parts import Body, Connector, _row
from gearcli.model.planet_spec import PlanetarySpec


def place_planetary(p: PlanetarySpec, k: int, bodies: list[Body], conns: list[Connector], body, out_inertia: float) -> None:
    """A planetary stage after its input member's body (the last one): the third member (unless held), the
    planets, then the output member's body; each planet's sun and ring meshes (:class:`PlanetarySpec`).
    The output body turns in its own running direction (its levers carry the sign of its Willis speed); the
    other members and the planets in the input member's sense."""
    n_in, rho_in = len(bodies) - 1, bodies[-1].ratio
    sign_out = 1.0 if p.unit_speed(p.output) >= 0.0 else -1.0
    where: dict[str, tuple[int, float]] = {p.input: (n_in, 1.0)}
    if p.third != p.fixed:
        body(p.third_inertia_kg_m2, f"stage {k + 1} {p.third}", rho_in * p.unit_speed(p.third))
        where[p.third] = (len(bodies) - 1, 1.0)
    first_planet = len(bodies)
    for j in range(p.planets):
        body(p.planet_inertia_kg_m2, f"stage {k + 1} planet {j + 1}", rho_in * p.planet_unit_speed)
    body(out_inertia, f"shaft {k + 2}", rho_in * abs(p.unit_speed(p.output)))
    n_out = len(bodies) - 1
    where[p.output] = (n_out, sign_out)
    # static force of every planet mesh per unit output torque: N c_out F = T_out sign_out (lossless)
    c_out = {"sun": -p.base_radius_sun_m, "ring": -p.base_radius_ring_m,
             "carrier": p.base_radius_sun_m + p.base_radius_ring_m}[p.output]
    per_output = sign_out / (p.planets * c_out)
    for j in range(p.planets):
        planet = first_planet + j
        for gear, mesh_law, levers in (
                ("sun", p.sun_mesh, {"sun": p.base_radius_sun_m, "carrier": -p.lever_sun_carrier_m}),
                ("ring", p.ring_mesh, {"ring": p.base_radius_ring_m, "carrier": -p.lever_ring_carrier_m})):
            idx = [planet]
            lev = [p.base_radius_planet_m if gear == "sun" else -p.base_radius_planet_m]
            for member, lever in levers.items():
                if member in where:
                    b, sgn = where[member]
                    idx.append(b)
                    lev.append(sgn * lever)
            # the mesh phase is counted on the input member's angle (the chain's body, on the angle tree):
            # first in the connector, with a zero lever where it is not part of this mesh
            if n_in in idx:
                i = idx.index(n_in)
                idx.insert(0, idx.pop(i))
                lev.insert(0, lev.pop(i))
            else:
                idx.insert(0, n_in)
                lev.insert(0, 0.0)
            contact = p.ring_contact_phase_cycles if gear == "ring" else 0.0
            row = _row(_planet_loss_row(law_of(kind_of("mesh")).pack(
                _phased_mesh(mesh_law, p.mesh_phase_cycles(j, gear), p, contact)), p, gear, idx, planet, where))
            if len(idx) == 3:
                kind, radii = kind_of("planet_mesh"), tuple(lev)
            else:
                kind, radii = kind_of("mesh"), (lev[0], -lev[1])
            # planet 1's sun mesh stands for the stage where a stage has one mesh (role "mesh": its F_t, DTE,
            # stiffness and error estimate); every planet mesh has its own channels besides
            role = "mesh" if (j == 0 and gear == "sun") else "planet"
            offset = p.planet_offsets_m[j] if (gear == "sun" and p.planet_offsets_m) else 0.0
            factor = p.sun_force_factor if gear == "sun" else p.ring_force_factor
            conns.append(Connector(kind, tuple(idx), radii, row, f"stage {k + 1} planet {j + 1} {gear} mesh", k,
                                   role, n_out, per_output * factor, j, gear, n_in, offset))


def _planet_loss_row(row, p: PlanetarySpec, gear: str, idx: list[int], planet: int, where: dict[str, tuple[int, float]]):
    """A lossy planet mesh's row with its loss geometry (:func:`gearcli.model.elements.mesh.planet_loss_slots`):
    the slots of its sun or ring, planet and carrier, and the carrier's share of the sun's (ring's) side force,
    kappa_a = l_a / (l_a + l_b) with l_a = r_bs, l_b = r_bp (sun mesh) or l_a = r_br, l_b = -r_bp (ring mesh)."""
    if not mesh.lossy(row):
        return row
    l_a = p.base_radius_sun_m if gear == "sun" else p.base_radius_ring_m
    l_b = p.base_radius_planet_m if gear == "sun" else -p.base_radius_planet_m
    slot_a = idx.index(where[gear][0]) if gear in where else -1
    slot_c = idx.index(where["carrier"][0]) if "carrier" in where else -1
    return mesh.with_planet_loss(row, slot_a, idx.index(planet), slot_c, l_a / (l_a + l_b))


def _phased_mesh(mesh, offset_cycles: float, p: PlanetarySpec, contact_cycles: float = 0.0):
    """A planet mesh's law: the mesh phase counted on the input member's angle, z_eff theta_in / 2 pi with
    z_eff = z_s |w_s - w_c| / |w_in| (mesh cycles per input radian under rigid kinematics: the mesh frequency
    is z_s |w_s - w_c| / 2 pi), its harmonics and its contact-line stiffness shifted by the planet's phase
    offset; the contact lines of a ring mesh also by ``contact_cycles``, the ring mesh's phase against the
    same planet's sun mesh (:mod:`gearcli.model.planet_phasing`), and so are its error and stiffness harmonics: the
    mesh cycle they follow is the one its contact lines count (without it a planet's two errors cancelled on the
    planet modes, which then no mesh order could drive)."""
    z_eff = p.sun_teeth * abs(p.unit_speed("sun") - p.unit_speed("carrier")) / abs(p.unit_speed(p.input))
    shift = 2.0 * math.pi * (offset_cycles + contact_cycles)
    te_phase = tuple(list(mesh.transmission_error_phase_rad) + [0.0] * len(mesh.transmission_error_m))
    ks_phase = tuple(list(mesh.stiffness_harmonics_phase_rad) + [0.0] * len(mesh.stiffness_harmonics))
    return replace(mesh, pinion_teeth=z_eff, contact_phase_cycles=(offset_cycles + contact_cycles) % 1.0,
                   transmission_error_phase_rad=tuple(te_phase[i] + (i + 1) * shift
                                                      for i in range(len(mesh.transmission_error_m))),
                   stiffness_harmonics_phase_rad=tuple(ks_phase[i] + (i + 1) * shift
                                                       for i in range(len(mesh.stiffness_harmonics))))
