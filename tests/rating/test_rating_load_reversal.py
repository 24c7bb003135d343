"""The rating's warnings where its unidirectional load is not the teeth's (`rating_out_of_range`, gearcli/design/rating.py).

configs/industrial_two_stage_rated.toml: two helical stages (19/75 m_n 3, 19/68 m_n 5, β = 12°, each η = 0.98). Under
load reversal (a negative output torque) the gear drives each stage and ISO 6336-1's F_t = T_1 / r_1, from the
pinion's torque, is the driven member's: by hand the driving gear's |T_2| / r_2 is 1/η of it. A load fluctuation
of more than 100 % of the torque changes its sign, so the teeth bend both ways (ISO 6336-5: 0.7 σ_FE)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

CONFIG = Path(__file__).resolve().parents[2] / "configs" / "industrial_two_stage_rated.toml"
COS = math.cos(math.radians(12.0))


def _warnings(*sets: str) -> list[dict]:
    res = CliRunner().invoke(cli, ["design", str(CONFIG), "--format", "json", "-q",
                                   *[a for s in sets for a in ("--set", s)]])
    assert res.exit_code == 0, res.output
    return [w for w in json.loads(res.stdout)["warnings"] if w["code"] == "rating_out_of_range"]


def test_a_reversed_load_names_the_pinions_force_and_the_driving_gears():
    found = {w["stage"]: w for w in _warnings("load.torque_Nm=-1340") if w["quantity"] == "load_reversal"}
    assert sorted(found) == [1, 2]
    t2 = 1340e3  # N mm on stage 2's gear; its pinion's, stage 1's gear's torque: T η 19/68 (power flowing back)
    t1 = t2 * 0.98 * 19 / 68
    for stage, torque, teeth, module in ((2, t2, 68, 5.0), (1, t1, 75, 3.0)):
        r_gear = 0.5 * teeth * module / COS
        w = found[stage]
        assert_allclose(w["driving_force_N"], torque / r_gear, rtol=1e-9)
        assert_allclose(w["value"], 0.98 * torque / r_gear, rtol=1e-9)  # T_1 / r_1 = η T_2 / r_2
        assert "load reversal" in w["message"] and f"{1 / 0.98:.4g}x" in w["message"]


def test_a_forward_load_is_not_warned():
    assert not _warnings("load.torque_Nm=1340")


@pytest.mark.parametrize(("fluctuation", "warned"), [
    ("[{amplitude_percent = 100, frequency_Hz = 5}]", None),  # touches zero, no reversal
    ("[{amplitude_percent = 60, frequency_Hz = 5}, {amplitude_percent = 45, frequency_Hz = 7}]", 105.0),
    ("[{amplitude_percent = 60, frequency_Hz = 5}]", None),
])
def test_a_load_that_changes_sign_warns_of_alternating_bending(fluctuation, warned):
    found = [w for w in _warnings(f"load.fluctuation={fluctuation}") if w["quantity"] == "alternating_load"]
    if warned is None:
        assert not found
        return
    (w,) = found
    assert_allclose(w["value"], warned, rtol=1e-12)
    assert "0.7" in w["message"] and w["stage"] is None
