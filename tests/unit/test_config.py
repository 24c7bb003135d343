"""Loading design files: the seed, stdin, --set overrides, error messages, starter file, schema."""

from __future__ import annotations

import hashlib
import io
import os
import tomllib
from pathlib import Path

import pytest

from gearcli.config import ConfigErrors, DesignFile, LoadedDesign, json_schema, load_design, starter_toml
from gearcli.errors import EXIT_USAGE, ConfigError

ROOT = Path(__file__).resolve().parents[2]
SEED = ROOT / "configs" / "concrete_mixer.toml"


@pytest.fixture
def seed_text() -> str:
    return SEED.read_text(encoding="utf-8")


def write(tmp_path: Path, text: str, name: str = "design.toml") -> str:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return str(path)


def error_of(path: str, overrides=(), **kw) -> ConfigError:
    with pytest.raises(ConfigError) as info:
        load_design(path, overrides, **kw)
    return info.value


# --- the seed --------------------------------------------------------------------------------


def test_seed_loads_with_its_numbers():
    loaded = load_design(str(SEED))
    assert isinstance(loaded, LoadedDesign) and isinstance(loaded.design, DesignFile)
    d = loaded.design
    assert [(s.pinion.teeth, s.gear.teeth) for s in d.stage] == [(21, 51), (17, 50), (17, 53)]
    assert d.stage[0].pinion.hand == "left" and d.stage[0].gear.hand == "right"
    assert d.input.speed_deg_s == 3600 and d.load.torque_Nmm == 5.31e6  # exact: TOML literals
    assert d.target is not None and d.target.output_speed_rpm == 23
    assert loaded.source == str(SEED)
    assert loaded.sha256 == hashlib.sha256(SEED.read_bytes()).hexdigest()  # = `sha256sum FILE`
    assert loaded.raw == tomllib.loads(SEED.read_text(encoding="utf-8"))


def test_stdin_gives_the_same_design_and_sha_as_the_file():
    raw = SEED.read_bytes()
    from_stdin = load_design("-", stdin=io.BytesIO(raw))
    from_file = load_design(str(SEED))
    assert from_stdin.source == "<stdin>"
    assert from_stdin.sha256 == from_file.sha256 == hashlib.sha256(raw).hexdigest()
    assert from_stdin.design == from_file.design


def test_utf8_bom_is_accepted(tmp_path, seed_text):
    path = tmp_path / "bom.toml"
    path.write_bytes(b"\xef\xbb\xbf" + seed_text.encode())
    assert load_design(str(path)).design == load_design(str(SEED)).design


def test_sha256_changes_with_overrides_and_is_documented_recipe():
    raw = SEED.read_bytes()
    plain = load_design(str(SEED)).sha256
    a = load_design(str(SEED), ["input.speed_rpm=1450"]).sha256
    b = load_design(str(SEED), ["input.speed_rpm=1500"]).sha256
    assert len({plain, a, b}) == 3
    assert a == hashlib.sha256(raw + b"\0--set input.speed_rpm=1450").hexdigest()


# --- --set overrides -------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("override", "get", "expected"),
    [
        ("stage.0.pinion.teeth=22", lambda d: d.stage[0].pinion.teeth, 22),  # int
        ("stage[2].gear.teeth=60", lambda d: d.stage[2].gear.teeth, 60),  # the bracket form of messages
        ("input.speed_rpm=1450", lambda d: d.input.speed_rpm, 1450.0),  # int -> float field
        ("simulation.rtol=1e-8", lambda d: d.simulation.rtol, 1e-8),  # float
        ("contact.time_varying=true", lambda d: d.contact.time_varying, True),  # bool
        ("contact.stiffness=iso6336", lambda d: d.contact.stiffness, "iso6336"),  # bare string
        ("contact.stiffness=2.5e6", lambda d: d.contact.stiffness, 2.5e6),  # the union's number branch
        ("simulation.method=Radau", lambda d: d.simulation.method, "Radau"),
        ('stage.0.pinion.hand="right"', lambda d: d.stage[0].pinion.hand, "right"),  # quoted string
        ("stage.1.gear.hand=right", lambda d: d.stage[1].gear.hand, "right"),
        ("load.torque_Nmm=-1e6", lambda d: d.load.torque_Nmm, -1e6),  # load reversal is allowed
        ("title=Mixer B", lambda d: d.title, "Mixer B"),
        ("stage.0.backlash_mm=0.1", lambda d: d.stage[0].backlash_mm, 0.1),  # absent key: created
        ("stage.0.mesh.damping_Ns_mm=10", lambda d: d.stage[0].mesh.damping_Ns_mm, 10.0),  # absent table
        ("materials.steel.poisson_ratio=0.3", lambda d: d.materials["steel"].poisson_ratio, 0.3),
        ("stage.0.pinion={ teeth = 19, face_width_mm = 190, hand = \"left\" }",
         lambda d: (d.stage[0].pinion.teeth, d.stage[0].pinion.material), (19, "steel")),  # inline table
    ],
)
def test_override_kinds(override, get, expected):
    loaded = load_design(str(SEED), [override])
    assert get(loaded.design) == expected


def test_override_creates_optional_table_and_material(tmp_path, seed_text):
    no_target = seed_text.split("[target]")[0] + "[simulation]" + seed_text.split("[simulation]")[1]
    loaded = load_design(write(tmp_path, no_target), ["target.output_speed_rpm=23"])
    assert loaded.design.target.output_speed_rpm == 23
    alu = ["materials.alu.density_kg_m3=2700", "materials.alu.youngs_modulus_MPa=7e4",
           "materials.alu.poisson_ratio=0.33", "stage.2.gear.material=alu"]
    d = load_design(str(SEED), alu).design
    assert d.materials["alu"].youngs_modulus_MPa == 7e4 and d.stage[2].gear.material == "alu"


def test_new_material_keeps_the_default_steel(tmp_path, seed_text):
    no_materials = seed_text.split("[materials.steel]")[0] + "[[stage]]" + seed_text.split("[[stage]]", 1)[1]
    path = write(tmp_path, no_materials)
    assert set(load_design(path).design.materials) == {"steel"}
    alu = ["materials.alu.density_kg_m3=2700", "materials.alu.youngs_modulus_MPa=7e4", "materials.alu.poisson_ratio=0.33"]
    assert set(load_design(path, alu).design.materials) == {"steel", "alu"}


def test_later_override_wins_and_file_is_untouched():
    loaded = load_design(str(SEED), ["stage.0.pinion.teeth=22", "stage.0.pinion.teeth=23"])
    assert loaded.design.stage[0].pinion.teeth == 23
    assert loaded.raw["stage"][0]["pinion"]["teeth"] == 23
    assert load_design(str(SEED)).design.stage[0].pinion.teeth == 21


@pytest.mark.parametrize(
    ("override", "table", "gone", "key"),
    [
        ("input.speed_rpm=1450", "input", "speed_deg_s", "speed_rpm"),
        ("input.speed_rad_s=100", "input", "speed_deg_s", "speed_rad_s"),
        ("load.torque_Nm=5310", "load", "torque_Nmm", "torque_Nm"),
        ("target.output_speed_deg_s=138", "target", "output_speed_rpm", "output_speed_deg_s"),
    ],
)
def test_override_replaces_its_exclusive_sibling(override, table, gone, key):
    loaded = load_design(str(SEED), [override])
    assert gone not in loaded.raw[table] and key in loaded.raw[table]
    assert getattr(getattr(loaded.design, table), gone) is None


def test_load_torque_speed_table_and_torque_key_replace_each_other(tmp_path, seed_text):
    """`[load] torque_speed` is the load's torque given as a table, instead of a torque key (the starter file's
    comment): `--set load.torque_speed=...` on a file with `torque_Nmm` replaces it, as `--set load.torque_Nm`
    does; before, it was exit 2 "torque_speed gives the load's torque: no torque_Nmm beside it"."""
    loaded = load_design(str(SEED), ["load.torque_speed=[[0, 4000], [30, 5310]]"])
    assert "torque_Nmm" not in loaded.raw["load"] and loaded.design.load.torque_Nmm is None
    assert loaded.design.load.torque_speed is not None
    table = seed_text.replace("torque_Nmm = 5.31e6", "torque_speed = [[0, 4000], [30, 5310]]", 1)
    assert table != seed_text
    loaded = load_design(write(tmp_path, table), ["load.torque_Nm=5310"])
    assert loaded.design.load.torque_Nm == 5310 and loaded.design.load.torque_speed is None


STEEL_4140 = "{density_kg_m3 = 7850, youngs_modulus_MPa = 205000, poisson_ratio = 0.29}"


@pytest.mark.parametrize("table", ["materials.4140", 'materials."4140"', "materials.'4140'"])
@pytest.mark.parametrize("name", ["4140", '"4140"'])
def test_a_material_named_by_a_number(table, name):
    """AISI 4140, a material name that is a number: `--set materials.4140={...}` defines it (a segment under a
    name-keyed table is a name, never an index) and `--set stage.0.pinion.material=4140` uses it (a key that holds
    a string takes the text as typed). Before: "materials: must be a string, got 4140" and
    "stage[0].pinion.material: must be a string, got 4140"."""
    loaded = load_design(str(SEED), [f"{table}={STEEL_4140}", f"stage.0.pinion.material={name}"])
    assert set(loaded.design.materials) == {"steel", "4140"}
    assert loaded.design.stage[0].pinion.material == "4140"
    assert loaded.design.materials["4140"].density_kg_m3 == 7850


def test_a_string_key_takes_a_number_as_its_text():
    assert load_design(str(SEED), ["title=2024"]).design.title == "2024"
    assert load_design(str(SEED), ["title=1e3"]).design.title == "1e3"  # as typed, not "1000.0"
    assert load_design(str(SEED), ['materials."a.b"=' + STEEL_4140]).design.materials["a.b"].density_kg_m3 == 7850
    err = error_of(str(SEED), ["simulation.method=1"])  # a choice of words stays a choice: 1 is none of them
    assert "must be 'auto'" in str(err) and err.exit_code == EXIT_USAGE
    err = error_of(str(SEED), ["stage.0.pinion.teeth=abc"])  # and a number stays a number
    assert str(err) == '--set: stage[0].pinion.teeth: must be a whole number, got "abc"'


def test_input_torque_override_replaces_its_sibling(tmp_path, seed_text):
    torque = seed_text.replace("ramp_s = 0.18\n", 'ramp_s = 0.18\ndrive = "torque"\ntorque_Nmm = 1e5\n', 1)
    loaded = load_design(write(tmp_path, torque), ["input.torque_Nm=250"])
    assert loaded.design.input.torque_Nm == 250 and loaded.design.input.torque_Nmm is None


def test_unknown_override_key_has_source_set_and_hint():
    err = error_of(str(SEED), ["stage.0.pinion.teath=22"])
    assert (err.source, err.key) == ("--set", "stage.0.pinion.teath")
    assert "did you mean 'teeth'" in str(err)
    err = error_of(str(SEED), ["inptu.speed_rpm=3"])
    assert err.source == "--set" and "did you mean 'input'" in err.message
    err = error_of(str(SEED), ["simulation.metod=Radau"])
    assert "did you mean 'method'" in err.message


@pytest.mark.parametrize(
    ("override", "fragment"),
    [
        ("stage.3.pinion.teeth=22", "index 3 is out of range: the file has 3 stage entries (0–2)"),
        ("stage.pinion.teeth=22", "give an index, e.g. stage.0.pinion.teeth"),
        # a word in the index's place that no stage has as a key is the index, mistyped: replaced, not kept before
        # (before: "e.g. stage.0.x.pinion.teeth", a key that does not exist either)
        ("stage.x.pinion.teeth=22", "give an index, e.g. stage.0.pinion.teeth"),
        ("stage.first.gear.teeth=22", "give an index, e.g. stage.0.gear.teeth"),
        ("stage.mesh.damping_ratio=0.1", "give an index, e.g. stage.0.mesh.damping_ratio"),  # a key: kept
        ("stage.fixed=ring", "give an index, e.g. stage.0.fixed"),  # a planetary stage's key: kept
        ("stage.ring.teeth=57", "give an index, e.g. stage.0.ring.teeth"),
        ("load.fluctuation.a.amplitude_percent=5", "e.g. load.fluctuation.0.amplitude_percent"),
        ("duty.name.hours=3", "e.g. duty.0.hours"),  # a key holding a value, not a table: not kept before "hours"
        ("input.speed_rpm.x=3", "input.speed_rpm is a value, not a table"),
        ("input.speed_rpm", "expected KEY=VALUE"),
        ("=3", "expected KEY=VALUE"),
        ("stage..teeth=3", "empty key segment"),
    ],
)
def test_bad_override_is_a_config_error(override, fragment):
    err = error_of(str(SEED), [override])
    assert err.source == "--set" and fragment in str(err), str(err)
    assert err.exit_code == EXIT_USAGE and len(str(err).splitlines()) == 1


def test_invalid_override_value_is_blamed_on_set():
    err = error_of(str(SEED), ["stage.0.pinion.teeth=3"])
    assert str(err) == "--set: stage[0].pinion.teeth: must be ≥ 5, got 3"
    err = error_of(str(SEED), ["input.speed_rpm=fast"])
    assert str(err) == '--set: input.speed_rpm: must be a number, got "fast"'
    err = error_of(str(SEED), ["input.torque_Nm=100"])  # drive is "speed": a table-level rule
    assert err.source == "--set" and err.key == "input"


# --- messages --------------------------------------------------------------------------------


def test_did_you_mean_at_depth(tmp_path, seed_text):
    path = write(tmp_path, seed_text.replace("teeth = 21,", "teath = 21,"), "teath.toml")
    err = error_of(path)
    assert str(err) == f"{path}: stage[0].pinion.teath: unknown key 'teath' (did you mean 'teeth'?)"
    assert (err.source, err.key) == (path, "stage[0].pinion.teath")


@pytest.mark.parametrize(
    ("old", "new", "key", "message"),
    [
        ("teeth = 17, face_width_mm = 250", "teeth = 4, face_width_mm = 250", "stage[1].pinion.teeth", "must be ≥ 5, got 4"),
        ("teeth = 21,", "teeth = 21.5,", "stage[0].pinion.teeth", "must be a whole number, got 21.5"),
        ("teeth = 21,", "teeth = 21.0,", "stage[0].pinion.teeth", "must be a whole number, got 21.0 (write 21)"),
        ("helix_angle_deg = 12", "helix_angle_deg = nan", "stage[0].helix_angle_deg", "must be a finite number, got nan"),
        ("helix_angle_deg = 12", "helix_angle_deg = 45", "stage[0].helix_angle_deg", "must be < 45, got 45"),
        ('hand = "left",', 'handd = "left",', "stage[0].pinion.handd", "unknown key 'handd' (did you mean 'hand'?)"),
        ('hand = "left",', 'hand = "Left",', "stage[0].pinion.hand",
         "must be 'left', 'right' or 'spur', got \"Left\" (did you mean 'left'?)"),
        ("poisson_ratio = 0.29", "poisson_ratio = 0.5", "materials.steel.poisson_ratio", "must be < 0.5, got 0.5"),
        ('stiffness = "hertz"', "stiffness = 0", "contact.stiffness", "must be ≥ 1, got 0"),
        ('stiffness = "hertz"', "stiffness = [1]", "contact.stiffness", "must be 'hertz', 'iso6336' or a number, got an array"),
        ("[simulation]", '[simulation]\nwindow_start_s = "0.3"', "simulation.window_start_s",
         'must be a number, got "0.3" (remove the quotes)'),
        ("speed_deg_s = 3600", "speed_deg_s = 3600\nspeed_rpm = 600", "input",
         "give exactly one of speed_deg_s, speed_rpm, speed_rad_s (got speed_deg_s, speed_rpm)"),
        ('[materials.steel]', '[materials."mild steel"]\ndensity_kg_m3 = 7850\nyoungs = 2e5\npoisson_ratio = 0.3\n'
         '[materials.steel]', 'materials."mild steel".youngs', "unknown key 'youngs' (did you mean 'youngs_modulus_MPa'?)"),
    ],
)
def test_one_error_is_one_line_with_file_key_and_engineer_wording(tmp_path, seed_text, old, new, key, message):
    assert old in seed_text
    path = write(tmp_path, seed_text.replace(old, new, 1))
    err = error_of(path)
    assert str(err) == f"{path}: {key}: {message}"
    assert (err.source, err.key, err.message) == (path, key, message)
    assert not isinstance(err, ConfigErrors)


def test_several_errors_one_line_each(tmp_path, seed_text):
    text = seed_text.replace("teeth = 21,", "teeth = 2,").replace("0.29", "-1").replace("[load]", "[lod]")
    path = write(tmp_path, text)
    err = error_of(path)
    assert isinstance(err, ConfigErrors) and err.exit_code == EXIT_USAGE
    assert str(err).splitlines() == [
        f"{path}: materials.steel.poisson_ratio: must be ≥ 0.01, got -1",
        f"{path}: stage[0].pinion.teeth: must be ≥ 5, got 2",
        f"{path}: lod: unknown key 'lod' (did you mean 'load'?)",
    ]
    assert (err.source, err.key) == (path, "materials.steel.poisson_ratio")  # the first error's


def test_many_errors_are_capped(tmp_path, seed_text):
    text = seed_text.replace("[simulation]", "[simulation]\n" + "".join(f"junk{i} = 1\n" for i in range(30)))
    lines = str(error_of(write(tmp_path, text))).splitlines()
    assert len(lines) == 21 and lines[-1].endswith("... and 10 more errors")


@pytest.mark.parametrize(
    ("content", "fragment"),
    [
        (b"", "file is empty"),
        (b"# only a comment\n", "file is empty"),
        (b"\x00\x01\x02garbage", "binary data"),
        (b'title = "caf\xe9"\n', "not UTF-8 text: byte 0xe9 at line 1, column 13"),
        (b"title = 'x'\n[input\n", "TOML syntax error at line 2, column 7"),
        (b"title = 'x'\ntitle = 'y'\n", "TOML syntax error at line 2"),
        (b"a = " + b"[" * 5000 + b"]" * 5000, "nested too deeply"),
        (b"a = 1" + b"0" * 5000, "integer with more than"),
    ],
)
def test_unreadable_content(tmp_path, content, fragment):
    path = tmp_path / "bad.toml"
    path.write_bytes(content)
    err = error_of(str(path))
    assert fragment in str(err) and err.source == str(path) and err.key is None
    assert len(str(err).splitlines()) == 1


def test_missing_file_directory_and_huge_file(tmp_path):
    missing = str(tmp_path / "nope.toml")
    assert str(error_of(missing)).startswith(f"{missing}: no such file")
    assert str(error_of(str(tmp_path))) == f"{tmp_path}: is a directory, not a design file"
    big = tmp_path / "big.toml"
    big.write_bytes(b"#" * (10 * 1024 * 1024 + 1))
    assert "larger than 1 MiB" in str(error_of(str(big)))
    assert "larger than 1 MiB" in str(error_of("-", stdin=io.BytesIO(b" " * (10 * 1024 * 1024 + 1))))
    assert "not a valid file name" in str(error_of("bad\0name.toml"))


def test_unreadable_file(tmp_path, monkeypatch):
    path = tmp_path / "locked.toml"
    path.write_text("title = 'x'\n")

    real_open = os.open

    def deny(name, *args, **kwargs):
        if str(name) == str(path):
            raise PermissionError(13, "Permission denied", str(name))
        return real_open(name, *args, **kwargs)

    monkeypatch.setattr(os, "open", deny)  # chmod 0 does not stop root
    assert str(error_of(str(path))) == f"{path}: permission denied"


# --- starter file and schema ---------------------------------------------------------------------


def test_starter_toml_round_trips_to_the_seed(tmp_path):
    text = starter_toml()
    loaded = load_design(write(tmp_path, text, "starter.toml"))
    assert loaded.design == load_design(str(SEED)).design
    assert loaded.raw == tomllib.loads(SEED.read_text(encoding="utf-8"))


def test_starter_toml_comments_every_table():
    lines = starter_toml().splitlines()
    headers = [i for i, line in enumerate(lines) if line.startswith("[")]
    first_of_table = [i for i in headers if lines[i] != "[[stage]]" or lines[i - 1].startswith("#")]
    assert len(first_of_table) == 7  # materials, first stage, contact, input, load, target, simulation
    for i in first_of_table:
        assert lines[i - 1].startswith("#"), lines[i]


def test_json_schema_has_the_top_level_properties():
    schema = json_schema()
    assert schema["title"] == "gearcli design file" and schema["description"]
    assert set(schema["properties"]) == {"title", "materials", "stage", "contact", "input", "load", "target", "simulation",
                                         "lubricant", "rating",  # the strength rating (issue 22)
                                         "bearing", "duty"}  # loads to life (issue 24)
    assert set(schema["required"]) == {"stage", "input", "load"}
    assert schema["additionalProperties"] is False
    import json

    json.dumps(schema)  # serialisable as it is
