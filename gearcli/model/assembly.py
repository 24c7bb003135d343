"""Bodies and connectors of one scene by index, and where every unknown lives in the state vector.

This module is the only one that knows indices. A connector is an element (:mod:`gearcli.model.elements`)
placed between bodies it names by index, two or more, with a lever on each (a mesh: base radii, deflection
along the line of action; a spring: 1, deflection = twist): ``delta_c = sum_j s_j r_j theta_{bodies[j]}``,
and its force ``F`` puts ``-s_j r_j F`` on body ``bodies[j]`` (two bodies: ``delta = r_a theta_a - r_b
theta_b``, ``-r_a F`` on a, ``+r_b F`` on b). Every consumer scatters forces to bodies by these indices.

A parallel-stage reducer (:func:`_chain`) numbers its bodies in power-flow order,

    [motor]  shaft 1  [shaft k+1 gear end | shaft k+1 pinion end] ...  last shaft  [drum]

and its connector c joins bodies (c, c+1): the input coupling, the meshes, the flexible shafts, the load
coupling. ``ModelSpec.elements`` adds further elements between any of these bodies.

State vector (its slices and indices: :class:`gearcli.model.layout.StateLayout`, :attr:`Layout.state`; deflection coordinates, not absolute angles: a mesh deflection of ~1e-5 m formed as the
difference of two ~1-10 m products of radius and angle would lose 5-6 of its 16 digits, so it is
integrated directly, ``delta_c' = sum_j s_j r_j w_{bodies[j]}``):

    y = [delta_0 .. delta_{nc-1} | w of the free bodies | theta_0 (torque drive, time-varying meshes only)
         | W_in, W_load, E_damp (, W_el_tv)]

With ``drive = "speed"`` body 0 has no state (its motion is the analytic STEP profile); with
``drive = "torque"`` it is free. The drive acts on body 0, the load on the last body. Angles, needed only
for the phase of phase-dependent elements (time-varying stiffness, stiffness harmonics, transmission
error) and for an input torque ripple, come from theta_0 (analytic, or the extra state) along a tree of
two-body connectors (:attr:`Layout.tree`): ``theta_b = (r_a theta_a - delta_c) / r_b``.

Each element's row is completed here once the bodies are known (:func:`_assembled`): a mesh with
``damping_ratio`` gets ``c = 2 zeta sqrt(k_lin m_e)``, k_lin the mesh's dF/d delta at the static load,
``m_e = 1 / sum_j r_j^2 / J_j`` from the bodies it joins (a speed-driven body counts as infinitely heavy).
The static forces are still those of the chain (:mod:`gearcli.model.linear`).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import field, replace
from functools import cached_property

import numpy as np

from gearcli.core.records import record
from gearcli.model.elements import (
    MAX_BODIES,
    N_PARAM,
    kind_of,
    law_of,
    machine,
    torque,
)
from gearcli.model.layout import StateLayout
from gearcli.model.parts import STAGE_ROLES, Body, Connector, _row
from gearcli.model.spec import DriveSpec, LoadSpec, MeshSpec, ModelSpec

#: a lossy element's power-flow sign is no wider than 1/SIGN_SHARPNESS of its nominal pitch-line speed, so that at that
#: speed it is 1 to tanh(12) = 1 - 2 e^-24 = 1 - 7.6e-11 and a settled run loses (1 - eta) of its power as rated
SIGN_SHARPNESS = 12.0


@record
class AngleRow:
    """A body's angle where no tree connector gives it (:attr:`Layout.angle_rows`):
    ``theta_b = sum coef theta_j (bodies) + sum coef delta_c (deflections) + constant``."""

    bodies: tuple[tuple[int, float], ...]  # (earlier body, coefficient)
    deflections: tuple[tuple[int, float], ...]  # (connector, coefficient)
    constant: float


def _chain(spec: ModelSpec) -> tuple[list[Body], list[Connector]]:
    """The parallel-stage drivetrain: a chain of bodies, each connector joining the last body to a new one."""
    bodies: list[Body] = []
    conns: list[Connector] = []

    def body(inertia: float, label: str, ratio: float | None = None) -> None:
        if ratio is None:
            ratio = 1.0 if not conns else bodies[-1].ratio * conns[-1].ra / conns[-1].rb
        bodies.append(Body(float(inertia), label, ratio))

    def join(name: str, part, ra: float, rb: float, label: str, role: str, index: int = -1) -> None:
        kind = kind_of(name)
        n = len(bodies)
        conns.append(Connector(kind, (n - 1, n), (ra, rb), _row(law_of(kind).pack(part)), label, index, role))

    if spec.motor is not None:
        body(spec.motor.inertia_kg_m2, "motor")
        join("spring", spec.motor.coupling, 1.0, 1.0, "input coupling", "coupling")
    body(spec.inertias_kg_m2[0], "shaft 1")
    for k, m in enumerate(spec.meshes):
        flex = spec.shafts[k] if k < len(spec.shafts) else None
        own = spec.stage_models[k] if k < len(spec.stage_models) else None
        stage = _Pair(m, join, flex is not None) if own is None else own
        stage.place(k, bodies, conns, body, spec.inertias_kg_m2[k + 1] if flex is None else flex.gear_end_kg_m2)
        if flex is None:
            continue
        join("spring", flex.spring, 1.0, 1.0, f"shaft {k + 2}", "shaft", k + 1)
        body(spec.inertias_kg_m2[k + 1] - flex.gear_end_kg_m2, f"shaft {k + 2} pinion end")
    if spec.drum is not None:
        join("spring", spec.drum.coupling, 1.0, 1.0, "load coupling", "coupling")
        body(spec.drum.inertia_kg_m2, "drum")
    for e in spec.elements:  # further elements between bodies of the chain, by body index
        kind = kind_of(e.name)
        conns.append(Connector(kind, tuple(e.bodies), tuple(e.radii), _row(law_of(kind).pack(e.part)), e.label))
        if not all(0 <= b < len(bodies) for b in e.bodies):
            raise ValueError(f"element {e.label!r} joins bodies {e.bodies}; the scene has bodies 0 to {len(bodies) - 1}")
    return bodies, _loss_widths(spec, bodies, _assembled(spec, bodies, conns))


@record
class _Pair:
    """A stage that is one pair mesh between its input shaft's body and a new body (the chain's own stage; a
    kind with a model of its own gives ``ModelSpec.stage_models``)."""

    mesh: MeshSpec
    join: Callable[..., None]
    flexible_output: bool  # the output shaft is flexible: this body is its gear end
    efficiency: float = 1.0  # the mesh's losses are its connector's
    reverse_efficiency: float = 1.0

    def place(self, k: int, bodies: list[Body], conns: list[Connector], body: Callable[..., None],
              out_inertia: float) -> None:
        m = self.mesh
        self.join("mesh", m, m.base_radius_pinion_m, m.base_radius_gear_m, f"stage {k + 1} mesh", "mesh", k)
        body(out_inertia, f"shaft {k + 2} gear end" if self.flexible_output else f"shaft {k + 2}")


def _loss_widths(spec: ModelSpec, bodies: list[Body], conns: list[Connector]) -> list[Connector]:
    """Connectors with the power scale W of every lossy element's power-flow sign filled in (its loss hook's
    ``with_loss_width``): W = F x ``LOSS_WIDTH`` x the larger of the nominal pitch-line speed v of its driving side
    and its vibration speed (:func:`loss_speeds`), the latter no more than v / (:data:`SIGN_SHARPNESS` x ``LOSS_WIDTH``)
    so that W / F stays within v / SIGN_SHARPNESS (floored at 1e-9 m/s). The nominal speed alone vanishes with the drive's: at 0.003 rpm the sign switched over 1e-8 m/s while the
    run-up's vibration swung the pitch line through zero at ~0.1 m/s, each crossing a near-step of (1 - eta) of the
    force (docs/numerics.md "Losses at crawl speeds")."""
    out = []
    for x in conns:
        if x.lossy:
            F, v, v_vib = loss_speeds(spec, bodies, x)
            lw = x.element.LOSS_WIDTH
            v = max(v, min(v_vib, v / (SIGN_SHARPNESS * lw)), 1e-9)
            x = replace(x, params=_row(x.element.with_loss_width(x.params, lw * F * v)))
        out.append(x)
    return out


def loss_speeds(spec: ModelSpec, bodies: Sequence[Body], x: Connector) -> tuple[float, float, float]:
    """(F, v, v_vib) of a lossy element: its static line force (at least 1 N), the nominal pitch-line speed of its
    driving side (``loss_sides``) and the speed of its own vibration: the static deflection its law's tangent gives
    at F (a mesh's normal approach, cos beta_b times its transverse deflection: a scale) times its own
    angular frequency sqrt(k / m_e) (k its tangent stiffness at F, ``m_e`` the equivalent mass of the bodies it
    joins, a speed-driven input body infinitely heavy), the speed whose kinetic energy m_e v^2 equals k delta^2
    (0 where it carries no load). Where v_vib > v the vibration reverses the power flow again and again."""
    if x.load_body >= 0:  # a planet mesh: the static force of its share of the output torque
        F = max(abs(spec.load.torque_Nm * bodies[-1].ratio / bodies[x.load_body].ratio * x.load_lever), 1.0)
    else:
        F = max(abs(spec.load.torque_Nm * bodies[-1].ratio / bodies[x.b].ratio / x.rb), 1.0)
    va = None
    for body, k in x.loss_speeds[0]:
        va = k * bodies[body].ratio if va is None else va + k * bodies[body].ratio
    stiffness, _, delta = x.element.tangent(x.params, F, False)
    mobility = _ordered_sum([0.0 if (j == 0 and spec.drive.kind == "speed") else lever**2 / bodies[j].inertia
                             for j, lever in zip(x.bodies, x.radii, strict=True)])
    v_vib = abs(delta) * math.sqrt(stiffness * mobility) if stiffness > 0.0 and mobility > 0.0 else 0.0
    return F, abs((va or 0.0) * spec.drive.speed_rad_s), v_vib


def _assembled(spec: ModelSpec, bodies: list[Body], conns: list[Connector]) -> list[Connector]:
    """Each element's row once the bodies are known (:func:`ElementLaw.assembled`): the static force it
    carries and the equivalent mass ``m_e = 1 / sum_j r_j^2 / J_j`` of the bodies it joins (a speed-driven
    body counts as infinitely heavy). A ``damping_ratio`` mesh gets its viscous damping here."""
    out = []
    losses = power_path_loss_factors(spec, conns)
    for x, loss in zip(conns, losses, strict=True):
        # the static force on the power path, with the losses after it (as gearcli.model.linear.static_forces;
        # a further element: none): a damping_ratio mesh's k_lin is the tangent at the force it carries
        F = abs(spec.load.torque_Nm * bodies[-1].ratio / bodies[x.b].ratio / x.rb) * loss if x.role else 0.0
        if x.load_body >= 0:  # a planet mesh: its share of the planetary's output torque
            F = abs(spec.load.torque_Nm * bodies[-1].ratio / bodies[x.load_body].ratio * x.load_lever) * loss
        floor = _linearisation_floor(spec, x)
        if floor > 0.0:
            x = replace(x, min_line_force=floor)
        mobility = [0.0 if (j == 0 and spec.drive.kind == "speed") else r**2 / bodies[j].inertia
                    for j, r in zip(x.bodies, x.radii, strict=True)]
        row = x.element.assembled(x.params, max(F, floor), 1.0 / _ordered_sum(mobility))
        if row is not x.params:
            x = replace(x, params=_row(row))
        out.append(x)
    return out


def _linearisation_floor(spec: ModelSpec, x: Connector) -> float:
    """The line force below which mesh ``x`` is linearised at that force (:attr:`MeshSpec.linearisation_line_force_N`:
    an iso6336 law's calibration load, where its tangent is ISO's k_n); 0 for every other connector."""
    if x.role not in ("mesh", "planet") or x.index < 0:
        return 0.0
    own = spec.stage_models[x.index] if x.index < len(spec.stage_models) else None
    if own is None:
        return spec.meshes[x.index].linearisation_line_force_N if x.role == "mesh" else 0.0
    mesh = getattr(own, f"{x.gear}_mesh", None) if x.gear else None
    return float(getattr(mesh, "linearisation_line_force_N", 0.0))


def power_path_loss_factors(spec: ModelSpec, conns: list[Connector], forward: bool | None = None) -> list[float]:
    """Per connector, what the losses between it and the load multiply its static force by: the product of
    1/eta of the lossy connectors (and lossy stage models) after it on the power path, and its own (the force of a
    lossy mesh is its driving side's: the pinion's); for a reversed load, whose power flows from the output, eta of
    those after it and not its own (its driving side is then the gear, which gets the law's whole force: f_b = f
    at sigma = -1, docs/physics.md "Stage efficiency in the dynamics"). A planet mesh's own loss is in its share of the output torque; its stage's loss counts before the
    stage. 1 everywhere when no connector loses (a stage model's own efficiency then counts nowhere either).
    ``forward``: the power flow's direction where it is not the nominal load's (a load law that changes sign)."""
    forward = spec.load.torque_Nm >= 0 if forward is None else forward
    out = [1.0] * len(conns)
    if not any(x.lossy for x in conns):
        return out
    factor, pending = 1.0, None
    for c in range(len(conns) - 1, -1, -1):
        x = conns[c]
        if pending is not None and not (x.load_body >= 0 and x.index == pending):
            # past the last planet mesh of a stage model (a planetary straight after another one included)
            p = spec.stage_models[pending]
            assert p is not None
            factor *= 1.0 / p.efficiency if forward else p.reverse_efficiency
            pending = None
        if x.load_body >= 0:
            out[c] = factor
            pending = x.index
            continue
        if x.lossy and forward:  # its driving side is the pinion's: its own loss is in its force
            factor *= 1.0 / x.efficiency
        out[c] = factor
        if x.lossy and not forward:  # its driving side is the gear's: only the meshes upstream lose its loss
            factor *= x.efficiency
    return out


def _ordered_sum(values: list[float]) -> float:
    total = values[0]
    for v in values[1:]:
        total = total + v
    return total


@record
class ModelArrays:
    """The model as plain arrays (picklable), for engines that interpret it (one compiled kernel for
    every scene). Kinds and parameter rows: :mod:`gearcli.model.elements`."""

    body_inertia: np.ndarray  # float64[N]
    conn_kind: np.ndarray  # int64[nc]: the element kind (gearcli.model.elements registry)
    conn_bodies: np.ndarray  # int64[nc, MAX_BODIES]: the bodies each connector joins, -1 padded
    conn_levers: np.ndarray  # float64[nc, MAX_BODIES]: signed levers s_j r_j (delta = sum lever theta), 0 padded
    conn_param: np.ndarray  # float64[nc, N_PARAM]
    body_tree: np.ndarray  # int64[N]: the two-body connector whose deflection gives a body's angle, -1 for body 0
    # (and a body nothing reaches), -2 for a body whose angle is its row of body_angle_row
    drive_kind: int  # 0 speed, 1 torque, 2 motor
    drive_value: float  # rad/s or N m
    drive_ramp_s: float
    drive_ripple: np.ndarray  # float64[R, 2]: amplitude (fraction), order per input revolution
    drive_angle_rad: float  # a speed drive's angle at t = 0 (sweep continuation)
    load_value_Nm: float
    load_ramp_s: float
    load_fluct: np.ndarray  # float64[F, 2]: amplitude (fraction), frequency_Hz
    load_clock_s: float  # the fluctuation's time at t = 0 (sweep continuation)
    motor_row: np.ndarray  # float64[M]: the motor's curve and start (gearcli.model.elements.machine); empty: none
    load_law: np.ndarray  # float64[L]: a speed-dependent load's law; empty: constant torque
    n_states: int
    i_delta0: int
    i_omega0: int
    i_theta: int  # -1 when there is no angle state
    i_quad: int
    atol: np.ndarray  # float64[n_states] at the scene's rtol (quadratures excluded: 1e20)
    i_quadratures: np.ndarray  # int64[4]: the state of each of layout.QUADRATURES (StateLayout.kernel_quadratures), -1 none
    # a lossy element's loss geometry (its loss hook, Connector.loss_speeds / loss_share; a lossless one: -1 / 0):
    conn_loss_bodies: np.ndarray  # int64[nc, 2, MAX_BODIES]: the bodies whose speeds make v_a (row 0) and v_b (row 1)
    conn_loss_speeds: np.ndarray  # float64[nc, 2, MAX_BODIES]: their coefficients, v = sum k w_body
    conn_loss_shares: np.ndarray  # float64[nc, MAX_BODIES, 2]: per slot, its shares of f_a and of f_b
    # float64[N, N + nc + 1]: Layout.angle_rows (body angles, deflections, constant); empty (0, 0) for none
    body_angle_row: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))


@record
class Layout:
    """Bodies, connectors and the state vector of one scene."""

    spec: ModelSpec
    bodies: tuple[Body, ...] = field(init=False)
    connectors: tuple[Connector, ...] = field(init=False)

    def __post_init__(self) -> None:
        bodies, conns = _chain(self.spec)
        object.__setattr__(self, "bodies", tuple(bodies))
        object.__setattr__(self, "connectors", tuple(conns))

    @classmethod
    def of(cls, spec: ModelSpec) -> Layout:
        return cls(spec)

    @property
    def drive(self) -> DriveSpec:
        return self.spec.drive

    @property
    def load(self) -> LoadSpec:
        return self.spec.load

    @property
    def n_bodies(self) -> int:
        return len(self.bodies)

    @property
    def n_conn(self) -> int:
        return len(self.connectors)

    @cached_property
    def inertias(self) -> tuple[float, ...]:
        return tuple(b.inertia for b in self.bodies)

    # ------------------------------------------------------------------------------- element roles
    @cached_property
    def stage_conn(self) -> tuple[int, ...]:
        """Connector index of each stage's connector (its mesh; a belt's span), in stage order."""
        return tuple(c for c, x in enumerate(self.connectors) if x.role in STAGE_ROLES)

    @property
    def shaft_body(self) -> tuple[int, ...]:
        """Body of each reducer shaft: shaft 1 the input pinion's, the others their gear end."""
        first = self.connectors[self.stage_conn[0]]
        return ((first.chain_in if first.chain_in >= 0 else first.a),) + tuple(
            x.load_body if x.load_body >= 0 else x.b for x in (self.connectors[c] for c in self.stage_conn))

    @property
    def shaft_conn(self) -> dict[int, int]:
        """Reducer shaft (0-based) -> its spring connector, for the flexible shafts."""
        return {x.index: c for c, x in enumerate(self.connectors) if x.role == "shaft"}

    def conn_named(self, label: str) -> int | None:
        return next((c for c, x in enumerate(self.connectors) if x.label == label), None)

    @property
    def motor_body(self) -> int | None:
        return 0 if self.spec.motor is not None else None

    @property
    def drum_body(self) -> int | None:
        return self.n_bodies - 1 if self.spec.drum is not None else None

    # --------------------------------------------------------------------------------------- flags
    @cached_property
    def speed_drive(self) -> bool:
        return self.drive.kind == "speed"

    @cached_property
    def motor_drive(self) -> bool:
        return self.drive.kind == "motor"

    @cached_property
    def motor_row(self) -> tuple[float, ...]:
        """The motor's row (:mod:`gearcli.model.elements.machine`) of a motor drive; empty otherwise."""
        motor = self.drive.motor
        return machine.motor_row(motor) if self.motor_drive and motor is not None else ()

    @cached_property
    def load_law(self) -> tuple[float, ...]:
        """The load's speed law row (empty: a constant torque), on the last body's nominal speed."""
        w_n = self.bodies[-1].ratio * self.drive.speed_rad_s
        # a table's torques over the (signed) reference torque: T_L = torque_Nm g(w) is the table's torque
        return machine.load_row(self.load.speed_exponent, w_n, self.load.table, self.load.torque_Nm or 1.0)

    def train_efficiency(self, forward: bool = True) -> float:
        """The power efficiency from the input to the output: every lossy pair mesh's eta, every stage model's
        (a planetary's planet meshes lose eta_m each, the stage eta as a whole); the load reversed: the stages'
        efficiencies with the power flowing back."""
        out = math.prod(x.efficiency for x in self.connectors if x.lossy and x.load_body < 0)
        for p in self.spec.stage_models:
            if p is not None:
                out *= p.efficiency if forward else p.reverse_efficiency
        return out

    @cached_property
    def n_lossy(self) -> int:
        return sum(x.lossy for x in self.connectors)

    @cached_property
    def n_tv(self) -> int:
        return sum(x.time_varying for x in self.connectors)

    @cached_property
    def ripple(self) -> tuple[float, ...]:
        """The input torque ripple row (:mod:`gearcli.model.elements.torque`); empty for none."""
        return torque.flat(self.drive.ripple)

    @cached_property
    def fluctuation(self) -> tuple[float, ...]:
        """The load fluctuation row; empty for none."""
        return torque.flat(self.load.fluctuation)

    @cached_property
    def needs_angles(self) -> bool:
        return any(x.phased for x in self.connectors) or bool(self.ripple)

    @cached_property
    def last_angle_body(self) -> int:
        """The last body whose angle a phase-dependent mesh needs (its pinion's body); -1 for none."""
        return max((x.a for x in self.connectors if x.phased), default=-1)

    @cached_property
    def has_theta_state(self) -> bool:
        return self.needs_angles and not self.speed_drive

    # ------------------------------------------------------------------------------------- indices
    @cached_property
    def state(self) -> StateLayout:
        """Where every unknown lives in the state vector: ask it, never count (:mod:`gearcli.model.layout`)."""
        return StateLayout(n_conn=self.n_conn, n_bodies=self.n_bodies, first_free=1 if self.speed_drive else 0,
                           theta=self.has_theta_state, n_quad=3 + int(self.n_tv > 0))

    @property
    def free_bodies(self) -> range:
        return range(self.state.first_free, self.n_bodies)

    # the state's indices, for short: each is the StateLayout's
    def i_delta(self, c: int) -> int:
        return self.state.delta(c)

    def i_omega(self, body: int) -> int | None:
        """State index of a body's speed; None for the speed-driven input body."""
        return self.state.omega(body)

    @property
    def i_theta(self) -> int | None:
        return self.state.i_theta

    @property
    def i_quad(self) -> int:
        return self.state.i_quad

    @property
    def n_quad(self) -> int:
        return self.state.n_quad

    @property
    def n_states(self) -> int:
        return self.state.n_states

    @property
    def tree(self) -> tuple[int, ...]:
        """Per body, the two-body connector that gives its angle from an earlier body's,
        ``theta_b = (r_a theta_a - delta_c) / r_b`` (the first connector with ``b`` as its second body and
        an earlier first body); -1 for body 0 and for a body no such connector reaches (a body with an
        :attr:`angle_rows` row gets its angle there)."""
        out = [-1] * self.n_bodies
        for c, x in enumerate(self.connectors):
            if x.load_body >= 0:  # a planet mesh: the planet's and the members' angles are coupled in pairs
                continue
            if len(x.bodies) == 2 and 0 <= x.a < x.b and out[x.b] < 0:
                out[x.b] = c
        return tuple(out)

    @cached_property
    def angle_rows(self) -> dict[int, AngleRow]:
        """The angle of every body the tree does not reach but the kinematics fix (a planetary's output member,
        its planets), as a linear combination of earlier bodies' angles and connector deflections.

        Every connector's deflection is ``delta_c = sum_j lever_j theta_{bodies[j]} + e_c`` exactly (it is
        integrated from the speeds; ``e_c`` its initial deflection), so for a body ``b`` outside the tree the
        connectors that join only bodies whose angle is known (K, below ``b``) or not (U, at most ``b``) give
        ``A_U theta_U = delta - e - A_K theta_K``; where that fixes ``theta_b`` (the least-squares solution's
        row of ``b`` is exact: ``b`` in the row space of ``A_U``), ``theta_b = pinv(A_U)[b] (delta - e - A_K
        theta_K)``. A planetary's output angle so follows its input member's angle and all its planet meshes'
        deflections, whatever the stage's arrangement; a mesh after it is phased on its own input body's
        angle. Bodies are taken in index order, so a row reads only bodies computed before it."""
        tree = self.tree
        known: set[int] = {0}
        rows: dict[int, AngleRow] = {}
        for b in range(1, self.n_bodies):
            c = tree[b]
            if c >= 0:
                if self.connectors[c].a in known:
                    known.add(b)
                continue
            unknown = [u for u in range(1, b + 1) if u not in known]
            conns = [c for c, x in enumerate(self.connectors)
                     if any(u in x.bodies for u in unknown)
                     and all(j in known or j in unknown or lever == 0.0 for j, lever in zip(x.bodies, x.levers, strict=True))]
            if not conns:
                continue
            col = {u: i for i, u in enumerate(unknown)}
            A = np.zeros((len(conns), len(unknown)))
            for r, c in enumerate(conns):
                for j, lever in zip(self.connectors[c].bodies, self.connectors[c].levers, strict=True):
                    if j in col:
                        A[r, col[j]] += lever
            P = np.linalg.pinv(A)
            if not np.allclose(P[col[b]] @ A, np.eye(len(unknown))[col[b]], rtol=0.0, atol=1e-9):
                continue  # the kinematics leave this body's angle free
            g = P[col[b]]
            bodies_coef: dict[int, float] = {}
            for r, c in enumerate(conns):
                for j, lever in zip(self.connectors[c].bodies, self.connectors[c].levers, strict=True):
                    if j in known and lever != 0.0:
                        bodies_coef[j] = bodies_coef.get(j, 0.0) - g[r] * lever
            rows[b] = AngleRow(tuple(sorted(bodies_coef.items())),
                               tuple((c, float(g[r])) for r, c in enumerate(conns) if g[r] != 0.0),
                               -float(sum(g[r] * self.connectors[c].initial_deflection for r, c in enumerate(conns))))
            known.add(b)
        return rows

    def angle_gradient(self, body: int) -> dict[int, float]:
        """d(theta_body)/dy as {column: coefficient}: theta_b = (r_a theta_a - delta_c) / r_b along the tree, or a
        body's :attr:`angle_rows` row (ValueError for a body whose angle nothing gives)."""
        if body == 0:
            return {self.state.i_theta: 1.0} if self.state.i_theta is not None else {}
        c = self.tree[body]
        if c >= 0:
            x = self.connectors[c]
            grad = {col: x.ra / x.rb * v for col, v in self.angle_gradient(x.a).items()}
            grad[self.state.delta(c)] = grad.get(self.state.delta(c), 0.0) - 1.0 / x.rb
            return grad
        row = self.angle_rows.get(body)
        if row is None:
            raise ValueError(f"nothing gives the angle of body {body} ({self.bodies[body].label})")
        out: dict[int, float] = {}
        for j, coef in row.bodies:
            for col, v in self.angle_gradient(j).items():
                out[col] = out.get(col, 0.0) + coef * v
        for c, coef in row.deflections:
            out[self.state.delta(c)] = out.get(self.state.delta(c), 0.0) + coef
        return out

    def angle_row_matrix(self) -> np.ndarray:
        """:attr:`angle_rows` as one dense array (the compiled kernel's), (n_bodies, n_bodies + n_conn + 1): per
        row body the coefficients of the body angles, then of the deflections, then the constant; zero
        elsewhere."""
        M = np.zeros((self.n_bodies, self.n_bodies + self.n_conn + 1))
        for b, row in self.angle_rows.items():
            for j, coef in row.bodies:
                M[b, j] = coef
            for c, coef in row.deflections:
                M[b, self.n_bodies + c] = coef
            M[b, -1] = row.constant
        return M

    def acting_on(self, body: int) -> list[tuple[int, int]]:
        """(connector, slot) of every connector that acts on ``body``, in connector order."""
        return [(c, j) for c, x in enumerate(self.connectors) for j, b in enumerate(x.bodies) if b == body]

    def body_speeds(self, y: np.ndarray, w0) -> np.ndarray:
        """Speeds of all bodies from states ``y`` (n_states, ...) and the input body's ``w0``."""
        free = y[self.state.speeds]
        return np.vstack([np.asarray(w0)[None, ...], free]) if self.speed_drive else free

    def arrays(self, atol: np.ndarray) -> ModelArrays:
        conns = self.connectors
        nc = len(conns)
        param = np.zeros((nc, N_PARAM))
        bodies = np.full((nc, MAX_BODIES), -1, dtype=np.int64)
        levers = np.zeros((nc, MAX_BODIES))
        loss_bodies = np.full((nc, 2, MAX_BODIES), -1, dtype=np.int64)
        loss_speeds = np.zeros((nc, 2, MAX_BODIES))
        loss_shares = np.zeros((nc, MAX_BODIES, 2))
        for c, x in enumerate(conns):
            param[c] = x.params + (0.0,) * (N_PARAM - len(x.params))
            bodies[c, :len(x.bodies)] = x.bodies
            levers[c, :len(x.bodies)] = x.levers
            if x.lossy:  # its loss hook's geometry, as the generated Python reads it
                for side, terms in enumerate(x.loss_speeds):
                    for k, (body, coef) in enumerate(terms):
                        loss_bodies[c, side, k], loss_speeds[c, side, k] = body, coef
                for j in range(len(x.bodies)):
                    loss_shares[c, j] = x.loss_share(j)
        drive = self.drive
        i_omega0, i_theta, i_quad = self.state.kernel_offsets  # the compiled kernel's ipar (gearcli.engine.pack)
        return ModelArrays(
            body_inertia=np.array(self.inertias), conn_kind=np.array([x.kind for x in conns], dtype=np.int64),
            conn_bodies=bodies, conn_levers=levers, conn_param=param,
            body_tree=np.array([-2 if b in self.angle_rows else c for b, c in enumerate(self.tree)], dtype=np.int64),
            body_angle_row=self.angle_row_matrix() if self.angle_rows else np.zeros((0, 0)),
            drive_kind=0 if self.speed_drive else 2 if self.motor_drive else 1,
            drive_value=drive.speed_rad_s if self.speed_drive else drive.torque_Nm, drive_ramp_s=drive.ramp_s,
            drive_ripple=np.array(self.ripple, float).reshape(-1, 2), drive_angle_rad=float(drive.angle_rad),
            load_value_Nm=self.load.torque_Nm, load_ramp_s=self.load.ramp_s,
            load_fluct=np.array(self.fluctuation, float).reshape(-1, 2), load_clock_s=float(self.load.clock_s),
            motor_row=np.array(self.motor_row, float), load_law=np.array(self.load_law, float),
            n_states=self.state.n_states, i_delta0=self.state.deflections.start, i_omega0=i_omega0, i_theta=i_theta,
            i_quad=i_quad, atol=np.asarray(atol, float),
            i_quadratures=np.array(self.state.kernel_quadratures, dtype=np.int64), conn_loss_bodies=loss_bodies,
            conn_loss_speeds=loss_speeds, conn_loss_shares=loss_shares)
