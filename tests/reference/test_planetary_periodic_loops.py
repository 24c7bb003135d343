"""``steady = "periodic"`` on a planetary stage (closed loops) must not lock a preload into the loops (trial tr15c).

A spur stage 21/30/81, 3 planets, ring held, the sun driven through a soft coupling, a 30 kg m² drum on the carrier
(a lightly damped 8.7 Hz mode) and a 5 µm second-harmonic transmission error on every mesh. Shooting's Newton step
solved (M - I) dx = -F with M - I singular along the loops' constants of the motion (2 here: 8 deflections over 6
free bodies); the step moved them, and the "converged" orbit had planet 1's sun mesh at +24.4 kN, planet 2's at
-321.6 kN (static 1.96 kN each), with no warning. In any periodic state each body's mean acceleration is 0, so
(torque balance, independent of the dynamics) the drum's coupling carries the load, 900 N m, and with equal planets
and no position errors each planet's sun mesh carries T_sun / (N r_s) on its pitch circle, T_sun = T_L / (1 + z_r/z_s).
"""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

from gearcli.cli import cli

T_LOAD, Z_S, Z_R, N, M_N = 900.0, 21, 81, 3, 3.0
SCENE = f"""
[[stage]]
type = "planetary"
normal_module_mm = {M_N}
normal_pressure_angle_deg = 20
sun    = {{ teeth = {Z_S}, face_width_mm = 40, inertia_kg_m2 = 0.002 }}
planet = {{ teeth = 30, face_width_mm = 38, count = {N}, inertia_kg_m2 = 0.004, mass_kg = 1.6 }}
ring   = {{ teeth = {Z_R}, face_width_mm = 38 }}
carrier = {{ inertia_kg_m2 = 0.15 }}
[contact]
stiffness = 5e5
exponent = 1
damping_ratio = 0.05
transmission_error_um = [0, 5]
[input]
speed_rpm = 1450
ramp_s = 0.2
inertia_kg_m2 = 0.05
coupling_stiffness_Nm_rad = 4e4
coupling_damping_Nms_rad = 3
[load]
torque_Nm = {T_LOAD}
ramp_s = 0.2
inertia_kg_m2 = 30
coupling_stiffness_Nm_rad = 1e5
coupling_damping_Nms_rad = 20
[simulation]
duration_s = 0.8
steady = "periodic"
"""


def _periodic_summary(tmp_path) -> dict:
    scene = tmp_path / "planetary.toml"
    scene.write_text(SCENE)
    out = CliRunner().invoke(cli, ["-q", "simulate", str(scene), "--format", "json"])
    assert out.exit_code == 0, out.output
    return json.loads(out.stdout)["summary"]


def test_the_periodic_orbit_of_a_planetary_stage_shares_the_load_as_the_torque_balance_says(tmp_path):
    share = T_LOAD / (1.0 + Z_R / Z_S) / (N * Z_S * M_N / 2 / 1000)  # N: 1960.78 on the sun's pitch circle
    summary = _periodic_summary(tmp_path)
    steady = summary["steady"]
    assert steady["method"] == "shooting" and steady["converged"] and steady["residual"] <= 1.0
    stage = summary["stages"][0]
    means = [p["sun"]["tangential_N"]["mean"] for p in stage["planets"]]
    assert means == pytest.approx([share] * N, rel=1e-4)  # was +24439, -321602, +303045
    assert stage["tangential_N"]["mean"] == pytest.approx(share, rel=1e-4)
