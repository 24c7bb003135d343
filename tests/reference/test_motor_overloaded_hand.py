"""A motor driven continuously above its rating (trial tr15c): a 30 kW four-pole motor (rated 1470 rpm, so
T_rated = P / w_rated = 30000 / (1470 * 2 pi / 60) = 194.88 N m) on one stage 19/83 of efficiency 0.97 and a
constant load. The motor carries the load over the ratio and the efficiency, T_L * 19/83 / 0.97; beyond 1.05 x
T_rated (S1 duty, docs/motors.md) ``motor_overloaded`` names the figures, in ``design`` (check) and ``simulate``
(the steady window's mean motor torque); at 1.04 x nothing. A table motor has no rated point: no warning."""

from __future__ import annotations

import json
import math

import pytest
from click.testing import CliRunner

from gearcli.cli import cli

T_RATED = 30_000.0 / (1470.0 * 2.0 * math.pi / 60.0)  # N m, 194.88
RATIO, ETA = 83.0 / 19.0, 0.97
NAMEPLATE = ("motor = { rated_power_kW = 30, rated_speed_rpm = 1470, synchronous_speed_rpm = 1500, "
             "breakdown_torque_ratio = 3.0, locked_rotor_torque_ratio = 2.5 }")
TABLE = "motor = { torque_speed = [[0, 500], [1200, 700], [1400, 600], [1500, 0]] }"
SCENE = """
input = {{ speed_rpm = {speed}, drive = "{drive}", {motor},{ramp} inertia_kg_m2 = 0.2, coupling_stiffness_Nm_rad = 3e4, coupling_damping_Nms_rad = 10 }}
load = {{ torque_Nm = {load}, inertia_kg_m2 = 3.0, coupling_stiffness_Nm_rad = 2e5, coupling_damping_Nms_rad = 50 }}
simulation = {{ duration_s = 1.2, window_start_s = 0.6 }}
[[stage]]
normal_module_mm = 4
helix_angle_deg = 15
efficiency = 0.97
pinion = {{ teeth = 19, face_width_mm = 60, hand = "left" }}
gear = {{ teeth = 83, face_width_mm = 55, hand = "right" }}
"""


def _load(factor: float) -> float:
    """The output torque that the motor carries as factor x its rated torque (hand: through ratio and efficiency)."""
    return factor * T_RATED * RATIO * ETA


def _overloads(tmp_path, command: str, factor: float, drive: str = "motor", motor: str = NAMEPLATE,
               speed: float = 1440.0) -> list[dict]:
    path = tmp_path / "drive.toml"
    path.write_text(SCENE.format(speed=speed, drive=drive, motor=motor, load=_load(factor),
                                 ramp=" ramp_s = 0.1," if drive == "speed" else ""))
    res = CliRunner().invoke(cli, ["-q", command, str(path), "--format", "json"])
    assert res.exit_code == 0, res.output
    return [w for w in json.loads(res.stdout)["warnings"]
            if "motor_overloaded" in (w["code"], w.get("check"))]


@pytest.mark.parametrize("command", ["design", "simulate"])
def test_a_motor_165_percent_loaded_is_warned_with_its_figures(tmp_path, command):
    found = _overloads(tmp_path, command, 1.65)
    assert len(found) == 1
    w = found[0]
    assert w["code"] == ("design" if command == "design" else "motor_overloaded")
    assert w["rated_torque_Nm"] == pytest.approx(T_RATED, rel=1e-9)
    assert w["torque_Nm"] == pytest.approx(1.65 * T_RATED, rel=1e-6)  # the window mean of a steady run: tight
    assert w["overload_ratio"] == pytest.approx(1.65, rel=1e-6)
    assert f"{1.65 * T_RATED:.4g} N·m" in w["message"] and f"{T_RATED:.4g} N·m" in w["message"]
    assert "1.65x" in w["message"]


@pytest.mark.parametrize(("factor", "warned"), [(1.04, False), (1.06, True)])
def test_the_margin_is_five_percent_on_both_sides(tmp_path, factor, warned):
    for command in ("design", "simulate"):
        assert bool(_overloads(tmp_path, command, factor)) is warned, command


def test_a_motor_at_its_rating_is_not_warned_nor_one_without_a_rated_point(tmp_path):
    assert _overloads(tmp_path, "design", 1.0) == []
    # a table motor: 1.65 x the nameplate's rated torque is 321.6 N m, which the table carries near 1460 rpm
    assert _overloads(tmp_path, "design", 1.65, motor=TABLE, speed=1460.0) == []


def test_a_start_not_settled_before_the_window_is_judged_at_its_operating_point(tmp_path):
    path = tmp_path / "drive.toml"
    path.write_text(SCENE.format(speed=1440.0, drive="motor", motor=NAMEPLATE, load=_load(1.65), ramp="")
                    .replace("window_start_s = 0.6", "window_start_s = 0.1"))
    res = CliRunner().invoke(cli, ["-q", "simulate", str(path), "--format", "json"])
    codes = {w["code"]: w for w in json.loads(res.stdout)["warnings"]}
    assert "start_not_settled" in codes  # the window's mean holds the start's acceleration torque
    assert codes["motor_overloaded"]["torque_Nm"] == pytest.approx(1.65 * T_RATED, rel=1e-9)  # not the window mean


def test_a_speed_drive_whose_described_motor_cannot_carry_the_design_torque_continuously(tmp_path):
    found = _overloads(tmp_path, "design", 1.3, drive="speed")
    assert [w["overload_ratio"] for w in found] == [pytest.approx(1.3, rel=1e-9)]
    found = _overloads(tmp_path, "simulate", 1.3, drive="speed")
    assert [w["overload_ratio"] for w in found] == [pytest.approx(1.3, rel=1e-4)]
