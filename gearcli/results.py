"""Frozen result objects of the design: ``DesignResult`` and its stages, gears, static forces, mesh stiffness,
ratings, shafts; a planetary stage's members and meshes and the bearings are in :mod:`gearcli.optional_results`
(re-exported here by name). What ``simulate`` produces
(``SimulationResult``, ``StageDynamics``, ``ChannelStats``, ``SolverStats`` ...) is in
:mod:`gearcli.simulate.results`.

Field names carry their units, as the JSON output does (docs/output.md). Stage and shaft
indices in these objects are 1-based, as an engineer numbers them (stage 1 is the input stage).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Protocol

from gearcli.core.jsontypes import JsonObject
from gearcli.core.records import record

if TYPE_CHECKING:
    from gearcli.diagnostics import Diagnostic
    from gearcli.optional_results import BearingResult, PlanetaryResult

#: the result types of a planetary stage and of bearings (:mod:`gearcli.optional_results`), imported on first use
OPTIONAL = ("BearingResult", "CarrierResult", "InternalMeshResult", "PlanetaryResult")


# ----------------------------------------------------------------------------------------- design
@record
class StaticForces:
    """Static tooth forces on the pinion pitch circle, N (signed: negative under load reversal)."""

    tangential: float
    radial: float
    axial: float
    normal: float


@record
class GearResult:
    """One member of a gear pair: its geometry, speed, torque and inertia (``design``'s ``pinion``/``gear``)."""

    teeth: int
    hand: str  # "left" | "right" | "spur"
    profile_shift: float
    face_width_mm: float
    pitch_diameter_mm: float
    base_diameter_mm: float
    tip_diameter_mm: float
    root_diameter_mm: float
    speed_deg_s: float
    speed_rpm: float
    torque_Nmm: float
    inertia_kg_m2: float
    inertia_given: bool  # True when the design file gave inertia_kg_m2
    # ISO 6336-1 gear body; additive fields (issue 10), defaults for hand-made results
    body_inertia_kg_m2: float = 0.0  # pi rho b (d_m^4 - d_bore^4)/32, or the given inertia: enters m_red
    bore_diameter_mm: float | None = None
    gear_blank_factor: float = 1.0  # C_R of this member (1 for a solid disc)
    torque_Nm: float = 0.0
    power_kW: float = 0.0  # torque x speed: positive when the power flows from pinion to gear
    # tooth-thickness allowances (ISO 21771; None without allowance keys): [upper, lower] limits
    generating_profile_shift: tuple[float, float] | None = None  # [x_E,e, x_E,i]
    manufactured_root_diameter_mm: tuple[float, float] | None = None  # [d_f,e, d_f,i], cut at x_E


@record
class Iso6336Factors:
    """The correction factors of c' = c'_th C_M C_R C_B cos beta (ISO 6336-1, clause 9)."""

    C_M: float = 0.8
    C_R: float = 1.0
    C_B: float = 0.975


class RatedMember(Protocol):
    """One member of a rated mesh, whatever the standard (``gearcli.rating``): its load cycles, and per failure mode
    ("pitting", "bending") its safety and its stress at the rating's operating point."""

    @property
    def load_cycles(self) -> float: ...

    def safety(self, mode: str) -> float: ...

    def stress_MPa(self, mode: str) -> float: ...


class RatedMesh(Protocol):
    """A mesh rated by a standard (``gearcli.rating``; ISO 6336's: ``gearcli.design.rating_results``): its title
    (JSON ``standard``), its dynamic factor and where it came from, its members (``pinion`` driving, ``gear``
    driven), and its factor table by the standard's names. Its JSON is its dataclass fields."""

    @property
    def standard(self) -> str: ...

    @property
    def K_v(self) -> float: ...

    @property
    def K_v_source(self) -> str: ...

    @property
    def pinion(self) -> RatedMember: ...

    @property
    def gear(self) -> RatedMember: ...

    def factor_table(self) -> Mapping[str, float | str]: ...


@record
class StageResult:
    """One stage's design results: ratio, geometry, contact ratios, stiffness and static forces."""

    index: int  # 1-based
    ratio: float
    efficiency: float
    normal_module_mm: float
    transverse_module_mm: float
    normal_pressure_angle_deg: float
    transverse_pressure_angle_deg: float
    working_pressure_angle_deg: float  # transverse, at the working centre distance
    helix_angle_deg: float
    base_helix_angle_deg: float
    center_distance_mm: float  # working centre distance (= reference one when x1 + x2 = 0)
    transverse_base_pitch_mm: float  # p_bt = pi m_t cos(alpha_t)
    face_width_mm: float  # the smaller of the two: the contact width b
    contact_ratio_transverse: float
    overlap_ratio: float
    contact_ratio_total: float
    mesh_frequency_Hz: float
    equivalent_radius_mm: float
    effective_modulus_MPa: float
    hertz_stiffness_N_mm1_5: float  # K = 4/3 sqrt(R) E*, for exponent 1.5
    static_approach_mm: float  # h_0 = (|F_n| / K)^(1/e) with the stage's contact law
    linearised_stiffness_N_mm: float  # k_lin = e K h_0^(e-1)
    static_force_N: StaticForces
    iso6336_single_pair_stiffness_N_mm_um: float  # c'
    iso6336_mesh_stiffness_N_mm_um: float  # c_gamma_alpha
    backlash_mm: float
    pinion: GearResult
    gear: GearResult
    # ISO 21771 / ISO 6336-1 completeness (issue 10): additive, with defaults for hand-made results
    tip_alteration_coefficient: float = 0.0  # k; tips shortened by k m_n (k <= 0)
    iso6336_mesh_stiffness_beta_N_mm_um: float = 0.0  # c_gamma_beta = 0.85 c_gamma_alpha
    iso6336_factors: Iso6336Factors = Iso6336Factors()  # immutable: one shared default
    reduced_mass_kg_mm: float = 0.0  # m_red per mm of face width, smaller wheel = 1
    resonance_speed_rpm: float = 0.0  # n_E1 of the smaller wheel
    resonance_ratio: float = 0.0  # N = n_smaller_wheel / n_E1
    resonance_lower_limit: float = 0.85  # N_S
    resonance_range: str = ""  # "subcritical" | "main resonance" | "intermediate" | "supercritical"
    rating: RatedMesh | None = None  # by the [rating] standard (ISO 6336-2/-3 by default); None without [rating]
    planetary: PlanetaryResult | None = None  # a planetary stage: this result is its sun–planet mesh
    # manufacturing allowances (ISO 21771; None without allowance keys)
    backlash_circumferential_mm: tuple[float, float] | None = None  # [max, min] on the working pitch circle
    backlash_normal_mm: tuple[float, float] | None = None  # [max, min] between the idle flanks
    contact_ratio_transverse_with_allowances: tuple[float, float, float] | None = None  # [e, m, i]
    mesh_stiffness: MeshStiffness | None = None  # the contact law at the static load beside ISO's (DESIGN 13)
    type: str = "parallel"  # the stage kind (the design file's stage ``type``; gearcli.stages); JSON: its own


@record
class ShaftResult:
    """A rigid shaft: shaft 1 carries pinion 1, shaft k+1 carries gear k and pinion k+1."""

    index: int  # 1-based
    speed_deg_s: float
    speed_rpm: float
    torque_Nmm: float  # torque the shaft transmits (input side of its pinion, or the load)
    inertia_kg_m2: float
    torque_Nm: float = 0.0
    power_kW: float = 0.0


# the bearing keys that appear only with their inputs (docs/bearings.md): ISO 76 with C_0, ISO 281 with C_u
BEARING_STATIC_KEYS = ("static_load_rating_kN", "static_equivalent_load_N", "static_safety", "static_safety_min")
BEARING_MODIFIED_KEYS = ("fatigue_load_limit_kN", "pitch_diameter_mm", "reliability_percent", "kappa", "a_ISO", "a_1",
                         "L_nm_Mrev", "L_nm_h", "kappa_points", "a_ISO_points")


def drop_absent_bearing_keys(doc: JsonObject) -> JsonObject:
    """A bearing's JSON without the ISO 76 keys when it has no C_0 and without ISO 281's modified life when it has
    no C_u (today's output for a file without them)."""
    if doc.get("static_load_rating_kN") is None:
        for k in BEARING_STATIC_KEYS:
            doc.pop(k, None)
    if doc.get("fatigue_load_limit_kN") is None:
        for k in BEARING_MODIFIED_KEYS:
            doc.pop(k, None)
    return doc


@record
class DesignResult:
    """The design calculations of a whole file (``gearcli design``'s document)."""

    title: str
    stages: tuple[StageResult, ...]
    shafts: tuple[ShaftResult, ...]
    total_ratio: float
    input_speed_deg_s: float
    output_speed_deg_s: float
    output_speed_rpm: float
    input_torque_Nmm: float
    output_torque_Nmm: float
    warnings: tuple[str, ...]
    input_power_kW: float = 0.0
    output_power_kW: float = 0.0
    bearings: tuple[BearingResult, ...] = ()  # with [[bearing]] tables only (docs/life.md)
    diagnostics: tuple[Diagnostic, ...] = ()  # the warnings' diagnostics (code, data); JSON writes these
    # the output units, the design file's key suffixes (speed, torque: io.units.key_units, set by the facade
    # gearcli.api); None: the contract's fixed keys only
    units: tuple[str, str] | None = None


@record
class MeshStiffness:
    """The contact law of one mesh: K in N/mm^e, its slope along the normal at the static load, and ISO 6336-1's
    normal mesh stiffness k_n = c_gamma_alpha b / cos^2 beta_b beside it (DESIGN section 13)."""

    law_N_mm_e: float  # K of F = K h^e, h in mm (the round-3 key; = K)
    exponent: float
    linearised_N_mm: float  # e K h0^(e-1) at the static approach h0 (K itself for e = 1)
    static_approach_mm: float
    law: str = ""  # "iso6336" | "hertz" | "given" (a number in the file); "" where not known
    K: float = 0.0  # = law_N_mm_e
    iso_N_mm: float = 0.0  # k_n = c_gamma_alpha b / cos^2 beta_b, N/mm (0 where not known)

    @property
    def departure(self) -> float | None:
        """linearised / ISO - 1 (None without an ISO value)."""
        return self.linearised_N_mm / self.iso_N_mm - 1.0 if self.iso_N_mm > 0.0 else None


def __getattr__(name: str) -> object:
    if name in OPTIONAL:
        from gearcli import optional_results  # lazy: a file without planetary stages or bearings never needs them

        return getattr(optional_results, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
