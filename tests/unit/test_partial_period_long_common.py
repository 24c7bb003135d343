"""A common excitation period longer than the window: `window_partial_period` names the run that holds one.

configs/mixer_time_varying_backlash.toml: the seed's three meshes at 600 rpm excite at 210, 70 and 23.8 Hz (and
harmonics); their common period is, by hand, lcm(1/210, 1/70, 5/119) = lcm(1, 1, 5) / gcd(210, 70, 119) = 5/7 s,
longer than the 0.244-0.5 s window. The warning said "(a longer simulation.duration_s)" with no figure; it now names
a window of one common period from the window's start, 0.244 + 5/7 s, sampled as the run was (0.5 s / 2000 steps),
and that run has no partial period left."""

from __future__ import annotations

import json
import math
from pathlib import Path

from click.testing import CliRunner

from gearcli.cli import cli

CONFIG = Path(__file__).resolve().parents[2] / "configs" / "mixer_time_varying_backlash.toml"


def _partial(*sets: str) -> list[str]:
    res = CliRunner().invoke(cli, ["simulate", str(CONFIG), "--format", "json", "-q",
                                   *[a for s in sets for a in ("--set", s)]])
    assert res.exit_code == 0, res.output
    return [w["message"] for w in json.loads(res.stdout)["warnings"] if w["code"] == "window_partial_period"]


def test_the_advised_run_of_one_common_period_has_no_partial_period():
    period = 5 / 7
    end = 0.244 + period
    steps = math.ceil(end / (0.5 / 2000))
    advice = (f"--set simulation.duration_s={end:.9g} --set simulation.steps={steps} --set "
              "simulation.window_start_s=0.244: one period")
    found = _partial()
    assert found and all(f"common period {period:.4g} s ({advice})" in m for m in found)
    assert not _partial(f"simulation.duration_s={end:.9g}", f"simulation.steps={steps}", "simulation.window_start_s=0.244")
