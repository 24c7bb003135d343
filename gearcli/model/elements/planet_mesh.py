"""A planet's mesh with the sun or the ring when all three bodies move: planet, sun (or ring), carrier.

The same force law as :mod:`gearcli.model.elements.mesh` (the Adams IMPACT law or viscous damping, with
its excitation), on the deflection along the mesh's line of action with the carrier's motion in the
kinematics (absolute body angles, the planet's included):

    sun–planet:   delta = r_bp theta_p + r_bs theta_s - r_c cos(alpha_wt,sp) theta_c
    ring–planet:  delta = -r_bp theta_p + r_br theta_r - r_c cos(alpha_wt,rp) theta_c

(r_c cos alpha_wt,sp = r_bs + r_bp and r_c cos alpha_wt,rp = r_br - r_bp: the carrier term is what makes
the relative rotations theta_s - theta_c, theta_p - theta_c appear). The levers carry the signs (``SIGNS``
are all +1; :func:`gearcli.model.planet_assembly.place_planetary` gives the signed levers). The first body is the stage's
input member, whose angle is on the angle tree and sets the mesh phase ``z_eff theta_in / 2 pi``
(``pinion_teeth`` = z_eff = z_s |w_s - w_c| / |w_in|); where the input member is not part of the mesh it joins
with a zero lever. A mesh with fewer moving bodies is a plain :mod:`~gearcli.model.elements.mesh`.
"""

from __future__ import annotations

from gearcli.model.elements import adopt as _adopt
from gearcli.model.elements import mesh as _mesh

NAME = "planet_mesh"
SIGNS = (1.0, 1.0, 1.0)  # delta = sum_j r_j theta_j with signed levers r_j


_adopt(_mesh, globals())
