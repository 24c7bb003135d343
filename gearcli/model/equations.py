"""The torsional model of a drivetrain: equations of motion, Jacobian, scales, energies.

Equations (SI; docs/tour.md "The model, in one paragraph"). Body i has inertia J_i and speed w_i; connector c joins bodies c and
c+1 with radii r_a, r_b (:mod:`gearcli.model.assembly`) and carries the force F_c of its element
(:mod:`gearcli.model.elements`):

    delta_c' = r_a,c w_c - r_b,c w_{c+1}
    J_i w_i' = r_b,i-1 F_i-1 - r_a,i F_i  (+ T_in on body 0 of a torque drive, - T_L on the last body)

Energy balance, integrated with the states (quadrature states; cheaper and more accurate than
integrating sampled output afterwards, and exact to the integrator's own accuracy):

    W_in - W_load - E_damp - dKE - dU_const - W_el,tv = 0

``W_in = int T_in w_0``, ``W_load = int T_L w_N``, ``E_damp`` the elements' dissipated work, ``U`` the
stored energy of the connectors of constant stiffness, and for time-varying meshes ``W_el,tv`` the work
done on their springs, which equals their potential change plus the parametric work that the varying
stiffness exchanges with the drive. The quadrature states get a huge absolute tolerance so they never
steer the step size.

Initial state: every connector undeflected (delta = 0); speeds rigid-body consistent, at rest for a
speed drive with a ramp, at the nominal speed for a speed drive without a ramp and for a torque drive.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from gearcli.core.records import record
from gearcli.model.assembly import Layout, ModelArrays
from gearcli.model.codegen import compile_function, source_of
from gearcli.model.linear import static_forces
from gearcli.model.outputs import kinetic_energy, potential_energy
from gearcli.model.parts import STAGE_ROLES
from gearcli.model.spec import ModelSpec
from gearcli.model.step import ramp_motion

QUADRATURE_ATOL = 1e20  # J: excludes the energy quadratures from step-size control
MIN_DEFLECTION_SCALE_M = 1e-6  # atol floor for unloaded meshes: 1 um of deflection
MIN_TWIST_SCALE_RAD = 1e-6  # atol floor for unloaded springs: 1 urad of twist


@record
class Energy:
    """The energy balance's terms at the end of a run (J)."""

    input_work_J: float
    load_work_J: float
    damping_loss_J: float
    kinetic_change_J: float
    potential_change_J: float
    parametric_work_J: float
    kinetic_end_J: float

    @property
    def residual_J(self) -> float:
        return (self.input_work_J - self.load_work_J - self.damping_loss_J - self.kinetic_change_J
                - self.potential_change_J + self.parametric_work_J)

    @property
    def residual_relative(self) -> float:
        scale = max(abs(self.input_work_J), abs(self.load_work_J), abs(self.kinetic_end_J))
        return abs(self.residual_J) / scale if scale > 0 else 0.0


class TorsionalModel:
    """Compiled equations of one scene. ``rhs(t, y)`` and ``jac(t, y)`` are plain functions of the
    state layout documented in :mod:`gearcli.model.assembly`; ``source`` is their generated code."""

    def __init__(self, spec: ModelSpec):
        self.spec = spec
        self.layout = Layout.of(spec)
        self._functions: dict[str, Callable] = {}  # generated on first use, each
        self._replaced: dict[str, Callable] = {}

    def _generated(self, name: str) -> Callable:
        """The generated ``rhs`` or ``jac``, made on first use: a run on the compiled engine (a sweep point)
        integrates the model's arrays and never needs them, a method without a Jacobian never needs ``jac``."""
        fn = self._functions.get(name)
        if fn is None:
            fn = self._functions[name] = compile_function(self.layout, name)
        return fn

    @property
    def rhs(self) -> Callable[[float, np.ndarray], np.ndarray]:
        return self._replaced.get("rhs") or self._generated("rhs")

    @rhs.setter
    def rhs(self, fn: Callable[[float, np.ndarray], np.ndarray]) -> None:
        self._replaced["rhs"] = fn

    @property
    def jac(self) -> Callable[[float, np.ndarray], np.ndarray]:
        return self._replaced.get("jac") or self._generated("jac")

    @jac.setter
    def jac(self, fn: Callable[[float, np.ndarray], np.ndarray]) -> None:
        self._replaced["jac"] = fn

    @property
    def source(self) -> str:
        """The generated module's source: ``rhs`` and ``jac`` with the scene's constants as literals."""
        return source_of(self.layout)

    @property
    def generated(self) -> bool:
        """Whether ``rhs`` and ``jac`` are still the generated ones (the arrays describe them); False when a
        caller replaced them (tests that sabotage a run), which only the Python engine can integrate."""
        return all(fn is self._generated(name) for name, fn in self._replaced.items())

    @property
    def n_states(self) -> int:
        return self.layout.state.n_states

    @property
    def arrays(self) -> ModelArrays:
        """The model as plain arrays (atol at rtol 1e-6; an engine rescales it by its own rtol); built once per
        model (the engine's choice, its options and the kernel read it)."""
        if getattr(self, "_arrays", None) is None:
            self._arrays = self.layout.arrays(self.atol(1e-6))
        return self._arrays

    # ------------------------------------------------------------------------------- start, scales
    def _input_speed(self, t: float = 0.0) -> float:
        """The input body's rigid-body speed at time t: a speed drive's prescribed speed, a torque
        drive's nominal speed."""
        lay = self.layout
        if lay.motor_drive:
            return 0.0  # a motor starts the train from rest
        return ramp_motion(t, lay.drive.ramp_s, lay.drive.speed_rad_s)[1] if lay.speed_drive \
            else lay.drive.speed_rad_s

    def _operating_speed(self, t: float = 0.0) -> float:
        """The input body's rigid-body speed at time t once running: :meth:`_input_speed`, but a motor drive's
        nominal speed (its start from rest aside): where a continued sweep point moves the previous point's
        speeds from and to."""
        return self.layout.drive.speed_rad_s if self.layout.motor_drive else self._input_speed(t)

    def input_angle(self, t: float) -> float:
        """The speed-driven input body's angle at time t (its start angle included); a torque drive's
        angle is a state (ValueError)."""
        drive = self.layout.drive
        if not self.layout.speed_drive:
            raise ValueError("a torque drive's input angle is a state")
        return ramp_motion(t, drive.ramp_s, drive.speed_rad_s)[0] + drive.angle_rad

    def initial_state(self) -> np.ndarray:
        lay = self.layout
        y0 = np.zeros(lay.state.n_states)
        w_in = self._input_speed()
        for i in lay.free_bodies:
            y0[lay.state.omega(i)] = lay.bodies[i].ratio * w_in
        rest: dict[int, float] = {}
        if any(x.initial_deflection for x in lay.connectors):  # planets with position errors: at rest, unloaded
            from gearcli.model.planet_statics import rest_deflections  # lazy: scipy, such scenes only

            rest = rest_deflections(lay)
        for c, x in enumerate(lay.connectors):  # a planet's position error: delta = R theta + e
            y0[lay.state.delta(c)] = rest.get(c, x.initial_deflection)
        return y0

    def continue_state(self, y_prev: np.ndarray, model_prev: TorsionalModel, t_prev: float | None = None) -> np.ndarray:
        """Start state continuing a previous run's end ``y_prev`` (of ``model_prev``, same chain, at its time
        ``t_prev``; None: past its ramps): keep the deflections and the deflection rates, move the rigid-body
        speeds from the previous run's speed at its end to this model's operating speed (the input body's
        speed at t = 0); quadratures reset to 0. The angles: a torque drive's input
        angle state is kept; a speed drive's is analytic, so this model should have been built with the
        previous run's end angle as its drive's ``angle_rad`` (:func:`gearcli.sweep.continuation.carry_phases`),
        or every mesh phase jumps back to the start while the vibration state goes on."""
        lay, prev = self.layout, model_prev.layout
        if (lay.n_conn, lay.n_bodies, lay.speed_drive) != (prev.n_conn, prev.n_bodies, prev.speed_drive):
            raise ValueError("continuation needs the same chain of bodies and connectors")
        # (zeros, not initial_state(): every entry it sets, each deflection and each free body's speed, is set below,
        # and it leaves the others 0; a planetary with position errors solved its rest deflections for nothing)
        y = np.zeros(lay.state.n_states)
        y[lay.state.deflections] = y_prev[prev.state.deflections]
        t_end = max(prev.drive.ramp_s, prev.load.ramp_s) if t_prev is None else t_prev
        w_prev_in = model_prev._operating_speed(t_end)
        w_in = self._operating_speed()  # a motor's too: it starts from rest only when cold
        for i in lay.free_bodies:  # same vibration about the new rigid speed
            rigid_prev = prev.bodies[i].ratio * w_prev_in
            y[lay.state.omega(i)] = lay.bodies[i].ratio * w_in + (y_prev[prev.state.omega(i)] - rigid_prev)
        if lay.state.i_theta is not None and prev.state.i_theta is not None:
            y[lay.state.i_theta] = y_prev[prev.state.i_theta]
        return y

    def deflection_scales(self) -> np.ndarray:
        """Static deflection of each connector at full load, floored (a mesh: backlash half-gap, 1 um;
        a spring: 1 urad)."""
        F = np.abs(static_forces(self.layout))
        out = np.empty(F.size)
        for c, x in enumerate(self.layout.connectors):
            floor = MIN_DEFLECTION_SCALE_M if x.role in STAGE_ROLES else MIN_TWIST_SCALE_RAD  # m on levers
            out[c] = x.element.deflection_scale(x.params, F[c], floor)
        return out

    def deflection_scales_m(self) -> np.ndarray:
        """Per mesh, in stage order (m)."""
        return self.deflection_scales()[list(self.layout.stage_conn)]

    def speed_scales_rad_s(self) -> np.ndarray:
        """Nominal speed of each free body, rad/s."""
        lay = self.layout
        return np.array([abs(lay.bodies[i].ratio) * self.spec.drive.speed_rad_s for i in lay.free_bodies])

    def atol(self, rtol: float) -> np.ndarray:
        """Per-state absolute tolerance: rtol x the state's natural scale."""
        st = self.layout.state
        out = np.empty(st.n_states)
        deflections, speeds = self._scales()
        out[st.deflections] = rtol * deflections
        out[st.speeds] = rtol * speeds
        if st.i_theta is not None:
            out[st.i_theta] = rtol * 2.0 * math.pi / max(m.pinion_teeth for m in self.spec.meshes)
        out[st.quadratures] = QUADRATURE_ATOL
        return out

    def _scales(self) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`deflection_scales` and :meth:`speed_scales_rad_s`, read only: worked out once per model (keyed by
        the model itself: its spec and layout, all they read, are fixed; a run's arrays at rtol 1e-6 and its
        integration's tolerances at its own rtol both scale them)."""
        kept = self.__dict__.get("_state_scales")
        if kept is None:
            kept = (self.deflection_scales(), self.speed_scales_rad_s())
            for a in kept:
                a.flags.writeable = False
            self.__dict__["_state_scales"] = kept
        return kept

    # ------------------------------------------------------------------------------------ energy
    def energy(self, s, Y: np.ndarray, start: int = 0) -> Energy:
        """Energy balance over the run from its samples ``s`` (``outputs.Sampled``) and states ``Y``, from sample
        ``start`` on (``energy(s.tail(start), Y[:, start:])``: the balance reads its first and last samples)."""
        lay = self.layout
        st = lay.state
        ends = [start, -1]
        ke = kinetic_energy(lay, s.omega_rad_s[:, ends])
        u_const = potential_energy(lay, s, time_varying=False, at=ends)
        u_tv = potential_energy(lay, s, time_varying=True, at=ends)
        d_u_tv = float(u_tv[-1] - u_tv[0])

        def change(name: str) -> float:  # a quadrature's change over the run; 0 where the scene has none
            i = st.quadrature(name)
            return 0.0 if i is None else float(Y[i, -1] - Y[i, start])

        w_el_tv = change("elastic_work_tv_J")
        return Energy(
            input_work_J=change("input_work_J"),
            load_work_J=change("load_work_J"),
            damping_loss_J=change("damping_loss_J"),
            kinetic_change_J=float(ke[1] - ke[0]),
            potential_change_J=float(u_const[-1] - u_const[0]) + d_u_tv,
            parametric_work_J=d_u_tv - w_el_tv,
            kinetic_end_J=float(ke[1]),
        )
