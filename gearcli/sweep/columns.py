"""The columns of a sweep's output, and one row from one simulation result: the mapping lives here only.

One row per point (docs: docs/sweeps.md): the varied keys (each named by its key path as the user wrote it),
``direction``, ``status`` (``ok``/``failed``), ``message``, then per stage k
``stage{k}_tangential_N_{mean,std,min,max}``, ``stage{k}_dte_um_{mean,rms,min,max}``,
``stage{k}_contact_loss_fraction``, ``stage{k}_dynamic_factor`` (steady-window max |F_t| / static),
``stage{k}_runup_factor`` (whole-run peak / static), a planetary stage's ``stage{k}_load_sharing_factor``
(the largest planet's window-mean sun-mesh |F_t| over the mean planet's, the sun torque's share; parallel stages have no such
column), then ``output_speed_rpm``, ``nfev`` (the point's evaluations: every run and check pass it took,
:func:`gearcli.simulate.spent.whole`), ``wall_s``. A cell the result does not provide is empty (``None``): the dynamic transmission error and
the contact-loss fraction come from the excitation outputs; :data:`STAGE_STATISTICS` reads them from
``StageDynamics.dte_um`` (an object with ``mean``/``rms``/``min``/``max``) and
``StageDynamics.contact_loss_fraction`` when those exist, so they fill in without touching the sweep.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import TypeAlias, cast

from gearcli.core.jsontypes import JsonScalar
from gearcli.simulate import spent
from gearcli.simulate.results import SimulationResult, StageDynamics

FIXED = ("direction", "status", "message")
TRAILING = ("output_speed_rpm", "nfev", "wall_s")
OK, FAILED = "ok", "failed"

#: one row of a sweep: column -> cell (a varied key's value, a statistic, the status, a message)
Row: TypeAlias = dict[str, JsonScalar]


def _attr(*path: str) -> Callable[[StageDynamics], float | None]:
    def get(stage: StageDynamics) -> float | None:
        obj: object = stage
        for name in path:
            obj = getattr(obj, name, None)
            if obj is None:
                return None
        value = float(cast(float, obj))
        return value if math.isfinite(value) else None

    return get


#: per-stage column suffix -> how to read it from one ``StageDynamics`` (the ONLY mapping)
STAGE_STATISTICS: dict[str, Callable[[StageDynamics], float | None]] = {
    "tangential_N_mean": _attr("tangential_N", "mean"),
    "tangential_N_std": _attr("tangential_N", "std"),
    "tangential_N_min": _attr("tangential_N", "min"),
    "tangential_N_max": _attr("tangential_N", "max"),
    "dte_um_mean": _attr("dte_um", "mean"),
    "dte_um_rms": _attr("dte_um", "rms"),
    "dte_um_min": _attr("dte_um", "min"),
    "dte_um_max": _attr("dte_um", "max"),
    "contact_loss_fraction": _attr("contact_loss_fraction"),
    "dynamic_factor": _attr("dynamic_factor"),
    "runup_factor": _attr("runup_factor"),
}


#: per-stage column suffixes of a planetary stage only -> how to read them from its ``StageDynamics``
PLANETARY_STATISTICS: dict[str, Callable[[StageDynamics], float | None]] = {
    "load_sharing_factor": _attr("load_sharing_factor"),
}


def stage_columns(n_stages: int, planetary: Sequence[int] = ()) -> list[str]:
    """Per stage k (1-based) its statistics; ``planetary``: the planetary stages' k, which add theirs."""
    return [f"stage{k}_{name}" for k in range(1, n_stages + 1)
            for name in (*STAGE_STATISTICS, *(PLANETARY_STATISTICS if k in planetary else ()))]


def columns(keys: Sequence[str], n_stages: int, planetary: Sequence[int] = ()) -> list[str]:
    return [*keys, *FIXED, *stage_columns(n_stages, planetary), *TRAILING]


def ok_row(values: Sequence[tuple[str, JsonScalar]], direction: str, result: SimulationResult, wall_s: float,
           n_stages: int, message: str = "", extra_nfev: int = 0) -> Row:
    row: Row = {**dict(values), "direction": direction, "status": OK, "message": message}
    for k, st in enumerate(result.stages[:n_stages], start=1):
        for name, get in STAGE_STATISTICS.items():
            row[f"stage{k}_{name}"] = get(st)
        if st.planets:  # a stage with planets: their load sharing
            for name, get in PLANETARY_STATISTICS.items():
                row[f"stage{k}_{name}"] = get(st)
    row["output_speed_rpm"] = result.output_speed_deg_s / 6.0
    row["nfev"] = spent.whole(result)[0] + extra_nfev  # every run it took (a jump's refinements: extra_nfev), as wall_s
    row["wall_s"] = wall_s
    return row


def failed_row(values: Sequence[tuple[str, JsonScalar]], direction: str, message: str, wall_s: float) -> Row:
    return {**dict(values), "direction": direction, "status": FAILED, "message": one_line(message),
            "wall_s": wall_s}


def one_line(message: str) -> str:
    """A message for one CSV cell: lines joined with '; '."""
    return "; ".join(line.strip() for line in str(message).splitlines() if line.strip())
