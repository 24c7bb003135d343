"""ISO 281 over the duty (docs/life.md, docs/bearings.md): per bearing the spectrum's equivalent load and basic
life L10; with its keys the modified life L_nm (per load level a_ISO at the level's own load and speed,
combined by Palmgren–Miner as ISO 281 does for variable conditions) and the ISO 76 static safety at the
largest peak load of the duty points and their starts.

Starts: :func:`bearing_lives` takes the duty points' start records as :class:`StartBearings` (per bearing the
revolutions of all the point's starts, their ISO 281 equivalent load, the bearing's mean speed during a start
and the start's peak static equivalent load P_0): their revolutions count in L10 and L_nm as load levels of
their own, their peaks in s_0. ``gearcli.life.run.start_bearings`` makes them from the evaluated points' start records.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

from gearcli.core.records import record
from gearcli.design import iso281
from gearcli.design.bearing_life import (
    AXIAL_NOT_RATED,
    KAPPA_OUT_OF_RANGE,
    axial_warning,
    duty_modified_life,
    kappa_warning,
    lubrication,
    min_static_safety,
    static_warning,
)
from gearcli.design.shafts import basic_life_Mrev, life_hours, spectrum_equivalent_load_N
from gearcli.life.result import BearingLife

if TYPE_CHECKING:
    from gearcli.diagnostics import Diagnostic
    from gearcli.life.run import _PointData


@record
class PointBearings:
    """What one duty point gives each bearing: the ISO 281 equivalent load of its (simulated) load and its
    peak ISO 76 static equivalent load P_0."""

    equivalent_N: tuple[float, ...]
    peak_static_N: tuple[float, ...]


@record
class StartBearings:
    """What the starts of one duty point give each bearing (from the point's start record)."""

    point: int  # index of the duty point in the evaluated points
    revolutions: tuple[float, ...]  # over all the point's starts
    equivalent_N: tuple[float, ...]  # ISO 281 equivalent load over a start's revolutions
    speed_rpm: tuple[float, ...]  # the bearing's mean speed during a start (kappa of the level)
    peak_static_N: tuple[float, ...]  # the start's peak ISO 76 P_0


@record
class _Level:
    """One load level of a bearing: its revolutions, equivalent load and speed, and the point it belongs to."""

    revolutions: float
    load_N: float
    speed_rpm: float
    point: int


def _levels(points: Sequence[_PointData], starts: Sequence[StartBearings], j: int) -> list[_Level]:
    """Bearing j's load levels: the duty points', then their starts'."""
    out = [_Level(pd.point.hours * 60.0 * abs(pd.design.bearings[j].speed_rpm), pd.bearings.equivalent_N[j],
                  pd.design.bearings[j].speed_rpm, i) for i, pd in enumerate(points)]
    return out + [_Level(s.revolutions[j], s.equivalent_N[j], s.speed_rpm[j], s.point) for s in starts]


def _modified(points: Sequence[_PointData], j: int, levels: Sequence[_Level]) -> dict:
    """The modified-life figures of bearing j over the duty (empty without C_u)."""
    b = points[0].design.bearings[j]
    cu_kN, d_m = b.fatigue_load_limit_kN, b.pitch_diameter_mm
    if cu_kN is None or d_m is None:
        return {}
    rated = []
    for lv in levels:
        pd = points[lv.point]
        lub = lubrication(pd.cfg)
        assert lub is not None  # design's check_inputs asked for it
        own = pd.design.bearings[j]
        l10 = basic_life_Mrev(own.dynamic_load_rating_kN * 1e3, lv.load_N, own.kind)
        m = iso281.modified_life(l10, lv.load_N, lv.speed_rpm, own.kind, (own.fatigue_load_limit_kN or cu_kN) * 1e3,
                                 own.pitch_diameter_mm or d_m, own.reliability_percent or 90.0, lub)
        rated.append((lv.revolutions / 1e6, l10, m))
    l_nm, a_iso = duty_modified_life(rated)
    hours = sum(pd.point.hours for pd in points)
    mean_rpm = sum(lv.revolutions for lv in levels) / (60.0 * hours) if hours else 0.0
    own_points = rated[:len(points)]
    return {"fatigue_load_limit_kN": b.fatigue_load_limit_kN, "pitch_diameter_mm": b.pitch_diameter_mm,
            "reliability_percent": b.reliability_percent, "kappa": min(m.kappa for _, _, m in rated),
            "a_ISO": a_iso, "a_1": rated[0][2].a_1, "L_nm_Mrev": l_nm, "L_nm_h": life_hours(l_nm, mean_rpm),
            "kappa_points": tuple(m.kappa for _, _, m in own_points),
            "a_ISO_points": tuple(m.a_ISO for _, _, m in own_points)}


def _static(points: Sequence[_PointData], j: int, starts: Sequence[StartBearings],
            held: Sequence[tuple[float, ...]] = ()) -> dict:
    """P_0 and s_0 of bearing j at the largest peak of the duty points, their starts and the loads ``held`` at
    standstill (each a P_0 per bearing; empty without C_0)."""
    b = points[0].design.bearings[j]
    if b.static_load_rating_kN is None:
        return {}
    peaks = [pd.bearings.peak_static_N[j] for pd in points] + [s.peak_static_N[j] for s in starts]
    peaks += [h[j] for h in held]
    p0, s0 = min_static_safety(b.static_load_rating_kN * 1e3, peaks)
    return {"static_load_rating_kN": b.static_load_rating_kN, "static_equivalent_load_N": p0, "static_safety": s0,
            "static_safety_min": s0}


def bearing_lives(points: Sequence[_PointData], starts: Sequence[StartBearings] = (),
                  held: Sequence[tuple[float, ...]] = ()) -> tuple[BearingLife, ...]:
    """Every bearing over the duty ``points`` (the life run's evaluated points) and the points' ``starts``; the
    ``held`` loads (per held torque, each bearing's static equivalent load P_0) count in s_0 alone."""
    base = points[0].design.bearings
    out = []
    for j, b in enumerate(base):
        levels = _levels(points, starts, j)
        revs = [lv.revolutions for lv in levels]
        p_eq = spectrum_equivalent_load_N([lv.load_N for lv in levels], revs, b.kind)
        l10 = basic_life_Mrev(b.dynamic_load_rating_kN * 1e3, p_eq, b.kind)
        hours = sum(pd.point.hours for pd in points)
        mean_rpm = sum(revs) / (60.0 * hours) if hours else 0.0
        out.append(BearingLife(b.shaft, b.position_mm, b.kind, b.dynamic_load_rating_kN, p_eq, sum(revs), l10,
                               life_hours(l10, mean_rpm), tuple(pd.bearings.equivalent_N[j] for pd in points),
                               b.planet_stage or 0, **_static(points, j, starts, held), **_modified(points, j, levels)))
    return tuple(out)


def bearing_warnings(points: Sequence[_PointData], lives: Sequence[BearingLife],
                     said: Sequence[str] = ()) -> list[Diagnostic]:
    """s_0 below the minimum over the duty (and its starts); kappa below ISO 281's range at any of the duty's
    loaded levels (a point's, or its starts' at their slower mean speed), once per bearing naming the points (and
    the starts) below it; an axial force the equivalent loads ignore. A kappa or axial-force word the life output
    already carries for the same bearing (the base file's design warning: the lowest kappa is the base file's own
    and no other point falls below, the same F_a/F_r) is not said twice."""
    cfg = points[0].cfg
    found = [static_warning(cfg, j, b.kind, b.static_safety, "at the largest peak load over the duty")
             for j, b in enumerate(lives)]
    found += [_kappa_word(points, j, b) for j, b in enumerate(lives)]
    for j in range(len(lives)):  # an axial force without factors: the first point's word (its F_a/F_r is the train's)
        found.append(next((d for pd in points if (d := axial_warning(pd.cfg, j, pd.design.bearings[j])) is not None),
                          None))
    return [d for d in found if d is not None and not _said(d, said)]


def _kappa_word(points: Sequence[_PointData], j: int, b: BearingLife) -> Diagnostic | None:
    """Bearing j's kappa below ISO 281's range over the duty, said once: the lowest, and the duty points (those
    that load it: an unloaded level has no a_ISO) and starts below the range (data ``points``)."""
    if b.kappa is None or b.a_ISO is None or b.kappa_points is None or b.a_ISO_points is None:
        return None
    below = [pd.point.name for pd, k, a in zip(points, b.kappa_points, b.a_ISO_points, strict=True)
             if k < iso281.KAPPA_MIN and a is not None]
    starts = b.kappa < min(b.kappa_points)  # a start's slower mean speed set the lowest
    named = ", ".join(below) + (" and " if below and starts else "") + ("its starts" if starts else "")
    return kappa_warning(j, b.kappa, f" (the lowest over the duty; below 0.1 at {'duty point' if below else ''}"
                         f"{'s' if len(below) > 1 else ''}{' ' if below else ''}{named})", below)


def _said(d: Diagnostic, said: Sequence[str]) -> bool:
    """Whether the base file's design warnings (``said``) already carry ``d``'s word: the same F_a/F_r, or the
    same kappa (the lowest over the duty is the base file's own) with no other point below the range."""
    if d.code == AXIAL_NOT_RATED:
        return d.message in said
    if d.code == KAPPA_OUT_OF_RANGE:
        base = kappa_warning(int(d.data["bearing"]) - 1, float(d.data["kappa"]))  # type: ignore[arg-type]
        return base is not None and base.message in said and len(d.data["points"]) <= 1  # type: ignore[arg-type]
    return False
