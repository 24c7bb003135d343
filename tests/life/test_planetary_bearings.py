"""Bearings on a planetary stage against hand calculations (docs/life.md, "Planetary stages").

Scene: sun 24 (input, left hand), three planets 30 (right hand), ring 84 held (right hand), m_n 4, beta 12 deg,
x = 0 (working = reference geometry: alpha_w = alpha_t on both meshes), 400 N m on the carrier, K_gamma 1.15.
Each planet's pin has two roller bearings 15 mm either side of the planet's mid-face; the sun shaft and the
carrier shaft have two bearings each.

Hand model, per planet (F_t = T_sun / (N r_w,s) at the working circle, F_a = F_t tan(beta) on each mesh):
- the sun and the ring both push the planet with F_t in the same tangential sense (the planet's moment
  balance): 2 F_t on the pin, K_gamma 2 F_t on the most loaded one, half on each bearing by the lever rule;
- the separating forces F_t tan(alpha_w) of the two meshes point outwards (sun) and inwards (ring): they
  cancel with equal working pressure angles;
- the axial forces of the two meshes are opposite (the same hand meets the sun and the ring on opposite
  flanks) and cancel, but they act r_w,p either side of the planet's axis: a tilting moment
  M = F_a (r_w,p + r_w,p) = 2 F_a r_w,p, taken as a couple +-M/L by the two bearings (span L), at right angles
  to the tangential load;
- the sun shaft: the planets' tangential forces are a pure torque and their radial forces cancel (equally
  spaced); the axial forces add: N F_a on the locating bearing; the carrier: the planets' forces on it cancel.
"""

from __future__ import annotations

import math

from numpy.testing import assert_allclose

from tests.life.scenes import design_of

Z_S, Z_P, Z_R, N, M_N, BETA, T_OUT, K_GAMMA = 24, 30, 84, 3, 4.0, 12.0, 400.0, 1.15
SPAN = 30.0

PLANETARY = f"""
[materials.steel]
density_kg_m3 = 7830
youngs_modulus_MPa = 206000
poisson_ratio = 0.3
treatment = "case_carburized"
contact_fatigue_limit_MPa = 1500
bending_fatigue_limit_MPa = 430

[[stage]]
type = "planetary"
normal_module_mm = {M_N}
helix_angle_deg = {BETA}
accuracy_grade = 6
sun = {{ teeth = {Z_S}, face_width_mm = 40, hand = "left", axial_position_mm = 100, flank_roughness_Rz_um = 4, root_roughness_Rz_um = 20 }}
planet = {{ teeth = {Z_P}, face_width_mm = 40, count = {N}, hand = "right", axial_position_mm = 100, flank_roughness_Rz_um = 4, root_roughness_Rz_um = 20 }}
ring = {{ teeth = {Z_R}, face_width_mm = 40, hand = "right", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 20 }}
fixed = "ring"
input = "sun"

[lubricant]
viscosity_40C_mm2_s = 220
viscosity_100C_mm2_s = 19
temperature_C = 70

[input]
speed_rpm = 300

[load]
torque_Nm = {T_OUT}

[rating]
required_life_h = 20000
load_sharing_factor = {K_GAMMA}

[[bearing]]
shaft = 1
position_mm = 0
dynamic_load_rating_kN = 50
kind = "ball"
locating = true
factors = {{ e = 0.3, X = 0.56, Y = 1.5 }}

[[bearing]]
shaft = 1
position_mm = 150
dynamic_load_rating_kN = 50
kind = "ball"

[[bearing]]
shaft = 2
position_mm = 50
dynamic_load_rating_kN = 80
kind = "roller"
locating = true

[[bearing]]
shaft = 2
position_mm = 250
dynamic_load_rating_kN = 80
kind = "roller"

[[bearing]]
planet_stage = 1
position_mm = {100 - SPAN / 2}
dynamic_load_rating_kN = 40
kind = "roller"
locating = true

[[bearing]]
planet_stage = 1
position_mm = {100 + SPAN / 2}
dynamic_load_rating_kN = 40
kind = "roller"
"""


def _hand():
    m_t = M_N / math.cos(math.radians(BETA))
    r_ws, r_wp = 0.5 * Z_S * m_t, 0.5 * Z_P * m_t  # x = 0: working = reference circles (mm)
    t_sun = T_OUT * 1e3 / (1 + Z_R / Z_S)  # N mm
    f_t = t_sun / (N * r_ws)
    f_a = f_t * math.tan(math.radians(BETA))
    return f_t, f_a, r_wp


def test_planet_pin_bearings_by_the_lever_rule_and_the_tilting_couple():
    _, design = design_of(PLANETARY)
    f_t, f_a, r_wp = _hand()
    pins = [b for b in design.bearings if b.planet_stage == 1]
    assert len(pins) == 2 and all(b.shaft == 0 for b in pins)
    tangential = K_GAMMA * 2 * f_t / 2
    couple = K_GAMMA * 2 * f_a * r_wp / SPAN
    for b in pins:
        assert_allclose(abs(b.radial_z_N), tangential, rtol=1e-9)  # z: the planet's tangential direction
        assert_allclose(abs(b.radial_y_N), couple, rtol=1e-9)  # y: radial, the tilting couple (radial forces cancel)
        assert_allclose(b.radial_N, math.hypot(tangential, couple), rtol=1e-9)
        assert_allclose(b.axial_N, 0.0, atol=1e-9 * f_a)  # the two meshes' axial forces cancel
    assert pins[0].radial_y_N == -pins[1].radial_y_N  # a couple
    # the pin turns at the planet's speed relative to the carrier: n_s (1 - 1/(1 + u)) z_s / z_p
    n_rel = 300 * (1 - 1 / (1 + Z_R / Z_S)) * Z_S / Z_P
    for b in pins:
        assert_allclose(b.speed_rpm, n_rel, rtol=1e-12)
        assert_allclose(b.L10_Mrev, (40e3 / b.equivalent_load_N) ** (10 / 3), rtol=1e-12)
        assert_allclose(b.L10_h, 1e6 * b.L10_Mrev / (60 * n_rel), rtol=1e-12)


def test_sun_and_carrier_shafts_see_the_balanced_planets():
    _, design = design_of(PLANETARY)
    f_t, f_a, _ = _hand()
    sun = [b for b in design.bearings if b.shaft == 1]
    carrier = [b for b in design.bearings if b.shaft == 2]
    for b in sun + carrier:
        assert b.radial_N == 0.0  # equally spaced identical planets: no net radial force
    loc = next(b for b in sun if b.locating)
    assert_allclose(abs(loc.axial_N), N * f_a, rtol=1e-9)  # N F_a on the sun's locating bearing
    assert all(b.axial_N == 0.0 for b in carrier)  # the planets' axial forces cancel on each pin
    # pure axial load on the ball bearing: P = X F_r + Y F_a = Y N F_a
    assert_allclose(loc.equivalent_load_N, 1.5 * N * f_a, rtol=1e-9)


DUTY = """
[[duty]]
name = "full"
hours = 1000
speed_rpm = 300
torque_Nm = 400

[[duty]]
name = "part"
hours = 3000
speed_rpm = 200
torque_Nm = 200
"""


def _life(tmp_path, *args):
    import json

    from click.testing import CliRunner

    from gearcli.cli import cli

    path = tmp_path / "planetary.toml"
    path.write_text(PLANETARY + DUTY)
    res = CliRunner().invoke(cli, ["life", str(path), "--format", "json", "-q", *args])
    return path, res, (json.loads(res.stdout) if res.exit_code == 0 else None)


def test_planet_bearings_over_a_duty_by_iso281(tmp_path):
    """life --static: each point's pin load scales with its torque, its revolutions (relative to the carrier)
    with its speed; P_eq = (sum P_i^p N_i / sum N_i)^(1/p) with p = 10/3; L10 = (C / P_eq)^p."""
    _, res, doc = _life(tmp_path, "--static")
    assert res.exit_code == 0, res.output
    _, design = design_of(PLANETARY)
    p_full = next(b for b in design.bearings if b.planet_stage == 1).equivalent_load_N
    loads = [p_full, p_full * 200 / 400]
    n_rel = (1 - 1 / (1 + Z_R / Z_S)) * Z_S / Z_P  # planet speed relative to the carrier per sun rpm
    revs = [1000 * 60 * 300 * n_rel, 3000 * 60 * 200 * n_rel]
    p = 10 / 3
    p_eq = (sum(f**p * n for f, n in zip(loads, revs, strict=True)) / sum(revs)) ** (1 / p)
    pin = doc["life"]["bearings"][4]
    assert_allclose(pin["loads_N"], loads, rtol=1e-9)
    assert_allclose(pin["revolutions"], sum(revs), rtol=1e-12)
    assert_allclose(pin["equivalent_load_N"], p_eq, rtol=1e-9)
    assert_allclose(pin["L10_Mrev"], (40e3 / p_eq) ** p, rtol=1e-9)


def test_the_sun_tooth_meets_every_planet(tmp_path):
    """Load cycles of the sun–planet mesh over the duty (static route): a sun tooth is loaded N times per
    revolution relative to the carrier, a planet tooth (on this flank) once."""
    _, res, doc = _life(tmp_path, "--static")
    assert res.exit_code == 0, res.output
    stage = doc["life"]["stages"][0]
    rel_sun = 1 - 1 / (1 + Z_R / Z_S)  # |n_s - n_c| per sun rpm
    rel_planet = rel_sun * Z_S / Z_P
    for point, hours, rpm in ((0, 1000, 300), (1, 3000, 200)):
        assert_allclose(stage["pinion"]["pitting"]["bins"][point]["cycles"], hours * 60 * rpm * rel_sun * N, rtol=1e-12)
        assert_allclose(stage["gear"]["pitting"]["bins"][point]["cycles"], hours * 60 * rpm * rel_planet, rtol=1e-12)


STEADY = ("--set", "contact.exponent=1.0", "--set", "contact.damping_ratio=0.3", "--set", 'contact.stiffness="iso6336"',
          "--set", "input.ramp_s=0.05", "--set", "load.ramp_s=0.05")


def test_the_dynamic_life_route_loads_the_pins_with_the_simulated_planets(tmp_path):
    """The dynamic route at a linear, well-damped steady state: identical planets share equally, so each pin
    carries the mean planet's load times the file's K_gamma (the design's pin load: the model does not see the
    unequal sharing K_gamma allows for) and the sun's locating bearing N F_a (as the statics); with a position
    error on planet 2 the simulation shares the load (K_gamma 1) and the pins report the most loaded planet: its
    sun-mesh force over the mean planet's times the equal-planet load without K_gamma (the pin load is linear in
    the planet's force)."""
    _, res, doc = _life(tmp_path, *STEADY)
    assert res.exit_code == 0, res.output
    _, design = design_of(PLANETARY)
    for j, b in enumerate(design.bearings):
        assert_allclose(doc["life"]["bearings"][j]["loads_N"][0], b.equivalent_load_N, rtol=1e-3)
    _, res2, doc2 = _life(tmp_path, *STEADY, "--set", "stage[0].planet.position_error_um=[0.0, 3.0, 0.0]")
    assert res2.exit_code == 0, res2.output
    gear = doc2["life"]["stages"][0]["gear"]["pitting"]
    assert gear["planet"] == 2
    f_2 = max(b["force_N"] for b in gear["bins"] if b["point"] == "full")
    f_mean = max(b["force_N"] for b in doc["life"]["stages"][0]["gear"]["pitting"]["bins"] if b["point"] == "full")
    assert f_2 > 1.05 * f_mean
    pin, pin_equal = doc2["life"]["bearings"][4], doc["life"]["bearings"][4]
    assert_allclose(pin["loads_N"][0], pin_equal["loads_N"][0] / K_GAMMA * f_2 / f_mean, rtol=1e-3)
    sun = doc2["life"]["bearings"][0]  # the sun's locating bearing: N F_a of the mean planet, whatever the sharing
    assert_allclose(sun["loads_N"][0], doc["life"]["bearings"][0]["loads_N"][0], rtol=1e-3)


def test_simulate_reports_the_planetary_bearing_channels():
    """The reaction channels of a simulation follow the statics sample by sample: at the steady state of a linear,
    well-damped scene the window means equal the design's static reactions (the pins without K_gamma: the
    simulation shares the load itself, equally here)."""
    from gearcli.config.load import load_design  # noqa: F401 - the TOML text goes through design_of
    from gearcli.simulate import run_simulation
    from gearcli.simulate.bearings import with_bearings

    cfg, design = design_of(PLANETARY, ("rating.load_sharing_factor=1.0", "contact.exponent=1.0",
                                        "contact.damping_ratio=0.3", "contact.stiffness=\"iso6336\"",
                                        "input.ramp_s=0.05", "load.ramp_s=0.05", "simulation.duration_s=0.3",
                                        "simulation.window_start_s=0.2", "simulation.steps=600"))
    sim = with_bearings(cfg, design, run_simulation(cfg, design))
    for j, b in enumerate(design.bearings):
        mean = sim.extra["bearings"][j]["radial_N"].mean
        assert_allclose(mean, b.radial_N, rtol=2e-3, atol=1e-6 * max(x.radial_N for x in design.bearings))


MIXED = """
[[stage]]
type = "planetary"
normal_module_mm = 3
sun = {{ teeth = 21, face_width_mm = 30 }}
planet = {{ teeth = 27, face_width_mm = 30, count = 3, axial_position_mm = 40 }}
ring = {{ teeth = 75, face_width_mm = 30, axial_position_mm = 40 }}
fixed = "{fixed}"
input = "sun"

[[stage]]
normal_module_mm = 4
normal_pressure_angle_deg = 20
helix_angle_deg = 15
center_angle_deg = 30
pinion = {{ teeth = 20, face_width_mm = 40, hand = "left", axial_position_mm = 100 }}
gear = {{ teeth = 60, face_width_mm = 40, hand = "right", axial_position_mm = 70 }}

[input]
speed_rpm = 1500
rotation = "cw"

[load]
torque_Nm = 600

[[bearing]]
shaft = 2
position_mm = 0
dynamic_load_rating_kN = 40
kind = "ball"
locating = true

[[bearing]]
shaft = 2
position_mm = 200
dynamic_load_rating_kN = 40
kind = "ball"
"""

ALONE = """
[[stage]]
normal_module_mm = 4
normal_pressure_angle_deg = 20
helix_angle_deg = 15
center_angle_deg = 30
pinion = {{ teeth = 20, face_width_mm = 40, hand = "left", axial_position_mm = 100 }}
gear = {{ teeth = 60, face_width_mm = 40, hand = "right", axial_position_mm = 70 }}

[input]
speed_rpm = 1500
rotation = "{rotation}"

[load]
torque_Nm = 600

[[bearing]]
shaft = 1
position_mm = 0
dynamic_load_rating_kN = 40
kind = "ball"
locating = true

[[bearing]]
shaft = 1
position_mm = 200
dynamic_load_rating_kN = 40
kind = "ball"
"""


def test_a_parallel_stage_after_a_planetary_turns_as_willis_says():
    """The parallel pinion on the planetary's output shaft: with the ring held the carrier turns with the sun
    (the same statics as the pinion driven directly in the input's sense), with the carrier held the ring turns
    backwards (the input's opposite sense); the balanced planets add nothing to that shaft."""
    for fixed, output, rotation in (("ring", "carrier", "cw"), ("carrier", "ring", "ccw")):
        _, mixed = design_of(MIXED.format(fixed=fixed))
        _, alone = design_of(ALONE.format(rotation=rotation))
        for a, b in zip(mixed.bearings, alone.bearings, strict=True):
            assert_allclose([a.radial_y_N, a.radial_z_N, a.axial_N], [b.radial_y_N, b.radial_z_N, b.axial_N],
                            rtol=1e-9, atol=1e-9 * b.radial_N)
        assert mixed.stages[0].planetary.output == output


def test_bad_planet_bearings_name_the_key(tmp_path):
    from click.testing import CliRunner

    from gearcli.cli import cli

    cases = (("bearing.4.planet_stage=2", "bearing[4].planet_stage"),  # no stage 2
             ("bearing.5.locating=true", "bearing[4].locating"),  # two locating bearings on the pins
             ("bearing.4.shaft=1", "bearing[4]"))  # both shaft and planet_stage
    path = tmp_path / "planetary.toml"
    path.write_text(PLANETARY)
    for setting, key in cases:
        res = CliRunner().invoke(cli, ["design", str(path), "--set", setting])
        assert res.exit_code == 2, (setting, res.output)
        assert f": {key}" in res.stderr and "Traceback" not in res.stderr, res.stderr  # the --set names the place


def test_life_names_a_planet_pins_bearing_by_its_stage(tmp_path):
    """`life` JSON: a planet pin's bearing says which planetary stage it belongs to (`planet_stage`, as in
    `design`); a shaft's bearing has no such key; the table names it "planets of stage k"."""
    _, res, doc = _life(tmp_path, "--static")
    assert res.exit_code == 0, res.output
    _, design = design_of(PLANETARY)
    for b, d in zip(doc["life"]["bearings"], design.bearings, strict=True):
        if d.planet_stage:
            assert (b["shaft"], b["planet_stage"]) == (0, d.planet_stage)
        else:
            assert "planet_stage" not in b and b["shaft"] == d.shaft
    assert any(d.planet_stage for d in design.bearings)
