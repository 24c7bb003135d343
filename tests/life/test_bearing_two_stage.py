"""A two-stage helical reducer with bearings at both ends of every shaft, checked against shaft statics by
hand (docs/life.md "Bearings", docs/bearings.md):

- output torque 600 N m, ratios 3 and 3, efficiency 1: T_1 = 600/9 N m, T_2 = 600/3 N m;
- tooth forces at the pitch circle: F_t = 2 T / d, F_r = F_t tan(alpha_t), F_a = F_t tan(beta);
- a right-hand pinion turning cw (positive about +x) and driving is pushed along +x: its tooth line
  d = cos(beta) x + sin(beta) t, the normal force is perpendicular to d, so with -F_t t it has +F_t tan(beta) x;
- the intermediate shaft's gear 1 (left) and pinion 2 (left) push opposite ways: |F_a2 - F_a1| on its locating
  bearing (the textbook rule: equal hands on the countershaft cancel thrust);
- each shaft simply supported, the moments in the two planes about bearing A, the axial force's moment with the
  pitch radius as its arm; an overhung gear (outside the bearings' span) gives a negative reaction at A.
"""

from __future__ import annotations

import json
import math

from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

SCENE = """[materials.steel]
density_kg_m3 = 7850
youngs_modulus_MPa = 2.06e5
poisson_ratio = 0.3

[[stage]]
normal_module_mm = 2
normal_pressure_angle_deg = 20
helix_angle_deg = 15
pinion = { teeth = 20, face_width_mm = 30, material = "steel", hand = "right", axial_position_mm = 40 }
gear   = { teeth = 60, face_width_mm = 28, material = "steel", hand = "left", axial_position_mm = 40 }

[[stage]]
normal_module_mm = 3
normal_pressure_angle_deg = 20
helix_angle_deg = 12
center_angle_deg = 90
pinion = { teeth = 18, face_width_mm = 40, material = "steel", hand = "left", axial_position_mm = 110 }
gear   = { teeth = 54, face_width_mm = 38, material = "steel", hand = "right", axial_position_mm = 110 }

[input]
speed_rpm = 1450
rotation = "cw"

[load]
torque_Nm = 600

[[bearing]]
shaft = 1
position_mm = 0
dynamic_load_rating_kN = 20
kind = "ball"
locating = true
factors = { e = 0.3, X = 0.56, Y = 1.5 }
[[bearing]]
shaft = 1
position_mm = 100
dynamic_load_rating_kN = 20
kind = "ball"
[[bearing]]
shaft = 2
position_mm = 0
dynamic_load_rating_kN = 60
kind = "roller"
[[bearing]]
shaft = 2
position_mm = 150
dynamic_load_rating_kN = 60
kind = "roller"
locating = true
factors = { e = 0.4, X = 0.4, Y = 1.5 }
[[bearing]]
shaft = 3
position_mm = 60
dynamic_load_rating_kN = 90
kind = "roller"
locating = true
[[bearing]]
shaft = 3
position_mm = 160
dynamic_load_rating_kN = 90
kind = "roller"
"""


def _design(tmp_path, text=SCENE):
    path = tmp_path / "two.toml"
    path.write_text(text)
    res = CliRunner().invoke(cli, ["design", str(path), "--format", "json"])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout[res.stdout.index("{"):])


def _forces(m_n, z, beta_deg, torque_Nmm):
    """F_t, F_r, F_a and the pitch radius of a pinion (x = 0, alpha_n = 20 deg) by hand."""
    beta = math.radians(beta_deg)
    d = m_n * z / math.cos(beta)
    alpha_t = math.atan(math.tan(math.radians(20.0)) / math.cos(beta))
    f_t = 2.0 * torque_Nmm / d
    return f_t, f_t * math.tan(alpha_t), f_t * math.tan(beta), d / 2.0


def test_two_stage_reactions_by_hand(tmp_path):
    b = _design(tmp_path)["bearings"]
    t1, t2 = 600e3 / 9.0, 600e3 / 3.0
    ft1, fr1, fa1, r1 = _forces(2.0, 20, 15.0, t1)
    ft2, fr2, fa2, r3 = _forces(3.0, 18, 12.0, t2)
    r2 = 3.0 * r1  # gear 1: 60 teeth
    r4 = 3.0 * r3  # gear 2: 54 teeth
    # shaft 1 (bearings at 0 and 100, pinion 1 at 40, u = +y, t = +z): on the pinion (F_a1, -F_r1, -F_t1) at (40, r1, 0)
    rb_z = ft1 * 40.0 / 100.0
    rb_y = (fr1 * 40.0 + fa1 * r1) / 100.0
    expect = [(fr1 - rb_y, ft1 - rb_z, -fa1), (rb_y, rb_z, 0.0)]
    # shaft 2 (0 and 150): gear 1 (-F_a1, F_r1, F_t1) at (40, -r2, 0); pinion 2 (stage 2 u = +z, t = -y, s = -1,
    # left hand): (F_a2, -F_t2, -F_r2) at (110, 0, r3)
    m_y = -40.0 * ft1 + (r3 * fa2 + 110.0 * fr2)
    m_z = 40.0 * fr1 - r2 * fa1 - 110.0 * ft2
    rb_y, rb_z = -m_z / 150.0, m_y / 150.0
    expect += [(-(fr1 - ft2) - rb_y, -(ft1 - fr2) - rb_z, 0.0), (rb_y, rb_z, fa1 - fa2)]
    # shaft 3 (60 and 160): gear 2 (-F_a2, F_t2, F_r2) at (110, 0, -r4)
    rb_y = -50.0 * ft2 / 100.0
    rb_z = (r4 * fa2 - 50.0 * fr2) / 100.0
    expect += [(-ft2 - rb_y, -fr2 - rb_z, fa2), (rb_y, rb_z, 0.0)]
    for j, (y, z, a) in enumerate(expect):
        # rel 1e-9: the same closed-form statics; atol 1e-6 N for the zero axial reactions
        assert_allclose([b[j]["radial_y_N"], b[j]["radial_z_N"], b[j]["axial_N"]], [y, z, a], rtol=1e-9, atol=1e-6,
                        err_msg=f"bearing {j}")
        assert_allclose(b[j]["radial_N"], math.hypot(y, z), rtol=1e-9)


def test_two_stage_equivalent_load_and_life_by_hand(tmp_path):
    b = _design(tmp_path)["bearings"]
    # bearing 0: ball, F_a/F_r > e = 0.3 -> P = 0.56 F_r + 1.5 F_a, L10 = (C/P)^3, L10h at 1450 r/min
    fr, fa = b[0]["radial_N"], abs(b[0]["axial_N"])
    assert fa / fr > 0.3
    p = 0.56 * fr + 1.5 * fa
    assert_allclose(b[0]["equivalent_load_N"], p, rtol=1e-12)
    assert_allclose(b[0]["L10_Mrev"], (20e3 / p) ** 3, rtol=1e-12)
    assert_allclose(b[0]["L10_h"], (20e3 / p) ** 3 * 1e6 / (60.0 * 1450.0), rtol=1e-12)
    # bearing 3: roller, F_a/F_r < e = 0.4 -> P = F_r, p = 10/3, at 1450/3 r/min
    fr, fa = b[3]["radial_N"], abs(b[3]["axial_N"])
    assert fa / fr < 0.4
    assert_allclose(b[3]["equivalent_load_N"], fr, rtol=1e-12)
    assert_allclose(b[3]["L10_Mrev"], (60e3 / fr) ** (10.0 / 3.0), rtol=1e-12)
    assert_allclose(b[3]["L10_h"], (60e3 / fr) ** (10.0 / 3.0) * 1e6 / (60.0 * 1450.0 / 3.0), rtol=1e-12)


def test_overhung_pinion_reactions_by_hand(tmp_path):
    b = _design(tmp_path, SCENE.replace("position_mm = 100", "position_mm = 30", 1))["bearings"]
    ft1, fr1, fa1, r1 = _forces(2.0, 20, 15.0, 600e3 / 9.0)
    rb_y, rb_z = (fr1 * 40.0 + fa1 * r1) / 30.0, ft1 * 40.0 / 30.0
    assert_allclose([b[1]["radial_y_N"], b[1]["radial_z_N"]], [rb_y, rb_z], rtol=1e-9)
    # A pulls the other way (lever): F - R_B < 0
    assert_allclose([b[0]["radial_y_N"], b[0]["radial_z_N"]], [fr1 - rb_y, ft1 - rb_z], rtol=1e-9)
    assert b[0]["radial_z_N"] < 0.0


def test_axial_without_factors_warning_names_the_ratio(tmp_path):
    """Bearing 5 (shaft 3, locating, no factors) carries F_a2 = F_t2 tan 12 deg against F_r = 4472.9 N (by hand in
    test_two_stage_reactions_by_hand): the warning names F_a/F_r and says P takes F_r alone."""
    path = tmp_path / "two.toml"
    path.write_text(SCENE)
    res = CliRunner().invoke(cli, ["design", str(path), "--format", "json"])
    assert res.exit_code == 0
    b = json.loads(res.stdout[res.stdout.index("{"):])["bearings"][4]
    ft2, _, fa2, _ = _forces(3.0, 18, 12.0, 600e3 / 3.0)
    assert_allclose(b["axial_N"], fa2, rtol=1e-9)
    ratio = f"{fa2 / b['radial_N']:.3g}"
    assert f"bearing 5 carries an axial force (F_a/F_r = {ratio})" in res.stderr
    assert "equivalent load P takes F_r alone" in res.stderr
    assert_allclose(b["equivalent_load_N"], b["radial_N"], rtol=0)  # default X = 1, Y = 0
