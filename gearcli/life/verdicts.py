"""The verdicts of a life over its duty (docs/life.md, "Verdicts"): a member's spectrum safety below the file's
minimum (or its Miner damage reaching 1 within the duty, or its life shorter than [rating] required_life_h), a
bearing whose life is shorter than the duty it carries or the required life, and a duty whose hours are not the
required life the rating and the verdicts are meant for.

ISO 6336-6 compares the spectrum's safety with the minimum safety factors S_Hmin and S_Fmin of ISO 6336-2/-3
([rating] min_safety_pitting, min_safety_bending); the safety is the one that makes D = 1 over the duty's hours,
so it is the required life's only when the duty's hours are the required life.
"""

from __future__ import annotations

from collections.abc import Sequence

from gearcli.core.text import beside
from gearcli.design.bearing_life import life_short_warning
from gearcli.diagnostics import (
    DUTY,
    DYNAMIC_UNEXCITED,
    LIFE_SAFETY_LOW,
    STARTS_NOT_FROM_REST,
    Diagnostic,
    warning,
)
from gearcli.life.duty import DutyPoint
from gearcli.life.result import BearingLife, ModeLife, StageLife, member_label
from gearcli.life.starts import StartData

UNEXCITED_K_V = 1e-6  # classes spread by no more than this share of the largest: one force at every engagement
HOURS_TOLERANCE = 1e-3  # relative difference of the duty's hours from [rating] required_life_h without a warning
_MEMBERS = ("pinion", "gear", "ring", "planet_ring_side")
_SYMBOL = {"pitting": "S_H", "bending": "S_F"}


def hours_warning(hours: float, required_h: float | None, series: str | None = None) -> list[Diagnostic]:
    """A duty whose hours differ from [rating] required_life_h: its D and spectrum safety are over its own hours.
    ``series``: the history file the duty was classed from (its record's time is the duty's hours)."""
    if required_h is None or abs(hours - required_h) <= HOURS_TOLERANCE * required_h:
        return []
    what = f"the history {series} records {hours:.6g} h" if series else f"the duty's hours sum to {hours:.6g} h"
    fix = (f"scale its time_s column by {required_h / hours:.6g} (ISO 6336-6 Annex C scales its 70-day record to "
           "the 30-year life)" if series else "give each point its hours over the required life (ISO 6336-6 "
           "scales the spectrum to it)")
    return [warning(DUTY, f"{what}, not [rating] required_life_h = {required_h:.6g} h: the Miner damage D and the "
                    "spectrum safety (the load multiplier that makes D = 1) are over those "
                    f"{hours:.6g} h, the life in hours is not affected; {fix}, or set rating.required_life_h to "
                    "the duty's hours", hours=hours, required_life_h=required_h)]


def _short_of_required(life_h: float | None, required_h: float | None) -> bool:
    """A life shorter than [rating] required_life_h: the target the duty's hours stand for (a duty given in time
    shares sums to 1 h, its D to far below 1, while the life in hours is the same)."""
    return life_h is not None and required_h is not None and life_h < required_h


def _mode_warning(stage: int, member: str, mode: str, ml: ModeLife, minimum: float, hours: float,
                  label: str | None = None, required_h: float | None = None) -> Diagnostic | None:
    low = ml.stress_safety is not None and ml.stress_safety < minimum
    short = _short_of_required(ml.life_h, required_h)
    if not (low or ml.damage >= 1.0 or short):
        return None
    where = f"stage {stage} {label or member}" + (f" (planet {ml.planet})" if ml.planet is not None else "")
    life = "" if ml.life_h is None else f", a life of {ml.life_h:.4g} h"
    damage = f"Miner damage D = {ml.damage:.4g} over the duty's {hours:.6g} h{life}"
    safety = "" if ml.stress_safety is None else (
        f" (spectrum safety {_SYMBOL[mode]} = {ml.stress_safety:.4g} on stress, load multiplier {ml.safety:.4g}; "
        f"minimum {minimum:g})")
    if low and ml.stress_safety is not None:
        text = (f"spectrum safety {_SYMBOL[mode]} = {beside(ml.stress_safety, minimum, '.4g')} on stress (load multiplier {ml.safety:.4g}) "
                f"is below the minimum {minimum:g} ([rating] min_safety_{mode}); {damage}")
    elif ml.damage >= 1.0:
        text = f"{damage}: it fails within the duty{safety}"
    else:
        text = f"{damage}: shorter than the required {required_h:.6g} h ([rating] required_life_h){safety}"
    return warning(LIFE_SAFETY_LOW, f"{where} {mode}: {text}", stage=stage, member=member, mode=mode, stress_safety=ml.stress_safety,
                   load_multiplier=ml.safety, min_safety=minimum, damage=ml.damage, life_h=ml.life_h, hours=hours,
                   required_life_h=required_h)


def gear_warnings(stages: Sequence[StageLife], min_pitting: float, min_bending: float, hours: float,
                  required_h: float | None = None) -> list[Diagnostic]:
    """Every member and mode whose spectrum safety on stress is below the minimum, whose damage reaches 1 within the
    duty, or whose life is shorter than ``required_h`` ([rating] required_life_h)."""
    out: list[Diagnostic] = []
    for st in stages:
        for member in _MEMBERS:
            ml_pair = getattr(st, member, None)
            if ml_pair is None:
                continue
            for mode, minimum in (("pitting", min_pitting), ("bending", min_bending)):
                d = _mode_warning(st.index, member, mode, getattr(ml_pair, mode), minimum, hours, member_label(st, member),
                                  required_h)
                if d is not None:
                    out.append(d)
        if st.planet_root is not None:
            d = _mode_warning(st.index, "planet_root", "bending", st.planet_root, min_bending, hours,
                              member_label(st, "planet_root"), required_h)
            if d is not None:
                out.append(d)
    return out


def bearing_life_warnings(bearings: Sequence[BearingLife], hours: float,
                          required_h: float | None = None) -> list[Diagnostic]:
    """Every bearing whose life over the duty (L_nm where its catalogue data give it, else L10) is shorter than the
    duty's hours or than ``required_h`` ([rating] required_life_h)."""
    found = [life_short_warning(j, b, "over the duty", hours, required_h) for j, b in enumerate(bearings)]
    return [d for d in found if d is not None]


def starts_warning(point: DutyPoint, start: StartData | None) -> list[Diagnostic]:
    """A point whose starts, as counted (each from rest to its settled window), take longer than the point's hours:
    more starts than its hours can hold (a typo in ``starts`` or ``hours``); the damage counts them all."""
    if start is None or not start.count:
        return []
    each_s = start.span_s[1] - start.span_s[0]
    total_h = start.count * each_s / 3600.0
    if total_h <= point.hours:
        return []
    return [warning(DUTY, f"duty point {point.name} ({point.key}): its {start.count} starts of {each_s:.4g} s each (from "
                    f"rest to the settled window, as counted) take {total_h:.4g} h, more than the point's {point.hours:.6g} "
                    "h: check starts and hours (the damage counts every start and every hour)", point=point.name,
                    starts=start.count, start_s=each_s, starts_h=total_h, hours=point.hours)]


def starts_from_rest_warning(point: DutyPoint, drive: str, ramp_s: float) -> list[Diagnostic]:
    """A point with starts whose run does not start from rest (docs/life.md, "Starts"): a torque drive's run starts
    at its nominal speed, a speed drive without ``ramp_s`` at its full speed; what is counted ``starts`` times is then
    that run before the window, not a start-up from rest."""
    if not point.starts or drive == "motor" or (drive == "speed" and ramp_s > 0):
        return []
    how = ("a torque drive's run starts at its nominal speed" if drive == "torque" else
           "a speed drive without ramp_s starts at its full speed")
    return [warning(STARTS_NOT_FROM_REST, f"duty point {point.name} ({point.key}): starts = {point.starts}, but {how}, "
                    "not from rest: what is counted as its start is the run before the window at that speed, not a "
                    "start-up; give drive = \"motor\" with its starting method (or a speed drive's input.ramp_s > 0) to "
                    "count starts from rest", point=point.name, starts=point.starts, drive=drive)]


def unexcited_warning(points: Sequence[str]) -> list[Diagnostic]:
    """The dynamic route's duty ``points`` whose steady window met one force at every tooth engagement (the
    classes of every loaded stage within :data:`UNEXCITED_K_V`): the model has none of the excitation that ISO
    6336-1's K_v stands for, so their damage carries no dynamic increment, less than the static route's; said once,
    as the identical planets' K_gamma is (the dynamic spectrum stands for K_v only as far as the model excites)."""
    if not points:
        return []
    return [warning(DYNAMIC_UNEXCITED, f"duty point(s) {', '.join(points)}: every simulated tooth engagement met the "
                    "same force, the steady one (no dynamic increment: the model has no mesh excitation, "
                    "transmission_error_um, stiffness_harmonics or time_varying, nor torque ripple or load "
                    "fluctuation), so these points' damage is the rating's at K_v = 1, below the static route's with "
                    "ISO 6336-1's K_v (--static); give the meshes their excitation for a dynamic spectrum that stands "
                    "for K_v", points=list(points))]
