"""The design facet of a stage kind (the design layer): what ``compute_design``, the checks, the shaft statics and
the layers above ask of a stage (its kinematics, its stage result, the inertias it puts on the chain's shafts, its
meshes, its own checks and warnings), and the lookup by the stage's ``type``.

The protocol and the lookup only: this module imports nothing of ``gearcli.design``, so every module inside it
may ask a stage's kind (the design layer's inner contract, ARCHITECTURE.md). The built-in kinds' facets are
``gearcli.stages.gear_design`` (imported, and so registered, by ``gearcli.design.compute``).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Iterable
from typing import TYPE_CHECKING, Protocol, TypeVar, cast

from gearcli.diagnostics import Diagnostic
from gearcli.errors import PluginError
from gearcli.results import MeshStiffness, RatedMesh, StageResult
from gearcli.stages import kinds

if TYPE_CHECKING:
    from gearcli.config.schema import DesignFile
    from gearcli.design.kinematics import Train

S = TypeVar("S")

class MeshResult(Protocol):
    """The pair's stage result: (the design file as pairs, stage index, train, meshes in parallel) -> StageResult;
    ``driving_side``: the train's torques give the mesh's driving-side force whichever way the load runs (a
    planetary's sun–planet mesh: over eta_m where the planet drives the sun), so its law calibrates at that force
    as it is (a parallel pair's F_t is the pinion's: over eta when the gear drives a reversed load)."""

    def __call__(self, cfg: DesignFile, k: int, kin: Train, planets: int = 1, /, *,
                 driving_side: bool = False) -> StageResult: ...



class DesignKind(Protocol):
    """What ``compute_design`` asks of a stage kind."""

    def reverse_efficiency(self, table: object, k: int) -> float | None:
        """The stage's efficiency with the power flowing back (None: its forward efficiency)."""

    def pair(self, table: object) -> object | None:
        """The stage as the pair the rating and the pair's code read (``cfg.pair(k)``): itself if it is one; None
        for a kind without a gear pair (a belt)."""

    @property
    def gear_pair(self) -> bool:
        """The stage is (or is designed as) a gear pair: the pair's checks and the rating read it, its columns
        are in the gear tables. A kind without one (a belt) gives its own figures and is not rated."""

    def result(self, cfg: DesignFile, pairs: DesignFile, k: int, kin: Train, mesh: MeshResult) -> StageResult:
        """The designed stage k (``mesh`` designs a pair)."""

    def inertia(self, result: StageResult, side: str) -> float:
        """The inertia the stage puts on its input (``side = "input"``) or output shaft, kg·m²."""

    def diagnostics(self, result: StageResult) -> tuple[Diagnostic, ...]:
        """The stage's own design warnings."""

    def check_inputs(self, cfg: DesignFile, k: int) -> None:
        """Refuse what the pair checks do not see (``DesignError`` naming the key)."""

    def file_key(self, k: int, key: str) -> str:
        """A key of the stage's pair (``stage[k].pinion.x``) as the design file names it."""

    @property
    def shares_load(self) -> bool:
        """The stage's meshes share its load among planets (its rating has K_γ; load-sharing columns)."""

    def meshes(self, result: StageResult) -> list[tuple[str, MeshStiffness | None]]:
        """The stage's meshes by name (a pair's ``mesh``) with the contact law at the static load."""

    def meetings(self, result: StageResult, member: int) -> int:
        """Contacts per turn of the pair's member (0 pinion, 1 gear) in its own frame (a planetary's sun: N)."""

    def idler(self, result: StageResult, member: int) -> bool:
        """The pair's member is an idler: its teeth bend both ways (ISO 6336-3's Y_M; a planetary's planet)."""

    def further_ratings(self, result: StageResult) -> list[RatedMesh]:
        """The ratings of the stage's meshes beyond its first (a planetary's planet–ring mesh)."""

    def output_speed_deg_s(self, result: StageResult) -> float:
        """The speed of the stage's output member, °/s (magnitude where the model counts it so)."""

    def fastest_rad_s(self, cfg: DesignFile, result: StageResult, k: int, inertia_in: float,
                      inertia_out: float) -> float:
        """The fastest angular frequency the stage puts in the model (the run budget's indicator,
        ``config.bounds``): its connector's stiffness on the two shafts' inertias, its excitation."""

    @property
    def model_signs_forces(self) -> bool:
        """The model's static force of the stage's mesh may differ in sign from the design's (its flank)."""


def design_kind(stage: object) -> DesignKind:
    """The design facet of a stage table or stage result (by its ``type``)."""
    return cast(DesignKind, kinds.facet(kinds.kind_of(stage), "design"))


def checked_figures(table: object, k: int) -> tuple[float, float]:
    """(speed_ratio, efficiency) of stage table k (0-based): a plug-in table's properties that are no ratio
    |omega_in / omega_out| (a finite number > 0) or no efficiency in (0, 1] are a
    :class:`~gearcli.errors.PluginError` naming the kind (the kinematics would carry them to every shaft)."""
    values = []
    for name, ok, what in (("speed_ratio", lambda v: v > 0.0, "a finite number > 0 (|ω_in / ω_out|)"),
                           ("efficiency", lambda v: 0.0 < v <= 1.0, "a number in (0, 1]")):
        v = kinds.table_figure(table, name)
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or not ok(v):
            raise PluginError(f'stage type "{kinds.kind_of(table)}" ({type(table).__module__}): its table\'s {name} '
                              f'is {v!r} for stage {k + 1}, not {what} (docs/plugins.md, "A stage kind")')
        values.append(float(v))
    return values[0], values[1]


RESULT_FIELDS = ("index", "ratio", "efficiency", "type", "rating")  # what every stage result has (docs/plugins.md)


def checked_result(table: object, k: int, result: StageResult) -> StageResult:
    """The design facet's result for stage k (0-based), or a :class:`~gearcli.errors.PluginError` naming the kind
    where it is no stage result (a frozen dataclass with :data:`RESULT_FIELDS`, its ``type`` the table's): every
    layer above reads its fields and its ``type``, and an object without them fails far from its cause."""
    kind = kinds.kind_of(table)
    lacks = [f for f in RESULT_FIELDS if not hasattr(result, f)]
    if dataclasses.is_dataclass(result) and not isinstance(result, type) and not lacks \
            and kinds.kind_of(result) == kind and result.index == k + 1:
        return result
    origin = getattr(kinds.facet(kind, "design"), "origin", None)
    why = (f"a {type(result).__name__}, not a dataclass" if not dataclasses.is_dataclass(result)
           or isinstance(result, type) else f"no {', '.join(lacks)}" if lacks
           else f'type "{kinds.kind_of(result)}"' if kinds.kind_of(result) != kind else f"index {result.index}")
    raise PluginError(f'stage type "{kind}"' + (f" ({origin})" if origin else "") + f": its design facet's result "
                      f"for stage {k + 1} has {why}: a stage result is a frozen dataclass with index (= {k + 1}), "
                      f'ratio, efficiency, type (= "{kind}") and rating (docs/plugins.md, "A stage kind")')


def checked_diagnostics(result: StageResult, diags: Iterable[object]) -> tuple[Diagnostic, ...]:
    """The design facet's own warnings for stage ``result``, or a :class:`~gearcli.errors.PluginError` naming the
    kind where one is no :class:`~gearcli.diagnostics.Diagnostic` (a text, say): every output reads its code and
    message, and a text there failed as gearcli's internal error far from its cause."""
    out = tuple(diags)
    wrong = next((d for d in out if not isinstance(d, Diagnostic)), None)
    if wrong is not None:
        kind = kinds.kind_of(result)
        origin = getattr(kinds.facet(kind, "design"), "origin", None)
        raise PluginError(f'stage type "{kind}"' + (f" ({origin})" if origin else "") + f": its design facet's "
                          f"diagnostics returned {wrong!r} for stage {result.index}, not a gearcli.diagnostics."
                          'Diagnostic (gearcli.diagnostics.warning(code, message); docs/plugins.md, "A stage kind")')
    return cast(tuple[Diagnostic, ...], out)


def pair_view(cfg: DesignFile) -> DesignFile:
    """``cfg`` with every stage seen as the pair its kind designs (the pair's code and the rating read it)."""
    stages = [design_kind(s).pair(s) or s for s in cfg.stage]
    if all(a is b for a, b in zip(stages, cfg.stage, strict=True)):
        return cfg
    return cfg.model_copy(update={"stage": stages})


def gear_pairs(stages: Iterable[S]) -> list[tuple[int, S]]:
    """(k, stage) of the stages (tables or results) whose kind is a gear pair, k 0-based in ``stages``."""
    return [(k, s) for k, s in enumerate(stages) if design_kind(s).gear_pair]


def member_name(stage: object, part: str) -> str:
    """A pair member (``part``: "pinion" or "gear") of stage table or result ``stage`` as the design file names it
    (a planetary's sun–planet pair: "sun", "planet"), for messages; diagnostics' ``member`` keys stay the pair's."""
    return design_kind(stage).file_key(0, f"stage[0].{part}.x").split(".")[1]


def file_key(cfg: DesignFile, key: str | None) -> str | None:
    """A key of the pair view (``stage[k].pinion.x``) as the design file names it (a planetary's ``sun.x``)."""
    if key is None or not key.startswith("stage["):
        return key
    k = int(key[len("stage["):key.index("]")])
    return design_kind(cfg.stage[k]).file_key(k, key) if k < len(cfg.stage) else key
