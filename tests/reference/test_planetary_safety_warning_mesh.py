"""A planetary stage's safety warnings say which mesh they rate: `mesh` "sun_planet" or "planet_ring".

The planet–ring mesh's `pitting_safety_low` / `bending_safety_low` carried `mesh` "planet_ring" (member "planet" or
"ring"), but the sun–planet mesh's carried no `mesh` (member "pinion"/"gear", the pair's), so a program reading the
JSON warnings could not tell the planet's sun-side root failing (member "gear") from a parallel stage's wheel, nor
find it beside the planet's ring-side warning, while every other sun–planet warning (`contact_ratio`,
`iso6336_resonance`, ...) carries `mesh` "sun_planet" (docs/output.md).

Scene: a spur star stage 40/17/74 (carrier held, three planets, m_n 3, x = 0, b = 30 mm), 4000 N·m on the ring:
the sun mesh's nominal contact stress by hand, σ_H0 = Z_H Z_E Z_ε √(F_t/(d1 b) (u + 1)/u) with the planet as
ISO's wheel 1 (17 < 40 teeth), and every warning's S the rating's of the member and mesh it names.
"""

from __future__ import annotations

import json
import math

from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

CASE = ('case = { density_kg_m3 = 7830, youngs_modulus_MPa = 206000, poisson_ratio = 0.3, treatment = "case_carburized", '
        'contact_fatigue_limit_MPa = 1500, bending_fatigue_limit_MPa = 430 }')
ROUGH = 'material = "case", flank_roughness_Rz_um = 2, root_roughness_Rz_um = 8'
SCENE = f"""
lubricant = {{ viscosity_40C_mm2_s = 100 }}
input = {{ speed_rpm = 1000 }}
load = {{ torque_Nm = 4000 }}
rating = {{ required_life_h = 10000 }}
[materials]
{CASE}
[[stage]]
type = "planetary"
normal_module_mm = 3
accuracy_grade = 5
sun = {{ teeth = 40, face_width_mm = 30, {ROUGH} }}
planet = {{ teeth = 17, face_width_mm = 30, count = 3, {ROUGH} }}
ring = {{ teeth = 74, face_width_mm = 30, {ROUGH} }}
fixed = "carrier"
input = "sun"
"""


def test_sun_planet_safety_warnings_name_their_mesh(tmp_path):
    path = tmp_path / "star.toml"
    path.write_text(SCENE)
    res = CliRunner().invoke(cli, ["design", str(path), "--format", "json", "-q"])
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    meshes = {m["name"]: m for m in out["stages"][0]["meshes"]}
    # the sun mesh's nominal contact stress by hand: spur, x = 0, lossless; T_sun = T_ring z_s/z_r over 3 planets
    m, alpha, b, u = 3.0, math.radians(20.0), 30.0, 40 / 17
    roll = [math.sqrt((z * m / 2 + m) ** 2 - (z * m * math.cos(alpha) / 2) ** 2) for z in (40, 17)]
    eps = (sum(roll) - 57 * m / 2 * math.sin(alpha)) / (math.pi * m * math.cos(alpha))  # ε_α 1.65
    f_t = 4000e3 * 40 / 74 / 3 / (40 * m / 2)  # N per planet at the sun's reference circle
    z_h_z_e = math.sqrt(2.0 / (math.cos(alpha) ** 2 * math.tan(alpha))) * math.sqrt(206000.0 / (2 * math.pi * 0.91))
    sigma_h0 = z_h_z_e * math.sqrt((4 - eps) / 3) * math.sqrt(f_t / (17 * m * b) * (u + 1) / u)  # d1: the planet
    assert_allclose(meshes["sun_planet"]["rating"]["sigma_H0_MPa"], sigma_h0, rtol=1e-9)
    low = [w for w in out["warnings"] if w["code"] in ("pitting_safety_low", "bending_safety_low")]
    tags = {(w["mesh"], w["member"], w["mode"]) for w in low}
    assert ("sun_planet", "pinion", "pitting") in tags and ("planet_ring", "planet", "bending") in tags, tags
    key = {"pinion": "pinion", "gear": "gear", "planet": "pinion", "ring": "gear"}
    for w in low:
        member = meshes[w["mesh"]]["rating"][key[w["member"]]]
        assert w["S"] == member["S_H" if w["mode"] == "pitting" else "S_F"] < w["S_min"]


def test_a_ring_in_its_static_range_is_said(tmp_path):
    """The same star over 0.9 h: the ring meets 3 planets per turn at n_r = 1000 · 40/74 rpm, N_L = 60 · 3 · 540.54 ·
    0.9 = 87,568 ≤ 10⁵, the first node of its Z_NT curve (case-carburized), where the sun's 60 · 3 · 1000 · 0.9 =
    162,000 and the planet's 60 · (1000 · 40/17) · 0.9 = 127,059 lie beyond: a `rating_out_of_range` (`quantity`
    "load_cycles") names the ring (`mesh` "planet_ring") and no other member. The ring's was never checked, so a slow
    ring (a slewing drive's) in the static range of its S-N curve was rated without a word."""
    path = tmp_path / "star.toml"
    path.write_text(SCENE.replace("required_life_h = 10000", "required_life_h = 0.9"))
    res = CliRunner().invoke(cli, ["design", str(path), "--format", "json", "-q"])
    assert res.exit_code == 0, res.output
    found = [w for w in json.loads(res.stdout)["warnings"] if w.get("quantity") == "load_cycles"]
    assert [(w["member"], w["mesh"]) for w in found] == [("ring", "planet_ring")], found
    assert_allclose(found[0]["value"], 60 * 3 * 1000 * 40 / 74 * 0.9, rtol=1e-12)
    assert "stage 1 ring: N_L = 8.76e+04 load cycles lie in the static range of Z_NT" in found[0]["message"]


def test_a_thin_sun_rim_is_said_on_the_sun_planet_mesh(tmp_path):
    """A 2 mm rim under the sun's teeth (x = 0: h_t = 2.25 m_n = 6.75 mm, s_R/h_t = 0.296 < 0.5): Y_B held at
    1.6 ln(2.242/0.5) = 2.40082 and a `rim_ratio` warning naming the sun, `mesh` "sun_planet" (the ring's own range
    warnings carry "planet_ring"; the sun mesh's carried no mesh)."""
    path = tmp_path / "star.toml"
    sun = "sun = { teeth = 40, face_width_mm = 30,"
    path.write_text(SCENE.replace(sun, sun + " rim_thickness_mm = 2, web_thickness_mm = 30,"))
    res = CliRunner().invoke(cli, ["design", str(path), "--format", "json", "-q"])
    assert res.exit_code == 0, res.output
    out = json.loads(res.stdout)
    found = [w for w in out["warnings"] if w.get("quantity") == "rim_ratio"]
    assert [(w["member"], w["mesh"]) for w in found] == [("pinion", "sun_planet")], found
    assert_allclose(found[0]["value"], 2.0 / 6.75, rtol=1e-12)
    assert found[0]["message"].startswith("stage 1 sun: rim s_R/h_t = 0.296 below 0.5")
    assert_allclose(out["stages"][0]["meshes"][0]["rating"]["pinion"]["Y_B"], 1.6 * math.log(2.242 / 0.5), rtol=1e-12)
