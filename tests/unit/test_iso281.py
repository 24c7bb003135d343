"""ISO 281:2007 modified rating life and ISO 76 static safety, against the standard's formulas written out by hand.

No bearing maker's worked example of ISO's a_ISO (not SKF's a_SKF) with all of its inputs printed could be
found for this test; the figures below are computed by hand from ISO 281:2007's equations, quoted in each test:
eq. (8)-(13) for a_ISO of radial bearings, 6.5.2.4 for nu_1, Table 12 for a_1, Table 13 for e_C.
"""

from __future__ import annotations

import math

import pytest
from numpy.testing import assert_allclose

from gearcli.design import iso281


def test_reliability_table_is_the_weibull_law_it_is_built_on():
    """ISO 281 Table 12 prints a_1 to two or three digits; each is 0.95 (ln R / ln 0.9)^(2/3) + 0.05
    (ISO/TR 1281-2) rounded: the transcription is checked against the law, not against itself."""
    for r, a1 in iso281.RELIABILITY_TABLE.items():
        law = 0.95 * (math.log(r / 100) / math.log(0.9)) ** (2 / 3) + 0.05
        digits = 2 if a1 >= 0.1 else 3
        assert round(law, digits) == pytest.approx(a1, abs=1e-12), r
    # between the table's reliabilities: the law itself
    assert_allclose(iso281.reliability_factor(99.5), 0.95 * (math.log(0.995) / math.log(0.9)) ** (2 / 3) + 0.05,
                    rtol=1e-12)
    assert iso281.reliability_factor(90.0) == 1.0


def test_reference_viscosity_by_hand():
    """nu_1 = 45000 n^-0.83 d_m^-0.5 (n < 1000 r/min), 4500 n^-0.5 d_m^-0.5 (n >= 1000)."""
    # n = 1000, d_m = 100: 4500 / sqrt(1000) / 10 = 14.2302...
    assert_allclose(iso281.reference_viscosity_mm2_s(1000.0, 100.0), 4500 / math.sqrt(1000) / 10, rtol=1e-14)
    assert_allclose(iso281.reference_viscosity_mm2_s(1000.0, 100.0), 14.2302, atol=1e-4)
    # n = 300, d_m = 250: 45000 * 300^-0.83 / sqrt(250)
    assert_allclose(iso281.reference_viscosity_mm2_s(300.0, 250.0), 45000 * 300 ** -0.83 / math.sqrt(250), rtol=1e-14)
    # the two branches nearly meet at 1000 r/min (45000 * 1000^-0.83 = 145.2 vs 4500 * 1000^-0.5 = 142.3)
    lo = iso281.reference_viscosity_mm2_s(999.999, 100.0)
    hi = iso281.reference_viscosity_mm2_s(1000.0, 100.0)
    assert abs(lo / hi - 1) < 0.025


def test_contamination_levels_of_table_13():
    """e_C by d_m below / from 100 mm, the lower end of each printed range."""
    assert iso281.contamination_factor("normal", 99.9) == 0.5
    assert iso281.contamination_factor("normal", 100.0) == 0.6
    assert iso281.contamination_factor("extreme", 50.0) == 1.0
    assert iso281.contamination_factor("very_severe", 500.0) == 0.0


def _ball_by_hand(kappa: float, x: float) -> float:
    """ISO 281 eq. (8)-(10), radial ball bearings."""
    if kappa < 0.4:
        c = 2.5671 - 2.2649 / kappa**0.054381
    elif kappa < 1.0:
        c = 2.5671 - 1.9987 / kappa**0.19087
    else:
        c = 2.5671 - 1.9987 / kappa**0.071739
    return 0.1 * (1 - c**0.83 * x ** (1 / 3)) ** -9.3


def _roller_by_hand(kappa: float, x: float) -> float:
    """ISO 281 eq. (11)-(13), radial roller bearings."""
    if kappa < 0.4:
        c = 1.5859 - 1.3993 / kappa**0.054381
    elif kappa < 1.0:
        c = 1.5859 - 1.2348 / kappa**0.19087
    else:
        c = 1.5859 - 1.2348 / kappa**0.071739
    return 0.1 * (1 - c * x**0.4) ** -9.185


@pytest.mark.parametrize("kappa", [0.15, 0.3, 0.5, 0.8, 1.0, 2.0, 3.9])
@pytest.mark.parametrize("x", [0.0, 0.05, 0.2, 0.5])
def test_a_iso_against_the_formulas(kappa, x):
    assert_allclose(iso281.life_modification_factor(kappa, x, "ball"), min(_ball_by_hand(kappa, x), 50.0),
                    rtol=1e-13)
    assert_allclose(iso281.life_modification_factor(kappa, x, "roller"), min(_roller_by_hand(kappa, x), 50.0),
                    rtol=1e-13)


def test_a_iso_worked_by_hand():
    """A roller bearing, kappa = 2, e_C C_u / P = 0.6 * 50 kN / 100 kN = 0.3:
    2^0.071739 = exp(0.049725) = 1.050982; 1.2348 / 1.050982 = 1.174900; 1.5859 - 1.174900 = 0.411000;
    0.3^0.4 = exp(-0.481589) = 0.617801; 1 - 0.411000 * 0.617801 = 0.746084;
    0.746084^-9.185 = exp(9.185 * 0.292920) = exp(2.690471) = 14.7382 -> a_ISO = 1.47382 (six digits carried)."""
    assert_allclose(iso281.life_modification_factor(2.0, 0.3, "roller"), 1.47382, atol=2e-5)
    # x = 0: no fatigue-limit benefit, a_ISO = 0.1 whatever kappa
    assert iso281.life_modification_factor(1.5, 0.0, "ball") == pytest.approx(0.1, rel=1e-14)


def test_a_iso_limits():
    # kappa above 4 is taken as 4; a_ISO never above 50 (and 50 where the bracket reaches zero)
    assert iso281.life_modification_factor(10.0, 0.1, "ball") == iso281.life_modification_factor(4.0, 0.1, "ball")
    assert iso281.life_modification_factor(4.0, 5.0, "roller") == 50.0
    assert iso281.life_modification_factor(4.0, 100.0, "ball") == 50.0
    # below kappa 0.1 ISO 281 does not apply: taken at 0.1 (the caller warns)
    assert iso281.life_modification_factor(0.01, 0.2, "roller") == iso281.life_modification_factor(0.1, 0.2, "roller")


def test_a_iso_is_continuous_at_the_branch_limits():
    """The printed constants make the three branches meet at kappa = 0.4 and 1 (to the constants' 5 digits)."""
    for kind in ("ball", "roller"):
        for k in (0.4, 1.0):
            below = iso281.life_modification_factor(k * (1 - 1e-12), 0.3, kind)
            at = iso281.life_modification_factor(k, 0.3, kind)
            assert_allclose(below, at, rtol=2e-3)


def test_viscosity_through_40_and_100_degrees():
    """ASTM D341: log log (nu + 0.7) linear in log T; it returns the given values at 40 and 100 °C and, for an
    ISO VG 220 oil with 19 mm²/s at 100 °C, the value of the same straight line at 70 °C worked by hand."""
    assert_allclose(iso281.viscosity_at_mm2_s(100.0, 220.0, 19.0), 19.0, rtol=1e-12)
    assert iso281.viscosity_at_mm2_s(40.0, 220.0, 19.0) == 220.0
    w40, w100 = math.log10(math.log10(220.7)), math.log10(math.log10(19.7))
    b = (w100 - w40) / (math.log10(373.15) - math.log10(313.15))
    w70 = w40 + b * (math.log10(343.15) - math.log10(313.15))
    assert_allclose(iso281.viscosity_at_mm2_s(70.0, 220.0, 19.0), 10 ** 10**w70 - 0.7, rtol=1e-12)
    assert 50.0 < iso281.viscosity_at_mm2_s(70.0, 220.0, 19.0) < 70.0  # a VG 220 gear oil at 70 °C: about 60


def test_static_safety_by_hand():
    """ISO 76: P_0 = X_0 F_r + Y_0 F_a, not less than F_r; s_0 = C_0 / P_0."""
    # 0.6 * 10 kN + 0.5 * 8 kN = 10 kN = F_r: both give 10 kN
    assert_allclose(iso281.static_equivalent_load_N(10e3, 8e3, 0.6, 0.5), 10e3, rtol=1e-15)
    # 0.6 * 10 kN + 0.5 * 20 kN = 16 kN > F_r
    assert_allclose(iso281.static_equivalent_load_N(10e3, -20e3, 0.6, 0.5), 16e3, rtol=1e-15)
    assert_allclose(iso281.static_safety(95e3, 16e3), 95 / 16, rtol=1e-15)
    assert iso281.static_safety(95e3, 0.0) is None


def test_modified_life_by_hand():
    """L_nm = a_1 a_ISO L_10 at one level: a ball bearing, C = 60 kN, P = 6 kN, C_u = 1.5 kN, d_m = 60 mm,
    n = 1500 r/min, nu = 30 mm²/s, "normal" cleanliness (e_C 0.5 below d_m 100 mm), 99 % reliability."""
    lub = iso281.Lubrication(30.0, "normal", None)
    l10 = (60.0 / 6.0) ** 3
    m = iso281.modified_life(l10, 6e3, 1500.0, "ball", 1.5e3, 60.0, 99.0, lub)
    nu1 = 4500 / math.sqrt(1500) / math.sqrt(60)
    assert_allclose(m.kappa, 30.0 / nu1, rtol=1e-14)
    assert_allclose(m.a_ISO, _ball_by_hand(30.0 / nu1, 0.5 * 1.5 / 6.0), rtol=1e-13)
    assert m.a_1 == 0.25
    assert_allclose(m.L_nm_Mrev, 0.25 * m.a_ISO * 1000.0, rtol=1e-14)


def test_an_unloaded_level_has_no_a_iso():
    """P = 0: ISO 281's e_C C_u / P is not defined and L10 is unbounded, so there is no a_ISO (None, not the cap
    50) and no L_nm; kappa = nu / nu_1 is the oil's and the speed's (nu_1 = 4500 n^-0.5 d_m^-0.5 at 1500 r/min)."""
    lub = iso281.Lubrication(30.0, "normal", None)
    m = iso281.modified_life(None, 0.0, 1500.0, "ball", 1.5e3, 60.0, 99.0, lub)
    assert m.a_ISO is None and m.L_nm_Mrev is None and m.a_1 == 0.25
    assert_allclose(m.kappa, 30.0 / (4500.0 / math.sqrt(1500.0) / math.sqrt(60.0)), rtol=1e-12)
