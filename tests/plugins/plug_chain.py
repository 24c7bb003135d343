"""A third party's plug-in, written from docs/plugins.md alone: a roller-chain stage kind ("test_chain") and a toy
Lewis rating standard ("test_toy_lewis"). ``tests/plugins/test_chain_plugin.py`` installs its text as a package of
its own (a ``*.dist-info`` with an entry point of the group ``gearcli.plugins``) in a tmp dir, and breaks copies of
it the ways a plug-in breaks.

Chain: sprockets of z1, z2 teeth, pitch p; mean ratio i = z2 / z1; efficiency eta (T_out = eta i T_in);
levers: the mean (chordal-average) radius r = z p / (2 pi), so r2 / r1 = i exactly; chain stiffness k (N/m)
along the tight span: F = k (r1 th1 - r2 th2) + c (...)' (the built-in mesh element, linear, no backlash, of
efficiency eta: the driver sprocket pulls F, the driven gets eta F); chain force: the driver's pull T_in / r1.

Toy Lewis: sigma_F = K_v F_t / (b m_n Y), Y = pi (0.154 - 0.912 / z) (Lewis, 20 deg full depth);
sigma_H = Z_E Z_H sqrt(K_v F_t / (b d1) (u + 1) / u), Z_E = 189.8 sqrt(MPa), Z_H = 2.495;
safeties: the material's limits over the stresses.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Annotated, Any, Literal

from pydantic import Field

from gearcli.config.bounds_types import StrictTable
from gearcli.config.schema import register_stage_table
from gearcli.errors import DesignError
from gearcli.model import elements
from gearcli.model.parts import Connector
from gearcli.model.spec import MeshSpec
from gearcli.rating import register as register_standard
from gearcli.rating.dynamic import stage_simulated_k_v
from gearcli.rating.sn import SNCurve
from gearcli.stages import kinds

KIND = "test_chain"
RPM = 30.0 / math.pi


class ChainStage(StrictTable):
    type: Literal["test_chain"]
    driver_teeth: Annotated[int, Field(ge=6, le=200)]
    driven_teeth: Annotated[int, Field(ge=6, le=400)]
    pitch_mm: Annotated[float, Field(gt=0, le=500)]
    chain_efficiency: Annotated[float, Field(gt=0, le=1)] = 0.98
    stiffness_N_m: Annotated[float, Field(gt=0, le=1e12)]
    damping_Ns_m: Annotated[float, Field(ge=0, le=1e9)] = 0.0
    driver_inertia_kg_m2: Annotated[float, Field(gt=0, le=1e6)]
    driven_inertia_kg_m2: Annotated[float, Field(gt=0, le=1e6)]
    mesh: None = None
    shaft: None = None

    @property
    def speed_ratio(self) -> float:
        return self.driven_teeth / self.driver_teeth

    @property
    def efficiency(self) -> float:
        return self.chain_efficiency


def mean_radius_m(z: int, pitch_mm: float) -> float:
    return z * pitch_mm * 1e-3 / (2.0 * math.pi)


@dataclass(frozen=True)
class ChainResult:
    index: int
    ratio: float
    efficiency: float
    driver_teeth: int
    driven_teeth: int
    pitch_mm: float
    input_speed_rpm: float
    output_speed_rpm: float
    output_speed_deg_s: float
    chain_speed_m_s: float
    input_torque_Nm: float
    output_torque_Nm: float
    chain_force_N: float
    stiffness_N_m: float
    damping_Ns_m: float
    driver_inertia_kg_m2: float
    driven_inertia_kg_m2: float
    type: str = KIND
    rating: None = None


class ChainDesign:
    gear_pair = False
    shares_load = False
    model_signs_forces = False

    def reverse_efficiency(self, table, k):
        return None

    def pair(self, table):
        return None

    def result(self, cfg, pairs, k, kin, mesh) -> ChainResult:
        t: ChainStage = cfg.stage[k]
        w_in, w_out = kin.shaft_speeds_rad_s[k], kin.shaft_speeds_rad_s[k + 1]
        t_in, t_out = (v / 1000.0 for v in kin.stage_torques_Nmm[k])
        r1 = mean_radius_m(t.driver_teeth, t.pitch_mm)
        return ChainResult(
            index=k + 1, ratio=t.speed_ratio, efficiency=t.efficiency, driver_teeth=t.driver_teeth,
            driven_teeth=t.driven_teeth, pitch_mm=t.pitch_mm, input_speed_rpm=w_in * RPM,
            output_speed_rpm=w_out * RPM, output_speed_deg_s=math.degrees(w_out),
            chain_speed_m_s=w_in * r1, input_torque_Nm=t_in,
            output_torque_Nm=t_out, chain_force_N=t_in / r1, stiffness_N_m=t.stiffness_N_m,
            damping_Ns_m=t.damping_Ns_m, driver_inertia_kg_m2=t.driver_inertia_kg_m2,
            driven_inertia_kg_m2=t.driven_inertia_kg_m2)

    def inertia(self, result, side):
        return result.driver_inertia_kg_m2 if side == "input" else result.driven_inertia_kg_m2

    def diagnostics(self, result):
        return ()

    def check_inputs(self, cfg, k):
        return None

    def file_key(self, k, key):
        return key

    def meshes(self, result):
        return []

    def meetings(self, result, member):
        return 0

    def idler(self, result, member):
        return False

    def further_ratings(self, result):
        return []

    def output_speed_deg_s(self, result):
        return result.output_speed_deg_s

    def fastest_rad_s(self, cfg, result, k, inertia_in, inertia_out):
        r1 = mean_radius_m(result.driver_teeth, result.pitch_mm)
        r2 = mean_radius_m(result.driven_teeth, result.pitch_mm)
        return math.sqrt(result.stiffness_N_m * (r1**2 / inertia_in + r2**2 / inertia_out))


@dataclass(frozen=True)
class ChainModel:
    r1: float
    r2: float
    line: MeshSpec  # the spans as a linear contact without backlash (either span pulls), of efficiency eta
    efficiency: float = 1.0  # its loss is its connector's
    reverse_efficiency: float = 1.0

    def place(self, k, bodies, conns, body, out_inertia):
        kind = elements.kind_of("mesh")  # a lossy element: the chain's loss acts in the dynamics
        law = elements.law_of(kind).pack(self.line)
        n = len(bodies)
        conns.append(Connector(kind, (n - 1, n), (self.r1, self.r2), tuple(float(v) for v in law),
                               f"stage {k + 1} chain", k, "stage"))
        body(out_inertia, f"shaft {k + 2}")


class ChainModelKind:
    def line(self, cfg, st, k, pair_mesh) -> MeshSpec:
        r1, r2 = mean_radius_m(st.driver_teeth, st.pitch_mm), mean_radius_m(st.driven_teeth, st.pitch_mm)
        return MeshSpec(base_radius_pinion_m=r1, base_radius_gear_m=r2, base_helix_angle_rad=0.0,
                        transverse_pressure_angle_rad=0.0, helix_angle_rad=0.0, stiffness_N_m_e=st.stiffness_N_m,
                        exponent=1.0, damping_Ns_m=st.damping_Ns_m, full_damping_m=1e-9,
                        static_tangential_N=st.chain_force_N, law="chain", iso_normal_stiffness_N_m=0.0)

    def stage_model(self, cfg, st, k, mesh):
        return ChainModel(mesh.base_radius_pinion_m, mesh.base_radius_gear_m, replace(mesh, efficiency=st.efficiency))


SIMULATED = {"tangential_N": "chain_force_N", "static_tangential_N": "static_chain_force_N",
             "peak_tangential_N": "peak_chain_force_N", "dynamic_factor": "dynamic_factor", "dte_um": "stretch_um"}


class ChainOutput:
    pair_members = False
    pair_names = None
    load_sharing = False

    def design_tables(self, r, stages):
        from rich.table import Table

        t = Table(title="chain stages")
        t.add_column("quantity")
        for st in stages:
            t.add_column(f"stage {st.index}")
        for label, attr in (("ratio z2/z1", "ratio"), ("chain speed [m/s]", "chain_speed_m_s"),
                            ("torque in [N·m]", "input_torque_Nm"), ("torque out [N·m]", "output_torque_Nm"),
                            ("chain force [N]", "chain_force_N")):
            t.add_row(label, *[f"{getattr(st, attr):.5g}" for st in stages])
        return [t]

    def simulation_tables(self, r, stages):
        from rich.table import Table

        t = Table(title="chain stages (simulated)")
        t.add_column("quantity")
        for st in stages:
            t.add_column(f"stage {st.index}")
        t.add_row("chain force mean [N]", *[f"{st.tangential_N.mean:.5g}" for st in stages])
        return [t]

    def json_stage(self, stage: dict[str, Any]) -> dict[str, Any]:
        stage.pop("rating", None)
        return {"index": stage.pop("index"), "type": stage.pop("type"), **stage, "rated": False}

    def json_simulated_stage(self, stage: dict[str, Any]) -> dict[str, Any]:
        return {"index": stage["index"], "type": KIND, **{SIMULATED[k]: v for k, v in stage.items() if k in SIMULATED}}


# ---------------------------------------------------------------------------------------------- the standard
LEWIS = "test_toy_lewis"
TITLE = "toy Lewis (a test plug-in)"
Z_E, Z_H = 189.8, 2.495
CURVES = {"pitting": ((1e5, 1.6), (5e7, 1.0), (1e10, 1.0)), "bending": ((1e4, 2.5), (3e6, 1.0), (1e10, 1.0))}


def lewis_y(z: int) -> float:
    return math.pi * (0.154 - 0.912 / z)


@dataclass(frozen=True)
class LewisMember:
    load_cycles: float
    Y: float
    sigma_H_MPa: float
    sigma_F_MPa: float
    S_H: float
    S_F: float

    def safety(self, mode):
        return self.S_H if mode == "pitting" else self.S_F

    def stress_MPa(self, mode):
        return self.sigma_H_MPa if mode == "pitting" else self.sigma_F_MPa


@dataclass(frozen=True)
class LewisRating:
    standard: str
    K_v: float
    K_v_source: str
    pinion: LewisMember
    gear: LewisMember

    def factor_table(self):
        return {"K_v": self.K_v, "K_v_source": self.K_v_source, "Y_pinion": self.pinion.Y, "Y_gear": self.gear.Y}


def _rate(cfg, k, st, k_v, source):
    f_t, b, m = abs(st.static_force_N.tangential), st.face_width_mm, st.normal_module_mm
    u = st.gear.teeth / st.pinion.teeth
    s_h = Z_E * Z_H * math.sqrt(k_v * f_t / (b * st.pinion.pitch_diameter_mm) * (u + 1.0) / u)
    members = []
    for part in ("pinion", "gear"):
        g = getattr(st, part)
        mat = cfg.materials[getattr(cfg.stage[k], part).material]
        y = lewis_y(g.teeth)
        s_f = k_v * f_t / (b * m * y)
        members.append(LewisMember(60.0 * abs(g.speed_rpm) * cfg.rating.required_life_h, y, s_h, s_f,
                                   mat.contact_fatigue_limit_MPa / s_h, mat.bending_fatigue_limit_MPa / s_f))
    return LewisRating(TITLE, k_v, source, *members)


class ToyLewis:
    name = LEWIS
    title = TITLE

    def check_inputs(self, cfg):
        for k, stage in enumerate(cfg.stage):
            if getattr(stage, "type", None) == "planetary":
                raise DesignError("test_toy_lewis rates parallel stages only", key=f"stage[{k}].type")
            for part in ("pinion", "gear"):
                m = getattr(stage, part, None)
                if m is None:
                    continue
                mat = cfg.materials.get(m.material)
                for key in ("contact_fatigue_limit_MPa", "bending_fatigue_limit_MPa"):
                    if mat is not None and getattr(mat, key) is None:
                        raise DesignError(f"test_toy_lewis needs {key}", key=f"materials.{m.material}.{key}")

    def _k_v(self, cfg):
        given = cfg.rating.dynamic_factor
        return (given, "given") if isinstance(given, float) else (1.0, "none")

    def rate_design(self, cfg, stages):
        k_v, src = self._k_v(cfg)
        return tuple(st if st.type not in (None, "parallel") else replace(st, rating=_rate(cfg, k, st, k_v, src))
                     for k, st in enumerate(stages)), ()

    def rate_simulation(self, cfg, design, stages):
        if cfg.rating.dynamic_factor != "simulated":
            return tuple(stages), []
        return tuple(sd if design.stages[k].type not in (None, "parallel") else
                     replace(sd, rating=_rate(cfg, k, design.stages[k], stage_simulated_k_v(sd), "simulated"))
                     for k, sd in enumerate(stages)), []

    def sn_curve(self, cfg, member, treatment, mode, variant):
        mat_limit = member.sigma_H_MPa * member.S_H if mode == "pitting" else member.sigma_F_MPa * member.S_F
        return SNCurve(CURVES[mode], mat_limit, variant, optimum=True)

    def curve_name(self, mode):
        return f"toy Lewis {mode} line"

    def table_rows(self, ratings, *, shared):
        rows = [("K_v", [f"{r.K_v:.4g}" for r in ratings])]
        for mode in ("pitting", "bending"):
            rows.append((f"{mode} stress p / g [MPa]",
                         [f"{r.pinion.stress_MPa(mode):.4g} / {r.gear.stress_MPa(mode):.4g}" for r in ratings]))
            rows.append((f"{mode} safety p / g", [f"{r.pinion.safety(mode):.4g} / {r.gear.safety(mode):.4g}"
                                                  for r in ratings]))
        return rows


def register() -> None:
    register_stage_table(KIND, ChainStage)
    kinds.provide(KIND, "design", ChainDesign())
    kinds.provide(KIND, "model", ChainModelKind())
    kinds.provide(KIND, "io", ChainOutput())
    register_standard(ToyLewis())


def withdraw() -> None:
    """Undo :func:`register` in a test process (the registries are the process's)."""
    from gearcli.config.schema import DesignFile
    from gearcli.rating.registry import withdraw as withdraw_standard

    for facet in ("table", "design", "model", "io"):
        kinds.withdraw(KIND, facet)
    withdraw_standard(LEWIS)
    DesignFile.model_rebuild(force=True)
