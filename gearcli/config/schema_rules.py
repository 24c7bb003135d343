"""The design file's bounds and rules: the physical bounds of every number, the rules between keys (stated in
the JSON Schema as well as checked by the validators, :mod:`gearcli.config.schema`), and the base of every table."""

from typing import Annotated, Any

from pydantic import Field

from gearcli.config.bounds_types import NotTiny, StrictTable

# Every number has physical bounds (docs/design-file.md lists them): far outside any real reducer, yet
# tight enough that a unit mistake (1e15, a subnormal like 1e-320) is an error naming the key and the
# bound, and every derived quantity (inertia ~ rho b d^4, forces, energies, the run's cost) stays finite.
# Quantities that may be 0 (a ramp, damping, backlash, a torque) may not be *nearly* 0: a nonzero
# magnitude below ``tiny`` is refused too (JSON Schema: a "not" range).


MAX_SPEED_RPM = 200_000.0  # a turbo-compressor pinion turns at ~60,000 rpm; this is generous
MIN_SPEED_RPM = 1e-3  # one turn in ~17 hours
MAX_TORQUE_NMM = 1e11  # 100 MN·m: a 15 MW wind rotor (~20 MN·m) or a girth-gear mill drive (~12 MN·m) with room to spare
RPM_TO_RAD_S = 2 * 3.141592653589793 / 60
MAX_TIME_S = 3600.0  # durations, ramps and windows: one hour of simulated time
MIN_DURATION_S = 1e-4  # simulation.duration_s: the shortest run
SpeedRpm = Annotated[float, Field(ge=MIN_SPEED_RPM, le=MAX_SPEED_RPM)]
SpeedDegS = Annotated[float, Field(ge=MIN_SPEED_RPM * 6, le=MAX_SPEED_RPM * 6)]
SpeedRadS = Annotated[float, Field(ge=MIN_SPEED_RPM * RPM_TO_RAD_S, le=MAX_SPEED_RPM * RPM_TO_RAD_S)]
TorqueNmm = Annotated[float, Field(ge=-MAX_TORQUE_NMM, le=MAX_TORQUE_NMM), NotTiny(1e-3)]
TorqueNm = Annotated[float, Field(ge=-MAX_TORQUE_NMM / 1e3, le=MAX_TORQUE_NMM / 1e3), NotTiny(1e-6)]
Seconds = Annotated[float, Field(ge=0, le=MAX_TIME_S), NotTiny(1e-6)]
# kept for code that imports them; every key now has its own bounds
PositiveFloat = Annotated[float, Field(gt=0, le=1e15)]
NonNegFloat = Annotated[float, Field(ge=0, le=1e15)]
Torque = TorqueNmm
Power = Annotated[float, Field(ge=-1e6, le=1e6), NotTiny(1e-6)]  # kW (1 GW); negative: load reversal

INPUT_TORQUE_KEYS = ("torque_Nm", "torque_Nmm", "power_kW")
LOAD_TORQUE_KEYS = ("torque_Nmm", "torque_Nm", "power_kW")


# Rules between keys, stated in the JSON Schema as well as checked by the validators below, so that the
# schema is never looser than validation (tests/unit/test_docs_and_schema.py). Only a material reference
# (a name that must be a key of [materials]) cannot be said in JSON Schema; docs/design-file.md states it.
def _required(*keys: str) -> dict:
    return {"required": list(keys)}


def _exactly_one(keys: tuple[str, ...]) -> list[dict]:
    pairs = [_required(a, b) for i, a in enumerate(keys) for b in keys[i + 1:]]
    return [{"anyOf": [_required(k) for k in keys]}, {"not": {"anyOf": pairs}}]


def _at_most_one(keys: tuple[str, ...]) -> list[dict]:
    return _exactly_one(keys)[1:]


def _coupling_rules() -> list[dict]:
    both = ("inertia_kg_m2", "coupling_stiffness_Nm_rad")
    return [{"anyOf": [_required(*both), {"not": {"anyOf": [_required(k) for k in both]}}]},
            {"anyOf": [_required(*both), {"not": _required("coupling_damping_Nms_rad")}]}]


def _all_of(*rules: dict) -> Any:
    """A model's ``json_schema_extra``: every rule holds."""
    return {"allOf": list(rules)}


def _hands_rule() -> Any:
    """β > 0 needs opposite hands given on pinion and gear (an external helical pair)."""
    def pair(p: str, g: str) -> dict:
        return {"properties": {"pinion": {"properties": {"hand": {"const": p}}, "required": ["hand"]},
                               "gear": {"properties": {"hand": {"const": g}}, "required": ["hand"]}}}

    return {"anyOf": [{"properties": {"helix_angle_deg": {"maximum": 0}}}, pair("left", "right"),
                      pair("right", "left")]}


class _Table(StrictTable):
    pass


# manufacturing allowances [upper, lower] in mm (ISO 21771 / ISO 1328 terms): tooth thickness A_sne, A_sni in the
# normal section (negative: thinner than nominal, for backlash), tip diameter A_dae, A_dai, centre distance A_ae, A_ai
AllowanceMm = Annotated[float, Field(ge=-50, le=50), NotTiny(1e-6)]
AllowancePair = Annotated[list[AllowanceMm], Field(min_length=2, max_length=2)]


class KeyedValueError(ValueError):
    """A table's cross-key rule that one of its keys breaks: ``key`` (dotted, relative to the table) is appended to
    the table's path in the message (``stage[0].ring.teeth: ...``, not ``stage[0]: ...``)."""

    def __init__(self, key: str, text: str) -> None:
        super().__init__(text)
        self.key = key


def _upper_not_below_lower(name: str, pair: list[float] | None) -> None:
    if pair is not None and pair[0] < pair[1]:
        raise ValueError(f"{name} = [upper, lower]: the upper allowance ({pair[0]:g}) is below the lower "
                         f"({pair[1]:g}); give [upper, lower]")


TorsionStiffness = Annotated[float, Field(ge=1.0, le=1e11)]  # N·m/rad: a soft elastomer coupling ~10, a 1 m shaft ~1e9
TorsionDamping = Annotated[float, Field(ge=0, le=1e8), NotTiny(1e-9)]  # N·m·s/rad
BodyInertia = Annotated[float, Field(ge=1e-9, le=1e7)]  # kg·m²: a micro-motor rotor ~1e-7, a mill drum ~1e5
