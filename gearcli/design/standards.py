"""The design's rating standard: ``[rating] standard`` looked up in :mod:`gearcli.rating`'s registry."""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING, Any, TypeVar

from gearcli import diagnostics as dg
from gearcli.errors import ConfigError, DesignError
from gearcli.rating import registry

if TYPE_CHECKING:
    from gearcli.config.schema import DesignFile
    from gearcli.rating.standard import RatingStandard
    from gearcli.results import DesignResult

Run = TypeVar("Run")  # a run (``gearcli.simulate.results.SimulationResult``, a layer above: read by its fields)


def standard_of(cfg: DesignFile) -> RatingStandard:
    """The standard ``[rating] standard`` names (``cfg.rating`` must be present); an unknown name is a
    ``DesignError`` (exit 2) naming ``rating.standard`` and the registered names."""
    assert cfg.rating is not None
    # lazy: start-up time, the rating's modules load only for a rated design (this import registers ISO 6336)
    import gearcli.design.iso6336  # noqa: F401

    try:
        return registry.standard(cfg.rating.standard)
    except ConfigError as exc:
        raise DesignError(exc.message, key=exc.key) from None


def with_simulated_rating(cfg: DesignFile, design: DesignResult, run: Run) -> Run:
    """A run of the design with ``[rating] dynamic_factor = "simulated"``: its stage summaries rated by the file's
    standard at their simulated K_v (``stages[k].rating``), the rating's new warnings appended; the run unchanged
    otherwise. The facade composes it after ``simulate`` (simulate knows no standard)."""
    if cfg.rating is None or cfg.rating.dynamic_factor != "simulated":
        return run
    result: Any = run  # a SimulationResult
    stages, diags = standard_of(cfg).rate_simulation(cfg, design, result.stages)
    new = [d for d in diags if d.message not in result.warnings]
    if result.steady is not None and result.steady.settled is False:  # never silently: K_v carries the transient
        if result.steady.mode == "periodic":  # a state the motion never settles into (its own warning)
            why = ("comes from a periodic state the motion does not settle into (see its warning): the motion from "
                   "rest keeps an undamped vibration; give the meshes damping")
        else:
            why = ("comes from a window that is not settled (it includes the start-up transient, see the window's "
                   'warning): give a longer simulation.duration_s or [simulation] steady = "periodic"')
        new.append(dg.warning(dg.WINDOW_NOT_SETTLED, '[rating] dynamic_factor = "simulated": the K_v the stages are '
                              f"rated at {why}", statistic="K_v"))
    return replace(result, stages=stages, warnings=result.warnings + dg.messages(new),
                   diagnostics=result.diagnostics + tuple(new))
