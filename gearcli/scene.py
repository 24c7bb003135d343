"""The design file and its design, as the torsional model's SI parameters (the design -> model boundary).

The model layer (:mod:`gearcli.model`) never sees the design file: this module converts once, here.
``K`` in N/mm^e becomes N/m^e by ``K 1000^e``, damping N s/mm becomes N s/m by ``x 1000``, lengths mm
become m by ``/ 1000``; drivetrain keys are SI already (kg m^2, N m/rad, N m s/rad). Excitation: transmission
error um -> m, phases deg -> rad, torque ripple and load fluctuation percent -> fractions.
A flexible intermediate shaft splits its inertia: the gear's on the gear end, the next pinion's on the
pinion end (the design gives each gear's inertia).
"""

from __future__ import annotations

import dataclasses
import math
from typing import TYPE_CHECKING

from gearcli import diagnostics as dg
from gearcli.design import contact_stiffness_N_mm_e
from gearcli.design.stiffness import (
    calibration_line_force_N,
    iso6336_normal_stiffness_N_mm,
    law_name,
)
from gearcli.errors import ConfigError
from gearcli.model import TorsionalModel
from gearcli.model.assembly import Layout
from gearcli.model.modes import resonances
from gearcli.model.spec import (
    MM,
    CoupledInertia,
    DriveSpec,
    FlexibleShaft,
    LoadSpec,
    MeshSpec,
    ModelSpec,
    MotorSpec,
    SpringSpec,
)
from gearcli.results import DesignResult, StageResult
from gearcli.stages import kinds
from gearcli.stages.design import design_kind
from gearcli.stages.model import checked_line_losses, model_kind, placed

if TYPE_CHECKING:  # the config layer is below this one; its pydantic models only name the types here
    from gearcli.config.schema import DesignFile, Input, Load
    from gearcli.diagnostics import Diagnostic
    from gearcli.model import TorsionalModel

RPM = 2.0 * math.pi / 60.0  # rad/s per rpm


def _mesh(cfg: DesignFile, st: StageResult, k: int) -> MeshSpec:
    law = cfg.contact_for(k)
    e = float(law.exponent)
    k_n = iso6336_normal_stiffness_N_mm(st.iso6336_mesh_stiffness_N_mm_um, st.face_width_mm,
                                        math.radians(st.base_helix_angle_deg))
    return MeshSpec(
        base_radius_pinion_m=st.pinion.base_diameter_mm * MM / 2,
        base_radius_gear_m=st.gear.base_diameter_mm * MM / 2,
        base_helix_angle_rad=math.radians(st.base_helix_angle_deg),
        transverse_pressure_angle_rad=math.radians(st.transverse_pressure_angle_deg),
        helix_angle_rad=math.radians(st.helix_angle_deg),
        stiffness_N_m_e=float(contact_stiffness_N_mm_e(st, law)) * 1000.0**e,
        exponent=e,
        damping_Ns_m=law.damping_Ns_mm * 1000.0,
        full_damping_m=law.full_damping_penetration_mm * MM,
        backlash_m=st.backlash_mm * MM,
        time_varying=bool(law.time_varying),
        contact_ratio=st.contact_ratio_transverse,
        overlap_ratio=st.overlap_ratio,
        pinion_teeth=st.pinion.teeth,
        normal_module_m=st.normal_module_mm * MM,
        static_tangential_N=st.static_force_N.tangential,
        efficiency=st.efficiency,
        transmission_error_m=tuple(v * 1e-6 for v in law.transmission_error_um),
        transmission_error_phase_rad=tuple(math.radians(v) for v in law.transmission_error_phase_deg),
        stiffness_harmonics=tuple(law.stiffness_harmonics),
        stiffness_harmonics_phase_rad=tuple(math.radians(v) for v in law.stiffness_harmonics_phase_deg),
        damping_ratio=law.damping_ratio,
        law=law_name(law.stiffness),
        iso_normal_stiffness_N_m=k_n * 1000.0,
        linearisation_line_force_N=calibration_line_force_N(
            law.stiffness, st.face_width_mm, math.radians(st.normal_pressure_angle_deg),
            math.radians(st.helix_angle_deg), math.radians(st.base_helix_angle_deg)),
    )


def _coupled(table: Input | Load) -> CoupledInertia | None:
    """The body outside the reducer and its coupling (the schema gives both or neither)."""
    if table.inertia_kg_m2 is None or table.coupling_stiffness_Nm_rad is None:
        return None
    return CoupledInertia(table.inertia_kg_m2, SpringSpec(table.coupling_stiffness_Nm_rad,
                                                          table.coupling_damping_Nms_rad))


def _shafts(cfg: DesignFile, design: DesignResult) -> tuple[FlexibleShaft | None, ...]:
    out = []
    for k, stage in enumerate(cfg.stage[:-1]):
        s = stage.shaft
        out.append(None if s is None else FlexibleShaft(SpringSpec(s.stiffness_Nm_rad, s.damping_Nms_rad),
                                                        _output_inertia(design.stages[k])))
    return tuple(out) if any(s is not None for s in out) else ()


def motor_spec(inp: Input) -> MotorSpec | None:
    """The induction motor of an ``[input]`` table (None without ``motor``): rpm -> rad/s, kW -> W."""
    m = inp.motor
    if m is None or inp.drive == "torque":  # a torque drive prescribes the input torque: its motor is ignored
        return None
    params = {"star_delta": ((inp.switch_speed_rpm or 0.0) * RPM, 0.0),
              "soft_start": (inp.voltage_ramp_s or 0.0, inp.initial_voltage_fraction),
              "vfd": (inp.ramp_s, inp.torque_limit_Nm or 0.0)}.get(inp.starting, (0.0, 0.0))
    if m.torque_speed is not None:
        table = tuple((float(n) * RPM, float(t)) for n, t in m.torque_speed)
        return MotorSpec(m.synchronous_rpm * RPM, inp.starting, params, table=table)
    assert m.rated_power_kW is not None and m.rated_speed_rpm is not None and m.synchronous_speed_rpm is not None
    assert m.breakdown_torque_ratio is not None and m.locked_rotor_torque_ratio is not None  # the schema's rule
    try:
        spec = MotorSpec.nameplate(m.rated_power_kW * 1000.0, m.rated_speed_rpm * RPM, m.synchronous_speed_rpm * RPM,
                                   m.breakdown_torque_ratio, m.locked_rotor_torque_ratio, starting=inp.starting,
                                   start_parameters=params)
    except ValueError as exc:  # the schema keeps the nameplate consistent; a curve that still cannot be fitted
        raise ConfigError(str(exc), key="input.motor") from exc
    if inp.drive == "motor" and inp.starting == "vfd":
        return vfd_supply(spec, inp.speed_rad_s_value - m.rated_speed_rpm * RPM)
    return spec


def vfd_supply(spec: MotorSpec, shift_rad_s: float) -> MotorSpec:
    """A frequency converter's motor at a supply whose synchronous speed is ``shift_rad_s`` above the nameplate's:
    constant V/f keeps the curve's shape in slip speed (w_s - w), so the motor carries its rated torque at
    ``[input] speed_rpm`` (a speed sweep's row runs at the speed it is designed at) up to the base speed (the
    nameplate's synchronous speed); above it the field weakens (the curve scaled by (w_B / w_s')^2, the motor's
    ``base_speed_rad_s`` stays the nameplate's) and the rated torque slips further. Extended Kloss in slip speed
    Delta: T = 2 T_b (1 + a s_b) Delta Delta_b / (Delta^2 + Delta_b^2 + 2 a s_b Delta_b |Delta|), Delta_b = s_b w_s:
    unchanged with w_s' when s_b' = s_b w_s / w_s' and a' s_b' = a s_b."""
    if shift_rad_s == 0.0 or spec.table:
        return spec
    ws = spec.synchronous_speed_rad_s
    ws_new = ws + shift_rad_s
    if ws_new <= 0.0:
        raise ConfigError(f"a frequency converter cannot run the motor at this speed (its supply would be "
                          f"{ws_new / RPM:.4g} rpm synchronous)", key="input.speed_rpm")
    sb = spec.breakdown_slip * ws / ws_new
    return dataclasses.replace(spec, synchronous_speed_rad_s=ws_new, breakdown_slip=sb,
                               kloss_a=spec.kloss_a * spec.breakdown_slip / sb,
                               rated_speed_rad_s=spec.rated_speed_rad_s + shift_rad_s)


def load_spec(load_cfg: Load) -> LoadSpec:
    """The load of a ``[load]`` table: a table's speeds rpm -> rad/s, its reference torque the table's torque at the
    nominal output speed (the design's static load, ``torque_Nm_value``), as a speed law's is: the model's static
    forces, linearisation and viscous damping then hold at the load the run settles at."""
    fluct = tuple((f.amplitude_percent / 100.0, f.frequency_Hz) for f in load_cfg.fluctuation)
    if load_cfg.torque_speed is not None:
        table = tuple((float(n) * RPM, float(t)) for n, t in load_cfg.torque_speed)
        return LoadSpec(torque_Nm=load_cfg.torque_Nm_value, ramp_s=load_cfg.ramp_s, fluctuation=fluct,
                        table=table)
    return LoadSpec(torque_Nm=load_cfg.torque_Nm_value, ramp_s=load_cfg.ramp_s, fluctuation=fluct,
                    speed_exponent=load_cfg.speed_exponent)


def spec_from_design(cfg: DesignFile, design: DesignResult) -> ModelSpec:
    """The model parameters of a validated ``DesignFile`` and its ``DesignResult``."""
    meshes = tuple(model_kind(st).line(cfg, st, k, _mesh) for k, st in enumerate(design.stages))
    own = tuple(placed(m, checked_line_losses(st, k, m, model_kind(st).stage_model(cfg, st, k, m)),
                       design_kind(st).gear_pair) for k, (st, m) in enumerate(zip(design.stages, meshes, strict=True)))
    inp = cfg.input
    drive = DriveSpec(kind=inp.drive, speed_rad_s=inp.speed_rad_s_value, ramp_s=inp.ramp_s,
                      torque_Nm=inp.torque_Nm_value or 0.0,
                      ripple=tuple((r.amplitude_percent / 100.0, r.order) for r in inp.torque_ripple),
                      motor=motor_spec(inp))
    load = load_spec(cfg.load)
    return ModelSpec(meshes, tuple(s.inertia_kg_m2 for s in design.shafts), drive, load,
                     motor=_coupled(inp), drum=_coupled(cfg.load), shafts=_shafts(cfg, design),
                     stage_models=own if any(p is not None for p in own) else (),
                     stage_types=tuple(kinds.kind_of(st) for st in design.stages))


def _output_inertia(st: StageResult) -> float:
    return design_kind(st).inertia(st, "output")


def build_model(cfg: DesignFile, design: DesignResult) -> TorsionalModel:
    """The compiled torsional model of a validated ``DesignFile`` and its ``DesignResult``."""
    return TorsionalModel(spec_from_design(cfg, design))


def resonance_diagnostics(cfg: DesignFile, design: DesignResult) -> tuple[Diagnostic, ...]:
    """The drivetrain's resonance warnings for ``gearcli design`` and ``gearcli modes``: an excitation (a mesh or
    shaft order, an input torque ripple order, a load fluctuation) at the nominal speed within
    the band of a natural frequency of the linearised chain (the modes capability, at the boundary the drive
    imposes: a speed drive holds the input body, a torque drive leaves the chain free), naming the mode and
    its dominant element — the same messages ``simulate`` gives. Imports numpy, never scipy."""
    lay = Layout.of(spec_from_design(cfg, design))
    boundary = "clamped_input" if lay.speed_drive else "free"
    return tuple(dg.warning(dg.RESONANCE, r.message, **r.data, boundary=boundary)
                 for r in resonances(lay, boundary, duration_s=cfg.simulation.duration_s))


def motor_start_warnings(cfg: DesignFile, design: DesignResult) -> tuple[Diagnostic, ...]:
    """A motor drive that cannot start its load, for ``gearcli design``: its curves against the load reflected
    through the train (:mod:`gearcli.model.motor_start`, the physics of ``simulate``'s ``motor_stalls``), and a
    motor (a speed drive's described one too) loaded beyond its rated torque. Imports numpy, never scipy; nothing
    for a torque drive or a drive without a motor."""
    if cfg.input.drive == "torque" or cfg.input.motor is None:
        return ()
    from gearcli.model.motor_start import motor_start_diagnostics  # lazy: a motor drive's design only

    return motor_start_diagnostics(Layout.of(spec_from_design(cfg, design)))
