"""A drivetrain engineer's own planetary trains, checked by hand (round 4's §11/§13 planetary re-test).

Scene S ("star then helical"): a spur planetary, sun 22 / planets 30 / ring 82 (z_r = z_s + 2 z_p, no profile
shift), m_n 4, b 40, steel, 4 planets ((22 + 82)/4 = 26), stage efficiency 0.97, the held member and the driven one
varied; then a helical parallel stage 19/57 (m_n 5, β 10°, η 0.98) to a 2000 N·m load; input 1500 rpm.

Scene P ("helical then planetary"): the reverse order, a parallel stage 20/50 driving the sun of a ring-held
planetary 24/36/96 with 3 planets.

Every expected number is a hand formula written out in the test (Willis, the textbook basic-efficiency relations,
F_t = T/(N r), ISO 21771 for the working pressure angle); none is taken from the code's output.
"""

from __future__ import annotations

import json
import math

import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

ZS, ZP, ZR, MN, B, N_PL = 22, 30, 82, 4.0, 40.0, 4
ETA1, ETA2 = 0.97, 0.98
Z1, Z2 = 19, 57
N_IN, T_OUT = 1500.0, 2000.0
U = ZR / ZS

def star(zs: int = ZS, zp: int = ZP, zr: int = ZR, count: int = N_PL, planet: str = "", fixed: str = "carrier",
         driven: str = "sun", eta: float = ETA1, contact: str = "", extra: str = "") -> str:
    """Scene S (module text), its planetary varied."""
    return f"""
title = "planetary then helical"
[materials.steel]
density_kg_m3 = 7850
youngs_modulus_MPa = 206000
poisson_ratio = 0.3
{contact}
[[stage]]
type = "planetary"
normal_module_mm = {MN}
normal_pressure_angle_deg = 20
efficiency = {eta}
sun    = {{ teeth = {zs}, face_width_mm = {B}, material = "steel" }}
planet = {{ teeth = {zp}, face_width_mm = {B}, count = {count}, material = "steel"{planet} }}
ring   = {{ teeth = {zr}, face_width_mm = {B}, material = "steel" }}
fixed = "{fixed}"
input = "{driven}"

[[stage]]
normal_module_mm = 5
helix_angle_deg = 10
efficiency = {ETA2}
pinion = {{ teeth = {Z1}, face_width_mm = 60, hand = "left", material = "steel" }}
gear   = {{ teeth = {Z2}, face_width_mm = 60, hand = "right", material = "steel" }}

[input]
speed_rpm = {N_IN}

[load]
torque_Nm = {T_OUT}
{extra}
"""


STAR = star()


def _run(*args: str):
    return CliRunner().invoke(cli, list(args), catch_exceptions=False)


def _write(tmp_path, text: str, name: str = "train.toml"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def design(tmp_path, text: str = STAR, *sets: str) -> dict:
    path = _write(tmp_path, text)
    res = _run("design", str(path), "--format", "json", *sum((["--set", s] for s in sets), []))
    assert res.exit_code == 0, res.stderr
    return json.loads(res.stdout)


def refused(tmp_path, text: str, *sets: str):
    path = _write(tmp_path, text)
    res = _run("design", str(path), "--format", "json", *sum((["--set", s] for s in sets), []))
    assert res.exit_code == 2, (res.exit_code, res.stderr)
    assert "Traceback" not in res.stderr and res.stdout == ""
    return path, res.stderr


# ---------------------------------------------------------------------------------------------------- angles
STEP = 360.0 / (ZS + ZR)  # 3.461538...°: where a planet meshes with both sun and ring


def test_declared_angles_typed_to_a_drawings_digits_are_accepted_and_taken_exactly(tmp_path):
    """Planet 4 at 80 steps = 276.923077°: typed as 276.923 (7.7e-5° off, 2e-5 of a step: 8e-5 mm on the 104 mm
    carrier circle) it is that position; the 1e-6° tolerance refused it, with a message whose 'nearest' (printed
    to 6 digits, 276.923°) was the value refused. The design reports (and the model phases) the exact angle."""
    doc = design(tmp_path, STAR, "stage[0].planet.angles_deg=[0,90,180,276.923]")
    st = doc["stages"][0]
    assert_allclose(st["planet_angles_deg"], [0.0, 26 * STEP, 52 * STEP, 80 * STEP], rtol=0, atol=1e-12)
    assert st["equal_spacing"] is False


def test_an_angle_between_the_assemblable_positions_names_them_to_digits_that_pass(tmp_path):
    path, err = refused(tmp_path, STAR, "stage[0].planet.angles_deg=[0,90,180,275]")
    # 275/3.4615 = 79.44 steps: the neighbours 79 and 80 steps
    lo, hi = 79 * STEP, 80 * STEP
    assert "stage[0].planet.angles_deg" in err and f"{lo:.6f}°" in err and f"{hi:.6f}°" in err
    # the printed neighbour, typed back, is accepted
    doc = design(tmp_path, STAR, f"stage[0].planet.angles_deg=[0,90,180,{hi:.6f}]")
    assert_allclose(doc["stages"][0]["planet_angles_deg"][3], hi, rtol=1e-14)


# ------------------------------------------------------------------------------------- what cannot be built
@pytest.mark.parametrize(("scene", "key", "says"), [
    # a ring too small: 70 teeth where 22 + 2 x 30 = 82 (the cross-key rule named only "stage[0]")
    (star(zr=70), "stage[0].ring.teeth", "ring.teeth (70)"),
    # the driven member held (named the key the file gives: input)
    (star(driven="carrier"), "stage[0].input", "same member ('carrier')"),
    (star(planet=", position_error_um = [1, 2]"), "stage[0].planet.position_error_um", "(4), got 2"),
    # spacing: (22 + 82)/5 = 20.8 is not whole
    (star(count=5), "stage[0].planet.count", "(22 + 82)/5 = 20.8"),
    # concentricity: ring 86 (spacing 108/4 = 27 fine): a_pr = (86 - 30) 4/2 = 112 mm, a_sp = (22 + 30) 4/2 = 104 mm
    (star(zr=86), "stage[0].ring.profile_shift", "a_w = 112.0000 mm"),
    # adjacency: 6 planets 32 teeth on ring 86 ((22 + 86)/6 = 18): a = 108 mm, 2 a sin 30° = 108 mm < d_a = 136 mm
    (star(zp=32, zr=86, count=6), "stage[0].planet.count", "centres 108.0000 mm apart"),
    # declared angles 20 steps apart (69.23°): 2 x 104 sin 34.615° = 118.1575 mm < 128 mm
    (star(planet=f", angles_deg = [0, {20 * STEP:.6f}, {40 * STEP:.6f}, {60 * STEP:.6f}]"),
     "stage[0].planet.angles_deg", "118.1575 mm"),
    (star(planet=", angles_deg = [0, 90, 180, 180]"), "stage[0].planet.angles_deg", "same position"),
    (star(planet=", angles_deg = [0, 90, 180]"), "stage[0].planet.angles_deg", "one angle per planet (4), got 3"),
])
def test_a_planetary_that_cannot_be_built_is_exit_2_naming_the_key_and_the_numbers(tmp_path, scene, key, says):
    path, err = refused(tmp_path, scene)
    assert f"{path.name}: {key}: " in err and says in err, err


# ------------------------------------------------------------------------------------- the books by hand
def _eta0_by_textbook(fixed: str, driven: str, eta: float) -> float:
    """The basic (carrier-held) efficiency from the stage's, inverting the textbook relation of each arrangement."""
    return {("ring", "sun"): (eta * (1 + U) - 1) / U,  # eta = (1 + eta0 u)/(1 + u)
            ("ring", "carrier"): U / ((1 + U) / eta - 1),  # eta = (1 + u)/(1 + u/eta0)
            ("carrier", "sun"): eta, ("carrier", "ring"): eta,
            ("sun", "ring"): eta * (1 + U) - U,  # eta = (u + eta0)/(1 + u)
            ("sun", "carrier"): eta / (1 + U - eta * U),  # eta = eta0 (1 + u)/(1 + eta0 u)
            }[(fixed, driven)]


ARRANGEMENTS = [("ring", "sun"), ("ring", "carrier"), ("carrier", "sun"), ("carrier", "ring"), ("sun", "ring"),
                ("sun", "carrier")]


@pytest.mark.parametrize(("fixed", "driven"), ARRANGEMENTS)
def test_willis_speeds_torques_moment_balance_and_mesh_forces_of_every_arrangement(tmp_path, fixed, driven):
    doc = design(tmp_path, star(fixed=fixed, driven=driven))
    st = doc["stages"][0]
    out = next(m for m in ("sun", "carrier", "ring") if m not in (fixed, driven))
    # Willis: w_s - w_c = -u (w_r - w_c), the held member at rest, the driven one at 1500 rpm
    w = {fixed: 0.0, driven: N_IN}
    if fixed == "ring":
        w[out] = N_IN * (1 + U) if out == "sun" else N_IN / (1 + U)
    elif fixed == "carrier":
        w[out] = -N_IN * U if out == "sun" else -N_IN / U
    else:  # sun held: w_c (1 + u) = u w_r
        w[out] = N_IN * U / (1 + U) if out == "carrier" else N_IN * (1 + U) / U
    for m in ("sun", "carrier", "ring"):
        assert_allclose(st[m]["speed_rpm"], w[m], rtol=1e-12, atol=1e-9)
    assert_allclose(st["ratio"], abs(N_IN / w[out]), rtol=1e-12)
    assert_allclose(st["willis_ratio"], -U, rtol=1e-12)
    # the planet's speed relative to the carrier (docs/output.md): |w_s - w_c| z_s / z_p
    assert_allclose(st["planet"]["speed_rpm"], abs(w["sun"] - w["carrier"]) * ZS / ZP, rtol=1e-12)
    assert_allclose(doc["output_speed_rpm"], abs(w[out]) * Z1 / Z2, rtol=1e-12)
    # torques: the helical stage's pinion (on the output member) needs T_out/(i_2 eta_2); the stage's input eta_1 less
    t_out = T_OUT / (Z2 / Z1 * ETA2)
    t_in = t_out / (st["ratio"] * ETA1)
    assert_allclose(doc["input_torque_Nm"], t_in, rtol=1e-12)
    eta0 = _eta0_by_textbook(fixed, driven, ETA1)
    assert_allclose(st["basic_efficiency"], eta0, rtol=1e-10)
    assert_allclose(st["mesh_efficiency"], math.sqrt(eta0), rtol=1e-10)
    # in the carrier's frame the sun drives when its power there, T_s (w_s - w_c), is positive; T_s runs with the
    # input where the sun is driven, against the output's motion where it is the output, and as the ring where held
    sun_drives = (fixed, driven) in (("ring", "sun"), ("carrier", "sun"), ("sun", "carrier"))
    rho = eta0 * U if sun_drives else U / eta0  # |T_ring| / |T_sun|
    mag = dict(zip((driven, out), (t_in, t_out), strict=True))
    if "sun" in mag:
        t_s = mag["sun"]
    else:  # the sun held: |T_carrier| = |T_s| (1 + rho), |T_ring| = rho |T_s|
        t_s = mag["carrier"] / (1 + rho)
    t_r, t_c = rho * t_s, (1 + rho) * t_s
    assert_allclose([st[m]["torque_Nm"] for m in ("sun", "ring", "carrier")], [t_s, t_r, t_c], rtol=1e-10)
    assert_allclose(mag[driven], {"sun": t_s, "ring": t_r, "carrier": t_c}[driven], rtol=1e-10)
    # the signed balance: the driven member's torque with its motion, the output's against its motion
    bal = st["moment_balance_Nm"]
    assert_allclose(bal[driven], t_in, rtol=1e-10)
    assert_allclose(bal[out], -math.copysign(t_out, w[out] / N_IN), rtol=1e-10)
    assert_allclose(sum(bal.values()), 0.0, atol=1e-9 * t_c)
    # per planet mesh, the driving side's force on the pitch circle (no profile shift: working = pitch)
    r_s, r_r = ZS * MN / 2e3, ZR * MN / 2e3
    if sun_drives:
        f_sp = t_s / (N_PL * r_s)
        f_pr = math.sqrt(eta0) * f_sp
    else:
        f_pr = t_r / (N_PL * r_r)
        f_sp = math.sqrt(eta0) * f_pr
    sp, pr = st["meshes"]
    assert (sp["name"], pr["name"]) == ("sun_planet", "planet_ring")
    assert_allclose([sp["static_force_N"]["tangential"], pr["static_force_N"]["tangential"]], [f_sp, f_pr],
                    rtol=1e-10)
    tan20 = math.tan(math.radians(20))
    assert_allclose([sp["static_force_N"]["radial"], pr["static_force_N"]["radial"]],
                    [f_sp * tan20, f_pr * tan20], rtol=1e-10)
    assert_allclose(sp["static_force_N"]["normal"], f_sp / math.cos(math.radians(20)), rtol=1e-10)
    # the planet's own torque: the planet-side force of either mesh (they are equal: it spins freely) on its lever,
    # the driven side's eta_m F where the sun drives; it was F_sp r_p whatever drove (1/eta_m too high)
    r_p = ZP * MN / 2e3
    assert_allclose(st["planet"]["torque_Nm"], min(f_sp, f_pr) * r_p, rtol=1e-10)


@pytest.mark.parametrize(("zs", "zp", "zr", "count"), [(24, 36, 96, 3), (22, 30, 82, 4), (40, 20, 80, 5)])
def test_planet_count_shares_the_sun_torque(tmp_path, zs, zp, zr, count):
    """Ring held, sun in, no losses: F_t per planet = T_s / (N r_s); the carrier's planets' translational inertia
    N m_p a^2 with the solid planet disc m_p = rho pi d^2 b / 4 of pitch diameter (docs/design-file.md)."""
    doc = design(tmp_path, star(zs, zp, zr, count, fixed="ring", driven="sun", eta=1.0))
    st = doc["stages"][0]
    i1 = 1 + zr / zs
    t_s = T_OUT / (Z2 / Z1 * ETA2) / i1
    assert_allclose(st["meshes"][0]["static_force_N"]["tangential"], t_s / (count * zs * MN / 2e3), rtol=1e-12)
    assert_allclose(st["meshes"][1]["static_force_N"]["tangential"], t_s / (count * zs * MN / 2e3), rtol=1e-12)
    a = (zs + zp) * MN / 2e3
    m_p = 7850 * math.pi * (zp * MN * 1e-3) ** 2 / 4 * B * 1e-3
    assert_allclose(st["carrier"]["planets_translational_inertia_kg_m2"], count * m_p * a**2, rtol=1e-12)
    assert_allclose(st["planet_angles_deg"], [360 * j / count for j in range(count)], rtol=1e-12)
    assert st["equal_spacing"] is True


# ------------------------------------------------------------------------------ a helical, shifted planetary
HELICAL = """
[materials.steel]
density_kg_m3 = 7850
youngs_modulus_MPa = 206000
poisson_ratio = 0.3

[[stage]]
type = "planetary"
normal_module_mm = 3
helix_angle_deg = 15
efficiency = 0.98
sun    = { teeth = 20, face_width_mm = 50, material = "steel", hand = "left", profile_shift = 0.3 }
planet = { teeth = 32, face_width_mm = 48, count = 3, material = "steel", hand = "right", profile_shift = 0.1 }
ring   = { teeth = 85, face_width_mm = 48, material = "steel", profile_shift = 0.03345573 }
fixed = "ring"
input = "sun"

[input]
speed_rpm = 1000

[load]
torque_Nm = 1500
"""


def _inv(a: float) -> float:
    return math.tan(a) - a


def _inv_inverse(v: float) -> float:
    lo, hi = 0.0, 1.5
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if _inv(mid) < v else (lo, mid)
    return 0.5 * (lo + hi)


def test_helical_shifted_planetary_centre_distances_and_forces_by_hand(tmp_path):
    """Sun 20 (x 0.3) / planets 32 (x 0.1) / ring 85, m_n 3, beta 15°, ring held. ISO 21771 with the internal
    gear's signed teeth (z_2 = -85, the ring's x as the file gives it, the KISSsoft/DIN 3960 convention): inv a_wt =
    inv a_t + 2 tan a_n (x_1 + x_2)/(z_1 + z_2) on both meshes, a_w = (z_1 + z_2) m_t cos a_t / (2 cos a_wt). The
    ring's x = 0.03345573 was solved by hand (bisection) for a_w,pr = a_w,sp = 81.8969 mm (concentric). Forces on
    the reference circle (DESIGN section 3): F_t = T_s / (N r_s) with T_s = T_out / ((1 + u) eta), the ring mesh
    eta_m F_t (eta_0 = (eta (1 + u) - 1)/u), F_r = F_t tan a_t, F_a = F_t tan beta; the ring has the planet's hand."""
    doc = design(tmp_path, HELICAL)
    st = doc["stages"][0]
    a_n, beta = math.radians(20), math.radians(15)
    a_t = math.atan(math.tan(a_n) / math.cos(beta))
    m_t = 3 / math.cos(beta)
    aw_sp = _inv_inverse(_inv(a_t) + 2 * math.tan(a_n) * (0.3 + 0.1) / (20 + 32))
    aw_pr = _inv_inverse(_inv(a_t) + 2 * math.tan(a_n) * (0.1 + 0.03345573) / (32 - 85))
    a_sp = (20 + 32) * m_t * math.cos(a_t) / (2 * math.cos(aw_sp))
    a_pr = (85 - 32) * m_t * math.cos(a_t) / (2 * math.cos(aw_pr))
    assert_allclose(a_pr, a_sp, atol=1e-6)  # the hand-solved shift makes the stage concentric
    sp, pr = st["meshes"]
    assert_allclose([sp["center_distance_mm"], pr["center_distance_mm"]], [a_sp, a_pr], rtol=1e-10)
    assert_allclose([sp["working_pressure_angle_deg"], pr["working_pressure_angle_deg"]],
                    [math.degrees(aw_sp), math.degrees(aw_pr)], rtol=1e-9)
    assert st["ring"]["hand"] == "right"
    u = 85 / 20
    t_s = 1500 / ((1 + u) * 0.98)
    f_t = t_s * 1e3 / (3 * 20 * m_t / 2)
    eta_m = math.sqrt((0.98 * (1 + u) - 1) / u)
    for mesh, f in ((sp, f_t), (pr, eta_m * f_t)):
        assert_allclose([mesh["static_force_N"][c] for c in ("tangential", "radial", "axial")],
                        [f, f * math.tan(a_t), f * math.tan(beta)], rtol=1e-10)


@pytest.mark.parametrize(("old", "new", "key", "says"), [
    ('hand = "left", profile_shift = 0.3', 'hand = "right", profile_shift = 0.3', "stage[0].planet.hand",
     'the sun is "right", so the planet must be "left"'),
    ('hand = "left", profile_shift = 0.3', 'profile_shift = 0.3', "stage[0].sun.hand",
     'needs hand = "left" (opposite to the planet), got no hand'),
    ('profile_shift = 0.03345573 }', 'profile_shift = 0.03345573, hand = "left" }', "stage[0].ring.hand",
     'the ring needs the planet\'s hand "right"'),
])
def test_helical_planetary_hands_are_named_as_the_file_names_the_members(tmp_path, old, new, key, says):
    """The sun–planet pair is checked as an external pair; its messages said "pinion" and "gear"."""
    path, err = refused(tmp_path, HELICAL.replace(old, new, 1))
    assert f"{path.name}: {key}: " in err and says in err and "pinion" not in err, err


# ---------------------------------------------------------------------------------------------- life keys
def _rated(text: str) -> str:
    """Scene text with what the rating needs: fatigue limits, roughness, accuracy, a lubricant, two duty points."""
    text = text.replace("poisson_ratio = 0.3\n", "poisson_ratio = 0.3\ntreatment = \"case_carburized\"\n"
                        "contact_fatigue_limit_MPa = 1500\nbending_fatigue_limit_MPa = 500\n", 1)
    text = text.replace('material = "steel"', 'material = "steel", flank_roughness_Rz_um = 3, root_roughness_Rz_um = 10')
    text = text.replace("normal_module_mm = ", "accuracy_grade = 6\nnormal_module_mm = ")
    return text + """
[lubricant]
viscosity_40C_mm2_s = 220
viscosity_100C_mm2_s = 19
temperature_C = 70

[rating]
required_life_h = 4000

[[duty]]
name = "rated"
hours = 1000
torque_Nm = 2000
speed_rpm = 1500

[[duty]]
name = "half"
hours = 3000
torque_Nm = 1000
speed_rpm = 1200
"""


def test_life_of_a_star_counts_the_turning_ring_and_keys_every_member(tmp_path):
    """Carrier held, the ring turning (z_s/z_r of the sun's speed, against it): per point, the sun's flanks meet N
    planets per turn, N n_s t; each planet tooth meets the sun and the ring once per planet turn, (z_s/z_p) n_s t on
    each flank (its root: both meshes' bins, docs/life.md's conservative sum); the ring meets N planets per turn of its own,
    N (z_s/z_r) n_s t. The forces: the static F_t per planet, halved at half the load. JSON keys: `sun`, `planet`,
    `ring`, `planet_ring_side`, `planet_root` (docs/life.md)."""
    path = _write(tmp_path, _rated(star()))
    res = _run("life", str(path), "--static", "--format", "json")
    assert res.exit_code == 0, res.stderr
    st = json.loads(res.stdout)["life"]["stages"][0]
    minutes = {"rated": (1000 * 60, 1500.0), "half": (3000 * 60, 1200.0)}
    want = {"sun": N_PL, "planet": ZS / ZP, "planet_ring_side": ZS / ZP, "ring": N_PL * ZS / ZR}
    for member, per_turn in want.items():
        for mode in ("pitting", "bending") if member != "planet" else ("pitting",):  # its bending: planet_root
            bins = st[member][mode]["bins"]
            for point, (t, n) in minutes.items():
                got = sum(b["cycles"] for b in bins if b["point"] == point)
                assert_allclose(got, per_turn * n * t, rtol=1e-12, err_msg=f"{member} {mode} {point}")
    for member in ("planet", "planet_root"):  # both meshes' bins on one root, conservatively (docs/life.md)
        root = st[member]["bending"]["bins"]
        assert_allclose(sum(b["cycles"] for b in root if b["point"] == "rated"), 2 * ZS / ZP * 1500 * 60000,
                        rtol=1e-12)
    f_sp = T_OUT / (Z2 / Z1 * ETA2) / (ZR / ZS * ETA1) / (N_PL * ZS * MN / 2e3)
    assert_allclose([b["force_N"] for b in st["sun"]["pitting"]["bins"]], [f_sp, f_sp / 2], rtol=1e-12)
    assert_allclose([b["force_N"] for b in st["ring"]["pitting"]["bins"]],
                    [math.sqrt(ETA1) * f_sp, math.sqrt(ETA1) * f_sp / 2], rtol=1e-12)


@pytest.mark.parametrize("command", ["design", "simulate", "modes", "life", "sweep"])
def test_an_infeasible_set_is_blamed_on_the_set_by_every_command(tmp_path, command):
    """`--set stage[0].planet.count=5` makes the stage unassemblable ((22 + 82)/5 = 20.8): every command names the
    --set that gave the value, as `design` does (life and sweep named the design file, whose count is 4)."""
    path = _write(tmp_path, _rated(star()))
    extra = ["--vary", "input.speed_rpm=1000,1500"] if command == "sweep" else []
    res = _run(command, str(path), "--set", "stage[0].planet.count=5", *extra)
    assert res.exit_code == 2, res.stderr
    assert "gearcli: --set: stage[0].planet.count: planet spacing" in res.stderr, res.stderr
    assert "Traceback" not in res.stderr


def test_rating_of_a_star_counts_the_turning_ring_and_bends_the_planet_both_ways(tmp_path):
    """`design` with [rating] (required life 4000 h): the sun–planet mesh's pinion (the sun) N n_s L, its gear (the
    planet) (z_s/z_p) n_s L; the planet–ring mesh's pinion (the planet) the same, its gear (the turning ring)
    N (z_s/z_r) n_s L (L in minutes); Y_M = 0.7 on the planet in both meshes (an idler, ISO 6336-3), 1 elsewhere."""
    doc = design(tmp_path, _rated(star()))
    sp, pr = (m["rating"] for m in doc["stages"][0]["meshes"])
    minutes = 4000 * 60
    assert_allclose([sp["pinion"]["load_cycles"], sp["gear"]["load_cycles"], pr["pinion"]["load_cycles"],
                     pr["gear"]["load_cycles"]],
                    [N_PL * N_IN * minutes, ZS / ZP * N_IN * minutes, ZS / ZP * N_IN * minutes,
                     N_PL * ZS / ZR * N_IN * minutes], rtol=1e-12)
    assert [sp["pinion"]["Y_M"], sp["gear"]["Y_M"], pr["pinion"]["Y_M"], pr["gear"]["Y_M"]] == [1.0, 0.7, 0.7, 1.0]
