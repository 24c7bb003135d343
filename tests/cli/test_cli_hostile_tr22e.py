"""Trial tr22e: hostile input on the fourth round's keys and files (tooth-thickness allowances, ISO 281/76 bearing
fields, duty sets, `--series` histories, `--set` of arrays and tables, sweeps over them). Each test failed on the
code the trial ran against (58e60ca) and passes now; the numbers are checked against hand formulas, not against
gearcli's own output.

In-process (click's CliRunner): every finding is about what one command does with its arguments and files.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli.cli import cli
from gearcli.sweep import worker

CONFIGS = Path(__file__).resolve().parents[2] / "configs"
ALLOWANCES = CONFIGS / "wind_turbine_allowances.toml"  # z 24/95, m_n 14, alpha_n 20°, x 0.48/0.6691
DUTY = CONFIGS / "mixer_duty.toml"
HISTORY = "time_s,torque_Nm,speed_rpm\n0,300000,600\n3600,500000,600\n7200,0,600\n"


def run(*args):
    return CliRunner().invoke(cli, [str(a) for a in args])


def assert_usage_error(res, *needles: str) -> None:
    """Exit 2, one clean message (no traceback) holding every needle."""
    assert res.exit_code == 2, (res.exit_code, res.stderr, res.stdout[-500:])
    assert "Traceback" not in res.stderr and "internal error" not in res.stderr, res.stderr
    for n in needles:
        assert n in res.stderr, (n, res.stderr)


# --------------------------------------------------------------- sweep: a list or a table varied as a whole
@pytest.mark.parametrize("vary, needles", [
    # reals on a list were refused as if the key took whole numbers ("takes whole numbers, and -0.3 is one of
    # its values"); whole values ran every point to a failed row ("must be an array"), exit 1
    ("stage.0.pinion.tooth_thickness_allowance_mm=-0.3,-0.1",
     ["stage.0.pinion.tooth_thickness_allowance_mm is a list",
      "--vary 'stage.0.pinion.tooth_thickness_allowance_mm.0=v1,v2,...'"]),
    ("stage.0.pinion.tooth_thickness_allowance_mm=0,1", ["is a list", ".0=v1,v2,..."]),
    ("stage.0.center_distance_allowance_mm=-0.05:0.05:3", ["stage.0.center_distance_allowance_mm is a list"]),
    ("contact=1,2", ["contact is a table", "--vary 'contact.KEY=v1,v2,...'"]),
    ("lubricant=1.5,2.5", ["lubricant is a table"]),
    ("stage.0.mesh=1,2", ["stage.0.mesh is a table"]),
])
def test_sweep_refuses_to_vary_a_whole_list_or_table_before_any_point(tmp_path, monkeypatch, vary, needles):
    def no_point(*a, **k):
        raise AssertionError("a point ran")

    monkeypatch.setattr(worker, "_evaluate", no_point)
    out = tmp_path / "s.csv"
    res = run("sweep", ALLOWANCES, "--vary", vary, "--jobs", "1", "-o", out)
    assert_usage_error(res, "--vary", *needles)
    assert "whole numbers" not in res.stderr
    assert not out.exists()


def test_sweep_refuses_a_number_among_whole_arrays(tmp_path, monkeypatch):
    """Whole arrays are values a list takes (``--vary KEY=[a, b],[c, d]``); a bare number among them is not."""
    monkeypatch.setattr(worker, "_evaluate", lambda *a, **k: pytest.fail("a point ran"))
    res = run("sweep", ALLOWANCES, "--vary", "stage.0.pinion.tooth_thickness_allowance_mm=[-0.1, -0.2],-0.3",
              "--jobs", "1", "-o", tmp_path / "s.csv")
    assert_usage_error(res, "is a list, and --vary gives a point -0.3",
                       "--vary 'stage.0.pinion.tooth_thickness_allowance_mm=[a, b],[c, d]'")


def test_sweep_still_varies_a_list_entry_by_index(tmp_path, monkeypatch):
    """The entry the message names is accepted: the sweep gets past its checks to its points."""
    ran = []

    def evaluate(evaluator, scene, point, prev, check=False):
        ran.append(point)
        raise KeyboardInterrupt  # stop at the first point: the checks before it are what this test is about

    monkeypatch.setattr(worker, "_evaluate", evaluate)
    res = run("sweep", ALLOWANCES, "--vary", "stage.0.pinion.tooth_thickness_allowance_mm.1=-0.3,-0.2",
              "--jobs", "1", "-o", tmp_path / "s.csv")
    assert ran, (res.exit_code, res.stderr)


# --------------------------------------------------------------- life --series: a row longer than the header
def _history(tmp_path: Path, text: str) -> Path:
    p = tmp_path / "h.csv"
    p.write_text(text)
    return p


def test_a_decimal_comma_history_is_refused_not_misread(tmp_path):
    """0.5 s, 1234.5 N·m, 1480.2 rpm written with decimal commas: the csv module splits each number in two, and the
    first three cells (0, 5, 1234) were read as the row: 5 N·m at 1234 rpm, in range, silently wrong."""
    history = _history(tmp_path, "time_s,torque_Nm,speed_rpm\n0,5,1234,5,1480,2\n3600,5,1500,0,1480,2\n"
                                 "7200,0,600\n")
    out = tmp_path / "life.json"
    res = run("life", DUTY, "--static", "--series", history, "-o", out)
    assert_usage_error(res, str(history), "row 2", "6 cells, more than the header's 3", "decimal comma")
    assert not out.exists()


def test_a_row_with_a_stray_cell_is_refused_and_trailing_empty_cells_are_not(tmp_path):
    res = run("life", DUTY, "--static", "--series", _history(tmp_path, HISTORY.replace("600\n3600", "600,7\n3600")))
    assert_usage_error(res, "row 2", "4 cells")
    # a spreadsheet's trailing separators leave empty cells: the row is the header's three numbers, whose
    # damage is the history's without them (one class per level: 1 h at 300 kN·m, 1 h at 500 kN·m)
    clean = run("life", DUTY, "--static", "--series", _history(tmp_path, HISTORY), "--format", "json")
    trailing = run("life", DUTY, "--static", "--series",
                   _history(tmp_path, HISTORY.replace("600\n", "600,,\n")), "--format", "json")
    assert clean.exit_code == 0 and trailing.exit_code == 0, trailing.stderr
    damage = [json.loads(r.stdout)["life"]["stages"][0]["pinion"]["pitting"]["damage"] for r in (clean, trailing)]
    assert damage[0] == damage[1] > 0.0


# --------------------------------------------------------------- --set: an array or a table TOML cannot read
@pytest.mark.parametrize("setting, needles", [
    # the text fell back to a word: "must be an array, got "[-0.1 -0.2]"" said nothing of the missing comma
    ("stage.0.pinion.tooth_thickness_allowance_mm=[-0.13 -0.25]", ["is not an array TOML can read",
                                                                  "Unclosed array (at character 8 of the value)"]),
    ("stage.0.pinion.tooth_thickness_allowance_mm=[-0.13, -0.25", ["Unclosed array (at the end of the value)"]),
    ("stage.0.pinion.tip_diameter_allowance_mm=[0; -0.1]", ["is not an array TOML can read"]),
    ("lubricant={viscosity_40C_mm2_s: 220}", ["is not an inline table TOML can read", "Expected '='"]),
    ("stage.0.mesh={damping_ratio=0.1, damping_ratio=0.2}", ["Duplicate inline table key 'damping_ratio'"]),
    ("load.fluctuation=[{amplitude_percent=10 frequency_Hz=5}]", ["is not an array TOML can read"]),
])
@pytest.mark.parametrize("command", [["design"], ["life", "--static"], ["modes"]])
def test_set_of_an_unreadable_array_or_table_says_why(tmp_path, setting, needles, command):
    out = tmp_path / "out.json"
    res = run(*command, ALLOWANCES, "--set", setting, "-o", out)
    assert_usage_error(res, "--set", setting.partition("=")[0], *needles)
    assert "must be an array, got" not in res.stderr and "must be a table, got" not in res.stderr
    assert not out.exists()


def test_set_of_a_readable_array_sets_the_allowance_the_hand_formula_reads():
    """A valid array still applies: x_E = x + A_sn / (2 m_n tan alpha_n) (ISO 21771), here 0.48 + A/(28 tan 20°);
    and a bracketed word stays a word where the key takes text."""
    res = run("design", ALLOWANCES, "--set", "stage.0.pinion.tooth_thickness_allowance_mm=[-0.13, -0.25]",
              "--set", "title=[draft] allowances", "--format", "json")
    assert res.exit_code == 0, res.stderr
    d = json.loads(res.stdout)
    x_e = [0.48 + a / (2 * 14 * math.tan(math.radians(20))) for a in (-0.13, -0.25)]
    assert d["stages"][0]["pinion"]["generating_profile_shift"] == pytest.approx(x_e, rel=1e-12)
    assert d["title"] == "[draft] allowances"


# --------------------------------------------------------------- --set into a duty point's set
MOTOR_DUTY = CONFIGS / "motor_duty_starts.toml"


def test_set_into_a_duty_points_set_says_to_quote_the_dotted_key():
    """A point's ``set`` holds design-file keys written as --set writes them: ``duty.0.set.contact.exponent`` was
    "duty[0].set.contact is a value, not a table"; the message now shows the quoted key, which works."""
    res = run("life", MOTOR_DUTY, "--static", "--set", "duty.0.set.contact.exponent=2")
    assert_usage_error(res, "duty[0].set takes a key of the design file",
                       "--set 'duty.0.set.\"contact.exponent\"=VALUE'")
    ok = run("life", MOTOR_DUTY, "--static", "--set", 'duty.0.set."contact.exponent"=2', "--format", "json")
    assert ok.exit_code == 0, ok.stderr


# --------------------------------------------------------------- IMPACT damping keys a damping_ratio overrides
def _modal_damping(*args) -> list[tuple[float, float]]:
    res = run("modes", *args, "--format", "json")
    assert res.exit_code == 0, res.stderr
    boundaries = json.loads(res.stdout)["boundaries"]
    first = boundaries[0] if isinstance(boundaries, list) else next(iter(boundaries.values()))
    modes = first["modes"] if isinstance(first, dict) else first
    return [(m["frequency_Hz"], m["damping_ratio"]) for m in modes]


def _ignored(*args) -> list[dict]:
    res = run("design", *args, "--format", "json")
    assert res.exit_code == 0, res.stderr
    return [w for w in json.loads(res.stdout)["warnings"] if w.get("check") == "damping_ignored"]


@pytest.mark.parametrize("setting, stage, table", [
    ("stage.1.mesh.damping_Ns_mm=10", 2, "stage 2: [stage.mesh] damping_Ns_mm = 10 has no effect"),
    ("contact.full_damping_penetration_mm=0.3", None, "[contact] full_damping_penetration_mm = 0.3 has no effect"),
])
def test_an_impact_key_beside_a_damping_ratio_is_said_to_have_no_effect(setting, stage, table):
    """The file's [contact] gives damping_ratio = 0.05, which damps every mesh viscously (DESIGN section 13): an
    IMPACT key beside it changed nothing, without a word. Now a warning names the key, the ratio and where it was
    given; and the modes are indeed those of the file without the key."""
    found = _ignored(MOTOR_DUTY, "--set", setting)
    assert len(found) == 1 and table in found[0]["message"], found
    assert found[0]["damping_ratio"] == 0.05 and found[0]["damping_ratio_given_in"] == "[contact]"
    assert found[0].get("stage") == stage
    assert _modal_damping(MOTOR_DUTY, "--set", setting) == _modal_damping(MOTOR_DUTY)


def test_an_impact_key_where_no_damping_ratio_is_given_takes_effect_without_the_note(tmp_path):
    """Without damping_ratio in [contact] (the 0.05 default), a stage's IMPACT key makes that mesh IMPACT-damped:
    no note, and its mesh mode's damping changes (the other modes barely)."""
    text = MOTOR_DUTY.read_text()
    assert "\ndamping_ratio = 0.05\n" in text
    free = tmp_path / "no_ratio.toml"
    free.write_text(text.replace("\ndamping_ratio = 0.05\n", "\n", 1))
    assert _ignored(free, "--set", "stage.1.mesh.damping_Ns_mm=10") == []
    viscous, ramp = _modal_damping(free), _modal_damping(free, "--set", "stage.1.mesh.damping_Ns_mm=10")
    assert [f for f, _ in viscous] == pytest.approx([f for f, _ in ramp], rel=1e-6)  # damping, not stiffness
    assert any(abs(a - b) > 0.01 for (_, a), (_, b) in zip(viscous, ramp, strict=True))


# --------------------------------------------------------------- --set of one key of a pair the file chose the other of
def _json(*args) -> dict:
    res = run(*args, "--format", "json")
    assert res.exit_code == 0, res.stderr
    return json.loads(res.stdout)


def test_set_k_gamma_replaces_the_files_load_sharing_factor():
    """K_gamma and load_sharing_factor are one factor under two names, one of them per file: --set of the other
    name was exit 2 ("give one of") and no --set could remove the file's, so K_gamma could not be overridden. Now
    the --set replaces it, and sigma_H = sigma_H0 sqrt(K_A K_gamma K_v K_Hbeta K_Halpha) (ISO 6336-2) carries 1.3."""
    d = _json("design", CONFIGS / "planetary_stage.toml", "--set", "rating.K_gamma=1.3")  # the file: 1.1
    for mesh in d["stages"][0]["meshes"]:
        r = mesh["rating"]
        assert r["K_gamma"] == 1.3
        factors = r["K_A"] * 1.3 * r["K_v"] * r["K_Hbeta"] * r["K_Halpha"]
        assert r["sigma_H_MPa"] == pytest.approx(r["sigma_H0_MPa"] * math.sqrt(factors), rel=1e-12)


def test_set_a_duty_points_power_replaces_its_torque():
    """A point's torque_Nm in the file, its power_kW by --set (exit 2 before: "give exactly one of"): the output
    torque P / omega_out at the output speed 1480 rpm / ((74/19)(92/18))."""
    d = _json("life", MOTOR_DUTY, "--static", "--set", "duty.2.power_kW=50")
    n_out = 1480.0 / ((74 / 19) * (92 / 18))
    assert d["life"]["points"][2]["torque_Nm"] == pytest.approx(50e3 / (n_out * math.pi / 30), rel=1e-12)


def test_set_e_c_replaces_the_files_cleanliness_level_in_iso_281():
    """[lubricant] contamination in the file, e_C by --set (exit 2 before): a_ISO of the ball bearing by ISO 281
    eq. (10) at that e_C, kappa from ASTM D341 (220 / 19 mm²/s at 40 / 100 °C, 70 °C) and nu_1 = 4500 n^-0.5 d_m^-0.5."""
    iso = ["--set", "bearing.0.fatigue_load_limit_kN=4.5", "--set", "bearing.0.pitch_diameter_mm=60",
           "--set", "lubricant.temperature_C=70", "--set", "lubricant.viscosity_100C_mm2_s=19",
           "--set", 'lubricant.contamination="normal"']
    b = _json("design", MOTOR_DUTY, *iso, "--set", "lubricant.e_C=0.3")["bearings"][0]

    def z(nu):
        return math.log10(math.log10(nu + 0.7))

    slope = (z(19.0) - z(220.0)) / (math.log10(373.15) - math.log10(313.15))
    nu = 10 ** (10 ** (z(220.0) + slope * (math.log10(343.15) - math.log10(313.15)))) - 0.7
    kappa = nu / (4500.0 * 1480.0 ** -0.5 * 60.0 ** -0.5)
    assert 1.0 < kappa < 4.0 and b["kappa"] == pytest.approx(kappa, rel=1e-9)
    x = 0.3 * 4500.0 / b["equivalent_load_N"]
    a_iso = 0.1 * (1 - (2.5671 - 1.9987 / kappa ** 0.071739) ** 0.83 * x ** (1 / 3)) ** -9.3
    assert b["a_ISO"] == pytest.approx(min(a_iso, 50.0), rel=1e-9)


def test_set_a_motor_table_replaces_the_files_nameplate():
    """A nameplate motor in the file, a torque-speed table by --set (exit 2 before: "the nameplate or torque_speed,
    not both"): the table runs where its line from (1400 rpm, 700 N·m) to (1500 rpm, 0) meets the load reflected to
    the motor, 6860 N·m / ((74/19)(92/18) 0.985²), which design's motor_speed_mismatch reports."""
    d = _json("design", MOTOR_DUTY, "--set", "input.motor.torque_speed=[[0, 800], [1400, 700], [1500, 0]]")
    reflected = 6860.0 / ((74 / 19) * (92 / 18) * 0.985 ** 2)
    mismatch = [w for w in d["warnings"] if w.get("check") == "motor_speed_mismatch"]
    assert len(mismatch) == 1
    assert mismatch[0]["operating_speed_rpm"] == pytest.approx(1400.0 + (700.0 - reflected) / 700.0 * 100.0, rel=1e-9)
    back = run("design", MOTOR_DUTY, "--set", "input.motor.torque_speed=[[0, 800], [1500, 0]]",
               "--set", "input.motor.rated_power_kW=55")  # a nameplate key replaces the table: the other four missing
    assert_usage_error(back, "missing rated_speed_rpm")


# --------------------------------------------------------------- a [[duty]] point's set, checked by every command
@pytest.mark.parametrize("point_set, key, needle", [
    ('{ "contact.exponnt" = 2 }', "duty[0].set.contact.exponnt", "unknown key 'exponnt'"),
    ('{ "input.motor.rated_power_kW" = -5 }', "duty[0].set.input.motor.rated_power_kW", "must be ≥ 0.001"),
    ('{ "load.fluctuation.0.amplitude_percent" = 10 }', "duty[0].set.load.fluctuation.0.amplitude_percent",
     "index 0 is out of range"),
])
@pytest.mark.parametrize("command", [["design"], ["modes"], ["life", "--static"]])
def test_a_bad_duty_set_is_exit_2_for_every_command(tmp_path, point_set, key, needle, command):
    """`life` refused a point's bad set, `design` and `modes` of the same file ran as if it were fine."""
    path = tmp_path / "duty.toml"
    path.write_text(MOTOR_DUTY.read_text().replace("starts = 1000 ", f"starts = 1000\nset = {point_set}\n#", 1))
    out = tmp_path / "out.json"
    res = run(*command, path, "-o", out)
    assert_usage_error(res, f"{path}: {key}: {needle}")
    assert not out.exists()


def test_a_good_duty_set_passes_every_command(tmp_path):
    path = tmp_path / "duty.toml"
    path.write_text(MOTOR_DUTY.read_text().replace(
        "starts = 1000 ", 'starts = 1000\nset = { "contact.damping_ratio" = 0.08, "lubricant.temperature_C" = 70 }\n#', 1))
    for command in (["design"], ["modes"], ["life", "--static"]):
        res = run(*command, path, "--format", "json")
        assert res.exit_code == 0, (command, res.stderr)


# --------------------------------------------------------------- a departure from the default mesh law names its key
@pytest.mark.parametrize("setting, stage, key", [
    ("stage.1.mesh.stiffness=1e5", 2, "[stage.mesh] stiffness = 100000"),
    ('contact.stiffness="hertz"', 1, '[contact] stiffness = "hertz"'),
])
def test_stiffness_not_iso_names_the_key_that_chose_the_law(setting, stage, key):
    """DESIGN section 13's stiffness_not_iso said "(stiffness = "iso6336" calibrates ...)" whichever table chose the
    law; it now names the key and its table beside the default and its source (ISO 6336-1's k_n). The linear law
    K = 1e5 N/mm has that stiffness at every load: its departure is 1e5 / k_n - 1 with k_n as reported."""
    found = [w for w in _json("design", MOTOR_DUTY, "--set", setting)["warnings"]
             if w["code"] == "stiffness_not_iso" and w["stage"] == stage]
    assert len(found) == 1, found
    w = found[0]
    assert f"({key}; the default stiffness = \"iso6336\" calibrates" in w["message"]
    assert "ISO 6336-1's k_n" in w["message"]
    if "1e5" in setting:
        assert w["linearised_N_mm"] == pytest.approx(1e5, rel=1e-12)
        assert w["departure"] == pytest.approx(1e5 / w["iso_N_mm"] - 1.0, rel=1e-12)
