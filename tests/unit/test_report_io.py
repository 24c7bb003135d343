"""The report writers on a synthetic report: JSON contract, markdown, rich tables, PNG plots."""

from __future__ import annotations

import json
import struct
import sys

import pytest
from test_report_fakes import fake_report

from gearcli.io.markdown import report_markdown
from gearcli.io.report_json import report_dict
from gearcli.io.report_tables import report_tables
from gearcli.io.serialize import to_json, with_meta
from gearcli.io.tables import render

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def report():
    return fake_report()


def png_size(path) -> tuple[int, int]:
    """Width and height from the IHDR chunk, which follows the 8-byte signature."""
    head = path.read_bytes()[:24]
    assert head[:8] == PNG_SIGNATURE and head[12:16] == b"IHDR"
    return struct.unpack(">II", head[16:24])


def test_json_contract_keys_and_strictness(report):
    doc = json.loads(to_json(with_meta(report_dict(report), "0" * 64)))
    assert {"gearcli_version", "input_sha256", "comparison", "accuracy", "design", "simulation",
            "dynamics", "warnings", "energy_residual"} <= set(doc)
    row = doc["comparison"][0]
    assert set(row) == {"stage", "quantity", "theory", "simulated", "error_percent"} and row["stage"] is None
    acc = doc["accuracy"]
    assert {"method", "rtol", "wall_s", "check_method", "check_rtol", "uncertainty"} <= set(acc["reference"])
    run = acc["runs"][0]
    assert {"method", "rtol", "wall_s", "nfev", "error_speed", "error_mean_force", "error_peak_force",
            "below_reference_resolution"} <= set(run)
    assert set(run["below_reference_resolution"]) == {"speed", "mean_force", "peak_force"}
    assert acc["recommended"]["method"] == "auto" and acc["recommended"]["rtol"] == 1e-5
    assert acc["file_settings_meet_accuracy"] is True and acc["requested_accuracy"] == 1e-4
    assert doc["design"]["stages"][0]["mesh_frequency_Hz"] > 0
    assert doc["simulation"]["solver"]["method"] == "DOP853"


def test_json_quick_has_null_accuracy():
    doc = report_dict(fake_report(quick=True))
    assert doc["accuracy"] is None


def test_markdown_has_headings_pipe_tables_and_the_method_paragraph(report):
    md = report_markdown(report, "ab" * 32)
    assert md.startswith("# gearcli report: fake")
    for heading in ("## Theory against simulation", "## Dominant frequency", "## Numerical accuracy",
                    "## Warnings"):
        assert heading in md
    assert "| stage | quantity | theory (static) | simulated (mean) | error [%] |" in md
    assert "**Method.**" in md and "checked by an independent run" in md
    # errors below the reference resolution are not printed as numbers: DOP853 at rtol 1e-10 (error 3e-10) against
    # the reference's 3e-9 (the check Radau's error at 1e-10)
    tight = report_markdown(fake_report(rtols=(1e-3, 1e-10)), "ab" * 32)
    assert "< 3.0e-09" in tight
    assert "\\|F_t\\|" in md  # a pipe inside a cell is escaped


def test_markdown_quick_says_the_study_was_skipped():
    assert "Skipped (`--quick`)" in report_markdown(fake_report(quick=True))


def test_tables_render_as_plain_text_with_units(report):
    text = render(report_tables(report))
    assert "Theory against simulation" in text and "wall [s]" in text and "at t [s]" in text
    assert "★" in text


def test_plots_are_pngs_of_reasonable_size(report, tmp_path):
    pytest.importorskip("matplotlib")
    from gearcli.io.plots import FILES, write_plots

    paths = write_plots(report, tmp_path / "plots")
    assert sorted(p.name for p in paths) == sorted(FILES)
    for p in paths:
        width, height = png_size(p)
        assert p.stat().st_size > 20_000, p.name
        assert width >= 800 and height >= 300, (p.name, width, height)


def test_plots_without_matplotlib_raise_plots_unavailable(report, tmp_path, monkeypatch):
    from gearcli.io.figures import PlotsUnavailable
    from gearcli.io.plots import write_plots

    for name in [m for m in sys.modules if m == "matplotlib" or m.startswith("matplotlib.")]:
        monkeypatch.delitem(sys.modules, name)
    monkeypatch.setitem(sys.modules, "matplotlib", None)  # "import matplotlib" now raises ImportError
    with pytest.raises(PlotsUnavailable, match="pip install"):
        write_plots(report, tmp_path / "plots")
    assert not (tmp_path / "plots").exists(), "nothing is created when the plots cannot be drawn"
