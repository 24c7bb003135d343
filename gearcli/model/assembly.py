"""The chain of bodies and connectors of one scene, and where every unknown lives in the state vector.

This module is the only one that knows indices. Bodies b = 0 .. N-1 in power-flow order:

    [motor]  shaft 1  [shaft k+1 gear end | shaft k+1 pinion end] ...  last shaft  [drum]

Connector c joins bodies (c, c+1): the input coupling, the meshes, the flexible shafts, the load
coupling, each with radii (r_a, r_b) so that its deflection is ``delta_c = r_a theta_c - r_b theta_{c+1}``
(a mesh: base radii, deflection along the line of action; a spring: r = 1, deflection = twist).

State vector (deflection coordinates, not absolute angles: a mesh deflection of ~1e-5 m formed as the
difference of two ~1-10 m products of radius and angle would lose 5-6 of its 16 digits, so it is
integrated directly, ``delta_c' = r_a w_c - r_b w_{c+1}``):

    y = [delta_0 .. delta_{nc-1} | w of the free bodies | theta_0 (torque drive, time-varying meshes only)
         | W_in, W_load, E_damp (, W_el_tv)]

With ``drive = "speed"`` body 0 has no state (its motion is the analytic STEP profile); with
``drive = "torque"`` it is free. Angles, needed only for the mesh phase of phase-dependent meshes
(time-varying stiffness, stiffness harmonics, transmission error) and for an input torque ripple, come
from theta_0 (analytic, or the extra state) and ``theta_{c+1} = (r_a theta_c - delta_c) / r_b``.

A mesh with ``damping_ratio`` gets its viscous damping here, where the chain is known
(:func:`_viscous`): ``c = 2 zeta sqrt(k_lin m_e)``, k_lin the mesh's dF/d delta at the static load,
``m_e = 1 / (r_a^2 / J_a + r_b^2 / J_b)`` from the two bodies it joins (a speed-driven body counts as
infinitely heavy).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from gearcli.model.elements import KIND_MESH, KIND_SPRING, N_HARM, N_PARAM, machine, mesh, spring, torque
from gearcli.model.spec import DriveSpec, LoadSpec, ModelSpec

QUADRATURES = ("input_work_J", "load_work_J", "damping_loss_J", "elastic_work_tv_J")


@dataclass(frozen=True)
class Body:
    inertia: float  # kg m^2
    label: str  # "motor", "shaft 1", "shaft 2 gear end", "shaft 2 pinion end", "drum"
    ratio: float  # nominal speed over the input body's speed (rigid kinematics)


@dataclass(frozen=True)
class Connector:
    kind: int  # KIND_SPRING or KIND_MESH
    a: int
    b: int
    ra: float
    rb: float
    params: tuple[float, ...]  # the element's parameter row, as Python floats
    label: str  # "input coupling", "stage 1 mesh", "shaft 2", "load coupling"
    index: int = -1  # 0-based stage of a mesh or reducer shaft of a flexible shaft; -1 for couplings

    @property
    def element(self):
        return mesh if self.kind == KIND_MESH else spring

    @property
    def damped(self) -> bool:
        return self.element.damped(self.params)

    @property
    def lossy(self) -> bool:
        """A mesh that loses (1 - eta) of the power it transmits (:func:`.mesh.loss_factors`)."""
        return self.kind == KIND_MESH and mesh.lossy(self.params)

    @property
    def time_varying(self) -> bool:
        return self.element.time_varying(self.params)

    @property
    def phased(self) -> bool:
        return self.element.phased(self.params)

    @property
    def excited(self) -> bool:
        return self.element.excited(self.params)


def _chain(spec: ModelSpec) -> tuple[list[Body], list[Connector]]:
    bodies: list[Body] = []
    conns: list[Connector] = []

    def body(inertia: float, label: str) -> None:
        ratio = 1.0 if not conns else bodies[-1].ratio * conns[-1].ra / conns[-1].rb
        bodies.append(Body(float(inertia), label, ratio))

    def join(kind: int, row: np.ndarray, ra: float, rb: float, label: str, index: int = -1) -> None:
        n = len(bodies)
        conns.append(Connector(kind, n - 1, n, ra, rb, tuple(float(v) for v in row), label, index))

    if spec.motor is not None:
        body(spec.motor.inertia_kg_m2, "motor")
        join(KIND_SPRING, spring.pack(spec.motor.coupling), 1.0, 1.0, "input coupling")
    body(spec.inertias_kg_m2[0], "shaft 1")
    for k, m in enumerate(spec.meshes):
        join(KIND_MESH, mesh.pack(m), m.base_radius_pinion_m, m.base_radius_gear_m, f"stage {k + 1} mesh", k)
        flex = spec.shafts[k] if k < len(spec.shafts) else None
        if flex is None:
            body(spec.inertias_kg_m2[k + 1], f"shaft {k + 2}")
            continue
        body(flex.gear_end_kg_m2, f"shaft {k + 2} gear end")
        join(KIND_SPRING, spring.pack(flex.spring), 1.0, 1.0, f"shaft {k + 2}", k + 1)
        body(spec.inertias_kg_m2[k + 1] - flex.gear_end_kg_m2, f"shaft {k + 2} pinion end")
    if spec.drum is not None:
        join(KIND_SPRING, spring.pack(spec.drum.coupling), 1.0, 1.0, "load coupling")
        body(spec.drum.inertia_kg_m2, "drum")
    return bodies, _loss_widths(spec, bodies, _viscous(spec, bodies, conns))


def _loss_widths(spec: ModelSpec, bodies: list[Body], conns: list[Connector]) -> list[Connector]:
    """Connectors with the power scale of every lossy mesh's power-flow sign filled in: ``LOSS_WIDTH`` x the
    static line force (at least 1 N) x the nominal pitch-line speed."""
    out = []
    for x in conns:
        if x.kind == KIND_MESH and mesh.lossy(x.params):
            F = max(abs(spec.load.torque_Nm * bodies[-1].ratio / bodies[x.b].ratio / x.rb), 1.0)
            v = abs(x.ra * bodies[x.a].ratio * spec.drive.speed_rad_s)
            row = mesh.with_loss_width(x.params, mesh.LOSS_WIDTH * F * v)
            x = Connector(x.kind, x.a, x.b, x.ra, x.rb, tuple(float(v) for v in row), x.label, x.index)
        out.append(x)
    return out


MIN_APPROACH_M = 1e-6  # an unloaded Hertzian mesh's k_lin: at a 1 um approach (as the cost estimate)


def _viscous(spec: ModelSpec, bodies: list[Body], conns: list[Connector]) -> list[Connector]:
    """Connectors with the viscous damping of every ``damping_ratio`` mesh filled in (module text)."""
    out = []
    for x in conns:
        if x.kind == KIND_MESH and x.params[mesh.I_VIS] != 0.0:
            F = abs(spec.load.torque_Nm * bodies[-1].ratio / bodies[x.b].ratio / x.rb)  # static line force
            k_lin = mesh.linear_stiffness(x.params, F, MIN_APPROACH_M)
            held = x.a == 0 and spec.drive.kind == "speed"
            m_e = 1.0 / ((0.0 if held else x.ra**2 / bodies[x.a].inertia) + x.rb**2 / bodies[x.b].inertia)
            row = mesh.with_viscous(x.params, k_lin, m_e)
            x = Connector(x.kind, x.a, x.b, x.ra, x.rb, tuple(float(v) for v in row), x.label, x.index)
        out.append(x)
    return out


@dataclass(frozen=True)
class ModelArrays:
    """The model as plain arrays (picklable), for engines that interpret it (one compiled kernel for
    every scene). Kinds and parameter rows: :mod:`gearcli.model.elements`."""

    body_inertia: np.ndarray  # float64[N]
    conn_kind: np.ndarray  # int64[nc]
    conn_bodies: np.ndarray  # int64[nc, 2]
    conn_radii: np.ndarray  # float64[nc, 2]
    conn_param: np.ndarray  # float64[nc, N_PARAM]
    conn_harm: np.ndarray  # float64[nc, N_HARM, 4]: TE amplitude m, TE phase rad, stiffness harmonic, phase
    #   (a copy of the mesh row's harmonics, gearcli.model.elements.mesh.I_TE ...; the row is authoritative)
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


@dataclass(frozen=True)
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

    @property
    def inertias(self) -> tuple[float, ...]:
        return tuple(b.inertia for b in self.bodies)

    # ------------------------------------------------------------------------------- element roles
    @property
    def stage_conn(self) -> tuple[int, ...]:
        """Connector index of each mesh, in stage order."""
        return tuple(c for c, x in enumerate(self.connectors) if x.kind == KIND_MESH)

    @property
    def shaft_body(self) -> tuple[int, ...]:
        """Body of each reducer shaft: shaft 1 the input pinion's, the others their gear end."""
        return (self.stage_conn[0],) + tuple(self.connectors[c].b for c in self.stage_conn)

    @property
    def shaft_conn(self) -> dict[int, int]:
        """Reducer shaft (0-based) -> its spring connector, for the flexible shafts."""
        return {x.index: c for c, x in enumerate(self.connectors) if x.label.startswith("shaft ")}

    def conn_named(self, label: str) -> int | None:
        return next((c for c, x in enumerate(self.connectors) if x.label == label), None)

    @property
    def motor_body(self) -> int | None:
        return 0 if self.spec.motor is not None else None

    @property
    def drum_body(self) -> int | None:
        return self.n_bodies - 1 if self.spec.drum is not None else None

    # --------------------------------------------------------------------------------------- flags
    @property
    def speed_drive(self) -> bool:
        return self.drive.kind == "speed"

    @property
    def motor_drive(self) -> bool:
        return self.drive.kind == "motor"

    @property
    def motor_row(self) -> tuple[float, ...]:
        """The motor's row (:mod:`gearcli.model.elements.machine`) of a motor drive; empty otherwise."""
        motor = self.drive.motor
        return machine.motor_row(motor) if self.motor_drive and motor is not None else ()

    @property
    def load_law(self) -> tuple[float, ...]:
        """The load's speed law row (empty: a constant torque), on the last body's nominal speed."""
        w_n = self.bodies[-1].ratio * self.drive.speed_rad_s
        return machine.load_row(self.load.speed_exponent, w_n, self.load.table, abs(self.load.torque_Nm) or 1.0)

    @property
    def n_lossy(self) -> int:
        return sum(x.lossy for x in self.connectors)

    @property
    def n_tv(self) -> int:
        return sum(x.time_varying for x in self.connectors)

    @property
    def ripple(self) -> tuple[float, ...]:
        """The input torque ripple row (:mod:`gearcli.model.elements.torque`); empty for none."""
        return torque.flat(self.drive.ripple)

    @property
    def fluctuation(self) -> tuple[float, ...]:
        """The load fluctuation row; empty for none."""
        return torque.flat(self.load.fluctuation)

    @property
    def needs_angles(self) -> bool:
        return any(x.phased for x in self.connectors) or bool(self.ripple)

    @property
    def last_angle_body(self) -> int:
        """The last body whose angle a phase-dependent mesh needs (its pinion's body); -1 for none."""
        return max((x.a for x in self.connectors if x.phased), default=-1)

    @property
    def has_theta_state(self) -> bool:
        return self.needs_angles and not self.speed_drive

    # ------------------------------------------------------------------------------------- indices
    @property
    def free_bodies(self) -> range:
        return range(1 if self.speed_drive else 0, self.n_bodies)

    def i_delta(self, c: int) -> int:
        return c

    def i_omega(self, body: int) -> int | None:
        """State index of a body's speed; None for the speed-driven input body."""
        first = self.free_bodies.start
        return None if body < first else self.n_conn + body - first

    @property
    def i_theta(self) -> int | None:
        return self.n_conn + len(self.free_bodies) if self.has_theta_state else None

    @property
    def i_quad(self) -> int:
        return self.n_conn + len(self.free_bodies) + int(self.has_theta_state)

    @property
    def n_quad(self) -> int:
        return 3 + int(self.n_tv > 0)

    @property
    def n_states(self) -> int:
        return self.i_quad + self.n_quad

    @property
    def n_dynamic(self) -> int:
        """States that carry the dynamics (step control); the quadratures follow them."""
        return self.i_quad

    @property
    def state_names(self) -> list[str]:
        names = [f"d{c}" for c in range(self.n_conn)] + [f"w{i}" for i in self.free_bodies]
        if self.has_theta_state:
            names.append("th0")
        return names + [f"_q{j}" for j in range(self.n_quad)]

    def angle_gradient(self, body: int) -> dict[int, float]:
        """d(theta_body)/dy as {column: coefficient}: theta_{c+1} = (r_a theta_c - delta_c) / r_b."""
        grad: dict[int, float] = {self.i_theta: 1.0} if self.i_theta is not None else {}
        for c in range(body):
            x = self.connectors[c]
            grad = {col: x.ra / x.rb * v for col, v in grad.items()}
            grad[self.i_delta(c)] = grad.get(self.i_delta(c), 0.0) - 1.0 / x.rb
        return grad

    def body_speeds(self, y: np.ndarray, w0) -> np.ndarray:
        """Speeds of all bodies from states ``y`` (n_states, ...) and the input body's ``w0``."""
        free = y[self.n_conn:self.n_conn + len(self.free_bodies)]
        return np.vstack([np.asarray(w0)[None, ...], free]) if self.speed_drive else free

    def arrays(self, atol: np.ndarray) -> ModelArrays:
        conns = self.connectors
        nc = len(conns)
        param = np.zeros((nc, N_PARAM))
        harm = np.zeros((nc, N_HARM, 4))
        for c, x in enumerate(conns):
            param[c] = x.params + (0.0,) * (N_PARAM - len(x.params))
            if x.kind == KIND_MESH:
                for i, start in enumerate((mesh.I_TE, mesh.I_TEP, mesh.I_KS, mesh.I_KSP)):
                    harm[c, :, i] = param[c, start:start + N_HARM]
        drive = self.drive
        return ModelArrays(
            body_inertia=np.array(self.inertias), conn_kind=np.array([x.kind for x in conns], dtype=np.int64),
            conn_bodies=np.array([[x.a, x.b] for x in conns], dtype=np.int64).reshape(nc, 2),
            conn_radii=np.array([[x.ra, x.rb] for x in conns]).reshape(nc, 2), conn_param=param,
            conn_harm=harm, drive_kind=0 if self.speed_drive else 2 if self.motor_drive else 1,
            drive_value=drive.speed_rad_s if self.speed_drive else drive.torque_Nm, drive_ramp_s=drive.ramp_s,
            drive_ripple=np.array(self.ripple, float).reshape(-1, 2), drive_angle_rad=float(drive.angle_rad),
            load_value_Nm=self.load.torque_Nm, load_ramp_s=self.load.ramp_s,
            load_fluct=np.array(self.fluctuation, float).reshape(-1, 2), load_clock_s=float(self.load.clock_s),
            motor_row=np.array(self.motor_row, float), load_law=np.array(self.load_law, float),
            n_states=self.n_states, i_delta0=0, i_omega0=self.n_conn,
            i_theta=-1 if self.i_theta is None else self.i_theta, i_quad=self.i_quad, atol=np.asarray(atol, float))
