"""Issue 21, field test: resonance warnings weigh how strongly the exciting mesh drives the mode (its share
of the mode's strain energy over twice the modal damping ratio), consider mesh orders 1x-3x and shaft 1x,
and say how strongly each crossing is excited."""

from __future__ import annotations

import json
import math
import shutil
from pathlib import Path

import pytest
from click.testing import CliRunner

from gearcli.cli import cli

ROOT = Path(__file__).resolve().parents[2]
ONE_STAGE = str(ROOT / "configs" / "extreme" / "one_stage.toml")


def _run(*args: str) -> tuple[dict, str]:
    res = CliRunner().invoke(cli, [*args, "--format", "json"])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout), res.stderr


def _messages(doc: dict) -> list[str]:
    return [w["message"] if isinstance(w, dict) else w for w in doc["warnings"]]


def test_single_mesh_oscillator_participation_and_gain_by_hand():
    """One stage, input held (speed drive): one mode, all its strain energy in the mesh (share 1). A viscous
    mesh with damping_ratio zeta = 0.05 has c = 2 zeta sqrt(k_n m_e) with k_n the normal slope; along the
    transverse line of action the stiffness is k_n cos^2(beta_b), so the mode's damping ratio is
    zeta / cos(beta_b) and the resonant gain s / (2 zeta_mode) = cos(beta_b) / (2 zeta)."""
    doc, _ = _run("modes", ONE_STAGE, "--set", "contact.damping_ratio=0.05", "--set", "contact.damping_Ns_mm=0")
    (mode,) = doc["boundaries"]["clamped_input"]
    alpha_t = math.atan(math.tan(math.radians(20)) / math.cos(math.radians(12)))
    beta_b = math.atan(math.tan(math.radians(12)) * math.cos(alpha_t))
    assert mode["damping_ratio"] == pytest.approx(0.05 / math.cos(beta_b), rel=1e-9)
    names = [c["excitation"] for c in mode["crossings"]]
    assert {"stage 1 mesh 1x", "stage 1 mesh 2x", "stage 1 mesh 3x"} <= set(names)
    for c in mode["crossings"]:
        if c["excitation"].startswith("stage 1 mesh"):
            assert c["participation"] == pytest.approx(1.0)
            assert c["amplification"] == pytest.approx(math.cos(beta_b) / 0.1, rel=1e-9)
            assert c["strength"] == "strongly"


def test_shaft_orders_are_considered():
    """Shaft 2 of the seed turns at 600 * 21/51 rpm: its 1x order meets a mode of f Hz at an input speed of
    60 f / (21/51) rpm (by hand from the mode's frequency)."""
    doc, _ = _run("modes", str(ROOT / "configs" / "concrete_mixer_drivetrain.toml"))
    modes = doc["boundaries"]["clamped_input"]
    low = modes[0]
    cross = {c["excitation"]: c for c in low["crossings"]}
    assert "shaft 2 1x" in cross
    assert cross["shaft 2 1x"]["input_speed_rpm"] == pytest.approx(60 * low["frequency_Hz"] / (21 / 51), rel=1e-9)


def test_conveyor_mode_3_is_not_warned_the_stage1_mesh_holds_0_05_percent(tmp_path):
    path = tmp_path / "conveyor.toml"
    shutil.copy(ROOT / "configs" / "conveyor.toml", path)
    doc, stderr = _run("design", str(path))
    assert not [m for m in _messages(doc) if m.startswith("resonance:")], _messages(doc)
    assert "mode 3" not in stderr
    modes, _ = _run("modes", str(path))
    mode3 = modes["boundaries"]["clamped_input"][2]
    assert mode3["energy_share"]["stage 1 mesh"] < 1e-3  # the figure the issue quotes: 0.05 %
    (c,) = [c for c in mode3["crossings"] if c["excitation"] == "stage 1 mesh 2x"]
    assert c["participation"] == pytest.approx(mode3["energy_share"]["stage 1 mesh"])
    assert c["strength"] == "weakly" and c["amplification"] < 0.1


def test_a_strongly_excited_crossing_is_warned_with_its_strength():
    """configs/industrial_two_stage.toml: stage 1's mesh 2x order lies 2.9 % from mode 1, in which that mesh
    holds 40 % of the strain energy: warned, saying how strongly and with the exciting mesh's share."""
    doc, _ = _run("design", str(ROOT / "configs" / "industrial_two_stage.toml"))
    found = [m for m in _messages(doc) if m.startswith("resonance:")]
    assert found and all(("strongly excited" in m or "moderately excited" in m) for m in found)
    assert all("of the mode's strain energy" in m for m in found)
