"""Fuzzing the loader: whatever a mutated design file (or --set) holds, load_design returns a
LoadedDesign or raises ConfigError with a clean message, never any other exception."""

from __future__ import annotations

import io
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from gearcli.config import LoadedDesign, load_design
from gearcli.config.schema import DesignFile
from gearcli.errors import ConfigError

SEED = (Path(__file__).resolve().parents[2] / "configs" / "concrete_mixer.toml").read_text(encoding="utf-8")
LINES = SEED.splitlines(keepends=True)
VALUE_LINES = [i for i, line in enumerate(LINES) if " = " in line and not line.startswith("#")]

TOML_VALUES = st.sampled_from([
    "nan", "-nan", "inf", "-inf", "+inf", "0", "-0.0", "-1", "-1e300", "1e308", "1e309", "9" * 30,
    "0x7fffffffffffffff", "21.5", "5e-324", "true", "false", '"12"', '""', '"left"', "'hertz'", "[]",
    "[1, 2]", "{}", "{ teeth = 3 }", "1979-05-27", "07:32:00", "1979-05-27T07:32:00Z", '"\\u0000"',
    "= 1", "[", "{", '"unterminated', "left", "1_000", "0b101", "1e", ".5",
])
ALPHABET = st.sampled_from(list('=[]{}",.#\n \t\'0123456789-+eE_abxyzé\x00\x7f\u2028'))


@st.composite
def mutated(draw) -> bytes:
    lines = list(LINES)
    for _ in range(draw(st.integers(1, 4))):
        kind = draw(st.sampled_from(["char", "line", "value", "bytes"]))
        text = "".join(lines)
        if kind == "char" and text:
            i = draw(st.integers(0, len(text) - 1))
            op = draw(st.sampled_from(["delete", "duplicate", "replace", "insert"]))
            c = draw(ALPHABET)
            text = {"delete": text[:i] + text[i + 1:], "duplicate": text[:i] + text[i] + text[i:],
                    "replace": text[:i] + c + text[i + 1:], "insert": text[:i] + c + text[i:]}[op]
            lines = text.splitlines(keepends=True)
        elif kind == "line" and lines:
            i = draw(st.integers(0, len(lines) - 1))
            op = draw(st.sampled_from(["delete", "duplicate", "swap"]))
            if op == "delete":
                del lines[i]
            elif op == "duplicate":
                lines.insert(i, lines[i])
            else:
                j = draw(st.integers(0, len(lines) - 1))
                lines[i], lines[j] = lines[j], lines[i]
        elif kind == "value":
            i = draw(st.sampled_from(VALUE_LINES))
            if i < len(lines) and " = " in lines[i]:
                key = lines[i].split(" = ", 1)[0]
                lines[i] = f"{key} = {draw(TOML_VALUES)}\n"
    raw = "".join(lines).encode("utf-8")
    if draw(st.booleans()) and draw(st.booleans()):  # a quarter of the cases: raw byte damage
        i = draw(st.integers(0, max(len(raw) - 1, 0)))
        raw = raw[:i] + draw(st.binary(min_size=1, max_size=4)) + raw[i:]
    return raw


KEYS = st.sampled_from([
    "stage.0.pinion.teeth", "stage.2.gear.hand", "stage.5.gear.hand", "stage.0.mesh.exponent", "stage.x",
    "input.speed_rpm", "input.speed_deg_s", "input.drive", "input.torque_Nm", "load.torque_Nm",
    "target.output_speed_deg_s", "materials.steel.poisson_ratio", "materials.new.density_kg_m3",
    "contact.stiffness", "simulation.method", "simulation.steps", "title", "stage", "input", "nope.key",
    "stage.0.pinion.teeth.more", "", "stage..x", "stage[1].gear.teeth",
])
OVERRIDES = st.lists(st.builds(lambda k, v, eq: f"{k}={v}" if eq else k, KEYS, TOML_VALUES, st.booleans()), max_size=3)


def _check_message(exc: ConfigError) -> None:
    text = str(exc)
    assert text and "Traceback" not in text
    for line in text.splitlines():
        assert line.startswith(("<stdin>: ", "--set: ")), text


@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(raw=mutated(), overrides=OVERRIDES)
def test_loader_returns_a_design_or_raises_config_error(raw, overrides):
    try:
        loaded = load_design("-", overrides, stdin=io.BytesIO(raw))
    except ConfigError as exc:
        _check_message(exc)
        return
    assert isinstance(loaded, LoadedDesign) and isinstance(loaded.design, DesignFile)
    assert DesignFile.model_validate(loaded.raw) == loaded.design  # raw is what was validated
    assert len(loaded.sha256) == 64
