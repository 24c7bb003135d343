"""The design file's member tables: a material, a gear (of a pair, of a planetary stage: sun, planet, ring), the
basic rack, the planet carrier."""

from typing import Annotated, Literal

from pydantic import Field, field_validator, model_validator
from pydantic.json_schema import SkipJsonSchema

from gearcli.config.bounds_types import NotTiny
from gearcli.config.duty import AxialPositionMm
from gearcli.config.schema_rules import AllowancePair, BodyInertia, _Table, _upper_not_below_lower


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
    """One gear of an external pair: a parallel stage's pinion (driving) or gear (driven), a planetary stage's
    sun or planet."""

    # tooth thickness allowances [A_sne, A_sni] (normal section, mm) and tip diameter allowances [A_dae, A_dai]:
    # generating profile shifts, manufactured root diameters, backlash and contact ratio with allowances
    # (docs/iso6336.md, "Tooth-thickness allowances"); a planetary stage's sun–planet mesh (docs/planetary.md)
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


class Sun(PairGear):
    """The sun of a planetary stage (its allowances act on the sun–planet mesh)."""


class Planet(PairGear):
    """The planets of a planetary stage: one gear description and how many there are."""

    count: Annotated[int, Field(ge=1, le=20)]
    mass_kg: Annotated[float, Field(ge=1e-6, le=1e6)] | None = None  # else from geometry (the inertia's body)
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
    # tooth thickness allowances [A_sne, A_sni] (normal section, mm; negative: thinner teeth, ISO 21771's signs, as
    # on an external gear): the ring's generating profile shift and root, the planet–ring backlash (docs/planetary.md,
    # "Tooth-thickness allowances")
    tooth_thickness_allowance_mm: AllowancePair | None = None
    # the tip allowance of an internal gear is not modelled: named here (not in the schema) to refuse it with the
    # reason
    tip_diameter_allowance_mm: SkipJsonSchema[AllowancePair | None] = None
    # an internal gear has no bore: named here (not in the schema) to refuse it with the reason (it was ignored)
    bore_diameter_mm: SkipJsonSchema[float | None] = None

    @field_validator("tip_diameter_allowance_mm")
    @classmethod
    def _no_internal_tip_allowance(cls, value: list[float] | None) -> None:
        if value is not None:
            raise ValueError("the ring (an internal gear) takes no tip diameter allowance yet: the planet–ring contact "
                             "ratio with allowances uses its nominal tip; give the ring's tooth_thickness_allowance_mm "
                             "and the planets' tip allowances (docs/planetary.md, \"Tooth-thickness allowances\")")
        return None

    @model_validator(mode="after")
    def _web_needs_rim(self) -> "Ring":
        # an internal gear is a rim: its rim_thickness_mm alone sets its Y_B (ISO 6336-3) and its inertia (an annulus
        # outside the root), with the solid blank's C_R; a web needs the rim it carries
        if self.web_thickness_mm is not None and self.rim_thickness_mm is None:
            raise ValueError("the ring's web_thickness_mm needs its rim_thickness_mm (the rim outside the root "
                             "the web carries; a rim alone is a ring without a web)")
        return self

    @model_validator(mode="after")
    def _allowance_order(self) -> "Ring":
        _upper_not_below_lower("tooth_thickness_allowance_mm", self.tooth_thickness_allowance_mm)
        return self

    @field_validator("bore_diameter_mm")
    @classmethod
    def _no_bore(cls, value: float | None) -> None:
        if value is not None:
            raise ValueError("the ring (an internal gear) has no bore: its teeth are inside, its body the rim "
                             "outside the root; give rim_thickness_mm (a web with web_thickness_mm) or inertia_kg_m2")
        return None


class Carrier(_Table):
    """The planet carrier's own body (the planets' translational inertia N m_p r_c² is added to it)."""

    inertia_kg_m2: BodyInertia | None = None  # absent: 0 of its own
