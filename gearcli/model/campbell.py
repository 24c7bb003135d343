"""The Campbell diagram's data types and :func:`campbell_of` (:func:`gearcli.model.modes.campbell_data`: ``gearcli modes
--plots``, ``report``, a sweep's Campbell diagram). Apart from :mod:`gearcli.model.modes`, which re-exports them by
name, so that a run that draws no diagram does not create their classes.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from gearcli.core.records import record
from gearcli.model.modes import (
    SPEED_RANGE,
    excitation_sources,
    meets,
    modal_analysis,
    order_crossing,
    torque_crossing,
    torque_sources,
)
from gearcli.model.planet_excitation import dominant_label, repeated_ranks

if TYPE_CHECKING:
    from gearcli.model.assembly import Layout
    from gearcli.model.modes import Crossing, Mode


@record
class CampbellCrossing:
    mode: int
    frequency_Hz: float
    crossing: Crossing


@record
class CampbellData:
    """What a Campbell diagram shows: the modes (linearised at full load, so flat in speed), every order line
    (mesh 1x-3x, shaft 1x, input torque ripple orders) as frequency per input revolution, every fixed frequency
    (load fluctuation: a horizontal line), and each crossing with how strongly it is excited, for input speeds
    0 .. ``max_input_rpm`` (a fixed frequency's: within ``RESONANCE_BAND`` of the mode, ``input_speed_rpm`` None)."""

    boundary: str
    nominal_input_rpm: float
    max_input_rpm: float
    modes: tuple[Mode, ...]  # the non-rigid ones
    orders: tuple[tuple[str, float], ...]  # (name, Hz per input Hz): lines through the origin
    crossings: tuple[CampbellCrossing, ...]
    fixed: tuple[tuple[str, float], ...] = ()  # (name, Hz): speed-independent excitations (load fluctuation)
    # repeated modes (a planetary's identical planets): (their numbers, the element holding the largest share of
    # their eigenspace's strain energy), drawn as one line with one label
    repeated: tuple[tuple[tuple[int, ...], str], ...] = ()

    @property
    def top_Hz(self) -> float:
        """The highest excitation's frequency at the top speed: the frequency range worth drawing."""
        top = max((r for _, r in self.orders), default=1.0) * self.max_input_rpm / 60.0
        return max([top] + [f for _, f in self.fixed])


def campbell_of(lay: Layout, boundary: str = "clamped_input", *, duration_s: float = 1.0,
                max_input_rpm: float | None = None) -> CampbellData:
    """The Campbell diagram of the chain up to ``max_input_rpm`` (default ``SPEED_RANGE`` x nominal): every
    crossing as the modal analysis's modes hold it (:func:`gearcli.model.modes.order_crossing`)."""
    ana = modal_analysis(lay, boundary, duration_s=duration_s)
    top = max_input_rpm if max_input_rpm is not None else SPEED_RANGE * ana.nominal_input_rpm
    sources = excitation_sources(lay)
    torques = torque_sources(lay)
    crossings = []
    for m in ana.modes:
        if m.rigid:
            continue
        for o in sources:
            c = order_crossing(lay, boundary, duration_s, m, o)
            if c.input_speed_rpm is not None and c.input_speed_rpm <= top:
                crossings.append(CampbellCrossing(m.number, m.frequency_Hz, c))
        crossings += [CampbellCrossing(m.number, m.frequency_Hz,
                                       torque_crossing(lay, t, m.frequency_Hz, m.shape, m.damping_ratio))
                      for t in torques if meets(t, m.frequency_Hz, top)]
    elastic = tuple(m for m in ana.modes if not m.rigid)
    hz = [(r, m.frequency_Hz) for r, m in enumerate(elastic)]
    groups = sorted({repeated_ranks(hz, 0, r) for r in range(len(elastic))})  # the modes' repeated groups
    orders = [(o.name, o.hz_per_input_hz) for o in sources] + [(t.name, t.hz_per_input_hz) for t in torques if t.fixed_Hz is None]
    return CampbellData(boundary, ana.nominal_input_rpm, top, elastic, tuple(orders), tuple(crossings),
                        tuple((t.name, t.fixed_Hz) for t in torques if t.fixed_Hz is not None),
                        tuple((tuple(elastic[r].number for r in g), _group_dominant(lay, [elastic[r] for r in g]))
                              for g in groups if len(g) > 1))


def _group_dominant(lay: Layout, group: list[Mode]) -> str:
    """The element holding the largest share of a repeated mode's strain energy over its eigenspace: the modes'
    shapes are mass-orthogonal and each share is its connector's strain over the mode's ω², so the eigenspace's
    shares are the modes' mean (the same for any basis; identical planets hold equal shares and are named
    together, as :func:`gearcli.model.planet_excitation.group_dominant` names them in a resonance warning)."""
    return dominant_label(lay, np.mean([m.energy_share for m in group], axis=0))
