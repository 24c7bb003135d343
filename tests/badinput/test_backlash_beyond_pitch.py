"""A normal backlash at or beyond the normal base pitch leaves the teeth no thickness: exit 2 naming the key.

The normal backlash j_n is what the normal base pitch p_bn = π m_n cos α_n leaves of the two teeth's normal base
thicknesses along the line of action (p_bn = s_bn1 + s_bn2 + j_n); j_n ≥ p_bn means teeth of zero or negative
thickness. ``backlash_mm = 10`` on a 3 mm module (p_bn = 8.856 mm) was simulated without a word, the gear free to
turn more than a whole pitch before its next contact.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli.cli import cli

CONFIGS = Path(__file__).resolve().parents[2] / "configs"
# (file, stage index, m_n, alpha_n): a spur and a helical (beta = 12°) stage; p_bn does not depend on beta
STAGES = [("spur_oscillator_te.toml", 0, 3.0, 20.0), ("industrial_two_stage_rated.toml", 0, 3.0, 20.0)]


def _design(path: Path, *sets: str):
    args = ["design", str(path), "--format", "json"]
    for s in sets:
        args += ["--set", s]
    return CliRunner().invoke(cli, args)


@pytest.mark.parametrize(("name", "k", "m_n", "alpha_n"), STAGES)
def test_backlash_beyond_the_normal_base_pitch_is_refused(name, k, m_n, alpha_n):
    p_bn = math.pi * m_n * math.cos(math.radians(alpha_n))  # 8.856 mm
    res = _design(CONFIGS / name, f"stage.{k}.backlash_mm={p_bn * 1.0001:.6g}")
    assert res.exit_code == 2, res.output
    assert f"stage[{k}].backlash_mm" in res.stderr and f"{p_bn:.4g} mm" in res.stderr, res.stderr
    assert "Traceback" not in res.stderr


@pytest.mark.parametrize(("name", "k", "m_n", "alpha_n"), STAGES)
def test_backlash_below_the_normal_base_pitch_is_a_design(name, k, m_n, alpha_n):
    p_bn = math.pi * m_n * math.cos(math.radians(alpha_n))
    res = _design(CONFIGS / name, f"stage.{k}.backlash_mm={p_bn * 0.999:.6g}")
    assert res.exit_code == 0, res.stderr
