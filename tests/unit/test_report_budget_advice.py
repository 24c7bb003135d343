"""The report's refusal advises a simulation.duration_s whose work fits its budget: rounded down to three digits,
never up past the limit (the run budget's advice had the same fault, fixed by tr28f; report/build.ReportBudget._fit)."""

from __future__ import annotations

import re

import pytest

from gearcli.errors import StudyTooLong
from gearcli.report.build import REPORT_WORK_CAP_S, ReportBudget


@pytest.mark.parametrize(("limit_s", "advised_s"), [(1977.8, 1970.0), (746.6, 746.0), (0.012396, 0.0123), (3.0, 3.0)])
def test_the_advised_duration_fits_the_budget(limit_s, advised_s):
    # the work grows with the duration: a study of 1.5 x limit_s spending 1.5 x the budget fits it at limit_s (by hand)
    budget = ReportBudget(0.0, 1.5 * limit_s)
    with pytest.raises(StudyTooLong) as err:
        budget.spend(1.5 * REPORT_WORK_CAP_S)
    advised = float(re.search(r"duration_s ≤ ([0-9.e+-]+) s", str(err.value)).group(1))
    assert advised == pytest.approx(advised_s, rel=1e-12)  # three digits, rounded down
    assert advised <= limit_s  # rounded to nearest, 1977.8 s read 1.98e+03: over the limit, refused again
