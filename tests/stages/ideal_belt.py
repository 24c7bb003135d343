"""A test-only stage kind: an ideal belt (or chain) drive, ``type = "test_belt"``, registered by its test only.

The drive joins the previous stage's output shaft (its input pulley, pitch diameter d_1) to a new shaft (its output
pulley, d_2): ratio i = d_2 / d_1, no slip and no loss (efficiency 1), the belt's stiffness along its tight span k
(N/m) and damping c (N s/m). The belt stretch is delta = r_1 theta_1 - r_2 theta_2 and its force
F = k delta + c delta' (a belt that stays tensioned: both signs carry force, as a pretensioned belt or a chain
with its slack span taken up). What the kind provides, one facet per layer, and nothing in gearcli names it:

- its schema table (``register_stage_table``);
- its design (``"design"``): ratio, pulley speeds and torques, the belt speed, the static span force T_2 / r_2
  and stretch F / k, the pulleys' inertias on the chain's shafts; it has no gear mesh, so it is not rated;
- its model (``"model"``): its line of action (the span: pulley radii as levers, no pressure or helix angle, the
  static span force) and a ``spring`` element on the stretch with the pulley radii as levers, as the stage's
  connector (role ``"stage"``: its force and stretch are the stage's statistics);
- its output (``"io"``): its design table, its design JSON object and its simulated statistics under the
  belt's names (span force, stretch).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Annotated, Any, Literal

from pydantic import Field

from gearcli.config.bounds_types import StrictTable
from gearcli.config.schema import register_stage_table
from gearcli.io.table_kit import _g, _quantity_table
from gearcli.model import elements
from gearcli.model.parts import Connector
from gearcli.model.spec import MM, MeshSpec, SpringSpec
from gearcli.stages import kinds

KIND = "test_belt"
RPM = 30.0 / math.pi  # rad/s -> rpm


class BeltStage(StrictTable):
    """``[[stage]] type = "test_belt"``: pulley pitch diameters and inertias, belt stiffness and damping."""

    type: Literal["test_belt"]
    pulley_in_diameter_mm: Annotated[float, Field(gt=0, le=1e4)]
    pulley_out_diameter_mm: Annotated[float, Field(gt=0, le=1e4)]
    stiffness_N_m: Annotated[float, Field(gt=0, le=1e12)]
    damping_Ns_m: Annotated[float, Field(ge=0, le=1e9)] = 0.0
    pulley_in_inertia_kg_m2: Annotated[float, Field(gt=0, le=1e6)]
    pulley_out_inertia_kg_m2: Annotated[float, Field(gt=0, le=1e6)]
    mesh: None = None  # no contact law (DesignFile.contact_for reads it)
    shaft: None = None  # no flexible output shaft

    @property
    def speed_ratio(self) -> float:
        return self.pulley_out_diameter_mm / self.pulley_in_diameter_mm

    @property
    def efficiency(self) -> float:
        return 1.0  # ideal: no slip, no loss


# ------------------------------------------------------------------------------------------------ design
@dataclass(frozen=True)
class BeltResult:
    """The designed belt stage (the design's stage result of this kind)."""

    index: int  # 1-based
    ratio: float
    efficiency: float
    pulley_in_diameter_mm: float
    pulley_out_diameter_mm: float
    input_speed_rpm: float
    output_speed_rpm: float
    output_speed_deg_s: float
    belt_speed_m_s: float
    input_torque_Nm: float
    output_torque_Nm: float
    span_force_N: float  # static tight-span force T_2 / r_2
    static_stretch_mm: float  # F / k
    stiffness_N_m: float
    damping_Ns_m: float
    pulley_in_inertia_kg_m2: float
    pulley_out_inertia_kg_m2: float
    type: str = KIND
    rating: None = None  # no gear mesh to rate


class BeltDesign:
    """The ``"design"`` facet: kinematics and statics of the ideal belt."""

    gear_pair = False  # not designed, checked or rated as a gear pair
    shares_load = False
    model_signs_forces = False

    def reverse_efficiency(self, table: object, k: int) -> float | None:
        return None

    def pair(self, table: object) -> object | None:
        return None  # no gear pair

    def result(self, cfg, pairs, k: int, kin, mesh) -> BeltResult:
        t: BeltStage = cfg.stage[k]
        w_in, w_out = kin.shaft_speeds_rad_s[k], kin.shaft_speeds_rad_s[k + 1]
        t_in, t_out = (v / 1000.0 for v in kin.stage_torques_Nmm[k])  # N m
        r_1, r_2 = 0.5e-3 * t.pulley_in_diameter_mm, 0.5e-3 * t.pulley_out_diameter_mm
        force = t_out / r_2
        return BeltResult(
            index=k + 1, ratio=t.speed_ratio, efficiency=t.efficiency, pulley_in_diameter_mm=t.pulley_in_diameter_mm,
            pulley_out_diameter_mm=t.pulley_out_diameter_mm, input_speed_rpm=w_in * RPM, output_speed_rpm=w_out * RPM,
            output_speed_deg_s=math.degrees(w_out), belt_speed_m_s=w_in * r_1, input_torque_Nm=t_in,
            output_torque_Nm=t_out, span_force_N=force, static_stretch_mm=force / t.stiffness_N_m * 1000.0,
            stiffness_N_m=t.stiffness_N_m, damping_Ns_m=t.damping_Ns_m,
            pulley_in_inertia_kg_m2=t.pulley_in_inertia_kg_m2, pulley_out_inertia_kg_m2=t.pulley_out_inertia_kg_m2)

    def inertia(self, result: BeltResult, side: str) -> float:
        return result.pulley_in_inertia_kg_m2 if side == "input" else result.pulley_out_inertia_kg_m2

    def diagnostics(self, result: BeltResult) -> tuple:
        return ()

    def check_inputs(self, cfg, k: int) -> None:
        return None

    def file_key(self, k: int, key: str) -> str:
        return key

    def meshes(self, result: BeltResult) -> list:
        return []  # no gear mesh: no contact law to report, nothing to rate

    def meetings(self, result: BeltResult, member: int) -> int:
        return 0  # no teeth (never asked: the pair's code reads gear pairs only)

    def idler(self, result: BeltResult, member: int) -> bool:
        return False

    def further_ratings(self, result: BeltResult) -> list:
        return []

    def output_speed_deg_s(self, result: BeltResult) -> float:
        return result.output_speed_deg_s

    def fastest_rad_s(self, cfg, result: BeltResult, k: int, inertia_in: float, inertia_out: float) -> float:
        r_1, r_2 = 0.5e-3 * result.pulley_in_diameter_mm, 0.5e-3 * result.pulley_out_diameter_mm
        return math.sqrt(result.stiffness_N_m * (r_1**2 / inertia_in + r_2**2 / inertia_out))


# ------------------------------------------------------------------------------------------------- model
@dataclass(frozen=True)
class BeltModel:
    """The belt in the chain (SI): a ``spring`` element on the stretch with levers r_1, r_2 between the input
    shaft's body and a new body for the output shaft."""

    radius_in_m: float
    radius_out_m: float
    stiffness_N_m: float
    damping_Ns_m: float = 0.0
    efficiency: float = 1.0
    reverse_efficiency: float = 1.0

    def place(self, k: int, bodies: list, conns: list, body, out_inertia: float) -> None:
        kind = elements.kind_of("spring")
        law = elements.law_of(kind).pack(SpringSpec(self.stiffness_N_m, self.damping_Ns_m))
        n = len(bodies)
        conns.append(Connector(kind, (n - 1, n), (self.radius_in_m, self.radius_out_m),
                               tuple(float(v) for v in law), f"stage {k + 1} belt", k, "stage"))
        body(out_inertia, f"shaft {k + 2}")


class BeltModelKind:
    """The ``"model"`` facet: the span as the stage's line of action, the belt as a spring on its stretch."""

    def line(self, cfg, st: BeltResult, k: int, pair_mesh) -> MeshSpec:
        r_1, r_2 = 0.5 * st.pulley_in_diameter_mm * MM, 0.5 * st.pulley_out_diameter_mm * MM
        return MeshSpec(base_radius_pinion_m=r_1, base_radius_gear_m=r_2, base_helix_angle_rad=0.0,
                        transverse_pressure_angle_rad=0.0, helix_angle_rad=0.0, stiffness_N_m_e=st.stiffness_N_m,
                        exponent=1.0, damping_Ns_m=st.damping_Ns_m, full_damping_m=1e-9,
                        static_tangential_N=st.span_force_N, law="belt", iso_normal_stiffness_N_m=0.0)

    def stage_model(self, cfg, st: BeltResult, k: int, mesh: MeshSpec) -> BeltModel:
        return BeltModel(mesh.base_radius_pinion_m, mesh.base_radius_gear_m, st.stiffness_N_m, st.damping_Ns_m)


def model_of(table: BeltStage) -> BeltModel:
    return BeltModel(0.5 * table.pulley_in_diameter_mm * MM, 0.5 * table.pulley_out_diameter_mm * MM,
                     table.stiffness_N_m, table.damping_Ns_m)


# ------------------------------------------------------------------------------------------------ output
#: the simulated stage statistics a belt has, under its names (the others are a gear mesh's)
SIMULATED = {"tangential_N": "span_force_N", "static_tangential_N": "static_span_force_N",
             "simulated_static_tangential_N": "simulated_static_span_force_N",
             "peak_tangential_N": "peak_span_force_N", "peak_time_s": "peak_time_s",
             "dynamic_factor": "dynamic_factor", "runup_factor": "runup_factor", "dte_um": "stretch_um",
             "error_estimate": "error_estimate"}


class BeltOutput:
    """The ``"io"`` facet: no gear columns, its own table, its JSON objects."""

    gear_columns = False
    pair_members = False
    load_sharing = False

    def design_tables(self, r, stages: list[BeltResult]) -> list:
        rows = [
            ("pulley d_1 / d_2 [mm]", [f"{_g(st.pulley_in_diameter_mm)} / {_g(st.pulley_out_diameter_mm)}"
                                       for st in stages]),
            ("ratio i = d_2/d_1", [_g(st.ratio, 6) for st in stages]),
            ("speed in / out [rpm]", [f"{_g(st.input_speed_rpm)} / {_g(st.output_speed_rpm)}" for st in stages]),
            ("belt speed [m/s]", [_g(st.belt_speed_m_s) for st in stages]),
            ("torque in / out [N·m]", [f"{_g(st.input_torque_Nm)} / {_g(st.output_torque_Nm)}" for st in stages]),
            ("span force F [N]", [_g(st.span_force_N) for st in stages]),
            ("stiffness k [N/m] / damping c [N·s/m]", [f"{_g(st.stiffness_N_m)} / {_g(st.damping_Ns_m)}"
                                                       for st in stages]),
            ("static stretch F/k [mm]", [_g(st.static_stretch_mm, 4) for st in stages]),
            ("rating", ["not rated (no gear mesh)" for _ in stages]),
        ]
        return [_quantity_table("belt stages", [f"stage {st.index}" for st in stages], rows)]

    def simulation_tables(self, r, stages: list) -> list:
        def stats(c) -> str:
            return f"{_g(c.mean)} / {_g(c.std, 3)} / {_g(c.min)} / {_g(c.max)}"

        rows = [
            ("span force mean / std / min / max [N]", [stats(st.tangential_N) for st in stages]),
            ("static span force T_2/r_2 [N]", [_g(st.static_tangential_N) for st in stages]),
            ("peak span force [N] at t [s]", [f"{_g(st.peak_tangential_N)} at {_g(st.peak_time_s, 3)}"
                                              for st in stages]),
            ("dynamic factor (window max / static)", [_g(st.dynamic_factor, 4) for st in stages]),
            ("stretch mean / rms / min / max [µm]", [f"{_g(st.dte_um.mean)} / {_g(st.dte_um.rms, 3)} / "
                                                     f"{_g(st.dte_um.min)} / {_g(st.dte_um.max)}" for st in stages]),
        ]
        return [_quantity_table(f"belt stages over the steady window {r.window_s[0]:.4g}–{r.window_s[1]:.4g} s",
                                [f"stage {st.index}" for st in stages], rows)]

    def json_stage(self, stage: dict[str, Any]) -> dict[str, Any]:
        stage.pop("rating", None)
        return {"index": stage.pop("index"), "type": stage.pop("type"), **stage, "rated": False}

    def json_simulated_stage(self, stage: dict[str, Any]) -> dict[str, Any]:
        return {"index": stage["index"], "type": KIND, **{SIMULATED[k]: v for k, v in stage.items() if k in SIMULATED}}


# ---------------------------------------------------------------------------------------- registration
FACETS = {"design": BeltDesign(), "model": BeltModelKind(), "io": BeltOutput()}


def register() -> None:
    """The kind's one registration: its table and one implementation per facet."""
    register_stage_table(KIND, BeltStage)
    for name, facet in FACETS.items():
        kinds.provide(KIND, name, facet)


def withdraw() -> None:
    """Undo :func:`register` (the registry is the process's; other tests expect the built-in kinds only)."""
    from gearcli.config.schema import DesignFile

    for name in ("table", *FACETS):
        kinds.withdraw(KIND, name)
    DesignFile.model_rebuild(force=True)
