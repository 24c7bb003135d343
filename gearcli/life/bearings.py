"""ISO 281 over the duty (docs/life.md, docs/bearings.md): per bearing the spectrum's equivalent load and basic
life L10; with its keys the modified life L_nm (per duty point a_ISO at the point's own load and speed,
combined by Palmgren–Miner as ISO 281 does for variable conditions) and the ISO 76 static safety at the
largest peak load of the duty points and their starts.

Starts: :func:`bearing_lives` takes, per duty point, the peak static equivalent loads of that point's start
(``start_peaks``; the ``starts`` work adds them from its start record) and counts them in the static safety.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from gearcli.design import iso281
from gearcli.design.bearing_life import duty_modified_life, lubrication, min_static_safety, static_warning
from gearcli.design.shafts import basic_life_Mrev, life_hours, spectrum_equivalent_load_N
from gearcli.life.result import BearingLife

if TYPE_CHECKING:
    from gearcli.life.run import _PointData


@dataclass(frozen=True)
class PointBearings:
    """What one duty point gives each bearing: the ISO 281 equivalent load of its (simulated) load and its
    peak ISO 76 static equivalent load P_0."""

    equivalent_N: tuple[float, ...]
    peak_static_N: tuple[float, ...]


def _modified(points: Sequence[_PointData], j: int, revs: Sequence[float]) -> dict:
    """The modified-life figures of bearing j over the duty (empty without C_u)."""
    b = points[0].design.bearings[j]
    cu_kN, d_m = b.fatigue_load_limit_kN, b.pitch_diameter_mm
    if cu_kN is None or d_m is None:
        return {}
    levels = []
    for pd, n in zip(points, revs, strict=True):
        lub = lubrication(pd.cfg)
        assert lub is not None  # design's check_inputs asked for it
        own = pd.design.bearings[j]
        p = pd.bearings.equivalent_N[j]
        l10 = basic_life_Mrev(own.dynamic_load_rating_kN * 1e3, p, own.kind)
        m = iso281.modified_life(l10, p, own.speed_rpm, own.kind, (own.fatigue_load_limit_kN or cu_kN) * 1e3,
                                 own.pitch_diameter_mm or d_m, own.reliability_percent or 90.0, lub)
        levels.append((n / 1e6, l10, m))
    l_nm, a_iso = duty_modified_life(levels)
    hours = sum(pd.point.hours for pd in points)
    mean_rpm = sum(revs) / (60.0 * hours) if hours else 0.0
    return {"fatigue_load_limit_kN": b.fatigue_load_limit_kN, "pitch_diameter_mm": b.pitch_diameter_mm,
            "reliability_percent": b.reliability_percent, "kappa": min(m.kappa for _, _, m in levels),
            "a_ISO": a_iso, "a_1": levels[0][2].a_1, "L_nm_Mrev": l_nm, "L_nm_h": life_hours(l_nm, mean_rpm),
            "kappa_points": tuple(m.kappa for _, _, m in levels), "a_ISO_points": tuple(m.a_ISO for _, _, m in levels)}


def _static(points: Sequence[_PointData], j: int, start_peaks: Sequence[Sequence[float]]) -> dict:
    """P_0 and s_0 of bearing j at the largest peak of the duty points and their starts (empty without C_0)."""
    b = points[0].design.bearings[j]
    if b.static_load_rating_kN is None:
        return {}
    peaks = [pd.bearings.peak_static_N[j] for pd in points] + [s[j] for s in start_peaks]
    p0, s0 = min_static_safety(b.static_load_rating_kN * 1e3, peaks)
    return {"static_load_rating_kN": b.static_load_rating_kN, "static_equivalent_load_N": p0, "static_safety": s0}


def bearing_lives(points: Sequence[_PointData], start_peaks: Sequence[Sequence[float]] = ()) -> tuple[BearingLife, ...]:
    """Every bearing over the duty ``points`` (the life run's evaluated points); ``start_peaks``: per start
    record, each bearing's peak static equivalent load P_0 (N) in that start."""
    base = points[0].design.bearings
    out = []
    for j, b in enumerate(base):
        revs = [pd.point.hours * 60.0 * abs(pd.design.bearings[j].speed_rpm) for pd in points]
        loads = [pd.bearings.equivalent_N[j] for pd in points]
        p_eq = spectrum_equivalent_load_N(loads, revs, b.kind)
        l10 = basic_life_Mrev(b.dynamic_load_rating_kN * 1e3, p_eq, b.kind)
        hours = sum(pd.point.hours for pd in points)
        mean_rpm = sum(revs) / (60.0 * hours) if hours else 0.0
        out.append(BearingLife(b.shaft, b.position_mm, b.kind, b.dynamic_load_rating_kN, p_eq, sum(revs), l10,
                               life_hours(l10, mean_rpm), tuple(loads), b.planet_stage or 0,
                               **_static(points, j, start_peaks), **_modified(points, j, revs)))
    return tuple(out)


def bearing_warnings(points: Sequence[_PointData], lives: Sequence[BearingLife]) -> list[str]:
    """s_0 below the minimum over the duty (and its starts)."""
    cfg = points[0].cfg
    found = [static_warning(cfg, j, b.kind, b.static_safety, "at the largest peak load over the duty")
             for j, b in enumerate(lives)]
    return [d.message for d in found if d is not None]
