"""ISO 281:2007 modified rating life and ISO 76:2006 static safety of a rolling bearing (docs/bearings.md).

- a_1, the life modification factor for reliability (ISO 281 Table 12); between the table's reliabilities the
  Weibull law the table is built on, a_1 = 0.95 (ln(R) / ln(0.9))^(2/3) + 0.05 (ISO/TR 1281-2).
- e_C, the contamination factor, from the cleanliness level and the pitch diameter d_m (ISO 281 Table 13; the
  lower, conservative end of each range), or given.
- nu_1, the reference kinematic viscosity (ISO 281 6.5.2.4): 45000 n^-0.83 d_m^-0.5 below 1000 r/min,
  4500 n^-0.5 d_m^-0.5 from 1000 r/min on; kappa = nu / nu_1, nu the oil's viscosity at the operating
  temperature (ASTM D341 / Ubbelohde–Walther through its 40 °C and 100 °C values).
- a_ISO (ISO 281 equations 8 to 13, radial bearings) from kappa and e_C C_u / P, at most 50 (none at P = 0); kappa is taken
  as 4 above 4 and as 0.1 below 0.1 (where ISO 281 says the method does not apply: the caller warns).
- L_nm = a_1 a_ISO L_10.
- Static equivalent load P_0 = max(F_r, X_0 F_r + Y_0 F_a) (ISO 76, radial bearings) and s_0 = C_0 / P_0.

Pure ``math``: the design layer never imports numpy or scipy.
"""

from __future__ import annotations

import math

from gearcli.core.records import record

BALL_EXPONENT = 3.0  # ISO 281: p = 3 for ball bearings
ROLLER_EXPONENT = 10.0 / 3.0  # p = 10/3 for roller bearings


def life_exponent(kind: str) -> float:
    """ISO 281 life exponent p: 3 for ball, 10/3 for roller bearings."""
    return BALL_EXPONENT if kind == "ball" else ROLLER_EXPONENT


# ISO 281:2007 Table 12: reliability % -> a_1
RELIABILITY_TABLE = {90.0: 1.0, 95.0: 0.64, 96.0: 0.55, 97.0: 0.47, 98.0: 0.37, 99.0: 0.25, 99.2: 0.22,
                     99.4: 0.19, 99.6: 0.16, 99.8: 0.12, 99.9: 0.093, 99.92: 0.087, 99.94: 0.08, 99.95: 0.077}
# ISO 281:2007 Table 13: cleanliness level -> (e_C for d_m < 100 mm, e_C for d_m >= 100 mm), the lower end of
# each printed range (extreme 1; high 0.8-0.6 / 0.9-0.8; normal 0.6-0.5 / 0.8-0.6; slight 0.5-0.3 / 0.6-0.4;
# typical 0.3-0.1 / 0.4-0.2; severe 0.1-0; very severe 0)
CONTAMINATION = {"extreme": (1.0, 1.0), "high": (0.6, 0.8), "normal": (0.5, 0.6), "slight": (0.3, 0.4),
                 "typical": (0.1, 0.2), "severe": (0.0, 0.0), "very_severe": (0.0, 0.0)}
A_ISO_MAX = 50.0
KAPPA_MIN, KAPPA_MAX = 0.1, 4.0
# Guideline minimum static safety s_0 by kind (SKF Rolling bearings catalogue, "Guideline values for the static
# safety factor s0": rotating bearing, normal performance requirements, normal operation)
MIN_STATIC_SAFETY = {"ball": 1.0, "roller": 1.5}


def reliability_factor(reliability_percent: float) -> float:
    """a_1 of ISO 281 Table 12 at its printed reliabilities, the Weibull law it is built on between them."""
    if reliability_percent in RELIABILITY_TABLE:
        return RELIABILITY_TABLE[reliability_percent]
    r = reliability_percent / 100.0
    return 0.95 * (math.log(r) / math.log(0.9)) ** (2.0 / 3.0) + 0.05


def contamination_factor(level: str, pitch_diameter_mm: float) -> float:
    """e_C of ISO 281 Table 13 (the lower end of the level's range) for the bearing's d_m."""
    small, large = CONTAMINATION[level]
    return small if pitch_diameter_mm < 100.0 else large


def reference_viscosity_mm2_s(speed_rpm: float, pitch_diameter_mm: float) -> float:
    """nu_1 of ISO 281 (6.5.2.4): the viscosity needed for adequate lubrication at speed n and d_m."""
    n = abs(speed_rpm)
    if n < 1000.0:
        return 45000.0 * n ** -0.83 * pitch_diameter_mm ** -0.5
    return 4500.0 * n ** -0.5 * pitch_diameter_mm ** -0.5


def viscosity_at_mm2_s(temperature_C: float, nu_40: float, nu_100: float | None) -> float:
    """The oil's kinematic viscosity at ``temperature_C`` through its 40 °C and 100 °C values by ASTM D341
    (log10 log10(nu + 0.7) linear in log10 T, T in kelvin); at 40 °C the 40 °C value."""
    if temperature_C == 40.0 or nu_100 is None:
        return nu_40
    t40, t100, t = 313.15, 373.15, temperature_C + 273.15
    w40, w100 = (math.log10(math.log10(v + 0.7)) for v in (nu_40, nu_100))
    slope = (w100 - w40) / (math.log10(t100) - math.log10(t40))
    w = w40 + slope * (math.log10(t) - math.log10(t40))
    return 10.0 ** (10.0 ** w) - 0.7


# ISO 281 equations 8-13, radial bearings: (kappa bounds) -> (c, d) in c - d / kappa^e
_BALL = ((0.4, 2.2649, 0.054381), (1.0, 1.9987, 0.19087), (math.inf, 1.9987, 0.071739))
_ROLLER = ((0.4, 1.3993, 0.054381), (1.0, 1.2348, 0.19087), (math.inf, 1.2348, 0.071739))


def life_modification_factor(kappa: float, contamination_x: float, kind: str) -> float:
    """a_ISO of ISO 281 for a radial ball or roller bearing; ``contamination_x`` = e_C C_u / P. kappa is held in
    [0.1, 4]; a_ISO at most 50 (also where the bracket reaches 0: the fatigue limit is not exceeded)."""
    k = min(max(kappa, KAPPA_MIN), KAPPA_MAX)
    x = max(contamination_x, 0.0)
    table = _BALL if kind == "ball" else _ROLLER
    _, d, e = next(row for row in table if k < row[0])
    if kind == "ball":
        bracket = 1.0 - (2.5671 - d / k ** e) ** 0.83 * x ** (1.0 / 3.0)
        exponent = -9.3
    else:
        bracket = 1.0 - (1.5859 - d / k ** e) * x ** 0.4
        exponent = -9.185
    if bracket <= 0.0:
        return A_ISO_MAX
    return min(0.1 * bracket ** exponent, A_ISO_MAX)


def static_equivalent_load_N(radial_N: float, axial_N: float, X0: float, Y0: float) -> float:
    """ISO 76 radial bearing: P_0 = X_0 F_r + Y_0 F_a, never less than F_r."""
    fr, fa = abs(radial_N), abs(axial_N)
    return max(fr, X0 * fr + Y0 * fa)


def static_safety(static_rating_N: float, static_load_N: float) -> float | None:
    """s_0 = C_0 / P_0 (None for an unloaded bearing: no limit)."""
    return None if static_load_N <= 0.0 else static_rating_N / static_load_N


@record
class Lubrication:
    """What a_ISO needs of the oil and its cleanliness (``[lubricant]``)."""

    viscosity_mm2_s: float  # nu at the operating temperature
    contamination: str | None  # ISO 281 level (or None with e_C given)
    e_C: float | None  # given contamination factor (replaces the level's)

    def e_c(self, pitch_diameter_mm: float) -> float:
        if self.e_C is not None:
            return self.e_C
        assert self.contamination is not None
        return contamination_factor(self.contamination, pitch_diameter_mm)


@record
class ModifiedLife:
    """One load level's modified life: kappa, a_ISO, a_1 and L_nm (10^6 revolutions; None: unbounded). An
    unloaded level (P = 0) has no a_ISO (None): ISO 281's e_C C_u / P is not defined, and its life is unbounded."""

    kappa: float
    a_ISO: float | None
    a_1: float
    L_nm_Mrev: float | None


def modified_life(l10_Mrev: float | None, load_N: float, speed_rpm: float, kind: str, fatigue_limit_N: float,
                  pitch_diameter_mm: float, reliability_percent: float, lub: Lubrication) -> ModifiedLife:
    """kappa, a_ISO, a_1 and L_nm = a_1 a_ISO L_10 at one load level P and speed n; an unloaded level (P = 0)
    has neither a_ISO nor L_nm (None, as its L_10)."""
    a1 = reliability_factor(reliability_percent)
    kappa = (lub.viscosity_mm2_s / reference_viscosity_mm2_s(speed_rpm, pitch_diameter_mm) if speed_rpm
             else KAPPA_MIN)  # a standing bearing builds no film
    if load_N <= 0.0:
        return ModifiedLife(kappa, None, a1, None)
    a_iso = life_modification_factor(kappa, lub.e_c(pitch_diameter_mm) * fatigue_limit_N / load_N, kind)
    return ModifiedLife(kappa, a_iso, a1, None if l10_Mrev is None else a1 * a_iso * l10_Mrev)
