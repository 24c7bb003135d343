"""The design file's stage tables: a parallel stage (a gear pair) and a planetary stage, the flexible shaft after a
stage, and the union of every registered stage kind's table (``type``, :mod:`gearcli.stages.kinds`)."""

from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from typing import Annotated, Any, Literal, cast

from pydantic import ConfigDict, Field, GetCoreSchemaHandler, Tag, model_validator
from pydantic_core import core_schema

from gearcli.config.bounds_types import IfGiven, NotTiny
from gearcli.config.contact import ContactOverride
from gearcli.config.duty import CenterAngleDeg
from gearcli.config.members import BasicRack, Carrier, PairGear, Planet, Ring, Sun
from gearcli.config.schema_rules import (
    AllowancePair,
    KeyedValueError,
    TorsionDamping,
    TorsionStiffness,
    _hands_rule,
    _required,
    _Table,
    _upper_not_below_lower,
)
from gearcli.stages import kinds


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
    mesh: Annotated[ContactOverride | None, IfGiven("stage.mesh")] = None
    basic_rack: BasicRack = BasicRack.model_construct()  # the defaults, valid: no validator built at import
    shaft: Annotated[ShaftSpring | None, IfGiven("stage.shaft")] = None
    center_angle_deg: CenterAngleDeg = 0.0  # line of centres pinion -> gear, from y, cw seen from the input end
    accuracy_grade: Annotated[int, Field(ge=1, le=12)] | None = None  # ISO 1328-1 flank tolerance class (rating)
    tip_relief_um: Annotated[float, Field(ge=0, le=1000)] | None = None  # C_a (rating; absent: 0, DESIGN §8)
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


PlanetaryMember = Literal["sun", "carrier", "ring"]


def _members_rule() -> Any:
    """``input`` and ``fixed`` (defaults "sun" and "ring") name different members."""
    same = [{**_required("input", "fixed"), "properties": {"input": {"const": m}, "fixed": {"const": m}}}
            for m in ("sun", "carrier", "ring")]
    # an absent key takes its default: input = "ring" with fixed absent (the ring) clashes, and so does fixed = "sun"
    # with input absent (the sun); "required" makes each apply only where its key is given (a "properties" clause
    # alone holds vacuously, so a stage giving neither key was refused by the schema, accepted by validation)
    same += [{**_required("input"), "properties": {"input": {"const": "ring"}}, "not": _required("fixed")},
             {**_required("fixed"), "properties": {"fixed": {"const": "sun"}}, "not": _required("input")}]
    return {"not": {"anyOf": same}}


class PlanetaryStage(_Table):
    """A simple planetary stage: sun, ``planet.count`` planets on a carrier (equally spaced, or at
    ``planet.angles_deg``), an internal ring (``ring.teeth`` is the number of internal teeth, given positive). One
    member is held (``fixed``); the previous stage (or the input) drives ``input``; the third member is the output
    the next stage (or the load) is driven by."""

    type: Literal["planetary"]
    normal_module_mm: Annotated[float, Field(ge=0.05, le=100)]
    normal_pressure_angle_deg: Annotated[float, Field(ge=10, le=35)] = 20.0
    helix_angle_deg: Annotated[float, Field(ge=0, lt=45)] = 0.0
    sun: Sun
    planet: Planet
    ring: Ring
    carrier: Carrier = Carrier.model_construct()
    fixed: PlanetaryMember = "ring"
    input: PlanetaryMember = "sun"
    backlash_mm: Annotated[float, Field(ge=0, le=10), NotTiny(1e-6)] = 0.0
    efficiency: Annotated[float, Field(ge=0.1, le=1)] = 1.0
    mesh: Annotated[ContactOverride | None, IfGiven("stage.mesh")] = None
    basic_rack: BasicRack = BasicRack.model_construct()  # the defaults, valid: no validator built at import
    shaft: Annotated[ShaftSpring | None, IfGiven("stage.shaft")] = None
    accuracy_grade: Annotated[int, Field(ge=1, le=12)] | None = None
    tip_relief_um: Annotated[float, Field(ge=0, le=1000)] | None = None
    model_config = ConfigDict(json_schema_extra=_members_rule())

    @model_validator(mode="after")
    def _members(self) -> "PlanetaryStage":
        if self.input == self.fixed:  # name the key the file gave (both given: the driven member)
            key = "fixed" if "input" not in self.model_fields_set else "input"
            raise KeyedValueError(key, f"input and fixed name the same member ({self.input!r}): the held member "
                                  "cannot be driven; name two different members of sun, carrier, ring")
        errors = self.planet.position_error_um
        if errors is not None and len(errors) != self.planet.count:
            raise KeyedValueError("planet.position_error_um", "planet.position_error_um needs one value per planet "
                                  f"({self.planet.count}), got {len(errors)}")
        if self.ring.teeth <= self.sun.teeth + 2 * self.planet.teeth - 3:
            raise KeyedValueError("ring.teeth", f"ring.teeth ({self.ring.teeth}) must be about sun.teeth + 2 "
                                  f"planet.teeth ({self.sun.teeth + 2 * self.planet.teeth}): the planets must fit "
                                  "between sun and ring")
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


#: the stage kinds a validator being built holds (None: every registered kind), :func:`only_kinds`
_ONLY: ContextVar[frozenset[str] | None] = ContextVar("gearcli_stage_kinds", default=None)


@contextmanager
def only_kinds(used: frozenset[str] | None) -> Iterator[None]:
    """Within: a validator built of the design file holds the tables of the stage kinds ``used`` only (None: every
    kind; :func:`gearcli.config.schema.validate_design`); the class's own validator and JSON Schema hold every kind."""
    token = _ONLY.set(used)
    try:
        yield
    finally:
        _ONLY.reset(token)


def kinds_named(data: dict) -> frozenset[str] | None:
    """The stage kinds the stage tables of ``data`` (a design file, parsed) name when each is a registered kind and
    they are not all of them, else None (a validator with every kind: it names them all in an unknown one's error)."""
    stages = data.get("stage")
    if not isinstance(stages, list):
        return None
    used = frozenset(_stage_tag(s) for s in stages)
    registered = set(kinds.kinds("table"))
    if not used:  # `stage = []`: no kind named, and a union of none is no validator (its error is the list's length)
        return frozenset((kinds.PARALLEL,))
    return used if used < registered else None


class _RegisteredStages:
    """A stage table validates as the table of its kind: one union of every registered kind's table, tagged by
    ``type`` (:mod:`gearcli.stages.kinds`; a kind registered later, :func:`register_stage_table`, rebuilds it), or
    of the kinds :func:`only_kinds` names (a stage's validation and its errors are those of its kind's table
    either way)."""

    def __get_pydantic_core_schema__(self, source: Any, handler: GetCoreSchemaHandler) -> core_schema.CoreSchema:
        only = _ONLY.get()
        choices = {k: handler.generate_schema(Annotated[cast(type, kinds.facet(k, "table")), Tag(k)])
                   for k in kinds.kinds("table") if only is None or k in only}
        return core_schema.tagged_union_schema(choices, discriminator=_stage_tag)


kinds.provide(kinds.PARALLEL, "table", Stage)
kinds.provide("planetary", "table", PlanetaryStage)

#: a stage table; statically the built-in kinds' (a plug-in kind's table validates at run time)
AnyStage = Annotated[Stage | PlanetaryStage, _RegisteredStages()]
