"""``gearcli report``: theory against simulation, numerical error against run time.

The core of the report: it runs the scene and returns frozen :class:`Report` objects; it never
prints (``gearcli.io.report_*``, ``gearcli.io.markdown`` and ``gearcli.io.plots`` format them).
"""

from gearcli.report.accuracy import DEFAULT_RTOLS, LadderSpec, accuracy_study, relative_errors
from gearcli.report.build import build_report
from gearcli.report.result import (
    AccuracyRun,
    AccuracyStudy,
    ComparisonRow,
    ReferenceRun,
    Report,
    RunMetrics,
    Spectrum,
    StageReport,
)
from gearcli.report.spectrum import force_spectrum

__all__ = [
    "AccuracyRun", "AccuracyStudy", "ComparisonRow", "DEFAULT_RTOLS", "LadderSpec", "ReferenceRun", "Report",
    "RunMetrics", "Spectrum", "StageReport", "accuracy_study", "build_report", "force_spectrum",
    "relative_errors",
]
