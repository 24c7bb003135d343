"""The accuracy study's "< u": each compared quantity is judged against the reference's own resolution of that
quantity (``reference.differences[q]``, the reference against its check run), not against the largest of the
three (``reference.uncertainty``). A run-up peak that two tight runs place 1e-8 apart says nothing about the
window-mean output speed they agree on to 1e-14: a rung's speed error of 1e-10 is resolved and is printed as a
number, not as "< 1.0e-08". The verdict ``meets_accuracy`` is unchanged (max(e_q, u_q) <= target for every q is
max(e_q) <= target and max(u_q) <= target, the old test). Figures by hand from the synthetic runs' known errors."""

from __future__ import annotations

from numpy.testing import assert_allclose
from test_report_fakes import fake_design, fake_simulation

from gearcli.io.report_sections import error_cell
from gearcli.report.accuracy import measure, reference_run


def _study_pieces(accuracy: float):
    design = fake_design()
    ref = fake_simulation(design, method="DOP853", rtol=1e-12)  # exact
    check = fake_simulation(design, speed_err=1e-14, force_err=1e-12, peak_err=1e-8, method="Radau", rtol=1e-10)
    reference = reference_run(ref, check, 1e-12, 1e-10)
    rung = fake_simulation(design, speed_err=1e-10, force_err=1e-9, peak_err=1e-9, method="DOP853", rtol=1e-6)
    return reference, measure(rung, "DOP853", 1e-6, reference, accuracy, file_settings=True)


def test_each_quantity_is_below_resolution_against_its_own_difference():
    reference, run = _study_pieces(1e-7)
    # the reference's differences by hand: the check's relative errors 1e-14, 1e-12, 1e-8; uncertainty their max
    assert_allclose([reference.differences[q] for q in ("speed", "mean_force", "peak_force")],
                    [1e-14, 1e-12, 1e-8], rtol=0.01)  # 1 + 1e-14 in binary: 0.4 % off
    assert_allclose(reference.uncertainty, 1e-8, rtol=1e-6)
    assert_allclose([run.error_speed, run.error_mean_force, run.error_peak_force], [1e-10, 1e-9, 1e-9], rtol=1e-3)
    # 1e-10 > 1e-14 and 1e-9 > 1e-12: resolved; 1e-9 < 1e-8: below the peak's resolution
    assert run.below_reference_resolution == {"speed": False, "mean_force": False, "peak_force": True}
    cells = [error_cell(run, q, reference) for q in ("speed", "mean_force", "peak_force")]
    assert cells == ["1.00e-10", "1.00e-09", "< 1.0e-08"]


def test_the_verdict_still_takes_every_quantity_and_its_resolution():
    assert _study_pieces(1e-7)[1].meets_accuracy  # every error and every resolution within 1e-7
    assert not _study_pieces(5e-9)[1].meets_accuracy  # the peak's resolution 1e-8 exceeds 5e-9
