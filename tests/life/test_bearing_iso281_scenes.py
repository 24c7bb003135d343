"""ISO 281:2007 modified life and ISO 76 static safety on scenes of their own, every figure against a hand
calculation written out here (docs/bearings.md):

- the reactions of a spur pinion midway between its bearings: F_t = 2 T_1 / d_1, F_r = F_t tan α, each bearing
  half of sqrt(F_t² + F_r²) (beam statics);
- L10 = (C/P)^p, p = 3 ball, 10/3 roller (ISO 281 eq. 1 and 2);
- the oil at its temperature by ASTM D341 (Walther: log10 log10(ν + 0.7) linear in log10 T);
- ν_1 = 45000 n^-0.83 d_m^-0.5 (n < 1000 r/min), 4500 n^-0.5 d_m^-0.5 (n ≥ 1000), κ = ν / ν_1 (ISO 281 6.5.2.4);
- e_C of ISO 281 Table 13 (lower end of the range), a_1 of Table 12;
- a_ISO by the branch of κ and kind (ISO 281 eq. 8–13), κ held in [0.1, 4], at most 50;
- variable conditions by Palmgren–Miner: P_eq = (Σ U_i P_i^p / Σ U_i)^(1/p) with U_i the revolutions, and
  L_nm = Σ U_i / Σ (U_i / L_nm,i);
- s_0 = C_0 / max(F_r, X_0 F_r + Y_0 F_a) (ISO 76).
"""

from __future__ import annotations

import json
import math

from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

GEARS = """
[materials.steel]
density_kg_m3 = 7850
youngs_modulus_MPa = 2.06e5
poisson_ratio = 0.3
treatment = "case_carburized"
contact_fatigue_limit_MPa = 1500
bending_fatigue_limit_MPa = 500

[rating]
required_life_h = 8000
"""

# Scene A: a spur stage, the gears midway between bearings 120 mm apart; a 6208-like ball bearing pair on the
# pinion shaft (the second at 99 % reliability), an NU 212-like roller pair on the gear shaft; VG 68 at 70 °C.
SPUR = GEARS + """
[[stage]]
normal_module_mm = 3
normal_pressure_angle_deg = 20
helix_angle_deg = 0
accuracy_grade = 6
pinion = { teeth = 20, face_width_mm = 40, material = "steel", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 12, axial_position_mm = 60 }
gear   = { teeth = 61, face_width_mm = 38, material = "steel", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 12, axial_position_mm = 60 }

[input]
speed_rpm = 1500

[load]
torque_Nm = 400

[lubricant]
viscosity_40C_mm2_s = 68
viscosity_100C_mm2_s = 8.7
temperature_C = 70
contamination = "normal"

[[bearing]]
shaft = 1
position_mm = 0
dynamic_load_rating_kN = 32.5
static_load_rating_kN = 19
fatigue_load_limit_kN = 0.8
pitch_diameter_mm = 60
kind = "ball"
locating = true
[[bearing]]
shaft = 1
position_mm = 120
dynamic_load_rating_kN = 32.5
static_load_rating_kN = 19
fatigue_load_limit_kN = 0.8
pitch_diameter_mm = 60
reliability_percent = 99
kind = "ball"
[[bearing]]
shaft = 2
position_mm = 0
dynamic_load_rating_kN = 108
static_load_rating_kN = 102
fatigue_load_limit_kN = 12.9
pitch_diameter_mm = 85
kind = "roller"
locating = true
[[bearing]]
shaft = 2
position_mm = 120
dynamic_load_rating_kN = 108
static_load_rating_kN = 102
fatigue_load_limit_kN = 12.9
pitch_diameter_mm = 85
kind = "roller"

[[duty]]
name = "full"
hours = 2000
torque_Nm = 400
speed_rpm = 1500
[[duty]]
name = "light"
hours = 6000
torque_Nm = 150
speed_rpm = 750
"""
RATIO = 61 / 20
D1_MM = 3 * 20  # spur: d = m z
BEARINGS = [  # C [N], C_0 [N], C_u [N], d_m, kind, a_1
    (32.5e3, 19e3, 800.0, 60.0, "ball", 1.0), (32.5e3, 19e3, 800.0, 60.0, "ball", 0.25),  # 99 %: Table 12
    (108e3, 102e3, 12.9e3, 85.0, "roller", 1.0), (108e3, 102e3, 12.9e3, 85.0, "roller", 1.0)]
E_C_NORMAL_SMALL = 0.5  # ISO 281 Table 13, normal cleanliness, d_m < 100 mm: 0.6 to 0.5


def _nu(t_c: float, nu40: float, nu100: float) -> float:
    """ASTM D341 through (40 °C, nu40) and (100 °C, nu100)."""
    w40, w100 = (math.log10(math.log10(v + 0.7)) for v in (nu40, nu100))
    slope = (w100 - w40) / (math.log10(373.15) - math.log10(313.15))
    return 10 ** 10 ** (w40 + slope * (math.log10(t_c + 273.15) - math.log10(313.15))) - 0.7


def _nu1(n: float, dm: float) -> float:
    return 45000 * n**-0.83 * dm**-0.5 if n < 1000 else 4500 * n**-0.5 * dm**-0.5


def _a_iso(kappa: float, x: float, kind: str) -> float:
    """ISO 281 eq. 8-13 written out branch by branch; kappa held in [0.1, 4], a_ISO at most 50."""
    k = min(max(kappa, 0.1), 4.0)
    if kind == "ball":
        if k < 0.4:
            bracket = 1 - (2.5671 - 2.2649 / k**0.054381) ** 0.83 * x ** (1 / 3)
        elif k < 1:
            bracket = 1 - (2.5671 - 1.9987 / k**0.19087) ** 0.83 * x ** (1 / 3)
        else:
            bracket = 1 - (2.5671 - 1.9987 / k**0.071739) ** 0.83 * x ** (1 / 3)
        return 50.0 if bracket <= 0 else min(0.1 * bracket**-9.3, 50.0)
    if k < 0.4:
        bracket = 1 - (1.5859 - 1.3993 / k**0.054381) * x**0.4
    elif k < 1:
        bracket = 1 - (1.5859 - 1.2348 / k**0.19087) * x**0.4
    else:
        bracket = 1 - (1.5859 - 1.2348 / k**0.071739) * x**0.4
    return 50.0 if bracket <= 0 else min(0.1 * bracket**-9.185, 50.0)


def _run(tmp_path, command: str, text: str, *args: str):
    path = tmp_path / "scene.toml"
    path.write_text(text)
    return CliRunner().invoke(cli, [command, str(path), *args])


def _json(tmp_path, command: str, text: str, *args: str) -> dict:
    res = _run(tmp_path, command, text, "--format", "json", "-q", *args)
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def _spur_point(torque_out_Nm: float, n_in: float) -> list[dict]:
    """Every bearing of scene A at one operating point, by hand."""
    t1 = torque_out_Nm * 1e3 / RATIO  # N·mm on the pinion (efficiency 1)
    ft = 2 * t1 / D1_MM
    fr = ft * math.tan(math.radians(20))
    reaction = 0.5 * math.hypot(ft, fr)  # the gear midway between the two bearings
    nu = _nu(70, 68, 8.7)
    out = []
    for j, (c, c0, cu, dm, kind, a1) in enumerate(BEARINGS):
        n = n_in if j < 2 else n_in / RATIO
        p = 3.0 if kind == "ball" else 10 / 3
        l10 = (c / reaction) ** p
        kappa = nu / _nu1(n, dm)
        a_iso = _a_iso(kappa, E_C_NORMAL_SMALL * cu / reaction, kind)
        out.append({"radial_N": reaction, "equivalent_load_N": reaction, "L10_Mrev": l10, "speed_rpm": n,
                    "kappa": kappa, "a_ISO": a_iso, "a_1": a1, "L_nm_Mrev": a1 * a_iso * l10,
                    "L_nm_h": a1 * a_iso * l10 * 1e6 / (60 * n), "static_equivalent_load_N": reaction,
                    "static_safety": c0 / reaction, "revolutions_per_h": 60 * n})
    return out


def test_spur_design_every_bearing_by_hand(tmp_path):
    """Scene A at its nominal point: reactions, L10, kappa (ball above 1, roller between 0.4 and 1), a_ISO,
    a_1 at 99 %, L_nm and s_0. The hand figures: ball kappa 1.342, a_ISO 7.24; roller kappa 0.707 with
    e_C C_u/P = 2.77, a_ISO 11.06."""
    got = _json(tmp_path, "design", SPUR)["bearings"]
    hand = _spur_point(400, 1500)
    assert 1 < hand[0]["kappa"] < 4 and 0.4 < hand[2]["kappa"] < 1  # the branches this scene checks
    for j, (b, h) in enumerate(zip(got, hand, strict=True)):
        for key in ("radial_N", "equivalent_load_N", "L10_Mrev", "speed_rpm", "kappa", "a_ISO", "a_1",
                    "L_nm_Mrev", "L_nm_h", "static_equivalent_load_N", "static_safety"):
            # the statics and formulas are closed-form: only the floating point rounding differs
            assert_allclose(b[key], h[key], rtol=1e-9, err_msg=f"bearing {j + 1} {key}")
        assert b["axial_N"] == 0.0  # spur


def test_spur_two_point_duty_palmgren_miner_by_hand(tmp_path):
    """Scene A's duty (2000 h at 400 N·m, 1500 r/min; 6000 h at 150 N·m, 750 r/min), static route: the
    equivalent load is the revolution-weighted p-mean of the points' loads, L10 at it, and L_nm the
    Palmgren–Miner sum of each point's own L_nm (its own kappa: the light point's roller bearings fall into
    ISO 281's 0.1 <= kappa < 0.4 branch, e_C C_u / P = 7.4 there)."""
    doc = _json(tmp_path, "life", SPUR, "--static")
    points = [(2000.0, _spur_point(400, 1500)), (6000.0, _spur_point(150, 750))]
    assert 0.1 < points[1][1][2]["kappa"] < 0.4
    for j, b in enumerate(doc["life"]["bearings"]):
        c, c0, _, _, kind, a1 = BEARINGS[j]
        p = 3.0 if kind == "ball" else 10 / 3
        revs = [h * pt[j]["revolutions_per_h"] for h, pt in points]
        loads = [pt[j]["equivalent_load_N"] for _, pt in points]
        p_eq = (sum(u * q**p for u, q in zip(revs, loads, strict=True)) / sum(revs)) ** (1 / p)
        l10 = (c / p_eq) ** p
        l_nm = sum(revs) / 1e6 / sum(u / 1e6 / pt[j]["L_nm_Mrev"] for u, (_, pt) in zip(revs, points, strict=True))
        mean_rpm = sum(revs) / (60 * 8000)
        expected = {"revolutions": sum(revs), "equivalent_load_N": p_eq, "L10_Mrev": l10,
                    "L10_h": l10 * 1e6 / (60 * mean_rpm), "L_nm_Mrev": l_nm, "L_nm_h": l_nm * 1e6 / (60 * mean_rpm),
                    "a_ISO": l_nm / (a1 * l10), "a_1": a1, "kappa": min(pt[j]["kappa"] for _, pt in points),
                    "static_equivalent_load_N": max(loads), "static_safety": c0 / max(loads)}
        for key, value in expected.items():
            assert_allclose(b[key], value, rtol=1e-9, err_msg=f"bearing {j + 1} {key}")
        assert_allclose(b["kappa_points"], [pt[j]["kappa"] for _, pt in points], rtol=1e-9)
        assert_allclose(b["a_ISO_points"], [pt[j]["a_ISO"] for _, pt in points], rtol=1e-9)
        assert_allclose(b["loads_N"], loads, rtol=1e-9)


def test_kappa_clamped_to_4_and_a_iso_capped_at_50(tmp_path):
    """A thick oil at 40 °C (VG 680) puts kappa far above 4: a_ISO is taken at kappa = 4; a fatigue load limit
    above the load makes the bracket negative: a_ISO = 50."""
    text = SPUR.replace("viscosity_40C_mm2_s = 68\nviscosity_100C_mm2_s = 8.7\ntemperature_C = 70",
                        "viscosity_40C_mm2_s = 680\ntemperature_C = 40")
    text = text.replace("fatigue_load_limit_kN = 12.9", "fatigue_load_limit_kN = 50")
    got = _json(tmp_path, "design", text)["bearings"]
    ball = got[0]
    kappa = 680 / _nu1(1500, 60)
    assert kappa > 4
    assert_allclose(ball["kappa"], kappa, rtol=1e-12)  # reported as computed
    x = 0.5 * 800 / ball["equivalent_load_N"]
    assert_allclose(ball["a_ISO"], 0.1 * (1 - (2.5671 - 1.9987 / 4**0.071739) ** 0.83 * x ** (1 / 3)) ** -9.3,
                    rtol=1e-12)  # eq. 10 at kappa = 4
    roller = got[2]
    assert 1 - (1.5859 - 1.2348 / min(roller["kappa"], 4) ** 0.071739) * (0.5 * 50e3 / roller["equivalent_load_N"]) ** 0.4 < 0
    assert roller["a_ISO"] == 50.0


# Scene B: a helical stage crawling at 100 r/min on a thin hot oil (kappa < 0.1), then 6000 r/min at a fifth
# of the torque.
SLOW = SPUR.replace("helix_angle_deg = 0", "helix_angle_deg = 15").replace(
    'material = "steel", flank', 'hand = "left", material = "steel", flank', 1).replace(
    'gear   = { teeth = 61, face_width_mm = 38, material', 'gear   = { teeth = 61, face_width_mm = 38, hand = "right", '
    'material').replace(
    "viscosity_40C_mm2_s = 68\nviscosity_100C_mm2_s = 8.7\ntemperature_C = 70\ncontamination = \"normal\"",
    "viscosity_40C_mm2_s = 10\nviscosity_100C_mm2_s = 2.7\ntemperature_C = 90\ne_C = 0.8").replace(
    "speed_rpm = 1500", "speed_rpm = 100").replace("speed_rpm = 750", "speed_rpm = 6000")


def test_kappa_below_the_range_is_taken_at_0_1_and_warned_in_the_life_json(tmp_path):
    """kappa < 0.1 at the crawl point: a_ISO at kappa = 0.1 (ISO 281 eq. 8 / 11: the method does not apply
    below), and the life output warns, in its JSON too, although the point is the base file's own (whose
    design warnings the life output does not repeat)."""
    design = _json(tmp_path, "design", SLOW)
    nu = _nu(90, 10, 2.7)
    for j, b in enumerate(design["bearings"]):
        dm, kind = BEARINGS[j][3], BEARINGS[j][4]
        kappa = nu / _nu1(b["speed_rpm"], dm)
        assert kappa < 0.1
        assert_allclose(b["kappa"], kappa, rtol=1e-12)
        assert_allclose(b["a_ISO"], _a_iso(0.1, 0.8 * BEARINGS[j][2] / b["equivalent_load_N"], kind), rtol=1e-12)
    assert [w["code"] for w in design["warnings"]].count("bearing_kappa_below_range") == 4
    life = _json(tmp_path, "life", SLOW, "--static")
    below = [w["message"] for w in life["warnings"] if w["code"] == "bearing_kappa_below_range"]
    assert [w.split(":")[0] for w in below] == [f"bearing {j}" for j in range(1, 5)], life["warnings"]
    for w, b in zip(below, life["life"]["bearings"], strict=True):
        assert f"kappa = {b['kappa']:.3g}" in w and b["kappa"] == min(b["kappa_points"])


def test_a_start_below_the_kappa_range_warns(tmp_path, monkeypatch):
    """The starts turn slower than the duty points, so their film is thinner: a start at 2 r/min (kappa far
    below 0.1 at scene A's oil) warns though every duty point is in range."""
    from gearcli.life import run
    from gearcli.life.bearings import StartBearings

    start = StartBearings(0, (1e4,) * 4, (3000.0,) * 4, (2.0,) * 4, (3000.0,) * 4)
    monkeypatch.setattr(run, "start_bearings", lambda points: [start])
    doc = _json(tmp_path, "life", SPUR, "--static")
    for j, b in enumerate(doc["life"]["bearings"]):
        kappa = _nu(70, 68, 8.7) / _nu1(2.0, BEARINGS[j][3])
        assert min(b["kappa_points"]) > 0.1
        assert_allclose(b["kappa"], kappa, rtol=1e-12)
        assert any(w["message"].startswith(f"bearing {j + 1}: viscosity ratio kappa = {kappa:.3g} (the lowest over "
                                           "the duty; below 0.1 at its starts)") for w in doc["warnings"]), doc["warnings"]


def test_an_oil_thicker_at_100_than_at_40_degrees_is_exit_2(tmp_path):
    """ASTM D341 through a 100 °C viscosity above the 40 °C one would make the oil thicken as it warms (and
    kappa grow with temperature): bad input, exit 2 naming the key, no traceback."""
    for nu100 in ("80", "68"):
        res = _run(tmp_path, "design", SPUR.replace("viscosity_100C_mm2_s = 8.7", f"viscosity_100C_mm2_s = {nu100}"))
        assert res.exit_code == 2, res.output
        assert "viscosity_100C_mm2_s" in res.output and "scene.toml" in res.output
        assert "Traceback" not in res.output


def test_mean_effective_load_of_a_textbook_duty(tmp_path):
    """Mott, *Machine Elements in Mechanical Design* (4th ed.), Example Problem 14-6: a 6308 ball bearing at a
    constant 600 r/min under 650 lb for 30 min, 750 lb for 10 min and 250 lb for 20 min has the mean effective
    load F_m = (Σ N_i F_i³ / N)^(1/3) = 597 lb (printed). Scene A's reactions are proportional to the output
    torque (spur, no losses), so a duty of 650, 750 and 250 N·m for 30, 10 and 20 h at one speed loads each
    bearing with F_i = r·T_i: its equivalent load over r is 597 to the printed digits."""
    text = SPUR.split("[[duty]]")[0] + "".join(
        f'[[duty]]\nname = "p{i}"\nhours = {h}\ntorque_Nm = {t}\nspeed_rpm = 1800\n'
        for i, (t, h) in enumerate(((650, 30), (750, 10), (250, 20))))
    bearings = _json(tmp_path, "life", text, "--static")["life"]["bearings"]
    per_Nm = 0.5 * math.hypot(1, math.tan(math.radians(20))) * 2e3 / RATIO / D1_MM  # reaction per N·m of output
    for b in bearings[:2]:  # the ball bearings (p = 3, as the example's)
        assert round(b["equivalent_load_N"] / per_Nm) == 597
        assert_allclose(b["equivalent_load_N"] / per_Nm, ((30 * 650**3 + 10 * 750**3 + 20 * 250**3) / 60) ** (1 / 3),
                        rtol=1e-9)


def test_x_and_y_without_e_is_exit_2(tmp_path):
    """ISO 281: P = F_r while F_a/F_r <= e, X F_r + Y F_a beyond; a catalogue's (X, Y, e) meet near F_r at
    F_a/F_r = e (deep-groove ball: 0.56 + 2.0 · 0.22 ≈ 1). Without e (default 0) scene B's locating bearing
    (F_a/F_r 0.48) with X 0.56, Y 1.0 got P = 0.56 F_r + F_a = 1.04 F_r, and at F_a/F_r = 0.36
    0.92 F_r, below F_r. Exit 2 naming the key now; e = 0 written out keeps that choice."""
    factors = "factors = { X = 0.56, Y = 1.0 }\n"
    text = SLOW.replace("kind = \"ball\"\nlocating = true", "kind = \"ball\"\nlocating = true\n" + factors, 1)
    res = _run(tmp_path, "design", text)
    assert res.exit_code == 2 and "bearing[0].factors" in res.output and "need e" in res.output, res.output
    assert "Traceback" not in res.output
    b = _json(tmp_path, "design", text.replace(factors, "factors = { X = 0.56, Y = 1.0, e = 0 }\n"))["bearings"][0]
    assert_allclose(b["equivalent_load_N"], 0.56 * b["radial_N"] + abs(b["axial_N"]), rtol=1e-12)
    b = _json(tmp_path, "design", text.replace(factors, "factors = { X = 0.56, Y = 1.0, e = 0.5 }\n"))["bearings"][0]
    assert abs(b["axial_N"]) / b["radial_N"] <= 0.5
    assert b["equivalent_load_N"] == b["radial_N"]  # below e: P = F_r


def test_dynamic_route_p_mean_of_a_fluctuating_load(tmp_path):
    """The dynamic route's bearing load of a point is the p-mean of P(t) over its window. Scene A's load torque
    T (1 + 0.3 sin 2π 5 Hz t), far below the mesh mode (quasi-static), over a window of whole periods: every
    reaction follows P_0 (1 + 0.3 sin), so P_eq / P_0 = (mean (1 + 0.3 sin)^p)^(1/p), by quadrature (1.043114
    ball; (1 + 1.5 · 0.09)^(1/3) in closed form), and the peak ISO 76 P_0 is 1.3 P_0. L_nm at that load by hand."""
    from scipy.integrate import quad

    text = SPUR.split("[[duty]]")[0] + ('[[duty]]\nname = "wavy"\nhours = 1000\ntorque_Nm = 400\nspeed_rpm = 1500\n'
                                       'set = { "load.fluctuation" = [{ amplitude_percent = 30, frequency_Hz = 5 }] }\n')
    doc = _json(tmp_path, "life", text)["life"]
    window = doc["points"][0]["solver"]["window_s"]
    assert abs((window[1] - window[0]) * 5 - round((window[1] - window[0]) * 5)) < 1e-9  # whole periods
    hand = _spur_point(400, 1500)
    assert_allclose(((1 + 1.5 * 0.09) ** (1 / 3)), 1.043114, atol=1e-6)
    for j, b in enumerate(doc["bearings"]):
        c, c0, cu, _, kind, a1 = BEARINGS[j]
        p = 3.0 if kind == "ball" else 10 / 3
        ratio = (quad(lambda t, p=p: (1 + 0.3 * math.sin(t)) ** p, 0, 2 * math.pi)[0] / (2 * math.pi)) ** (1 / p)
        p_eq = ratio * hand[j]["equivalent_load_N"]
        # the mesh's own dynamics (its mode ~ kHz) ripple the reactions by ~1e-7 of the load
        assert_allclose(b["loads_N"][0], p_eq, rtol=1e-5, err_msg=f"bearing {j + 1}")
        assert_allclose(b["static_equivalent_load_N"], 1.3 * hand[j]["equivalent_load_N"], rtol=1e-5)
        l_nm = a1 * _a_iso(hand[j]["kappa"], E_C_NORMAL_SMALL * cu / p_eq, kind) * (c / p_eq) ** p
        assert_allclose(b["L_nm_Mrev"], l_nm, rtol=5e-5)  # L ∝ P^-p (and a_ISO): a few times the load's 1e-5


def test_an_axial_force_without_factors_warns(tmp_path):
    """Scene B's locating bearing on the pinion shaft carries the helix's axial force (F_a/F_r from the statics:
    F_a = F_t tan β on the locating bearing, F_r = half of the gear force's radial part, the gear midway), but
    has no factors: P = F_r (default X = 1, Y = 0) ignores it, and so does P_0 without static_factors. The design
    says so once per bearing; the life output once over the duty (F_a/F_r is the train's at every point)."""
    design = _json(tmp_path, "design", SLOW)
    found = [w for w in design["warnings"] if w["code"] == "bearing_axial_not_rated"]
    b = design["bearings"][0]
    assert [w["bearing"] for w in found] == [1, 3]  # the locating bearings; the floating ones carry no F_a
    assert b["equivalent_load_N"] == b["radial_N"] and b["static_equivalent_load_N"] == b["radial_N"]
    # hand statics: pinion shaft, gear midway between bearings 120 mm apart; the axial force's moment
    # F_a d_1/2 shifts the radial reactions by ± F_a d_1 / (2 · 120) in the plane of F_r
    beta, alpha_n = math.radians(15), math.radians(20)
    d1 = 3 * 20 / math.cos(beta)
    ft = 2 * (400e3 / RATIO) / d1  # output 400 N·m, no losses
    fr_gear, fa = ft * math.tan(alpha_n) / math.cos(beta), ft * math.tan(beta)
    radial = [math.hypot(ft / 2, fr_gear / 2 + s * fa * d1 / 2 / 120) for s in (1, -1)]
    assert_allclose(sorted([b["radial_N"], design["bearings"][1]["radial_N"]]), sorted(radial), rtol=1e-9)
    assert_allclose(abs(b["axial_N"]), fa, rtol=1e-9)
    assert f"F_a/F_r = {fa / b['radial_N']:.3g}" in found[0]["message"] and "static_factors" in found[0]["message"]
    life = _json(tmp_path, "life", SLOW, "--static")
    assert len([w for w in life["warnings"] if w["code"] == "bearing_axial_not_rated"]) == 2  # once per bearing over two points
    text = SLOW.replace('kind = "ball"\nlocating = true', 'kind = "ball"\nlocating = true\nfactors = { e = 0.3, X = 0.56, '
                        'Y = 1.5 }\nstatic_factors = { X0 = 0.6, Y0 = 0.5 }', 1)
    assert [w["bearing"] for w in _json(tmp_path, "design", text)["warnings"]
            if w["code"] == "bearing_axial_not_rated"] == [3]
    # the dynamic factors alone (tr10c): its P_0 still took F_r alone, silently; now said, naming static_factors
    text = SLOW.replace('kind = "ball"\nlocating = true', 'kind = "ball"\nlocating = true\nfactors = { e = 0.3, X = 0.56, '
                        'Y = 1.5 }', 1)
    said = {w["bearing"]: w["message"] for w in _json(tmp_path, "design", text)["warnings"]
            if w["code"] == "bearing_axial_not_rated"}
    assert sorted(said) == [1, 3] and "no static_factors" in said[1] and "P_0 takes F_r alone" in said[1]
    assert not [w for w in _json(tmp_path, "design", SPUR)["warnings"] if w["code"] == "bearing_axial_not_rated"]


def test_a_point_may_not_set_a_bearing_but_may_heat_the_oil(tmp_path):
    """A duty point's `set` of a bearing key (here its reliability) made L_nm mix a_1 = 0.64 into one level
    while the output reported the first point's a_1 = 1 and reliability 90 %: exit 2 naming duty[1] now. The oil's
    temperature per point stays: the light point at 90 °C has its own kappa (ASTM D341, ν_1 at 750 r/min)."""
    hot = SPUR.replace('name = "light"\nhours = 6000\n',
                       'name = "light"\nhours = 6000\nset = { "lubricant.temperature_C" = 90 }\n')
    res = _run(tmp_path, "life", hot.replace('"lubricant.temperature_C" = 90',
                                             '"lubricant.temperature_C" = 90, "bearing[0].reliability_percent" = 95'),
               "--static", "--format", "json")
    assert res.exit_code == 2 and "duty[1]" in res.output and "bearing[0].reliability_percent" in res.output
    b = _json(tmp_path, "life", hot, "--static")["life"]["bearings"][0]
    assert_allclose(b["kappa_points"], [_nu(70, 68, 8.7) / _nu1(1500, 60), _nu(90, 68, 8.7) / _nu1(750, 60)],
                    rtol=1e-12)
