"""A dynamic duty point's loads from its run: the bearings' ISO 281 equivalent loads over the settled window and
the start from rest before it (:mod:`gearcli.life.starts`), a planetary stage's central members carrying its
planets' mean force (docs/life.md, "Starts"; docs/bearings.md)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from gearcli.config import DesignFile
from gearcli.core.channels import Channel
from gearcli.design.shafts import equivalent_load_N, life_exponent, stage_layout
from gearcli.diagnostics import MOTOR_STALLS
from gearcli.errors import ConfigError, SimulationError
from gearcli.life import spectra
from gearcli.life.bearings import PointBearings
from gearcli.life.duty import DutyPoint
from gearcli.life.starts import StartData, start_bearings, start_data
from gearcli.results import DesignResult, StageResult
from gearcli.simulate.bearings import peak_static_load_N, reaction_series
from gearcli.simulate.results import SimulationResult
from gearcli.stages.life import life_kind


def k_gamma(st: StageResult) -> float:
    """A stage's load-sharing factor K_gamma in its design (1 where nothing shares the load)."""
    return life_kind(st).k_gamma(st)


def window_loads(design: DesignResult, result: SimulationResult) -> list[spectra.StageLoads]:
    """The tooth-force classes of the point's steady window (a periodic state repeated, :mod:`gearcli.life.spectra`).
    A window without a whole mesh cycle whose motor stalls (``simulate``'s ``motor_stalls``: its curve cannot carry the
    load, which holds the train almost at rest) is refused naming the stall: a longer run, the remedy for a window
    too short, would only count the stalled motor's creep at the point's speed_rpm."""
    try:
        return spectra.dynamic_loads(spectra.periodic_tiled(result, design), design)
    except ConfigError as exc:
        stall = next((d for d in result.diagnostics if d.code == MOTOR_STALLS), None)
        if stall is None:
            raise
        what = exc.message.partition(":")[0]
        raise ConfigError(f"{what}: the steady window holds no whole mesh cycle, so there is no tooth load to count, "
                          f"because the motor does not run: {stall.message} (a longer run would count its creep at "
                          "the point's speed_rpm, no operating point)") from None


def k_v_factors(result: SimulationResult, loads: list[spectra.StageLoads]) -> tuple[float, ...]:
    """Per stage the point's K_v: the largest class force over the static F_t of the load the run applies
    (``simulated_static_tangential_N``, simulate's dynamic factor's reference, DESIGN §8), 1 for an unloaded stage.
    A motor runs at its slip, not at the point's ``speed_rpm``, and a speed-dependent load carries its law's torque
    there: over the point's design force, a DOL motor 0.4 % fast on a fan load read K_v 1.008 on a quiet window
    (tests/life/test_tr28g_motor_k_v.py). The classes' stresses are rated at their own forces: only this ratio's
    reference moves."""
    refs = [abs(s.simulated_static_tangential_N or ld.static_N) for s, ld in zip(result.stages, loads, strict=True)]
    return tuple(max(ld.forces_N) / ref if ld.static_N and ref else 1.0 for ld, ref in zip(loads, refs, strict=True))


def start_of(point: DutyPoint, cfg: DesignFile, design: DesignResult, result: SimulationResult) -> StartData:
    """The point's start from rest (its run before the settled window), with the bearings' loads."""
    if result.window_s[0] <= result.time_s[0]:
        raise SimulationError(f"duty point {point.name}: starts = {point.starts} needs the run from rest before its "
                              "window; simulation.window_start_s = 0 leaves no start to count")
    lay = stage_layout(cfg, design.stages)
    if lay is None:
        return start_data(point.starts, result, design)
    series = with_planet_mean(design, dict(result.series))
    start = start_data(point.starts, result, design, reaction_series(lay, design, series), lay.specs)
    # a pin bearing carries its worst planet's force times K_gamma over the start as in the window
    loads, peaks, static = (list(start.bearing_loads_N), list(start.bearing_peaks), list(start.bearing_peak_static_N))
    for stage, each in planet_series(design, series).items():
        pins = [j for j, spec in enumerate(lay.specs) if spec.planet_stage == stage]
        figures = [start_bearings(result, reaction_series(lay, design, s), lay.specs) for s in each]
        for j in pins:
            loads[j] = max(f[0][j] for f in figures)
            peaks[j] = max((f[1][j] for f in figures), key=lambda x: x["peak_radial_N"])
            static[j] = max(f[2][j] for f in figures)
    return replace(start, bearing_loads_N=tuple(loads), bearing_peaks=tuple(peaks), bearing_peak_static_N=tuple(static))


def planet_series(design: DesignResult, series: dict[Channel, np.ndarray]) -> dict[int, list[dict[Channel, np.ndarray]]]:
    """Per stage with planets (1-based), one series per planet whose stage force is that planet's sun-mesh force
    times the design's K_gamma (1 where the simulated position errors share the load): a pin bearing's load."""
    out: dict[int, list[dict[Channel, np.ndarray]]] = {}
    for st in design.stages:
        forces = life_kind(st).planet_forces(st, series)
        if forces:
            own = Channel("tangential_force", f"stage{st.index}")
            out[st.index] = [{**series, own: f * k_gamma(st)} for f in forces]
    return out


def with_planet_mean(design: DesignResult, series: dict[Channel, np.ndarray]) -> dict[Channel, np.ndarray]:
    """The series with each stage with planets its own F_t channel: its planets' sun-mesh mean (the central
    members' load; the statics' input)."""
    for st in design.stages:
        forces = life_kind(st).planet_forces(st, series)
        if forces:
            series[Channel("tangential_force", f"stage{st.index}")] = np.mean(forces, axis=0)
    return series


def dynamic_bearing_loads(cfg: DesignFile, design: DesignResult, result: SimulationResult) -> PointBearings:
    """Per bearing, the ISO 281 equivalent of the window's varying load: (mean of P(t)^p)^(1/p) over the
    window (at a steady speed, revolutions are proportional to time), and the window's peak ISO 76 P_0."""
    lay = stage_layout(cfg, design.stages)
    if lay is None:
        return PointBearings((), ())
    t = result.time_s
    mask = (t >= result.window_s[0] - 1e-12) & (t <= result.window_s[1] + 1e-12)
    series = {k: v[mask] for k, v in result.series.items()}
    specs = lay.specs

    def equivalent(r: np.ndarray, j: int) -> tuple[float, float]:
        spec = specs[j]
        fr, fa = np.hypot(r[j, 0], r[j, 1]), r[j, 2]
        p = np.array([equivalent_load_N(a, b, spec.e, spec.X, spec.Y) for a, b in zip(fr, fa, strict=True)])
        e = life_exponent(spec.kind)
        return float(np.mean(p**e) ** (1.0 / e)), peak_static_load_N(spec, fr, fa)

    # a planetary stage: the central members carry the mean planet's force N times (their torque), each pin its
    # own planet's times the design's K_gamma (1 where the simulated position errors share the load); a pin bearing
    # reports the worst planet's
    series = with_planet_mean(design, series)
    per_planet = planet_series(design, series)
    r = reaction_series(lay, design, series)
    out = []
    for j, spec in enumerate(specs):
        if spec.planet_stage and spec.planet_stage in per_planet:
            each = [equivalent(reaction_series(lay, design, s), j) for s in per_planet[spec.planet_stage]]
            out.append((max(e for e, _ in each), max(p for _, p in each)))  # the worst planet's
        else:
            out.append(equivalent(r, j))
    return PointBearings(tuple(e for e, _ in out), tuple(p for _, p in out))
