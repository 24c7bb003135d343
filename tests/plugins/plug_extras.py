"""A third party's plug-in, written from docs/plugins.md alone and installed by its tests the way pip installs a
package (a ``*.dist-info`` with an ``entry_points.txt`` of the group ``gearcli.plugins`` naming :func:`register`):

- a rating standard ``test_iso6336_marine``: ISO 6336:2006 method B with a classification society's minimum
  safeties (S_Hmin raised to 1.4, S_Fmin to 1.8): every factor and safety ISO's, the permissible stresses
  sigma_HP = sigma_HG / S_Hmin and sigma_FP = sigma_FG / S_Fmin and the warnings at the raised minima, its ratings
  titled :data:`TITLE`;
- a stage kind ``test_fixed_ratio``: an ideal speed ratio i = omega_in / omega_out (no loss) with a torsional
  stiffness k on its input shaft (twist = theta_in - i theta_out), its input and output inertias; not rated;
- a model element ``test_plugin_spring`` (``plug_element.py``) the stage kind places with ``law =
  "test_plugin_spring"``.

And the misbehaving standards the guard is tested with (:data:`MISBEHAVING`), registered by their test only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Annotated, Literal

from pydantic import Field

from gearcli.config.bounds_types import StrictTable
from gearcli.config.schema import register_stage_table
from gearcli.design.iso6336 import ISO6336
from gearcli.model import elements
from gearcli.model.parts import Connector
from gearcli.model.spec import MeshSpec, SpringSpec
from gearcli.rating import register as register_standard
from gearcli.stages import kinds

MARINE = "test_iso6336_marine"
TITLE = "ISO 6336:2006 method B, marine minima (a test plug-in)"
S_H_MIN, S_F_MIN = 1.4, 1.8
KIND = "test_fixed_ratio"
RPM = 30.0 / math.pi


# ------------------------------------------------------------------------------------------- the standard
def _raised(cfg):
    """The file with its minimum safeties raised to the standard's."""
    r = cfg.rating
    return cfg.model_copy(update={"rating": r.model_copy(update={
        "min_safety_pitting": max(S_H_MIN, r.min_safety_pitting),
        "min_safety_bending": max(S_F_MIN, r.min_safety_bending)})})


def _titled(stage, ring: bool = True):
    """The stage's ratings under this standard's title: its rating, and a planetary stage's planet–ring rating
    (a design's ``planetary.planet_ring.rating``, a run's ``planet_ring_rating``)."""
    if getattr(stage, "rating", None) is None:
        return stage
    stage = replace(stage, rating=replace(stage.rating, standard=TITLE))
    if not ring:
        return stage
    if getattr(stage, "planet_ring_rating", None) is not None:
        return replace(stage, planet_ring_rating=replace(stage.planet_ring_rating, standard=TITLE))
    p = getattr(stage, "planetary", None)
    if p is not None and p.planet_ring.rating is not None:
        ring_mesh = replace(p.planet_ring, rating=replace(p.planet_ring.rating, standard=TITLE))
        return replace(stage, planetary=replace(p, planet_ring=ring_mesh))
    return stage


class Marine:
    name = MARINE
    title = TITLE

    def check_inputs(self, cfg) -> None:
        ISO6336.check_inputs(cfg)

    def rate_design(self, cfg, stages):
        rated, diags = ISO6336.rate_design(_raised(cfg), stages)
        return tuple(_titled(s) for s in rated), diags

    def rate_simulation(self, cfg, design, stages):
        rated, diags = ISO6336.rate_simulation(_raised(cfg), design, stages)
        return tuple(_titled(s) for s in rated), diags

    def sn_curve(self, cfg, member, treatment, mode, variant):
        return ISO6336.sn_curve(_raised(cfg), member, treatment, mode, variant)

    def rate_at_force(self, cfg, stage, force_ratio):
        """Life's load classes re-rated as ISO re-rates them (every load factor at the class's load)."""
        rating = ISO6336.rate_at_force(_raised(cfg), stage, force_ratio)
        return None if rating is None else replace(rating, standard=TITLE)

    def curve_name(self, mode: str) -> str:
        return ISO6336.curve_name(mode)

    def table_rows(self, ratings, *, shared: bool):
        return ISO6336.table_rows(ratings, shared=shared)


# ------------------------------------------------------------------------------------------ the stage kind
class FixedRatioStage(StrictTable):
    type: Literal["test_fixed_ratio"]
    ratio: Annotated[float, Field(gt=0, le=1e4)]
    stiffness_Nm_rad: Annotated[float, Field(gt=0, le=1e12)]  # on the input shaft
    damping_Nms_rad: Annotated[float, Field(ge=0, le=1e9)] = 0.0
    input_inertia_kg_m2: Annotated[float, Field(gt=0, le=1e6)]
    output_inertia_kg_m2: Annotated[float, Field(gt=0, le=1e6)]
    law: Literal["spring", "test_plugin_spring"] = "spring"  # the element on the twist (the plug-in's own, or not)
    mesh: None = None  # no contact law
    shaft: None = None  # no flexible output shaft

    @property
    def speed_ratio(self) -> float:
        return self.ratio

    @property
    def efficiency(self) -> float:
        return 1.0


@dataclass(frozen=True)
class FixedRatioResult:
    index: int
    ratio: float
    efficiency: float
    input_speed_rpm: float
    output_speed_rpm: float
    output_speed_deg_s: float
    input_torque_Nm: float
    output_torque_Nm: float
    stiffness_Nm_rad: float
    damping_Nms_rad: float
    static_twist_deg: float
    law: str
    input_inertia_kg_m2: float
    output_inertia_kg_m2: float
    type: str = KIND
    rating: None = None


class FixedRatioDesign:
    gear_pair = False
    shares_load = False
    model_signs_forces = False

    def reverse_efficiency(self, table, k):
        return None

    def pair(self, table):
        return None

    def result(self, cfg, pairs, k, kin, mesh):
        t = cfg.stage[k]
        w_in, w_out = kin.shaft_speeds_rad_s[k], kin.shaft_speeds_rad_s[k + 1]
        t_in, t_out = (v / 1000.0 for v in kin.stage_torques_Nmm[k])
        return FixedRatioResult(k + 1, t.ratio, 1.0, w_in * RPM, w_out * RPM, math.degrees(w_out), t_in, t_out,
                                t.stiffness_Nm_rad, t.damping_Nms_rad, math.degrees(t_in / t.stiffness_Nm_rad),
                                t.law, t.input_inertia_kg_m2, t.output_inertia_kg_m2)

    def inertia(self, result, side):
        return result.input_inertia_kg_m2 if side == "input" else result.output_inertia_kg_m2

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
        i = result.ratio
        return math.sqrt(result.stiffness_Nm_rad * (1.0 / inertia_in + i * i / inertia_out))


@dataclass(frozen=True)
class FixedRatioModel:
    ratio: float
    stiffness_Nm_rad: float
    damping_Nms_rad: float
    law: str = "spring"
    efficiency: float = 1.0
    reverse_efficiency: float = 1.0

    def place(self, k, bodies, conns, body, out_inertia):
        kind = elements.kind_of(self.law)
        law = elements.law_of(kind).pack(SpringSpec(self.stiffness_Nm_rad, self.damping_Nms_rad))
        n = len(bodies)  # twist = 1 theta_in - i theta_out: levers (1 m, i m), the "force" the input torque
        conns.append(Connector(kind, (n - 1, n), (1.0, self.ratio), tuple(float(v) for v in law),
                               f"stage {k + 1} fixed ratio", k, "stage"))
        body(out_inertia, f"shaft {k + 2}")


class FixedRatioModelKind:
    def line(self, cfg, st, k, pair_mesh):
        return MeshSpec(base_radius_pinion_m=1.0, base_radius_gear_m=st.ratio, base_helix_angle_rad=0.0,
                        transverse_pressure_angle_rad=0.0, helix_angle_rad=0.0, stiffness_N_m_e=st.stiffness_Nm_rad,
                        exponent=1.0, damping_Ns_m=st.damping_Nms_rad, full_damping_m=1e-9,
                        static_tangential_N=st.input_torque_Nm, law=KIND, iso_normal_stiffness_N_m=0.0)

    def stage_model(self, cfg, st, k, mesh):
        return FixedRatioModel(st.ratio, st.stiffness_Nm_rad, st.damping_Nms_rad, st.law)


SIMULATED = {"tangential_N": "input_torque_Nm", "static_tangential_N": "static_input_torque_Nm",
             "peak_tangential_N": "peak_input_torque_Nm", "peak_time_s": "peak_time_s",
             "dynamic_factor": "dynamic_factor"}


class FixedRatioOutput:
    pair_members = False
    pair_names = None
    load_sharing = False

    def design_tables(self, r, stages):
        from rich.table import Table

        t = Table(title="fixed-ratio stages")
        t.add_column("quantity")
        for st in stages:
            t.add_column(f"stage {st.index}")
        t.add_row("ratio", *[f"{st.ratio:g}" for st in stages])
        t.add_row("torque in / out [N·m]", *[f"{st.input_torque_Nm:.6g} / {st.output_torque_Nm:.6g}" for st in stages])
        return [t]

    def simulation_tables(self, r, stages):
        from rich.table import Table

        t = Table(title="fixed-ratio stages over the window")
        t.add_column("quantity")
        for st in stages:
            t.add_column(f"stage {st.index}")
        t.add_row("input torque mean [N·m]", *[f"{st.tangential_N.mean:.6g}" for st in stages])
        return [t]

    def json_stage(self, stage):
        stage.pop("rating", None)
        return {"index": stage.pop("index"), "type": stage.pop("type"), **stage, "rated": False}

    def json_simulated_stage(self, stage):
        return {"index": stage["index"], "type": KIND, **{SIMULATED[k]: v for k, v in stage.items() if k in SIMULATED}}


FACETS = {"design": FixedRatioDesign(), "model": FixedRatioModelKind(), "io": FixedRatioOutput()}


def register() -> None:
    """The entry point (``gearcli.plugins``): the standard and the stage kind."""
    import plug_element

    elements.register(plug_element)  # the Python engine only (compiled=False): the kernel and its cache unchanged
    register_standard(Marine())
    register_stage_table(KIND, FixedRatioStage)
    for name, facet in FACETS.items():
        kinds.provide(KIND, name, facet)


def withdraw() -> None:
    from gearcli.config.schema import DesignFile
    from gearcli.rating.registry import withdraw as withdraw_standard

    withdraw_standard(MARINE)
    for name in ("table", *FACETS):
        kinds.withdraw(KIND, name)
    DesignFile.model_rebuild(force=True)


# ------------------------------------------------------------------------------ standards that misbehave
class _Misbehaving(Marine):
    """ISO's rating, then one thing wrong (``how``)."""

    def __init__(self, how: str):
        self.name, self.how = f"test_bad_{how}", how

    def rate_design(self, cfg, stages):
        rated, diags = super().rate_design(cfg, stages)
        if self.how == "raises":
            raise ZeroDivisionError("float division by zero")
        if self.how == "nan":
            st = rated[0]
            return (replace(st, rating=replace(st.rating, pinion=replace(st.rating.pinion, S_H=math.nan))),
                    *rated[1:]), diags
        if self.how == "untitled":
            return tuple(replace(s, rating=replace(s.rating, standard="ISO 6336:2006 method B")) for s in rated), diags
        if self.how == "dict":
            return tuple(replace(s, rating={"S_H": 1.0}) for s in rated), diags
        if self.how == "short":
            return rated[:1], diags
        if self.how == "ring_untitled":  # a planetary stage's planet–ring rating left ISO's
            return tuple(_titled(s, ring=False) for s in ISO6336.rate_design(_raised(cfg), stages)[0]), diags
        return rated, (*diags, "a plain string")  # warning_text


MISBEHAVING = ("raises", "nan", "untitled", "dict", "short", "warning_text", "ring_untitled")
