"""The output contract's time-series columns (docs/output.md): names and units, made here from the simulation's
SI series (:class:`gearcli.core.channels.Channel`).

:func:`column` names one channel in the contract's base units (speeds in °/s, the input torque in N·mm, the
motor's and the couplings' torques in N·m, penetrations in mm, transmission errors in µm, twists in degrees);
:func:`named` gives every series of a result under those names, in the simulation's order;
:func:`gearcli.io.units.channels` then renames speeds and torques to the design file's units. A new output
channel: its :class:`Channel` in the simulation (or in :mod:`gearcli.simulate.bearings`), its name and factor here.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import TYPE_CHECKING

from gearcli.core.channels import Channel

if TYPE_CHECKING:  # `gearcli design` imports the writers: no numpy at start-up
    import numpy as np

    from gearcli.simulate.results import SimulationResult

RAD_TO_DEG = 180.0 / math.pi
RAD_S_TO_RPM = 60.0 / (2.0 * math.pi)

#: quantity -> (column suffix, factor from SI) for every owner without its own entry in ``_SPECIAL``
_SUFFIX: dict[str, tuple[str, float]] = {
    "speed": ("speed_deg_s", RAD_TO_DEG),
    "torque": ("torque_Nm", 1.0),
    "tangential_force": ("tangential_N", 1.0),
    "radial_force": ("radial_N", 1.0),
    "axial_force": ("axial_N", 1.0),
    "penetration": ("penetration_mm", 1e3),
    "dte": ("dte_um", 1e6),
    "twist": ("twist_deg", RAD_TO_DEG),
}
#: the channels whose column does not follow ``{owner}_{suffix}``
_SPECIAL: dict[Channel, tuple[str, float]] = {
    Channel("torque", "input"): ("input_torque_Nmm", 1e3),
    Channel("torque", "drive"): ("motor_torque_Nm", 1.0),
    Channel("speed", "drive"): ("motor_speed_rpm", RAD_S_TO_RPM),
}


def column(channel: Channel) -> tuple[str, float]:
    """The contract's column name of ``channel`` and the factor from its SI samples to the column's unit."""
    special = _SPECIAL.get(channel)
    if special is not None:
        return special
    suffix, factor = _SUFFIX[channel.quantity]
    return f"{channel.owner}_{suffix}", factor


def named_series(series: Mapping[Channel, np.ndarray]) -> dict[str, np.ndarray]:
    """``{column name: samples}`` in the contract's base units, in the order of ``series``."""
    out: dict[str, np.ndarray] = {}
    for channel, samples in series.items():
        name, factor = column(channel)
        out[name] = samples if factor == 1.0 else samples * factor
    return out


def named(result: SimulationResult) -> dict[str, np.ndarray]:
    """A result's time series under the contract's names, in its base units (empty without series)."""
    return named_series(result.series)
