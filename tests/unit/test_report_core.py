"""Unit tests of the report core on synthetic results (no solver): spectrum, comparison, accuracy study.

The synthetic runs have a known error law, error = C_method * rtol^p_method, so the study's errors,
flags and recommendation can be checked against numbers computed by hand.
"""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_allclose
from test_report_fakes import LAW, FakeSolver, fake_design, fake_report, fake_simulation

from gearcli.report import LadderSpec, accuracy_study, force_spectrum, relative_errors
from gearcli.report.accuracy import ladder_methods, meets, struggling, struggling_text
from gearcli.report.compare import comparison_rows, relative_error_percent, stage_reports
from gearcli.report.result import RunMetrics
from gearcli.report.spectrum import name_peak


# ------------------------------------------------------------------------------------- spectrum
def test_spectrum_finds_a_sine_and_its_amplitude():
    fs, f0, amp = 4000.0, 210.0, 12.0
    t = np.arange(0, 0.5 + 1e-12, 1 / fs)
    force = 1851.0 + 40.0 * t + amp * np.sin(2 * np.pi * f0 * t)  # trend + ripple
    sp = force_spectrum(t, force, (0.244, 0.5), stage=1, mesh_frequency_Hz=210.0, natural_frequencies_Hz=(900.0,))
    # window 0.256 s, 1025 samples: resolution 1/(1025/4000) = 3.90 Hz
    assert_allclose(sp.resolution_Hz, fs / sp.frequency_Hz.size / 2, rtol=2e-3)
    assert abs(sp.peak_frequency_Hz - f0) <= sp.resolution_Hz, "peak within one bin of the true line"
    # the line's amplitude A, not the largest bin's (which Hann scalloping lowers by up to 15 %)
    assert_allclose(sp.peak_amplitude_N, amp, rtol=2e-3)
    assert sp.matches == "mesh frequency"
    assert_allclose(sp.nyquist_Hz, fs / 2, rtol=1e-3)


@pytest.mark.parametrize("offset_bins", [0.0, 0.25, 0.5])
def test_spectrum_peak_amplitude_is_the_sine_amplitude_between_bins(offset_bins):
    # a sine of amplitude 150 N half-way between two FFT bins: the largest bin shows 150 N x 0.849 (Hann
    # scalloping, W(1/2)/W(0) = sinc(1/2) / (1 - 1/4) = 8/(3 pi) = 0.8488); the reported amplitude is the
    # sine's own, 150 N
    fs, n, amp = 8000.0, 2561, 150.0
    t = 0.18 + np.arange(n) / fs
    resolution = fs / n
    f0 = (50 + offset_bins) * resolution
    force = 6657.6 + amp * np.cos(2 * np.pi * f0 * t + 0.7)
    sp = force_spectrum(t, force, (t[0], t[-1]), stage=2, mesh_frequency_Hz=f0)
    assert_allclose(sp.peak_amplitude_N, amp, rtol=1e-3)
    k = int(np.argmin(np.abs(sp.frequency_Hz - sp.peak_frequency_Hz)))
    scalloped = 1.0 if offset_bins == 0 else np.sinc(offset_bins) / (1 - offset_bins ** 2)  # Hann W(d)/W(0)
    assert_allclose(sp.amplitude_N[k], amp * scalloped, rtol=2e-3)  # the spectrum itself stays the FFT's


def test_spectrum_over_whole_periods_is_the_exact_line_amplitude():
    # one period of a periodic steady state (closing sample included, as the run gives it), lines at 1x and 2x of
    # 51 Hz only: every line on a bin. A Hann window mixes each bin with -1/2 of its neighbours' (here 136 - 30/2 x
    # e^(i dphi)); the plain DFT of the record less its mean gives 136 and 30 exactly, the mesh-order table's figures
    f0, n = 51.0, 2000
    t = 0.3588 + np.arange(n + 1) / (n * f0)
    force = 2981.7 + 136.0 * np.cos(2 * np.pi * f0 * (t - t[0]) + 0.4) + 30.0 * np.cos(4 * np.pi * f0 * (t - t[0]) - 2.5)
    sp = force_spectrum(t, force, (t[0], t[-1]), stage=1, mesh_frequency_Hz=f0, whole_periods=True)
    assert sp.whole_periods
    assert_allclose(sp.resolution_Hz, f0, rtol=1e-9)
    assert_allclose(sp.peak_frequency_Hz, f0, rtol=1e-9)
    assert_allclose(sp.peak_amplitude_N, 136.0, rtol=1e-9)
    assert_allclose(sp.amplitude_N[[1, 2, 3]], [136.0, 30.0, 0.0], atol=1e-9)
    assert_allclose([o.tangential_N for o in sp.mesh_orders], [136.0, 30.0, 0.0], atol=1e-9)
    assert sp.matches == "mesh frequency"
    hann = force_spectrum(t, force, (t[0], t[-1]), stage=1, mesh_frequency_Hz=f0)  # the fixed window's estimate
    assert abs(hann.peak_amplitude_N - 136.0) > 5.0  # is not exact here: why whole periods take the DFT


def test_spectrum_of_a_constant_force_has_no_peak():
    t = np.linspace(0, 0.5, 2001)
    sp = force_spectrum(t, np.full_like(t, 1851.0), (0.25, 0.5), stage=1, mesh_frequency_Hz=210.0)
    assert sp.peak_frequency_Hz is None and sp.matches == "no fluctuation"


def test_spectrum_with_too_few_samples_is_empty_not_an_error():
    t = np.linspace(0, 0.5, 11)
    sp = force_spectrum(t, np.sin(t), (0.4, 0.5), stage=1, mesh_frequency_Hz=10.0)
    assert sp.peak_frequency_Hz is None and sp.frequency_Hz.size == 0


def test_name_peak_prefers_the_nearest_line_within_two_bins():
    assert name_peak(212.0, 4.0, 210.0, (900.0,)) == "mesh frequency"
    assert name_peak(421.0, 4.0, 210.0, ()) == "mesh harmonic 2"
    assert name_peak(903.0, 4.0, 210.0, (150.0, 900.0)) == "natural frequency 2"
    assert name_peak(500.0, 4.0, 210.0, (900.0,)) == "none"


# ------------------------------------------------------------------------------------- comparison
def test_relative_error_is_signed_and_none_for_zero_theory():
    assert_allclose(relative_error_percent(1796.0, 1851.0), -2.971, atol=1e-3)  # the seed's F_t, signed
    assert relative_error_percent(5.0, 0.0) is None


def test_comparison_rows_against_a_design_with_known_errors():
    design = fake_design()
    sim = fake_simulation(design, speed_err=-1e-3, force_err=2e-3)
    rows = {(r.stage, r.quantity): r for r in comparison_rows(design, sim)}
    assert_allclose(rows[(None, "ratio")].theory, 6.0, rtol=1e-12)
    # output 0.1 % slow: ratio 0.1 % high; error_percent = 100 (1/(1-1e-3) - 1)
    assert_allclose(rows[(None, "ratio")].error_percent, 100 * (1 / (1 - 1e-3) - 1), rtol=1e-9)
    assert_allclose(rows[(None, "output_speed_deg_s")].error_percent, -0.1, rtol=1e-9)
    # the 160 Hz ripple makes 40 whole periods in the 0.25 s window: its sample mean is 0
    assert_allclose(rows[(1, "tangential_N")].error_percent, 0.2, atol=1e-3)
    assert_allclose(rows[(2, "radial_N")].error_percent, 0.2, atol=1e-3)
    assert rows[(1, "axial_N")].error_percent is None  # spur: F_a theory is 0
    assert_allclose(rows[(2, "ratio")].error_percent, 100 * (1 / (1 - 1e-3) - 1), rtol=1e-9)  # last stage


def test_stage_reports_carry_the_spectrum_of_each_mesh():
    design = fake_design()
    reps = stage_reports(design, fake_simulation(design, ripple_Hz=160.0))
    assert [r.stage for r in reps] == [1, 2]
    for r in reps:
        assert abs(r.spectrum.peak_frequency_Hz - 160.0) <= r.spectrum.resolution_Hz
        assert r.spectrum.matches == "natural frequency 1"


# ------------------------------------------------------------------------------------- accuracy
def test_relative_errors_take_the_worst_stage():
    ref = RunMetrics(100.0, (1000.0, 2000.0), (1500.0, 3000.0))
    m = RunMetrics(100.1, (1001.0, 2010.0), (1500.0, 2970.0))
    e = relative_errors(m, ref)
    assert_allclose([e["speed"], e["mean_force"], e["peak_force"]], [1e-3, 5e-3, 1e-2], rtol=1e-9)


def test_meets_uses_the_larger_of_error_and_uncertainty():
    assert meets({"speed": 1e-6, "mean_force": 1e-6, "peak_force": 1e-6}, 1e-8, 1e-4)
    assert not meets({"speed": 1e-6, "mean_force": 1e-6, "peak_force": 1e-6}, 1e-3, 1e-4)
    assert not meets({"speed": None, "mean_force": 1e-6, "peak_force": 1e-6}, 1e-8, 1e-4)


def test_ladder_swaps_the_method_auto_resolves_to_for_its_sibling():
    assert ladder_methods(("auto", "DOP853", "Radau"), "DOP853") == ("auto", "RK45", "Radau")
    assert ladder_methods(("auto", "DOP853", "Radau"), "Radau") == ("auto", "DOP853", "BDF")
    assert ladder_methods(("auto", "DOP853", "Radau"), None) == ("auto", "DOP853", "Radau")


def test_the_file_settings_run_once_on_the_ladder_or_are_added_to_it():
    design = fake_design()
    solver = FakeSolver(design)
    study = accuracy_study(solver, file_method="auto", file_rtol=3e-7, auto_choice="DOP853",
                           spec=LadderSpec(rtols=(1e-3, 1e-6)))
    assert solver.calls.count(("auto", 3e-7)) == 1
    assert [(r.method, r.rtol) for r in study.runs if r.file_settings] == [("auto", 3e-7)]
    solver.calls.clear()
    study = accuracy_study(solver, file_method="auto", file_rtol=1e-6, spec=LadderSpec(rtols=(1e-3, 1e-6)))
    assert solver.calls.count(("auto", 1e-6)) == 1 and len(study.runs) == 6


def test_a_file_method_that_auto_also_picks_still_runs_at_the_file_rtol():
    solver = FakeSolver(fake_design(), auto="DOP853")
    study = accuracy_study(solver, file_method="DOP853", file_rtol=1e-6, spec=LadderSpec(rtols=(1e-3, 1e-6)))
    assert {r.method for r in study.runs} == {"auto", "RK45", "Radau", "DOP853"}
    assert [(r.method, r.rtol) for r in study.runs if r.file_settings] == [("DOP853", 1e-6)]


def test_the_reference_is_explicit_unless_the_scene_is_very_stiff():
    assert LadderSpec().reference_pair(None) == (("DOP853", 1e-12), ("Radau", 1e-10))
    assert LadderSpec().reference_pair(3.6e4) == (("DOP853", 1e-12), ("Radau", 1e-10))
    assert LadderSpec().reference_pair(1e6) == (("Radau", 1e-11), ("BDF", 1e-10))
    assert LadderSpec(reference=("RK45", 1e-10)).reference_pair(1e6)[0] == ("RK45", 1e-10)


def test_accuracy_study_errors_flags_and_recommendation():
    design = fake_design()
    solver = FakeSolver(design)
    spec = LadderSpec(rtols=(1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9))
    study = accuracy_study(solver, file_method="auto", file_rtol=1e-6, accuracy=1e-4, spec=spec)
    ref = study.reference
    # reference DOP853 at 1e-12: error 3e-12; check Radau at 1e-10: error 3e-9; uncertainty ~ 3e-9
    assert (ref.method, ref.rtol, ref.check_method, ref.check_rtol) == ("DOP853", 1e-12, "Radau", 1e-10)
    assert_allclose(ref.uncertainty, 3e-9, rtol=0.01)
    assert {r.method for r in study.runs} == {"auto", "RK45", "Radau"}  # auto is DOP853: RK45 instead
    # the reference pair runs first (a study that cannot afford it ends at once), then auto, to learn what it
    # resolves to before its siblings
    assert solver.calls[:2] == [("DOP853", 1e-12), ("Radau", 1e-10)]
    assert solver.calls[2][0] == "auto", "auto runs first on the ladder, to learn what it resolves to"
    for run in study.runs:
        c, p, _ = LAW[run.method_used]
        true = c * run.rtol**p
        if true > 10 * ref.uncertainty:  # resolvable: measured error = true error within the reference's
            assert_allclose(run.error_speed, true, rtol=0.05)
        assert run.below_reference_resolution["speed"] == (run.error_speed < ref.differences["speed"])
    rec = study.recommended
    # meets 1e-4: DOP853 (auto) at rtol <= 3e-5 -> 1e-5 rung; RK45 at 1e-5; Radau at 1e-6; cheapest: auto 1e-5
    assert (rec.method, rec.rtol) == ("auto", 1e-5)
    assert study.file_settings_meet_accuracy
    assert study.file_run.method == "auto" and study.file_run.rtol == 1e-6


def test_accuracy_study_flags_errors_below_the_reference_resolution():
    design = fake_design()
    study = accuracy_study(FakeSolver(design), file_method="Radau", file_rtol=1e-3, accuracy=1e-6,
                           spec=LadderSpec(rtols=(1e-3, 1e-10), methods=("DOP853", "Radau")))
    tight = next(r for r in study.runs if r.method == "DOP853" and r.rtol == 1e-10)
    # error 3e-10 against an uncertainty of 3e-9 (Radau's error at the check's rtol 1e-10)
    assert all(tight.below_reference_resolution.values())
    assert tight.meets_accuracy  # max(3e-10, 3e-9) <= 1e-6
    assert not study.file_settings_meet_accuracy  # Radau 1e-3: error 3e-2


def test_a_failed_rung_is_recorded_and_the_study_goes_on():
    from gearcli.errors import SimulationError

    design = fake_design()
    solver = FakeSolver(design)

    def run(method, rtol):
        if method == "RK45" and rtol == 1e-3:
            raise SimulationError("step size too small")
        return solver(method, rtol)

    study = accuracy_study(run, file_method="DOP853", file_rtol=1e-6, spec=LadderSpec(rtols=(1e-3, 1e-6),
                           methods=("DOP853", "RK45")))
    bad = next(r for r in study.runs if r.failure)
    assert bad.error_speed is None and not bad.meets_accuracy
    assert any("step size too small" in n for n in study.notes)


def test_struggling_run_is_flagged_against_the_ladder_median():
    design = fake_design()
    study = accuracy_study(FakeSolver(design), file_method="DOP853", file_rtol=1e-6,
                           spec=LadderSpec(rtols=(1e-6,), methods=("DOP853", "RK45", "Radau")))
    runs = list(study.runs)
    assert struggling(runs, runs) == []
    heavy = runs[0].__class__(**{**runs[0].__dict__, "nfev": 100 * runs[0].nfev})
    assert "struggles" in struggling_text(*struggling([heavy], [heavy, *runs[1:]])[0])
    # the report's warning carries the numbers (DESIGN §12): the file's heavy run against the median of the three
    # runs at its rtol, by hand
    import dataclasses

    from gearcli.report.checks import accuracy_checks

    mine = dataclasses.replace(heavy, file_settings=True)
    ladder = [mine, *runs[1:]]
    (w,) = [w for w in accuracy_checks(dataclasses.replace(study, runs=tuple(ladder)), "DOP853", 1e-6)
            if "struggles" in w.message]
    median = sorted(r.nfev for r in ladder)[1]
    assert w.data == {"method": mine.method, "method_used": mine.method_used, "rtol": 1e-6, "nfev": mine.nfev,
                      "median_nfev": median}


def test_progress_counts_every_planned_run():
    design = fake_design()
    seen = []
    accuracy_study(FakeSolver(design), file_method="DOP853", file_rtol=1e-6,
                   spec=LadderSpec(rtols=(1e-3, 1e-6), methods=("DOP853", "Radau")),
                   progress=lambda label, done, total: seen.append((done, total)))
    assert seen[-1][0] == seen[-1][1] == 2 + 4  # reference + check + 4 rungs
    assert all(d <= t for d, t in seen)


@pytest.mark.parametrize("quick", [True, False])
def test_build_report_with_a_stand_in_solver(quick):
    rep = fake_report(quick=quick, rtols=(1e-4, 1e-7))
    assert (rep.accuracy is None) == quick
    assert len(rep.stages) == 2 and rep.comparison[0].quantity == "ratio"
    assert rep.warnings == ()  # the fake run is clean: no check may fire


# ------------------------------------------------------------------------------------------ checks
def _with(sim, **solver_changes):
    import dataclasses

    return dataclasses.replace(sim, solver=dataclasses.replace(sim.solver, **solver_changes))


def test_energy_check_warns_on_either_sign_but_not_twice():
    from gearcli.report.checks import energy_check

    sim = fake_simulation(fake_design())
    assert energy_check(_with(sim, energy_residual=1e-7)) == []
    assert "-2.00e-02" in energy_check(_with(sim, energy_residual=-2e-2))[0]  # energy created: warned too
    import dataclasses

    from gearcli.diagnostics import ENERGY_RESIDUAL, warning

    said = warning(ENERGY_RESIDUAL, "energy balance residual 0.02 ...")
    already = dataclasses.replace(_with(sim, energy_residual=2e-2), warnings=(said.message,), diagnostics=(said,))
    assert energy_check(already) == []  # the simulation's diagnostic code, not its text, decides
    reworded = dataclasses.replace(already, diagnostics=(warning(ENERGY_RESIDUAL, "reworded"),), warnings=("x",))
    assert energy_check(reworded) == []


def test_sampling_check_names_lines_above_nyquist():
    from gearcli.report.checks import sampling_checks

    design = fake_design()
    stages = stage_reports(design, fake_simulation(design))  # 2001 samples over 0.5 s: Nyquist 2000 Hz
    assert sampling_checks(stages, (160.0, 900.0)) == []
    msg = [w.message for w in sampling_checks(stages, (160.0, 4700.0))]
    assert len(msg) == 1 and "4700 Hz" in msg[0] and "simulation.steps" in msg[0]
    # with the run's steps, the value to use. The check's Nyquist is half the sample rate less one bin 1/T:
    # 2000 - 1/0.5 s = 1998 Hz, linear in the steps: 2000 x 1.25 x 4700 / 1998 = 5880.9 -> 5881, whose Nyquist
    # 5881 / (2 x 0.5 s) - 2 Hz = 5879 Hz holds 1.25 x 4700 = 5875 Hz
    (hint,) = sampling_checks(stages, (160.0, 4700.0), 2000)
    assert "Nyquist frequency 1998 Hz" in hint.message, hint
    assert hint.message.endswith("--set simulation.steps=5881 would sample it"), hint
    assert hint.data["steps"] == 5881 and hint.data["frequency_Hz"] == 4700.0
    (capped,) = sampling_checks(stages, (4.7e9,), 2000)  # 5.875e9 steps: beyond the schema's 2e6
    assert "beyond the schema's maximum 2000000" in capped.message and "duration_s" in capped.message
    assert capped.data["steps"] is None and capped.data["steps_cap"] == 2_000_000


def test_sampling_warning_names_its_stage_and_numbers():
    """DESIGN §12: a JSON warning carries the diagnostic's data, ``stage`` 1-based where it is about a stage. The
    report's ``sampling`` warning of a mesh line above the Nyquist frequency named "stage 1" in its message and
    had ``stage: null`` and no numbers (found by trial tr24h). By hand: the fake train's stage 1 pinion, 20 teeth
    at 3600 deg/s = 10 rev/s, meshes at 200 Hz, its stage 2 pinion at 1800 deg/s at 100 Hz; 201 samples over
    0.5 s are 400 samples/s, Nyquist 200 Hz less a bin: stage 1's line is above it, stage 2's below."""
    from gearcli.diagnostics import SAMPLING, as_dict
    from gearcli.report.checks import sampling_checks

    design = fake_design()
    stages = stage_reports(design, fake_simulation(design, n=201))
    found = sampling_checks(stages, (160.0, 900.0), 200)
    rows = [as_dict(w) for w in found]
    assert [r["code"] for r in rows] == [SAMPLING, SAMPLING]
    mesh, modes = rows
    assert mesh["stage"] == 1 and mesh["excitation"] == "stage 1 mesh"
    assert mesh["frequency_Hz"] == pytest.approx(20 * 3600 / 360, rel=1e-12)
    fs = 200 / 0.5  # samples per second
    half_bin = fs / 101 / 2  # half the resolution of the window's 101 samples (0.25 ... 0.5 s)
    assert mesh["nyquist_Hz"] == pytest.approx(fs / 2 - half_bin, rel=1e-12)
    # the suggested steps sample the line with its 1.25 margin: their Nyquist, about half a bin below fs / 2
    assert mesh["steps"] / (2 * 0.5) - half_bin >= 1.25 * 200 and mesh["steps_cap"] == 2_000_000
    assert f"--set simulation.steps={mesh['steps']}" in mesh["message"]
    assert modes["stage"] is None and modes["natural_frequencies_Hz"] == [900.0] and modes["frequency_Hz"] == 900.0
    assert modes["steps"] / (2 * 0.5) - half_bin >= 1.25 * 900


def test_accuracy_check_says_what_to_use_instead():
    from gearcli.report.checks import accuracy_checks

    study = accuracy_study(FakeSolver(fake_design()), file_method="Radau", file_rtol=1e-3,
                           spec=LadderSpec(rtols=(1e-3, 1e-5), methods=("DOP853", "Radau")))
    msg = [w.message for w in accuracy_checks(study, "Radau", 1e-3)]
    assert any('do not meet' in m and 'method = "DOP853", rtol = 1e-05' in m for m in msg), msg
    # its JSON data (DESIGN §12): the file's settings, the accuracy asked, the rung that meets it. By the fake law
    # error = C rtol^p: Radau at 1e-3 errs 30 x 1e-3 = 3e-2, DOP853 at 1e-5 3 x 1e-5 = 3e-5 (LAW above)
    (miss,) = [w.data for w in accuracy_checks(study, "Radau", 1e-3) if "do not meet" in w.message]
    assert miss == {"method": "Radau", "rtol": 1e-3, "requested_accuracy": study.requested_accuracy,
                    "recommended_method": "DOP853", "recommended_rtol": 1e-5}
    assert LAW["Radau"][0] * 1e-3 > study.requested_accuracy >= LAW["DOP853"][0] * 1e-5


def test_a_failed_reference_is_an_error_not_a_study():
    from gearcli.errors import SimulationError

    solver = FakeSolver(fake_design())

    def run(method, rtol):
        if rtol < 1e-10:
            raise SimulationError("budget exceeded")
        return solver(method, rtol)

    with pytest.raises(SimulationError, match="reference run .*--quick"):
        accuracy_study(run, file_method="DOP853", file_rtol=1e-6, spec=LadderSpec(rtols=(1e-6,)))


def test_recommendation_prices_runs_by_evaluations_not_by_one_noisy_wall_time():
    # the seed's auto ladder as measured once: the 1e-5 rung took 59 ms against 50 ms for 1e-6 (timing
    # noise: it needs 3892 evaluations against 5407). Priced at the method's median seconds per
    # evaluation, 1e-5 is the cheaper of the two, as its evaluation count says; Radau's dearer
    # evaluations keep it behind at equal nfev.
    from gearcli.report.accuracy import _cost
    from gearcli.report.result import AccuracyRun

    def rung(method, rtol, wall, nfev):
        return AccuracyRun(method, method, rtol, wall, nfev, 0, 0, 1e-6, 1e-6, 1e-6, {}, True)

    runs = [rung("auto", 1e-4, 0.040, 2878), rung("auto", 1e-5, 0.059, 3892), rung("auto", 1e-6, 0.050, 5407),
            rung("auto", 1e-7, 0.064, 7246), rung("Radau", 1e-5, 0.16, 3892), rung("Radau", 1e-6, 0.23, 9726)]
    cost = _cost(runs)
    by_cost = sorted(runs[1:3] + runs[4:5], key=cost)
    assert [(r.method, r.rtol) for r in by_cost] == [("auto", 1e-5), ("auto", 1e-6), ("Radau", 1e-5)]
    # a failed rung has no rate of its own and never looks cheap
    failed = AccuracyRun("RK45", "RK45", 1e-3, 0.001, 10, 0, 0, None, None, None, {}, False, failure="budget")
    assert cost(failed) == float("inf")


def test_ladder_rungs_skip_the_check_pass_the_report_never_reads():
    # a rung's error comes from the study's reference; only the report's own simulation estimates its statistics
    from test_report_fakes import fake_cfg

    from gearcli.report import build_report

    design = fake_design()
    solver = FakeSolver(design)
    calls = []

    def simulate(cfg_, design_, *, method=None, rtol=None, want_series=True, error_estimate=None):
        calls.append((want_series, error_estimate))
        return solver(method or cfg_.simulation.method, rtol or cfg_.simulation.rtol)

    build_report(fake_cfg(), design, quick=False, spec=LadderSpec(rtols=(1e-4, 1e-6)), simulate=simulate)
    assert calls[0] == (True, None)  # the report's simulation: the file's own setting
    assert len(calls) > 3 and all(c == (False, False) for c in calls[1:])
