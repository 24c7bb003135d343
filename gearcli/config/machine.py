"""Design-file tables of the machines at the ends of the train: the induction motor's nameplate or
torque-speed table (``[input] motor``) and a load's torque-speed table (``[load] torque_speed``)."""


from typing import Annotated

from pydantic import ConfigDict, Field, model_validator

from gearcli.config.bounds_types import StrictTable
from gearcli.config.schema_rules import MAX_TORQUE_NMM

MAX_TABLE = 32
MAX_RATED_SLIP = 0.25  # high-slip (NEMA D) motors reach ~13 %; 25 % is past any induction motor's nameplate
NAMEPLATE = ("rated_power_kW", "rated_speed_rpm", "synchronous_speed_rpm", "breakdown_torque_ratio",
             "locked_rotor_torque_ratio")

TablePoint = Annotated[list[Annotated[float, Field(ge=-MAX_TORQUE_NMM / 1e3, le=MAX_TORQUE_NMM / 1e3)]], Field(min_length=2, max_length=2)]
Table = Annotated[list[TablePoint], Field(min_length=2, max_length=MAX_TABLE)]


def table_value(points, speed: float) -> float:
    """A torque-speed table at ``speed`` as the model integrates it (``gearcli.model.elements.machine``): linear
    between its points, constant below its first, its last segment extended above its last. The design reads a
    load table's torque at the nominal output speed with it, so that the design's load is the model's there."""
    xs, ys = [float(p[0]) for p in points], [float(p[1]) for p in points]
    if speed <= xs[0]:
        return ys[0]
    j = next((i for i in range(len(xs) - 1) if speed <= xs[i + 1]), len(xs) - 2)
    return ys[j] + (ys[j + 1] - ys[j]) * (speed - xs[j]) / (xs[j + 1] - xs[j])


def increasing_speeds(points: list[list[float]], what: str, *, non_negative: bool = False) -> None:
    speeds = [p[0] for p in points]
    if any(b <= a for a, b in zip(speeds, speeds[1:], strict=False)):
        raise ValueError(f"{what}: the speeds (first entry of each [rpm, N·m] pair) must increase")
    if non_negative and speeds[0] < 0:
        raise ValueError(f"{what}: speeds must be 0 or more (the law is mirrored for reverse rotation)")


class Motor(StrictTable):
    """An induction motor: the five nameplate values (an extended Kloss curve through the rated, breakdown and
    locked-rotor points) or a torque-speed table ``[[rpm, N·m], ...]``, linear between its points."""

    model_config = ConfigDict(json_schema_extra={"anyOf": [
        {"required": list(NAMEPLATE), "not": {"required": ["torque_speed"]}},
        {"required": ["torque_speed"], "not": {"anyOf": [{"required": [k]} for k in NAMEPLATE]}}]})

    rated_power_kW: Annotated[float, Field(ge=1e-3, le=1e5)] | None = None
    rated_speed_rpm: Annotated[float, Field(ge=1.0, le=200_000.0)] | None = None
    synchronous_speed_rpm: Annotated[float, Field(ge=1.0, le=200_000.0)] | None = None
    breakdown_torque_ratio: Annotated[float, Field(gt=1.0, le=10.0)] | None = None
    locked_rotor_torque_ratio: Annotated[float, Field(gt=0.0, le=10.0)] | None = None
    torque_speed: Table | None = None

    @model_validator(mode="after")
    def _one_description(self) -> "Motor":
        given = [k for k in NAMEPLATE if getattr(self, k) is not None]
        if self.torque_speed is not None:
            if given:
                raise ValueError(f"give the nameplate ({', '.join(NAMEPLATE)}) or torque_speed, not both")
            increasing_speeds(self.torque_speed, "torque_speed")
            if self.torque_speed[0][0] < 0.0:
                raise ValueError("torque_speed: speeds must be 0 or more (from standstill to the synchronous speed)")
            speed, torque = self.torque_speed[-1]
            if self.torque_speed[0][1] <= 0.0:
                raise ValueError(f"torque_speed: an induction motor's torque is positive from standstill and falls to 0 at "
                                 f"its synchronous speed; this table starts at {self.torque_speed[0]!r} (no torque at "
                                 "standstill: the motor could not start): start it with the locked-rotor torque")
            if torque > 0.0:
                raise ValueError(f"torque_speed: an induction motor's torque is positive from standstill and falls to 0 at "
                                 f"its synchronous speed; this table ends at {self.torque_speed[-1]!r} (held past its "
                                 "last point the motor would run away): end it at (or past) the synchronous speed with "
                                 "torque 0")
            return self
        if len(given) != len(NAMEPLATE):
            missing = [k for k in NAMEPLATE if getattr(self, k) is None]
            raise ValueError(f"a motor needs torque_speed or all five nameplate values; missing {', '.join(missing)}")
        assert self.rated_speed_rpm is not None and self.synchronous_speed_rpm is not None
        assert self.breakdown_torque_ratio is not None and self.locked_rotor_torque_ratio is not None
        if not self.rated_speed_rpm < self.synchronous_speed_rpm:
            raise ValueError("rated_speed_rpm must be below synchronous_speed_rpm (an induction motor runs with slip)")
        slip = 1.0 - self.rated_speed_rpm / self.synchronous_speed_rpm
        if slip > MAX_RATED_SLIP:
            raise ValueError(f"rated_speed_rpm {self.rated_speed_rpm:g} with synchronous_speed_rpm "
                             f"{self.synchronous_speed_rpm:g} is a rated slip of {slip:.3g}: an induction motor's "
                             f"rated slip is a few per cent (at most {MAX_RATED_SLIP:g} here); check the nameplate")
        if not self.locked_rotor_torque_ratio < self.breakdown_torque_ratio:
            raise ValueError("locked_rotor_torque_ratio must be below breakdown_torque_ratio (the breakdown torque is "
                             "the curve's maximum)")
        return self

    @property
    def synchronous_rpm(self) -> float:
        """The synchronous speed: the nameplate's, or where the table's torque first falls to 0."""
        if self.torque_speed is None:
            assert self.synchronous_speed_rpm is not None
            return self.synchronous_speed_rpm
        pts = self.torque_speed
        for (n0, t0), (n1, t1) in zip(pts, pts[1:], strict=False):
            if t1 <= 0.0 < t0:
                return n0 + (n1 - n0) * t0 / (t0 - t1)
        return pts[-1][0]
