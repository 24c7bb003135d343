"""A test-only stage kind: an ideal belt (or chain) drive, ``type = "test_belt"``, registered by its test only.

The drive joins the previous stage's output shaft (its input pulley, diameter d_1) to a new shaft (its output
pulley, d_2): ratio i = d_2 / d_1, the belt's stiffness along its tight span k (N/m) and damping c (N s/m); the
belt stretch is delta = r_1 theta_1 - r_2 theta_2 and its force F = k delta + c delta'. What a kind provides at
the seams that exist today: its schema table (``register_stage_table``) and its model (the ``"model"`` facet:
a ``StageModel`` that places the belt in the chain as a ``spring`` element with the pulley radii as levers).
It imports only gearcli's registry, schema and model modules; nothing in gearcli names it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Annotated, Literal

from pydantic import Field

from gearcli.config.bounds_types import StrictTable
from gearcli.config.schema import register_stage_table
from gearcli.model import elements
from gearcli.model.assembly import Connector
from gearcli.model.spec import MM, MeshSpec, SpringSpec
from gearcli.stages import kinds

KIND = "test_belt"


class BeltStage(StrictTable):
    """``[[stage]] type = "test_belt"``: pulley diameters, belt stiffness and damping, efficiency."""

    type: Literal["test_belt"]
    pulley_in_diameter_mm: Annotated[float, Field(gt=0, le=1e4)]
    pulley_out_diameter_mm: Annotated[float, Field(gt=0, le=1e4)]
    stiffness_N_m: Annotated[float, Field(gt=0, le=1e12)]
    damping_Ns_m: Annotated[float, Field(ge=0, le=1e9)] = 0.0
    efficiency: Annotated[float, Field(ge=0.1, le=1)] = 1.0
    mesh: None = None  # no contact law (DesignFile.contact_for reads it)
    shaft: None = None  # no flexible output shaft

    @property
    def speed_ratio(self) -> float:
        return self.pulley_out_diameter_mm / self.pulley_in_diameter_mm


@dataclass(frozen=True)
class BeltModel:
    """The belt in the chain (SI): a ``spring`` element with levers r_1, r_2 between the input shaft's body and
    a new body for the output shaft."""

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
                               tuple(float(v) for v in law), f"stage {k + 1} belt", k, "coupling"))
        body(out_inertia, f"shaft {k + 2}")


class BeltModelKind:
    """The ``"model"`` facet: no mesh law of its own to sign, its ``BeltModel`` from the stage's table."""

    def signed(self, mesh: MeshSpec, st: object) -> MeshSpec:
        return mesh

    def stage_model(self, cfg, st, k: int, mesh: MeshSpec) -> BeltModel:
        table = cfg.stage[k]
        return model_of(table)


def model_of(table: BeltStage) -> BeltModel:
    return BeltModel(0.5 * table.pulley_in_diameter_mm * MM, 0.5 * table.pulley_out_diameter_mm * MM,
                     table.stiffness_N_m, table.damping_Ns_m, table.efficiency, table.efficiency)


def register() -> None:
    """The kind's one registration: its table and its model facet."""
    register_stage_table(KIND, BeltStage)
    kinds.provide(KIND, "model", BeltModelKind())


def withdraw() -> None:
    """Undo :func:`register` (the registry is the process's; other tests expect the built-in kinds only)."""
    from gearcli.config.schema import DesignFile

    kinds.withdraw(KIND, "table")
    kinds.withdraw(KIND, "model")
    DesignFile.model_rebuild(force=True)
