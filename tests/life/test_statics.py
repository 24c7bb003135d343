"""Shaft statics against hand calculations: the lever rule with the axial force's couple F_a r_w.

Each expected value is written out the way one would on paper: the force components from the textbook rules
(the driven gear's tangential force points the way its teeth move at the mesh, the driver's the other way;
the radial forces push the wheels apart; the axial force from the screw rule), then moments about one
bearing. None of it calls the code's vector statics.
"""

from __future__ import annotations

import math

import pytest
from numpy.testing import assert_allclose

from gearcli.design.shafts import basic_life_Mrev, equivalent_load_N, life_hours, spectrum_equivalent_load_N
from gearcli.errors import DesignError
from tests.life.scenes import COUNTERSHAFT, ONE_STAGE, design_of

RTOL = 1e-12  # the same arithmetic in another order


def _pitch_forces(torque_Nmm: float, pitch_radius_mm: float, alpha_n_deg: float, beta_deg: float):
    """F_t, F_r, F_a at the pitch circle (x = 0: working = reference pitch circle)."""
    a_t = math.atan(math.tan(math.radians(alpha_n_deg)) / math.cos(math.radians(beta_deg)))
    f_t = torque_Nmm / pitch_radius_mm
    return f_t, f_t * math.tan(a_t), f_t * math.tan(math.radians(beta_deg))


def test_single_helical_gear_between_two_bearings():
    """Gear (z = 60, m_n = 4, beta = 15 deg) at x = 70 mm on a shaft with bearings at 0 (locating) and 200 mm.

    Frame: the pinion shaft on the axis, the gear shaft along +y (center angle 0), input cw (positive about +x),
    so the gear turns ccw. Its teeth at the mesh (on its -y side) move along +z: F_t on the gear is +z.
    The radial force pushes the gear away from the pinion: +y. Axial: the driving pinion is a left-hand screw
    turned positively; a left-hand screw advances along -x, and the nut (the gear) pulls the screw the way it
    advances (a tightened bolt is in tension), so the pinion is pushed along -x and the gear along +x.
    The axial force acts at the pitch point, r_w off the axis on the -y side: a couple F_a r_w about +z.
    """
    cfg, d = design_of(ONE_STAGE)
    r_w = 0.5 * 60 * 4 / math.cos(math.radians(15))
    f_t, f_r, f_a = _pitch_forces(600e3, r_w, 20, 15)  # the gear carries the output torque 600 N·m
    a, span = 70.0, 200.0
    # z: the lever rule alone
    rb_z = -f_t * a / span
    ra_z = -f_t * (span - a) / span
    # y: F_r at the axis and the couple of F_a (at y = -r_w, along +x): M_z = a F_r + r_w F_a about A
    rb_y = -(f_r * a + f_a * r_w) / span
    ra_y = -f_r - rb_y
    a_res, b_res = d.bearings
    assert_allclose([a_res.radial_y_N, a_res.radial_z_N, a_res.axial_N], [ra_y, ra_z, -f_a], rtol=RTOL)
    assert_allclose([b_res.radial_y_N, b_res.radial_z_N, b_res.axial_N], [rb_y, rb_z, 0.0], rtol=RTOL, atol=1e-9)
    assert_allclose(a_res.radial_N, math.hypot(ra_y, ra_z), rtol=RTOL)
    # the couple moves load from one bearing to the other: without it the y reactions would split by the lever
    assert abs(rb_y) > f_r * a / span


def test_countershaft_with_two_gears_at_an_angle():
    """Shaft 2 carries gear 1 (x = 50) and pinion 2 (x = 180); bearings at 0 and 240 (locating).

    Input ccw, so shaft 2 turns cw (positive about +x). Stage 1's line of centres is +y (shaft 2 above
    shaft 1); stage 2's is at 90 deg, i.e. +z (shaft 3 beside shaft 2).
    Gear 1 meshes on its -y side; turning positively, a point at -y moves along x X (-y) = -z: F_t1 on the
    driven gear is -z, its radial force +y (away from pinion 1). Pinion 1 is a right-hand screw turned
    negatively (ccw): it advances along -x, so it is pulled -x and gear 1 pushed +x.
    Pinion 2 meshes on its +z side; a point at +z turning positively moves along x X z = -y: the driver's F_t2
    opposes it, +y. Its radial force points to its own axis, -z. Pinion 2 is a left-hand screw turned
    positively: it advances along -x and is pulled that way: -x.
    Couples: gear 1's F_a1 at (y = -r_w2) gives M_z = +r F_a1; pinion 2's axial force -F_a2 at z = +r_w3
    gives M = (0, 0, r) X (-F_a2, 0, 0) = (0, -r F_a2, 0).
    """
    cfg, d = design_of(COUNTERSHAFT)
    t2 = d.stages[0].gear.torque_Nmm  # shaft 2's torque: gear 1 receives it, pinion 2 passes it on
    r_g1 = 0.5 * 57 * 3 / math.cos(math.radians(12))
    r_p2 = 0.5 * 17 * 4 / math.cos(math.radians(10))
    f_t1, f_r1, f_a1 = _pitch_forces(t2, r_g1, 20, 12)
    f_t2, f_r2, f_a2 = _pitch_forces(t2, r_p2, 20, 10)
    x1, x2, span = 50.0, 180.0, 240.0
    fy = [(x1, f_r1), (x2, f_t2)]  # (position, force along y)
    fz = [(x1, -f_t1), (x2, -f_r2)]
    my = -r_p2 * f_a2  # the couples about A
    mz = r_g1 * f_a1
    # moments about A: M_z = sum x F_y + couples_z + span R_By = 0;  M_y = -sum x F_z + couples_y - span R_Bz = 0
    rb_y = -(sum(x * f for x, f in fy) + mz) / span
    rb_z = (-sum(x * f for x, f in fz) + my) / span
    ra_y = -sum(f for _, f in fy) - rb_y
    ra_z = -sum(f for _, f in fz) - rb_z
    axial = -(f_a1 - f_a2)  # gear 1 pushed +x, pinion 2 pulled -x; the locating bearing (B) balances them
    a_res, b_res = d.bearings
    assert_allclose([a_res.radial_y_N, a_res.radial_z_N, a_res.axial_N], [ra_y, ra_z, 0.0], rtol=RTOL, atol=1e-9)
    assert_allclose([b_res.radial_y_N, b_res.radial_z_N, b_res.axial_N], [rb_y, rb_z, axial], rtol=RTOL)


def test_rotation_reverses_tangential_and_axial_but_not_radial():
    """Turning the input the other way reverses F_t and F_a on every gear; the radial force still separates."""
    _, cw = design_of(ONE_STAGE)
    _, ccw = design_of(ONE_STAGE, ("input.rotation=ccw",))
    for a, b in zip(cw.bearings, ccw.bearings, strict=True):
        assert_allclose([b.radial_z_N, b.axial_N], [-a.radial_z_N, -a.axial_N], rtol=RTOL, atol=1e-9)
    # y: F_r keeps its sign, the couple F_a r_w flips
    _, spur_cw = design_of(ONE_STAGE, ("stage.0.helix_angle_deg=0",))
    _, spur_ccw = design_of(ONE_STAGE, ("stage.0.helix_angle_deg=0", "input.rotation=ccw"))
    assert_allclose([b.radial_y_N for b in spur_ccw.bearings], [b.radial_y_N for b in spur_cw.bearings], rtol=RTOL)


def test_iso281_textbook_examples():
    """L10 = (C/P)^p: C/P = 7 for a ball bearing gives 7^3 = 343 million revolutions; a roller bearing at
    C/P = 10 gives 10^(10/3) = 2154.4; at 1000 rpm 343e6 rev last 343e6 / 60e3 = 5716.7 h."""
    assert_allclose(basic_life_Mrev(7.0, 1.0, "ball"), 343.0, rtol=1e-14)
    assert_allclose(basic_life_Mrev(100e3, 10e3, "roller"), 2154.4347, rtol=1e-7)
    assert_allclose(life_hours(343.0, 1000.0), 5716.6667, rtol=1e-7)
    assert basic_life_Mrev(1.0, 0.0, "ball") is None and life_hours(1.0, 0.0) is None


def test_equivalent_load_switches_at_e():
    """P = F_r while F_a/F_r <= e; above it X F_r + Y F_a (deep-groove ball bearing, e = 0.3, X = 0.56, Y = 1.5)."""
    assert equivalent_load_N(1000.0, 300.0, 0.3, 0.56, 1.5) == 1000.0
    assert_allclose(equivalent_load_N(1000.0, 500.0, 0.3, 0.56, 1.5), 560.0 + 750.0, rtol=1e-15)
    assert_allclose(equivalent_load_N(1000.0, -500.0, 0.3, 0.56, 1.5), 1310.0, rtol=1e-15)  # magnitudes


def test_spectrum_equivalent_load_gives_miners_life():
    """Two levels: 1e6 rev at 2 kN and 3e6 rev at 1 kN on a ball bearing C = 20 kN. Miner over the levels'
    L10: life = total / sum(n_i / L_i); the equivalent load must give the same L10."""
    c, p, n = 20e3, [2e3, 1e3], [1e6, 3e6]
    lives = [(c / x) ** 3 * 1e6 for x in p]
    miner = sum(n) / sum(ni / li for ni, li in zip(n, lives, strict=True))
    eq = spectrum_equivalent_load_N(p, n, "ball")
    assert_allclose(eq, (sum(x**3 * ni for x, ni in zip(p, n, strict=True)) / 4e6) ** (1 / 3), rtol=1e-14)
    assert_allclose((c / eq) ** 3 * 1e6, miner, rtol=1e-12)


@pytest.mark.parametrize(("override", "key"), [
    ("bearing.1.shaft=1", "bearing[1].shaft"),  # shaft 1 (checked first) with one bearing
    ("bearing.1.locating=true", "bearing[0].locating"),
    ("bearing.1.position_mm=0", "bearing[1].position_mm"),
    ("bearing.1.shaft=7", "bearing[1].shaft"),
])
def test_bad_bearing_layout_names_the_key(override, key):
    with pytest.raises(DesignError) as exc:
        design_of(ONE_STAGE, (override,))
    assert exc.value.key == key


def test_a_supported_shaft_needs_axial_positions():
    text = ONE_STAGE.replace(', axial_position_mm = 70', '')
    with pytest.raises(DesignError) as exc:
        design_of(text)
    assert exc.value.key == "stage[0].gear.axial_position_mm"


def test_cli_bad_bearing_is_exit_2_naming_file_and_key(tmp_path):
    from click.testing import CliRunner

    from gearcli.cli import cli

    path = tmp_path / "shaft.toml"
    path.write_text(ONE_STAGE)
    res = CliRunner().invoke(cli, ["design", str(path), "--set", "bearing.1.locating=true"])
    assert res.exit_code == 2
    assert f"{path}: bearing[0].locating: shaft 2 has 2 locating bearings" in res.stderr
    assert "Traceback" not in res.stderr
