"""Natural frequencies against the swept input speed, for the Campbell diagram.

:func:`natural_frequencies_Hz` is the one call to the modes capability (the undamped
frequencies of ``gearcli modes``). Mesh-order lines: stage s meshes at ``z_p,s n_s / 60`` Hz with ``n_s`` its pinion's rpm.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from gearcli.design import compute_design
from gearcli.model.modes import modal_analysis
from gearcli.scene import build_model
from gearcli.sweep.worker import Scene, load_point

SPEED_KEYS = ("input.speed_rpm", "input.speed_deg_s", "input.speed_rad_s")


def natural_frequencies_Hz(cfg, design) -> tuple[float, ...]:
    """The modes capability's frequencies (``gearcli modes``) at the boundary the drive imposes: a speed
    drive holds the input body (``clamped_input``), a torque drive leaves the chain ``free``; the rigid
    mode (0 Hz) left out."""
    lay = build_model(cfg, design).layout
    boundary = "clamped_input" if lay.speed_drive else "free"
    analysis = modal_analysis(lay, boundary, duration_s=cfg.simulation.duration_s)
    return tuple(float(m.frequency_Hz) for m in analysis.modes if not m.rigid)


@dataclass(frozen=True)
class CampbellPoint:
    input_rpm: float
    natural_Hz: tuple[float, ...]
    mesh_Hz: tuple[float, ...]  # first-order mesh frequency of each stage


def campbell(scene: Scene, key: str, values: Sequence[Any], fixed: Sequence[str] = ()) -> list[CampbellPoint]:
    """Natural and mesh frequencies at each swept input speed (the other keys at ``fixed`` overrides)."""
    out = []
    for v in values:
        cfg = load_point(scene, (*fixed, f"{key}={float(v)!r}"))
        design = compute_design(cfg)
        mesh = tuple(st.pinion.teeth * st.pinion.speed_rpm / 60.0 for st in design.stages)
        out.append(CampbellPoint(design.stages[0].pinion.speed_rpm, natural_frequencies_Hz(cfg, design), mesh))
    return out
