"""Mass moments of inertia of gears and shafts (docs/design-file.md)."""

from __future__ import annotations

import math

MM = 1e-3  # m per mm


def solid_disc_inertia_kg_m2(density_kg_m3: float, face_width_mm: float, diameter_mm: float) -> float:
    """J = π ρ b d⁴ / 32 (solid cylinder of diameter d and length b about its axis), SI units."""
    return math.pi * density_kg_m3 * (face_width_mm * MM) * (diameter_mm * MM) ** 4 / 32.0


def annulus_inertia_kg_m2(density_kg_m3: float, face_width_mm: float, outer_mm: float, bore_mm: float) -> float:
    """J = π ρ b (d⁴ − d_bore⁴) / 32: a disc of diameter d with a concentric bore, SI units."""
    return solid_disc_inertia_kg_m2(density_kg_m3, face_width_mm, outer_mm) - solid_disc_inertia_kg_m2(
        density_kg_m3, face_width_mm, bore_mm)


def mean_body_diameter_mm(tip_diameter_mm: float, root_diameter_mm: float) -> float:
    """d_m = (d_a + d_f) / 2: the diameter ISO 6336-1 takes for the body of a gear (reduced mass m_red)."""
    return 0.5 * (tip_diameter_mm + root_diameter_mm)


def body_inertia_kg_m2(given_kg_m2: float | None, density_kg_m3: float, face_width_mm: float,
                       mean_diameter_mm: float, bore_mm: float | None) -> float:
    """ISO 6336-1's gear body: ``inertia_kg_m2`` if given, else π ρ b (d_m⁴ − d_bore⁴)/32 (no bore: solid)."""
    if given_kg_m2 is not None:
        return given_kg_m2
    return annulus_inertia_kg_m2(density_kg_m3, face_width_mm, mean_diameter_mm, bore_mm or 0.0)


def gear_inertia_kg_m2(given_kg_m2: float | None, density_kg_m3: float, face_width_mm: float,
                       pitch_diameter_mm: float) -> float:
    """The design file's ``inertia_kg_m2`` if given, else a solid disc of pitch diameter and face width."""
    if given_kg_m2 is not None:
        return given_kg_m2
    return solid_disc_inertia_kg_m2(density_kg_m3, face_width_mm, pitch_diameter_mm)


def shaft_inertias_kg_m2(pinions: tuple[float, ...], gears: tuple[float, ...]) -> tuple[float, ...]:
    """Shaft 1: pinion 1; shaft k+1: gear k + pinion k+1 (one rigid body); last shaft: the last gear."""
    inner = tuple(g + p for g, p in zip(gears[:-1], pinions[1:], strict=True))
    return (pinions[0], *inner, gears[-1])
