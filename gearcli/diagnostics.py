"""Diagnostics as data: what a computation noticed, with a stable code, a severity and its numbers.

Results carry a tuple of :class:`Diagnostic`; the report and the CLI decide by ``code`` (never by
matching message text), and the JSON ``warnings`` list stays the messages for the output contract.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any, Literal

Severity = Literal["info", "warning"]

# Codes (one place): simulation
ENERGY_RESIDUAL = "energy_residual"
RAMPS_OUTLAST_RUN = "ramps_outlast_run"
OUTPUT_STANDS_STILL = "output_stands_still"
PENETRATION_BEYOND_DAMPING = "penetration_beyond_damping"
PENETRATION_OVER_MODULE = "penetration_over_module"
CONTACT_LOSS = "contact_loss"
PEAK_OVER_RIGID = "peak_over_rigid"
EFFICIENCY_NOT_MODELLED = "efficiency_not_modelled"
STIFF_FOR_EXPLICIT = "stiff_for_explicit"
FORCE_NOISE = "force_noise"
RESONANCE = "resonance"
ENGINE_FALLBACK = "engine_fallback"
SLOW_PACE = "slow_pace"  # a run far slower than auto's cost model predicted (or switched engine for it)
STATISTICS_UNRESOLVED = "statistics_unresolved"
DESIGN = "design"  # a warning of the design the simulation ran on
NOT_PERIODIC = "not_periodic"  # steady = "periodic": no repeat found up to the cap
SUBHARMONIC = "subharmonic"  # steady = "periodic": the response repeats after k > 1 periods
PERIOD_NOT_COMMON = "period_not_common"  # the excitations have no usable common period
OTHER = "other"


@dataclass(frozen=True)
class Diagnostic:
    code: str
    severity: Severity
    message: str
    data: dict[str, Any] = field(default_factory=dict)


def warning(code: str, message: str, **data: Any) -> Diagnostic:
    return Diagnostic(code, "warning", message, data)


def messages(diags: Iterable[Diagnostic]) -> tuple[str, ...]:
    """The message strings (the JSON ``warnings`` list)."""
    return tuple(d.message for d in diags)


def has(diags: Iterable[Diagnostic], code: str) -> bool:
    return any(d.code == code for d in diags)
