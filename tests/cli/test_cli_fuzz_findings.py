"""Regression tests for what the bounds fuzz test (tests/property/test_bounds_fuzz.py) found, one each."""

from __future__ import annotations

from pathlib import Path

from click.testing import CliRunner

from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]
SEED = ROOT / "configs" / "concrete_mixer.toml"


def run(*args):
    return CliRunner().invoke(cli, [str(a) for a in args])


def assert_clean_exit_2(res, *fragments: str) -> None:
    assert res.exit_code == 2, (res.exit_code, res.output)
    assert "Traceback" not in res.stderr and "internal error" not in res.stderr, res.stderr
    for f in fragments:
        assert f in res.stderr, (f, res.stderr)


def test_a_bore_wider_than_the_gear_is_a_design_error_not_an_internal_error():
    # stage 1 pinion: z 21, m_n 12, beta 12 deg: d = 21 * 12 / cos 12 deg = 257.6 mm, d_f = d - 2.5 m_n = 227.6 mm;
    # a 10,000 mm bore (the key's upper bound) left a negative inertia ("shaft inertias must be positive")
    for cmd in ("design", "modes", "simulate"):
        res = run(cmd, SEED, "--set", "stage.0.pinion.bore_diameter_mm=10000")
        assert_clean_exit_2(res, "stage[0].pinion.bore_diameter_mm", "root diameter", "227.6")


def test_a_bore_just_inside_the_root_diameter_is_accepted():
    res = run("design", SEED, "--set", "stage.0.pinion.bore_diameter_mm=200", "--format", "json")
    assert res.exit_code == 0, res.stderr


def test_a_bore_with_a_given_inertia_does_not_set_the_inertia():
    res = run("design", SEED, "--set", "stage.0.pinion.bore_diameter_mm=300", "--set",
              "stage.0.pinion.inertia_kg_m2=2.5", "--format", "json")
    assert res.exit_code == 0, res.stderr


def test_a_window_after_the_end_of_the_run_is_refused_naming_the_file_or_set(tmp_path):
    # was "gearcli: simulation.window_start_s: ..." without the file, and only after the design warnings
    res = run("simulate", SEED, "--set", "simulation.window_start_s=3600")
    assert_clean_exit_2(res, "gearcli: --set: simulation.window_start_s", "0.5 s")
    f = tmp_path / "late_window.toml"
    f.write_text(SEED.read_text() + "window_start_s = 0.5\n")  # [simulation] is the seed's last table
    res = run("design", f)
    assert_clean_exit_2(res, f"gearcli: {f}: simulation.window_start_s", "must be below")


def test_a_subnormal_torque_ripple_order_is_refused_naming_the_key(tmp_path):
    # was "internal error: ValueError: cannot convert NaN to integer ratio" after overflow warnings
    f = tmp_path / "ripple.toml"
    text = SEED.read_text().replace("[input]                        # 600 rpm motor, STEP(t, 0, 0, 0.18, 3600 deg/s)\n",
                                    "[input]\ndrive = \"torque\"\ntorque_Nm = 240\n"
                                    "torque_ripple = [{ amplitude_percent = 5, order = 5e-324 }]\n")
    assert "torque_ripple" in text
    f.write_text(text)
    for cmd in ("design", "simulate"):
        res = run(cmd, f, "--set", "simulation.duration_s=0.02", "--set", "simulation.steps=20")
        assert_clean_exit_2(res, "input.torque_ripple[0].order", "must be ≥ 0.001")
