"""Load spectra per duty point (docs/life.md, "Spectra").

Static route: the point's design with its ISO 6336 rating (K_A = 1, the rating's K_v): one bin per point,
its force the static tangential force, its stress the rating's.
Dynamic route: the point simulated (the sweep's point evaluation, the compiled engine where it pays off) with
K_v = 1 in the rating; every mesh cycle of the steady window is one tooth engagement, counted at the largest
|F_t| it meets; the cycles are put into classes, and a class's stress is the rating's at K_v = 1 scaled to
its force (sigma_H ∝ sqrt(F_t), sigma_F ∝ F_t at the point's other factors). A planetary stage counts every planet
mesh in the carrier's frame (:func:`planetary_loads`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import replace
from typing import Protocol, cast

import numpy as np

from gearcli.core.channels import Channel
from gearcli.core.records import record
from gearcli.errors import ConfigError, SimulationError
from gearcli.stages import kinds

MESH_CLASSES = 20  # load classes of the dynamic spectrum per stage and point
CLASS_RESOLUTION = 1e-6  # a spread of the peaks below this share of the force is noise: one class
SAMPLES_PER_MESH_CYCLE = 128  # output samples per mesh cycle of the fastest mesh (peaks: see peak_error)
MAX_STEPS = 400_000
MIN_WINDOW_MESH_CYCLES = 40  # whole mesh cycles of the slowest mesh in the steady window
SETTLE_FRACTION = 0.2  # gearcli.simulate.stats: the window starts 20 % of the time after the ramps
MAX_DURATION_S = 600.0


@record
class StageLoads:
    """A stage's tooth-force classes at one point: forces (N, reference circle) and their share of the
    engagements (sums to 1); ``static_N`` the point's static F_t."""

    forces_N: tuple[float, ...]
    shares: tuple[float, ...]
    static_N: float
    mesh_cycles: int
    peak_error: float = 0.0  # estimated relative error of the mean mesh-cycle peak from the output sampling
    mean_peak_N: float = 0.0  # the mean mesh-cycle peak the error is relative to (what :func:`referred` rescales)
    planetary: PlanetaryLoads | None = None  # a planetary stage's dynamic spectra per member (the stage's own: the sun's)


@record
class PlanetaryLoads:
    """A planetary stage's dynamic spectra (docs/life.md, "Planetary stages, dynamic route"): the sun's and the
    ring's are the union of their N meshes' engagements (each mesh cycle of planet j's mesh is one tooth of the
    central member meeting planet j); a planet's are its own meshes' (index j - 1: planet j)."""

    sun: StageLoads
    ring: StageLoads
    planet_sun: tuple[StageLoads, ...]
    planet_ring: tuple[StageLoads, ...]


def static_loads(static_N: float) -> StageLoads:
    return StageLoads((abs(static_N),), (1.0,), static_N, 0)


def pinion_angle_rad(t: np.ndarray, series: Mapping[Channel, np.ndarray], shaft: int) -> np.ndarray:
    """The angle of shaft ``shaft`` (1-based) from its speed series (rad/s; trapezoid)."""
    speed = series.get(Channel("speed", f"shaft{shaft}"))
    if speed is None:
        raise SimulationError(f"no speed channel of shaft {shaft} to count the mesh cycles")
    w = np.abs(speed)
    return np.concatenate(([0.0], np.cumsum(0.5 * (w[1:] + w[:-1]) * np.diff(t))))


def mesh_cycle_peaks(t: np.ndarray, ft: np.ndarray, angle_rad: np.ndarray, teeth: int) -> np.ndarray:
    """max |F_t| over each whole mesh cycle (pinion phase z theta / 2 pi between integers) of the samples.

    The phase counts from the first sample, so the first cycle, [0, 1), is as whole as every later one: it is
    counted (a start from rest meets its largest force there, in the first fraction of a tooth pitch); the last,
    cut off by the end of the samples, is not."""
    phase = teeth * (angle_rad - angle_rad[0]) / (2.0 * math.pi)
    cycle = np.floor(phase).astype(np.int64)
    starts = np.flatnonzero(np.diff(cycle)) + 1  # first sample of each new cycle
    if len(starts) < 1:
        return np.empty(0)
    bounds = np.concatenate(([0], starts[:-1]))  # cycle i: samples bounds[i] .. starts[i]-1
    return np.maximum.reduceat(np.abs(ft)[: starts[-1]], bounds)


def classes(peaks: np.ndarray, static_N: float, n: int = MESH_CLASSES) -> StageLoads:
    """Equal-width classes of the per-cycle peaks; each class stands at its largest peak (conservative by at
    most one class width), its share the fraction of cycles in it. Peaks that spread by no more than
    :data:`CLASS_RESOLUTION` of the force are one class at the largest (a quiet window's engagements differ by the
    integration's noise only: 20 classes of the same 2297.3044 N, 5e-10 apart, said nothing and filled the table)."""
    lo, hi = float(peaks.min()), float(peaks.max())
    mean = float(np.mean(peaks))
    if hi - lo <= CLASS_RESOLUTION * max(abs(hi), 1.0):
        return StageLoads((hi,), (1.0,), static_N, len(peaks), mean_peak_N=mean)
    idx = np.minimum(((peaks - lo) / (hi - lo) * n).astype(np.int64), n - 1)
    forces, shares = [], []
    for c in range(n):
        members = peaks[idx == c]
        if len(members):
            forces.append(float(members.max()))
            shares.append(len(members) / len(peaks))
    return StageLoads(tuple(forces), tuple(shares), static_N, len(peaks), mean_peak_N=mean)


def referred(loads: StageLoads, reference_N: float) -> StageLoads:
    """``loads`` with its peak error relative to the larger of its mean peak and ``reference_N``, the force the run
    resolves on the stage (docs/output.md, ``reference_N``): a zero-load step's engagements meet 1e-8 N of
    round-off whose every-second-sample estimate is 4e-3 of itself, an error no finer sampling removes and no damage
    follows from; a loaded stage's mean peak is the larger, and its error is unchanged."""
    ref = max(loads.mean_peak_N, reference_N)
    if not ref or not loads.mean_peak_N:
        return loads
    return replace(loads, peak_error=loads.peak_error * loads.mean_peak_N / ref)


def resolved_force_N(result, k: int) -> float:
    """The force stage k's targets refer to in the run (``reference_N``: at least the force the run resolves, a stage
    at rest carrying round-off only), 0 where the run gives none."""
    st = result.stages[k] if k < len(result.stages) else None
    est = None if st is None else (st.sampling_error or st.error_estimate)
    return float(est.reference_N) if est is not None else 0.0


def dynamic_loads(result, design, span: tuple[float, float] | None = None) -> list[StageLoads]:
    """Per stage, the classes of the mesh-cycle peaks of |F_t| over the run's steady window, or over ``span``
    (a start: from rest to the window; a planetary stage: the sun's, with every member's in ``planetary``)."""
    t = result.time_s
    lo, hi = span if span is not None else result.window_s
    mask = (t >= lo - 1e-12) & (t <= hi + 1e-12)
    series = {n: c[mask] for n, c in result.series.items()}
    return [cast(_KindLoads, kinds.facet(kinds.kind_of(st), "life")).dynamic_loads(t[mask], series, st, k)
            for k, st in enumerate(design.stages)]


@record
class _Window:
    """A window's samples as :func:`dynamic_loads` reads them (``time_s``, ``window_s``, ``series``)."""

    time_s: np.ndarray
    window_s: tuple[float, float]
    series: dict[Channel, np.ndarray]


def periodic_tiled(result, design):
    """The converged periodic state's window repeated until it holds MIN_WINDOW_MESH_CYCLES of the slowest mesh
    (exact: the state repeats every window), so that a mesh cycle longer than the period (a slow stage's, when the
    period is the fastest excitation's) is counted; ``result`` itself for any other run. The periodic window of a
    two-stage drive without excitation is one stage-2 mesh period: it held no whole cycle of it (exit 2)."""
    steady = getattr(result, "steady", None)
    if steady is None or steady.mode != "periodic" or not steady.converged or steady.periodicity == "none":
        return result
    t = result.time_s
    lo, hi = result.window_s
    mask = (t >= lo - 1e-12) & (t <= hi + 1e-12)
    tw = t[mask]
    period = float(tw[-1] - tw[0])
    if tw.size < 2 or period <= 0.0:
        return result
    f_min = min(abs(st.mesh_frequency_Hz) for st in design.stages)  # at the design's input speed
    speed = result.series.get(Channel("speed", "shaft1"))
    nominal = abs(design.input_speed_deg_s) * math.pi / 180.0
    if speed is not None and nominal > 0.0:  # a motor runs at its operating point, off the nominal speed
        f_min *= float(np.mean(np.abs(speed[mask]))) / nominal
    if not f_min > 0.0:  # at standstill (a motor that cannot start): no mesh cycle to repeat the window for
        return result
    copies = max(1, math.ceil((MIN_WINDOW_MESH_CYCLES + 2) / f_min / period))  # +2: the cycles cut by both ends
    if copies == 1:
        return result
    time = np.concatenate([tw[:-1] + i * period for i in range(copies)] + [tw[-1:] + (copies - 1) * period])
    series = {n: np.concatenate([c[mask][:-1]] * copies + [c[mask][-1:]]) for n, c in result.series.items()}
    return _Window(time, (float(time[0]), float(time[-1])), series)


class _KindLoads(Protocol):
    """What the spectra ask of a stage's kind (its life facet, :mod:`gearcli.stages.life`)."""

    def dynamic_loads(self, t: np.ndarray, series: Mapping[Channel, np.ndarray], st, k: int) -> StageLoads:
        """The stage's tooth-force classes over the window samples ``t``."""


def pair_loads(t: np.ndarray, series: Mapping[Channel, np.ndarray], st, k: int) -> StageLoads:
    """A gear pair's classes: the mesh-cycle peaks of its |F_t| over the window samples ``t`` (stage k, 0-based)."""
    angle = pinion_angle_rad(t, series, k + 1)
    ft = series[Channel("tangential_force", f"stage{k + 1}")]
    peaks = mesh_cycle_peaks(t, ft, angle, st.pinion.teeth)
    if len(peaks) == 0:
        raise _no_mesh_cycle(f"stage {k + 1}")
    # every second sample, both ways (a response locked to the sampling puts its peaks on one parity)
    error = max(peak_error(peaks, mesh_cycle_peaks(t[i::2], ft[i::2], angle[i::2], st.pinion.teeth))
                for i in (0, 1))
    return replace(classes(peaks, st.static_force_N.tangential), peak_error=error)


def relative_angle_rad(t: np.ndarray, series: Mapping[Channel, np.ndarray], st, member: str) -> np.ndarray:
    """The angle of a planetary stage's central ``member`` ("sun" or "ring") relative to its carrier (rad,
    trapezoid of |omega_member - omega_carrier|): the stage's input member turns with shaft k, its output member
    with shaft k + 1, the held member not at all."""
    p = st.planetary

    def speed(m: str) -> np.ndarray:
        if m == p.fixed:
            return np.zeros_like(t)
        shaft = st.index if m == p.input else st.index + 1
        w = series.get(Channel("speed", f"shaft{shaft}"))
        if w is None:
            raise SimulationError(f"no speed channel of shaft {shaft} to count the mesh cycles")
        return w

    w = np.abs(speed(member) - speed("carrier"))
    return np.concatenate(([0.0], np.cumsum(0.5 * (w[1:] + w[:-1]) * np.diff(t))))


def _mesh_peaks(t: np.ndarray, ft: np.ndarray, angle: np.ndarray, teeth: int, what: str) -> tuple[np.ndarray, float]:
    """A mesh's cycle peaks over the window and their estimated relative error (every second sample)."""
    peaks = mesh_cycle_peaks(t, ft, angle, teeth)
    if len(peaks) == 0:
        raise _no_mesh_cycle(what)
    error = max(peak_error(peaks, mesh_cycle_peaks(t[i::2], ft[i::2], angle[i::2], teeth)) for i in (0, 1))
    return peaks, error


def planetary_loads(t: np.ndarray, series: Mapping[Channel, np.ndarray], st) -> StageLoads:
    """A planetary stage's spectra over the window samples ``t``: every planet's sun mesh counted on the sun's
    angle relative to the carrier (z_s cycles per relative turn), its ring mesh on the ring's (z_r). The sun's
    and the ring's classes are of all N meshes' peaks together, a planet's of its own mesh's; the stage's own
    loads are the sun's (its ``mesh_cycles`` the N meshes' together), ``peak_error`` the largest of the 2N meshes'."""
    p = st.planetary
    sun_angle = relative_angle_rad(t, series, st, "sun")
    ring_angle = relative_angle_rad(t, series, st, "ring")
    sun_static, ring_static = st.static_force_N.tangential, p.planet_ring.static_force_N.tangential
    sun_peaks: list[np.ndarray] = []
    ring_peaks: list[np.ndarray] = []
    errors: list[float] = []
    for j in range(1, p.planet_count + 1):
        for gear, angle, teeth, out in (("sun", sun_angle, abs(p.sun.teeth), sun_peaks),
                                        ("ring", ring_angle, abs(p.ring.teeth), ring_peaks)):
            name = f"stage{st.index}_planet{j}_{gear}"
            ft = series.get(Channel("tangential_force", name))
            if ft is None:
                raise SimulationError(f"stage {st.index}: no {gear} mesh force series of planet {j}")
            peaks, error = _mesh_peaks(t, ft, angle, teeth, f"stage {st.index} planet {j} {gear} mesh")
            out.append(peaks)
            errors.append(error)
    error = max(errors)
    sun = replace(classes(np.concatenate(sun_peaks), sun_static), peak_error=error)
    ring = replace(classes(np.concatenate(ring_peaks), ring_static), peak_error=error)
    loads = PlanetaryLoads(sun, ring, tuple(classes(pk, sun_static) for pk in sun_peaks),
                           tuple(classes(pk, ring_static) for pk in ring_peaks))
    return replace(sun, planetary=loads)


def _no_mesh_cycle(what: str) -> ConfigError:
    """A window too short (or too slow: a motor still starting) to hold one tooth engagement: the duration the
    file or a --set gave is too short for a load spectrum (exit 2 naming the key, like any bad value)."""
    return ConfigError(f"{what}: the steady window holds no whole mesh cycle, so there is no tooth load to count; "
                       "lengthen simulation.duration_s", key="simulation.duration_s")


def peak_error(fine: np.ndarray, coarse: np.ndarray) -> float:
    """Estimated relative error of the mean mesh-cycle peak on the output samples, from the peaks of every
    second sample (step 2h): a sampled maximum misses the true one by O(h^2), so Richardson's estimate is
    |fine - coarse| / (2^2 - 1). Measured on the excited test scene (tests/life/scenes.py, EXCITED, point
    "light"): the estimate falls 12x and 16x for each 4x finer sampling, as h^2 says."""
    if len(coarse) == 0:
        return math.inf
    a, b = float(np.mean(fine)), float(np.mean(coarse))
    return abs(a - b) / (3.0 * abs(a)) if a else 0.0


def duration_for(cfg, design) -> float:
    """A run long enough that its steady window holds MIN_WINDOW_MESH_CYCLES of the slowest mesh (at least
    the file's duration): the window is [ramps + 20 % of the rest, end], or [window_start_s, end]."""
    f_min = min(abs(st.mesh_frequency_Hz) for st in design.stages)
    # +1: the cycle the window's end cuts off, which mesh_cycle_peaks does not count (40 periods of window held
    # 39 whole cycles)
    window = (MIN_WINDOW_MESH_CYCLES + 1) / f_min
    sim = cfg.simulation
    if sim.window_start_s is not None:
        need = sim.window_start_s + window
    else:
        need = max(cfg.input.ramp_s, cfg.load.ramp_s) + window / (1.0 - SETTLE_FRACTION)
    return float(min(MAX_DURATION_S, max(sim.duration_s, need)))


def steps_for(design, duration_s: float, steps: int) -> int:
    """Output samples so that the fastest mesh gets SAMPLES_PER_MESH_CYCLE per cycle (at least ``steps``)."""
    f_max = max(abs(st.mesh_frequency_Hz) for st in design.stages)
    need = math.ceil(SAMPLES_PER_MESH_CYCLE * f_max * duration_s)
    return int(min(MAX_STEPS, max(steps, need)))
