"""The operating point of planets with position errors: how they share a planetary stage's load in the settled state.

:func:`gearcli.model.linear.static_forces` gives every planet its equal share, the design's. A planet's position
error e_j (``planet.position_error_um``, the connector's ``initial_deflection``: delta = R theta + e along its sun
mesh) changes the share in the run: the planet's sun and ring meshes are in series and the planet's own angle
cancels from their sum, so in the settled state delta_sp,j + delta_rp,j = S + e_j with S common to the stage (the
central members' rigid angles). Each planet's ring-mesh force is its sun mesh's times the equal share's ratio (the
planet's moment balance with its meshes' losses), and the sun's moment balance sums the sun meshes to N times the
equal share. A linearisation at "the operating point" (``modes``, the run's natural frequencies) takes each mesh's
tangent at its own force there: a Hertzian law's k grows as F^(1/3), so unequal planets split the N - 1 fold
planet modes. The mesh laws' calibration (K) stays the design's, at the equal share.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from gearcli.model.elements import mesh

if TYPE_CHECKING:
    from gearcli.model.assembly import Layout


def planet_groups(lay: Layout) -> dict[int, list[tuple[int, int]]]:
    """Stage (0-based) -> per planet (sun-mesh connector, ring-mesh connector), planets in order: the planetary
    stages whose planets carry a position error (the others share equally: nothing to solve)."""
    found: dict[int, dict[int, dict[str, int]]] = {}
    for c, x in enumerate(lay.connectors):
        if x.load_body >= 0:
            found.setdefault(x.index, {}).setdefault(x.planet, {})[x.gear] = c
    out = {}
    for k, planets in found.items():
        pairs = [(p["sun"], p["ring"]) for _, p in sorted(planets.items()) if "sun" in p and "ring" in p]
        if any(lay.connectors[s].initial_deflection != 0.0 for s, _ in pairs):
            out[k] = pairs
    return out


def operating_forces(lay: Layout, static: np.ndarray) -> np.ndarray:
    """``static`` (:func:`gearcli.model.linear.static_forces`) with every planet mesh of a stage with position
    errors at its settled force: the module's statics, solved for S by bisection on the monotone sum of the sun
    meshes (each planet's force by bisection on its own monotone series deflection). A planet whose S + e_j lies
    within its meshes' gaps carries nothing; without a gap a negative one presses its back flank."""
    out = np.array(static, dtype=float)
    for pairs in planet_groups(lay).values():
        sun0, ring0 = static[pairs[0][0]], static[pairs[0][1]]
        if sun0 == 0.0:
            continue
        for (s, r), f in zip(pairs, _shares(lay, pairs, sun0, ring0 / sun0), strict=True):
            out[s], out[r] = f, ring0 / sun0 * f
    return out


def _shares(lay: Layout, pairs: list[tuple[int, int]], sun0: float, ratio: float) -> list[float]:
    """The settled sun-mesh forces of a stage's planets (:func:`operating_forces`): ``sun0`` the equal share,
    ``ratio`` a planet's ring-mesh force over its sun mesh's."""
    rows = [(lay.connectors[s].params, lay.connectors[r].params) for s, r in pairs]
    errors = np.array([lay.connectors[s].initial_deflection for s, _ in pairs])

    def series(f: float, j: int) -> float:  # delta_sp + delta_rp of planet j at sun-mesh force f (signed)
        return mesh.static_deflection(rows[j][0], f) + mesh.static_deflection(rows[j][1], ratio * f)

    def force(s: float, j: int) -> float:  # the sun-mesh force of planet j at S + e_j = s
        if series(math.copysign(1e-300, s), j) * math.copysign(1.0, s) >= abs(s):  # inside the gaps
            return 0.0
        hi = abs(sun0)
        while abs(series(math.copysign(hi, s), j)) < abs(s):
            hi *= 2.0
        return math.copysign(_bisect(lambda f: abs(series(math.copysign(f, s), j)) - abs(s), 0.0, hi), s)

    def total(S: float) -> float:  # the sun meshes' sum less the sun's moment balance's, N sun0
        return sum(force(S + e, j) for j, e in enumerate(errors)) - len(pairs) * sun0

    s0 = series(sun0, 0)
    S = _bisect(total, s0 - float(errors.max()), s0 - float(errors.min()))
    return [force(S + e, j) for j, e in enumerate(errors)]


def rest_deflections(lay: Layout) -> dict[int, float]:
    """Planet mesh connector -> its deflection at rest and unloaded, where a run from rest starts, for the stages
    whose planets carry position errors: the module's statics with no load (the sun meshes' sum 0, a planet's two
    meshes carrying the same force: nothing rolls, nothing is lost), S common to the stage. Without a gap the planets
    preload each other (f_j = k (S + e_j) in series, summing to 0); with one, a planet inside its meshes' gaps carries
    nothing and its S + e_j is split between them in proportion to their half gaps. delta = R theta + e then
    holds with the central members turned by S (the carrier's start angle), not with every body at 0: there the
    planets with the largest errors pressed their meshes, the carrier was kicked at t = 0 and the run's peak
    force was that kick's (2819 N at 0 s against a settled 2738 N on a 5-planet stage)."""
    out: dict[int, float] = {}
    for pairs in planet_groups(lay).values():
        out.update(_at_rest(lay, pairs))
    return out


def _at_rest(lay: Layout, pairs: list[tuple[int, int]]) -> dict[int, float]:
    """:func:`rest_deflections` of one stage's planets (``pairs``: sun- and ring-mesh connectors)."""
    rows = [(lay.connectors[s].params, lay.connectors[r].params) for s, r in pairs]
    errors = [lay.connectors[s].initial_deflection for s, _ in pairs]

    def series(f: float, j: int) -> float:  # delta_sp + delta_rp of planet j at force f on both meshes
        return mesh.static_deflection(rows[j][0], f) + mesh.static_deflection(rows[j][1], f)

    def force(d: float, j: int) -> float:  # planet j's force at delta_sp + delta_rp = d
        if abs(series(math.copysign(1e-300, d), j)) >= abs(d):  # inside the gaps
            return 0.0
        hi = 1.0
        while abs(series(math.copysign(hi, d), j)) < abs(d):
            hi *= 2.0
        return math.copysign(_bisect(lambda g: abs(series(math.copysign(g, d), j)) - abs(d), 0.0, hi), d)

    S = _bisect(lambda x: sum(force(x + e, j) for j, e in enumerate(errors)), -max(errors), -min(errors))
    out: dict[int, float] = {}
    for j, ((s, r), e) in enumerate(zip(pairs, errors, strict=True)):
        f = force(S + e, j)
        if f != 0.0:
            out[s] = mesh.static_deflection(rows[j][0], f)
        else:
            half = [row[mesh.I_HALF] / row[mesh.I_CB] for row in rows[j]]
            out[s] = (S + e) * half[0] / sum(half) if sum(half) > 0.0 else 0.0
        out[r] = S + e - out[s]  # the loop closes exactly
    return out


def _bisect(g, lo: float, hi: float) -> float:
    """A root of the increasing ``g`` on [lo, hi] (g(lo) <= 0 <= g(hi)) to the floats' resolution."""
    from scipy.optimize import brentq  # lazy: scipy, a scene with position errors only

    g_lo, g_hi = g(lo), g(hi)
    if g_lo >= 0.0:
        return lo
    if g_hi <= 0.0:
        return hi
    return float(brentq(g, lo, hi, xtol=1e-300, rtol=4.0 * np.finfo(float).eps, maxiter=500))
