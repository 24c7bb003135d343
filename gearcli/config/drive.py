"""The design file's drive tables: the input (speed, torque or induction-motor drive, its starting method) and
the load (torque, power or a torque-speed law), each with the body and coupling outside the reducer."""

import math
from typing import Annotated, Literal

from pydantic import ConfigDict, Field, PrivateAttr, ValidationInfo, field_validator, model_validator

from gearcli.config.bounds_types import IfGiven
from gearcli.config.excitation import MAX_HARMONICS, Fluctuation, Ripple
from gearcli.config.machine import Motor, Table, increasing_speeds
from gearcli.config.schema_rules import (
    INPUT_TORQUE_KEYS,
    LOAD_TORQUE_KEYS,
    MAX_SPEED_RPM,
    MAX_TIME_S,
    MAX_TORQUE_NMM,
    BodyInertia,
    Power,
    Seconds,
    SpeedDegS,
    SpeedRadS,
    SpeedRpm,
    TorqueNm,
    TorqueNmm,
    TorsionDamping,
    TorsionStiffness,
    _all_of,
    _at_most_one,
    _coupling_rules,
    _exactly_one,
    _required,
    _Table,
)


class _Coupled(_Table):
    """A body outside the reducer and the torsional coupling that joins it (both or neither)."""

    inertia_kg_m2: BodyInertia | None = None
    coupling_stiffness_Nm_rad: TorsionStiffness | None = None
    coupling_damping_Nms_rad: TorsionDamping = 0.0

    def _check_coupling(self, table: str) -> None:
        if (self.inertia_kg_m2 is None) != (self.coupling_stiffness_Nm_rad is None):
            missing = "coupling_stiffness_Nm_rad" if self.coupling_stiffness_Nm_rad is None else "inertia_kg_m2"
            raise ValueError(f"{table}.inertia_kg_m2 and {table}.coupling_stiffness_Nm_rad go together: "
                             f"give {missing} too")
        if self.inertia_kg_m2 is None and "coupling_damping_Nms_rad" in self.model_fields_set:
            raise ValueError(f"{table}.coupling_damping_Nms_rad needs {table}.inertia_kg_m2 and "
                             "coupling_stiffness_Nm_rad")


#: Each starting method's own parameters (the VFD's also ramp_s, which a motor drive takes for it alone)
START_PARAMETERS = {"switch_speed_rpm": "star_delta", "voltage_ramp_s": "soft_start",
                    "initial_voltage_fraction": "soft_start", "torque_limit_Nm": "vfd"}


def _starting_rules() -> list[dict]:
    """A starting method and its parameters need drive = "motor"; each parameter belongs to its method; star-delta
    needs its switch-over speed, the soft start its ramp; ramp_s > 0 on a motor only for the VFD."""
    motor = {**_required("drive"), "properties": {"drive": {"const": "motor"}}}
    # another drive ignores them (with a note in the design), so that --set input.drive="speed" works on a motor file
    rules: list[dict] = []
    for key, method in START_PARAMETERS.items():
        rules.append({"not": {**_required("drive", key), "properties": {"drive": {"const": "motor"}},
                              "not": {**_required("starting"), "properties": {"starting": {"const": method}}}}})
    for method, key in (("star_delta", "switch_speed_rpm"), ("soft_start", "voltage_ramp_s")):
        rules.append({"not": {**_required("starting", "drive"),
                              "properties": {"drive": {"const": "motor"}, "starting": {"const": method}},
                              "not": _required(key)}})
    rules.append({"not": {**motor, **_required("drive", "ramp_s"),
                          "properties": {"drive": {"const": "motor"}, "ramp_s": {"exclusiveMinimum": 0}},
                          "not": {**_required("starting"), "properties": {"starting": {"const": "vfd"}}}}})
    return rules


class Input(_Coupled):
    """The input drive. Exactly one speed key: the prescribed speed (``drive = "speed"``) or, with
    ``drive = "torque"``, the nominal speed the train starts at."""

    speed_deg_s: SpeedDegS | None = None
    speed_rpm: SpeedRpm | None = None
    speed_rad_s: SpeedRadS | None = None
    ramp_s: Seconds = 0.0
    drive: Literal["speed", "torque", "motor"] = "speed"
    torque_Nm: TorqueNm | None = None
    torque_Nmm: TorqueNmm | None = None
    power_kW: Power | None = None  # converted to a torque at the nominal input speed
    torque_ripple: Annotated[list[Ripple], Field(max_length=MAX_HARMONICS), IfGiven("input.torque_ripple")] = []
    rotation: Literal["cw", "ccw"] = "cw"  # seen from the input end looking along +x (shaft statics)
    # an induction motor (drive = "motor"; with drive = "speed" it checks that the motor can follow the ramp)
    motor: Annotated[Motor | None, IfGiven("input.motor")] = None
    starting: Literal["direct", "star_delta", "soft_start", "vfd"] = "direct"
    switch_speed_rpm: Annotated[float, Field(ge=1.0, le=MAX_SPEED_RPM)] | None = None  # star_delta
    voltage_ramp_s: Annotated[float, Field(ge=1e-3, le=MAX_TIME_S)] | None = None  # soft_start
    initial_voltage_fraction: Annotated[float, Field(ge=0.05, le=1.0)] = 0.3  # soft_start
    torque_limit_Nm: Annotated[float, Field(gt=0.0, le=MAX_TORQUE_NMM / 1e3)] | None = None  # vfd
    _torque_from_power_Nm: float | None = PrivateAttr(default=None)
    _ignored_keys: tuple[str, ...] = PrivateAttr(default=())  # starting keys another drive than "motor" ignores
    model_config = ConfigDict(json_schema_extra=_all_of(
        *_exactly_one(("speed_deg_s", "speed_rpm", "speed_rad_s")), *_at_most_one(INPUT_TORQUE_KEYS),
        {"not": {**_required("drive"), "properties": {"drive": {"const": "torque"}},
                 "not": {"anyOf": [_required(k) for k in INPUT_TORQUE_KEYS]}}},
        {"not": {"anyOf": [_required(k) for k in INPUT_TORQUE_KEYS], "properties": {"drive": {"const": "speed"}}}},
        {"not": {"anyOf": [_required(k) for k in INPUT_TORQUE_KEYS], "properties": {"drive": {"const": "motor"}},
                 **_required("drive")}},
        {"not": {**_required("drive"), "properties": {"drive": {"const": "motor"}}, "not": _required("motor")}},
        *_starting_rules(),
        *_coupling_rules()))

    @field_validator("torque_ripple")
    @classmethod
    def _ripple_needs_torque_drive(cls, v: list[Ripple], info: ValidationInfo) -> list[Ripple]:
        if v and info.data.get("drive") == "motor":
            raise ValueError('needs drive = "torque": a motor drive\'s torque is its curve with its starting method; '
                             "a ripple on it is not modelled")
        if v and info.data.get("drive") != "torque":
            raise ValueError('needs drive = "torque": a speed drive prescribes the input motion, so a torque '
                             "ripple would act on nothing")
        return v

    @model_validator(mode="after")
    def _one_speed_one_torque(self) -> "Input":
        given = [k for k in ("speed_deg_s", "speed_rpm", "speed_rad_s") if getattr(self, k) is not None]
        if len(given) != 1:
            raise ValueError(
                "give exactly one of speed_deg_s, speed_rpm, speed_rad_s"
                + (f" (got {', '.join(given)})" if given else "")
            )
        torques = [k for k in INPUT_TORQUE_KEYS if getattr(self, k) is not None]
        if len(torques) > 1:
            raise ValueError(f"give at most one of {', '.join(INPUT_TORQUE_KEYS)} (got {', '.join(torques)})")
        if self.drive == "torque" and not torques:
            raise ValueError('drive = "torque" needs torque_Nm, torque_Nmm or power_kW')
        if self.drive != "torque" and torques:
            raise ValueError('torque_Nm/torque_Nmm/power_kW are only used with drive = "torque"')
        self._check_motor()
        if self.drive == "torque" and self.motor is not None:  # a torque drive prescribes the torque: noted, ignored
            self._ignored_keys = ("motor", *self._ignored_keys)
        if self.power_kW is not None:  # the input speed is known here: P = T ω
            self._torque_from_power_Nm = self.power_kW * 1000.0 / self.speed_rad_s_value
        self._check_coupling("input")
        return self

    def _check_motor(self) -> None:
        if self.drive == "motor" and self.motor is None:
            raise ValueError('drive = "motor" needs motor = { rated_power_kW, rated_speed_rpm, synchronous_speed_rpm, '
                             "breakdown_torque_ratio, locked_rotor_torque_ratio } or motor = { torque_speed = [...] }")
        if self.drive != "motor":  # a starting method belongs to drive = "motor": ignored here, with a note
            self._ignored_keys = tuple(k for k in ("starting", "switch_speed_rpm", "voltage_ramp_s",
                                                   "initial_voltage_fraction", "torque_limit_Nm")
                                       if k in self.model_fields_set)
            return
        need = {"star_delta": "switch_speed_rpm", "soft_start": "voltage_ramp_s"}.get(self.starting)
        if need is not None and getattr(self, need) is None:
            raise ValueError(f'starting = "{self.starting}" needs {need}')
        if self.switch_speed_rpm is not None and self.motor is not None \
                and self.switch_speed_rpm >= self.motor.synchronous_rpm:
            raise ValueError(f"switch_speed_rpm {self.switch_speed_rpm:g} is not below the motor's synchronous speed "
                             f"{self.motor.synchronous_rpm:.6g} rpm: the star-delta start would never switch to delta")
        own = {"star_delta": {"switch_speed_rpm"}, "soft_start": {"voltage_ramp_s", "initial_voltage_fraction"},
               "vfd": {"torque_limit_Nm"}}.get(self.starting, set())
        stray = [k for k in ("switch_speed_rpm", "voltage_ramp_s", "initial_voltage_fraction", "torque_limit_Nm")
                 if k in self.model_fields_set and k not in own]
        if stray:
            raise ValueError(f'{", ".join(stray)}: not a parameter of starting = "{self.starting}"')
        if self.ramp_s > 0 and self.starting != "vfd":
            raise ValueError('ramp_s: with drive = "motor" only the VFD ramps its speed (starting = "vfd"); the other '
                             "starts follow the motor's curve")

    @property
    def ignored_keys(self) -> tuple[str, ...]:
        """Keys of another drive, ignored (the design notes them): the starting method's with a drive other than
        "motor", and ``motor`` with a torque drive."""
        return self._ignored_keys

    @property
    def speed_rad_s_value(self) -> float:
        if self.speed_rad_s is not None:
            return self.speed_rad_s
        if self.speed_rpm is not None:
            return self.speed_rpm * 2 * math.pi / 60
        assert self.speed_deg_s is not None  # the validator requires exactly one speed
        return math.radians(self.speed_deg_s)

    @property
    def torque_Nm_value(self) -> float | None:
        if self.torque_Nm is not None:
            return self.torque_Nm
        if self.torque_Nmm is not None:
            return self.torque_Nmm / 1000.0
        return self._torque_from_power_Nm


class Load(_Coupled):
    """Torque on the output shaft (or on the driven machine, when ``inertia_kg_m2`` and a coupling are
    given), resisting its rotation (negative: load reversal)."""

    torque_Nmm: TorqueNmm | None = None
    torque_Nm: TorqueNm | None = None
    ramp_s: Seconds = 0.0
    application_factor: Annotated[float, Field(ge=1.0, le=10.0)] = 1.0
    power_kW: Power | None = None  # converted to a torque at the nominal output speed (see DesignFile)
    fluctuation: Annotated[list[Fluctuation], Field(max_length=MAX_HARMONICS), IfGiven("load.fluctuation")] = []
    # torque against speed: a power law of the load body's speed (the torque given at the nominal output
    # speed), or a table [[rpm, N·m], ...] of the output speed (then no torque key: the table gives it)
    speed_exponent: Literal[0, 1, 2] = 0
    torque_speed: Table | None = None
    _torque_from_power_Nm: float | None = PrivateAttr(default=None)
    model_config = ConfigDict(json_schema_extra=_all_of(
        *_at_most_one(LOAD_TORQUE_KEYS),
        {"anyOf": [_required(k) for k in (*LOAD_TORQUE_KEYS, "torque_speed")]},
        {"not": {**_required("torque_speed"), "anyOf": [_required(k) for k in (*LOAD_TORQUE_KEYS, "speed_exponent")]}},
        *_coupling_rules()))

    @model_validator(mode="after")
    def _one_torque(self) -> "Load":
        given = [k for k in LOAD_TORQUE_KEYS if getattr(self, k) is not None]
        if self.torque_speed is not None:
            if given or "speed_exponent" in self.model_fields_set:
                raise ValueError(f"torque_speed gives the load's torque: no {', '.join((*given, 'speed_exponent')[:1])} "
                                 "beside it")
            increasing_speeds(self.torque_speed, "torque_speed", non_negative=True)
        elif len(given) != 1:
            raise ValueError(f"give exactly one of {', '.join(LOAD_TORQUE_KEYS)} or torque_speed"
                             + (f" (got {', '.join(given)})" if given else ""))
        self._check_coupling("load")
        return self

    @property
    def torque_Nm_value(self) -> float:
        if self.torque_Nm is not None:
            return self.torque_Nm
        if self.torque_Nmm is not None:
            return self.torque_Nmm / 1000.0
        if self._torque_from_power_Nm is None:
            raise ValueError("[load] power_kW is converted to a torque by the DesignFile it belongs to")
        return self._torque_from_power_Nm
