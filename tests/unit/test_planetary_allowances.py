"""Tooth-thickness and tip allowances on a planetary stage's sun and planets (the sun–planet mesh, an external
pair: docs/planetary.md, "Tooth-thickness allowances"), by hand; the ring's own allowances and the planet–ring
mesh: tests/unit/test_ring_allowances.py.

The stage is configs/planetary_stage.toml (NREL 5 MW stage 1: spur, m_n 45, z 19/17/56, x 0.617/0.8021/−0.5013)
with A_sn = [−0.3, −0.5] mm on the sun and the planets and A_da = [0, −0.2] mm on the sun. At the nominal
centre distance the backlash has a closed form: inv α_w − inv α_wE = 2 tan α (Σx − Σx_E)/Σz = −ΣA_sn/(m Σz),
so j_t = m cos α / cos α_w · Σz (inv α_w − inv α_wE) = −ΣA_sn cos α / cos α_w and j_n = j_t cos α_w = −ΣA_sn cos α
(spur: β_b = 0)."""

from __future__ import annotations

import json
import math
from pathlib import Path

from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli
from gearcli.design import rating_root as rr

ROOT = Path(__file__).resolve().parents[2]
BASE = (ROOT / "configs" / "planetary_stage.toml").read_text()
M, ALPHA = 45.0, math.radians(20.0)
SUN_A, PLANET_A, SUN_TIP = (-0.3, -0.5), (-0.3, -0.5), (0.0, -0.2)


def _text(sun: bool = True, planet: bool = True) -> str:
    text = BASE
    if sun:
        text = text.replace("profile_shift = 0.617,", f"profile_shift = 0.617, tooth_thickness_allowance_mm = "
                            f"{list(SUN_A)}, tip_diameter_allowance_mm = {list(SUN_TIP)},")
    if planet:
        text = text.replace("profile_shift = 0.8021,", f"profile_shift = 0.8021, tooth_thickness_allowance_mm = "
                            f"{list(PLANET_A)},")
    return text


def _run(tmp_path, text: str, *args: str):
    path = tmp_path / "planetary.toml"
    path.write_text(text)
    return CliRunner().invoke(cli, ["design", str(path), "--format", "json", *args])


def _stage(tmp_path, text: str) -> dict:
    res = _run(tmp_path, text)
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)["stages"][0]


def test_generating_shifts_and_roots_by_hand(tmp_path):
    st = _stage(tmp_path, _text())
    two_m_tan = 2 * M * math.tan(ALPHA)  # 32.757318
    for member, x, a in (("sun", 0.617, SUN_A), ("planet", 0.8021, PLANET_A)):
        x_e = [x + a_s / two_m_tan for a_s in a]
        assert_allclose(st[member]["generating_profile_shift"], x_e, rtol=1e-12)
        d = st[member]["pitch_diameter_mm"]
        # d_f = d + 2 (x_E m_n − h_fP), h_fP = 1.25 m_n
        assert_allclose(st[member]["manufactured_root_diameter_mm"], [d + 2 * (xe * M - 1.25 * M) for xe in x_e],
                        rtol=1e-12)
    # sun: 0.617 − 0.3/32.757318 = 0.607842; 855 + 2 (0.607842 · 45 − 56.25) = 797.206 mm
    assert_allclose(st["sun"]["generating_profile_shift"][0], 0.607842, atol=5e-7)
    assert_allclose(st["sun"]["manufactured_root_diameter_mm"][0], 797.206, atol=5e-4)
    # the ring without an allowance of its own, in a stage whose planets have one: its nominal x and root (as a
    # parallel stage's member without the key)
    assert_allclose(st["ring"]["generating_profile_shift"], [-0.5013, -0.5013], rtol=0, atol=1e-15)
    assert_allclose(st["ring"]["manufactured_root_diameter_mm"], [st["ring"]["root_diameter_mm"]] * 2, rtol=1e-14)


def test_sun_planet_backlash_in_closed_form(tmp_path):
    st = _stage(tmp_path, _text())
    mesh = st["meshes"][0]
    assert mesh["name"] == "sun_planet"
    alpha_w = math.radians(mesh["working_pressure_angle_deg"])
    thinnest, thickest = -(SUN_A[1] + PLANET_A[1]), -(SUN_A[0] + PLANET_A[0])  # 1.0 and 0.6 mm
    assert_allclose(mesh["backlash_normal_mm"], [thinnest * math.cos(ALPHA), thickest * math.cos(ALPHA)], rtol=1e-9)
    assert_allclose(mesh["backlash_circumferential_mm"],
                    [thinnest * math.cos(ALPHA) / math.cos(alpha_w), thickest * math.cos(ALPHA) / math.cos(alpha_w)],
                    rtol=1e-9)


def test_contact_ratio_with_the_sun_tip_allowance(tmp_path):
    """ε_α = (√(r_a1² − r_b1²) + √(r_a2² − r_b2²) − a_w sin α_w) / p_bt with the sun's tips d_a + A_da (e: 0,
    m: −0.1, i: −0.2 mm), the planet's nominal, at a_w (no centre-distance allowance on a planetary stage)."""
    st = _stage(tmp_path, _text())
    mesh, sun, planet = st["meshes"][0], st["sun"], st["planet"]
    alpha_w = math.radians(mesh["working_pressure_angle_deg"])

    def eps(tip_sun: float) -> float:
        path = (math.sqrt((tip_sun / 2) ** 2 - (sun["base_diameter_mm"] / 2) ** 2)
                + math.sqrt((planet["tip_diameter_mm"] / 2) ** 2 - (planet["base_diameter_mm"] / 2) ** 2)
                - mesh["center_distance_mm"] * math.sin(alpha_w))
        return path / mesh["transverse_base_pitch_mm"]

    assert_allclose(mesh["contact_ratio_transverse_with_allowances"],
                    [eps(sun["tip_diameter_mm"] + t) for t in (0.0, -0.1, -0.2)], rtol=1e-9)
    assert_allclose(mesh["contact_ratio_transverse_with_allowances"][0], mesh["contact_ratio_transverse"], rtol=1e-12)


def test_roots_rated_at_the_generating_shift(tmp_path):
    """[rating] root_profile_shift (default "lower"): the sun's and the planet's roots at x_E,i in the sun mesh, the
    planet's root in the ring mesh too; "nominal" gives the file without allowances' root figures."""
    st = _stage(tmp_path, _text())
    sun, planet = st["sun"], st["planet"]
    ring_mesh = st["meshes"][1]
    eps_sp, eps_pr = st["meshes"][0]["contact_ratio_transverse"], ring_mesh["contact_ratio_transverse"]
    rack = (1.25, 0.38)

    def y_f(g: dict, eps: float) -> float:
        return rr.tooth_form(g["teeth"], M, ALPHA, 0.0, 0.0, g["generating_profile_shift"][1], g["tip_diameter_mm"],
                             g["pitch_diameter_mm"], eps, rack)["Y_F"]

    rating = st["meshes"][0]["rating"]
    assert_allclose([rating["pinion"]["Y_F"], rating["gear"]["Y_F"]], [y_f(sun, eps_sp), y_f(planet, eps_sp)],
                    rtol=1e-12)
    assert_allclose(ring_mesh["rating"]["pinion"]["Y_F"], y_f(planet, eps_pr), rtol=1e-12)
    nominal = _stage(tmp_path, _text().replace("[rating]", '[rating]\nroot_profile_shift = "nominal"'))
    plain = _stage(tmp_path, BASE)
    for mesh in (0, 1):
        for member in ("pinion", "gear"):
            assert (nominal["meshes"][mesh]["rating"][member]["Y_F"]
                    == plain["meshes"][mesh]["rating"][member]["Y_F"])


def test_without_the_keys_nothing_is_added(tmp_path):
    st = _stage(tmp_path, BASE)
    for member in ("sun", "planet", "ring"):
        assert "generating_profile_shift" not in st[member]
    assert not any("allowances" in k or k.startswith("backlash_c") for k in st["meshes"][0])


def test_the_ring_refuses_a_tip_allowance_naming_the_key(tmp_path):
    """Its tooth-thickness allowance is taken (tests/unit/test_ring_allowances.py), its tip allowance not yet."""
    key = "tip_diameter_allowance_mm"
    text = BASE.replace("profile_shift = -0.5013,", f"profile_shift = -0.5013, {key} = [-0.1, -0.2],")
    res = _run(tmp_path, text)
    assert res.exit_code == 2
    assert f"stage[0].ring.{key}" in res.output and "internal gear" in res.output
    assert "Traceback" not in res.output


def test_a_planetary_stage_takes_no_centre_distance_allowance(tmp_path):
    res = _run(tmp_path, BASE.replace('type = "planetary"', 'type = "planetary"\n'
                                      "center_distance_allowance_mm = [0.1, -0.1]"))
    assert res.exit_code == 2 and "center_distance_allowance_mm" in res.output
