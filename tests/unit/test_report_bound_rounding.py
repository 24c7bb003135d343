"""A ``< e`` cell of `gearcli report` states that a figure lies below e, so the printed e must not be rounded below it.

A rattling light-load helical stage (trial tr28b: m_n 2, 23/61 teeth, 0.1 mm backlash, 10 µm TE, 2 N·m) simulated
its window-mean F_t 1.444 % under the static 32.289 N, with an estimated error of that mean of 1.455 %: the report
printed the error as "< 1" (the estimate to one digit, rounded to nearest), a false statement about a 1.444 %
difference. The bound is now rounded up ("< 2"), as are the mesh-order amplitudes' "< e" and the accuracy study's
"< u" (an error of 1.03e-8 below a resolution of 1.04e-8 printed "< 1.0e-08"). Figures by hand from the synthetic
results of tests/unit/test_report_fakes.py (theory F_t 1000 N on stage 1)."""

from __future__ import annotations

import dataclasses

from test_report_fakes import fake_cfg, fake_design, fake_simulation

from gearcli.io.report_sections import comparison_section, error_cell
from gearcli.report import LadderSpec, build_report
from gearcli.report.accuracy import measure, reference_run
from gearcli.simulate.results import ChannelStats, StatisticsError


def _estimate(stage: int, mean_N: float, relative_mean: float) -> StatisticsError:
    zero = ChannelStats(relative_mean * mean_N, 0.0, 0.0, 0.0)
    return StatisticsError(stage, mean_N, 1e-3, zero, 0.0, {"mean": relative_mean}, 0.0, 0.0, (), None,
                           total_relative={"mean": relative_mean})


def test_a_mean_force_difference_below_its_estimate_prints_a_bound_above_the_difference():
    design = fake_design()

    def simulate(cfg_, design_, *, method=None, rtol=None, want_series=True, error_estimate=None):
        sim = fake_simulation(design, force_err=-0.01444, method="DOP853", rtol=1e-6)
        st = [dataclasses.replace(s, error_estimate=_estimate(s.index, s.tangential_N.mean, 0.01455))
              for s in sim.stages]
        return dataclasses.replace(sim, stages=tuple(st))

    r = build_report(fake_cfg(), design, quick=True, spec=LadderSpec(rtols=(1e-6,)), simulate=simulate)
    rows = {(row[0], row[1]): row[4] for row in comparison_section(r).rows}
    # by hand: the fake F_t is 1000 N (1 - 0.01444) plus a 5 % sine of whole periods over the window: -1.444 %
    error = next(c.error_percent for c in r.comparison if c.stage == 1 and c.quantity == "tangential_N")
    assert abs(error - (-1.444)) < 0.005, error
    cell = rows[("1", "F_t mean [N]")]
    assert cell.startswith("< "), cell
    assert float(cell[2:]) >= 1.455 > 1.444, cell  # one digit, rounded up: "< 2" (was "< 1", below 1.444)


def test_an_error_below_the_references_resolution_prints_a_bound_above_the_error():
    design = fake_design()
    ref = fake_simulation(design, method="DOP853", rtol=1e-12)
    check = fake_simulation(design, speed_err=1e-14, force_err=1e-12, peak_err=1.04e-8, method="Radau", rtol=1e-10)
    reference = reference_run(ref, check, 1e-12, 1e-10)
    rung = fake_simulation(design, speed_err=1e-10, force_err=1e-9, peak_err=1.03e-8, method="DOP853", rtol=1e-6)
    run = measure(rung, "DOP853", 1e-6, reference, 1e-7, file_settings=True)
    assert run.below_reference_resolution["peak_force"]  # 1.03e-8 < 1.04e-8
    cell = error_cell(run, "peak_force", reference)
    assert cell == "< 1.1e-08", cell  # 1.04e-8 rounded up; "< 1.0e-08" would claim the 1.03e-8 error is below 1e-8
