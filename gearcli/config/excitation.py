"""Design-file tables and rules of the mesh excitation (docs/elements.md "Excitation"): harmonic lists of the
transmission error and the stiffness, the viscous damping ratio, the input torque ripple and the load
fluctuation. :mod:`gearcli.config.schema` puts them into ``[contact]``, ``[stage.mesh]``, ``[input]`` and
``[load]``.
"""


from typing import Annotated

from pydantic import Field, ValidationInfo

from gearcli.config.bounds_types import STRICT, NotTiny, StrictTable

__all__ = ["STRICT"]  # re-exported: the tables' config, defined with their base class

# Mesh excitation (harmonics j = 1, 2, ... of the mesh phase z_p theta_p): at most MAX_HARMONICS of each
# kind (gearcli.model.elements.N_HARM; a test keeps the two equal).
MAX_HARMONICS = 8
TransmissionErrorUm = Annotated[float, Field(ge=-1000.0, le=1000.0), NotTiny(1e-6)]  # um: ground gears ~1, rough ones ~50
PhaseDeg = Annotated[float, Field(ge=-360.0, le=360.0)]
StiffnessHarmonic = Annotated[float, Field(gt=-1.0, lt=1.0), NotTiny(1e-9)]  # fraction of K; sum of |s_j| below 1
DampingRatio = Annotated[float, Field(ge=0.0, le=10.0), NotTiny(1e-9)]  # gear meshes: 0.03 .. 0.17 (Kahraman & Singh)
_HARMONIC_KEYS = (("transmission_error_um", "transmission_error_phase_deg"),
                  ("stiffness_harmonics", "stiffness_harmonics_phase_deg"))


def check_harmonics(law, where: str, own: frozenset[str] | set[str] | None = None) -> None:
    """Phases no more than amplitudes (ValueError naming the key); ``where`` prefixes the key path. ``own``: the keys
    the table at ``where`` gives itself (a stage's ``[stage.mesh]``), the others named as inherited from
    ``[contact]``."""
    def named(key: str) -> str:
        return key if own is None or key in own else f"{key} (inherited from [contact])"

    for amp, phase in _HARMONIC_KEYS:
        a, p = getattr(law, amp), getattr(law, phase)
        if p is not None and len(p) > len(a or []):
            raise ValueError(f"{where}{named(phase)} has {len(p)} entries for {len(a or [])} harmonics "
                             f"({named(amp)}): give at most one phase per harmonic")


def phases_fit(v: list[float] | None, info: ValidationInfo) -> list[float] | None:
    """Field validator of a phase list: no more phases than the amplitudes given before it."""
    amp = {p: a for a, p in _HARMONIC_KEYS}[str(info.field_name)]
    a = info.data.get(amp)
    if v is not None and a is not None and len(v) > len(a):
        raise ValueError(f"{len(v)} phases for {len(a)} harmonics ({amp}): give at most one phase per harmonic")
    return v


def keeps_k_positive(v: list[float] | None) -> list[float] | None:
    """Field validator of stiffness harmonics: sum |s_j| < 1 keeps K (1 - sum s_j cos(...)) positive."""
    if v is not None and sum(abs(x) for x in v) >= 1.0:
        raise ValueError(f"the sum of |s_j| is {sum(abs(x) for x in v):g}, it must stay below 1 so that the mesh "
                         "stiffness K (1 - sum s_j cos(j phi + psi_j)) stays positive")
    return v



class _Table(StrictTable):
    pass


class Ripple(_Table):
    """One harmonic of the input torque: T_in (1 + amplitude_percent / 100 cos(order theta_in))."""

    amplitude_percent: Annotated[float, Field(ge=0.0, le=100.0), NotTiny(1e-6)]
    order: Annotated[float, Field(ge=1e-3, le=1000.0)]  # per input revolution (a 4-pole motor's slot
    # order ~36); at least 1e-3: a subnormal order overflowed the ripple's period (fuzz finding)


class Fluctuation(_Table):
    """One harmonic of the load torque: T_L (1 + amplitude_percent / 100 sin(2 pi frequency_Hz t))."""

    amplitude_percent: Annotated[float, Field(ge=0.0, le=100.0), NotTiny(1e-6)]
    frequency_Hz: Annotated[float, Field(ge=1e-3, le=1e5)]
