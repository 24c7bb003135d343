"""Diagnostics as data: what a computation noticed, with a stable code, a severity and its numbers.

Results carry a tuple of :class:`Diagnostic`; the report and the CLI decide by ``code`` (never by
matching message text). The JSON ``warnings`` list holds one object per warning (:func:`warning_objects`):
``code``, ``message`` and the diagnostic's data; tables, CSV and stderr print the messages.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import field
from typing import Literal, cast

from gearcli.core.jsontypes import JsonObject, JsonValue
from gearcli.core.records import record

Severity = Literal["info", "warning"]

# Codes (one place): simulation
ENERGY_RESIDUAL = "energy_residual"
RAMPS_OUTLAST_RUN = "ramps_outlast_run"
OUTPUT_STANDS_STILL = "output_stands_still"
PENETRATION_BEYOND_DAMPING = "penetration_beyond_damping"
PENETRATION_OVER_MODULE = "penetration_over_module"
CONTACT_LOSS = "contact_loss"
PEAK_OVER_RIGID = "peak_over_rigid"
MOTOR_STALLS = "motor_stalls"  # the motor's curve cannot carry the load at some speed below the operating point
RAMP_OVER_BREAKDOWN = "ramp_over_breakdown"  # a prescribed speed ramp needs more than the motor's breakdown torque
START_NOT_SETTLED = "start_not_settled"  # the motor start has not settled before the statistics window
MOTOR_ROLLS_BACK = "motor_rolls_back"  # the load turns the train backwards: the start's torque at standstill is short
MOTOR_RUNS_AWAY = "motor_runs_away"  # the motor turns well past its synchronous speed: nothing holds it
STAR_DELTA_RESWITCH = "star_delta_reswitch"  # a star-delta motor fell back below its switch band after switching
MOTOR_OVERLOADED = "motor_overloaded"  # the steady motor torque exceeds the nameplate's rated torque beyond the margin
STIFF_FOR_EXPLICIT = "stiff_for_explicit"
FORCE_NOISE = "force_noise"
RESONANCE = "resonance"
STIFFNESS_NOT_ISO = "stiffness_not_iso"  # a mesh law's linearised stiffness departs from ISO 6336-1's by > 25 %
ENGINE_FALLBACK = "engine_fallback"
SLOW_PACE = "slow_pace"  # a run far slower than auto's cost model predicted (or switched engine for it)
STATISTICS_UNRESOLVED = "statistics_unresolved"
STATISTICS_UNDERSAMPLED = "statistics_undersampled"  # the output samples miss the window's min/max between them
EXCITATION_UNDERSAMPLED = "excitation_undersampled"  # an excitation has too few output samples a period
WINDOW_PARTIAL_PERIOD = "window_partial_period"  # a partial period of the slowest excitation biases the mean
PEAK_UNDERSAMPLED = "peak_undersampled"  # the output samples miss the run's peak |F_t| (and run-up factor) between them
PEAK_UNRESOLVED = "peak_unresolved"  # the solver's error of the run's peak |F_t| (check pass) beyond the target
RTOL_TIGHTENED = "rtol_tightened"  # auto repeated a run at a tighter rtol to resolve its window means
DESIGN = "design"  # a warning of the design the simulation ran on
NOT_PERIODIC = "not_periodic"  # steady = "periodic": no repeat found up to the cap
SUBHARMONIC = "subharmonic"  # steady = "periodic": the response repeats after k > 1 periods
PERIOD_NOT_COMMON = "period_not_common"  # the excitations have no usable common period
WINDOW_RINGING = "window_ringing"  # a lightly damped mode still rings from the run-up through the window
WINDOW_NOT_SETTLED = "window_not_settled"  # a start-up transient left at the window's start (gearcli.simulate.settle)
SAMPLING = "sampling"  # report: a line above the Nyquist frequency of the output samples
ACCURACY = "accuracy"  # report: the accuracy study's verdict on the file's solver settings
NEAR_BIFURCATION = "near_bifurcation"  # steady = "periodic": a Floquet multiplier near +1 (fold, jump) or -1
SHOOTING_FALLBACK = "shooting_fallback"  # steady = "periodic": Newton on the period map failed; brute force
PERIODIC_NOT_ATTRACTING = "periodic_not_attracting"  # steady = "periodic": a state the motion never settles into
# life (gearcli life): about the duty, a point's run, the spectrum
DUTY = "duty"  # about the duty itself: a series' reverse rows, a load reversal
LOAD_SHARING = "load_sharing"  # how the dynamic route takes the planets' load sharing
DYNAMIC_UNEXCITED = "dynamic_unexcited"  # the dynamic route's window met one force at every engagement (K_v = 1)
MOTOR_SPEED_MISMATCH = "motor_speed_mismatch"  # the motor runs at another speed than the point's speed_rpm
PEAKS_UNRESOLVED = "peaks_unresolved"  # the mesh-cycle peaks are resolved worse than the target
STARTS_NOT_COUNTED = "starts_not_counted"  # --static: the duty's starts are counted on the dynamic route only
STARTS_NOT_FROM_REST = "starts_not_from_rest"  # starts on a drive whose run does not start from rest
BEYOND_STATIC_STRENGTH = "beyond_static_strength"  # load classes beyond the static strength (slope extrapolated)
LIFE_SAFETY_LOW = "life_safety_low"  # a member's spectrum safety below the minimum, or D >= 1 within the duty
BEARING_LIFE_SHORT = "bearing_life_short"  # a bearing's ISO 281 life (over the duty, or at the design load) shorter than required
OTHER = "other"


@record
class Diagnostic:
    """A warning as data: its stable ``code``, severity, message and the values it names."""

    code: str
    severity: Severity
    message: str
    data: JsonObject = field(default_factory=dict)


def warning(code: str, message: str, **data: JsonValue) -> Diagnostic:
    return Diagnostic(code, "warning", message, data)


def messages(diags: Iterable[Diagnostic]) -> tuple[str, ...]:
    """The message strings (the JSON ``warnings`` list)."""
    return tuple(d.message for d in diags)


def has(diags: Iterable[Diagnostic], code: str) -> bool:
    return any(d.code == code for d in diags)


#: JSON Schema of one entry of a JSON ``warnings`` list (docs/output.md, "Warnings")
WARNING_SCHEMA: JsonObject = {
    "type": "object",
    "required": ["code", "message"],
    "properties": {
        "code": {"type": "string", "pattern": "^[a-z][a-z0-9]*(_[a-z0-9]+)*$"},
        "message": {"type": "string"},
        "stage": {"anyOf": [{"type": "integer", "minimum": 1}, {"type": "null"}]},
        # a parallel stage's pinion/gear; a planetary stage's ring (its planet–ring mesh); life's members
        "member": {"enum": ["pinion", "gear", "sun", "planet", "ring", "planet_ring_side", "planet_root"]},
        # the statistics a warning is about, comma-separated ("mean, std, min, max, dynamic_factor"); a warning
        # that lists them (``statistics``: statistics_unresolved, statistics_undersampled) has both
        "statistic": {"type": "string"},
    },
}


def _json_value(v: object) -> JsonValue:
    """A data value as plain JSON: non-finite floats become null, numpy scalars and tuples plain."""
    if hasattr(v, "tolist"):
        v = v.tolist()
    if isinstance(v, float):
        return v if math.isfinite(v) else None
    if isinstance(v, (list, tuple)):
        return [_json_value(x) for x in v]
    if isinstance(v, dict):
        return {str(k): _json_value(x) for k, x in v.items()}
    return cast(JsonValue, v)  # str, int, bool or None


def as_dict(d: Diagnostic) -> JsonObject:
    """One JSON ``warnings`` entry: ``code``, ``message``, then the diagnostic's data; ``stage`` is in every entry,
    null for a warning about the train (one no stage's diagnostic carries: docs/output.md, "Warnings")."""
    data = {"stage": None, **{k: _json_value(v) for k, v in d.data.items() if k not in ("code", "message")}}
    named = data.get("statistics")
    if "statistic" not in data and isinstance(named, list):  # the contract's key beside the list (DESIGN §12)
        data["statistic"] = ", ".join(str(s) for s in named)
    return {"code": d.code, "message": d.message, **data}


def carrying(messages_: Iterable[str], diags: Iterable[Diagnostic] = ()) -> list[Diagnostic]:
    """One diagnostic per message, in the messages' order: the one that carries it (code ``other`` for a message
    no diagnostic carries)."""
    by_message: dict[str, Diagnostic] = {}
    for d in diags:
        by_message.setdefault(d.message, d)
    return [by_message.get(m) or Diagnostic(OTHER, "warning", m) for m in messages_]


def warning_objects(messages_: Iterable[str], diags: Iterable[Diagnostic] = ()) -> list[JsonObject]:
    """The JSON ``warnings`` list: one object per message, in the messages' order, from the diagnostic
    that carries it (code ``other`` for a message no diagnostic carries)."""
    return [as_dict(d) for d in carrying(messages_, diags)]
