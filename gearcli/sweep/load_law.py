"""A speed-dependent load across a speed sweep: the load's torque key is its torque at the file's speed.

A load T_L (n / n_0)^p (``[load] speed_exponent`` p = 1, 2: a mixer, a fan or a centrifugal pump) is a property of
the driven machine: its torque key is the torque at the file's nominal speed n_0. A point that sets the input speed
would otherwise take that torque at its own speed (every row of a fan's speed sweep at full torque); the point's
load key is therefore set to T_0 (n / n_0)^p (a power key to P_0 (n / n_0)^(p + 1)), the affinity laws of
fans and centrifugal pumps (torque ∝ n², power ∝ n³ at one density: the conversion of a fan's data to another
speed, ISO 13348; of a pump's test results, ISO 9906), T_0 the file's value or the point's own when the sweep
varies it too, in whichever of the three keys the point gives it (``load.torque_Nmm`` varied in a file that says
``torque_Nm``: the point's own key and value, as its ``--set`` would replace the file's), and p the point's own
``load.speed_exponent`` when the sweep varies that. The speed ratio is the input's, at the file's gear ratios. A
table load (``torque_speed``) is in absolute speeds and needs nothing; a constant torque key (p = 0) neither, but a
constant load given by its power (``power_kW``, converted to a torque at each point's own speed) is P_0 n / n_0: the
same torque at every speed.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, NamedTuple, cast

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
    """The file's load given by a torque or power key (its exponent p, 0 for a constant torque: a point may vary
    ``load.speed_exponent``), or None (a table)."""
    load = cfg.load
    key = next((k for k in LOAD_KEYS if getattr(load, k) is not None), None)
    if load.torque_speed is not None or key is None:
        return None
    return LoadLaw(load.speed_exponent, cfg.input.speed_rad_s_value, key, float(getattr(load, key)))


def _number(v: object) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def law_overrides(law: LoadLaw | None, values: Sequence[tuple[str, JsonScalar]]) -> list[str]:
    """The ``--set`` that puts a point's load on the law: ``load.<key>=`` its value at the point's input speed, in
    the point's own load key (a varied ``load.torque_Nmm`` in a file that says ``torque_Nm``) at the point's own
    exponent (a varied ``load.speed_exponent``); none when the point sets no input speed (or its load does not
    depend on speed)."""
    if law is None or law.speed_rad_s <= 0.0:
        return []
    given = dict(values)
    speed = next(((k, v) for k, v in given.items() if k in TO_RAD_S), None)
    if speed is None or not _number(speed[1]):
        return []
    key = next((k for k in LOAD_KEYS if f"load.{k}" in given), law.key)  # a varied load key replaces the file's
    own = given.get(f"load.{key}", law.value)
    exponent = given.get("load.speed_exponent", law.exponent)
    if not _number(own) or not _number(exponent):  # (a value the schema rejects: the point's run names it)
        return []
    power = float(cast(float, exponent)) + (1 if key == "power_kW" else 0)
    if power == 0.0:  # a constant torque: the same at every speed
        return []
    ratio = float(cast(float, speed[1])) * TO_RAD_S[speed[0]] / law.speed_rad_s
    return [f"load.{key}={float(cast(float, own)) * abs(ratio) ** power!r}"]
