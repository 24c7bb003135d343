"""The mesh resonance of ISO 6336-1 (method B): reduced mass, resonance speed, resonance ratio, ranges.

Units as ISO 6336-1 writes them: masses per unit face width in kg/mm, stiffness per unit face width in
N/(mm·µm), speeds in rpm. c_γα/m_red in these units is 1e-6 of its SI value (N/m² over kg/m, 1/s²), so the
mesh's natural angular frequency is ω = 1000 √(c_γα/m_red) rad/s; the smaller wheel runs at resonance
when its mesh frequency z1 n/60 equals ω/(2π), i.e. n_E1 = 30 000/(π z1) √(c_γα/m_red) rpm.

Index 1 is the smaller wheel, whichever member drives (ISO 6336-1 calls it the pinion).
"""

from __future__ import annotations

import math

from gearcli.design.stiffness import FULL_LOAD_LINE_LOAD_N_mm

KG_MM2_PER_KG_M2 = 1e6
MAIN_RESONANCE_UPPER = 1.15  # N above which the main resonance range ends (ISO 6336-1)
SUPERCRITICAL_FROM = 1.5  # N from which the supercritical range starts (ISO 6336-1)
FULL_LOAD_LOWER_LIMIT = 0.85  # N_S when F_t K_A / b >= 100 N/mm (ISO 6336-1)
SUBHARMONICS = (2, 3)  # the subcritical resonances near N = 1/2 and 1/3 (ISO 6336-1, subcritical range)


def body_mass_per_width_kg_mm(inertia_kg_m2: float, face_width_mm: float, base_diameter_mm: float) -> float:
    """m* = J* / r_b², J* = J / b the polar moment of inertia per unit face width (ISO 6336-1, m_red)."""
    j_per_width = inertia_kg_m2 * KG_MM2_PER_KG_M2 / face_width_mm  # kg·mm²/mm
    return j_per_width / (0.5 * base_diameter_mm) ** 2


def reduced_mass_kg_mm(mass_1_kg_mm: float, mass_2_kg_mm: float) -> float:
    """m_red = m1* m2* / (m1* + m2*): the two bodies reduced to the line of action, per mm of face width.

    For solid (or bored) discs of ISO's mean diameter d_m this is ISO 6336-1 eq. (30),
    m_red = (π/8) (d_m1/d_b1)² d_m1² / (1/((1 − q1⁴) ρ1) + 1/((1 − q2⁴) ρ2 u²)), with d_m2/d_b2 = d_m1/d_b1
    taken exactly rather than approximately.
    """
    return mass_1_kg_mm * mass_2_kg_mm / (mass_1_kg_mm + mass_2_kg_mm)


def resonance_speed_rpm(teeth_1: int, mesh_stiffness_N_mm_um: float, reduced_mass: float) -> float:
    """n_E1 = 30 000 / (π z1) √(c_γα / m_red), rpm of the smaller wheel (ISO 6336-1, eq. 6)."""
    return 30000.0 / (math.pi * teeth_1) * math.sqrt(mesh_stiffness_N_mm_um / reduced_mass)


def lower_main_resonance_limit(line_load_N_mm: float) -> float:
    """N_S = 0.5 + 0.35 √(F_t K_A / (100 b)) below 100 N/mm, else 0.85 (ISO 6336-1, eqs. 11 and 12)."""
    if line_load_N_mm < FULL_LOAD_LINE_LOAD_N_mm:
        return 0.5 + 0.35 * math.sqrt(line_load_N_mm / FULL_LOAD_LINE_LOAD_N_mm)
    return FULL_LOAD_LOWER_LIMIT


def resonance_range(ratio: float, lower_limit: float) -> str:
    """The ISO 6336-1 speed range of N = n1/n_E1: "subcritical" (N ≤ N_S), "main resonance"
    (N_S < N ≤ 1.15), "intermediate" (1.15 < N < 1.5) or "supercritical" (N ≥ 1.5)."""
    if ratio <= lower_limit:
        return "subcritical"
    if ratio <= MAIN_RESONANCE_UPPER:
        return "main resonance"
    if ratio < SUPERCRITICAL_FROM:
        return "intermediate"
    return "supercritical"


def subharmonic_orders(ratio: float, lower_limit: float) -> tuple[int, ...]:
    """In the subcritical range, every order j (2, 3) whose band, the main range's scaled by 1/j, (N_S/j, 1.15/j],
    holds N: the mesh frequency's j-th harmonic excites the resonance. Below N_S = 0.767 the two bands overlap (a
    light load: N_S = 0.58 puts N = 0.292 in both, its 2nd harmonic at 0.584 and its 3rd at 0.876 of n_E1)."""
    if ratio > lower_limit:
        return ()
    return tuple(j for j in SUBHARMONICS if lower_limit / j < ratio <= MAIN_RESONANCE_UPPER / j)
