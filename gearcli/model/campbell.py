"""The Campbell diagram's data types (:func:`gearcli.model.modes.campbell_data` fills them: ``gearcli modes
--plots``, ``report``, a sweep's Campbell diagram). Apart from :mod:`gearcli.model.modes`, which re-exports them by
name, so that a run that draws no diagram does not create their classes.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from gearcli.core.records import record

if TYPE_CHECKING:
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

    @property
    def top_Hz(self) -> float:
        """The highest excitation's frequency at the top speed: the frequency range worth drawing."""
        top = max((r for _, r in self.orders), default=1.0) * self.max_input_rpm / 60.0
        return max([top] + [f for _, f in self.fixed])
