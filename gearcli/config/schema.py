"""The design file, one pydantic model per TOML table (docs/design-file.md, generated from these models).

Units are in the key names (``_mm``, ``_deg``, ``_MPa`` ...) and stay as the user wrote them here;
conversion to SI happens in the design layer. Every model forbids unknown keys and rejects NaN and
infinity; numbers are strict (a string ``"21"`` is not a tooth count), except that an integer is
accepted where a float is expected, as TOML users write ``module = 12``.
"""


import math
from typing import Annotated, Any, Literal

from pydantic import (
    ConfigDict,
    Discriminator,
    Field,
    PrivateAttr,
    Tag,
    ValidationInfo,
    field_validator,
    model_validator,
)

from gearcli.config.bounds_types import NotTiny, StrictTable
from gearcli.config.contact import (  # noqa: F401 (re-exported: the design file's tables, one namespace)
    DEFAULT_DAMPING_RATIO,
    IMPACT_KEYS,
    Contact,
    ContactOverride,
    DampingDepthMm,
    DampingNsmm,
    Stiffness,
)
from gearcli.config.duty import AxialPositionMm, Bearing, CenterAngleDeg, Duty
from gearcli.config.excitation import (
    MAX_HARMONICS,
    Fluctuation,
    Ripple,
    check_harmonics,
)
from gearcli.config.machine import Motor, Table, increasing_speeds
from gearcli.core.methods import NAMES as METHODS  # the one registry of integration methods

# Every number has physical bounds (docs/design-file.md lists them): far outside any real reducer, yet
# tight enough that a unit mistake (1e15, a subnormal like 1e-320) is an error naming the key and the
# bound, and every derived quantity (inertia ~ rho b d^4, forces, energies, the run's cost) stays finite.
# Quantities that may be 0 (a ramp, damping, backlash, a torque) may not be *nearly* 0: a nonzero
# magnitude below ``tiny`` is refused too (JSON Schema: a "not" range).


MAX_SPEED_RPM = 200_000.0  # a turbo-compressor pinion turns at ~60,000 rpm; this is generous
MIN_SPEED_RPM = 1e-3  # one turn in ~17 hours
MAX_TORQUE_NMM = 1e10  # 10 MN·m: beyond the largest mill and ship drives
RPM_TO_RAD_S = 2 * 3.141592653589793 / 60
MAX_TIME_S = 3600.0  # durations, ramps and windows: one hour of simulated time
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


class Material(_Table):
    density_kg_m3: Annotated[float, Field(ge=100, le=1e5)]  # foams ~100, osmium 22,590
    youngs_modulus_MPa: Annotated[float, Field(ge=1e3, le=1e7)]  # polymers ~1e3, diamond 1.2e6
    poisson_ratio: Annotated[float, Field(ge=0.01, lt=0.5)]
    # strength rating (ISO 6336-5), required for the materials a stage uses once [rating] is present
    treatment: Literal["case_carburized", "nitrided", "nitrocarburized", "induction_hardened", "flame_hardened",
                       "through_hardened", "structural_steel", "cast_steel", "nodular_iron", "grey_iron"] | None = None
    contact_fatigue_limit_MPa: Annotated[float, Field(ge=100, le=3000)] | None = None  # sigma_Hlim
    bending_fatigue_limit_MPa: Annotated[float, Field(ge=20, le=1500)] | None = None  # sigma_Flim
    surface_hardness_HV: Annotated[float, Field(ge=50, le=1500)] | None = None  # Z_W of a softer wheel


# manufacturing allowances [upper, lower] in mm (ISO 21771 / ISO 1328 terms): tooth thickness A_sne, A_sni in the
# normal section (negative: thinner than nominal, for backlash), tip diameter A_dae, A_dai, centre distance A_ae, A_ai
AllowanceMm = Annotated[float, Field(ge=-50, le=50), NotTiny(1e-6)]
AllowancePair = Annotated[list[AllowanceMm], Field(min_length=2, max_length=2)]


def _upper_not_below_lower(name: str, pair: list[float] | None) -> None:
    if pair is not None and pair[0] < pair[1]:
        raise ValueError(f"{name} = [upper, lower]: the upper allowance ({pair[0]:g}) is below the lower "
                         f"({pair[1]:g}); give [upper, lower]")


class Gear(_Table):
    """One gear of a stage: pinion (driving) or gear (driven)."""

    teeth: Annotated[int, Field(ge=5, le=10000)]
    face_width_mm: Annotated[float, Field(ge=0.1, le=1e4)]
    hand: Literal["left", "right", "spur"] | None = None
    material: str = "steel"
    profile_shift: Annotated[float, Field(ge=-1.5, le=1.5), NotTiny(1e-6)] = 0.0
    inertia_kg_m2: Annotated[float, Field(ge=1e-09, le=1000000.0)] | None = None  # a 5 mm pinion ~1e-9; a mill girth gear ~1e5
    # gear body (ISO 6336-1): absent = solid disc; web and rim make a webbed blank (gear blank factor C_R)
    bore_diameter_mm: Annotated[float, Field(ge=0.1, le=1e4)] | None = None
    rim_thickness_mm: Annotated[float, Field(ge=0.1, le=1e4)] | None = None
    web_thickness_mm: Annotated[float, Field(ge=0.1, le=1e4)] | None = None
    axial_position_mm: AxialPositionMm | None = None  # gear centre along x (shaft statics, docs/life.md)
    # strength rating (ISO 6336-2/-3): mean peak-to-valley roughness of the flank and of the root fillet
    flank_roughness_Rz_um: Annotated[float, Field(ge=0.01, le=200)] | None = None
    root_roughness_Rz_um: Annotated[float, Field(ge=0.01, le=200)] | None = None

    @model_validator(mode="after")
    def _web_needs_rim(self) -> "Gear":
        if (self.web_thickness_mm is None) != (self.rim_thickness_mm is None):
            raise ValueError("a webbed gear body needs both web_thickness_mm and rim_thickness_mm "
                             "(give both, or neither for a solid disc)")
        return self

    @property
    def body_given(self) -> bool:
        """True when any of bore_diameter_mm, rim_thickness_mm, web_thickness_mm is given."""
        return any(v is not None for v in (self.bore_diameter_mm, self.rim_thickness_mm, self.web_thickness_mm))


class PairGear(Gear):
    """One gear of a parallel stage: pinion (driving) or gear (driven)."""

    # tooth thickness allowances [A_sne, A_sni] (normal section, mm) and tip diameter allowances [A_dae, A_dai]:
    # generating profile shifts, manufactured root diameters, backlash and contact ratio with allowances
    # (docs/iso6336.md, "Tooth-thickness allowances"); parallel stages
    tooth_thickness_allowance_mm: AllowancePair | None = None
    tip_diameter_allowance_mm: AllowancePair | None = None

    @model_validator(mode="after")
    def _allowance_order(self) -> "PairGear":
        _upper_not_below_lower("tooth_thickness_allowance_mm", self.tooth_thickness_allowance_mm)
        _upper_not_below_lower("tip_diameter_allowance_mm", self.tip_diameter_allowance_mm)
        return self


class BasicRack(_Table):
    """The basic rack profile (ISO 53) in multiples of the normal module; default profile A."""

    addendum: Annotated[float, Field(ge=0.5, le=2.0)] = 1.0  # h_aP*
    dedendum: Annotated[float, Field(ge=0.5, le=2.5)] = 1.25  # h_fP*
    root_radius: Annotated[float, Field(ge=0.0, le=1.0), NotTiny(1e-6)] = 0.38  # rho_fP*

    @model_validator(mode="after")
    def _clearance(self) -> "BasicRack":
        if self.dedendum < self.addendum:
            raise ValueError(f"dedendum ({self.dedendum:g}) must be at least the addendum ({self.addendum:g}): "
                             "the bottom clearance h_fP* - h_aP* cannot be negative")
        return self


TorsionStiffness = Annotated[float, Field(ge=1.0, le=1e11)]  # N·m/rad: a soft elastomer coupling ~10, a 1 m shaft ~1e9
TorsionDamping = Annotated[float, Field(ge=0, le=1e8), NotTiny(1e-9)]  # N·m·s/rad
BodyInertia = Annotated[float, Field(ge=1e-9, le=1e7)]  # kg·m²: a micro-motor rotor ~1e-7, a mill drum ~1e5


class ShaftSpring(_Table):
    """The torsional stiffness of the shaft that carries this stage's gear and the next stage's pinion
    (absent: a rigid shaft, one body). For a solid round shaft k = G pi d^4 / (32 L)."""

    stiffness_Nm_rad: TorsionStiffness
    damping_Nms_rad: TorsionDamping = 0.0


class Stage(_Table):
    """One gear pair, in the order power flows. The pinion drives the gear."""

    normal_module_mm: Annotated[float, Field(ge=0.05, le=100)]  # watch gears ~0.05; the largest girth gears ~50
    normal_pressure_angle_deg: Annotated[float, Field(ge=10, le=35)] = 20.0
    helix_angle_deg: Annotated[float, Field(ge=0, lt=45), NotTiny(1e-6)] = 0.0
    pinion: PairGear
    gear: PairGear
    backlash_mm: Annotated[float, Field(ge=0, le=10), NotTiny(1e-6)] = 0.0
    efficiency: Annotated[float, Field(ge=0.1, le=1)] = 1.0
    mesh: ContactOverride | None = None
    basic_rack: BasicRack = BasicRack()
    shaft: ShaftSpring | None = None
    center_angle_deg: CenterAngleDeg = 0.0  # line of centres pinion -> gear, from y, cw seen from the input end
    accuracy_grade: Annotated[int, Field(ge=1, le=12)] | None = None  # ISO 1328-1 flank tolerance class (rating)
    tip_relief_um: Annotated[float, Field(ge=0, le=1000)] | None = None  # C_a (rating; absent: running-in C_ay)
    type: Literal["parallel"] = "parallel"  # a planetary stage says type = "planetary"
    center_distance_allowance_mm: AllowancePair | None = None  # [A_ae, A_ai] on the working centre distance
    model_config = ConfigDict(json_schema_extra=_hands_rule())

    @model_validator(mode="after")
    def _allowance_order(self) -> "Stage":
        _upper_not_below_lower("center_distance_allowance_mm", self.center_distance_allowance_mm)
        return self

    @property
    def has_allowances(self) -> bool:
        """True when any manufacturing allowance of the pair is given."""
        return self.center_distance_allowance_mm is not None or any(
            g.tooth_thickness_allowance_mm is not None or g.tip_diameter_allowance_mm is not None
            for g in (self.pinion, self.gear))

    @property
    def speed_ratio(self) -> float:
        """ω_in / ω_out = z_gear / z_pinion."""
        return self.gear.teeth / self.pinion.teeth


class Planet(Gear):
    """The planets of a planetary stage: one gear description and how many there are."""

    count: Annotated[int, Field(ge=1, le=20)]
    mass_kg: Annotated[float, Field(ge=1e-6, le=1e6)] | None = None  # else from geometry (a solid disc)
    # per planet, its position error along its sun mesh's line of action (a constant transmission error, um;
    # positive: that planet meets the sun early and carries more); the simulation's load sharing sees it
    position_error_um: Annotated[list[Annotated[float, Field(ge=-1000, le=1000)]], Field(max_length=20)] | None = None
    # unequal spacing: each planet's position on the carrier, degrees (planet 1 first); absent: 360 j / count.
    # Each must be a whole multiple of 360/(z_s + z_r) from planet 1 (the design checks it)
    angles_deg: Annotated[list[Annotated[float, Field(ge=-360, le=720)]], Field(min_length=1, max_length=20)] | None = None


class Ring(Gear):
    """The internal ring gear of a planetary stage."""

    # the pinion-type cutter that generates the ring: its teeth z_0 set the root fillet the ring's tooth-root rating
    # uses (ISO 6336-3 for internal gears); absent: the basic rack's fillet (z_0 -> infinity: smaller, conservative)
    cutter_teeth: Annotated[int, Field(ge=8, le=200)] | None = None


class Carrier(_Table):
    """The planet carrier's own body (the planets' translational inertia N m_p r_c² is added to it)."""

    inertia_kg_m2: BodyInertia | None = None  # absent: 0 of its own


PlanetaryMember = Literal["sun", "carrier", "ring"]


def _members_rule() -> Any:
    """``input`` and ``fixed`` (defaults "sun" and "ring") name different members."""
    same = [{**_required("input", "fixed"), "properties": {"input": {"const": m}, "fixed": {"const": m}}}
            for m in ("sun", "carrier", "ring")]
    same += [{"properties": {"input": {"const": "ring"}}, "not": _required("fixed")},
             {"properties": {"fixed": {"const": "sun"}}, "not": _required("input")}]
    return {"not": {"anyOf": same}}


class PlanetaryStage(_Table):
    """A simple planetary stage: sun, ``planet.count`` equally spaced planets on a carrier, an internal ring
    (``ring.teeth`` is the number of internal teeth, given positive). One member is held (``fixed``); the
    previous stage (or the input) drives ``input``; the third member is the output the next stage (or the
    load) is driven by."""

    type: Literal["planetary"]
    normal_module_mm: Annotated[float, Field(ge=0.05, le=100)]
    normal_pressure_angle_deg: Annotated[float, Field(ge=10, le=35)] = 20.0
    helix_angle_deg: Annotated[float, Field(ge=0, lt=45)] = 0.0
    sun: Gear
    planet: Planet
    ring: Ring
    carrier: Carrier = Carrier()
    fixed: PlanetaryMember = "ring"
    input: PlanetaryMember = "sun"
    backlash_mm: Annotated[float, Field(ge=0, le=10), NotTiny(1e-6)] = 0.0
    efficiency: Annotated[float, Field(ge=0.1, le=1)] = 1.0
    mesh: ContactOverride | None = None
    basic_rack: BasicRack = BasicRack()
    shaft: ShaftSpring | None = None
    accuracy_grade: Annotated[int, Field(ge=1, le=12)] | None = None
    tip_relief_um: Annotated[float, Field(ge=0, le=1000)] | None = None
    model_config = ConfigDict(json_schema_extra=_members_rule())

    @model_validator(mode="after")
    def _members(self) -> "PlanetaryStage":
        if self.input == self.fixed:
            raise ValueError(f"input and fixed name the same member ({self.input!r}): the held member "
                             "cannot be driven; name two different members of sun, carrier, ring")
        errors = self.planet.position_error_um
        if errors is not None and len(errors) != self.planet.count:
            raise ValueError(f"planet.position_error_um needs one value per planet ({self.planet.count}), "
                             f"got {len(errors)}")
        if self.ring.teeth <= self.sun.teeth + 2 * self.planet.teeth - 3:
            raise ValueError(f"ring.teeth ({self.ring.teeth}) must be about sun.teeth + 2 planet.teeth "
                             f"({self.sun.teeth + 2 * self.planet.teeth}): the planets must fit between sun and ring")
        return self

    @property
    def output(self) -> str:
        """The member that drives the next stage (or the load): neither held nor driven."""
        return next(m for m in ("sun", "carrier", "ring") if m not in (self.input, self.fixed))

    @property
    def speed_ratio(self) -> float:
        """|ω_in / ω_out| from Willis' equation ω_s − ω_c = −(z_r/z_s)(ω_r − ω_c) with the held member at rest
        (u = z_r/z_s): 1 + u sun↔carrier (ring held), u sun↔ring (carrier held), (1 + u)/u ring↔carrier (sun
        held), the faster member named first; the signed member speeds are ``design.planetary_balance``'s."""
        u = self.ring.teeth / self.sun.teeth
        ratio, faster = {"ring": (1.0 + u, "sun"), "carrier": (u, "sun"), "sun": ((1.0 + u) / u, "ring")}[self.fixed]
        return ratio if self.input == faster else 1.0 / ratio


def _stage_tag(value: Any) -> str:
    """The union tag of a stage table: its ``type``, "parallel" when absent."""
    if isinstance(value, dict):
        return str(value.get("type", "parallel"))
    return str(getattr(value, "type", "parallel"))


AnyStage = Annotated[Annotated[Stage, Tag("parallel")] | Annotated[PlanetaryStage, Tag("planetary")],
                     Discriminator(_stage_tag)]


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


_START_PARAMS = {"switch_speed_rpm": "star_delta", "voltage_ramp_s": "soft_start",
                 "initial_voltage_fraction": "soft_start", "torque_limit_Nm": "vfd"}


def _starting_rules() -> list[dict]:
    """A starting method and its parameters need drive = "motor"; each parameter belongs to its method; star-delta
    needs its switch-over speed, the soft start its ramp; ramp_s > 0 on a motor only for the VFD."""
    motor = {**_required("drive"), "properties": {"drive": {"const": "motor"}}}
    # another drive ignores them (with a note in the design), so that --set input.drive="speed" works on a motor file
    rules: list[dict] = []
    for key, method in _START_PARAMS.items():
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
    torque_ripple: Annotated[list[Ripple], Field(max_length=MAX_HARMONICS)] = []  # drive = "torque" only
    rotation: Literal["cw", "ccw"] = "cw"  # seen from the input end looking along +x (shaft statics)
    # an induction motor (drive = "motor"; with drive = "speed" it checks that the motor can follow the ramp)
    motor: Motor | None = None
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
    fluctuation: Annotated[list[Fluctuation], Field(max_length=MAX_HARMONICS)] = []
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


class Target(_Table):
    output_speed_rpm: Annotated[float, Field(ge=1e-06, le=MAX_SPEED_RPM)] | None = None
    output_speed_deg_s: Annotated[float, Field(ge=6e-06, le=MAX_SPEED_RPM * 6)] | None = None
    tolerance_percent: Annotated[float, Field(ge=1e-6, le=100)] = 5.0
    model_config = ConfigDict(json_schema_extra=_all_of(*_exactly_one(("output_speed_rpm", "output_speed_deg_s"))))

    @model_validator(mode="after")
    def _one_speed(self) -> "Target":
        if (self.output_speed_rpm is None) == (self.output_speed_deg_s is None):
            raise ValueError("give exactly one of output_speed_rpm, output_speed_deg_s")
        return self

    @property
    def output_speed_rpm_value(self) -> float:
        if self.output_speed_rpm is not None:
            return self.output_speed_rpm
        assert self.output_speed_deg_s is not None  # the validator requires exactly one speed
        return self.output_speed_deg_s / 6.0


# Output samples are held in memory (state, channels, then the text written): at this cap the seed scene
# peaked at ~0.9 GB RSS for JSON and ~1.6 GB for CSV (docs/numerics.md, "Numerical robustness"); more is refused.
MAX_STEPS = 2_000_000


class Simulation(_Table):
    duration_s: Annotated[float, Field(ge=1e-4, le=MAX_TIME_S)] = 0.5
    steps: Annotated[int, Field(ge=1, le=MAX_STEPS)] = 2000
    method: Literal[METHODS] = "auto"  # type: ignore[valid-type]
    rtol: Annotated[float, Field(ge=1e-13, le=1e-2)] = 1e-6
    engine: Literal["auto", "python", "compiled"] = "auto"
    window_start_s: Annotated[float, Field(ge=0, le=MAX_TIME_S), NotTiny(1e-6)] | None = None
    steady: Literal["window", "periodic"] = "window"
    error_estimate: bool = True


class Lubricant(_Table):
    """The gear oil (ISO 6336-2: Z_L from the 40 °C viscosity; the others are recorded)."""

    viscosity_40C_mm2_s: Annotated[float, Field(ge=2, le=10000)] | None = None
    viscosity_100C_mm2_s: Annotated[float, Field(ge=1, le=1000)] | None = None
    temperature_C: Annotated[float, Field(ge=-60, le=300)] | None = None
    # the bearings' ISO 281 modified life (docs/bearings.md): cleanliness level (e_C by d_m) or e_C itself
    contamination: Literal["extreme", "high", "normal", "slight", "typical", "severe", "very_severe"] | None = None
    e_C: Annotated[float, Field(ge=0.0, le=1.0)] | None = None

    @model_validator(mode="after")
    def _one_cleanliness(self) -> "Lubricant":
        if self.contamination is not None and self.e_C is not None:
            raise ValueError("give one of contamination (an ISO 281 cleanliness level) and e_C (its factor)")
        return self


class Rating(_Table):
    """Strength rating of every stage by the standard ``standard`` names: ISO 6336-2 (pitting) and -3 (tooth root),
    2006 editions, method B, by default. With this table present, every key the rating needs is required
    (materials, accuracy, roughness, oil)."""

    # the rating standard, a name registered in gearcli.rating (docs/iso6336.md, "Rating standards")
    standard: Annotated[str, Field(min_length=1, max_length=64)] = "iso6336"
    required_life_h: Annotated[float, Field(ge=1e-3, le=1e7)]  # load cycles N_L = 60 n t per member
    face_load_factor: Annotated[float, Field(ge=1, le=10)] | None = None  # K_Hbeta; absent: an ISO estimate
    min_safety_pitting: Annotated[float, Field(ge=0.5, le=10)] = 1.0  # S_Hmin
    min_safety_bending: Annotated[float, Field(ge=0.5, le=10)] = 1.4  # S_Fmin
    material_quality: Literal["normal", "optimum"] = "normal"  # Z_NT, Y_NT at 1e10 cycles: 0.85 or 1.0
    # the profile shift of the tooth-root rating (ISO 6336-3 method B) on members with tooth-thickness allowances:
    # the generating x_E of the "lower" (default: the thinnest tooth, as K_Fbeta's depth), "upper" or "mean"
    # allowance, or the "nominal" x (as some commercial reports rate)
    root_profile_shift: Literal["nominal", "upper", "lower", "mean"] = "lower"
    dynamic_factor: Literal["iso", "simulated"] | Annotated[float, Field(ge=1, le=10)] = "iso"  # K_v
    load_sharing_factor: Annotated[float, Field(ge=1, le=3)] | None = None  # K_gamma of planetary stages; absent: 1
    # a bearing's ISO 76 s_0 below it warns; absent: ball 1.0, roller 1.5 (docs/bearings.md)
    min_static_safety_bearing: Annotated[float, Field(ge=0.1, le=20)] | None = None


class DesignFile(_Table):
    """The whole design file."""

    title: Annotated[str, Field(max_length=200)] = ""
    materials: Annotated[dict[str, Material], Field(max_length=50)] = Field(
        default_factory=lambda: {"steel": Material(density_kg_m3=7800, youngs_modulus_MPa=2.07e5, poisson_ratio=0.29)}
    )
    stage: Annotated[list[AnyStage], Field(min_length=1, max_length=50)]
    contact: Contact = Contact()
    input: Input
    load: Load
    target: Target | None = None
    simulation: Simulation = Simulation()
    bearing: Annotated[list[Bearing], Field(max_length=200)] = []  # shaft statics and ISO 281 (docs/life.md)
    duty: Annotated[list[Duty], Field(max_length=200)] = []  # duty cycle of `gearcli life`
    lubricant: Lubricant | None = None
    rating: Rating | None = None

    @model_validator(mode="after")
    def _load_power_to_torque(self) -> "DesignFile":
        """[load] power_kW becomes the output torque at the nominal output speed, ω_in / Π z_gear/z_pinion;
        a [load] torque_speed table gives its torque at that speed."""
        ratio = math.prod(s.speed_ratio for s in self.stage)
        if self.load.power_kW is not None:
            load = self.load.model_copy()  # never write into a Load another DesignFile may share
            load._torque_from_power_Nm = self.load.power_kW * 1000.0 * ratio / self.input.speed_rad_s_value
            object.__setattr__(self, "load", load)
        elif self.load.torque_speed is not None:
            import numpy as np  # lazy: numpy, start-up time of --help and init (config is numpy-free)

            table = np.array(self.load.torque_speed, dtype=float)
            n_out = self.input.speed_rad_s_value / ratio * 60.0 / (2.0 * math.pi)
            load = self.load.model_copy()
            load._torque_from_power_Nm = float(np.interp(n_out, table[:, 0], table[:, 1]))
            if load._torque_from_power_Nm == 0.0:
                raise ValueError(f"load.torque_speed: the table's torque at the nominal output speed ({n_out:.4g} rpm) "
                                 "is 0; the design needs a load there")
            object.__setattr__(self, "load", load)
        return self

    @model_validator(mode="after")
    def _no_shaft_after_last_stage(self) -> "DesignFile":
        if self.stage[-1].shaft is not None:
            raise ValueError(f"stage[{len(self.stage) - 1}].shaft: the last stage's gear sits on the output shaft, "
                             "which has no next pinion; a flexible output is [load] inertia_kg_m2 with "
                             "coupling_stiffness_Nm_rad")
        return self

    @model_validator(mode="after")
    def _merged_harmonics(self) -> "DesignFile":
        """A stage's phases against the amplitudes it inherits from [contact]."""
        for k, stage in enumerate(self.stage):
            if stage.mesh is not None:
                check_harmonics(self.contact_for(k), f"stage[{k}].mesh.")
        return self

    def pair(self, k: int) -> "Stage":
        """Stage k as a gear pair: a parallel stage (a planetary one is seen as its sun–planet pair through
        ``design.planetary.pair_equivalent``)."""
        stage = self.stage[k]
        if not isinstance(stage, Stage):
            raise TypeError(f"stage[{k}] is a planetary stage, not a gear pair")
        return stage

    def contact_for(self, k: int) -> Contact:
        """The contact law of mesh k (0-based): ``[contact]`` with ``[stage.mesh]`` applied."""
        return self.contact.merged(self.stage[k].mesh)
