"""An unexcited train of two planetary stages run by Radau: its ramp's ringing has decayed physically long before
the window, so the window is at rest and no ``statistics_unresolved`` warning ("whose vibration it damps
numerically") may stand beside it (gearcli.simulate.stepped_over: quiet planetary stages count as quiet).

Scene (not a shipped config): sun 25 / planets 20 (3) / ring 65 held, then sun 21 / planets 27 (4) / ring 75 held,
spur, m_n 4 and 6, x = 0, 12 kN m on the second carrier, default mesh law (damping ratio 0.05: the fastest light
mode, ~2 kHz, decays in ~2 ms). Hand reference (Willis and each sun's moment balance, lossless): T_sun,2 = T /
(1 + 75/21), T_sun,1 = T_sun,2 / (1 + 65/25), and each planet's reference-circle F_t = T_sun / (N r_sun).
"""

from __future__ import annotations

import json

from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

T_OUT = 12000.0
STAGES = ((25, 20, 65, 3, 4.0), (21, 27, 75, 4, 6.0))  # z_s, z_p, z_r, planets, m_n

SCENE = "\n".join(f"""
[[stage]]
type = "planetary"
normal_module_mm = {m}
sun    = {{ teeth = {zs}, face_width_mm = {15 * m} }}
planet = {{ teeth = {zp}, face_width_mm = {15 * m}, count = {n} }}
ring   = {{ teeth = {zr}, face_width_mm = {15 * m} }}
fixed = "ring"
input = "sun"
""" for zs, zp, zr, n, m in STAGES) + f"""
[input]
speed_rpm = 1500
ramp_s = 0.1

[load]
torque_Nm = {T_OUT}
ramp_s = 0.1

[simulation]
duration_s = 0.5
method = "Radau"
"""


def test_quiet_planetary_window_at_rest_and_not_warned(tmp_path):
    path = tmp_path / "planetary_pair.toml"
    path.write_text(SCENE)
    res = CliRunner().invoke(cli, ["-q", "simulate", str(path), "--format", "json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    assert doc["solver"]["method"] == "Radau"
    assert not [w for w in doc["warnings"] if w["code"] == "statistics_unresolved"], doc["warnings"]
    t_sun = T_OUT * 1e3  # N mm, carried back through both stages
    expected = []
    for zs, _zp, zr, n, m in reversed(STAGES):
        t_sun /= 1 + zr / zs
        expected.insert(0, t_sun / (n * 0.5 * zs * m))
    for st, f_t in zip(doc["summary"]["stages"], expected, strict=True):
        for stat in ("mean", "min", "max"):
            assert_allclose(abs(st["tangential_N"][stat]), f_t, rtol=1e-6)
