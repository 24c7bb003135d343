"""A planetary stage's planet modes in closed form (trial tr15c): a spur stage 21/30/81, 3 planets, ring held. In
the N - 1 planet modes the sun and the carrier stand still and each planet swings between its sun and ring mesh
(the same linear stiffness k along both lines of action): w^2 = 2 k r_bp^2 / J_p. Each mesh's viscous c =
2 zeta sqrt(k m_e), m_e = 1 / sum r_j^2 / J_j over the bodies that move its line of action (docs/physics.md): with
the sun held by the speed drive and the ring held, both meshes join the planet and the carrier (r_c cos a_w, its
inertia with the planets' N m_p r_c^2). In a scene with an input coupling the sun's r_bs^2 / J_s joins too; the
two-body formula alone (planet only) would give sqrt(2) zeta = 7.071 %. The mode's
damping ratio is then (c_s + c_r) r_bp^2 / (2 J_p w)."""

from __future__ import annotations

import json
import math

import pytest
from click.testing import CliRunner

from gearcli.cli import cli

K, ZETA, J_S, J_P, M_P, J_C, N = 5e8, 0.05, 0.002, 0.004, 1.6, 0.15, 3
SCENE = f"""
[[stage]]
type = "planetary"
normal_module_mm = 3
normal_pressure_angle_deg = 20
sun    = {{ teeth = 21, face_width_mm = 40, inertia_kg_m2 = {J_S} }}
planet = {{ teeth = 30, face_width_mm = 38, count = {N}, inertia_kg_m2 = {J_P}, mass_kg = {M_P} }}
ring   = {{ teeth = 81, face_width_mm = 38 }}
carrier = {{ inertia_kg_m2 = {J_C} }}
[contact]
stiffness = {K / 1000}
exponent = 1
damping_ratio = {ZETA}
[input]
speed_rpm = 1450
[load]
torque_Nm = 900
"""


def test_planet_modes_frequency_and_damping_ratio_in_closed_form(tmp_path):
    cos_a = math.cos(math.radians(20))
    r_p = 30 * 3 / 2 * cos_a / 1e3  # the planet's base radius, m
    r_c = (21 + 30) * 3 / 2 / 1e3  # zero shifts: the working angle is 20 deg on both meshes
    j_c = J_C + N * M_P * r_c**2
    carrier = (r_c * cos_a) ** 2 / j_c
    # the speed drive holds the sun (infinitely heavy), the ring is held: both meshes join planet and carrier
    m_sun = m_ring = 1.0 / (r_p**2 / J_P + carrier)
    w = math.sqrt(2.0 * K * r_p**2 / J_P)
    c = 2.0 * ZETA * (math.sqrt(K * m_sun) + math.sqrt(K * m_ring))
    zeta_mode = c * r_p**2 / (2.0 * J_P * w)
    path = tmp_path / "planetary.toml"
    path.write_text(SCENE)
    res = CliRunner().invoke(cli, ["-q", "modes", str(path), "--format", "json"])
    assert res.exit_code == 0, res.output
    modes = json.loads(res.stdout)["boundaries"]["clamped_input"]
    planet = [m for m in modes if m["frequency_Hz"] == pytest.approx(w / (2 * math.pi), rel=1e-6)
              and abs(m["shape"]["shaft 2"]) < 1e-9]  # the carrier (shaft 2) still; the sun is held by the drive
    assert len(planet) >= N - 1  # the repeated planet modes
    for m in planet:
        assert m["damping_ratio"] == pytest.approx(zeta_mode, rel=1e-4)  # 6.852 %; without the carrier term 7.071 %
