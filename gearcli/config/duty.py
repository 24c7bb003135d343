"""Design-file tables of loads to life (docs/life.md): ``[[bearing]]`` rolling bearings under the shafts and
``[[duty]]`` operating points of a duty cycle. :mod:`gearcli.config.schema` puts them into the design file.

The rules between tables (a bearing's shaft exists, two bearings per shaft with exactly one locating, the
gears of a supported shaft have axial positions) need the whole train; ``gearcli.design.shafts`` checks
them and names the key.
"""


import math
from typing import Annotated, Any, Literal

from pydantic import ConfigDict, Field, model_validator

from gearcli.config.bounds_types import StrictTable
from gearcli.config.schema_rules import MAX_TORQUE_NMM

AxialPositionMm = Annotated[float, Field(ge=-1e5, le=1e5)]  # along x from the housing plane, mm
CenterAngleDeg = Annotated[float, Field(ge=-360.0, le=360.0)]
DUTY_TORQUE_KEYS = ("torque_Nm", "torque_Nmm", "power_kW")
MAX_DUTY_POINTS = 200
#: the keys a duty point sets itself from its speed_rpm and torque (and K_A = 1): its ``set`` may not give them
POINT_OWN_KEYS = frozenset({"input.speed_rpm", "input.speed_deg_s", "input.speed_rad_s", "input.torque_Nm",
                            "input.torque_Nmm", "input.power_kW", "load.torque_Nm", "load.torque_Nmm",
                            "load.power_kW", "load.torque_speed", "load.application_factor"})
#: the keys that judge or make the duty as a whole (its required life, minimum safeties, its points): the same for
#: every point, so a point's ``set`` may not give them (the duty's verdicts would follow one point's)
DUTY_WIDE_KEYS = frozenset({"rating.required_life_h", "rating.min_safety_pitting", "rating.min_safety_bending",
                            "rating.min_static_safety_bearing"})
MAX_BEARINGS = 200
#: what makes a rated gear and its S-N curve (docs/life.md "Inputs"): the Miner sum adds one member's damage over the
#: points, so a point's ``set`` may not give another gear (stage.k's geometry and members, the materials, the curve)
GEAR_STAGE_KEYS = frozenset({"normal_module_mm", "normal_pressure_angle_deg", "helix_angle_deg", "pinion", "gear",
                             "sun", "planet", "ring", "basic_rack", "accuracy_grade", "type", "fixed", "input",
                             "center_angle_deg", "center_distance_allowance_mm"})
GEAR_RATING_KEYS = frozenset({"rating.standard", "rating.material_quality", "rating.root_profile_shift",
                              "rating.virtual_tooth_count"})


def is_gear_key(path: str) -> bool:
    """Whether the dotted ``path`` a duty point's ``set`` writes gives a gear of its own: the stage list or a
    stage table, a stage's geometry or member key, a material, or the rating's S-N curve and standard."""
    parts = path.split(".")
    if parts[0] == "materials" or path in GEAR_RATING_KEYS:
        return True
    if parts[0] != "stage":
        return False
    return len(parts) < 3 or parts[2] in GEAR_STAGE_KEYS


def set_paths(key: str, value: Any) -> list[tuple[str, str]]:
    """The keys a duty point's ``set`` entry writes, each as (written, its dotted path): the key read as ``--set``
    reads it (``input."speed_rpm"`` and ``stage[0]`` are ``input.speed_rpm`` and ``stage.0``), and, where the value
    is a table (``{"input" = {"speed_rpm" = 3}}`` replaces the whole [input]), every key under it."""
    from gearcli.config.overrides import split_key  # lazy: overrides imports the schema, which imports this module

    head = ".".join(seg for seg, _ in split_key(key)).replace(" ", "")
    out = [(key.strip(), head)]
    if isinstance(value, dict):
        out += [(f"{key.strip()}.{k}", p) for k, v in value.items()
                for _, p in set_paths(f"{head}.{_quoted(str(k))}", v)]
    return out


def _quoted(segment: str) -> str:
    return f'"{segment}"' if "." in segment or '"' in segment else segment


class _Table(StrictTable):
    pass


class BearingFactors(_Table):
    """ISO 281 dynamic equivalent load P = F_r when F_a/F_r <= e, else X F_r + Y F_a (catalogue values)."""

    e: Annotated[float, Field(ge=0.0, le=100.0)] = 0.0
    X: Annotated[float, Field(ge=0.0, le=10.0)] = 1.0
    Y: Annotated[float, Field(ge=0.0, le=100.0)] = 0.0

    @model_validator(mode="after")
    def _e_with_x_and_y(self) -> "BearingFactors":
        # without e (default 0) any axial force switched to X F_r + Y F_a, below F_r for a small F_a (X < 1)
        if "e" not in self.model_fields_set and (self.X != 1.0 or self.Y != 0.0):
            raise ValueError(f"X = {self.X:g}, Y = {self.Y:g} need e, the catalogue's limit of F_a/F_r below which P = F_r "
                             "(give e = 0 to apply X and Y at any axial force)")
        if self.X == 0.0 and self.Y == 0.0:  # P = 0 above e: no load, an infinite life, whatever the forces
            raise ValueError("X = 0 and Y = 0 make the equivalent load P = X F_r + Y F_a zero when F_a/F_r > e (no load, "
                             "an infinite life): give the catalogue's X and Y (a radial bearing: X 0.4 to 0.56, Y > 0; "
                             "a thrust bearing: X 0, Y 1)")
        return self


class StaticFactors(_Table):
    """ISO 76 static equivalent load of a radial bearing: P_0 = max(F_r, X0 F_r + Y0 F_a) (catalogue values)."""

    X0: Annotated[float, Field(ge=0.0, le=10.0)] = 1.0
    Y0: Annotated[float, Field(ge=0.0, le=100.0)] = 0.0


class Bearing(_Table):
    """A rolling bearing under one shaft: two per supported shaft, exactly one of them locating (it takes
    the shaft's axial force). Shaft 1 carries pinion 1, shaft k+1 gear k and pinion k+1 (a planetary stage
    k: its input member is on shaft k, its output member on shaft k+1). ``planet_stage = k`` instead of
    ``shaft`` puts the bearing on the pin of every planet of planetary stage k (two per pin; ``position_mm``
    along the pin, from the same housing plane as ``planet.axial_position_mm``)."""

    shaft: Annotated[int, Field(ge=1, le=51)] | None = None
    planet_stage: Annotated[int, Field(ge=1, le=50)] | None = None
    position_mm: AxialPositionMm
    dynamic_load_rating_kN: Annotated[float, Field(ge=1e-3, le=1e5)]  # C
    kind: Literal["ball", "roller"]
    locating: bool = False
    factors: BearingFactors = BearingFactors.model_construct()
    # ISO 76 static safety and ISO 281 modified life (docs/bearings.md); all optional
    static_load_rating_kN: Annotated[float, Field(ge=1e-3, le=1e5)] | None = None  # C_0
    static_factors: StaticFactors = StaticFactors.model_construct()
    fatigue_load_limit_kN: Annotated[float, Field(ge=1e-4, le=1e4)] | None = None  # C_u
    pitch_diameter_mm: Annotated[float, Field(ge=1.0, le=1e4)] | None = None  # d_m = (d + D) / 2
    reliability_percent: Annotated[float, Field(ge=90.0, le=99.95)] | None = None  # a_1; absent: 90
    model_config = ConfigDict(json_schema_extra={"oneOf": [{"required": ["shaft"]}, {"required": ["planet_stage"]}]})

    @model_validator(mode="after")
    def _one_place(self) -> "Bearing":
        if (self.shaft is None) == (self.planet_stage is None):
            raise ValueError("give exactly one of shaft (a shaft's bearing) and planet_stage (a planet pin's bearing)")
        return self


#: the most hours one duty point (a [[duty]] table, or a --series history) may hold: 1,141 years
MAX_DUTY_HOURS = 1e7


class Duty(_Table):
    """One operating point of the duty cycle: its share of the life in hours, the output torque (one of
    torque_Nm, torque_Nmm, power_kW at the output speed) and the input speed; ``set`` holds any other key
    of the design file as ``--set`` takes it (``{"load.fluctuation" = ...}``)."""

    name: Annotated[str, Field(min_length=1, max_length=60)]
    hours: Annotated[float, Field(ge=0.0, le=MAX_DUTY_HOURS)]  # 0: an empty bin of a spectrum (left out, with a note)
    speed_rpm: Annotated[float, Field(ge=1e-3, le=200_000.0)]
    torque_Nm: Annotated[float, Field(ge=-MAX_TORQUE_NMM / 1e3, le=MAX_TORQUE_NMM / 1e3)] | None = None
    torque_Nmm: Annotated[float, Field(ge=-MAX_TORQUE_NMM, le=MAX_TORQUE_NMM)] | None = None
    power_kW: Annotated[float, Field(ge=-1e6, le=1e6)] | None = None
    set: Annotated[dict[str, Any], Field(max_length=50)] = {}
    starts: Annotated[int, Field(ge=0, le=100_000_000)] = 0  # start-ups over the point's hours (issue 30)
    model_config = ConfigDict(json_schema_extra={"allOf": [
        {"anyOf": [{"required": [k]} for k in DUTY_TORQUE_KEYS]},
        {"not": {"anyOf": [{"required": [a, b]} for i, a in enumerate(DUTY_TORQUE_KEYS)
                           for b in DUTY_TORQUE_KEYS[i + 1:]]}}]})

    @model_validator(mode="after")
    def _one_torque(self) -> "Duty":
        given = [k for k in DUTY_TORQUE_KEYS if getattr(self, k) is not None]
        if len(given) != 1:
            raise ValueError(f"give exactly one of {', '.join(DUTY_TORQUE_KEYS)}"
                             + (f" (got {', '.join(given)})" if given else ""))
        paths = [pair for k, v in self.set.items() for pair in set_paths(k, v)]
        own = [shown for shown, p in paths if p in POINT_OWN_KEYS]
        if own:
            raise ValueError(f"set: {own[0]} is the point's own: its torque is {given[0]}, its speed speed_rpm, "
                             "K_A = 1 (the spectrum is the load); a set of it would contradict the point reported")
        wide = [shown for shown, p in paths if p in DUTY_WIDE_KEYS or p.split(".")[0] == "duty"]
        if wide:
            raise ValueError(f"set: {wide[0]} is the duty's, not a point's: the duty's hours, required life and "
                             "minimum safeties judge all its points together; set it in the file itself")
        hardware = [shown for shown, p in paths if p.startswith("bearing")]
        if hardware:
            raise ValueError(f"set: {hardware[0]}: a bearing is the same at every duty point (its catalogue data, place "
                             "and reliability hold over the whole duty, which its L10, L_nm and s_0 sum); set it in "
                             "[[bearing]] itself")
        gears = [shown for shown, p in paths if is_gear_key(p)]
        if gears:
            raise ValueError(f"set: {gears[0]}: a gear is the same at every duty point (its geometry, material and "
                             "S-N curve hold over the whole duty, whose Miner sum adds its points' damage); set it in "
                             "the file itself, or run life on each variant")
        return self

    def output_torque_Nm(self, total_ratio: float) -> float:
        """The output torque of this point; power_kW at the output speed speed_rpm / total_ratio."""
        if self.torque_Nm is not None:
            return self.torque_Nm
        if self.torque_Nmm is not None:
            return self.torque_Nmm / 1000.0
        assert self.power_kW is not None  # the validator requires exactly one torque key
        return self.power_kW * 1000.0 / (self.speed_rpm * 2 * math.pi / 60 / total_ratio)
