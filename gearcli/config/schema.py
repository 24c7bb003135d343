"""The design file, one pydantic model per TOML table (docs/design-file.md, generated from these models).

Units are in the key names (``_mm``, ``_deg``, ``_MPa`` ...) and stay as the user wrote them here;
conversion to SI happens in the design layer. Every model forbids unknown keys and rejects NaN and
infinity; numbers are strict (a string ``"21"`` is not a tooth count), except that an integer is
accepted where a float is expected, as TOML users write ``module = 12``.
"""

from __future__ import annotations

from typing import Annotated, Literal, Optional, Union

from pydantic import AfterValidator, BaseModel, ConfigDict, Field, model_validator

# Every number has physical bounds (docs/design-file.md lists them): far outside any real reducer, yet
# tight enough that a unit mistake (1e15, a subnormal like 1e-320) is an error naming the key and the
# bound, and every derived quantity (inertia ~ rho b d^4, forces, energies, the run's cost) stays finite.
# Quantities that may be 0 (a ramp, damping, backlash, a torque) may not be *nearly* 0: a nonzero
# magnitude below ``tiny`` is refused too (JSON Schema: a "not" range).


def _not_tiny(tiny: float):
    def check(v: float) -> float:
        if v != 0 and abs(v) < tiny:
            raise ValueError(f"must be 0 or at least {tiny:g} in magnitude, got {v!r} (a value this small is a "
                             "mistake)")
        return v

    return check


def Bounded(lo: float, hi: float, *, tiny: Optional[float] = None, lo_open: bool = False):
    """A float in [lo, hi] (``lo_open``: (lo, hi]); with ``tiny``, also 0 < |x| < tiny refused."""
    field = Field(gt=lo, le=hi) if lo_open else Field(ge=lo, le=hi)
    if tiny is None:
        return Annotated[float, field]
    not_range = [{"exclusiveMinimum": 0, "exclusiveMaximum": tiny}]
    if lo < 0:
        not_range.append({"exclusiveMinimum": -tiny, "exclusiveMaximum": 0})
    extra = {"not": {"anyOf": not_range}}
    return Annotated[float, field, AfterValidator(_not_tiny(tiny)), Field(json_schema_extra=extra)]


MAX_SPEED_RPM = 200_000.0  # a turbo-compressor pinion turns at ~60,000 rpm; this is generous
MIN_SPEED_RPM = 1e-3  # one turn in ~17 hours
MAX_TORQUE_NMM = 1e10  # 10 MN·m: beyond the largest mill and ship drives
MAX_TIME_S = 3600.0  # durations, ramps and windows: one hour of simulated time
SpeedRpm = Bounded(MIN_SPEED_RPM, MAX_SPEED_RPM)
SpeedDegS = Bounded(MIN_SPEED_RPM * 6, MAX_SPEED_RPM * 6)
SpeedRadS = Bounded(MIN_SPEED_RPM * 2 * 3.141592653589793 / 60, MAX_SPEED_RPM * 2 * 3.141592653589793 / 60)
TorqueNmm = Bounded(-MAX_TORQUE_NMM, MAX_TORQUE_NMM, tiny=1e-3)
TorqueNm = Bounded(-MAX_TORQUE_NMM / 1e3, MAX_TORQUE_NMM / 1e3, tiny=1e-6)
Seconds = Bounded(0, MAX_TIME_S, tiny=1e-6)
Stiffness = Bounded(1.0, 1e14)  # N/mm^e: linear meshes ~1e6 N/mm, Hertz K ~1e5 N/mm^1.5
DampingNsmm = Bounded(0, 1e6, tiny=1e-9)
DampingDepthMm = Bounded(1e-6, 10.0)
# kept for code that imports them; every key now has its own bounds
PositiveFloat = Annotated[float, Field(gt=0, le=1e15)]
NonNegFloat = Annotated[float, Field(ge=0, le=1e15)]
Torque = TorqueNmm

METHODS = ("auto", "RK45", "DOP853", "Radau", "BDF", "LSODA")


class _Table(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True, allow_inf_nan=False, frozen=True)


class Material(_Table):
    density_kg_m3: Bounded(100, 1e5)  # foams ~100, osmium 22,590
    youngs_modulus_MPa: Bounded(1e3, 1e7)  # polymers ~1e3, diamond 1.2e6
    poisson_ratio: Annotated[float, Field(ge=0.01, lt=0.5)]


class Gear(_Table):
    """One gear of a stage: pinion (driving) or gear (driven)."""

    teeth: Annotated[int, Field(ge=5, le=10000)]
    face_width_mm: Bounded(0.1, 1e4)
    hand: Optional[Literal["left", "right", "spur"]] = None
    material: str = "steel"
    profile_shift: Annotated[float, Field(ge=-1.5, le=1.5)] = 0.0
    inertia_kg_m2: Optional[Bounded(1e-9, 1e6)] = None  # a 5 mm pinion ~1e-9; a mill girth gear ~1e5


class ContactOverride(_Table):
    """The mesh force law (Adams IMPACT). In ``[contact]`` every key has the seed's default; in a
    stage's ``[stage.mesh]`` every key is optional and overrides ``[contact]`` for that mesh."""

    stiffness: Optional[Union[Literal["hertz", "iso6336"], Stiffness]] = None
    exponent: Optional[Annotated[float, Field(ge=1.0, le=3.0)]] = None
    damping_Ns_mm: Optional[DampingNsmm] = None
    full_damping_penetration_mm: Optional[DampingDepthMm] = None
    time_varying: Optional[bool] = None


class Contact(_Table):
    stiffness: Union[Literal["hertz", "iso6336"], Stiffness] = "hertz"
    exponent: Annotated[float, Field(ge=1.0, le=3.0)] = 1.5
    damping_Ns_mm: DampingNsmm = 50.0
    full_damping_penetration_mm: DampingDepthMm = 0.1
    time_varying: bool = False

    def merged(self, override: Optional[ContactOverride]) -> "Contact":
        """This law with a stage's overrides applied."""
        if override is None:
            return self
        changes = {k: v for k, v in override.model_dump().items() if v is not None}
        return self.model_copy(update=changes)


class Stage(_Table):
    """One gear pair, in the order power flows. The pinion drives the gear."""

    normal_module_mm: Bounded(0.05, 100)  # watch gears ~0.05; the largest girth gears ~50
    normal_pressure_angle_deg: Annotated[float, Field(ge=10, le=35)] = 20.0
    helix_angle_deg: Annotated[float, Field(ge=0, lt=45)] = 0.0
    pinion: Gear
    gear: Gear
    backlash_mm: Bounded(0, 10, tiny=1e-6) = 0.0
    efficiency: Bounded(0.1, 1) = 1.0
    mesh: Optional[ContactOverride] = None


class Input(_Table):
    """The input drive. Exactly one speed key: the prescribed speed (``drive = "speed"``) or, with
    ``drive = "torque"``, the nominal speed the train starts at."""

    speed_deg_s: Optional[SpeedDegS] = None
    speed_rpm: Optional[SpeedRpm] = None
    speed_rad_s: Optional[SpeedRadS] = None
    ramp_s: Seconds = 0.0
    drive: Literal["speed", "torque"] = "speed"
    torque_Nm: Optional[TorqueNm] = None
    torque_Nmm: Optional[TorqueNmm] = None

    @model_validator(mode="after")
    def _one_speed_one_torque(self) -> "Input":
        given = [k for k in ("speed_deg_s", "speed_rpm", "speed_rad_s") if getattr(self, k) is not None]
        if len(given) != 1:
            raise ValueError(
                "give exactly one of speed_deg_s, speed_rpm, speed_rad_s"
                + (f" (got {', '.join(given)})" if given else "")
            )
        torques = [k for k in ("torque_Nm", "torque_Nmm") if getattr(self, k) is not None]
        if len(torques) > 1:
            raise ValueError("give at most one of torque_Nm, torque_Nmm")
        if self.drive == "torque" and not torques:
            raise ValueError('drive = "torque" needs torque_Nm or torque_Nmm')
        if self.drive == "speed" and torques:
            raise ValueError('torque_Nm/torque_Nmm are only used with drive = "torque"')
        return self

    @property
    def speed_rad_s_value(self) -> float:
        import math

        if self.speed_rad_s is not None:
            return self.speed_rad_s
        if self.speed_rpm is not None:
            return self.speed_rpm * 2 * math.pi / 60
        return math.radians(self.speed_deg_s)

    @property
    def torque_Nm_value(self) -> Optional[float]:
        if self.torque_Nm is not None:
            return self.torque_Nm
        if self.torque_Nmm is not None:
            return self.torque_Nmm / 1000.0
        return None


class Load(_Table):
    """Torque on the output shaft, resisting its rotation (negative: load reversal)."""

    torque_Nmm: Optional[TorqueNmm] = None
    torque_Nm: Optional[TorqueNm] = None
    ramp_s: Seconds = 0.0
    application_factor: Annotated[float, Field(ge=1.0, le=10.0)] = 1.0

    @model_validator(mode="after")
    def _one_torque(self) -> "Load":
        given = [k for k in ("torque_Nmm", "torque_Nm") if getattr(self, k) is not None]
        if len(given) != 1:
            raise ValueError("give exactly one of torque_Nmm, torque_Nm" + (f" (got {', '.join(given)})" if given else ""))
        return self

    @property
    def torque_Nm_value(self) -> float:
        return self.torque_Nm if self.torque_Nm is not None else self.torque_Nmm / 1000.0


class Target(_Table):
    output_speed_rpm: Optional[Bounded(1e-6, MAX_SPEED_RPM)] = None
    output_speed_deg_s: Optional[Bounded(6e-6, MAX_SPEED_RPM * 6)] = None
    tolerance_percent: Annotated[float, Field(gt=0, le=100)] = 5.0

    @model_validator(mode="after")
    def _one_speed(self) -> "Target":
        if (self.output_speed_rpm is None) == (self.output_speed_deg_s is None):
            raise ValueError("give exactly one of output_speed_rpm, output_speed_deg_s")
        return self

    @property
    def output_speed_rpm_value(self) -> float:
        if self.output_speed_rpm is not None:
            return self.output_speed_rpm
        return self.output_speed_deg_s / 6.0


# Output samples are held in memory (state, channels, then the text written): at this cap the seed scene
# peaked at ~0.9 GB RSS for JSON and ~1.6 GB for CSV (README, "Numerical robustness"); more is refused.
MAX_STEPS = 2_000_000


class Simulation(_Table):
    duration_s: Bounded(1e-4, MAX_TIME_S) = 0.5
    steps: Annotated[int, Field(ge=1, le=MAX_STEPS)] = 2000
    method: Literal[METHODS] = "auto"  # type: ignore[valid-type]
    rtol: Annotated[float, Field(ge=1e-13, le=1e-2)] = 1e-6
    window_start_s: Optional[Bounded(0, MAX_TIME_S)] = None


class DesignFile(_Table):
    """The whole design file."""

    title: Annotated[str, Field(max_length=200)] = ""
    materials: Annotated[dict[str, Material], Field(max_length=50)] = Field(
        default_factory=lambda: {"steel": Material(density_kg_m3=7800, youngs_modulus_MPa=2.07e5, poisson_ratio=0.29)}
    )
    stage: Annotated[list[Stage], Field(min_length=1, max_length=50)]
    contact: Contact = Contact()
    input: Input
    load: Load
    target: Optional[Target] = None
    simulation: Simulation = Simulation()

    def contact_for(self, k: int) -> Contact:
        """The contact law of mesh k (0-based): ``[contact]`` with ``[stage.mesh]`` applied."""
        return self.contact.merged(self.stage[k].mesh)
