"""``report`` in the design file's units (DESIGN §12, docs/output.md "Units"), on the synthetic report of
test_report_fakes (input 3600 °/s, stage ratios 2 and 3, input torque 1e5 N·mm): by hand, 3600 °/s = 600 rpm =
20π rad/s; the stages' gears turn at 1800 °/s = 300 rpm and 600 °/s = 100 rpm; 1e5 N·mm = 100 N·m.

- the JSON comparison keeps its °/s rows in their places and, in an rpm or rad/s file, gives the speed rows again in
  the file's unit after them all (it gave only ``input_speed_deg_s``/``output_speed_deg_s`` while the tables printed
  rpm);
- the comparison table prints a speed row in the file's unit and, beside °/s or rad/s, in rpm (a °/s file's
  table gave °/s alone);
- `simulate`'s footer of a rad/s file adds rpm, as the °/s file's and the report's solver line do (it gave rad/s
  alone);
- the design section adds rpm beside °/s or rad/s and N·m beside N·mm, as every table does (it printed the file's
  unit alone: "input torque 100000 N·mm").
"""

from __future__ import annotations

import dataclasses
import math

import pytest
from test_report_fakes import fake_report

from gearcli.io.report_json import report_dict
from gearcli.io.report_sections import comparison_section, design_section, solver_lines
from gearcli.io.tables import footer_speeds


@pytest.fixture(scope="module")
def base():
    return fake_report(quick=True)


def in_units(report, speed: str, torque: str):
    return dataclasses.replace(report, simulation=dataclasses.replace(report.simulation, units=(speed, torque)))


def rows(doc) -> dict[tuple[int | None, str], dict]:
    return {(r["stage"], r["quantity"]): r for r in doc["comparison"]}


@pytest.mark.parametrize(("speed", "factor"), [("rpm", 1 / 6), ("rad_s", math.pi / 180)])
def test_comparison_speed_rows_in_the_file_unit(base, speed, factor):
    by = rows(report_dict(in_units(base, speed, "Nm")))
    hand = {(None, "input"): 3600.0, (None, "output"): 600.0, (1, "output"): 1800.0, (2, "output"): 600.0}
    for (stage, which), deg_s in hand.items():
        fixed, own = by[(stage, f"{which}_speed_deg_s")], by[(stage, f"{which}_speed_{speed}")]
        assert fixed["theory"] == pytest.approx(deg_s, rel=1e-12)  # the fixed °/s row is kept
        assert own["theory"] == pytest.approx(deg_s * factor, rel=1e-12)
        assert own["simulated"] == pytest.approx(fixed["simulated"] * factor, rel=1e-12)
        assert own["error_percent"] == fixed["error_percent"]
    assert by[(None, "input_speed_rpm" if speed == "rpm" else "input_speed_rad_s")]["theory"] == pytest.approx(
        600.0 if speed == "rpm" else 20 * math.pi, rel=1e-12)
    # the rows a °/s file gives keep their places: the file-unit rows come after them all
    own_doc, deg_doc = report_dict(in_units(base, speed, "Nm")), report_dict(in_units(base, "deg_s", "Nm"))
    n = len(deg_doc["comparison"])
    assert [(r["stage"], r["quantity"]) for r in own_doc["comparison"][:n]] == \
        [(r["stage"], r["quantity"]) for r in deg_doc["comparison"]]
    assert all(r["quantity"].endswith(f"_speed_{speed}") for r in own_doc["comparison"][n:])


def test_comparison_of_a_deg_s_file_is_unchanged(base):
    doc = report_dict(in_units(base, "deg_s", "Nmm"))
    assert not [r for r in doc["comparison"] if r["quantity"].endswith(("_rpm", "_rad_s"))]
    assert [r["quantity"] for r in doc["comparison"][:3]] == ["ratio", "input_speed_deg_s", "output_speed_deg_s"]


def design_text(report) -> tuple[list[str], str]:
    sec = design_section(report)
    return [row[0] for row in sec.rows], " ".join(sec.notes)


def test_design_section_of_a_deg_s_Nmm_file_adds_rpm_and_Nm(base):
    labels, notes = design_text(in_units(base, "deg_s", "Nmm"))
    assert {"pinion speed [°/s]", "pinion speed [rpm]", "pinion torque [N·mm]", "pinion torque [N·m]"} <= set(labels)
    assert "input 3600 °/s = 600 rpm" in notes and "output 600 °/s = 100 rpm" in notes
    assert "input torque 100000 N·mm = 100 N·m" in notes


def test_design_section_of_a_rad_s_file_adds_rpm(base):
    labels, notes = design_text(in_units(base, "rad_s", "Nm"))
    assert {"pinion speed [rad/s]", "pinion speed [rpm]", "pinion torque [N·m]"} <= set(labels)
    assert "pinion torque [N·mm]" not in labels
    assert f"input {20 * math.pi:.6g} rad/s = 600 rpm" in notes and "input torque 100 N·m," in notes


def test_design_section_of_an_rpm_Nm_file_is_in_its_units_alone(base):
    labels, notes = design_text(in_units(base, "rpm", "Nm"))
    assert "pinion speed [rpm]" in labels and "pinion speed [°/s]" not in labels
    assert "input 600 rpm, output 100 rpm; input torque 100 N·m," in notes


@pytest.mark.parametrize(("speed", "units"), [("deg_s", {"°/s": 1.0, "rpm": 1 / 6}),
                                              ("rad_s", {"rad/s": math.pi / 180, "rpm": 1 / 6}),
                                              ("rpm", {"rpm": 1 / 6})])
def test_comparison_table_speed_rows_in_the_table_units(base, speed, units):
    sec = comparison_section(in_units(base, speed, "Nmm"))
    printed = {(row[0], row[1]): float(row[2]) for row in sec.rows}
    hand = {("train", "input speed"): 3600.0, ("train", "output speed"): 600.0, ("1", "stage output speed"): 1800.0,
            ("2", "stage output speed"): 600.0}
    for (stage, name), deg_s in hand.items():
        for unit, factor in units.items():
            assert printed[(stage, f"{name} [{unit}]")] == pytest.approx(deg_s * factor, rel=1e-5)  # 6 digits
    assert not [label for _, label in printed if label.endswith("]") and "speed" in label
                and label[label.rindex("[") + 1:-1] not in units]


def speed_words(deg_s: float, speed: str) -> str:
    """By hand: 1 rpm = 6 °/s, 1 rad/s = 180/π °/s; the file's unit (6 digits), then rpm (5) unless it is rpm."""
    rpm = f"{deg_s / 6:.5g} rpm"
    if speed == "rpm":
        return f"{deg_s / 6:.6g} rpm"
    own = f"{deg_s:.6g} °/s" if speed == "deg_s" else f"{deg_s * math.pi / 180:.6g} rad/s"
    return f"{own} = {rpm}"


@pytest.mark.parametrize("speed", ["deg_s", "rad_s", "rpm"])
def test_simulate_footer_and_report_solver_line(base, speed):
    report = in_units(base, speed, "Nm")
    sim = report.simulation
    assert sim.input_speed_deg_s == pytest.approx(3600.0) and sim.output_speed_deg_s == pytest.approx(600.0, rel=1e-4)
    output, input_ = speed_words(sim.output_speed_deg_s, speed), speed_words(sim.input_speed_deg_s, speed)
    footer = footer_speeds(sim)
    assert f"output {output}   input {input_}" in footer, footer
    assert solver_lines(report)[-1].endswith(f"output {output}")
    assert ("rpm" in footer.split("input")[1]) and (speed == "rpm" or " = " in footer)
