"""A bearing maker's worked example: SKF Rolling bearings catalogue, "Calculation examples", example 1 ("Basic
rating life and SKF rating life"), as published on yumpu.com (document 55668573, "SKF - Rolling Bearings", page
92): an SKF Explorer 6309 deep groove ball bearing at 3 000 r/min under a constant radial load F_r = 10 kN, oil
of 20 mm²/s at the operating temperature, 90 % reliability, very clean conditions.

What the example prints and how it was obtained:
- C = 55,3 kN and P_u = 1,34 kN from the product table; P = F_r = 10 kN (purely radial).
- L10 = (55,3/10)³ = 169 million revolutions and L10h = 10⁶/(60 · 3 000) · 169 = 940 h: ISO 281's basic rating
  life, computed, printed to three digits. **Asserted here to the printed digits through gearcli's own L10 and
  L10h** (``design.shafts``, the functions ``design``, ``simulate`` and ``life`` use).
- d_m = 0,5 (45 + 100) = 72,5 mm and P_u/P = 0,134: arithmetic on catalogue data, asserted.
- ν_1 = 8,15 mm²/s "from diagram 5", κ = 20/8,15 = 2,45, and the SKF rating life with a_SKF read from the
  catalogue's diagram on its SKF Explorer scale. These are **not ISO 281's figures**: the catalogue's ν_1 diagram
  is SKF's own (revised from ISO's; ISO 281:2007, 6.5.2.4, gives ν_1 = 4500 n^-0.5 d_m^-0.5 = 9,649 mm²/s here)
  and a_SKF on the Explorer scale is SKF's model for its own bearings, not ISO's a_ISO (equations 8-10). gearcli
  computes ISO's; the example's κ and a_SKF are therefore not asserted (a diagram reading to one or two digits
  would in any case support no more than that). The ISO figures for the example's inputs are written out by hand
  below instead.

No bearing maker's worked example of ISO's a_ISO itself with all its inputs printed was found in the reference
library (SKF, Schaeffler/FAG, NSK, NMB, ISO/TR 1281-2 were searched: docs/bearings.md, "Checked against").
"""

from __future__ import annotations

import math

from numpy.testing import assert_allclose

from gearcli.design import iso281, shafts

C_N, P_N, PU_N, N_RPM = 55.3e3, 10e3, 1.34e3, 3000.0
D_BORE, D_OUT = 45.0, 100.0


def test_basic_rating_life_as_printed():
    l10 = shafts.basic_life_Mrev(C_N, P_N, "ball")
    assert l10 is not None
    assert_allclose(l10, 169, atol=0.5)  # "L10 = 169 million revolutions" (169.11)
    assert_allclose(shafts.life_hours(l10, N_RPM), 940, atol=0.5)  # "L10h = 940 operating hours" (939.51)
    # the catalogue multiplies its rounded 169 (938.9 h) and prints 940; gearcli's unrounded 169.11 gives 939.51 h


def test_catalogue_arithmetic():
    assert 0.5 * (D_BORE + D_OUT) == 72.5  # "d_m = 0,5 (45 + 100) = 72,5 mm"
    assert_allclose(PU_N / P_N, 0.134, atol=5e-4)  # "P_u/P = 1,34/10 = 0,134"


def test_the_same_bearing_by_iso_281():
    """ISO 281:2007 for the example's inputs, written out (not the catalogue's SKF figures, see the module text).
    ν_1 = 4500 · 3000^-0.5 · 72.5^-0.5 = 4500 / 54.7723 / 8.51469 = 9.64901 mm²/s; κ = 20/9.64901 = 2.07275.
    With e_C = 0.8 (ISO 281 Table 13, "high cleanliness", d_m < 100 mm: 0.8 … 0.6, its upper end):
    e_C C_u/P = 0.1072; eq. (10), κ ≥ 1: 2.07275^0.071739 = e^0.052289 = 1.053680; 1.9987/1.053680 = 1.896876;
    2.5671 − 1.896876 = 0.670224; ^0.83 = e^(−0.332119) = 0.717425; 0.1072^(1/3) = 0.475040;
    1 − 0.717425 · 0.475040 = 0.659194; ^−9.3 = e^3.875673 = 48.21; a_ISO = 4.821; L_10m = 4.821 · 169.11 = 815."""
    nu1 = iso281.reference_viscosity_mm2_s(N_RPM, 72.5)
    assert_allclose(nu1, 9.64901, atol=5e-6)
    lub = iso281.Lubrication(20.0, None, 0.8)
    m = iso281.modified_life(shafts.basic_life_Mrev(C_N, P_N, "ball"), P_N, N_RPM, "ball", PU_N, 72.5, 90.0, lub)
    assert_allclose(m.kappa, 2.07275, atol=5e-6)
    assert_allclose(m.a_ISO, 4.821, atol=2e-3)  # the hand chain carries six digits into an exponent of 9.3
    assert m.a_1 == 1.0
    assert m.L_nm_Mrev is not None
    assert_allclose(m.L_nm_Mrev, 815, atol=1.0)
    assert math.isclose(m.L_nm_Mrev, m.a_ISO * 169.112377, rel_tol=1e-6)
