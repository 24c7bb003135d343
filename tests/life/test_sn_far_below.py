"""A duty point far below the S–N curve (a load of a few N·m on a gearbox rated for 1 MN·m, within the schema's
bounds): N = N_a (y_a / y)^k on the slope continued past the knee overflows a float for a tiny stress ratio y, and
Python's ``**`` raises OverflowError there, where it meant "no damage". ``gearcli life --static`` on the planetary
duty was gearcli's "internal error: OverflowError" (exit 1); a bin whose N passes every float now counts no damage.

Independent check: Miner's sum is additive over bins, so the damage with the gust point at 2 N·m equals, to
round-off, the damage of the same file without the gust point at all (its ~1e-300 share is below a double's
resolution beside the other points')."""

from __future__ import annotations

import json
import math
from pathlib import Path

from click.testing import CliRunner

from gearcli.cli import cli
from gearcli.rating.sn import SNCurve

ROOT = Path(__file__).resolve().parents[2]
DUTY = ROOT / "configs" / "planetary_duty.toml"


def test_cycles_to_failure_far_below_the_curve_is_unbounded_not_an_error():
    curve = SNCurve(((1e5, 1.6), (5e7, 1.0), (1e10, 0.85)), 1500.0, "iso", optimum=False)
    k = math.log(5e7 / 1e5) / math.log(1.6)  # the finite-life exponent, by hand
    assert math.isclose(curve.cycles_to_failure(1.3 * 1500.0), 1e5 * (1.6 / 1.3) ** k, rel_tol=1e-12)
    assert curve.cycles_to_failure(1e-9) == math.inf  # (0.85 / 6.7e-13)^k' overflows a float


def _damage(doc: dict) -> dict:
    out = {}
    for st in doc["life"]["stages"]:
        for member, modes in st.items():
            if isinstance(modes, dict) and "pitting" in modes:
                for mode in ("pitting", "bending"):
                    out[(st["index"], member, mode)] = modes[mode]["damage"]
    return out


def test_a_duty_point_far_below_the_curve_adds_no_damage(tmp_path):
    text = DUTY.read_text(encoding="utf-8")
    gust = '[[duty]]                         # gusts: 25 % over rated torque\nname = "gust"\nhours = 5200\n' \
           'torque_Nm = 1250000\nspeed_rpm = 12.127\n'
    assert gust in text
    without = tmp_path / "without.toml"
    without.write_text(text.replace(gust, ""), encoding="utf-8")
    runs = {}
    for name, args in (("tiny", [str(DUTY), "--set", "duty.2.torque_Nm=2"]), ("without", [str(without)])):
        out = tmp_path / f"{name}.json"
        res = CliRunner().invoke(cli, ["life", *args, "--static", "-q", "-o", str(out)])
        assert res.exit_code == 0, res.output
        runs[name] = _damage(json.loads(out.read_text(encoding="utf-8")))
    assert runs["tiny"].keys() == runs["without"].keys() and len(runs["tiny"]) >= 8
    for key, d in runs["without"].items():
        assert math.isclose(runs["tiny"][key], d, rel_tol=1e-9, abs_tol=1e-300), key
