"""A planet pin's bearings over a start from rest carry what they carry in the window (tr23f): the worst planet's
force times the file's K_gamma (docs/life.md, "Planetary stages"; K_gamma stands for the unequal sharing the
identical simulated planets do not show, during a start as in operation, and the start's planet-mesh classes
carry it too). The start's pin figures took the mean planet's force without K_gamma: its peak P_0, and so the pin
bearings' ISO 76 static safety over the duty (set by the start's peak), 1/K_gamma = 13 % too favourable here.

Hand model of the pin (the scene of tests/life/test_planetary_bearings.py, x = 0, lossless: both meshes push the
planet with F_t, their separating forces cancel, their axial forces F_t tan(beta) make a couple over the span L):
per bearing, tangential K_gamma F_t and radial K_gamma 2 F_t tan(beta) r_w,p / L, so the radial reaction is
linear in the planet's force and the start's peak radial reaction is that of the start's peak sun-mesh force,
the largest over the planets (`points[i].start.peak_tangential_N`). s_0 = C_0 / P_0 with P_0 = F_r (no axial
load on a pin bearing: the two meshes' axial forces cancel).
"""

from __future__ import annotations

import json
import math

from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli
from tests.life.test_planetary_bearings import BETA, K_GAMMA, M_N, PLANETARY, SPAN, STEADY, Z_P

C0_N = 30e3

DUTY = """
[simulation]
duration_s = 0.3
steps = 600

[[duty]]
name = "full"
hours = 1000
speed_rpm = 300
torque_Nm = 400
starts = 500
"""


def test_the_start_loads_the_pins_with_the_worst_planet_and_k_gamma(tmp_path):
    text = PLANETARY.replace("dynamic_load_rating_kN = 40\n", f"dynamic_load_rating_kN = 40\nstatic_load_rating_kN = {C0_N / 1e3}\n")
    assert text.count("static_load_rating_kN") == 2
    path = tmp_path / "planetary.toml"
    path.write_text(text + DUTY)
    # a load step at t = 0 under a 0.05 s speed ramp: the start's peak is well above the window's force
    args = [a for a in STEADY if a != "load.ramp_s=0.05"]
    args = args[:-1] if args[-1] == "--set" else args
    res = CliRunner().invoke(cli, ["life", str(path), "--format", "json", "-q", *args])
    assert res.exit_code == 0, res.output
    life = json.loads(res.stdout)["life"]
    start = life["points"][0]["start"]
    f_peak = start["peak_tangential_N"][0]
    r_wp = 0.5 * Z_P * M_N / math.cos(math.radians(BETA))
    per_newton = math.hypot(1.0, 2 * math.tan(math.radians(BETA)) * r_wp / SPAN)  # radial reaction per N of F_t
    peak_radial = K_GAMMA * f_peak * per_newton
    window_radial = life["bearings"][4]["loads_N"][0]
    assert peak_radial > 1.2 * window_radial  # the start decides the static safety
    assert all("planet_stage" not in b for b in start["bearings"][:4])  # a shaft's bearing keeps its keys
    for j in (4, 5):  # the two pin bearings
        # the start's record names a pin's bearing as life's bearings[j] does: planet_stage beside shaft 0
        assert start["bearings"][j]["planet_stage"] == life["bearings"][j]["planet_stage"] == 1
        assert start["bearings"][j]["shaft"] == 0
        assert_allclose(start["bearings"][j]["peak_radial_N"], peak_radial, rtol=1e-9)
        assert_allclose(life["bearings"][j]["static_equivalent_load_N"], peak_radial, rtol=1e-9)
        assert_allclose(life["bearings"][j]["static_safety"], C0_N / peak_radial, rtol=1e-9)
