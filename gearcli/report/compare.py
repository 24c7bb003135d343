"""Theory against simulation (seed paper section 4.1-4.2, with the corrected theory values).

Theory is the design layer's static answer (ratios z2/z1, shaft speeds down the train, tooth forces
F_t = T / r, F_r = F_t tan α_t, F_a = F_t tan β; under a reversed load on a lossy stage the driving gear's,
T_g / r_g, the design's pinion-side force over η); simulation is the mean over the steady window.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from gearcli.core.channels import Channel
from gearcli.rating.dynamic import stage_simulated_k_v  # one formula, shared with the simulated rating
from gearcli.report.result import ComparisonRow, RatingComparison, StageReport, TheoryPoint
from gearcli.report.spectrum import force_spectrum, window_mask
from gearcli.results import DesignResult
from gearcli.simulate.results import SimulationResult
from gearcli.simulate.stats import window_means
from gearcli.stages.design import design_kind

RAD_TO_DEG = 180.0 / math.pi


def relative_error_percent(simulated: float, theory: float) -> float | None:
    """Signed ``100 (simulated - theory) / |theory|``; ``None`` when the theory value is 0."""
    if theory == 0 or not np.isfinite(theory):
        return None
    return 100.0 * (simulated - theory) / abs(theory)


def _row(stage: int | None, quantity: str, theory: float, simulated: float, judged: bool = True) -> ComparisonRow:
    """``judged`` False: the theory is a state the run never reaches, so no error is given."""
    return ComparisonRow(stage, quantity, float(theory), float(simulated),
                         relative_error_percent(float(simulated), float(theory)) if judged else None)


def shaft_mean_speeds_deg_s(sim: SimulationResult, n_shafts: int) -> list[float]:
    """Mean speed of every shaft over the steady window, from the shafts' speed series (the trapezoid rule's
    integral over the window, as every mean of simulate; the plain mean of the samples erred by
    (mean − (x_0 + x_N)/2) / N: 3.5e-6 on a shaft whose speed swings 0.5 %).

    The input and output means are taken from the simulation's own summary, so the report and
    ``gearcli simulate`` agree to the last digit.
    """
    mask = window_mask(sim.time_s, sim.window_s)
    means = []
    for i in range(1, n_shafts + 1):
        series = sim.series.get(Channel("speed", f"shaft{i}"))
        # the integral over the window (trapezoid rule, DESIGN §7), as simulate's means; over whole periods the
        # closed window's trapezoid rule is the periodic mean too
        means.append(float(window_means(sim.time_s[mask], (series * RAD_TO_DEG)[mask], False)[0])
                     if series is not None and mask.any() else float("nan"))
    means[0] = float(sim.input_speed_deg_s)
    means[-1] = float(sim.output_speed_deg_s)
    return means


def comparison_rows(design: DesignResult, sim: SimulationResult,
                    point: TheoryPoint | None = None) -> tuple[ComparisonRow, ...]:
    """Train rows (ratio, input and output speed), then per stage: ratio, gear speed, F_t, F_r, F_a; the theory at
    the operating point ``point`` where the drive does not prescribe the speed (None: the design's nominal)."""
    speeds = shaft_mean_speeds_deg_s(sim, len(design.shafts))
    at_speed = 1.0 if point is None else point.speed_factor
    at_load = 1.0 if point is None else point.load_factor
    # a run that settles nowhere (TheoryPoint.reached False): its speeds and forces are a transient's, the nominal
    # point's theory no state of it; only the ratios (kinematics) are compared
    ok = point is None or point.reached
    rows = [
        _row(None, "ratio", design.total_ratio, sim.ratio),
        _row(None, "input_speed_deg_s", at_speed * design.input_speed_deg_s, sim.input_speed_deg_s, ok),
        _row(None, "output_speed_deg_s", at_speed * design.output_speed_deg_s, sim.output_speed_deg_s, ok),
    ]
    for st, dyn in zip(design.stages, sim.stages, strict=True):
        k = st.index
        pinion_speed, gear_speed = speeds[k - 1], speeds[k]
        ratio_sim = pinion_speed / gear_speed if gear_speed != 0 else float("nan")
        static = st.static_force_N
        kind = design_kind(st)
        out_speed, sign = kind.output_speed_deg_s(st), 1.0  # the output member's speed
        if kind.model_signs_forces:  # F_t with the flank sign the model gives it
            sign = -1.0 if (dyn.static_tangential_N < 0) != (static.tangential < 0) else 1.0
        share = _planets_mean_over_planet_1(dyn)
        sign *= driving_gear_factor(st, kind.model_signs_forces) * at_load
        reference = dyn.simulated_static_tangential_N
        if at_load < 0.0 and static.tangential != 0.0 and reference is not None:  # a planetary's: its planets' mean
            # the load law's torque turned sign at the operating point, and the power flow with it: the losses act
            # the other way than in the design's statics; the run's static reference carries them (F_r, F_a pro rata)
            sign = reference / static.tangential
        rows += [
            _row(k, "ratio", st.ratio, ratio_sim),
            _row(k, "output_speed_deg_s", at_speed * out_speed, gear_speed, ok),
            _row(k, "tangential_N", sign * static.tangential, share * dyn.tangential_N.mean, ok),
            _row(k, "radial_N", sign * static.radial, share * dyn.radial_N.mean, ok),
            _row(k, "axial_N", sign * static.axial, share * dyn.axial_N.mean, ok),
        ]
    return tuple(r for r in rows if np.isfinite(r.simulated))


def driving_gear_factor(st, planetary: bool) -> float:
    """1/η for a lossy parallel stage under a reversed load (power from gear to pinion), else 1.

    The design's static forces are the pinion's (T_p = T_g η / i, F_t = 2 T_p / d_p); under a reversed load the gear
    drives, and the tooth force is the driving gear's, F_t = T_g / r_g = the design's over η: what the mesh carries
    and what the simulation's window mean of a settled run equals (docs/physics.md, "Mesh losses"). Comparing it
    with the pinion's would show 1/η − 1 as an "error" in the rigid limit."""
    eta = float(getattr(st, "efficiency", 1.0) or 1.0)
    if planetary or st.static_force_N.tangential >= 0 or not 0.0 < eta < 1.0:
        return 1.0
    return 1.0 / eta


def reversed_lossy_stages(design: DesignResult) -> list[int]:
    """The stages whose theory forces are the driving gear's (:func:`driving_gear_factor` ≠ 1)."""
    return [st.index for st in design.stages if driving_gear_factor(st, design_kind(st).model_signs_forces) != 1.0]


def _planets_mean_over_planet_1(dyn) -> float:
    """1 for a parallel stage; a planetary stage's mean window-mean F_t over its planets' sun meshes over planet 1's
    (the stage's channels): theory's static force is each planet's at equal sharing, which the planets' mean meets
    whatever their sharing (the moment balance), and F_r, F_a are F_t's multiples on every planet's sun mesh."""
    planets = getattr(dyn, "planets", ())
    if not planets or dyn.tangential_N.mean == 0.0:
        return 1.0
    return float(np.mean([p.sun.tangential_N.mean for p in planets])) / dyn.tangential_N.mean


def _whole_periods(sim: SimulationResult) -> bool:
    """The window is whole periods of a response that repeats over them (a periodic steady state that found its
    period-k orbit), so every line of the response lies on a bin of its DFT; not where the periodic search found no
    repetition (``periodicity`` "none": excitations without a common period, a response that never repeats), whose
    window's lines fall between the bins."""
    steady = sim.steady
    return steady is not None and steady.mode == "periodic" and steady.periodicity not in (None, "none")


def stage_reports(design: DesignResult, sim: SimulationResult, speed_factor: float = 1.0) -> tuple[StageReport, ...]:
    """Fluctuation, run-up peak, dynamic factor and the F_t spectrum of every mesh. ``speed_factor``: the window's
    mean input speed over the design's (:func:`window_speed_factor`; 1 for a prescribed speed), so the mesh lines
    and orders are taken where the run has them, not at the nominal speed a motor or torque drive does not run at."""
    out = []
    natural: Sequence[float] = tuple(sim.natural_frequencies_Hz)
    meshes = [(st.index, speed_factor * float(st.mesh_frequency_Hz)) for st in design.stages]
    for st, dyn in zip(design.stages, sim.stages, strict=True):
        series = sim.series.get(Channel("tangential_force", f"stage{st.index}"))
        dte_m = sim.series.get(Channel("dte", f"stage{st.index}"))
        if series is None:
            series = np.zeros_like(sim.time_s)
        spectrum = force_spectrum(sim.time_s, series, sim.window_s, stage=st.index,
                                  mesh_frequency_Hz=speed_factor * st.mesh_frequency_Hz, natural_frequencies_Hz=natural,
                                  dte_um=dte_m * 1e6 if dte_m is not None else None,
                                  whole_periods=_whole_periods(sim),
                                  other_meshes_Hz=[m for m in meshes if m[0] != st.index],
                                  damped_modes=(sim.extra or {}).get("damped_modes", ()))
        out.append(StageReport(
            stage=st.index, tangential_N=dyn.tangential_N, radial_N=dyn.radial_N, axial_N=dyn.axial_N,
            static_tangential_N=dyn.static_tangential_N, peak_tangential_N=dyn.peak_tangential_N,
            peak_time_s=dyn.peak_time_s, dynamic_factor=dyn.dynamic_factor, spectrum=spectrum,
            runup_factor=dyn.runup_factor, simulated_static_tangential_N=dyn.simulated_static_tangential_N,
        ))
    return tuple(out)


def window_speed_factor(design: DesignResult, sim: SimulationResult, speed_drive: bool) -> float:
    """The steady window's mean input speed over the design's nominal one: 1 for a prescribed speed; a motor runs at
    its slip and a torque drive at its balance, where the mesh phases (z_p θ_p) turn and so the mesh lines lie (a
    30 kW motor at 1471.7 rpm, not its nameplate 1470: the 1x line at 466.04 Hz, not 465.5 Hz, 1.3 bins of a 2.4 s
    window off, where the mesh order's projection read a third of its amplitude)."""
    nominal, mean = float(design.input_speed_deg_s), float(sim.input_speed_deg_s)
    if speed_drive or not nominal or not np.isfinite(mean) or mean <= 0.0:
        return 1.0
    return mean / nominal


def _least(ratings, mode: str) -> float:
    """The smallest safety against ``mode`` over the members of every rated mesh (any standard's)."""
    return min(m.safety(mode) for r in ratings for m in (r.pinion, r.gear))


def rating_comparison(design: DesignResult, sim: SimulationResult) -> tuple[RatingComparison, ...]:
    """Per rated stage, ISO 6336-1's K_v beside the simulated one and the smallest safeties at each."""
    out = []
    for st, sd in zip(design.stages, sim.stages, strict=False):
        if st.rating is None:
            continue
        iso, at_sim = st.rating, sd.rating
        # every mesh of the stage counts: a planetary stage's planet–ring mesh beside its sun–planet mesh
        isos = [iso, *design_kind(st).further_ratings(st)]
        sims = [r for r in (at_sim, getattr(sd, "planet_ring_rating", None)) if r is not None]
        out.append(RatingComparison(
            stage=st.index, K_v_iso=iso.K_v, K_v_iso_source=iso.K_v_source,
            K_v_simulated=stage_simulated_k_v(sd),
            min_S_H_iso=_least(isos, "pitting"), min_S_F_iso=_least(isos, "bending"),
            min_S_H_simulated=None if at_sim is None else _least(sims, "pitting"),
            min_S_F_simulated=None if at_sim is None else _least(sims, "bending")))
    return tuple(out)
