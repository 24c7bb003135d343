"""A nameplate whose locked-rotor torque ratio is vanishingly small (within the schema's bound > 0): the extended
Kloss curve T = 2 T_b (1 + a s_b) s s_b / (s^2 + s_b^2 + 2 a s_b^2 |s|) through T(1) = T_lr has
a = (2 k_b - k_lr (1/s_b + s_b)) / (2 s_b (k_lr - k_b)) -> -1/s_b as k_lr -> 0, so 1 + a s_b -> 0 (no torque anywhere)
and the denominator becomes (s - s_b)^2: no curve passes through the rated point, and the fit divided by zero.
Before: gearcli's "internal error: ZeroDivisionError" (exit 1) from every command; now exit 2 naming the file (or
the --set) and input.motor, in one line, before any run."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli.cli import cli
from gearcli.model.spec import MotorSpec

ROOT = Path(__file__).resolve().parents[2]
STAR_DELTA = ROOT / "configs" / "motor_star_delta.toml"
RPM = 2.0 * math.pi / 60.0


def test_the_curve_degenerates_as_the_locked_rotor_ratio_vanishes():
    k_b, k_lr = 2.8, 1e-20
    for s_b in (0.05, 0.2, 0.6):  # the hand formula for a: 1 + a s_b is k_lr's order, the curve's torque 0
        a = (2 * k_b - k_lr * (1 / s_b + s_b)) / (2 * s_b * (k_lr - k_b))
        assert abs(1 + a * s_b) < 1e-15
    with pytest.raises(ValueError, match="no Kloss curve passes through these nameplate points"):
        MotorSpec.nameplate(15e3, 1460.0 * RPM, 1500.0 * RPM, k_b, k_lr)  # the file's nameplate


@pytest.mark.parametrize("command", ["design", "modes", "simulate"])
def test_a_degenerate_nameplate_is_exit_2_naming_file_and_key(tmp_path, command):
    text = STAR_DELTA.read_text(encoding="utf-8")
    assert "locked_rotor_torque_ratio = 2.3" in text
    path = tmp_path / "motor.toml"
    path.write_text(text.replace("locked_rotor_torque_ratio = 2.3", "locked_rotor_torque_ratio = 1e-20"),
                    encoding="utf-8")
    out = tmp_path / "out.json"
    res = CliRunner().invoke(cli, [command, str(path), "-o", str(out), "--format", "json"])
    assert res.exit_code == 2, res.output
    lines = [line for line in res.output.splitlines() if line.strip()]
    assert len(lines) == 1 and f"{path}: input.motor: no Kloss curve" in lines[0], res.output
    assert not out.exists()


def test_a_degenerate_nameplate_by_set_names_the_set():
    res = CliRunner().invoke(cli, ["design", str(STAR_DELTA), "--set", "input.motor.locked_rotor_torque_ratio=1e-20",
                                   "--format", "json"])
    assert res.exit_code == 2, res.output
    assert res.output.strip().startswith("gearcli: --set: input.motor: no Kloss curve"), res.output
