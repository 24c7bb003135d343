"""A scene's parts: a body and a connector (an element placed between bodies by index, with its levers).

Below ``assembly`` (the parallel-stage chain, the state vector) and ``planet_assembly`` (a planetary stage's
bodies and connectors), which both build them; neither imports the other's builder back.
"""

from __future__ import annotations

from functools import cached_property

from gearcli.core.records import record
from gearcli.model.elements import law_of, loses

#: the roles of the connector that stands for a stage (its forces, deflection and statistics), one per stage
STAGE_ROLES = ("mesh", "stage")


@record
class Body:
    """One rigid body of the chain: inertia, label and nominal speed ratio to the input body."""

    inertia: float  # kg m^2
    label: str  # "motor", "shaft 1", "shaft 2 gear end", "shaft 2 pinion end", "drum"
    ratio: float  # nominal speed over the input body's speed (rigid kinematics)


@record
class Connector:
    """One element placed in the scene: its kind (:mod:`gearcli.model.elements`), the bodies it joins by
    index and its lever on each (a mesh: base radii; a spring: 1), its parameter row, and its role."""

    kind: int
    bodies: tuple[int, ...]
    radii: tuple[float, ...]
    params: tuple[float, ...]  # the element's parameter row, as Python floats
    label: str  # "input coupling", "stage 1 mesh", "shaft 2", "load coupling"
    index: int = -1  # 0-based stage of a mesh or reducer shaft of a flexible shaft; -1 for couplings
    role: str = ""  # "mesh" (a stage's mesh), "stage" (a stage's connector that is no gear mesh: a belt's span,
    # its stage's forces and deflection as a mesh's are; STAGE_ROLES), "shaft" (a flexible reducer shaft),
    # "coupling", "planet" (a planet's sun or ring mesh), or "" (other)
    load_body: int = -1  # a planet mesh: its static force is T_L rho_N / rho[load_body] * load_lever
    load_lever: float = 0.0
    planet: int = -1  # a planet mesh: its planet (0-based) and which mesh ("sun" or "ring")
    gear: str = ""
    chain_in: int = -1  # a planet mesh: the body of its stage's input member (the reducer shaft before it)
    initial_deflection: float = 0.0  # a planet's position error along its sun mesh (m): delta - R theta
    min_line_force: float = 0.0  # a mesh linearised at a smaller |F| holds at this one (MeshSpec's
    # linearisation_line_force_N, set by the assembly)

    @property
    def element(self):
        """The element's law module (the registry's)."""
        return law_of(self.kind)

    @property
    def a(self) -> int:
        """The first body (a mesh's pinion: its phase is the element's)."""
        return self.bodies[0]

    @property
    def b(self) -> int:
        return self.bodies[1]

    @property
    def ra(self) -> float:
        return self.radii[0]

    @property
    def rb(self) -> float:
        return self.radii[1]

    @cached_property
    def levers(self) -> tuple[float, ...]:
        """Signed levers s_j r_j: delta = sum_j levers[j] theta_{bodies[j]}; body j takes -levers[j] F."""
        return tuple(s * r for s, r in zip(self.element.SIGNS, self.radii, strict=True))

    @cached_property
    def damped(self) -> bool:
        return self.element.damped(self.params)

    @cached_property
    def lossy(self) -> bool:
        """An element that loses (1 - eta) of the power it transmits (its loss hook, :data:`.elements.LOSS_HOOK`)."""
        return loses(self.element, self.params)

    @cached_property
    def efficiency(self) -> float:
        """eta of a lossy element; 1 otherwise."""
        return self.element.efficiency(self.params) if self.lossy else 1.0

    @property
    def loss_speeds(self) -> tuple[list[tuple[int, float]], list[tuple[int, float]]]:
        """A lossy element's pitch-line speeds as (body, coefficient) terms, ``v_a = sum k w_body`` and ``v_b``
        likewise, from its loss hook's sides (``loss_sides``): ``k = share lever`` on side a, ``-share lever``
        on side b."""
        side_a, side_b = self.element.loss_sides(self.params)
        lev = self.levers
        return ([(self.bodies[j], share * lev[j]) for j, share in side_a],
                [(self.bodies[j], -(share * lev[j])) for j, share in side_b])

    def loss_share(self, slot: int) -> tuple[float, float]:
        """(share of f_a, share of f_b) of the side force a lossy element puts on its body ``slot``; (0, 0):
        the law's own force (a lossless element's every slot)."""
        if not self.lossy:
            return 0.0, 0.0
        side_a, side_b = self.element.loss_sides(self.params)
        return (sum(s for j, s in side_a if j == slot), sum(s for j, s in side_b if j == slot))

    @cached_property
    def time_varying(self) -> bool:
        return self.element.time_varying(self.params)

    @cached_property
    def phased(self) -> bool:
        return self.element.phased(self.params)

    @cached_property
    def excited(self) -> bool:
        return self.element.excited(self.params)


def _row(values) -> tuple[float, ...]:
    return tuple(map(float, values))  # float(v) of each in order, in C (a point's model packs some 180 numbers)
