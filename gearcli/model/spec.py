"""Plain SI parameters of the torsional model (m, N, rad, s, kg m^2).

Shaft 1 carries pinion 1; shaft k+1 carries gear k and pinion k+1; the last shaft carries the last
gear. Mesh k joins shaft k (its pinion drives) and shaft k+1 (its gear is driven). Optional drivetrain
elements: a motor rotor joined to shaft 1 by a coupling, a driven machine (drum) joined to the last
shaft by a coupling, and flexible intermediate shafts (gear k and pinion k+1 then become two bodies
joined by a torsional spring). The model layer never sees the design file: the design's engineering
units are converted once, in :func:`gearcli.scene.spec_from_design`.

Stage efficiency acts in the dynamics: a mesh with ``efficiency < 1`` passes on eta of its force in the
direction of power flow (:func:`gearcli.model.elements.mesh.loss_factors`). A drive may be an induction
motor (:class:`MotorSpec`), a load may depend on speed (:class:`LoadSpec`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Literal, Protocol

from gearcli.core.records import record
from gearcli.model.elements.machine import field_weakening, kloss_fit, motor_curve, motor_row, motor_torque

if TYPE_CHECKING:  # the parts a stage model places (model.parts builds on this module's specs)
    from gearcli.model.parts import Body, Connector

MM = 1e-3  # m per mm


@record
class MeshSpec:
    """One mesh along its transverse line of action (all SI)."""

    base_radius_pinion_m: float
    base_radius_gear_m: float
    base_helix_angle_rad: float
    transverse_pressure_angle_rad: float  # F_r = F_t tan(alpha_t), as the design's static forces
    helix_angle_rad: float  # F_a = F_t tan(beta)
    stiffness_N_m_e: float  # K in N/m^e
    exponent: float
    damping_Ns_m: float  # C, reached at the full-damping penetration
    full_damping_m: float  # d
    backlash_m: float = 0.0  # normal backlash j (gap of j/2 on each side)
    time_varying: bool = False
    contact_ratio: float = 1.5  # eps_alpha (used by time-varying stiffness)
    overlap_ratio: float = 0.0  # eps_beta
    pinion_teeth: int = 20  # mesh phase z_p theta_p / 2 pi
    normal_module_m: float = 0.0  # for the "penetration > 10 % of the module" warning (0: no check)
    static_tangential_N: float = 0.0  # design's F_t at full load (signed)
    efficiency: float = 1.0  # eta: the mesh passes on eta of its force in the power-flow direction
    # mesh excitation (gearcli.model.elements.mesh): harmonics j = 1, 2, ... of the mesh phase
    transmission_error_m: tuple[float, ...] = ()  # e_j along the transverse line of action
    transmission_error_phase_rad: tuple[float, ...] = ()  # psi_j (missing: 0)
    stiffness_harmonics: tuple[float, ...] = ()  # s_j: K (1 - sum s_j cos(j phi + chi_j))
    stiffness_harmonics_phase_rad: tuple[float, ...] = ()  # chi_j (missing: 0)
    damping_ratio: float | None = None  # viscous c = 2 zeta sqrt(k_lin m_e) instead of the IMPACT ramp
    contact_phase_cycles: float = 0.0  # time-varying stiffness: L(phi + this) (a planet mesh's phase offset)
    # what the law was calibrated to (reported, never integrated): the design file's law, and ISO 6336-1's normal
    # mesh stiffness k_n = c_gamma_alpha b / cos^2 beta_b (N/m; 0: unknown)
    law: str = ""
    iso_normal_stiffness_N_m: float = 0.0
    # the line force F_bt (N) below which the linearisation (modes, a viscous mesh's k_lin) holds at this force:
    # an iso6336 law's calibration load, 1 N/mm of face width (DESIGN section 13: its tangent is k_n there, as the
    # reported mesh_stiffness says); 0: at the static load, whatever it is
    linearisation_line_force_N: float = 0.0

    def __post_init__(self) -> None:
        problem = _mesh_problem(self)
        if problem is not None:  # a plug-in's line (docs/plugins.md) or a script's spec: named, not NaN output
            raise ValueError(f"MeshSpec.{problem}")
        if len(self.transmission_error_phase_rad) > len(self.transmission_error_m) or \
                len(self.stiffness_harmonics_phase_rad) > len(self.stiffness_harmonics):
            raise ValueError("more harmonic phases than amplitudes")
        if sum(abs(s) for s in self.stiffness_harmonics) >= 1.0:
            raise ValueError("stiffness harmonics: sum |s_j| must stay below 1 (K stays positive)")
        if self.damping_ratio is not None and not (self.damping_ratio >= 0 and math.isfinite(self.damping_ratio)):
            raise ValueError("damping_ratio must be non-negative and finite")

    @property
    def cos_beta_b(self) -> float:
        return math.cos(self.base_helix_angle_rad)


#: MeshSpec's numbers and what each must be: (fields, test, wording); every one finite
_MESH_RULES: tuple[tuple[tuple[str, ...], Callable[[float], bool], str], ...] = (
    (("base_radius_pinion_m", "base_radius_gear_m", "stiffness_N_m_e", "full_damping_m", "contact_ratio"),
     lambda v: v > 0, "a finite number > 0"),
    (("base_helix_angle_rad", "transverse_pressure_angle_rad", "helix_angle_rad"),
     lambda v: abs(v) < math.pi / 2, "a finite angle below pi/2 rad"),
    (("exponent", "pinion_teeth"), lambda v: v >= 1, "a finite number >= 1"),
    (("efficiency",), lambda v: 0 < v <= 1, "a number in (0, 1]"),
    (("damping_Ns_m", "backlash_m", "overlap_ratio", "normal_module_m", "iso_normal_stiffness_N_m",
      "linearisation_line_force_N"), lambda v: v >= 0, "a finite number >= 0"),
    (("static_tangential_N", "contact_phase_cycles"), lambda v: True, "a finite number"),
)


def _mesh_problem(spec: MeshSpec) -> str | None:
    """What of ``spec`` the model cannot integrate (a non-finite number, a lever or stiffness <= 0, ...), as
    ``field must be ..., got value``; None when every field holds."""
    for names, ok, wording in _MESH_RULES:
        for name in names:
            v = getattr(spec, name)
            # a float is a number (its type first: a sweep point builds every mesh's spec), an int too but a bool
            if (type(v) is not float and (isinstance(v, bool) or not isinstance(v, (int, float)))) \
                    or not (math.isfinite(v) and ok(v)):
                return f"{name} must be {wording}, got {v!r}"
    for name in ("transmission_error_m", "transmission_error_phase_rad", "stiffness_harmonics",
                 "stiffness_harmonics_phase_rad"):
        values = getattr(spec, name)
        if not all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in values):
            return f"{name} must hold finite numbers, got {values!r}"
    return None


@record
class MotorSpec:
    """An induction motor (:mod:`gearcli.model.elements.machine`): the extended Kloss curve (breakdown torque,
    breakdown slip, shape term a) or a table of (speed rad/s, torque N m), and its starting method with its two
    parameters: star_delta (switch-over speed rad/s, 0), soft_start (voltage ramp s, initial voltage
    fraction), vfd (speed ramp s, torque limit N m or 0), direct (0, 0). ``base_speed_rad_s``: a nameplate's
    synchronous speed at its rated voltage and frequency; a converter's supply above it weakens the field (the curve
    scaled by (w_B / w_s)^2, :func:`gearcli.model.elements.machine.field_weakening`; 0: none, a table)."""

    synchronous_speed_rad_s: float
    starting: Literal["direct", "star_delta", "soft_start", "vfd"] = "direct"
    start_parameters: tuple[float, float] = (0.0, 0.0)
    breakdown_torque_Nm: float = 0.0
    breakdown_slip: float = 0.0
    kloss_a: float = 0.0
    rated_torque_Nm: float = 0.0  # nameplate (0 for a table)
    rated_speed_rad_s: float = 0.0
    table: tuple[tuple[float, float], ...] = ()
    base_speed_rad_s: float = 0.0

    def __post_init__(self) -> None:
        if not (self.synchronous_speed_rad_s > 0 and math.isfinite(self.synchronous_speed_rad_s)):
            raise ValueError("a motor needs a positive synchronous speed")
        if self.table and (len(self.table) < 2 or any(b[0] <= a[0] for a, b in zip(self.table, self.table[1:], strict=False))):
            raise ValueError("a torque-speed table needs two or more points at increasing speeds")

    @classmethod
    def nameplate(cls, rated_power_W: float, rated_speed_rad_s: float, synchronous_speed_rad_s: float,
                  breakdown_ratio: float, locked_ratio: float, **start) -> MotorSpec:
        """The extended Kloss curve through the nameplate's rated, breakdown and locked-rotor points."""
        if not 0 < rated_speed_rad_s < synchronous_speed_rad_s:
            raise ValueError("the rated speed must lie between 0 and the synchronous speed")
        t_r = rated_power_W / rated_speed_rad_s
        slip = 1.0 - rated_speed_rad_s / synchronous_speed_rad_s
        try:
            sb, a = kloss_fit(t_r, breakdown_ratio, locked_ratio, slip)
        except (ZeroDivisionError, OverflowError):  # k_lr -> 0: a -> -1/s_b, the curve (s - s_b)^2 = 0 everywhere
            raise ValueError(f"no Kloss curve passes through these nameplate points (breakdown ratio "
                             f"{breakdown_ratio:g}, locked-rotor ratio {locked_ratio:g}, rated slip {slip:.4g}: the "
                             "curve degenerates; an induction motor's locked-rotor torque is some 0.5 to 3 x its "
                             "rated torque)") from None
        return cls(synchronous_speed_rad_s, breakdown_torque_Nm=breakdown_ratio * t_r, breakdown_slip=sb,
                   kloss_a=a, rated_torque_Nm=t_r, rated_speed_rad_s=rated_speed_rad_s,
                   base_speed_rad_s=synchronous_speed_rad_s, **start)

    def torque(self, t: float, w: float) -> float:
        """The motor's torque (N m) at time t and speed w (rad/s), starting method included."""
        return motor_torque(motor_row(self), t, w)[0]

    def curve(self, w: float) -> float:
        """The bare curve's torque (N m) at speed w (the running motor, after any start)."""
        return motor_curve(motor_row(self), w, self.synchronous_speed_rad_s)[0]

    @property
    def peak_torque_Nm(self) -> float:
        """The curve's largest torque at or below synchronous speed (the breakdown torque)."""
        if self.table:
            return max(t for _, t in self.table)
        return self.breakdown_torque_Nm * self.field_weakening

    @property
    def field_weakening(self) -> float:
        """(w_B / w_s)^2 of a converter's supply above the base speed, else 1: the curve's scale."""
        return field_weakening(self.base_speed_rad_s, self.synchronous_speed_rad_s)

    @property
    def continuous_torque_Nm(self) -> float:
        """The torque the motor carries continuously (S1): its rated torque P_r / w_r; a converter's supply above the
        base speed, the rated power over the speed at which the supply puts the rated slip (the constant-power range
        of field weakening, at rated current); 0 for a table."""
        shift = self.synchronous_speed_rad_s - self.base_speed_rad_s
        if self.base_speed_rad_s <= 0.0 or shift <= 0.0 or self.rated_speed_rad_s <= 0.0:
            return self.rated_torque_Nm
        return self.rated_torque_Nm * (self.rated_speed_rad_s - shift) / self.rated_speed_rad_s


@record
class DriveSpec:
    """``kind = "speed"``: shaft 1 follows ``ramp(t, ramp_s, speed_rad_s)`` exactly (no DOF).
    ``kind = "torque"``: shaft 1 is free, driven by ``ramp(t, ramp_s, torque_Nm)`` times the ripple
    (:mod:`gearcli.model.elements.torque`); every shaft starts at its nominal speed (rigid-body
    consistent), so the run begins in motion, not at rest. ``kind = "motor"``: shaft 1 (or the motor rotor)
    is free, driven by the ``motor``'s torque at its speed; every body starts at rest; ``speed_rad_s`` is the
    nominal speed (the load law's reference). ``angle_rad``: a speed drive's angle at
    t = 0 (0 for a run of its own; a continued sweep point carries the previous point's end angle on, so
    the mesh phases continue with the vibration state)."""

    kind: Literal["speed", "torque", "motor"]
    speed_rad_s: float
    ramp_s: float = 0.0
    torque_Nm: float = 0.0
    ripple: tuple[tuple[float, float], ...] = ()  # (amplitude fraction, order per input revolution)
    angle_rad: float = 0.0  # speed drive: theta_0(0)
    motor: MotorSpec | None = None  # kind = "motor"; with a speed drive: the motor that must follow the ramp

    @property
    def ramps_end_s(self) -> float:
        """When the drive stops changing with time: its own ramp, or a soft start's voltage ramp (the motor's
        torque grows as u(t)^2 until then, so its speed and the train's forces drift until that ramp ends)."""
        motor = self.motor
        if self.kind == "motor" and motor is not None and motor.starting == "soft_start":
            return max(self.ramp_s, motor.start_parameters[0])
        return self.ramp_s

    def __post_init__(self) -> None:
        if self.ripple and self.kind != "torque":
            raise ValueError("a torque ripple needs a torque drive (a speed drive prescribes the motion)")
        if self.kind == "motor" and self.motor is None:
            raise ValueError('drive kind "motor" needs a MotorSpec')


@record
class LoadSpec:
    """Torque resisting the last shaft's rotation, ``ramp(t, ramp_s, torque_Nm)`` (negative: reversal),
    times the fluctuation (:mod:`gearcli.model.elements.torque`). ``clock_s``: the fluctuation's time at
    t = 0 (0 for a run of its own; a continued sweep point carries the previous point's end time on)."""

    torque_Nm: float
    ramp_s: float = 0.0
    fluctuation: tuple[tuple[float, float], ...] = ()  # (amplitude fraction, frequency Hz): x (1 + b sin 2 pi f t)
    clock_s: float = 0.0  # the fluctuation is a function of t + clock_s
    speed_exponent: int = 0  # 0 constant, 1 linear, 2 quadratic in the load body's speed (torque_Nm at nominal)
    table: tuple[tuple[float, float], ...] = ()  # (load body speed rad/s, N m); torque_Nm: its T at the nominal speed

    def __post_init__(self) -> None:
        if self.speed_exponent not in (0, 1, 2):
            raise ValueError("speed_exponent must be 0, 1 or 2")
        if self.table and (len(self.table) < 2 or self.table[0][0] < 0
                           or any(b[0] <= a[0] for a, b in zip(self.table, self.table[1:], strict=False))):
            raise ValueError("a load table needs two or more points at increasing, non-negative speeds")


@record
class SpringSpec:
    """A torsional spring-damper (coupling or shaft): torque = k twist + c twist rate."""

    stiffness_Nm_rad: float
    damping_Nms_rad: float = 0.0

    def __post_init__(self) -> None:
        if not (self.stiffness_Nm_rad > 0 and math.isfinite(self.stiffness_Nm_rad)):
            raise ValueError("a spring needs a positive, finite stiffness")
        if not (self.damping_Nms_rad >= 0 and math.isfinite(self.damping_Nms_rad)):
            raise ValueError("a spring's damping must be non-negative and finite")


@record
class CoupledInertia:
    """A body outside the reducer (motor rotor, driven drum) and the coupling that joins it."""

    inertia_kg_m2: float
    coupling: SpringSpec


@record
class FlexibleShaft:
    """An intermediate shaft as two bodies: the gear end (``gear_end_kg_m2``, gear k's inertia) and the
    pinion end (the rest of the shaft's inertia), joined by the shaft's torsional spring."""

    spring: SpringSpec
    gear_end_kg_m2: float


@record
class ElementSpec:
    """A further element of a registered type (:mod:`gearcli.model.elements`) placed between bodies given by
    their index in the assembly (:class:`gearcli.model.assembly.Layout`), with its lever on each body (1 for
    a torsional element) and what the element's ``pack`` takes (``part``)."""

    name: str
    bodies: tuple[int, ...]
    radii: tuple[float, ...]
    part: object
    label: str = "element"

    def __post_init__(self) -> None:
        if len(self.bodies) != len(self.radii) or len(set(self.bodies)) != len(self.bodies):
            raise ValueError("an element joins distinct bodies, one lever per body")
        if not all(r > 0 and math.isfinite(r) for r in self.radii):
            raise ValueError("an element's levers must be positive and finite")


class StageModel(Protocol):
    """A stage's own model (a kind's, :mod:`gearcli.stages.model`): where the chain has no stage model
    (``ModelSpec.stage_models[k]`` None or absent) stage k is the pair ``meshes[k]``."""

    @property
    def efficiency(self) -> float:
        """The stage's power efficiency beyond its connectors' own losses (1: none)."""

    @property
    def reverse_efficiency(self) -> float:
        """The same with the load reversed."""

    def place(self, k: int, bodies: list[Body], conns: list[Connector], body: Callable[..., None],
              out_inertia: float) -> None:
        """Add the stage's bodies and connectors after its input body (the last one in ``bodies``), ending with
        its output shaft's body of inertia ``out_inertia``; ``body(inertia, label, ratio)`` adds a body."""


@record
class ModelSpec:
    """The torsional model's SI parameters: ``meshes``, ``inertias_kg_m2`` (one per reducer shaft), ``drive``,
    ``load``, the optional ``motor`` and ``drum`` couplings, flexible ``shafts``, further ``elements``, and per stage
    its own model (``stage_models``) and kind (``stage_types``)."""

    meshes: tuple[MeshSpec, ...]
    inertias_kg_m2: tuple[float, ...]  # one per reducer shaft: len(meshes) + 1
    drive: DriveSpec
    load: LoadSpec
    motor: CoupledInertia | None = None  # drive acts on it; joined to shaft 1
    drum: CoupledInertia | None = None  # load acts on it; joined to the last shaft
    shafts: tuple[FlexibleShaft | None, ...] = ()  # per intermediate shaft k = 1 .. n-1 (or empty)
    elements: tuple[ElementSpec, ...] = ()  # further elements between the chain's bodies, by body index
    stage_models: tuple[StageModel | None, ...] = ()  # per stage: its own model (meshes[k] then unused), or None
    stage_types: tuple[str, ...] = ()  # per stage: its kind (the design file's ``type``); empty: every stage parallel

    def __post_init__(self) -> None:
        if len(self.inertias_kg_m2) != len(self.meshes) + 1:
            raise ValueError("need one inertia per shaft: len(meshes) + 1")
        if not all(j > 0 and math.isfinite(j) for j in self.inertias_kg_m2):
            raise ValueError("shaft inertias must be positive and finite")
        if self.shafts and len(self.shafts) != len(self.meshes) - 1:
            raise ValueError("flexible shafts: one entry (or None) per intermediate shaft, len(meshes) - 1")
        for k, s in enumerate(self.shafts):
            if s is not None and not 0 < s.gear_end_kg_m2 < self.inertias_kg_m2[k + 1]:
                raise ValueError("a flexible shaft's gear end must carry part of the shaft's inertia")

    @property
    def speed_ratios(self) -> tuple[float, ...]:
        """Nominal speed of each shaft over the input speed (rigid kinematics on base radii)."""
        out = [1.0]
        for m in self.meshes:
            out.append(out[-1] * m.base_radius_pinion_m / m.base_radius_gear_m)
        return tuple(out)


def __getattr__(name: str) -> object:
    if name == "PlanetarySpec":  # PEP 562
        from gearcli.model.planet_spec import PlanetarySpec  # lazy: a scene without planetary stages never creates it

        return PlanetarySpec
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
