"""Output units that follow the design file: speeds in the unit of the input's speed key, torques in the unit of
the load's torque key (docs/output.md, "Units").

The simulation's SI series get the contract's base names (``shaft{i}_speed_deg_s``, ``input_torque_Nmm``,
``*_coupling_torque_Nm``) in :mod:`gearcli.io.channels`; the writers rename and convert them to the design
file's units here, so a script reads the unit from the column name. A file with ``speed_deg_s`` and ``torque_Nmm`` (the seed) gets its channels unchanged, the same
arrays under the same names.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING, TypeVar

from gearcli.core.records import record
from gearcli.io.channels import named

if TYPE_CHECKING:  # `gearcli design` imports this module: no numpy at start-up
    import numpy as np

    from gearcli.config import DesignFile
    from gearcli.results import DesignResult
    from gearcli.simulate.results import SimulationResult

SPEED_UNITS = {"deg_s": ("°/s", 1.0), "rpm": ("rpm", 1.0 / 6.0), "rad_s": ("rad/s", math.pi / 180.0)}  # from °/s
#: a value or the samples of a channel (the conversions keep the type: float in, float out; array in, array out)
Number = TypeVar("Number", float, "np.ndarray")

TORQUE_UNITS = {"Nmm": ("N·mm", 1000.0), "Nm": ("N·m", 1.0)}  # from N·m


@record
class OutputUnits:
    """The units a file's outputs are written in: those of its speed and torque keys."""

    speed: str = "deg_s"  # "deg_s" | "rpm" | "rad_s": the suffix of the input's speed key
    torque: str = "Nmm"  # "Nmm" | "Nm": the suffix of the load's torque key (power_kW: N·m)

    @property
    def speed_label(self) -> str:
        return SPEED_UNITS[self.speed][0]

    @property
    def torque_label(self) -> str:
        return TORQUE_UNITS[self.torque][0]

    def speed_from_deg_s(self, v: Number) -> Number:
        factor = SPEED_UNITS[self.speed][1]
        return v if factor == 1.0 else v * factor

    def torque_from_Nm(self, v: Number) -> Number:
        factor = TORQUE_UNITS[self.torque][1]
        return v if factor == 1.0 else v * factor

    def torque_from_Nmm(self, v: Number) -> Number:
        return v if self.torque == "Nmm" else self.torque_from_Nm(v / 1000.0)

    def speed_text(self, deg_s: float) -> str:
        """A speed as the footers print it: in the file's unit, then rpm beside °/s or rad/s ("8700 °/s = 1450
        rpm"; 6 significant digits, rpm 5)."""
        own = f"{self.speed_from_deg_s(deg_s):.6g} {self.speed_label}"
        return own if self.speed == "rpm" else f"{own} = {deg_s / 6.0:.5g} rpm"

    def table_speeds(self) -> list[tuple[str, Callable[[float], float]]]:
        """(label, from °/s) of every speed a table prints (docs/output.md, "Units"): the file's unit, and for a
        °/s or rad/s file rpm beside it."""
        rpm = ("rpm", _rpm_from_deg_s)
        return [rpm] if self.speed == "rpm" else [(self.speed_label, self.speed_from_deg_s), rpm]

    def table_torques(self) -> list[tuple[str, Callable[[float], float]]]:
        """(label, from N·mm) of every torque a table prints: the file's unit, and for an N·mm file N·m beside it."""
        n_m = ("N·m", _nm_from_nmm)
        return [(self.torque_label, self.torque_from_Nmm), n_m] if self.torque == "Nmm" else [n_m]


def _rpm_from_deg_s(v: float) -> float:
    return v / 6.0


def _nm_from_nmm(v: float) -> float:
    return v / 1000.0


DEFAULT = OutputUnits()


def key_units(cfg: DesignFile) -> tuple[str, str]:
    """(speed, torque) key suffixes the outputs use: the input's speed key (``deg_s``, ``rpm``, ``rad_s``) and
    the load's torque key (``Nmm``, ``Nm``; ``power_kW`` gives N·m)."""
    inp = cfg.input
    speed = "rpm" if inp.speed_rpm is not None else "rad_s" if inp.speed_rad_s is not None else "deg_s"
    torque = "Nmm" if getattr(cfg.load, "torque_Nmm", None) is not None else "Nm"
    return speed, torque


def of_design_file(cfg: DesignFile) -> OutputUnits:
    """The units a validated design file writes in."""
    return OutputUnits(*key_units(cfg))


def of_result(result: SimulationResult | DesignResult) -> OutputUnits:
    """The units a simulation or design result is written in (its ``units``: speed and torque key suffixes)."""
    units = getattr(result, "units", None)
    return OutputUnits(*units) if units else DEFAULT


def channels(ch: Mapping[str, np.ndarray], units: OutputUnits | None) -> dict[str, np.ndarray]:
    """The simulation's channels renamed and converted to ``units`` (same order)."""
    u = units or DEFAULT
    out = {}
    for name, v in ch.items():
        if name.endswith("_speed_deg_s") and u.speed != "deg_s":
            out[name[: -len("deg_s")] + u.speed] = u.speed_from_deg_s(v)
        elif name.endswith("_torque_Nmm") and u.torque != "Nmm":
            out[name[: -len("Nmm")] + u.torque] = u.torque_from_Nmm(v)
        elif name.endswith("_torque_Nm") and u.torque != "Nm":
            out[name[: -len("Nm")] + u.torque] = u.torque_from_Nm(v)
        else:
            out[name] = v
    return out


def input_torque_window_means(result: SimulationResult) -> tuple[float, float] | None:
    """(mean input torque N·m, mean input power kW) over the statistics window, from the series: the power as
    the mean of torque x speed of the driven body (the motor when there is one), not a product of means; each the
    integral over the window by the trapezoid rule (the plain mean over a periodic window's whole periods).
    None without series."""
    import numpy as np  # lazy: numpy, kept out of io.units' import (a design file's units need none)

    ch = named(result)
    torque = ch.get("input_torque_Nmm")
    speed = ch.get("motor_speed_deg_s", ch.get("shaft1_speed_deg_s"))
    if torque is None or speed is None or not len(torque):
        return None
    t = np.asarray(result.time_s)
    eps = 1e-9 * max(1.0, abs(result.window_s[1]))
    mask = (t >= result.window_s[0] - eps) & (t <= result.window_s[1] + eps)
    if not mask.any():
        return None
    t_nm = np.asarray(torque)[mask] / 1000.0
    power_kw = t_nm * np.radians(np.asarray(speed)[mask]) / 1000.0
    tw = t[mask]
    steady = getattr(result, "steady", None)
    if (steady is not None and steady.mode == "periodic") or tw.size < 2 or tw[-1] <= tw[0]:
        return float(t_nm.mean()), float(power_kw.mean())  # whole periods without their closing sample
    span = tw[-1] - tw[0]  # the integral over the window (trapezoid rule), as the stages' means
    return float(np.trapezoid(t_nm, tw) / span), float(np.trapezoid(power_kw, tw) / span)
