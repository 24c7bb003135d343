"""The extreme-scene catalogue (configs/extreme/): every scene finishes with the method ``"auto"`` is
expected to pick, gives finite output within its evaluation ceiling, and passes its independent checks
(spec table and reasons: tests/extreme/catalogue.py; README table: benchmarks/robustness.py).

Each scene also runs through the CLI (in-process): exit 0, JSON with finite numbers, no traceback.
"""

from __future__ import annotations

import json
import math

import pytest
from catalogue import SCENES, SCENES_DIR, run_scene
from click.testing import CliRunner

from gearcli.cli import cli

PARAMS = [pytest.param(s, id=s.name, marks=[pytest.mark.slow] if s.slow else []) for s in SCENES]


@pytest.mark.parametrize("scene", PARAMS)
def test_scene_passes_its_independent_checks(scene):
    run = run_scene(scene)
    failed = [f"{o.kind}: {o.text}" for o in run.outcomes if not o.ok]
    assert not failed, f"{scene.name}: " + "; ".join(failed)


@pytest.mark.parametrize("scene", PARAMS)
def test_scene_through_the_cli_exits_0_without_traceback(scene):
    res = CliRunner().invoke(cli, ["simulate", str(scene.path), "--format", "json"])
    assert res.exit_code == 0, res.output
    assert "Traceback" not in res.output
    doc = json.loads(res.stdout)
    numbers = [doc["summary"]["ratio"], doc["solver"]["energy_residual"]]
    numbers += [v for st in doc["summary"]["stages"] for ch in ("tangential_N", "radial_N", "axial_N")
                for v in st[ch].values()]
    assert all(isinstance(x, (int, float)) and math.isfinite(x) for x in numbers)
    assert doc["solver"]["method"] in scene.method.split("|")  # "A|B": a scene near auto's line (catalogue.py)


def test_every_scene_file_has_a_spec_and_a_header_that_states_the_right_answer():
    files = {p.stem for p in SCENES_DIR.glob("*.toml")}
    assert files == {s.name for s in SCENES}
    for scene in SCENES:
        head = scene.path.read_text().split("\ntitle")[0]
        assert "Right answer:" in head and "Stresses" in head, scene.name
        assert f"gearcli simulate configs/extreme/{scene.name}.toml" in head
        assert all(c.reason for c in scene.checks), scene.name


def test_the_catalogue_covers_the_brief():
    # each extreme named in issue 5 has its scene
    names = {s.name for s in SCENES}
    assert {"stiff_linear_100x", "stiff_linear_10000x", "stiff_hertz_100x", "stiff_hertz_10000x", "light_pinion",
            "zero_damping", "heavy_damping", "damping_depth_tiny", "damping_depth_huge", "overload",
            "rattle_zero_load", "load_reversal", "instant_ramps", "slow_ramps", "long_run", "one_stage",
            "five_stages", "spur", "high_helix", "low_speed", "high_speed", "unequal_inertias"} <= names
