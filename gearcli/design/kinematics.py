"""Speeds down the train and torques back up it (docs/physics.md, "Design calculations").

Shaft 1 carries pinion 1 (the input); shaft k+1 carries gear k and pinion k+1 (rigid); the last
shaft carries the last gear and the load. Every speed is positive in its shaft's own running
direction. Torques are in N·mm and signed: a negative load torque (load reversal) makes every
torque in the train negative.
"""

from __future__ import annotations

import math

from gearcli.core.records import record

RAD_S_TO_RPM = 60.0 / (2.0 * math.pi)


def stage_ratio(pinion_teeth: int, gear_teeth: int) -> float:
    """i = z_gear / z_pinion (> 1 for a reducer)."""
    return gear_teeth / pinion_teeth


def shaft_speeds_rad_s(input_speed_rad_s: float, ratios: tuple[float, ...]) -> tuple[float, ...]:
    """ω_1 = input, ω_{k+1} = ω_k / i_k: one speed per shaft (n stages, n + 1 shafts)."""
    speeds = [input_speed_rad_s]
    for ratio in ratios:
        speeds.append(speeds[-1] / ratio)
    return tuple(speeds)


def pinion_torque_Nmm(gear_torque_Nmm: float, ratio: float, efficiency: float,
                      reverse_efficiency: float | None = None) -> float:
    """Torque the pinion must deliver for a gear torque T_g: T_p = T_g / (i η).

    The mesh loses power in the direction the power flows. Under load reversal (T_g < 0) power flows
    from the gear back to the pinion, so the loss is taken from the gear side: T_p = T_g η / i. Either
    way |P_pinion| and |P_gear| differ by the factor η and no power is created. ``reverse_efficiency``: the
    stage's efficiency when the power flows back, where it differs from η (a planetary stage's).
    """
    if gear_torque_Nmm >= 0.0:
        return gear_torque_Nmm / (ratio * efficiency)
    return gear_torque_Nmm * (efficiency if reverse_efficiency is None else reverse_efficiency) / ratio


def stage_torques_Nmm(load_torque_Nmm: float, ratios: tuple[float, ...], efficiencies: tuple[float, ...],
                      reverse: tuple[float | None, ...] | None = None) -> tuple[tuple[float, float], ...]:
    """(T_pinion_k, T_gear_k) per stage, from the output load back to the input.

    The last gear carries the load; gear k carries what pinion k+1 on the same shaft needs. ``reverse``: per
    stage its efficiency under a reversed load where it differs from η (None: η).
    """
    torques: list[tuple[float, float]] = []
    gear_torque = load_torque_Nmm
    back = reverse if reverse is not None else (None,) * len(ratios)
    for ratio, eta, eta_back in zip(reversed(ratios), reversed(efficiencies), reversed(back), strict=True):
        pinion = pinion_torque_Nmm(gear_torque, ratio, eta, eta_back)
        torques.append((pinion, gear_torque))
        gear_torque = pinion
    return tuple(reversed(torques))


def mesh_frequency_Hz(pinion_teeth: int, pinion_speed_rad_s: float) -> float:
    """f_z = z_pinion n_pinion, n in revolutions per second."""
    return pinion_teeth * pinion_speed_rad_s / (2.0 * math.pi)


def speed_deg_s(speed_rad_s: float) -> float:
    return math.degrees(speed_rad_s)


def speed_rpm(speed_rad_s: float) -> float:
    return speed_rad_s * RAD_S_TO_RPM


def power_kW(torque_Nmm: float, speed_rad_s: float) -> float:
    """P = T ω, kW from N·mm and rad/s (1 N·mm · 1 rad/s = 1e-3 W = 1e-6 kW)."""
    return torque_Nmm * speed_rad_s * 1e-6


@record
class Train:
    """Ratios, shaft speeds (rad/s) and stage torques (N·mm) of the whole train."""

    ratios: tuple[float, ...]
    shaft_speeds_rad_s: tuple[float, ...]
    stage_torques_Nmm: tuple[tuple[float, float], ...]  # (pinion, gear) per stage
    load_torque_Nmm: float

    @property
    def total_ratio(self) -> float:
        return math.prod(self.ratios)

    def shaft_torque_Nmm(self, shaft: int) -> float:
        """Torque shaft ``shaft`` (0-based) transmits: its pinion's torque, or the load on the last."""
        if shaft < len(self.stage_torques_Nmm):
            return self.stage_torques_Nmm[shaft][0]
        return self.load_torque_Nmm


def train(teeth: tuple[tuple[int, int], ...], efficiencies: tuple[float, ...],
          input_speed_rad_s: float, load_torque_Nmm: float) -> Train:
    """The kinematics of a train of stages given as (z_pinion, z_gear) pairs in power-flow order."""
    return train_from_ratios(tuple(stage_ratio(zp, zg) for zp, zg in teeth), efficiencies, input_speed_rad_s,
                             load_torque_Nmm)


def train_from_ratios(ratios: tuple[float, ...], efficiencies: tuple[float, ...], input_speed_rad_s: float,
                      load_torque_Nmm: float, reverse: tuple[float | None, ...] | None = None) -> Train:
    """The kinematics of a train of stages given by their speed ratios |ω_in / ω_out| (any stage type);
    ``reverse``: per stage its efficiency under a reversed load where it differs (a planetary stage's)."""
    return Train(ratios, shaft_speeds_rad_s(input_speed_rad_s, ratios),
                 stage_torques_Nmm(load_torque_Nmm, ratios, efficiencies, reverse), load_torque_Nmm)
