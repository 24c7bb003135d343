"""A duty point without starts counts its settled window, never the run from rest that reaches it (tr11a): the
run-up's own warnings (`peak_over_rigid`: "give ramp_s > 0 for a smooth run-up"; the run's peak unresolved by the
samples or the solver) change no figure of the life and are not given; a point with starts counts its run-up and
keeps them. Before, a speed drive stepped to its speed (ramp_s = 0) warned every point "the start's peak mesh force
... is 2.25x the rigid-body start's ... give ramp_s > 0", whose advice moves no damage (checked here: the same
damage with and without the ramps, each engagement of an unexcited settled window meeting the static force)."""

from __future__ import annotations

from numpy.testing import assert_allclose

from tests.life.engineer_duties import PAR_BASE, duty_text, run_life

STEPPED = PAR_BASE.replace("ramp_s = 0.05", "ramp_s = 0")
RUN_UP = {"peak_over_rigid", "peak_undersampled", "peak_unresolved"}
POINTS = (("full", 4000.0, 900.0, 1500.0), ("part", 16000.0, 500.0, 1000.0))


def test_points_without_starts_carry_no_run_up_warnings_and_their_damage_ignores_the_run_up(tmp_path):
    assert STEPPED != PAR_BASE
    stepped = run_life(tmp_path, STEPPED + duty_text(POINTS))
    assert not RUN_UP & {w["code"] for w in stepped["warnings"]}, stepped["warnings"]
    ramped = run_life(tmp_path, PAR_BASE + duty_text(POINTS))
    for st, st0 in zip(stepped["life"]["stages"], ramped["life"]["stages"], strict=True):
        for member in ("pinion", "gear"):
            for mode in ("pitting", "bending"):
                # no excitation: every engagement of a settled window meets the static force, however it started
                assert_allclose(st[member][mode]["damage"], st0[member][mode]["damage"], rtol=1e-6)


def test_a_point_with_starts_keeps_its_run_up_warning(tmp_path):
    # the stepped start is counted 100 times: its run-up's peak is now part of the spectrum
    duty = duty_text(POINTS).replace("speed_rpm = 1500.0\n", "speed_rpm = 1500.0\nstarts = 100\n")
    doc = run_life(tmp_path, STEPPED + duty)
    codes = {w["code"] for w in doc["warnings"]}
    assert "peak_over_rigid" in codes, doc["warnings"]
