"""The design's result types of the parts a file may leave out: a planetary stage's members and ring mesh
(``StageResult.planetary``) and the ``[[bearing]]`` tables' reactions and lives (``DesignResult.bearings``).

They live apart from :mod:`gearcli.results`, which re-exports them by name (``from gearcli.results import
PlanetaryResult`` still works), so that a file without planetary stages or bearings does not create their
classes: a frozen dataclass costs about 40 us per field to create on Python 3.11, and these four hold 80 fields.
"""

from __future__ import annotations

from dataclasses import field
from typing import TYPE_CHECKING

from gearcli.core.records import record

if TYPE_CHECKING:
    from gearcli.results import GearResult, Iso6336Factors, MeshStiffness, RatedMesh, StaticForces


@record
class BearingResult:
    """One bearing's static reaction on its shaft (N; y, z radial components, axial along x) and its ISO 281
    basic rating life (None, JSON null, when the bearing carries no load or its shaft stands still)."""

    shaft: int  # 1-based
    position_mm: float
    radial_N: float
    radial_y_N: float
    radial_z_N: float
    axial_N: float
    equivalent_load_N: float
    L10_Mrev: float | None
    L10_h: float | None
    kind: str = "ball"
    locating: bool = False
    dynamic_load_rating_kN: float = 0.0
    speed_rpm: float = 0.0
    planet_stage: int | None = None  # a planet pin's bearing (shaft 0): its planetary stage, 1-based
    # ISO 76 static safety (with static_load_rating_kN) and ISO 281 modified life (with fatigue_load_limit_kN):
    # absent from JSON without their keys (docs/bearings.md)
    static_load_rating_kN: float | None = None
    static_equivalent_load_N: float | None = None  # P_0
    static_safety: float | None = None  # s_0 = C_0 / P_0
    fatigue_load_limit_kN: float | None = None
    pitch_diameter_mm: float | None = None
    reliability_percent: float | None = None
    kappa: float | None = None
    a_ISO: float | None = None
    a_1: float | None = None
    L_nm_Mrev: float | None = None
    L_nm_h: float | None = None


# ------------------------------------------------------------------------------ planetary stages (issue 25)
@record
class CarrierResult:
    """The planet carrier: its speed and torque, its own inertia and the planets' translational N m_p r_c²."""

    radius_mm: float  # r_c, the working centre distance of the sun–planet mesh
    speed_deg_s: float
    speed_rpm: float
    torque_Nmm: float
    torque_Nm: float
    power_kW: float
    own_inertia_kg_m2: float
    planets_translational_inertia_kg_m2: float
    inertia_kg_m2: float  # own + planets' translational


@record
class InternalMeshResult:
    """The planet–ring mesh of one planet (ISO 21771 internal gear geometry, ISO 6336-1 stiffness)."""

    working_pressure_angle_deg: float
    center_distance_mm: float
    transverse_base_pitch_mm: float
    face_width_mm: float
    contact_ratio_transverse: float
    overlap_ratio: float
    contact_ratio_total: float
    static_force_N: StaticForces  # per planet, on the planet's reference circle (= the sun mesh's F_t)
    equivalent_radius_mm: float  # r_p r_r / (r_r − r_p): a convex flank on a concave one
    effective_modulus_MPa: float  # E* of the planet's and the ring's materials (DESIGN 3, 11: a stage's keys)
    hertz_stiffness_N_mm1_5: float
    iso6336_single_pair_stiffness_N_mm_um: float
    iso6336_mesh_stiffness_N_mm_um: float
    iso6336_mesh_stiffness_beta_N_mm_um: float
    iso6336_factors: Iso6336Factors
    mesh_frequency_Hz: float
    rating: RatedMesh | None = None  # ISO 6336-2/-3 of the internal mesh (docs/iso6336.md)
    # ISO 6336-1 resonance of this mesh: m_red = the planet's m* (the ring taken infinitely heavy), n_E1 in
    # planet rpm relative to the carrier, N = n_p/n_E1, N_S (0 where not computed)
    reduced_mass_kg_mm: float = 0.0
    resonance_speed_rpm: float = 0.0
    resonance_ratio: float = 0.0
    resonance_lower_limit: float = 0.0
    resonance_range: str = ""  # "subcritical" | "main resonance" | "intermediate" | "supercritical"
    mesh_stiffness: MeshStiffness | None = None  # the contact law at the static load beside ISO's (DESIGN 13)
    # the law at the static load as a parallel stage states it (DESIGN 3: h_0 and k_lin; = mesh_stiffness's)
    static_approach_mm: float = 0.0
    linearised_stiffness_N_mm: float = 0.0
    # tooth-thickness allowances of the planet and the ring (ISO 21771; None without them), at the carrier's radius
    backlash_circumferential_mm: tuple[float, float] | None = None  # [max, min] on the working circles
    backlash_normal_mm: tuple[float, float] | None = None  # [max, min] between the idle flanks
    contact_ratio_transverse_with_allowances: tuple[float, float, float] | None = None  # [e, m, i]
    # the smallest tip clearances with allowances (planet tip on the ring's root, ring tip on the planet's root) for
    # the ``tip_clearance`` warning; not in the JSON (as a parallel stage's, only the warning carries them)
    tip_clearance_with_allowances_mm: tuple[float, float] | None = None
    # the planet's lowest involute point (its root form circle, cut by the stage's basic rack) from its base tangent
    # point along the line of action, max(q, 0), for the ``interference`` warning; not in the JSON (as above)
    planet_form_from_tangent_mm: float = 0.0


@record
class PlanetaryResult:
    """What a planetary stage adds to its sun–planet mesh: members, the ring mesh, assembly checks."""

    fixed: str
    input: str
    output: str
    planet_count: int
    ratio: float  # |ω_input / ω_output|
    willis_ratio: float  # i_0 = −z_r / z_s (carrier held)
    sun: GearResult  # absolute speeds; torque of the member (all planets)
    planet: GearResult  # speed relative to the carrier; torque per planet
    ring: GearResult
    carrier: CarrierResult
    planet_mass_kg: float
    planet_ring: InternalMeshResult
    load_sharing_factor: float  # K_gamma
    equal_spacing: bool  # the planets sit 360°/N apart (implied: (z_s + z_r)/N whole; or as declared)
    tip_clearance_between_planets_mm: float | None  # 2 a sin(Δψ/2) − d_a,planet (adjacency); None: one planet
    concentricity_mm: float  # a_w(planet–ring) − a_w(sun–planet)
    mesh_efficiency: float = 1.0  # η_m of every planet mesh (carrier frame), from the stage's efficiency
    basic_efficiency: float = 1.0  # η_0 = η_m², the stage's efficiency with the carrier held
    # signed external torques on sun, carrier, ring (positive in the input member's running sense), N·m: sum 0
    moment_balance_Nm: dict[str, float] = field(default_factory=dict)
    planet_angles_deg: tuple[float, ...] = ()  # each planet's position on the carrier
    ring_treatment: str | None = None  # the ring material's treatment (its tip thickness limit); not in the JSON
