"""The design re-rated at the simulated dynamic factor: ``[rating] dynamic_factor = "simulated"`` (issue 22).

Called by ``simulate`` after the run; above ``rating`` (the external pair) and ``rating_internal`` (the
planet–ring mesh), so neither imports the other (the design layer's inner contract, ARCHITECTURE.md).
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING

from gearcli.design.planetary import nominal_with_sharing, pair_equivalent, with_load_sharing
from gearcli.design.rating import rate_stage, ring_simulated_k_v, safety_diagnostics, stage_simulated_k_v
from gearcli.design.rating_internal import planet_ring_safety_diagnostics, rate_planet_ring

if TYPE_CHECKING:
    from gearcli.config.schema import DesignFile
    from gearcli.diagnostics import Diagnostic


def simulated_ratings(cfg: DesignFile, design, stages) -> tuple[tuple, list[Diagnostic]]:
    """With ``[rating] dynamic_factor = "simulated"``: simulate's stage summaries (``StageDynamics``) each with
    its ``rating`` at the simulated K_v, and the safety warnings of that rating; unchanged otherwise. A
    planetary stage's planet–ring mesh is rated too, at its own meshes' simulated K_v (``planet_ring_rating``)."""
    if cfg.rating is None or cfg.rating.dynamic_factor != "simulated":
        return tuple(stages), []
    pairs = pair_equivalent(cfg)  # a planetary stage is rated as its sun–planet mesh, its most loaded planet's
    out, diags = [], []
    for k, sd in enumerate(stages):
        k_v = stage_simulated_k_v(sd)
        shared = with_load_sharing(design.stages[k])
        rating = rate_stage(pairs, k, shared, simulated_k_v=k_v)
        if shared.planetary is not None:  # ISO's nominal σ_H0, σ_F0; K_gamma among the load factors
            rating = nominal_with_sharing(rating, shared.planetary.load_sharing_factor)
        rated = replace(design.stages[k], rating=rating)
        diags += safety_diagnostics(pairs, rated)
        ring = None
        if rated.planetary is not None and sd.planets:
            ring = rate_planet_ring(cfg, k, with_load_sharing(design.stages[k]),
                                    simulated_k_v=ring_simulated_k_v(sd, design.stages[k]))
            if ring is not None:
                mesh = replace(rated.planetary.planet_ring, rating=ring)
                diags += planet_ring_safety_diagnostics(cfg, replace(rated, planetary=replace(rated.planetary,
                                                                                               planet_ring=mesh)))
        out.append(replace(sd, rating=rated.rating, planet_ring_rating=ring))
    return tuple(out), diags
