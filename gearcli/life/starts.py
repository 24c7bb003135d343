"""Starts counted as starts (docs/life.md, "Starts"): a duty point's ``starts = N`` start-ups from rest.

The point's simulation runs from rest with the file's starting method (a DOL motor's full curve, a star-delta
switch-over, a soft start, a VFD ramp, or a prescribed speed ramp) until its window is shown settled
(:mod:`gearcli.simulate.settle`); the part of the run before the window is the start. Its mesh-cycle peaks are
classed like the window's (:func:`gearcli.life.spectra.dynamic_loads` over the span ``[0, window start]``)
and each member's classes count ``N`` times the member's load cycles of one start (its revolutions during the
start, by the design's kinematics from the input shaft's, times its contacts per turn), in bins of their own
(named ``"<point> (start)"``). The bearings take the start's ISO 281 equivalent load (P^p averaged over the
start's revolutions) for ``N`` times the start's revolutions of their shaft (a planet pin's: the worst planet's
force times the design's K_gamma, as in the window). What runs after the start has
settled but before the window is counted with the start (conservative; a few settled cycles where the window
follows the settling, all of it where a file's ``window_start_s`` puts the window later).
"""

from __future__ import annotations

import math

import numpy as np

from gearcli.core.channels import Channel
from gearcli.core.records import record
from gearcli.design.shafts import equivalent_load_N, life_exponent
from gearcli.life import spectra
from gearcli.life.spectra import StageLoads
from gearcli.results import DesignResult
from gearcli.simulate.bearings import peak_static_load_N
from gearcli.simulate.results import SimulationResult
from gearcli.stages.life import life_kind

START_LABEL = "{name} (start)"


@record
class StartData:
    """One start of a duty point: its tooth-force classes per stage (the window's format), the input shaft's
    revolutions during it, the peak |F_t| per stage, and per bearing the start's ISO 281 equivalent load and
    its peak reactions."""

    count: int
    span_s: tuple[float, float]
    loads: list[StageLoads]
    input_revolutions: float
    peak_tangential_N: tuple[float, ...]
    bearing_loads_N: tuple[float, ...] = ()  # ISO 281 equivalent load over the start's revolutions
    bearing_peaks: tuple[dict[str, float], ...] = ()  # {peak_radial_N, axial_at_peak_radial_N, peak_axial_N}
    bearing_peak_static_N: tuple[float, ...] = ()  # the start's peak ISO 76 static equivalent load P_0


def label(point_name: str) -> str:
    return START_LABEL.format(name=point_name)


def _mask(t: np.ndarray, span: tuple[float, float]) -> np.ndarray:
    return (t >= span[0] - 1e-12) & (t <= span[1] + 1e-12)


def stage_force_series(result: SimulationResult, design: DesignResult, k: int) -> np.ndarray:
    """|F_t| of stage ``k`` (0-based); a stage with planets: the largest of its sun meshes' at each sample."""
    st = design.stages[k]
    planets = life_kind(st).planet_forces(st, result.series)
    if not planets:
        return np.abs(result.series[Channel("tangential_force", f"stage{k + 1}")])
    return np.max([np.abs(f) for f in planets], axis=0)


def start_data(count: int, result: SimulationResult, design: DesignResult,
               bearing_series: np.ndarray | None = None, bearing_specs=()) -> StartData:
    """The start of a point's run from rest: ``[0, window start]`` of ``result`` (module text).
    ``bearing_series``: the reactions (bearings x 3 (y, z, axial) x samples) with the bearings' ``specs``."""
    t = result.time_s
    span = (float(t[0]), float(result.window_s[0]))
    mask = _mask(t, span)
    loads = spectra.dynamic_loads(result, design, span=span)
    angle = spectra.pinion_angle_rad(t[mask], {n: c[mask] for n, c in result.series.items()}, 1)
    revs = float(angle[-1] / (2.0 * math.pi))
    peaks = tuple(float(np.max(stage_force_series(result, design, k)[mask])) for k in range(len(design.stages)))
    if bearing_series is None:
        return StartData(count, span, loads, revs, peaks)
    b_loads, b_peaks, b_static = start_bearings(result, bearing_series, bearing_specs)
    return StartData(count, span, loads, revs, peaks, tuple(b_loads), tuple(b_peaks), tuple(b_static))


def start_bearings(result: SimulationResult, bearing_series: np.ndarray, bearing_specs
                   ) -> tuple[list[float], list[dict[str, float]], list[float]]:
    """Per bearing over the start ``[0, window start]``: the ISO 281 equivalent load (P^p averaged over the input
    shaft's revolutions), the peak reactions and the peak ISO 76 P_0, from ``bearing_series`` (bearings x 3 (y, z,
    axial) x samples)."""
    mask = _mask(result.time_s, (float(result.time_s[0]), float(result.window_s[0])))
    w = np.abs(result.series[Channel("speed", "shaft1")][mask])
    b_loads, b_peaks, b_static = [], [], []
    for j, spec in enumerate(bearing_specs):
        r = bearing_series[j][:, mask]
        fr, fa = np.hypot(r[0], r[1]), r[2]
        p = np.array([equivalent_load_N(a, b, spec.e, spec.X, spec.Y) for a, b in zip(fr, fa, strict=True)])
        e = life_exponent(spec.kind)
        weight = np.sum(w)
        b_loads.append(float((np.sum(p**e * w) / weight) ** (1.0 / e)) if weight > 0 else float(np.max(p)))
        i = int(np.argmax(fr))
        b_peaks.append({"peak_radial_N": float(fr[i]), "axial_at_peak_radial_N": float(abs(fa[i])),
                        "peak_axial_N": float(np.max(np.abs(fa)))})
        b_static.append(peak_static_load_N(spec, fr, fa))
    return b_loads, b_peaks, b_static


def member_start_cycles(start: StartData, input_rpm: float, member_rpm: float, contacts: int) -> float:
    """Load cycles of one tooth of a member over all ``count`` starts: its revolutions during a start (the input
    shaft's scaled by the design's speed ratio) times its contacts per turn."""
    if input_rpm == 0:
        return 0.0
    return start.count * start.input_revolutions * abs(member_rpm / input_rpm) * contacts
