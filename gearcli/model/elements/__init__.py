"""Element types of the torsional model: each module owns one force law, written once.

A connector joins bodies (a, b) = (c, c+1) of the chain with radii (r_a, r_b): its deflection is
``delta = r_a theta_a - r_b theta_b``, its force ``F`` puts ``-r_a F`` on body a and ``+r_b F`` on body b.
Every connector module defines ``PARAMS`` (the names of its parameter row), ``pack(spec)`` (the row,
float64, padded to ``N_PARAM``) and

    force(P, d, dd, phi, wphi) -> (F, dF_dd, dF_ddd, dF_dphi, dF_dwphi, p_damp, p_elastic_tv, p_te)

in plain ``math`` on floats (so numba can compile it unchanged): ``P`` the parameter row (a tuple or
an array), ``d``/``dd`` the deflection and its rate, ``phi`` the mesh phase in mesh cycles,
``z_p theta_p / 2 pi``, and ``wphi = d phi/dt = z_p w_p / 2 pi`` its rate (both 0 for springs and for
meshes that do not depend on their phase; cycles rather than radians so that the phase is formed
exactly as before the element redesign: a rattling mesh is sensitive to its last bit),
``p_damp`` the power the element dissipates, ``p_elastic_tv`` the power into a time-varying spring,
``p_te`` the power a prescribed transmission error does on the bodies (``-F de/dt``; part of the input
work). The right-hand side, the Jacobian, the output channels and the linearisation all call it.
``power_gradient(P, d, dd, phi, wphi)`` gives the partials of the three power terms by
(d, dd, phi, wphi) (the Jacobian's energy rows), ``potential(P, d, phi)`` the stored elastic energy,
``static_deflection(P, F)`` the deflection that carries the force ``F`` in steady state.

Torques on the end bodies (input torque ripple, load fluctuation) are laws of :mod:`.torque`.
"""

from __future__ import annotations

KIND_SPRING = 0  # torsional spring-damper: couplings, flexible shafts
KIND_MESH = 1  # gear mesh along its transverse line of action (Adams IMPACT law)
N_HARM = 8  # transmission-error / stiffness harmonics per mesh
N_PARAM = 22 + 4 * N_HARM  # width of every parameter row (the mesh's: gearcli.model.elements.mesh.PARAMS)

KIND_NAMES = {KIND_SPRING: "spring", KIND_MESH: "mesh"}


def module_of(kind: int):
    """The element module of a connector kind."""
    from gearcli.model.elements import mesh, spring

    return {KIND_SPRING: spring, KIND_MESH: mesh}[kind]
