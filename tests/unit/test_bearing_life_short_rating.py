"""`bearing_life_short` names the dynamic load rating that lasts the required life, and following it clears it.

configs/motor_duty_starts.toml's bearing 1 (a ball bearing, C = 90 kN, on the 1480 rpm input shaft) carries
P = 7767.6 N at the design load. By hand, ISO 281: L10 = (C / P)^3 10^6 / (60 n) = 17,516 h, short of
[rating] required_life_h = 40,000 h; the life goes as C^p at the same load, so C >= P (40,000 h 60 n / 10^6)^(1/3)
= 118.5 kN lasts it: 119 kN (three digits, rounded up). The warning gave the life and said nothing of a cure. A
roller bearing (p = 10/3) the same way against a longer required life."""

from __future__ import annotations

import json
import math
from pathlib import Path

from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

CONFIG = Path(__file__).resolve().parents[2] / "configs" / "motor_duty_starts.toml"
N_RPM = 1480.0


def _short(*sets: str) -> dict[int, dict]:
    res = CliRunner().invoke(cli, ["design", str(CONFIG), "--format", "json", "-q",
                                   *[a for s in sets for a in ("--set", s)]])
    assert res.exit_code == 0, res.output
    return {w["bearing"]: w for w in json.loads(res.stdout)["warnings"] if w["code"] == "bearing_life_short"}


def test_a_short_ball_bearing_is_told_the_rating_that_lasts_it():
    found = _short()
    w = found[1]
    P = float(w["message"].split("equivalent load ")[1].split(" N")[0])
    assert_allclose(w["life_h"], (90e3 / P) ** 3 * 1e6 / (60 * N_RPM), rtol=1e-4)  # ISO 281 L10 by hand
    needed = P * (40000 * 60 * N_RPM / 1e6) ** (1 / 3) / 1e3
    assert 118.4 < needed < 118.6
    assert w["required_dynamic_load_rating_kN"] == math.ceil(needed)
    assert "bearing[0].dynamic_load_rating_kN ≥ 119 kN lasts it" in w["message"]
    assert 1 in _short("bearing[0].dynamic_load_rating_kN=118")
    assert 1 not in _short("bearing[0].dynamic_load_rating_kN=119")


def test_a_short_roller_bearing_takes_p_ten_thirds():
    found = _short("rating.required_life_h=2e6")
    w = found[3]  # shaft 2's roller bearing, C = 250 kN
    needed = 250 * (2e6 / w["life_h"]) ** 0.3
    assert w["required_dynamic_load_rating_kN"] >= needed
    assert w["required_dynamic_load_rating_kN"] < needed * 1.01
    c = w["required_dynamic_load_rating_kN"]
    assert 3 not in _short("rating.required_life_h=2e6", f"bearing[2].dynamic_load_rating_kN={c!r}")
    assert 3 in _short("rating.required_life_h=2e6", f"bearing[2].dynamic_load_rating_kN={0.99 * needed!r}")
