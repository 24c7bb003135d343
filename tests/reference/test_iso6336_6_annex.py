"""ISO 6336-6:2019 Annex C (the pitting damage of a load spectrum) through the code ``gearcli life`` uses.

Source: Table C.2 of the annex as transcribed in the public repository github.com/gfsReboucas/Drivetrain
(``tests/reference/data/iso6336_6_annex_c/``, its README gives the provenance). A case-carburized pinion
(σ_Hlim 1500 N/mm²) under 42 loaded torque bins; per bin the table prints the stress σ_H·S_H, Z_NT, the cycles
to failure N_i and the damage U_i = n_i/N_i; the U_i sum to 0.99945 (the annex finds S_H by making D = 1).

How each column is read:
- ``n_30y`` (n_i): the load cycles of 30 years: the bin's time over the recorded 70 days (whole seconds) times
  the pinion speed, scaled by 30 × 365 days / 70 days (checked below, then used as printed).
- ``sigma_HxS_H``: the stress at which the bin meets the S–N curve (σ_H of the bin times the spectrum's S_H),
  printed to 1 N/mm².
- ``N_i``: cycles to failure on the S–N curve of ISO 6336-2 for the material group (Table 2, no pitting
  permitted: Z_NT 1.6 up to 1e5 cycles, 1.0 at 5e7, 0.85 at 1e10, power laws between, the last slope continued
  as ISO 6336-6 states), printed to 3 significant digits.
- ``Z_NT``: σ_i / σ_HG,ref, the life factor the bin's stress asks for (2 decimals; not capped at the static 1.6),
  checked to one unit of its last digit: bins 31 and 44 print 1.37 and 0.91 where their own stress and N_i both
  give 1.364 and 0.905 (rounding slips of the table).
- ``U_i``: n_i / N_i, printed to 3 significant digits.

The curve's endurance stress σ_HG,ref = σ_Hlim Z_L Z_v Z_R Z_W Z_X is not printed to more digits than its factors
(1500 × 1.02 × 0.943 × 1.01 = 1457.2, each factor rounded: ±0.6 %). The table fixes it better: every finite-life
bin gives σ_i (N_i/5e7)^(1/k); their geometric mean is used, and checked against the factors' product.

Tolerance of a printed figure: half a unit of its last digit, plus what the printed stress's own rounding
(±0.5 N/mm²) moves it through the curve's exponent k (N ∝ σ^-k: k × 0.5/σ relative).
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np
import pytest

from gearcli.design import rating_factors as rf
from gearcli.life.miner import SNCurve, miner_damage
from gearcli.life.run import _from_raw

DATA = Path(__file__).parent / "data" / "iso6336_6_annex_c" / "tableC2_damage.csv"
YEARS_OVER_RECORD = 30.0 * 365.0 / 70.0  # 30 years of operation over the 70 recorded days
TABLE_SUM = 0.99945
# ISO 6336-2:2006 Table 2, St, V, GGG (perl.), Eh, IF, no pitting permitted, written out by hand
NODES = ((1e5, 1.6), (5e7, 1.0), (1e10, 0.85))
K_FINITE = math.log(5e7 / 1e5) / math.log(1.6 / 1.0)  # 13.2225: N ∝ σ^-k from the static node to the knee
K_LONG = math.log(1e10 / 5e7) / math.log(1.0 / 0.85)  # 32.601 beyond the knee


def _rows() -> list[dict[str, float]]:
    with DATA.open() as fh:
        rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(fh)]
    return [r for r in rows if r["N_i"] > 0]  # bins 1-2 and 45-48 carry no cycles (printed 0: not evaluated)


def _half_unit(value: float, digits: int) -> float:
    """Half a unit of the last of ``digits`` significant digits of ``value``."""
    return 0.5 * 10.0 ** (math.floor(math.log10(abs(value))) - digits + 1)


def _sigma_ref(rows) -> tuple[float, float]:
    """The endurance stress (Z_NT = 1) the finite-life bins imply, and its standard error."""
    fin = [r for r in rows if r["N_i"] < 5e7]
    refs = np.array([r["sigma_HxS_H"] * (r["N_i"] / 5e7) ** (1.0 / K_FINITE) for r in fin])
    return float(np.exp(np.log(refs).mean())), float(refs.std(ddof=1) / math.sqrt(len(refs)))


def _exponent(stress: float, ref: float) -> float:
    return K_FINITE if stress >= ref else K_LONG


def test_library_curve_is_the_standards():
    """The life command's curve for a case-carburized flank is ISO 6336-2's Table 2 as written above."""
    assert rf.znt_curve("case_carburized") == NODES


def test_table_reads_as_iso_6336_2_curve():
    """Independent of the library: a free fit of ln N_i against ln σ_i over the finite-life bins gives the
    exponent of the standard's curve, and the endurance stress the table implies is the factors' product."""
    rows = _rows()
    fin = [r for r in rows if r["N_i"] < 5e7]
    slope = np.polyfit([math.log(r["sigma_HxS_H"]) for r in fin], [math.log(r["N_i"]) for r in fin], 1)[0]
    # 40 bins, stresses rounded to 1 N/mm² (0.02 %): the fitted slope is good to a few 0.1 %
    np.testing.assert_allclose(-slope, K_FINITE, rtol=5e-3)
    ref, se = _sigma_ref(rows)
    assert se < 0.05  # the 40 bins agree on one endurance stress to 0.003 %
    # σ_Hlim Z_L Z_v Z_R (Z_W = Z_X = 1) = 1457.2, the factors printed to 3 digits (Z_R to 2): ±0.6 %
    np.testing.assert_allclose(ref, 1500.0 * 1.02 * 0.943 * 1.01, rtol=6e-3)


def test_load_cycles_column():
    """n_30y = time × speed / 60 × 30 years / 70 days (time in whole seconds, n printed to 4 digits)."""
    for r in _rows():
        n = r["time_70d"] * r["n_rpm"] / 60.0 * YEARS_OVER_RECORD
        tol = _half_unit(r["n_30y"], 4) + n * 0.5 / r["time_70d"]
        assert abs(n - r["n_30y"]) <= tol, r["Bin_No"]


def _life(rows, ref):
    """Table C.2 through the life command's damage sum: each bin (stress, cycles) on the member's S–N curve
    exactly as ``gearcli life`` builds it (``SNCurve(znt_curve(treatment), σ_HG/Z_NT, "iso", optimum)``)."""
    curve = SNCurve(rf.znt_curve("case_carburized"), ref, "iso", False)
    raw = [(f"bin {int(r['Bin_No'])}", 0.0, r["sigma_HxS_H"], r["n_30y"], curve) for r in rows]
    return curve, _from_raw(raw, "pitting", 30.0 * 365.0 * 24.0)


def test_cycles_to_failure_and_damage_per_bin():
    rows = _rows()
    ref, se = _sigma_ref(rows)
    _, life = _life(rows, ref)
    assert len(life.bins) == 42
    for r, b in zip(rows, life.bins, strict=True):
        k = _exponent(r["sigma_HxS_H"], ref)
        spread = k * (0.5 / r["sigma_HxS_H"] + 2.0 * se / ref)  # the printed stress's rounding, σ_ref's error
        tol_n = _half_unit(r["N_i"], 3) / r["N_i"] + spread
        assert b.cycles_to_failure == pytest.approx(r["N_i"], rel=tol_n), r["Bin_No"]
        tol_u = _half_unit(r["U_i"], 3) / r["U_i"] + _half_unit(r["n_30y"], 4) / r["n_30y"] + spread
        assert b.damage == pytest.approx(r["U_i"], rel=tol_u), r["Bin_No"]
        assert abs(r["sigma_HxS_H"] / ref - r["Z_NT"]) <= 0.01, r["Bin_No"]


def test_damage_sum_and_spectrum_safety():
    """D = Σ U_i = 0.99945 (printed to 5 digits); the annex's S_H makes D = 1, so the spectrum safety (the load
    multiplier to D = 1) on the table's stresses is 1."""
    rows = _rows()
    ref, se = _sigma_ref(rows)
    curve, life = _life(rows, ref)
    # the sum inherits the bins' stress rounding; bound: Σ U_i k_i (0.5/σ_i + 2 se/σ_ref)
    tol = sum(r["U_i"] * _exponent(r["sigma_HxS_H"], ref) * (0.5 / r["sigma_HxS_H"] + 2.0 * se / ref)
              for r in rows)
    assert tol < 4e-3
    assert life.damage == pytest.approx(TABLE_SUM, abs=tol)
    assert life.damage == pytest.approx(
        miner_damage([r["sigma_HxS_H"] for r in rows], [r["n_30y"] for r in rows], [curve] * len(rows)), rel=1e-12)
    # pitting: stress ∝ √load, D ∝ s^(k/2) near D = 1, so |s − 1| ≲ (2/k) |D − 1|
    assert life.safety == pytest.approx(1.0, abs=2.0 / K_FINITE * (abs(TABLE_SUM - 1.0) + tol))


FIGURE = Path(__file__).parent / "data" / "iso6336_6_annex_c" / "figC1_sn_curves_digitised.csv"


def test_curve_is_the_annex_figure_c1():
    """Figure C.1's S–N curve (curve ``SN``, digitised: a few 0.1 % of noise) against the curve ``gearcli life``
    builds with the endurance stress the table implies: on the finite-life line (1.2e5 to 5e7 cycles) and beyond
    the knee (the 0.85-at-1e10 slope, to 6e9 cycles) within 1 %; up to the static node the figure is flat at the
    static strength 1.6 σ_HG,ref, the curve's value at its static node (the damage sum continues the finite line
    above it, as Table C.2's bins 3-6 do: a warning says so)."""
    with FIGURE.open() as fh:
        pts = [(float(r["N_SN"]), float(r["sigma_SN"])) for r in csv.DictReader(fh) if r["N_SN"]]
    ref, _ = _sigma_ref(_rows())
    curve = SNCurve(rf.znt_curve("case_carburized"), ref, "iso", False)
    sloped = [(n, s) for n, s in pts if 1.2e5 <= n <= 6e9]
    flat = [(n, s) for n, s in pts if n <= 8e4]
    assert len(sloped) > 40 and len(flat) > 30
    for n, s in sloped:
        assert curve.stress_at(n) == pytest.approx(s, rel=1e-2), n
    np.testing.assert_allclose([s for _, s in flat], curve.stress_at(curve.static_cycles), rtol=5e-3)
    np.testing.assert_allclose(curve.stress_at(curve.static_cycles), 1.6 * ref, rtol=1e-12)
