"""A planetary stage's planets in a run's result (``StageDynamics.planets``): imported by a file with planetary
stages only (:mod:`gearcli.simulate.planet_stats`), and by name from :mod:`gearcli.simulate.results`."""

from __future__ import annotations

from typing import TYPE_CHECKING

from gearcli.core.records import record

if TYPE_CHECKING:
    from gearcli.simulate.results import ChannelStats, DteStats


@record
class PlanetMeshDynamics:
    """One planet mesh over the statistics window: F_t (N) and the dynamic transmission error (um)."""

    tangential_N: ChannelStats
    dte_um: DteStats


@record
class PlanetDynamics:
    """One planet's sun and ring meshes' simulated forces."""

    index: int  # 1-based
    sun: PlanetMeshDynamics
    ring: PlanetMeshDynamics
