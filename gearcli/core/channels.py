"""What a simulation's time series are, keyed by what they measure: :class:`Channel` (a quantity of an owner),
always in SI.

The simulation returns ``{Channel: samples}`` (:attr:`gearcli.simulate.results.SimulationResult.series`); the output
contract's column names and units (``stage1_dte_um``, ``input_torque_Nmm``, speeds in the design file's unit)
are made from them in one place, :mod:`gearcli.io.channels`.
"""

from __future__ import annotations

from typing import Literal, NamedTuple

Quantity = Literal["speed", "torque", "tangential_force", "radial_force", "axial_force", "penetration", "dte",
                   "twist"]

#: the SI unit of each quantity's samples
SI_UNITS: dict[Quantity, str] = {
    "speed": "rad/s", "torque": "N m", "tangential_force": "N", "radial_force": "N", "axial_force": "N",
    "penetration": "m", "dte": "m", "twist": "rad",
}


class Channel(NamedTuple):
    """A quantity of an owner. Owners: ``shaft{i}`` (a reducer shaft's speed, a flexible shaft's twist),
    ``stage{k}`` (a parallel mesh), ``stage{k}_planet{j}_{sun|ring}`` (a planet mesh), ``input`` (the drive's
    torque), ``drive`` (the electric motor's speed and torque), ``motor`` and ``drum`` (those bodies' speeds),
    ``input_coupling`` and ``load_coupling`` (their torques), ``bearing{j}`` (its reactions). 1-based."""

    quantity: Quantity
    owner: str

    def __str__(self) -> str:
        return f"{self.owner} {self.quantity.replace('_', ' ')} ({SI_UNITS[self.quantity]})"


__all__ = ["SI_UNITS", "Channel", "Quantity"]
