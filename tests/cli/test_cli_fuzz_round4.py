"""Regression tests for what the round-4 robustness campaign found (mutated design files, hostile options,
every command), one test per finding, through the real command line."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from tests.cli.test_cli_fuzz_findings import assert_clean_exit_2, run  # the same one-line-error check

ROOT = Path(__file__).resolve().parents[2]
CONVEYOR = ROOT / "configs" / "conveyor.toml"
SHORT = ("--set", "simulation.duration_s=0.05", "--set", "simulation.steps=50")


@pytest.mark.parametrize("vary", ["load.torque_Nm=nan,1", "input.speed_rpm=inf", "load.torque_Nm=1,-inf"])
def test_a_non_finite_vary_value_is_a_usage_error_and_writes_nothing(tmp_path, vary):
    # was exit 1, "internal error: ValueError: Out of range float values are not JSON compliant: nan", after the
    # sweep had run (the START:STOP:N form already refused nan; the list form parsed it as a TOML float)
    out = tmp_path / "sweep.json"
    res = run("sweep", CONVEYOR, *SHORT, "--vary", vary, "--jobs", "1", "-o", out)
    assert_clean_exit_2(res, "--vary", vary.split("=")[0], "finite")
    assert list(tmp_path.iterdir()) == []


PERIODIC = ROOT / "configs" / "conveyor_periodic.toml"


@pytest.mark.parametrize("command", [("simulate",), ("report", "--quick")])
def test_a_periodic_run_too_short_for_one_period_names_the_set(tmp_path, command):
    # conveyor_periodic has 1 s ramps: a 0.05 s run cannot hold one excitation period after them. Was
    # "gearcli: simulation.duration_s: ..." naming neither the --set nor the file
    out = tmp_path / "run.json"
    res = run(*command, PERIODIC, "--set", "simulation.duration_s=0.05", "-o", out)
    assert_clean_exit_2(res, "gearcli: --set: simulation.duration_s: steady = \"periodic\"")
    assert not out.exists()


def test_a_periodic_file_too_short_for_one_period_names_the_file(tmp_path):
    f = tmp_path / "short_periodic.toml"
    text = PERIODIC.read_text()
    assert "\nduration_s =" in text
    f.write_text("\n".join("duration_s = 0.5" if ln.startswith("duration_s =") else ln for ln in text.splitlines()))
    res = run("simulate", f, "-o", tmp_path / "run.json")
    assert_clean_exit_2(res, f"gearcli: {f}: simulation.duration_s: steady = \"periodic\"")
    assert not (tmp_path / "run.json").exists()


def test_an_unloaded_rattling_run_with_one_sample_writes_finite_json(tmp_path):
    # configs/extreme/rattle_zero_load.toml (no load, backlash) with simulation.steps = 1: the run's window F_t of
    # stage 2 was 0 while the check pass saw contact, so its relative error was inf and `-o run.json` an
    # internal error ("Out of range float values are not JSON compliant: inf")
    out = tmp_path / "run.json"
    res = run("simulate", ROOT / "configs" / "extreme" / "rattle_zero_load.toml", "--set", "simulation.steps=1", "-o", out)
    assert res.exit_code == 0, res.output
    assert "internal error" not in res.stderr and " inf " not in res.stderr, res.stderr

    def finite_only(constant):
        raise AssertionError(f"non-finite {constant} in the JSON")

    doc = json.loads(out.read_text(), parse_constant=finite_only)
    assert all(s["error_estimate"] is None or all(isinstance(v, float) for v in s["error_estimate"]["relative"].values())
               for s in doc["summary"]["stages"])


MOTOR_DUTY = ROOT / "configs" / "motor_duty_starts.toml"


def test_a_life_run_shorter_than_the_motor_start_is_lengthened_past_the_start(tmp_path):
    # the conveyor's motor start (900 kg m^2 drum) in a 0.05 s run. Was exit 2, "no whole mesh cycle ... lengthen
    # simulation.duration_s": the window sat inside the start. The start has not reached its operating speed by the
    # run's end, so the settle test cannot call the window settled and moves it past the run's end until the start
    # is over (gearcli.simulate.settle.next_window): the window is then after the motor's start, its mesh cycles
    # counted, and what is still ringing there is warned
    out = tmp_path / "life.json"
    res = run("life", MOTOR_DUTY, "--set", "simulation.duration_s=0.05", "--format", "json", "-o", out)
    assert res.exit_code == 0, res.output
    doc = json.loads(out.read_text())
    for point in doc["life"]["points"]:
        assert min(point["mesh_cycles"]) >= 1, point
        if point["start"] is not None:  # a point with starts: the start counted outlasts the run given
            assert point["start"]["span_s"][1] > 0.05, point["start"]
    windows = [w["message"] for w in doc["warnings"] if "statistics window" in w["message"]]
    assert windows and all(float(m.split("statistics window ")[1].split("–")[0]) > 0.05 for m in windows), windows


def test_a_life_point_too_slow_to_simulate_says_the_duration_is_the_routes_and_names_the_file(tmp_path):
    # a duty point at 0.001 rpm: the dynamic route lengthens its run to hold 40 mesh cycles of the slowest mesh
    # (capped at 600 s), which is over the computing budget. The message said only "Shorten simulation.duration_s"
    # (the route would lengthen it again) and named no file
    out = tmp_path / "life.json"
    res = run("life", ROOT / "configs" / "mixer_planetary_motor.toml", "--set", "duty.0.speed_rpm=0.001",
              "--set", "simulation.steps=50", "-o", out)
    assert_clean_exit_2(res, "mixer_planetary_motor.toml: duty point mixing:", "600 s",
                        "whatever simulation.duration_s says", "--static")
    assert res.stderr.count("mixer_planetary_motor.toml") == 1, res.stderr  # the file named once
    assert not out.exists()


@pytest.mark.skipif(sys.platform != "linux", reason="/dev/stdout is a link into /proc/self/fd")
def test_o_dev_stdout_writes_the_stream_the_shell_opened(tmp_path):
    # /dev/stdout names descriptor 1, the stream the shell opened. On a pipe it was refused as a FIFO; on
    # `>> log` the atomic write replaced the log file behind the link, losing what it held. Both are stdout now:
    # the pipe gets the JSON, the log keeps its first line and gets the JSON after it
    res = subprocess.run([sys.executable, "-m", "gearcli", "design", str(CONVEYOR), "--format", "json", "-o",
                          "/dev/stdout"], capture_output=True, text=True, timeout=120)
    assert res.returncode == 0, res.stderr
    assert json.loads(res.stdout)["stages"]
    log = tmp_path / "log"
    log.write_text("kept line\n")
    with open(log, "a") as fh:
        res = subprocess.run([sys.executable, "-m", "gearcli", "design", str(CONVEYOR), "--format", "json", "-o",
                              "/dev/fd/1"], stdout=fh, stderr=subprocess.PIPE, text=True, timeout=120)
    assert res.returncode == 0, res.stderr
    head, body = log.read_text().split("\n", 1)
    assert head == "kept line" and json.loads(body)["stages"]


@pytest.mark.skipif(sys.platform != "linux", reason="/dev/stderr is a link into /proc/self/fd")
def test_o_another_open_descriptor_is_refused_not_replaced(tmp_path):
    # `-o /dev/stderr 2>> log` replaced the log with the data; another descriptor than stdout is refused (exit 2)
    log = tmp_path / "log"
    log.write_text("kept line\n")
    with open(log, "a") as fh:
        res = subprocess.run([sys.executable, "-m", "gearcli", "design", str(CONVEYOR), "--format", "json", "-o",
                              "/dev/stderr"], stdout=subprocess.PIPE, stderr=fh, text=True, timeout=120)
    assert res.returncode == 2 and res.stdout == ""
    text = log.read_text()
    assert text.startswith("kept line\n") and "open descriptor 2" in text and "Traceback" not in text


def test_o_a_named_fifo_is_still_refused(tmp_path):
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    res = run("design", CONVEYOR, "-o", fifo)
    assert_clean_exit_2(res, "is a FIFO")


def test_a_dangling_link_names_its_targets_missing_directory(tmp_path):
    # was "no such directory: <the link's own directory>", which exists
    link = tmp_path / "out.json"
    link.symlink_to(tmp_path / "gone" / "out.json")
    res = run("design", CONVEYOR, "-o", link)
    assert_clean_exit_2(res, f"no such directory: {tmp_path / 'gone'} (the link's target)")
    assert not (tmp_path / "gone").exists() and link.is_symlink()
