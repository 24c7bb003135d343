"""Every broken design file of the corpus, through the real command line (issue 5).

Each must give exit code 2, a message on stderr that names the file and the key path (or the
line for a syntax error), no traceback, nothing on stdout, and must not touch an ``-o`` file.
A hypothesis test then fuzzes the command with mutated design files: exit 0, 1 or 2, never a crash.
"""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest
from click.testing import CliRunner
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]
SEED_TEXT = (ROOT / "configs" / "concrete_mixer.toml").read_text()

_spec = importlib.util.spec_from_file_location("badinput_cases", ROOT / "tests" / "badinput" / "cases.py")
cases = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(cases)

ALL_CASES = cases.CONFIG_CASES + cases.DESIGN_CASES


@pytest.mark.parametrize("name,fragment", ALL_CASES, ids=[c[0] for c in ALL_CASES])
@pytest.mark.parametrize("command", ["design", "simulate"])
def test_bad_input_exit_2_one_clean_message(tmp_path, name, fragment, command):
    path = cases.materialize(name, tmp_path)
    out = tmp_path / "previous_output.json"
    out.write_text("keep me\n")
    res = CliRunner().invoke(cli, [command, path, "-o", str(out)])
    assert res.exit_code == 2, (res.exit_code, res.stderr)
    assert "Traceback" not in res.stderr and res.exception is None or isinstance(res.exception, SystemExit)
    assert res.stdout == ""
    assert Path(name).name in res.stderr  # the file is named
    assert fragment in res.stderr  # the key path (or line, or cause) is named
    first = res.stderr.splitlines()[0]
    assert first.startswith("gearcli: ")
    assert out.read_text() == "keep me\n"


@pytest.mark.parametrize("override,fragment", [
    ("stage.0.pinion.teath=22", "stage.0.pinion.teath"),
    ("stage.7.pinion.teeth=22", "stage"),
    ("nosuchtable.key=1", "nosuchtable"),
    ("stage.0.pinion.teeth", "KEY=VALUE"),
])
def test_bad_set_override_exit_2(override, fragment):
    res = CliRunner().invoke(cli, ["design", str(ROOT / "configs" / "concrete_mixer.toml"), "--set", override])
    assert res.exit_code == 2, res.stderr
    assert "--set" in res.stderr and fragment in res.stderr
    assert "Traceback" not in res.stderr


_VALUES = st.sampled_from(["0", "-1", "nan", "inf", "-inf", "1e308", '"x"', "true", "[]", "{}", "1.5", "99999999",
                           '"left"', "0.0001", "3"])


@st.composite
def mutated_seed(draw) -> str:
    """The seed file with a few values replaced, lines dropped or duplicated, or characters flipped."""
    lines = SEED_TEXT.splitlines()
    for _ in range(draw(st.integers(1, 4))):
        i = draw(st.integers(0, len(lines) - 1))
        kind = draw(st.sampled_from(["value", "drop", "dup", "char"]))
        if kind == "value" and "=" in lines[i] and not lines[i].lstrip().startswith("#"):
            key = lines[i].split("=", 1)[0]
            lines[i] = f"{key}= {draw(_VALUES)}"
        elif kind == "drop":
            del lines[i]
        elif kind == "dup":
            lines.insert(i, lines[i])
        elif lines[i]:
            j = draw(st.integers(0, len(lines[i]) - 1))
            lines[i] = lines[i][:j] + draw(st.sampled_from(list("=[]{}\"'#.,0x \\"))) + lines[i][j + 1:]
        if not lines:
            break
    return "\n".join(lines) + "\n"


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(text=mutated_seed())
def test_fuzzed_design_files_never_crash_the_cli(text):
    res = CliRunner().invoke(cli, ["design", "-", "--format", "json"], input=text)
    assert res.exit_code in (0, 1, 2), res.stderr
    assert "Traceback" not in res.stderr
    assert "internal error" not in res.stderr, res.stderr
