"""The report's modes table gives a mode's damping ratio in per cent to 2 significant digits, whole numbers written
out as `gearcli modes --format table` writes them: a motor coupling that damps the light sun of a planetary stage
(5 N·m·s/rad on J = 7.1e-5 kg·m² at 1174 Hz: ζ = c / (2 J ω) far above 1 on the sun alone, 99.6 % for the mode)
printed "1e+02", read as 1 % by a hurried eye."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from gearcli.io.report_sections import modes_section


def _report(zeta: float):
    mode = SimpleNamespace(number=2, rigid=False, crossings=[], frequency_Hz=1173.85, damping_ratio=zeta, damped_frequency_Hz=None,
                           dominant="input coupling", energy_share=[0.88, 0.12])
    modes = SimpleNamespace(modes=[mode], nominal_input_rpm=1460.0, boundary="free")
    return SimpleNamespace(modes=modes, simulation=SimpleNamespace(units=None))


@pytest.mark.parametrize(("zeta", "text"), [(0.9961, "100"), (0.0069, "0.69"), (0.0534, "5.3"), (2.5, "250")])
def test_damping_ratio_in_per_cent_without_exponents(zeta, text):
    section = modes_section(_report(zeta))
    assert section is not None
    assert section.rows[0][2] == text


def test_the_table_tells_where_the_damping_ratios_eigenvalue_rings():
    """Beside zeta, the frequency of the damped eigenvalue it is taken from (`damped_frequency_Hz`; a slip-damped
    11.21 Hz free mode rings at 8.11 Hz with zeta 0.485: tests/reference/test_modes_engineer_scenes.py), a dash where
    none rings (an overdamped mode's projection)."""
    report = _report(0.485)
    report.modes.modes[0].damped_frequency_Hz = 8.11007840101613
    section = modes_section(report)
    assert section is not None and section.headers[3] == "rings at [Hz]" and section.rows[0][3] == "8.1101"
    report.modes.modes[0].damped_frequency_Hz = None
    assert modes_section(report).rows[0][3] == "–"
