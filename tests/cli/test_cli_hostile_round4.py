"""Issue 31, the fourth hostile re-test: data lost, hangs and crashes, and unclear behaviour, each finding as
measured there (the compiled-engine and planetary findings have their own files). Every test failed on the
code the issue was filed against (7c75a79) and passes now.

In-process (click's CliRunner) wherever a fresh interpreter proves nothing more; a subprocess where the
finding is about the process: a FIFO that would hang it, a device that refuses its standard output.
"""

from __future__ import annotations

import csv
import io
import json
import math
import os
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]
CONFIGS = ROOT / "configs"
DUTY = CONFIGS / "mixer_duty.toml"  # D of the issue
SEED = CONFIGS / "concrete_mixer.toml"  # S
PLANETARY = CONFIGS / "planetary_stage.toml"  # P
POSIX = pytest.mark.skipif(sys.platform == "win32", reason="POSIX FIFOs, devices and descriptors")
HISTORY = "time_s,torque_Nm,speed_rpm\n0,300000,600\n3600,500000,600\n7200,0,600\n"  # s.csv of the issue


def run(*args, env=None, input=None):
    return CliRunner(env=env).invoke(cli, [str(a) for a in args], input=input)


def gearcli(*args, timeout=60, **kw) -> subprocess.CompletedProcess:
    streams = {} if "stdout" in kw else {"capture_output": True}
    return subprocess.run([sys.executable, "-m", "gearcli", *map(str, args)], text=True, timeout=timeout,
                          **streams, **kw)


def assert_usage_error(res, *needles: str) -> None:
    """Exit 2, one clean message (no traceback, no internal error) holding every needle."""
    err = res.stderr
    assert res.exit_code == 2, (res.exit_code, err, res.stdout[-500:])
    assert "Traceback" not in err and "internal error" not in err, err
    for n in needles:
        assert n in err, (n, err)


def _history(tmp_path: Path, text: str = HISTORY, name: str = "s.csv") -> Path:
    p = tmp_path / name
    p.write_text(text)
    return p


# ------------------------------------------------------------------------------------------ data lost
def test_life_series_file_is_protected_from_o(tmp_path):
    # was: exit 0, the measured history replaced by the life CSV
    s = _history(tmp_path)
    res = run("life", DUTY, "--static", "--series", s, "-o", s)
    assert_usage_error(res, "is the input file")
    assert s.read_text() == HISTORY
    assert sorted(os.listdir(tmp_path)) == ["s.csv"]  # no temporary file either


def test_life_series_file_is_protected_from_plots(tmp_path):
    # the series named like a figure in the --plots directory: --plots would have written over it
    s = _history(tmp_path, name="pitting.png")
    res = run("life", DUTY, "--static", "--series", s, "--plots", tmp_path, "-o", tmp_path / "l.csv")
    assert_usage_error(res, "--plots would overwrite")
    assert s.read_text() == HISTORY
    assert not (tmp_path / "l.csv").exists()  # refused before any work


def test_the_inputs_protected_from_o_are_named_in_one_place():
    """One rule: every parameter that names a file a command reads is protected, by the same function, from
    -o and from --plots (gearcli.cli.INPUT_PARAMS); a command gaining an input adds it there."""
    import inspect

    from gearcli import cli as cli_module
    from gearcli.cli import common, design_cmds, engine_cmds, study_cmds

    assert cli_module.INPUT_PARAMS == ("file", "series")
    src = "".join(inspect.getsource(m) for m in (cli_module, common, design_cmds, engine_cmds, study_cmds))
    assert src.count("inputs=context_inputs()") + src.count("inputs=context_inputs(),") >= 2  # check_target, sweep
    assert "[file, target.path]" not in src  # no command keeps a list of its own


RESUME = ("--vary", "input.speed_rpm=1320,1380", "--set", "simulation.duration_s=0.4", "--jobs", "1")


def _rows(path: Path) -> list[list[str]]:
    return list(csv.reader(io.StringIO(path.read_text().partition("\n")[2])))


def test_sweep_resume_with_nothing_to_do_leaves_the_file_byte_identical(tmp_path):
    # was: every negative number of the finished rows rewritten as '-249.68 (the formula escape on numbers)
    out = tmp_path / "a.csv"
    # the load reversed: every mesh force of every row negative (a settled window of the forward load may have none)
    reversed_load = (*RESUME, "--set", "load.torque_Nmm=-5.31e6")
    assert run("sweep", SEED, *reversed_load, "-o", out).exit_code == 0
    fresh = out.read_bytes()
    rows = _rows(out)
    assert any(cell.startswith("-") for row in rows[1:] for cell in row[4:]), "the scene must give negative numbers"
    res = run("sweep", SEED, *reversed_load, "-o", out)
    assert res.exit_code == 0, res.stderr
    assert out.read_bytes() == fresh
    assert "'-" not in out.read_text()


def test_sweep_resumed_rows_equal_fresh_rows(tmp_path):
    out = tmp_path / "a.csv"
    assert run("sweep", SEED, *RESUME, "-o", out).exit_code == 0
    fresh = out.read_text()
    lines = fresh.splitlines(keepends=True)
    out.write_text("".join(lines[:-1]))  # the last point lost (an interrupted sweep)
    res = run("sweep", SEED, *RESUME, "-o", out)
    assert res.exit_code == 0, res.stderr
    again, first = _rows(out), list(csv.reader(io.StringIO("".join(lines[1:]))))
    header = first[0]
    timing = {header.index("wall_s")}  # the one column a rerun may change (docs/sweep: "except wall_s")
    assert len(again) == len(first)
    for a, b in zip(again, first, strict=True):
        assert [x for i, x in enumerate(a) if i not in timing] == [x for i, x in enumerate(b) if i not in timing]
    assert out.read_text().splitlines()[:-1] == fresh.splitlines()[:-1]  # the kept row byte for byte


def test_life_series_rows_with_negative_speed_are_counted_and_said(tmp_path):
    # was: the reverse row dropped without a word: hours 1.0 instead of 2.0, the highest torque's hour gone
    s = _history(tmp_path, HISTORY.replace("3600,500000,600", "3600,500000,-600"))
    res = run("life", DUTY, "--static", "--series", s, "--format", "json")
    assert res.exit_code == 0, res.stderr
    doc = json.loads(res.stdout)
    assert doc["life"]["hours"] == pytest.approx(2.0, rel=1e-12)  # both rows' hours: 3600 s + 3600 s
    top = max(p["torque_Nm"] for p in doc["life"]["points"])
    assert top == pytest.approx(500000.0, rel=1e-12)  # the reverse row's level is in the spectrum
    said = [w["message"] for w in doc["warnings"] if "reverse" in w["message"]]
    assert said and "drive flanks" in said[0] and "data row 2" in said[0], doc["warnings"]
    # its revolutions count like a forward row's: the same damage as the history with +600 rpm
    fwd = run("life", DUTY, "--static", "--series", _history(tmp_path, name="f.csv"), "--format", "json")
    assert json.loads(fwd.stdout)["life"]["stages"] == doc["life"]["stages"]


# ---------------------------------------------------------------------------------- hang, crash
@POSIX
def test_life_series_fifo_without_a_writer_is_refused_not_a_hang(tmp_path):
    fifo = tmp_path / "f"
    os.mkfifo(fifo)
    res = gearcli("life", DUTY, "--static", "--series", fifo, timeout=60)  # was: hung for ever
    assert res.returncode == 2, res.stderr
    assert "FIFO" in res.stderr and "Traceback" not in res.stderr


def test_motor_table_with_negative_speeds_is_a_validation_error():
    # was: accepted by validation, then "internal error: ValueError: a motor needs a positive synchronous speed"
    res = run("design", CONFIGS / "conveyor_motor.toml", "--set", "input.motor={torque_speed=[[-100,700],[-50,600]]}")
    assert_usage_error(res, "input.motor", "torque_speed", "0 or more")


@POSIX
@pytest.mark.skipif(not os.path.exists("/dev/full"), reason="needs /dev/full")
@pytest.mark.parametrize("args", [("design", SEED, "--format", "json"), ("life", DUTY, "--static", "--format", "json"),
                                  ("schema",), ("init",), ("--help",), ("modes", SEED, "--format", "csv")],
                         ids=lambda a: str(a[0]))
def test_a_full_device_on_stdout_is_exit_2_naming_it(args):
    # was: "internal error: OSError: [Errno 28] No space left on device", exit 1
    with open("/dev/full", "w") as full:
        res = gearcli(*args, stdout=full, stderr=subprocess.PIPE)
    assert res.returncode == 2, res.stderr
    assert "standard output: cannot write: No space left on device" in res.stderr
    assert "Traceback" not in res.stderr and "internal error" not in res.stderr and "Exception ignored" not in res.stderr


# ------------------------------------------------------------------------ verdicts from impossible input
def _duty_file(tmp_path: Path, extra: str) -> Path:
    text = DUTY.read_text()
    anchor = 'name = "charging"\nhours = 3000\ntorque_Nm = 300000\nspeed_rpm = 600\n'
    assert anchor in text
    f = tmp_path / "duty.toml"
    f.write_text(text.replace(anchor, anchor + extra))
    return f


def test_a_duty_set_that_contradicts_the_point_is_an_error(tmp_path):
    # was: table and JSON 300000 / 600 while the damage was computed at 600 kN m / 1200 rpm
    f = _duty_file(tmp_path, 'set = { "load.torque_Nm" = 600000, "input.speed_rpm" = 1200 }\n')
    for cmd in (("life", f, "--static"), ("design", f)):
        assert_usage_error(run(*cmd), "duty[0]", "load.torque_Nm", "the point's own")


def test_a_duty_point_reports_what_it_computed():
    """The point's reported torque is the one its rating used: the last stage's static tangential force is
    the pinion torque T_out / (u η) over the pinion's pitch radius (F_t = 2 T_1 / d_1, written out here)."""
    doc = json.loads(run("life", DUTY, "--static", "--format", "json").stdout)
    design = json.loads(run("design", DUTY, "--format", "json").stdout)
    last = design["stages"][-1]
    for p in doc["life"]["points"]:
        t_pinion_Nmm = p["torque_Nm"] * 1e3 / (last["ratio"] * last["efficiency"])
        f_t = 2.0 * t_pinion_Nmm / last["pinion"]["pitch_diameter_mm"]
        bins = doc["life"]["stages"][-1]["gear"]["pitting"]["bins"]
        force = next(b["force_N"] for b in bins if b["point"] == p["name"])
        assert force == pytest.approx(f_t, rel=1e-9)  # rounding of the printed ratio and diameters only


def test_per_point_design_warnings_reach_the_life_output(tmp_path):
    # was: pinion damage 171.5 and no warning, where `design` of the same change warns of undercut; a point's own
    # tooth count is now refused (its damage would be summed with another gear's: tr10c), so the point's own
    # warnings come from a point's face load factor
    f = _duty_file(tmp_path, 'set = { "rating.face_load_factor" = 4.0 }\n')
    res = run("life", f, "--static", "--format", "json")
    assert res.exit_code == 0, res.stderr
    warnings = [w["message"] for w in json.loads(res.stdout)["warnings"]]
    assert any(w.startswith("duty point charging:") and "S_H" in w for w in warnings), warnings
    assert "duty point charging:" in res.stderr and "S_H" in res.stderr  # and on the terminal
    assert not any(w.startswith("duty point mixing:") for w in warnings)  # only what differs from the base file
    teeth = _duty_file(tmp_path, 'set = { "stage.0.pinion.teeth" = 5 }\n')
    assert_usage_error(run("life", teeth, "--static"), "duty[0]", "stage.0.pinion.teeth", "a gear is the same")


def test_a_negative_duty_torque_gets_the_warning_docs_promise(tmp_path):
    res = run("life", DUTY, "--static", "--set", "duty.0.torque_Nm=-300000", "--format", "json")
    assert res.exit_code == 0, res.stderr
    warnings = [w["message"] for w in json.loads(res.stdout)["warnings"]]
    assert any("charging" in w and "load reversal" in w and "back flanks" in w for w in warnings), warnings


def test_a_motor_table_held_past_its_last_speed_is_refused():
    # was: the motor ran away (3290 rpm at 1 s) and the only warning said it "cannot start"
    res = run("design", CONFIGS / "conveyor_motor.toml", "--set", "input.motor={torque_speed=[[0,2000],[1500,2000]]}")
    assert_usage_error(res, "input.motor", "falls to 0 at its synchronous speed", "run away")


def test_a_motor_table_ending_in_braking_keeps_its_synchronous_speed_where_torque_is_0():
    from gearcli import api

    loaded, design = api.load_and_design(str(CONFIGS / "conveyor_motor.toml"), [
        "input.motor={torque_speed=[[0,600],[1400,600],[1500,0],[1550,-300]]}"])
    motor = api.model_spec(loaded.design, design).drive.motor
    # the zero crossing (1500 rpm), not the table's last speed (1550 rpm, which the old code took)
    assert motor.synchronous_speed_rad_s * 30.0 / math.pi == pytest.approx(1500.0, rel=1e-12)


def test_a_run_away_motor_is_detected_and_named():
    # an overhauling load (-30 kN m at the drum) drives the motor through its generating breakdown: it runs
    # away; the old code said only that the motor "cannot start"
    res = run("simulate", CONFIGS / "conveyor_motor.toml", "--set", "load.torque_Nm=-30000", "--set",
              "simulation.duration_s=0.4", "--set", "simulation.steps=400", "--set", "simulation.engine=python",
              "--format", "json")
    assert res.exit_code == 0, res.stderr
    assert "the motor runs away" in res.stderr, res.stderr
    assert "cannot start" not in res.stderr
    runaway = next(line for line in res.stderr.splitlines() if "runs away" in line)
    assert "1500 rpm" in runaway  # names the synchronous speed it passed


@pytest.mark.parametrize(("sets", "needles"), [
    (("input.motor.rated_speed_rpm=1",), ("rated slip", "0.999")),
    (('input.starting="star_delta"', "input.switch_speed_rpm=1600"), ("switch_speed_rpm", "never switch")),
], ids=["nameplate_55kW_at_1rpm", "switch_above_synchronous"])
def test_impossible_machines_are_refused(sets, needles):
    args = [a for s in sets for a in ("--set", s)]
    assert_usage_error(run("design", CONFIGS / "conveyor_motor.toml", *args), *needles)


def test_a_switch_speed_below_synchronous_stays_accepted():
    res = run("design", CONFIGS / "conveyor_motor.toml", "--set", 'input.starting="star_delta"', "--set",
              "input.switch_speed_rpm=1350", "--format", "json")
    assert res.exit_code == 0, res.stderr


# ----------------------------------------------------------------------------------- unclear behaviour
@pytest.mark.parametrize("args", [("life", DUTY, "--static"), ("life", DUTY), ("sweep", SEED, "--vary",
                                  "input.speed_rpm=300", "--jobs", "1"), ("design", SEED)],
                         ids=["life_static", "life", "sweep", "design"])
def test_memory_limit_garbage_is_refused_by_every_command(args):
    res = run(*args, env={"GEARCLI_MEMORY_LIMIT_MB": "garbage"})
    assert_usage_error(res, "GEARCLI_MEMORY_LIMIT_MB", "'garbage'")


@pytest.mark.parametrize("args", [("life", DUTY), ("sweep", SEED, "--vary", "input.speed_rpm=300", "--jobs", "1")],
                         ids=["life", "sweep"])
def test_memory_limit_of_1_MiB_is_honoured_by_life_and_sweep(args, tmp_path):
    # the mixer's runs hold 2000+ samples x 29 values x 28 bytes: well over 1 MiB (bounds.BYTES_PER_VALUE)
    res = run(*args, "-o", tmp_path / "out.csv", env={"GEARCLI_MEMORY_LIMIT_MB": "1"})
    assert_usage_error(res, "over the limit of 1 MiB")
    assert not (tmp_path / "out.csv").exists()


def test_life_plots_into_an_unwritable_place_fails_before_any_work(tmp_path):
    # was: the full run, the CSV written, then exit 1 (modes/report/sweep check up front)
    blocker = tmp_path / "file"
    blocker.write_text("x")
    res = run("life", DUTY, "--static", "--plots", blocker / "figures", "-o", tmp_path / "l.csv")
    assert_usage_error(res, "--plots")
    assert not (tmp_path / "l.csv").exists()


@pytest.mark.skipif(hasattr(os, "geteuid") and os.geteuid() == 0, reason="root writes into a read-only directory")
def test_life_plots_into_a_read_only_directory_fails_before_any_work(tmp_path):
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o555)
    try:
        res = run("life", DUTY, "--static", "--plots", ro, "-o", tmp_path / "l.csv")
    finally:
        ro.chmod(0o755)
    assert_usage_error(res, "--plots", "not writable")
    assert not (tmp_path / "l.csv").exists()


def test_life_series_dash_reads_stdin(tmp_path):
    # was: "-: cannot read: No such file or directory"
    res = run("life", DUTY, "--static", "--series", "-", "--format", "json", input=HISTORY)
    assert res.exit_code == 0, res.stderr
    from_stdin = json.loads(res.stdout)["life"]
    from_file = json.loads(run("life", DUTY, "--static", "--series", _history(tmp_path), "--format",
                               "json").stdout)["life"]
    assert from_stdin["stages"] == from_file["stages"] and from_stdin["hours"] == pytest.approx(2.0, rel=1e-12)


def test_life_design_file_and_series_both_on_stdin_is_refused():
    res = run("life", "-", "--static", "--series", "-", input=DUTY.read_text())
    assert_usage_error(res, "(standard input) already carries the design file")


@pytest.mark.parametrize("key", ["stage.0.planet.count", "load.speed_exponent"])
def test_sweep_refuses_a_whole_number_key_drawn_from_a_continuous_distribution(tmp_path, key):
    # was: every point failed at run time (exit 1)
    res = run("sweep", PLANETARY, "--random", f"{key}=uniform(1,5)", "--samples", "2", "-o", tmp_path / "x.csv")
    assert_usage_error(res, "--random", key, "whole number")
    assert not (tmp_path / "x.csv").exists()


def test_sweep_still_draws_a_real_key(tmp_path):
    res = run("sweep", SEED, "--random", "stage.0.backlash_mm=uniform(0.1,0.3)", "--samples", "1", "--seed", "1",
              "--jobs", "1", "--set", "simulation.duration_s=0.05", "-o", tmp_path / "x.csv")
    assert res.exit_code == 0, res.stderr


# --------------------------------------------------------------------------------------------- cosmetic
def test_narrow_terminal_life_table_keeps_every_number_whole():
    # was: `1.02 / 4e+0 / 9` for 1.024e+09 at COLUMNS=60
    pd = CONFIGS / "planetary_duty.toml"
    doc = json.loads(run("life", pd, "--static", "--format", "json").stdout)["life"]
    table = run("life", pd, "--static", "--format", "table", env={"COLUMNS": "60"}).stdout
    assert max(len(line) for line in table.splitlines()) <= 60
    pit = doc["stages"][0]["pinion"]["pitting"]
    want = [f"{sum(b['cycles'] for b in pit['bins']):.4g}", f"{pit['damage']:.4g}"]  # the sum row, as printed
    want += [f"{b['cycles']:.4g}" for b in pit["bins"]] + [f"{b['damage']:.3g}" for b in pit["bins"]]
    for w in want:
        assert w in table, (w, table[:3000])
    assert "left out" not in table  # the spectrum split into parts that fit, nothing dropped


SUBNORMAL_KEYS = [
    (DUTY, "duty.0.hours", "duty[0].hours"),
    (DUTY, "bearing.0.factors.e", "bearing[0].factors.e"),
    (DUTY, "bearing.0.factors.Y", "bearing[0].factors.Y"),
    (DUTY, "lubricant.temperature_C", "lubricant.temperature_C"),
    (PLANETARY, "stage.0.planet.position_error_um=[0.0, 5e-324, 0.0]", "stage[0].planet.position_error_um"),
    (CONFIGS / "conveyor_motor.toml", "input.motor={torque_speed=[[0, 700], [5e-324, 600], [1500, 0]]}",
     "input.motor.torque_speed"),
    (CONFIGS / "motor_vfd.toml", "input.torque_limit_Nm", "input.torque_limit_Nm"),
]


@pytest.mark.parametrize(("path", "key", "shown"), SUBNORMAL_KEYS, ids=[s for _, _, s in SUBNORMAL_KEYS])
def test_subnormal_values_are_refused_on_every_float_key(path, key, shown):
    # was: 5e-324 accepted (JSON then held 1.78e-319 cycles)
    setting = key if "=" in key else f"{key}=5e-324"
    assert_usage_error(run("design", path, "--set", setting), shown, "must be", "subnormal")


def test_the_float_rule_lives_in_one_place():
    """Every table of the design file derives from StrictTable, whose one field validator refuses a
    subnormal in any float (a key added later is covered without a word)."""
    from gearcli.config import DesignFile
    from gearcli.config.bounds_types import StrictTable
    from gearcli.config.keys import is_model, item_type, unwrap

    seen: set[type] = set()

    def walk(tp) -> None:
        tp = unwrap(tp)
        for arg in getattr(tp, "__args__", ()) or ():
            walk(arg)
        if is_model(tp) and tp not in seen:
            seen.add(tp)
            for info in tp.model_fields.values():
                walk(info.annotation)
        elif getattr(tp, "__origin__", None) in (list, dict):
            walk(item_type(tp))

    walk(DesignFile)
    assert len(seen) > 15
    assert [m.__name__ for m in seen if not issubclass(m, StrictTable)] == []


def test_zero_and_ordinary_small_values_stay_accepted():
    res = run("design", DUTY, "--set", "bearing.0.factors.e=0.0", "--set", "lubricant.temperature_C=1e-300",
              "--format", "json")
    assert res.exit_code == 0, res.stderr


def test_quiet_goes_before_or_after_every_command(tmp_path):
    # was: "No such option '-q'" for sweep and schema; `gearcli -q sweep` printed its summary
    assert run("schema", "-q").exit_code == 0
    sweep = ("sweep", SEED, "--vary", "input.speed_rpm=300", "--jobs", "1", "--set", "simulation.duration_s=0.05")
    for args in (("-q", *sweep), (*sweep, "-q")):
        res = run(*args, "-o", tmp_path / "q.csv")
        assert res.exit_code == 0, res.stderr
        assert res.stderr == "", res.stderr
        (tmp_path / "q.csv").unlink()
    loud = run(*sweep, "-o", tmp_path / "q.csv")
    assert "sweep: 1 points, 0 failed" in loud.stderr


@POSIX
def test_init_on_a_fifo_does_not_suggest_an_option_init_lacks(tmp_path):
    fifo = tmp_path / "f"
    os.mkfifo(fifo)
    res = run("init", fifo)
    assert_usage_error(res, "FIFO")
    assert "-o -" not in res.stderr and "'-'" in res.stderr
