"""Natural frequencies against the swept input speed, for the Campbell diagram.

:func:`natural_frequencies_Hz` is the one call to the model's linearisation (today the undamped
frequencies ``simulate`` reports, from ``gearcli.simulate.choice``); swap it for the modes capability
when that lands. Mesh-order lines: stage s meshes at ``z_p,s n_s / 60`` Hz with ``n_s`` its pinion's rpm.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from gearcli.sweep.worker import Scene, load_point

SPEED_KEYS = ("input.speed_rpm", "input.speed_deg_s", "input.speed_rad_s")


def natural_frequencies_Hz(cfg, design) -> tuple[float, ...]:
    from gearcli.model import spec_from_design
    from gearcli.simulate.choice import choose_method

    spec = spec_from_design(cfg, design)
    return choose_method(spec, cfg.simulation.duration_s, "auto").natural_frequencies_Hz


@dataclass(frozen=True)
class CampbellPoint:
    input_rpm: float
    natural_Hz: tuple[float, ...]
    mesh_Hz: tuple[float, ...]  # first-order mesh frequency of each stage


def campbell(scene: Scene, key: str, values: Sequence[Any], fixed: Sequence[str] = ()) -> list[CampbellPoint]:
    """Natural and mesh frequencies at each swept input speed (the other keys at ``fixed`` overrides)."""
    from gearcli.design import compute_design

    out = []
    for v in values:
        cfg = load_point(scene, (*fixed, f"{key}={float(v)!r}"))
        design = compute_design(cfg)
        mesh = tuple(st.pinion.teeth * st.pinion.speed_rpm / 60.0 for st in design.stages)
        out.append(CampbellPoint(design.stages[0].pinion.speed_rpm, natural_frequencies_Hz(cfg, design), mesh))
    return out
