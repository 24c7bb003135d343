"""``[contact]`` and ``[stage.mesh]``: the mesh force law, its damping and its excitation (DESIGN sections 2, 6, 13;
docs/physics.md, "The default mesh law"). :mod:`gearcli.config.schema` puts them into the design file.
"""


from typing import Annotated, Literal

from pydantic import Field, field_validator, model_validator

from gearcli.config.bounds_types import NotTiny, StrictTable
from gearcli.config.excitation import (
    MAX_HARMONICS,
    DampingRatio,
    PhaseDeg,
    StiffnessHarmonic,
    TransmissionErrorUm,
    keeps_k_positive,
    phases_fit,
)

Stiffness = Annotated[float, Field(ge=1.0, le=1e14)]  # N/mm^e: linear meshes ~1e6 N/mm, Hertz K ~1e5 N/mm^1.5
DampingNsmm = Annotated[float, Field(ge=0, le=1e6), NotTiny(1e-9)]
DampingDepthMm = Annotated[float, Field(ge=1e-6, le=10.0)]


class _Table(StrictTable):
    pass


class ContactOverride(_Table):
    """The mesh force law and its excitation. In ``[contact]`` every key has its default (the law calibrated to
    ISO 6336-1: ``stiffness = "iso6336"``, ``exponent = 1.5``, ``damping_ratio = 0.05``); in a stage's
    ``[stage.mesh]`` every key is optional and overrides ``[contact]`` for that mesh (an IMPACT damping key there
    makes that mesh IMPACT-damped unless a ``damping_ratio`` applies).
    Excitation (harmonics j = 1, 2, ... of the mesh phase phi = z_p theta_p): the static transmission error
    e(phi) = sum e_j cos(j phi + psi_j) (um, along the transverse line of action; the mesh acts on
    q = delta - e), stiffness harmonics K (1 - sum s_j cos(j phi + psi_j)), phases in degrees (default 0);
    ``damping_ratio`` zeta replaces the IMPACT damping by viscous damping c = 2 zeta sqrt(k_lin m_e) on
    q' at all times, also inside the backlash."""

    stiffness: Literal["hertz", "iso6336"] | Stiffness | None = None
    exponent: Annotated[float, Field(ge=1.0, le=3.0)] | None = None
    damping_Ns_mm: DampingNsmm | None = None
    full_damping_penetration_mm: DampingDepthMm | None = None
    time_varying: bool | None = None
    transmission_error_um: Annotated[list[TransmissionErrorUm], Field(max_length=MAX_HARMONICS)] | None = None
    transmission_error_phase_deg: Annotated[list[PhaseDeg], Field(max_length=MAX_HARMONICS)] | None = None
    stiffness_harmonics: Annotated[list[StiffnessHarmonic], Field(max_length=MAX_HARMONICS)] | None = None
    stiffness_harmonics_phase_deg: Annotated[list[PhaseDeg], Field(max_length=MAX_HARMONICS)] | None = None
    damping_ratio: DampingRatio | None = None

    _phases = field_validator("transmission_error_phase_deg", "stiffness_harmonics_phase_deg")(phases_fit)
    _k_positive = field_validator("stiffness_harmonics")(keeps_k_positive)


#: the IMPACT damping's keys: a law that gives one of them (and no ``damping_ratio``) is damped by the IMPACT ramp
IMPACT_KEYS = ("damping_Ns_mm", "full_damping_penetration_mm")
DEFAULT_DAMPING_RATIO = 0.05  # viscous, on the dynamic transmission error (gear meshes: 0.03 .. 0.17)


class Contact(_Table):
    """The mesh force law F = K h^exponent along the line of action, its damping and its excitation; see
    ``[stage.mesh]``. Omitted, or for omitted keys: the law calibrated to ISO 6336-1 at the operating point:
    ``stiffness = "iso6336"`` chooses K so that the law's tangent e K h0^(e-1) at the run's static normal load
    equals ISO's mesh stiffness k_n = c_gamma_alpha b / cos^2 beta_b (ISO 6336-1, method B; every duty and sweep
    point at its own load), ``exponent = 1.5`` (a Hertzian spring; the static deflection is then e times ISO's
    F/k_n, the linearised stiffness ISO's), and viscous ``damping_ratio = 0.05`` on the dynamic transmission error.
    ``stiffness = "hertz"`` is the seed's point-contact K = 4/3 sqrt(R) E*, or give K in N/mm^exponent. The seed's
    MSC Adams IMPACT damping (a STEP ramp of ``damping_Ns_mm`` reached at ``full_damping_penetration_mm``; 50 N s/mm
    and 0.1 mm when only the other is given) applies where a file gives one of its keys and no ``damping_ratio``:
    the seed reducer's law is ``stiffness = "hertz"``, ``exponent = 1.5`` with both."""

    stiffness: Literal["hertz", "iso6336"] | Stiffness = "iso6336"
    exponent: Annotated[float, Field(ge=1.0, le=3.0)] = 1.5
    damping_Ns_mm: DampingNsmm = 50.0
    full_damping_penetration_mm: DampingDepthMm = 0.1
    time_varying: bool = False
    transmission_error_um: Annotated[list[TransmissionErrorUm], Field(max_length=MAX_HARMONICS)] = []
    transmission_error_phase_deg: Annotated[list[PhaseDeg], Field(max_length=MAX_HARMONICS)] = []
    stiffness_harmonics: Annotated[list[StiffnessHarmonic], Field(max_length=MAX_HARMONICS)] = []
    stiffness_harmonics_phase_deg: Annotated[list[PhaseDeg], Field(max_length=MAX_HARMONICS)] = []
    damping_ratio: DampingRatio | None = DEFAULT_DAMPING_RATIO  # None: the IMPACT ramp (module text above)

    _phases = field_validator("transmission_error_phase_deg", "stiffness_harmonics_phase_deg")(phases_fit)
    _k_positive = field_validator("stiffness_harmonics")(keeps_k_positive)

    @model_validator(mode="after")
    def _damping_law(self) -> "Contact":
        """An IMPACT key given without a ``damping_ratio`` asks for the IMPACT damping: no default ratio then."""
        given = self.model_fields_set
        if "damping_ratio" not in given and any(k in given for k in IMPACT_KEYS):
            object.__setattr__(self, "damping_ratio", None)
        return self

    @property
    def impact_damping(self) -> bool:
        """The mesh is damped by the IMPACT ramp (else viscously, by ``damping_ratio``)."""
        return self.damping_ratio is None

    def ignored_impact_keys(self, override: ContactOverride | None = None) -> tuple[dict[str, float], str | None]:
        """The IMPACT keys given for a mesh that have no effect, with their values, and where the ``damping_ratio``
        that replaces them by viscous damping was given (``"[contact]"`` or ``"[stage.mesh]"``; None: none is
        ignored). Without ``override``: ``[contact]``'s own keys beside its ``damping_ratio``; with it: the stage's
        ``[stage.mesh]`` keys beside a ``damping_ratio`` there or in ``[contact]``."""
        given = self.model_fields_set
        if override is None:
            keys = {k: getattr(self, k) for k in IMPACT_KEYS if k in given}
            return (keys, "[contact]") if keys and "damping_ratio" in given else ({}, None)
        keys = {k: getattr(override, k) for k in IMPACT_KEYS if getattr(override, k) is not None}
        where = "[stage.mesh]" if override.damping_ratio is not None else "[contact]" if "damping_ratio" in given \
            else None
        return (keys, where) if keys and where else ({}, None)

    def merged(self, override: ContactOverride | None) -> "Contact":
        """This law with a stage's overrides applied (an override's IMPACT key turns the default viscous damping
        into the IMPACT ramp, as in ``[contact]``)."""
        if override is None:
            return self
        changes = {k: v for k, v in override.model_dump().items() if v is not None}
        given = self.model_fields_set | set(changes)
        if "damping_ratio" not in given and any(k in given for k in IMPACT_KEYS):
            changes["damping_ratio"] = None
        return self.model_copy(update=changes)
