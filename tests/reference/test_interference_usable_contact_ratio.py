"""Tip interference eats into the contact ratio: the check on ε_α reads the nominal (tip-to-tip) value, so the
interference warning says what a usable ε_α below 1.2 (or below 1) means. Figures by hand for spur pairs at
m = 4 mm, α = 20°, x = 0 (an undercut pinion: its involute reaches down to its base tangent point T1, so the usable
path runs from T1 to the pinion's tip point, g_a1 = √(r_a1² − r_b1²), over p_bt = π m cos α)."""

from __future__ import annotations

import json
import math

import pytest
from click.testing import CliRunner

from gearcli.cli import cli

M, ALPHA = 4.0, math.radians(20.0)


def _scene(z1: int, z2: int) -> str:
    return (f'title = "spur pair"\n[materials.steel]\ndensity_kg_m3 = 7850\nyoungs_modulus_MPa = 2.06e5\n'
            f"poisson_ratio = 0.3\n[[stage]]\nnormal_module_mm = {M}\nnormal_pressure_angle_deg = 20\n"
            f'pinion = {{ teeth = {z1}, face_width_mm = 40, material = "steel" }}\n'
            f'gear = {{ teeth = {z2}, face_width_mm = 40, material = "steel" }}\n'
            "[input]\nspeed_rpm = 1500\n[load]\ntorque_Nm = 500\n")


def _usable_by_hand(z1: int) -> float:
    r_a, r_b = M * z1 / 2 + M, M * z1 / 2 * math.cos(ALPHA)
    return math.sqrt(r_a**2 - r_b**2) / (math.pi * M * math.cos(ALPHA))


def _interference(tmp_path, z1: int, z2: int) -> dict:
    path = tmp_path / "pair.toml"
    path.write_text(_scene(z1, z2), encoding="utf-8")
    res = CliRunner().invoke(cli, ["design", str(path), "--format", "json"])
    assert res.exit_code == 0, res.output
    (found,) = [w for w in json.loads(res.stdout)["warnings"] if w.get("check") == "interference"]
    assert found["stage"] == 1 and found["member"] == "pinion"
    return found


@pytest.mark.parametrize(("z1", "z2", "meaning"), [
    (10, 40, None),                                  # usable 1.264: no qualifier
    (8, 60, "(< 1.2: little margin"),                # usable 1.117, nominal 1.546
    (5, 200, "(< 1: contact is interrupted"),         # usable 0.632, nominal 1.298
])
def test_usable_contact_ratio_by_hand_and_what_it_means(tmp_path, z1, z2, meaning):
    found = _interference(tmp_path, z1, z2)
    usable = _usable_by_hand(z1)
    assert found["contact_ratio_transverse_usable"] == pytest.approx(usable, rel=1e-9)
    assert found["contact_ratio_transverse"] >= 1.2  # the contact-ratio check itself stays silent
    text = found["message"]
    assert f"the usable transverse contact ratio is {usable:.3f}" in text
    if meaning is None:
        assert f"{usable:.3f}, not" in text
    else:
        assert f"{usable:.3f} {meaning}" in text
    assert text.count("usable transverse contact ratio") == 1
