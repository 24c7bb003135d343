"""Hostile inputs that reached an internal error (exit 1, "internal error: ...") instead of the contract's exit 2
naming the file and the key, with no output file left behind (trial tr17d).

- A planetary ring cut by a sharp basic rack (``basic_rack.root_radius = 0``) and no pinion-type cutter has a root
  fillet of radius ρ_F = ρ_fP = 0: ISO 6336-3's notch parameter q_s = s_Fn / (2 ρ_F) divided by zero.
- A sweep's ``-o FILE`` whose identity is valid JSON of another shape (a list, ``"sweep": 3``), or whose JSON rows
  are not objects: ``'list' object has no attribute 'get'``.
"""

from __future__ import annotations

import csv
import json
import math
import shutil
from pathlib import Path

import pytest
from cases import HERE
from click.testing import CliRunner

from gearcli.cli import cli

SHARP = HERE / "rule_planetary_ring_sharp_root.toml"
SEED = Path(__file__).resolve().parents[2] / "configs" / "concrete_mixer.toml"
ONE_POINT = ["--vary", "input.speed_rpm=600", "--jobs", "1"]


def _run(*args: str):
    return CliRunner().invoke(cli, list(args))


def _refused(res, source: str, key: str) -> None:
    assert res.exit_code == 2, (res.exit_code, res.stderr)
    assert f"gearcli: {source}: {key}: " in res.stderr, res.stderr
    assert "Traceback" not in res.stderr and "internal error" not in res.stderr, res.stderr


@pytest.mark.parametrize("command", [["design"], ["life", "--static"]])
def test_a_ring_with_a_sharp_rack_root_is_refused_naming_the_key(command, tmp_path):
    design = tmp_path / "sharp.toml"
    shutil.copyfile(SHARP, design)
    if command[0] == "life":
        design.write_text(design.read_text() + '\n[[duty]]\nname = "run"\nhours = 1000\ntorque_Nm = 100\nspeed_rpm = 1000\n')
    out = tmp_path / "out.json"
    res = _run(*command, str(design), "-o", str(out))
    _refused(res, str(design), "stage[0].basic_rack.root_radius")
    assert "ρ_F = 0 mm" in res.stderr and "cutter_teeth" in res.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["sharp.toml"]  # no output, no temporary file


def test_the_same_ring_rates_with_a_fillet_or_a_cutter(tmp_path):
    """The refusal is the sharp root's alone: the ISO 53 rack's fillet (ρ_fP = 0.38 m_n), or a pinion-type cutter,
    whose generation rounds the root even from a sharp rack (ρ_F = 2 G² m_n / (cos θ (z_0 cos² θ − 2G)) > 0)."""
    text = SHARP.read_text()
    for name, edited in (("fillet", text.replace("root_radius = 0 }", "root_radius = 0.38 }")),
                         ("cutter", text.replace("root_roughness_Rz_um = 20 }\n\n[lub",
                                                 "root_roughness_Rz_um = 20, cutter_teeth = 25 }\n\n[lub"))):
        assert edited != text
        design = tmp_path / f"{name}.toml"
        design.write_text(edited)
        res = _run("design", str(design), "--format", "json", "-q")
        assert res.exit_code == 0, res.stderr
        ring = json.loads(res.stdout)["stages"][0]["meshes"][1]["rating"]["gear"]
        assert ring["Y_S"] > 1.0 and ring["S_F"] > 0.0  # a finite stress correction and safety


def _resume_against(tmp_path: Path, name: str, text: str):
    out = tmp_path / name
    out.write_text(text)
    before = out.read_bytes()
    res = _run("sweep", str(SEED), *ONE_POINT, "-q", "-o", str(out))
    return res, out, before


@pytest.mark.parametrize(("name", "text"), [
    ("list.csv", '# gearcli sweep: [1, 2]\ninput.speed_rpm,status\n600,ok\n'),
    ("number.csv", '# gearcli sweep: 3\n'),
    ("sweep_is_a_number.csv", '# gearcli sweep: {"sweep": 3}\ninput.speed_rpm,status\n600,ok\n'),
    ("list.json", '[{"sweep": {}, "rows": []}]'),
    ("sweep_is_a_list.json", '{"gearcli_version": "0.1.0", "sweep": [1], "rows": []}'),
    ("sweep_is_text.json", '{"gearcli_version": "0.1.0", "sweep": "x", "rows": []}'),
    ("sweep_is_null.json", '{"gearcli_version": "0.1.0", "sweep": null, "rows": []}'),
    # nested past the JSON parser's recursion limit: RecursionError, an internal error too
    ("deep.json", "[" * 200_000 + "]" * 200_000),
    ("deep_identity.csv", "# gearcli sweep: " + "[" * 200_000 + "]" * 200_000 + "\n"),
])
def test_a_resume_file_of_another_shape_is_not_ours(tmp_path, name, text):
    res, out, before = _resume_against(tmp_path, name, text)
    assert res.exit_code == 2, (res.exit_code, res.stderr)
    assert f"gearcli: {out}: exists and is not a gearcli sweep file" in res.stderr, res.stderr
    assert "internal error" not in res.stderr and "Traceback" not in res.stderr
    assert out.read_bytes() == before  # left as it was, nothing beside it
    assert sorted(p.name for p in tmp_path.iterdir()) == [name]


def test_json_rows_that_are_not_objects_are_computed_again(tmp_path):
    """A resume file of this very sweep whose rows were replaced by numbers, text, null and a list: those are no
    finished points, so the point runs and the file ends as an uninterrupted run's (one row, at its speed). (A row's
    cells may be lists or tables: a varied key's value can be an array.)"""
    fresh = tmp_path / "fresh.json"
    assert _run("sweep", str(SEED), *ONE_POINT, "-q", "-o", str(fresh)).exit_code == 0
    doc = json.loads(fresh.read_text())
    doc["rows"] = [1, "x", None, []]
    res, out, _ = _resume_against(tmp_path, "resume.json", json.dumps(doc))
    assert res.exit_code == 0, res.stderr
    rows = json.loads(out.read_text())["rows"]
    assert [(r["input.speed_rpm"], r["status"]) for r in rows] == [(600, "ok")]


DUTY = Path(__file__).resolve().parents[2] / "configs" / "mixer_duty.toml"
HOUR_CAP_S = 1e7 * 3600.0  # a [[duty]] point's hours are at most 1e7; a history may span no more


def _history(tmp_path: Path, *times: float) -> Path:
    path = tmp_path / "history.csv"
    path.write_text("time_s,torque_Nm,speed_rpm\n" + "".join(f"{t!r},1000,600\n" for t in times))
    return path


@pytest.mark.parametrize("times", [(0.0, 1e300), (-1e308, 1e308), (0.0, 1e308), (0.0, HOUR_CAP_S * 1.001)],
                         ids=["1e300_s", "overflows", "1e308_s", "just_over_the_cap"])
def test_a_history_longer_than_a_duty_point_may_hold_is_refused(tmp_path, times):
    """A time_s column that is not in seconds (or absurd) spanned 1e300 s: the classes' cycles overflowed to inf
    (exit 1, "Out of range float values are not JSON compliant") or the speed the class keeps its revolutions by
    came out inf and was blamed on the design file's input.speed_rpm."""
    history, out = _history(tmp_path, *times), tmp_path / "life.json"
    res = _run("life", str(DUTY), "--static", "--series", str(history), "-o", str(out))
    _refused(res, str(history), "row 3, column time_s")
    assert "more than a duty point may hold" in res.stderr and "input.speed_rpm" not in res.stderr
    assert not out.exists() and sorted(p.name for p in tmp_path.iterdir()) == ["history.csv"]


def test_a_history_at_the_cap_is_rated_with_its_cycles(tmp_path):
    """At the cap (1e7 h = 3.6e10 s) the history is a duty: the input pinion turns 600/60 rev/s for 3.6e10 s, 3.6e11
    load cycles, at F_t = T_out / i / r_1 = 1000 N m / (51/21 · 50/17 · 53/17) / (21 · 12 mm / cos 12° / 2) = 348.6 N."""
    history = _history(tmp_path, 0.0, HOUR_CAP_S)
    res = _run("life", str(DUTY), "--static", "--series", str(history), "--format", "json", "-q")
    assert res.exit_code == 0, res.stderr
    (pinion_bin,) = json.loads(res.stdout)["life"]["stages"][0]["pinion"]["pitting"]["bins"]
    assert pinion_bin["cycles"] == pytest.approx(600.0 / 60.0 * HOUR_CAP_S, rel=1e-12)
    ratio = 51 / 21 * 50 / 17 * 53 / 17
    r_1 = 21 * 12.0 / math.cos(math.radians(12.0)) / 2.0
    assert pinion_bin["force_N"] == pytest.approx(1000e3 / ratio / r_1, rel=1e-9)


MODES_SCENE = Path(__file__).resolve().parents[2] / "configs" / "extreme" / "one_stage.toml"


@pytest.mark.parametrize("where", ["{long}", "new/{long}/figures"])
def test_a_plots_directory_the_filesystem_cannot_name_is_refused_before_the_run(tmp_path, where):
    """A ``--plots`` name longer than NAME_MAX (255 bytes on Linux): looking the name up raised OSError (exit 1,
    internal error), and under a directory still to create it ran the command, created ``new/`` and failed at the
    figures' mkdir (exit 1). Now exit 2 naming the option, nothing run, created or written."""
    plots = tmp_path / where.format(long="p" * 300)
    out = tmp_path / "modes.json"
    res = _run("modes", str(MODES_SCENE), "-o", str(out), "--plots", str(plots))
    assert res.exit_code == 2, (res.exit_code, res.stderr)
    assert res.stderr.startswith("gearcli: ") and "--plots: " in res.stderr, res.stderr
    assert "internal error" not in res.stderr and "Traceback" not in res.stderr
    assert list(tmp_path.iterdir()) == []  # no -o file, no new/ directory, no figure


@pytest.mark.parametrize("args", [["design", "-"], ["life", str(DUTY), "--static", "--series", "-"]],
                         ids=["design_file", "series"])
def test_a_closed_standard_input_is_named(tmp_path, args):
    """``gearcli design - <&-`` (a script that closed stdin): Python leaves ``sys.stdin`` None, and reading '-' was an
    internal error (exit 1, "'NoneType' object has no attribute 'buffer'")."""
    import os
    import subprocess
    import sys

    out = tmp_path / "out.json"
    res = subprocess.run([sys.executable, "-m", "gearcli", *args, "-o", str(out)], cwd=tmp_path, capture_output=True,
                         text=True, preexec_fn=lambda: os.close(0), timeout=120)
    assert res.returncode == 2, (res.returncode, res.stderr)
    assert res.stderr == "gearcli: <stdin>: standard input is closed ('-' reads it): pipe the file in, or give its path\n"
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(("vary", "fraction"), [("stage.0.pinion.teeth=20:21:3", "20.5 is one of its values"),
                                                ("stage[0].pinion.teeth=21,21.5", "21.5 is one of its values"),
                                                ("load.speed_exponent=0.5,1", "0.5 is one of its values"),
                                                ("stage.0.pinion.teeth=20.0:22.0:3",
                                                 "20.0 is written as a real number (write 20)")])
def test_a_fractional_value_of_a_whole_number_key_is_refused_before_any_point(tmp_path, vary, fraction):
    """``--vary stage.0.pinion.teeth=20:21:3`` steps by (21 - 20)/(3 - 1) = 0.5: the grid 20, 20.5, 21 came out as
    floats and every point was a failed row ("must be a whole number, got 20.0"), exit 1 after running the sweep.
    A value no design file could hold is a usage error (as ``--random`` on such a key is): exit 2, nothing written."""
    out = tmp_path / "sweep.csv"
    res = _run("sweep", str(SEED), "--vary", vary, "--jobs", "1", "-o", str(out))
    column = vary.partition("=")[0]
    assert res.exit_code == 2, (res.exit_code, res.stderr)
    assert res.stderr.startswith(f"gearcli: --vary: {column} takes whole numbers, and {fraction}: "), res.stderr
    assert list(tmp_path.iterdir()) == []


def test_a_whole_step_range_of_a_whole_number_key_runs_as_integers():
    """20:22:3 steps by (22 - 20)/2 = 1: teeth 20, 21, 22, each a design of its own."""
    res = _run("sweep", str(MODES_SCENE), "--vary", "stage.0.pinion.teeth=20:22:3", "--jobs", "1", "-q")
    assert res.exit_code == 0, res.stderr
    lines = res.stdout.splitlines()[1:]
    assert [line.split(",")[:3] for line in lines] == [["20", "none", "ok"], ["21", "none", "ok"], ["22", "none", "ok"]]


def test_a_resume_file_with_a_cell_over_the_csv_field_limit_is_read_back(tmp_path):
    """The csv module refuses a field over 128 KiB (131,072 characters) by default: a sweep file whose row carries a
    longer message (a point's warnings) was an internal error on resume. The row is this sweep's and is kept."""
    out = tmp_path / "sweep.csv"
    assert _run("sweep", str(SEED), *ONE_POINT, "-q", "-o", str(out)).exit_code == 0
    identity, header, row = out.read_text().splitlines()
    fields = next(csv.reader([row]))
    fields[header.split(",").index("message")] = "w" * 200_000
    out.write_text("\n".join([identity, header, ",".join(f'"{f}"' for f in fields)]) + "\n")
    res = _run("sweep", str(SEED), *ONE_POINT, "-q", "-o", str(out))
    assert res.exit_code == 0, res.stderr
    assert "w" * 200_000 in out.read_text()  # the finished point, not computed again


def test_a_history_cell_over_the_csv_field_limit_is_named(tmp_path):
    history = tmp_path / "history.csv"
    history.write_text('time_s,torque_Nm,speed_rpm\n0,"' + "1" * 200_000 + '",600\n1,1000,600\n')
    res = _run("life", str(DUTY), "--static", "--series", str(history), "-o", str(tmp_path / "life.json"))
    _refused(res, str(history), "row 2")
    assert "not CSV (field larger than field limit" in res.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["history.csv"]
