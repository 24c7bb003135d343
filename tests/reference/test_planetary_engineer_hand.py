"""Planetary trains the shipped configs do not have, checked by hand (a drivetrain engineer's own scenes).

Scene A: a simple spur planetary, sun 24 / planets 36 / ring 96 (z_r = z_s + 2 z_p: no profile shift needed),
m_n 4, b 40, steel, sun driven at 1500 rpm, ring held, carrier out, 5000 N·m on the carrier; N = 3 planets unless
a test says otherwise ((z_s + z_r)/N = 120/N whole for N = 1 ... 6; the tips clash from N = 5).

Hand formulas (ISO 21771, ISO 6336-1, Willis) written out in each test; no expected number is taken from the code.
"""

from __future__ import annotations

import math

import pytest
from numpy.testing import assert_allclose

from tests.life.scenes import design_of as _design_of

def design_of(toml: str, overrides: tuple[str, ...] = ()):
    return _design_of(toml, overrides)[1]


Z_S, Z_P, Z_R, M_N, B = 24, 36, 96, 4.0, 40.0
N_IN, T_OUT = 1500.0, 5000.0


def scene_a(count: int = 3, planet: str = "", bearings: str = "", sun: str = "") -> str:
    return f"""
[materials.steel]
density_kg_m3 = 7850
youngs_modulus_MPa = 206000
poisson_ratio = 0.3

[[stage]]
type = "planetary"
normal_module_mm = {M_N}
sun    = {{ teeth = {Z_S}, face_width_mm = {B}, material = "steel"{sun} }}
planet = {{ teeth = {Z_P}, face_width_mm = {B}, count = {count}, material = "steel"{planet} }}
ring   = {{ teeth = {Z_R}, face_width_mm = {B}, material = "steel" }}
fixed = "ring"
input = "sun"

[input]
speed_rpm = {N_IN}

[load]
torque_Nm = {T_OUT}
{bearings}
"""


SUN_BEARINGS = """
[[bearing]]
shaft = 1
position_mm = 0
dynamic_load_rating_kN = 100
kind = "ball"
locating = true

[[bearing]]
shaft = 1
position_mm = 200
dynamic_load_rating_kN = 100
kind = "ball"
"""


# ------------------------------------------------------------------------ unequal spacing: the sun's bearings
@pytest.mark.parametrize("angles", [(0.0, 120.0), (60.0, 180.0), (0.0, 117.0)])
def test_unequally_spaced_planets_load_the_sun_bearings_with_their_resultant(angles):
    """Two planets declared at psi_1, psi_2 (whole multiples of 360/(z_s + z_r) = 3 deg apart): each pushes the sun
    with its in-plane mesh force F_t / cos(alpha) (tangential F_t = T_sun / (N r_s), radial F_t tan(alpha)) at its
    own angle, so the sun carries the resultant 2 (F_t / cos alpha) cos((psi_2 - psi_1)/2), shared equally by two
    bearings symmetric about the sun's plane. Equal spacing (psi = 0, 180) would cancel it; the statics placed the
    planets at 360 j/N whatever angles_deg declared and gave 0 N."""
    extra = f", angles_deg = [{angles[0]}, {angles[1]}], axial_position_mm = 100"
    d = design_of(scene_a(2, planet=extra, sun=", axial_position_mm = 100", bearings=SUN_BEARINGS))
    t_sun = T_OUT / (1.0 + Z_R / Z_S)  # N·m, ring held
    f_t = t_sun * 1e3 / (2 * 0.5 * Z_S * M_N)  # N per planet, r_s = z_s m / 2
    in_plane = f_t / math.cos(math.radians(20.0))
    resultant = 2.0 * in_plane * math.cos(math.radians(angles[1] - angles[0]) / 2.0)
    radial = [b.radial_N for b in d.bearings]
    assert_allclose(radial, [resultant / 2.0] * 2, rtol=1e-12)  # closed form; round-off only
    # the resultant turns with the planets: its direction rotated by psi_1 from the (0, 120) case's
    y, z = sum(b.radial_y_N for b in d.bearings), sum(b.radial_z_N for b in d.bearings)
    ref = design_of(scene_a(2, planet=", angles_deg = [0, 120], axial_position_mm = 100",
                            sun=", axial_position_mm = 100", bearings=SUN_BEARINGS))
    y0, z0 = sum(b.radial_y_N for b in ref.bearings), sum(b.radial_z_N for b in ref.bearings)
    half = math.radians(angles[1] - angles[0]) / 2.0 - math.radians(60.0)  # the bisector moves with the gap too
    turn = math.radians(angles[0]) + half
    scale = math.cos(math.radians(angles[1] - angles[0]) / 2.0) / math.cos(math.radians(60.0))
    assert_allclose([y, z], [scale * (y0 * math.cos(turn) - z0 * math.sin(turn)),
                             scale * (y0 * math.sin(turn) + z0 * math.cos(turn))], rtol=1e-9, atol=1e-6)


def test_equally_spaced_planets_declared_or_implied_leave_the_sun_unloaded():
    """Three planets at 0/120/240 (declared, or implied by equal spacing) and two at 0/180: no net radial force."""
    for count, extra in ((3, ", angles_deg = [0, 120, 240]"), (3, ""), (2, ", angles_deg = [0, 180]")):
        d = design_of(scene_a(count, planet=extra + ", axial_position_mm = 100", sun=", axial_position_mm = 100",
                              bearings=SUN_BEARINGS))
        assert [b.radial_N for b in d.bearings] == [0.0, 0.0]


# ------------------------------------------------------------------------------------------ hostile inputs
def _cli(tmp_path, text: str, *args: str):
    from click.testing import CliRunner

    from gearcli.cli import cli

    path = tmp_path / "hostile.toml"
    path.write_text(text, encoding="utf-8")
    return path, CliRunner().invoke(cli, ["design", str(path), *args], catch_exceptions=False)


@pytest.mark.parametrize(("old", "new", "key", "says"), [
    # a ring with fewer teeth than the sun: the planets cannot fit (z_r must be about z_s + 2 z_p = 96)
    (f"teeth = {Z_R},", "teeth = 20,", "stage[0]", "ring.teeth (20)"),
    (f"count = 3,", "count = -3,", "stage[0].planet.count", "must be ≥ 1"),
    # five planets: (24 + 96)/5 = 24 spaces them, but 2 a sin 36° = 141.07 mm < d_a = (36 + 2) 4 = 152 mm
    (f"count = 3,", "count = 5,", "stage[0].planet.count", "141.0685 mm"),
    # seven: 120/7 = 17.14 is not whole
    (f"count = 3,", "count = 7,", "stage[0].planet.count", "(24 + 96)/7"),
    # two planets declared 30° apart: 2 a sin 15° = 62.1166 mm < 152 mm; the declared angles place them
    (f"count = 3,", "count = 2, angles_deg = [0, 30],", "stage[0].planet.angles_deg", "62.1166 mm"),
])
def test_a_planetary_that_cannot_be_built_is_exit_2_naming_file_and_key(tmp_path, old, new, key, says):
    path, res = _cli(tmp_path, scene_a().replace(old, new, 1))
    assert res.exit_code == 2, res.stderr
    assert f"{path.name}: {key}" in res.stderr and says in res.stderr
    assert "Traceback" not in res.stderr


def test_helical_planetary_hands_external_pair_and_ring(tmp_path):
    """The sun and planet (an external pair) need opposite hands; the ring (internal) the planet's."""
    helical = scene_a().replace("normal_module_mm = 4", "normal_module_mm = 4\nhelix_angle_deg = 15")
    same = helical.replace(f"teeth = {Z_S},", f'teeth = {Z_S}, hand = "left",').replace(
        f"teeth = {Z_P},", f'teeth = {Z_P}, hand = "left",')
    path, res = _cli(tmp_path, same)
    assert res.exit_code == 2 and f"{path.name}: stage[0].planet.hand" in res.stderr and "Traceback" not in res.stderr
    ring = same.replace(f'teeth = {Z_P}, hand = "left",', f'teeth = {Z_P}, hand = "right",').replace(
        f"teeth = {Z_R},", f'teeth = {Z_R}, hand = "left",')
    path, res = _cli(tmp_path, ring)
    assert res.exit_code == 2 and f"{path.name}: stage[0].ring.hand" in res.stderr and "Traceback" not in res.stderr
    path, res = _cli(tmp_path, ring.replace(f'teeth = {Z_R}, hand = "left",', f'teeth = {Z_R}, hand = "right",'))
    assert res.exit_code == 0, res.stderr
