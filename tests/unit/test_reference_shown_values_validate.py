"""docs/design-file.md shows what validation accepts: every inclusive bound the reference prints validates when
a file gives it, and a key's type is the one validation takes.

Found by a consumer that fed each documented bound back through `--set`: `input.speed_rad_s` was shown as
[0.00010472, 20944] while validation's ceiling is 200000 rpm = 200000 * 2 pi / 60 = 20943.951 rad/s, so the
documented 20944 was refused; `load.speed_exponent` was typed "string" though it is the integer 0, 1 or 2 (the
string "2" is refused).
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

from gearcli import api
from gearcli.config.reference import design_file_reference
from gearcli.errors import ConfigError

ROOT = Path(__file__).resolve().parents[2]
SEED = str(ROOT / "configs" / "concrete_mixer.toml")


def _row(key: str, section: str) -> list[str]:
    text = design_file_reference().split(f"## {section}\n", 1)[1].split("\n## ", 1)[0]
    line = next(x for x in text.splitlines() if x.startswith(f"| `{key}` |"))
    return [c.strip() for c in line.strip().strip("|").split("|")]


def test_speed_rad_s_bounds_as_shown_validate(tmp_path):
    allowed = _row("speed_rad_s", "[input]")[2]
    lo, hi = (float(x) for x in re.fullmatch(r"\[([^,]+), ([^\]]+)\]", allowed).groups())
    # the bounds by hand: 0.001 rpm and 200000 rpm in rad/s, shown to 6 digits
    assert 0.001 * 2 * math.pi / 60 <= lo == pytest.approx(0.001 * 2 * math.pi / 60, rel=1e-5)
    assert 200000 * 2 * math.pi / 60 >= hi == pytest.approx(200000 * 2 * math.pi / 60, rel=1e-5)
    for v in (lo, hi):  # a file giving the shown bound validates
        path = tmp_path / "rad_s.toml"
        path.write_text(Path(SEED).read_text().replace("speed_deg_s = 3600", f"speed_rad_s = {v!r}"))
        assert api.load(str(path)).design.input.speed_rad_s == v


def test_speed_exponent_is_documented_as_the_integer_validation_takes():
    cells = _row("speed_exponent", "[load]")
    assert cells[1] == "integer"
    api.load(SEED, ["load.speed_exponent=2"])
    with pytest.raises(ConfigError, match="speed_exponent"):
        api.load(SEED, ['load.speed_exponent="2"'])
