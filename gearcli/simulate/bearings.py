"""Bearing reactions as simulation channels (docs/life.md): the shaft statics of
:mod:`gearcli.design.shafts` applied sample by sample to the simulated mesh forces.

A reaction component is linear in the stages' transverse line-of-action forces F_bt (the tangential and
axial tooth forces) plus a term in |F_bt| (the radial force, which separates the wheels on either flank), so
the statics is solved once per stage for a unit F_bt and the channels are sums of those influence
coefficients times the force series. Only scenes with ``[[bearing]]`` tables compute them.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping

import numpy as np

from gearcli.config import DesignFile
from gearcli.core.channels import Channel
from gearcli.design.bearing_life import static_warning
from gearcli.design.iso281 import static_safety
from gearcli.design.shafts import BearingSpec, ShaftLayout, stage_layout
from gearcli.diagnostics import Diagnostic, messages
from gearcli.results import DesignResult
from gearcli.simulate.results import BearingStats, SimulationExtra, SimulationResult
from gearcli.simulate.stats import channel_stats, window_mask
from gearcli.stages.design import design_kind


def influence(lay: ShaftLayout, n_stages: int) -> tuple[np.ndarray, np.ndarray]:
    """Coefficients (bearings x 3 components y, z, axial x stages): reaction = A @ F_bt + B @ |F_bt|.
    The statics is evaluated at F_bt = +1 and -1 per stage: A = (R(+1) - R(-1))/2, B = (R(+1) + R(-1))/2."""
    n_bearings = len(lay.specs)
    a = np.zeros((n_bearings, 3, n_stages))
    b = np.zeros((n_bearings, 3, n_stages))
    for k in range(n_stages):
        plus, minus = ([float(sign) if i == k else 0.0 for i in range(n_stages)] for sign in (1, -1))
        rp = [(r.y_N, r.z_N, r.axial_N) for _, r in lay.reactions(plus, sharing=False)]
        rm = [(r.y_N, r.z_N, r.axial_N) for _, r in lay.reactions(minus, sharing=False)]
        a[:, :, k] = 0.5 * (np.array(rp) - np.array(rm))
        b[:, :, k] = 0.5 * (np.array(rp) + np.array(rm))
    return a, b


def line_force_series(design: DesignResult, series: Mapping[Channel, np.ndarray]) -> np.ndarray:
    """F_bt per stage (stages x samples) from the simulated F_t = F_bt cos(alpha_t); a planetary stage's is planet
    1's sun mesh's, as a magnitude in the design's load direction (the pins carry the simulated planet 1's load, the
    central members the balanced sum of N such planets)."""
    rows = []
    for s in design.stages:
        f = series[Channel("tangential_force", f"stage{s.index}")] / math.cos(
            math.radians(s.transverse_pressure_angle_deg))
        rows.append(np.abs(f) if design_kind(s).model_signs_forces else f)
    return np.array(rows)


def reaction_series(lay: ShaftLayout, design: DesignResult, series: Mapping[Channel, np.ndarray]) -> np.ndarray:
    """(bearings x 3 x samples): y, z and axial reaction of each bearing, in [[bearing]] order."""
    a, b = influence(lay, len(design.stages))
    f = line_force_series(design, series)
    return np.einsum("bck,ks->bcs", a, f) + np.einsum("bck,ks->bcs", b, np.abs(f))


def with_bearings(cfg: DesignFile, design: DesignResult, result: SimulationResult) -> SimulationResult:
    """The result with each bearing's radial and axial reaction series (``bearing{j}``, j 1-based, [[bearing]]
    order; the output's ``bearing{j}_radial_N``, ``bearing{j}_axial_N``) and their window statistics in
    ``extra["bearings"]``; unchanged without ``[[bearing]]`` tables."""
    lay = stage_layout(cfg, design.stages)
    if lay is None:
        return result
    r = reaction_series(lay, design, result.series)
    series = dict(result.series)
    mask = window_mask(result.time_s, result.window_s)
    summary: list[BearingStats] = []
    diags: list[Diagnostic] = []
    specs = lay.specs
    for j, spec in enumerate(specs):
        radial, axial = np.hypot(r[j, 0], r[j, 1]), r[j, 2]
        series[Channel("radial_force", f"bearing{j + 1}")] = radial
        series[Channel("axial_force", f"bearing{j + 1}")] = axial
        stats = BearingStats(shaft=spec.shaft, position_mm=spec.position_mm, radial_N=channel_stats(radial, mask),
                             axial_N=channel_stats(axial, mask))
        if spec.planet_stage:
            stats["planet_stage"] = spec.planet_stage
        if spec.static_rating_N is not None:  # ISO 76 at the window's peak P_0 (docs/bearings.md)
            peak = peak_static_load_N(spec, radial[mask], axial[mask])
            s0 = static_safety(spec.static_rating_N, peak)
            stats["static_safety_min"] = s0
            found = static_warning(cfg, j, spec.kind, s0, "at the peak of the simulated window")
            if found is not None:
                diags.append(found)
        summary.append(stats)
    extra = result.extra.copy() if result.extra else SimulationExtra()
    extra["bearings"] = summary
    return dataclasses.replace(result, series=series, extra=extra, warnings=(*result.warnings, *messages(diags)),
                               diagnostics=(*result.diagnostics, *diags))


def peak_static_load_N(spec: BearingSpec, radial_N: np.ndarray, axial_N: np.ndarray) -> float:
    """The largest ISO 76 static equivalent load P_0(t) = max(F_r, X0 F_r + Y0 |F_a|) over the samples given."""
    if radial_N.size == 0:
        return 0.0
    p0 = np.maximum(np.abs(radial_N), spec.X0 * np.abs(radial_N) + spec.Y0 * np.abs(axial_N))
    return float(np.max(p0))
