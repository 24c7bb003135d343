"""The accuracy study's method paragraph names the grid that ran: a file rtol off the ladder is one run of the file's
method, not a rung of every method (stand-in solver of test_report_fakes: no integration)."""

from __future__ import annotations

from test_report_fakes import FakeSolver, fake_design

from gearcli.io.report_sections import method_paragraph
from gearcli.report import LadderSpec, accuracy_study


def _study(file_method: str, file_rtol: float):
    design = fake_design()
    solver = FakeSolver(design)
    study = accuracy_study(solver, file_method=file_method, file_rtol=file_rtol,
                           spec=LadderSpec(rtols=(1e-4, 1e-6), methods=("auto", "DOP853", "Radau")))
    return study, solver.calls


def test_a_file_rtol_off_the_ladder_is_named_as_the_files_own_run_not_as_a_rung_of_every_method():
    study, calls = _study("auto", 3e-4)
    # what ran, by hand: auto, RK45 (DOP853 swapped for its sibling: auto resolves to DOP853), Radau at 1e-4, 1e-6;
    # the file's auto at 3e-4 once; the reference pair
    ladder = {(m, r) for m, r in calls if r in (1e-4, 1e-6)}
    assert ladder == {(m, r) for m in ("auto", "RK45", "Radau") for r in (1e-4, 1e-6)}
    assert [(m, r) for m, r in calls if r == 3e-4] == [("auto", 3e-4)]
    assert study.file_run_extra
    text = method_paragraph(study)
    assert "The scene was run with auto, RK45, Radau at rtol 0.0001, 1e-06, and the file's own setting, auto at " \
           "rtol 0.0003." in text


def test_a_file_setting_on_the_ladder_adds_nothing():
    study, _ = _study("auto", 1e-6)
    assert not study.file_run_extra
    assert "The scene was run with auto, RK45, Radau at rtol 0.0001, 1e-06. " in method_paragraph(study)


def test_a_file_method_swapped_for_its_sibling_is_its_own_run():
    # the file asks DOP853 at 1e-6; the ladder runs RK45 in its place (auto is DOP853): DOP853 1e-6 runs besides
    study, calls = _study("DOP853", 1e-6)
    assert ("DOP853", 1e-6) in calls and study.file_run_extra
    text = method_paragraph(study)
    assert "The scene was run with auto, RK45, Radau at rtol 0.0001, 1e-06, and the file's own setting, DOP853 at " \
           "rtol 1e-06." in text
