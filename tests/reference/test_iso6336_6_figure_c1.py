"""The pitting S–N curve of ISO 6336-6:2019 Annex C, Figure C.1, against the life factor Z_NT gearcli rates with.

Source: Figure C.1 as digitised in the public repository github.com/gfsReboucas/Drivetrain (``data/Fig_C1.csv``,
copied to ``tests/reference/data/iso6336_6_annex_c/``; its README gives the provenance). The curve ``SN`` is the
case-carburized pinion's flank: σ(N) = σ_HG,ref Z_NT(N), with σ_HG,ref = σ_Hlim Z_L Z_v Z_R Z_W Z_X = 1500 · 1.02 ·
0.943 · 1.01 = 1457.2 N/mm² (the annex's factors, as tests/reference/test_iso6336_6_annex.py quotes them) and Z_NT
of ISO 6336-2:2006 Table 2 (Eh, no pitting permitted): 1.6 up to 1e5 cycles (the static plateau, 2331 N/mm²), 1.0 at
5e7, 0.85 at 1e10 ("normal" quality), straight in log–log between.

What it checks, independently of the Table C.2 test: the plateau below 1e5, the knee at 5e7 and the slope on either
side, point by point over 113 digitised points from 1e2 to 1e10 cycles.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np

from gearcli.design import rating_factors as rf

DATA = Path(__file__).parent / "data" / "iso6336_6_annex_c" / "figC1_sn_curves_digitised.csv"
SIGMA_REF = 1500.0 * 1.02 * 0.943 * 1.01  # σ_Hlim Z_L Z_v Z_R, each printed to 3 digits (Z_R to 2): ±0.6 %


def _points() -> list[tuple[float, float]]:
    with DATA.open() as fh:
        return [(float(r["N_SN"]), float(r["sigma_SN"])) for r in csv.DictReader(fh) if r["N_SN"]]


def _hand_znt(n: float) -> float:
    """ISO 6336-2:2006 Table 2 written out: 1.6 (N ≤ 1e5), (5e7/N)^0.0756 up to 5e7, (5e7/N)^0.0307 to 1e10
    (exponents log 1.6/log 500 = 0.075629 and log(1/0.85)/log 200 = 0.030673), 0.85 beyond."""
    if n <= 1e5:
        return 1.6
    if n <= 5e7:
        return (5e7 / n) ** (math.log(1.6) / math.log(500.0))
    return max((5e7 / n) ** (math.log(1.0 / 0.85) / math.log(200.0)), 0.85)


def test_figure_c1_is_the_life_factor_curve():
    points = _points()
    assert len(points) == 113
    n = np.array([p[0] for p in points])
    sigma = np.array([p[1] for p in points])
    library = np.array([rf.life_factor_pitting("case_carburized", x, "normal") for x in n])
    np.testing.assert_allclose(library, [_hand_znt(x) for x in n], rtol=1e-12)
    residual = sigma / (SIGMA_REF * library) - 1.0
    # digitisation noise: every point within 0.6 %, no bias beyond 0.1 % (mean −0.02 %, std 0.14 % measured)
    assert np.max(np.abs(residual)) < 6e-3
    assert abs(residual.mean()) < 1e-3
    # the plateau is the static Z_NT 1.6 of the same endurance stress: 2329 N/mm² digitised, 1.6 · 1457.2 = 2331.5
    plateau = sigma[n < 1e5]
    np.testing.assert_allclose(plateau.mean() / 1.6, SIGMA_REF, rtol=3e-3)
    # the tail: the last digitised point, 9.86e9 cycles, at 0.85 of the endurance stress (1238.6 N/mm²; the curve
    # gives 0.8504 there, 1239.2): 1239.8 digitised
    assert n[-1] > 9.8e9
    np.testing.assert_allclose(sigma[-1], SIGMA_REF * 0.85, rtol=2e-3)
