"""A speed-dependent load across a speed sweep: the load's torque key is its torque at the file's speed.

A load T_L (n / n_0)^p (``[load] speed_exponent`` p = 1, 2: a mixer, a fan or a centrifugal pump) is a property of
the driven machine: its torque key is the torque at the file's nominal speed n_0. A point that sets the input speed
would otherwise take that torque at its own speed (every row of a fan's speed sweep at full torque); the point's
load key is therefore set to T_0 (n / n_0)^p (a power key to P_0 (n / n_0)^(p + 1)), the affinity laws of
fans and centrifugal pumps (torque ∝ n², power ∝ n³ at one density: the conversion of a fan's data to another
speed, ISO 13348; of a pump's test results, ISO 9906), T_0 the file's value or the point's own when the sweep
varies it too. The speed ratio is the input's, at the file's gear ratios. A table load (``torque_speed``) is in
absolute speeds and needs nothing; a constant torque key (p = 0) neither, but a constant load given by its power
(``power_kW``, converted to a torque at each point's own speed) is P_0 n / n_0: the same torque at every speed.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, NamedTuple

if TYPE_CHECKING:
    from gearcli.config import DesignFile
    from gearcli.core.jsontypes import JsonScalar

TO_RAD_S = {"input.speed_rpm": 2.0 * math.pi / 60.0, "input.speed_deg_s": math.pi / 180.0, "input.speed_rad_s": 1.0}
LOAD_KEYS = ("torque_Nm", "torque_Nmm", "power_kW")


class LoadLaw(NamedTuple):
    exponent: int  # p
    speed_rad_s: float  # the file's input speed n_0
    key: str  # the load's key that gives its size: torque_Nm, torque_Nmm or power_kW
    value: float  # its value at n_0


def load_law_of(cfg: DesignFile) -> LoadLaw | None:
    """The file's speed-dependent load (or a constant one given by its power), or None (a constant torque, a
    table)."""
    load = cfg.load
    key = next((k for k in LOAD_KEYS if getattr(load, k) is not None), None)
    if load.torque_speed is not None or key is None or (load.speed_exponent == 0 and key != "power_kW"):
        return None
    return LoadLaw(load.speed_exponent, cfg.input.speed_rad_s_value, key, float(getattr(load, key)))


def law_overrides(law: LoadLaw | None, values: Sequence[tuple[str, JsonScalar]]) -> list[str]:
    """The ``--set`` that puts a point's load on the law: ``load.<key>=`` its value at the point's input speed;
    none when the point sets no input speed (or the load does not depend on speed)."""
    if law is None or law.speed_rad_s <= 0.0:
        return []
    given = dict(values)
    speed = next(((k, v) for k, v in given.items() if k in TO_RAD_S), None)
    if speed is None or not isinstance(speed[1], (int, float)) or isinstance(speed[1], bool):
        return []
    own = given.get(f"load.{law.key}", law.value)
    if not isinstance(own, (int, float)) or isinstance(own, bool):
        return []
    ratio = float(speed[1]) * TO_RAD_S[speed[0]] / law.speed_rad_s
    power = law.exponent + (1 if law.key == "power_kW" else 0)
    return [f"load.{law.key}={float(own) * abs(ratio) ** power!r}"]
