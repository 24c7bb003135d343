"""The state vector's layout: the one place that knows where each state sits.

``y = [deflections (one per connector) | speeds (one per free body) | input angle (a torque drive that needs
angles) | quadratures (the energy integrals, :data:`QUADRATURES`)]``. The generated Python, the compiled
kernel (through ``ipar``: the first speed, the angle, each quadrature), the outputs, the energy guard,
the solvers' tolerances, the periodic steady state and the shooting's variational block ask a
:class:`StateLayout` for their slices and indices; none counts them again.
"""

from __future__ import annotations

from gearcli.core.records import record

#: the energy quadratures, in state order (the last only with time-varying springs)
QUADRATURES = ("input_work_J", "load_work_J", "damping_loss_J", "elastic_work_tv_J")


@record
class StateLayout:
    """Slices and indices of one scene's state vector.

    ``n_conn`` connectors (one deflection each), ``n_bodies`` bodies of which the first ``first_free`` have no
    speed state (1: the speed-driven input body, else 0), ``theta`` whether the input angle is a state,
    ``n_quad`` quadratures (the first ``n_quad`` of :data:`QUADRATURES`)."""

    n_conn: int
    n_bodies: int
    first_free: int
    theta: bool
    n_quad: int

    # ------------------------------------------------------------------------------------- blocks
    @property
    def n_free(self) -> int:
        """Bodies with a speed state."""
        return self.n_bodies - self.first_free

    @property
    def deflections(self) -> slice:
        return slice(0, self.n_conn)

    @property
    def speeds(self) -> slice:
        """The free bodies' speeds, body ``first_free`` first."""
        return slice(self.n_conn, self.n_conn + self.n_free)

    @property
    def n_mechanical(self) -> int:
        """Deflections and speeds: the states a period maps and the shooting's variational equations follow."""
        return self.n_conn + self.n_free

    @property
    def mechanical(self) -> slice:
        return slice(0, self.n_mechanical)

    @property
    def i_theta(self) -> int | None:
        """The input angle's state (a torque drive whose meshes need angles); None otherwise."""
        return self.n_mechanical if self.theta else None

    @property
    def i_quad(self) -> int:
        """The first quadrature; every state before it carries the dynamics (step control)."""
        return self.n_mechanical + int(self.theta)

    @property
    def dynamic(self) -> slice:
        """The states that carry the dynamics (the Jacobian's block that matters, step control)."""
        return slice(0, self.i_quad)

    @property
    def quadratures(self) -> slice:
        return slice(self.i_quad, self.n_states)

    @property
    def n_states(self) -> int:
        return self.i_quad + self.n_quad

    # ------------------------------------------------------------------------------------ indices
    def delta(self, c: int) -> int:
        """The deflection of connector ``c``."""
        return c

    def omega(self, body: int) -> int | None:
        """The speed of ``body``; None for the speed-driven input body."""
        return None if body < self.first_free else self.n_conn + body - self.first_free

    def quadrature(self, name: str) -> int | None:
        """The state of quadrature ``name`` (one of :data:`QUADRATURES`); None when this scene has none (the
        work on time-varying springs without such a spring)."""
        j = QUADRATURES.index(name)
        return self.i_quad + j if j < self.n_quad else None

    @property
    def names(self) -> list[str]:
        """The generated Python's names of the states, in order."""
        names = [f"d{c}" for c in range(self.n_conn)] + [f"w{i}" for i in range(self.first_free, self.n_bodies)]
        if self.theta:
            names.append("th0")
        return names + [f"_q{j}" for j in range(self.n_quad)]

    # -------------------------------------------------------------------------- the compiled kernel
    @property
    def kernel_offsets(self) -> tuple[int, int, int]:
        """``ipar``'s offsets for the compiled kernel: (first speed, input angle or -1, first quadrature)."""
        return self.n_conn, -1 if self.i_theta is None else self.i_theta, self.i_quad

    @property
    def kernel_quadratures(self) -> tuple[int, ...]:
        """``ipar``'s quadrature offsets for the compiled kernel: each of :data:`QUADRATURES`' state
        (:meth:`quadrature`), -1 where this scene has none."""
        return tuple(-1 if (i := self.quadrature(name)) is None else i for name in QUADRATURES)

    # ------------------------------------------------------------------------ the variational block
    @property
    def n_augmented(self) -> int:
        """States of ``[y | Phi]``: the state and the ``d x d`` variational block of its mechanical states."""
        return self.n_states + self.n_mechanical**2

    @property
    def variational(self) -> slice:
        """``Phi`` in ``[y | Phi]``, column-major (column k: the response to a unit change of mechanical state k)."""
        return slice(self.n_states, self.n_augmented)
