"""The design file, one pydantic model per TOML table (docs/design-file.md, generated from these models).

Units are in the key names (``_mm``, ``_deg``, ``_MPa`` ...) and stay as the user wrote them here;
conversion to SI happens in the design layer. Every model forbids unknown keys and rejects NaN and
infinity; numbers are strict (a string ``"21"`` is not a tooth count), except that an integer is
accepted where a float is expected, as TOML users write ``module = 12``.

The tables by concern: the bounds and rules between keys (:mod:`~gearcli.config.schema_rules`), the members
(:mod:`~gearcli.config.members`), the stages (:mod:`~gearcli.config.stage_tables`), the drive and the load
(:mod:`~gearcli.config.drive`), contact, duty, bearings, excitation and machines in their modules; here the
whole file (:class:`DesignFile`) and the small tables, with every table's name re-exported (one namespace).
"""

import math
from typing import Annotated, Literal, get_args

from pydantic import BaseModel, ConfigDict, Field, PrivateAttr, TypeAdapter, model_validator

from gearcli.config.bounds_types import IfGiven, NotTiny, given_tables
from gearcli.config.contact import (  # noqa: F401 (re-exported: the design file's tables, one namespace)
    DEFAULT_DAMPING_RATIO,
    IMPACT_KEYS,
    Contact,
    ContactOverride,
    DampingDepthMm,
    DampingNsmm,
    Stiffness,
)
from gearcli.config.drive import Input, Load  # noqa: F401 (re-exported)
from gearcli.config.duty import Bearing, Duty
from gearcli.config.excitation import MAX_HARMONICS, check_harmonics  # noqa: F401 (MAX_HARMONICS re-exported)
from gearcli.config.machine import table_value
from gearcli.config.members import BasicRack, Carrier, Gear, Material, PairGear, Planet, Ring, Sun  # noqa: F401
from gearcli.config.schema_rules import (  # noqa: F401 (re-exported)
    INPUT_TORQUE_KEYS,
    LOAD_TORQUE_KEYS,
    MAX_SPEED_RPM,
    MAX_TIME_S,
    MAX_TORQUE_NMM,
    MIN_DURATION_S,
    MIN_SPEED_RPM,
    RPM_TO_RAD_S,
    AllowanceMm,
    AllowancePair,
    BodyInertia,
    NonNegFloat,
    PositiveFloat,
    Power,
    Seconds,
    SpeedDegS,
    SpeedRadS,
    SpeedRpm,
    Torque,
    TorqueNm,
    TorqueNmm,
    TorsionDamping,
    TorsionStiffness,
    _all_of,
    _exactly_one,
    _Table,
)
from gearcli.config.stage_tables import (  # noqa: F401 (re-exported)
    AnyStage,
    PlanetaryMember,
    PlanetaryStage,
    ShaftSpring,
    Stage,
    kinds_named,
    only_kinds,
)
from gearcli.core import plugins
from gearcli.core.methods import NAMES as METHODS  # the one registry of integration methods
from gearcli.errors import PluginError
from gearcli.stages import kinds

#: what every layer reads of any stage table (docs/plugins.md, "A stage kind"): its fields and its properties
STAGE_TABLE_FIELDS = ("type", "mesh", "shaft")
STAGE_TABLE_PROPERTIES = ("speed_ratio", "efficiency")


def check_stage_table(kind: str, table: object) -> None:
    """A :class:`~gearcli.errors.PluginError` naming the kind and what the table lacks where it is no pydantic
    model class with the fields ``type`` (``Literal[kind]``), ``mesh`` and ``shaft`` and the properties
    ``speed_ratio`` and ``efficiency``: the validation, the kinematics and the model read them of every stage, and
    a table without them failed there as gearcli's internal error (an AttributeError far from its cause)."""
    where = f'stage type "{kind}" ({getattr(table, "__module__", type(table).__module__)})'
    if not (isinstance(table, type) and issubclass(table, BaseModel)):
        raise PluginError(f"{where}: its table is {table!r}, not a pydantic model class (register_stage_table(kind, "
                          'TableClass), a gearcli.config.bounds_types.StrictTable; docs/plugins.md, "A stage kind")')
    fields = table.model_fields
    lacks = [f for f in STAGE_TABLE_FIELDS if f not in fields]
    lacks += [p for p in STAGE_TABLE_PROPERTIES if p not in fields and not hasattr(table, p)]
    tag = get_args(fields["type"].annotation) if "type" in fields else (kind,)
    if lacks or tag != (kind,):
        what = ([f"no {', '.join(lacks)}"] if lacks else []) + ([f"type {fields['type'].annotation!r}"]
                                                                 if tag != (kind,) else [])
        raise PluginError(f"{where}: its table {table.__name__} has {' and '.join(what)}: every stage table has "
                          f'type: Literal["{kind}"], the fields mesh and shaft (None = None without a contact law or '
                          "a flexible output shaft) and the properties speed_ratio and efficiency (docs/plugins.md, "
                          '"A stage kind")')


def register_stage_table(kind: str, table: type[BaseModel]) -> None:
    """Register the schema table of stage ``type = kind`` (a plug-in kind) and rebuild the design file's
    schema with it; a table without what every stage table has is refused (:func:`check_stage_table`), after a
    second registrant of the name (a conflict names both, docs/plugins.md, "Names")."""
    kinds.provide(kind, "table", table)
    try:
        check_stage_table(kind, table)
    except PluginError:
        kinds.withdraw(kind, "table")
        raise
    _BY_KINDS.clear()
    DesignFile.model_rebuild(force=True)


def _rebuild_without(claims: list[tuple[str, str, str]]) -> None:
    """The design file's schema without the tables of a plug-in that failed to load (withdrawn by the registry)."""
    if any(what == kinds.SEAM and part == "table" for what, _, part in claims):
        _BY_KINDS.clear()
        DesignFile.model_rebuild(force=True)


plugins.on_failure(_rebuild_without)


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
    duration_s: Annotated[float, Field(ge=MIN_DURATION_S, le=MAX_TIME_S)] = 0.5
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
        nu40, nu100 = self.viscosity_40C_mm2_s, self.viscosity_100C_mm2_s
        if nu40 is not None and nu100 is not None and nu100 >= nu40:
            raise ValueError(f"viscosity_100C_mm2_s = {nu100:g} is not below viscosity_40C_mm2_s = {nu40:g}: an oil "
                             "thins as it warms (the bearings' viscosity at temperature_C runs through both, ASTM D341)")
        return self


BEARING_ONLY = frozenset({"min_static_safety_bearing"})  # [rating] keys about the bearings, not the gears


def _rating_schema(schema: dict) -> None:
    """The JSON Schema of [rating]: ``required_life_h`` (a number) unless the table holds the bearings' keys only."""
    schema["required"] = [k for k in schema.get("required", []) if k != "required_life_h"]
    if not schema["required"]:
        del schema["required"]
    life = schema["properties"]["required_life_h"]
    schema["properties"]["required_life_h"] = {**life["anyOf"][0], "title": life.get("title", "Required Life H")}
    schema["anyOf"] = [{"required": ["required_life_h"]},
                       {"required": sorted(BEARING_ONLY), "maxProperties": len(BEARING_ONLY)}]


class Rating(_Table):
    """Strength rating of every stage by the standard ``standard`` names: ISO 6336-2 (pitting) and -3 (tooth root),
    2006 editions, method B, by default. With this table present, every key the rating needs is required
    (required_life_h, materials, accuracy, roughness, oil), unless the table sets only min_static_safety_bearing:
    then it rates no gear and sets the bearings' ISO 76 minimum alone."""

    model_config = ConfigDict(json_schema_extra=_rating_schema)

    # the rating standard, a name registered in gearcli.rating (docs/iso6336.md, "Rating standards")
    standard: Annotated[str, Field(min_length=1, max_length=64)] = "iso6336"
    # load cycles N_L = 60 n t per member; required (None only in a table that sets only the bearings' minimum)
    required_life_h: Annotated[float, Field(ge=1e-3, le=1e7)] | None
    face_load_factor: Annotated[float, Field(ge=1, le=10)] | None = None  # K_Hbeta; absent: an ISO estimate
    min_safety_pitting: Annotated[float, Field(ge=0.5, le=10)] = 1.0  # S_Hmin
    min_safety_bending: Annotated[float, Field(ge=0.5, le=10)] = 1.4  # S_Fmin
    material_quality: Literal["normal", "optimum"] = "normal"  # Z_NT, Y_NT at 1e10 cycles: 0.85 or 1.0
    # the profile shift of the tooth-root rating (ISO 6336-3 method B) on members with tooth-thickness allowances:
    # the generating x_E of the "lower" (default: the thinnest tooth, as K_Fbeta's depth), "upper" or "mean"
    # allowance, or the "nominal" x (as some commercial reports rate)
    root_profile_shift: Literal["nominal", "upper", "lower", "mean"] = "lower"
    # the virtual tooth count in method B's load angle γ_e: ISO 6336-3's z_n = z/(cos² β_b cos β) ("iso"), or the
    # classical approximation z/cos³ β ("cos3", not ISO: reproduces reports of tools that use it; docs/iso6336.md)
    virtual_tooth_count: Literal["iso", "cos3"] = "iso"
    dynamic_factor: Literal["iso", "simulated"] | Annotated[float, Field(ge=1, le=10)] = "iso"  # K_v
    load_sharing_factor: Annotated[float, Field(ge=1, le=3)] | None = None  # K_gamma of planetary stages; absent: 1
    K_gamma: Annotated[float, Field(ge=1, le=3)] | None = None  # the same K_gamma under DESIGN §11's name (one of the two)
    # a bearing's ISO 76 s_0 below it warns; absent: ball 1.0, roller 1.5 (docs/bearings.md)
    min_static_safety_bearing: Annotated[float, Field(ge=0.1, le=20)] | None = None

    @property
    def life_h(self) -> float:
        """``required_life_h`` of a table that rates the gears (the only kind ``DesignFile.rating`` holds)."""
        assert self.required_life_h is not None, "a bearing-only [rating] table rates no gear"
        return self.required_life_h

    @model_validator(mode="after")
    def _one_load_sharing_factor(self) -> "Rating":
        """``K_gamma`` is ``load_sharing_factor`` under the symbol's name: either key, not both."""
        if self.K_gamma is not None:
            if self.load_sharing_factor is not None:
                raise ValueError("give one of load_sharing_factor and K_gamma: both are the planets' K_gamma")
            object.__setattr__(self, "load_sharing_factor", self.K_gamma)
        return self

    @model_validator(mode="before")
    @classmethod
    def _bearing_only(cls, data: object) -> object:
        """A table of the bearings' keys only rates no gear: its life is None (DesignFile then drops the table
        from the gear rating); any other table without ``required_life_h`` is that key missing, as pydantic says."""
        if isinstance(data, dict) and data and set(data) <= BEARING_ONLY:
            return {**data, "required_life_h": None}
        return data


#: the design file's optional tables (:class:`~gearcli.config.bounds_types.IfGiven`): a validator of the tables a
#: file gives (:func:`validate_design`) holds these only when the file gives them
OPTIONAL_TABLES = ("bearing", "duty", "lubricant", "rating", "input.motor", "input.torque_ripple", "load.fluctuation",
                   "stage.mesh", "stage.shaft")


class DesignFile(_Table):
    """The whole design file."""

    title: Annotated[str, Field(max_length=200)] = ""
    materials: Annotated[dict[str, Material], Field(max_length=50)] = Field(
        default_factory=lambda: {"steel": Material(density_kg_m3=7800, youngs_modulus_MPa=2.07e5, poisson_ratio=0.29)}
    )
    stage: Annotated[list[AnyStage], Field(min_length=1, max_length=50)]
    contact: Contact = Contact.model_construct()  # the defaults, valid: no validator built at import
    input: Input
    load: Load
    target: Target | None = None
    simulation: Simulation = Simulation.model_construct()  # the defaults (as contact)
    bearing: Annotated[list[Bearing], Field(max_length=200), IfGiven("bearing")] = []  # shaft statics, ISO 281
    duty: Annotated[list[Duty], Field(max_length=200), IfGiven("duty")] = []  # duty cycle of `gearcli life`
    lubricant: Annotated[Lubricant | None, IfGiven("lubricant")] = None
    rating: Annotated[Rating | None, IfGiven("rating")] = None
    _min_static_safety_bearing: float | None = PrivateAttr(default=None)  # of a bearing-only [rating] table

    @model_validator(mode="after")
    def _bearing_only_rating(self) -> "DesignFile":
        """A ``[rating]`` table that sets only the bearings' ISO 76 minimum (``Rating._bearing_only``) rates no
        gear: ``rating`` None, the minimum kept for :attr:`min_static_safety_bearing`."""
        r = self.rating
        if r is None or r.required_life_h is not None:
            return self
        self._min_static_safety_bearing = r.min_static_safety_bearing
        object.__setattr__(self, "rating", None)
        return self

    @property
    def min_static_safety_bearing(self) -> float | None:
        """``[rating] min_static_safety_bearing``, whether the table rates the gears or sets only this minimum."""
        return self.rating.min_static_safety_bearing if self.rating is not None else self._min_static_safety_bearing

    @model_validator(mode="after")
    def _load_power_to_torque(self) -> "DesignFile":
        """[load] power_kW becomes the output torque at the nominal output speed, ω_in / Π z_gear/z_pinion;
        a [load] torque_speed table gives its torque at that speed."""
        ratio = math.prod(kinds.table_figure(s, "speed_ratio") for s in self.stage)
        if self.load.power_kW is not None:
            load = self.load.model_copy()  # never write into a Load another DesignFile may share
            load._torque_from_power_Nm = self.load.power_kW * 1000.0 * ratio / self.input.speed_rad_s_value
            object.__setattr__(self, "load", load)
        elif self.load.torque_speed is not None:
            n_out = self.input.speed_rad_s_value / ratio * 60.0 / (2.0 * math.pi)
            load = self.load.model_copy()
            # as the model takes the table (its last segment extended): the design's load is the run's at that speed
            load._torque_from_power_Nm = table_value(self.load.torque_speed, n_out)
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
                check_harmonics(self.contact_for(k), f"stage[{k}].mesh.", stage.mesh.model_fields_set)
        return self

    def pair(self, k: int) -> Stage:
        """Stage k as a gear pair: a parallel stage (another kind is seen as the pair it designs through
        ``gearcli.stages.design.pair_view``)."""
        stage = self.stage[k]
        if not isinstance(stage, Stage):
            raise TypeError(f"stage[{k}] is of type {getattr(stage, 'type', '?')!r}, not a gear pair")
        return stage

    def contact_for(self, k: int) -> Contact:
        """The contact law of mesh k (0-based): ``[contact]`` with ``[stage.mesh]`` applied."""
        return self.contact.merged(self.stage[k].mesh)


#: the design file's validators of the tables a file gives (:func:`validate_design`), by its stage kinds (each with
#: the table class registered for it when the validator was built) and optional tables
_BY_KINDS: dict[tuple[bool, frozenset[tuple[str, object]], frozenset[str]], TypeAdapter] = {}


def _given(data: dict) -> frozenset[str]:
    """The :data:`OPTIONAL_TABLES` ``data`` (a design file, parsed) gives: a key of its table, or of any stage
    (a table of the wrong type counts as given: its own error comes first)."""
    out = []
    for path in OPTIONAL_TABLES:
        head, _, key = path.partition(".")
        if head not in data:
            continue
        value = data[head]
        items = [value] if isinstance(value, dict) else value if isinstance(value, list) else None
        if not key or items is None or any(not isinstance(v, dict) or key in v for v in items):
            out.append(path)
    return frozenset(out)


def validate_design(data: dict) -> DesignFile:
    """``DesignFile.model_validate(data)``, by a validator of the tables the file gives: of the stage kinds it
    names (:func:`gearcli.config.stage_tables.kinds_named`: a parallel file's holds no planetary stage table, its
    members and their rules) and of the :data:`OPTIONAL_TABLES` it gives (no bearing, duty, motor or mesh override
    table without them), about half of what building the whole file's validator costs on the first load (~17 ms).
    The same instance and the same errors: a stage validates by its kind's table either way, and a table the file
    does not give is never validated."""
    used = kinds_named(data)
    given = _given(data)
    if used is None and len(given) == len(OPTIONAL_TABLES):
        return DesignFile.model_validate(data)
    # keyed by the kinds' table classes too, every registered kind's where the validator holds them all: a table
    # withdrawn or provided again (kinds.withdraw, kinds.provide: a test swapping or removing a plug-in's table) is
    # validated, and an unknown kind's error names the kinds, as DesignFile's rebuilt validator does
    named = used if used is not None else kinds.kinds("table")
    key = (used is None, frozenset((k, kinds.facet(k, "table")) for k in named), given)
    adapter = _BY_KINDS.get(key)
    if adapter is None:
        adapter = TypeAdapter(DesignFile)  # a table's validator is deferred (STRICT): built now, of those tables
        with only_kinds(used), given_tables(given):
            adapter.rebuild()
        _BY_KINDS[key] = adapter
    return adapter.validate_python(data)
