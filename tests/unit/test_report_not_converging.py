"""The work-precision study on a quantity that does not converge with rtol (tr21b).

An unloaded rattle (configs/extreme/rattle_zero_load.toml, 0.25 s) is chaotic: its window-mean F_t on each
rung departed from the DOP853 1e-12 reference by 0.33, 1.02, 0.37, 0.73 (auto, rtol 1e-4 .. 1e-7), RK45 1.15 ..
0.32, Radau 0.51 .. 0.22, all ~30-100x the reference's uncertainty 1.1e-2; the study advised "tighten the
reference". A converging method of order p drops its error ~10^p-fold over three decades of rtol; the note
names the quantity that falls by less than 10x on every method, and only when clearly above the uncertainty.
"""

from __future__ import annotations

from gearcli.report.accuracy import not_converging
from gearcli.report.result import AccuracyRun

RTOLS = (1e-4, 1e-5, 1e-6, 1e-7)


def _runs(errors: dict[str, tuple[float, ...]], speed=1e-9, peak=1e-9) -> list[AccuracyRun]:
    return [AccuracyRun(m, m, rtol, 0.01, 1000, 0, 0, speed, e, peak, {}, False)
            for m, es in errors.items() for rtol, e in zip(RTOLS, es, strict=True)]


def test_the_rattles_mean_force_is_named():
    runs = _runs({"auto": (0.331, 1.02, 0.366, 0.731), "RK45": (1.15, 0.682, 0.396, 0.323),
                  "Radau": (0.509, 0.445, 0.430, 0.217)})
    assert not_converging(runs, 1.1e-2) == ["error_mean_force"]


def test_a_converging_ladder_is_not():
    # 5th-order errors, C rtol^(5/4) ... and one method already at the reference's resolution
    runs = _runs({"auto": tuple(3.0 * r ** 1.25 for r in RTOLS), "RK45": tuple(50.0 * r for r in RTOLS),
                  "Radau": (2e-6, 2e-6, 2e-6, 2e-6)})
    assert not_converging(runs, 1e-6) == []


def test_one_converging_method_clears_the_quantity():
    runs = _runs({"auto": (0.3, 0.3, 0.3, 0.3), "RK45": (1e-2, 1e-3, 1e-4, 1e-5)})
    assert not_converging(runs, 1e-7) == []


def test_a_flat_error_at_the_references_uncertainty_is_the_references():
    runs = _runs({"auto": (5e-3, 5e-3, 5e-3, 5e-3), "RK45": (8e-3, 6e-3, 5e-3, 5e-3)})
    assert not_converging(runs, 1e-3) == []  # within 10x the uncertainty: flat because the reference is
