"""Issue 21, field test: the report puts the engineering first (design, modes and resonances, theory against
simulation, dynamic factors) and the work-precision study after it, in every format."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]
SEED = str(ROOT / "configs" / "concrete_mixer.toml")
ORDER = ["## Design", "## Modes and resonances", "## Theory against simulation", "## Dynamic factor",
         "## Mesh force fluctuation", "## Numerical accuracy", "## Warnings"]


@pytest.fixture(scope="module")
def markdown() -> str:
    res = CliRunner().invoke(cli, ["report", SEED, "--rtols", "1e-4,1e-6", "--format", "markdown"])
    assert res.exit_code == 0, res.output
    return res.stdout


def test_markdown_sections_engineering_first(markdown):
    where = [markdown.find(h) for h in ORDER]
    assert all(i >= 0 for i in where), dict(zip(ORDER, where, strict=True))
    assert where == sorted(where)


def test_design_section_has_the_geometry_by_hand(markdown):
    design = markdown.split("## Design", 1)[1].split("## ", 1)[0]
    assert "| teeth z1 / z2 | 21 / 51 | 17 / 50 | 17 / 53 |" in design  # Table 1 of the seed paper
    assert "| normal module m_n [mm] | 12 | 18 | 25 |" in design
    # a = m_n (z1 + z2) / (2 cos beta) = 12 x 72 / (2 cos 12 deg) = 441.65 mm
    assert "| centre distance a [mm] | 441.65" in design
    assert "input power" in design and "°/s" in design  # the seed's speed key is speed_deg_s


def test_modes_section_lists_the_seed_modes(markdown):
    modes = markdown.split("## Modes and resonances", 1)[1].split("## ", 1)[0]
    for f in ("58.01", "112.4", "184.1"):  # the hand linear model's 58.010, 112.441, 184.115 Hz (test_seed_modes_hand)
        assert f"| {f}" in modes


def test_json_keys_engineering_first():
    res = CliRunner().invoke(cli, ["report", SEED, "--quick", "--format", "json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    keys = [k for k in doc if k not in ("gearcli_version", "input_sha256")]
    assert keys.index("design") < keys.index("modes") < keys.index("comparison") < keys.index("accuracy")
    freqs = [m["frequency_Hz"] for m in doc["modes"]["modes"]]
    assert freqs == pytest.approx([58.01, 112.4, 184.1], rel=5e-4)  # the hand model's (test_seed_modes_hand)
