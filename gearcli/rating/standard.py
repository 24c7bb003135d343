"""What a rating standard provides and what its rated meshes show the layers above (``gearcli.rating``)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Protocol

if TYPE_CHECKING:
    from gearcli.config.schema import DesignFile
    from gearcli.diagnostics import Diagnostic
    from gearcli.rating.sn import SNCurve
    from gearcli.results import DesignResult, StageDynamics, StageResult

MODES = ("pitting", "bending")  # the failure modes every standard rates: flank and tooth root


class RatedMember(Protocol):
    """One member of a rated mesh: its load cycles, and per failure mode its safety and its stress."""

    @property
    def load_cycles(self) -> float: ...

    def safety(self, mode: str) -> float:
        """The safety factor against ``mode`` ("pitting" or "bending")."""
        ...

    def stress_MPa(self, mode: str) -> float:
        """The rated stress of ``mode`` at the rating's operating point (contact or root stress)."""
        ...


class RatedMesh(Protocol):
    """A mesh rated by a standard: its title (JSON ``standard``), its dynamic factor and where it came from, its two
    members (``pinion`` driving, ``gear`` driven), and its factor table by name."""

    @property
    def standard(self) -> str: ...

    @property
    def K_v(self) -> float: ...

    @property
    def K_v_source(self) -> str: ...

    @property
    def pinion(self) -> RatedMember: ...

    @property
    def gear(self) -> RatedMember: ...

    def factor_table(self) -> Mapping[str, float | str]:
        """The mesh-level factors by their standard's names."""
        ...


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

    def rate_simulation(self, cfg: DesignFile, design: DesignResult, stages: Sequence[StageDynamics]
                        ) -> tuple[tuple[StageDynamics, ...], list[Diagnostic]]:
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
