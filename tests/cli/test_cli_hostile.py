"""Issue 11: hostile or careless input through the real command line, each case as measured in the issue.

Every refusal is exit 2, one clean message naming the file (or `--set`) and the key, no traceback, no
"internal error". Every accepted text field comes out literally: no rich markup, no escape sequence, no
line that could pass for one of gearcli's own messages.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]
SEED = ROOT / "configs" / "concrete_mixer.toml"
SEED_TEXT = SEED.read_text()


def run(*args, env=None):
    return CliRunner(env=env).invoke(cli, [str(a) for a in args])


def assert_clean_exit_2(res, *fragments: str) -> None:
    assert res.exit_code == 2, (res.exit_code, res.output)
    assert "Traceback" not in res.stderr and "internal error" not in res.stderr, res.stderr
    for f in fragments:
        assert f in res.stderr, (f, res.stderr)


# ------------------------------------------------------------------------------- bounds, subnormals
@pytest.mark.parametrize(("key", "value"), [
    ("materials.steel.youngs_modulus_MPa", "1e-320"),
    ("materials.steel.density_kg_m3", "1e-320"),
    ("input.speed_deg_s", "1e-320"),
    ("input.ramp_s", "1e-320"),
    ("load.ramp_s", "1e-320"),
    ("load.torque_Nmm", "1e-320"),
    ("contact.full_damping_penetration_mm", "1e-320"),
    ("contact.damping_Ns_mm", "1e-320"),
    ("input.speed_deg_s", "1e15"),
    ("load.torque_Nmm", "1e15"),
    ("simulation.duration_s", "1e15"),
])
@pytest.mark.parametrize("command", ["design", "simulate", "report"])
def test_values_a_validator_must_refuse_are_exit_2_naming_the_key_and_bound(command, key, value):
    res = run(command, SEED, "--set", f"{key}={value}")
    assert_clean_exit_2(res, "--set", key)
    assert "must be" in res.stderr  # the bound is stated


def test_set_error_blames_the_module_not_the_profile_shift():
    res = run("design", SEED, "--set", "stage.0.normal_module_mm=1e-300")
    assert_clean_exit_2(res, "--set", "stage[0].normal_module_mm", "must be ≥")
    assert "profile_shift" not in res.stderr and str(SEED) not in res.stderr  # --set is blamed, not the file


def test_set_with_a_non_ascii_digit_is_a_clean_exit_2():
    res = run("design", SEED, "--set", "stage.².pinion.teeth=3")
    assert_clean_exit_2(res, "--set")


def test_a_1_mb_key_name_is_shortened_in_the_message():
    res = run("design", SEED, "--set", "a" * 1_000_000 + "=1")
    assert_clean_exit_2(res, "--set", "characters)")
    assert len(res.stderr) < 2000


def test_unknown_keys_are_capped_and_counted(tmp_path):
    path = tmp_path / "junk.toml"
    path.write_text(SEED_TEXT + "".join(f"\n[junk{i}]\nx = 1\n" for i in range(300)))
    res = run("design", path)
    assert_clean_exit_2(res, "junk.toml", "unknown key", "more errors")
    assert len(res.stderr.splitlines()) <= 25


@pytest.mark.parametrize(("name", "content", "fragment"), [
    ("deep.toml", b"a" + b".a" * 40000 + b" = 1\n", "nested too deeply"),
    ("million.toml", b"".join(b"k%d=1\n" % i for i in range(150000)), "larger than 1 MiB"),
    ("many.toml", b"".join(b"k%d=1\n" % i for i in range(100000)), "keys and tables"),
    ("utf16.toml", SEED_TEXT.encode("utf-16"), "UTF-16 text"),
    ("gz.toml", __import__("gzip").compress(SEED_TEXT.encode()), "gzip-compressed data"),
    ("nul.toml", SEED_TEXT.encode()[:200] + b"\0" + SEED_TEXT.encode()[200:], "binary data"),
])
def test_hostile_files_are_refused_fast_naming_the_file(tmp_path, name, content, fragment):
    path = tmp_path / name
    path.write_bytes(content)
    res = run("design", path)
    assert_clean_exit_2(res, name, fragment)


@pytest.mark.parametrize("variant", ["bom", "crlf", "bom+crlf"])
def test_utf8_with_bom_and_crlf_are_accepted(tmp_path, variant):
    text = SEED_TEXT.replace("\n", "\r\n") if "crlf" in variant else SEED_TEXT
    raw = ("\ufeff" if "bom" in variant else "").encode() + text.encode()
    (tmp_path / "in.toml").write_bytes(raw)
    res = run("design", tmp_path / "in.toml", "--format", "json")
    plain = run("design", SEED, "--format", "json")
    assert res.exit_code == 0, res.stderr
    assert json.loads(res.stdout)["total_ratio"] == json.loads(plain.stdout)["total_ratio"]


# ------------------------------------------------------------------------------- report options
@pytest.mark.parametrize("args", [["--accuracy", "nan"], ["--accuracy", "inf"],
                                  ["--rtols", ",".join(["1e-6"] * 400)],
                                  ["--rtols", ",".join(f"{1e-3 / (1 + i / 400):.6e}" for i in range(400))],
                                  ["--rtols", "1e-4,1e-5,1e-4"]])
def test_report_option_values_refused(args):
    res = run("report", SEED, *args)
    assert res.exit_code == 2 and "Traceback" not in res.stderr, res.output


# ------------------------------------------------------------------------------- resource bounds
def test_series_json_at_the_steps_cap_is_refused_with_the_estimate():
    res = run("simulate", SEED, "--format", "json", "--series", "--set", "simulation.steps=2000000")
    assert_clean_exit_2(res, "simulation.steps", "GiB", "--series")


def _many_stages(n: int) -> str:
    stage = ('[[stage]]\nnormal_module_mm = 4\nhelix_angle_deg = 10\n'
             'pinion = { teeth = 20, face_width_mm = 40, hand = "left" }\n'
             'gear = { teeth = 22, face_width_mm = 40, hand = "right" }\n')
    return ('title = "many stages"\n' + stage * n + "[input]\nspeed_rpm = 1500\nramp_s = 0.1\n"
            "[load]\ntorque_Nm = 50\nramp_s = 0.1\n")


def test_fifty_stages_at_2e5_steps_is_refused_by_the_memory_estimate(tmp_path):
    (tmp_path / "fifty.toml").write_text(_many_stages(50))
    res = run("simulate", tmp_path / "fifty.toml", "-o", tmp_path / "x.csv", "--set", "simulation.steps=200000")
    assert_clean_exit_2(res, "fifty.toml", "simulation.steps", "memory")
    assert not (tmp_path / "x.csv").exists()


def test_absurd_cost_is_refused_up_front_with_the_estimate():
    # time-varying mesh stiffness at a fast but bounded speed over an hour: every one of ~2e8 mesh cycles
    # must be resolved, ~3e10 evaluations (days)
    absurd = ["--set", "input.speed_rpm=150000", "--set", "simulation.duration_s=3600",
              "--set", "contact.time_varying=true"]
    res = run("simulate", SEED, *absurd)
    assert_clean_exit_2(res, "simulation.duration_s", "evaluations", "set simulation.duration_s ≤")
    res = run("report", SEED, *absurd)
    assert_clean_exit_2(res, "simulation.duration_s", "evaluations")
    advised = float(res.stderr.split("set simulation.duration_s ≤ ")[1].split(",")[0])
    assert advised >= 1e-4  # the schema's least duration: the advice is a run the file may ask for


def test_absurd_cost_at_the_least_duration_advises_no_duration_below_it():
    # a linear 1e14 N/mm mesh on a 1e-9 kg m^2 gear (m_n 3 mm, 25 teeth: r_b = 37.5 mm cos 20° = 35.2 mm) driven at a
    # prescribed speed: omega = r_b sqrt(k / J) = 0.0352 m x sqrt(1e17 / 1e-9) = 3.5e11 rad/s, so even the least
    # duration 1e-4 s needs ~30 omega T = 1.1e9 evaluations, over the 5e8 limit; the refusal once advised
    # simulation.duration_s ≤ 2.7e-05 (on a scene like it), which the schema refuses
    tiny = ["--set", "contact.stiffness=1e14", "--set", "stage.0.gear.inertia_kg_m2=1e-9"]
    res = run("simulate", ROOT / "configs" / "spur_oscillator_te.toml", *tiny, "--set", "simulation.duration_s=1e-4")
    assert_clean_exit_2(res, "simulation.duration_s", "evaluations", "no simulation.duration_s from its least 0.0001 s")
    assert "set simulation.duration_s ≤" not in res.stderr


# ------------------------------------------------------------------------------- literal text
HOSTILE_TITLES = ["[/]", "[/bold] x [bold]", "[link=file:///etc/passwd]click[/link]",
                  "\x1b]8;;file:///etc/passwd\x07click\x1b]8;;\x07", "bell\x07 esc\x1b[31mred",
                  "line1\n# Injected heading\ngearcli: wrote /etc/passwd"]


@pytest.mark.parametrize("title", HOSTILE_TITLES)
@pytest.mark.parametrize("fmt", ["table", "json", "csv"])
def test_design_titles_are_printed_literally(tmp_path, title, fmt):
    path = tmp_path / "t.toml"
    path.write_text(SEED_TEXT.replace('title = "Concrete mixer reducer, three helical stages (seed paper)"',
                                      f"title = {json.dumps(title)}"))
    res = run("design", path, "--format", fmt)
    assert res.exit_code == 0, res.output
    assert "\x1b" not in res.output and "\x07" not in res.output
    assert not any(line.startswith(("gearcli:", "# ")) for line in res.stdout.splitlines())
    if fmt == "table":
        assert "[link=file:///etc/passwd]" in res.stdout or "[/" in res.stdout or "\\x" in res.stdout \
            or "\\n" in res.stdout


@pytest.mark.parametrize("title", HOSTILE_TITLES)
def test_report_markdown_title_cannot_inject_headings_or_escapes(title):
    res = run("report", SEED, "--quick", "--format", "markdown", "--set", f"title={json.dumps(title)}")
    assert res.exit_code == 0, res.output
    assert "\x1b" not in res.stdout and "\x07" not in res.stdout
    headings = [line for line in res.stdout.splitlines() if line.startswith("#")]
    assert headings[0].startswith("# gearcli report: ") and not any("Injected" in h for h in headings[1:])
    assert "](" not in headings[0].replace("\\](", "")  # no live link


def test_report_table_with_markup_title_does_not_crash():
    res = run("report", SEED, "--quick", "--format", "table", "--set", "title=[/] [/bold]")
    assert res.exit_code == 0, res.output
    assert "[/] [/bold]" in res.stdout


def test_a_key_with_a_newline_cannot_forge_a_gearcli_line(tmp_path):
    path = tmp_path / "k.toml"
    path.write_text(SEED_TEXT + '\n["x\\ngearcli: wrote /etc/passwd\\u001b[2J"]\na = 1\n')
    res = run("design", path)
    assert_clean_exit_2(res, "k.toml")
    assert all(line.startswith("gearcli: ") and str(path) in line for line in res.stderr.splitlines())
    assert "\x1b" not in res.stderr
    res = run("design", SEED, "--set", "x\ngearcli: forged=1")
    assert_clean_exit_2(res)
    assert len(res.stderr.splitlines()) == 1 and "\\n" in res.stderr


def test_a_title_with_controls_is_escaped_in_an_output_text_file(tmp_path):
    out = tmp_path / "d.txt"
    res = run("design", SEED, "-o", out, "--set", 'title="a\\u001b[31m\\u0007b"')
    assert res.exit_code == 0, res.output
    text = out.read_text()
    assert "\x1b" not in text and "\x07" not in text and "\\x1b[31m\\x07b" in text


def test_csv_text_cells_are_neutralised_numbers_are_not():
    from gearcli.io.serialize import csv_text

    text = csv_text(["name", "value"], [["=HYPERLINK(\"x\")", -1.5], ["+1", 2.0], ["@SUM(A1)", 3.0], ["-x", 4.0],
                                          ["plain", -5.0]])
    rows = text.splitlines()[1:]
    assert rows[0].startswith("\"'=HYPERLINK") and rows[0].endswith(",-1.5")
    assert rows[1] == "'+1,2.0" and rows[2] == "'@SUM(A1),3.0" and rows[3] == "'-x,4.0"
    assert rows[4] == "plain,-5.0"


def test_report_in_a_latin_1_terminal_does_not_crash(tmp_path):
    env = {**os.environ, "PYTHONIOENCODING": "latin-1"}
    for fmt in ("markdown", "table"):
        res = subprocess.run([sys.executable, "-m", "gearcli", "report", str(SEED), "--quick", "--format", fmt],
                             capture_output=True, env=env, timeout=300)
        assert res.returncode == 0, res.stderr.decode("latin-1")
        assert b"Traceback" not in res.stderr


# ------------------------------------------------------------------------------- tables
def _numbers_of(res_json: dict) -> list[str]:
    return [f"{s['ratio']:.5g}" for s in res_json["stages"]] + [f"{s['center_distance_mm']:.5g}"
                                                                for s in res_json["stages"]]


@pytest.mark.parametrize("n_stages", [10, 50])
@pytest.mark.parametrize("columns", ["40", "0", "200"])
def test_tables_never_drop_a_number(tmp_path, n_stages, columns):
    path = tmp_path / "many.toml"
    path.write_text(_many_stages(n_stages))
    doc = json.loads(run("design", path, "--format", "json").stdout)
    res = run("design", path, "--format", "table", env={"COLUMNS": columns})
    assert res.exit_code == 0, res.output
    assert "…" not in res.stdout
    cells = res.stdout.replace("│", " ").replace("|", " ").split()
    for value in _numbers_of(doc):
        assert value in cells, value
    assert res.stdout.count("ratio i") >= 1
    if columns != "0":
        assert max(len(line) for line in res.stdout.splitlines()) <= int(columns)


def test_numeric_runtime_warnings_never_reach_the_user_raw(monkeypatch):
    import warnings

    import gearcli.design as design_pkg

    real = design_pkg.compute_design

    def noisy(cfg):
        warnings.warn("overflow encountered in exp", RuntimeWarning, stacklevel=1)
        return real(cfg)

    monkeypatch.setattr(design_pkg, "compute_design", noisy)
    res = run("design", SEED, "--format", "json")
    assert res.exit_code == 0
    assert "RuntimeWarning" not in res.stderr and ".py:" not in res.stderr
    assert "warning: numerical warning during the run: overflow encountered in exp" in res.stderr
    assert run("-q", "design", SEED, "--format", "json").stderr == ""
