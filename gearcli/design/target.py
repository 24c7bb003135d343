"""The design's target-speed check: the output speed against ``[target]``, with the ratio that meets it."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from gearcli.core.text import beside

if TYPE_CHECKING:
    from gearcli.config.schema import DesignFile


def target_speed_warning(cfg: DesignFile, output_speed_rpm: float) -> str | None:
    if cfg.target is None:
        return None
    target = cfg.target.output_speed_rpm_value
    deviation = 100.0 * (output_speed_rpm - target) / target
    if abs(deviation) <= cfg.target.tolerance_percent:
        return None
    # in the unit the target is given in (DESIGN §12): a target in °/s is not echoed back in rpm
    scale, unit = (6.0, "°/s") if cfg.target.output_speed_rpm is None else (1.0, "rpm")
    tol = min(cfg.target.tolerance_percent / 100.0, 0.999)  # a ratio's bounds (a 100 % tolerance has no upper one)
    return (f"output speed {scale * output_speed_rpm:.4g} {unit} misses the target {scale * target:.4g} {unit} by "
            f"{beside(deviation, math.copysign(cfg.target.tolerance_percent, deviation), '+.1f')} % (tolerance ±{cfg.target.tolerance_percent:g} %)"
            f" ([target] {'output_speed_rpm' if unit == 'rpm' else 'output_speed_deg_s'} and tolerance_percent): the "
            f"train's ratio would need to be {output_speed_rpm / target:.5g}x its present one (within the tolerance: "
            f"{output_speed_rpm / (target * (1 + tol)):.5g}x to {output_speed_rpm / (target * (1 - tol)):.5g}x)")
