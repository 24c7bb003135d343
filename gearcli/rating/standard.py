"""What a rating standard provides (``gearcli.rating``); what its rated meshes show the layers above is
``gearcli.results``' ``RatedMesh`` and ``RatedMember``, re-exported here."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Protocol, TypeVar

from gearcli.results import RatedMember, RatedMesh

if TYPE_CHECKING:
    from gearcli.config.schema import DesignFile
    from gearcli.diagnostics import Diagnostic
    from gearcli.rating.sn import SNCurve
    from gearcli.results import DesignResult, StageResult

__all__ = ["MODES", "RatedMember", "RatedMesh", "RatingStandard"]

MODES = ("pitting", "bending")  # the failure modes every standard rates: flank and tooth root
S = TypeVar("S")  # a run's stage summary (``gearcli.simulate.results.StageDynamics``, a layer above: read by its fields)


class RatingStandard(Protocol):
    """A strength-rating standard: registered under ``name`` (``[rating] standard``), its ratings titled ``title``."""

    name: str
    title: str

    def check_inputs(self, cfg: DesignFile) -> None:
        """Every key the standard needs is given (a ``DesignError`` naming the missing one)."""
        ...

    def rate_design(self, cfg: DesignFile, stages: tuple[StageResult, ...]
                    ) -> tuple[tuple[StageResult, ...], tuple[Diagnostic, ...]]:
        """The design's stages with their ratings (every mesh the stage has), and the rating's warnings."""
        ...

    def rate_simulation(self, cfg: DesignFile, design: DesignResult, stages: Sequence[S]
                        ) -> tuple[tuple[S, ...], list[Diagnostic]]:
        """With ``[rating] dynamic_factor = "simulated"``: the run's stage summaries rated at their simulated K_v
        (:mod:`gearcli.rating.dynamic`), and that rating's warnings; unchanged otherwise."""
        ...

    def sn_curve(self, cfg: DesignFile, member: RatedMember, treatment: str, mode: str, variant: str) -> SNCurve:
        """The S–N curve of a rated member of material ``treatment`` in failure ``mode``, Miner ``variant``."""
        ...

    def curve_name(self, mode: str) -> str:
        """How the life output names the curve of ``mode`` (``"Z_NT (ISO 6336-2:2006)"``)."""
        ...

    def table_rows(self, ratings: Sequence[RatedMesh], *, shared: bool) -> list[tuple[str, list[str]]]:
        """The rows of a rating table, one cell per rated mesh (``shared``: a planetary stage among them)."""
        ...
