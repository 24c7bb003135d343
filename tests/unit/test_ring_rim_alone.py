"""A ring gear is a rim: `ring.rim_thickness_mm` alone (no web) is its body.

ISO 6336-3:2006 rates an internal gear's root with the rim thickness s_R under it, Y_B = 1.15 ln(8.324 m_n/s_R) for
1.75 < s_R/m_n < 3.5 (in normal modules, where an external gear's Y_B takes s_R/h_t; before 2026-12-01 gearcli took
the ring's tooth depth h_t = (d_f - d_a)/2 here, so an 8 mm rim under m_n 3, s_R/h_t 1.19, was held at 1.79), and the ring's inertia is the annulus between its tip circle
and the rim's outside, J = rho pi b (D^4 - d_a^4)/32 with D = d_f + 2 s_R; its gear blank factor is the solid
blank's C_R = 1 (ISO 6336-1: no web). The external members' rule (a web needs its rim and a rim its web, the
webbed blank of C_R) was applied to the ring too, so a ring with its rim alone was exit 2 asking for a web it does
not have. A web without its rim stays refused.
"""

from __future__ import annotations

import json
import math

from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

M_N, Z_S, Z_P, Z_R, B = 3.0, 21, 30, 81, 38.0
RHO = 7850.0


def scene(ring_body: str) -> str:
    return f"""
[materials]
case = {{ density_kg_m3 = {RHO}, youngs_modulus_MPa = 206000, poisson_ratio = 0.3, treatment = "case_carburized", contact_fatigue_limit_MPa = 1500, bending_fatigue_limit_MPa = 460 }}
[[stage]]
type = "planetary"
normal_module_mm = {M_N}
accuracy_grade = 6
sun = {{ teeth = {Z_S}, face_width_mm = 40, material = "case", flank_roughness_Rz_um = 3, root_roughness_Rz_um = 10 }}
planet = {{ teeth = {Z_P}, face_width_mm = {B}, count = 3, material = "case", flank_roughness_Rz_um = 3, root_roughness_Rz_um = 10 }}
ring = {{ teeth = {Z_R}, face_width_mm = {B}, material = "case", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 12{ring_body} }}
fixed = "ring"
input = "sun"
[lubricant]
viscosity_40C_mm2_s = 220
[input]
speed_rpm = 1480
[load]
torque_Nm = 3000
[rating]
required_life_h = 20000
"""


def run(tmp_path, text: str):
    path = tmp_path / "ring.toml"
    path.write_text(text)
    return CliRunner().invoke(cli, ["design", str(path), "--format", "json", "-q"])


def test_a_rim_alone_sets_the_rings_y_b_and_inertia(tmp_path):
    s_r = 8.0  # 2.67 m_n, 1.19 h_t
    res = run(tmp_path, scene(f", rim_thickness_mm = {s_r}"))
    assert res.exit_code == 0, res.output
    st = json.loads(res.stdout)["stages"][0]
    d = M_N * Z_R  # spur, x = 0: the ring's tip d - 2 m, root d + 2 h_fP* m (profile A: 1.25)
    d_a, d_f = d - 2.0 * M_N, d + 2.0 * 1.25 * M_N
    h_t = (d_f - d_a) / 2.0
    assert 1.75 < s_r / M_N < 3.5 and s_r / h_t < 1.75
    assert_allclose(st["meshes"][1]["rating"]["gear"]["Y_B"], 1.15 * math.log(8.324 * M_N / s_r), rtol=1e-12)
    assert_allclose(st["meshes"][1]["rating"]["gear"]["Y_B"], 1.3091, atol=5e-5)  # 1.15 ln(3.1215) = 1.15 · 1.13831
    outer = d_f + 2.0 * s_r
    inertia = RHO * math.pi * B * ((outer * 1e-3) ** 4 - (d_a * 1e-3) ** 4) / 32.0 * 1e-3
    assert_allclose(st["ring"]["inertia_kg_m2"], inertia, rtol=1e-12)
    assert st["ring"]["gear_blank_factor"] == 1.0


def test_a_thick_rim_alone_has_y_b_one(tmp_path):
    res = run(tmp_path, scene(", rim_thickness_mm = 10.5"))  # s_R/m_n = 3.5: Y_B = 1 (s_R/h_t = 1.56)
    assert res.exit_code == 0, res.output
    assert json.loads(res.stdout)["stages"][0]["meshes"][1]["rating"]["gear"]["Y_B"] == 1.0


def test_a_web_without_its_rim_is_refused(tmp_path):
    res = run(tmp_path, scene(", web_thickness_mm = 38"))
    assert res.exit_code == 2
    assert "stage[0].ring" in res.output and "rim_thickness_mm" in res.output
    assert "Traceback" not in res.output
