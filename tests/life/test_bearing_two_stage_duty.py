"""The two-stage reducer of test_bearing_two_stage.py over a three-point duty (``life --static``), every bearing
figure by hand (docs/bearings.md, docs/life.md):

- static route: each point's reactions scale with its torque (600, 300, 900 N m), so P_i = P_600 T_i / 600;
- revolutions per point U_i = 60 n_i h_i (the bearing's shaft speed), the equivalent load over the duty the
  p-mean over revolutions, P = (sum U_i P_i^p / sum U_i)^(1/p), p = 3 ball, 10/3 roller;
- kappa = nu / nu_1: nu at 65 C by ASTM D341 (log10 log10(nu + 0.7) linear in log10 T) through VG 150's 150 and
  14.5 mm2/s; nu_1 = 45000 n^-0.83 d_m^-0.5 (n < 1000 r/min), 4500 n^-0.5 d_m^-0.5 (n >= 1000), ISO 281 6.5.2.4;
- e_C "slight" (ISO 281 Table 13, lower end): 0.3 below d_m = 100 mm, 0.4 from it;
- a_ISO by ISO 281 eq. (8)-(13) with the (c, e) of kappa's branch; a_1 = 0.64 at 95 %, 0.25 at 99 % (Table 12);
- L_nm = sum U_i / sum(U_i / (a_1 a_ISO,i (C / P_i)^p)), L_nmh at the duty's mean speed;
- s_0 = C_0 / max_i max(F_r, X_0 F_r + Y_0 F_a) (ISO 76).
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
treatment = "case_carburized"
contact_fatigue_limit_MPa = 1500
bending_fatigue_limit_MPa = 500

[rating]
required_life_h = 8000

[[stage]]
normal_module_mm = 2
normal_pressure_angle_deg = 20
helix_angle_deg = 15
accuracy_grade = 6
pinion = { teeth = 20, face_width_mm = 30, material = "steel", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 12, hand = "right", axial_position_mm = 40 }
gear   = { teeth = 60, face_width_mm = 28, material = "steel", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 12, hand = "left", axial_position_mm = 40 }

[[stage]]
normal_module_mm = 3
normal_pressure_angle_deg = 20
helix_angle_deg = 12
accuracy_grade = 6
center_angle_deg = 90
pinion = { teeth = 18, face_width_mm = 40, material = "steel", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 12, hand = "left", axial_position_mm = 110 }
gear   = { teeth = 54, face_width_mm = 38, material = "steel", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 12, hand = "right", axial_position_mm = 110 }

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
static_load_rating_kN = 11
static_factors = { X0 = 0.6, Y0 = 0.5 }
fatigue_load_limit_kN = 0.5
pitch_diameter_mm = 46
reliability_percent = 95
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
static_load_rating_kN = 55
static_factors = { X0 = 0.5, Y0 = 0.8 }
fatigue_load_limit_kN = 7
pitch_diameter_mm = 110
reliability_percent = 99
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

[lubricant]
viscosity_40C_mm2_s = 150
viscosity_100C_mm2_s = 14.5
temperature_C = 65
contamination = "slight"

[[duty]]
name = "a"
hours = 1000
torque_Nm = 600
speed_rpm = 1450
[[duty]]
name = "b"
hours = 3000
torque_Nm = 300
speed_rpm = 900
[[duty]]
name = "c"
hours = 500
torque_Nm = 900
speed_rpm = 600
"""

TORQUES = (600.0, 300.0, 900.0)
SPEEDS = (1450.0, 900.0, 600.0)  # input r/min
HOURS = (1000.0, 3000.0, 500.0)


def _run(tmp_path, command):
    path = tmp_path / "duty.toml"
    path.write_text(SCENE)
    args = [command, str(path), "--format", "json"] + (["--static"] if command == "life" else [])
    res = CliRunner().invoke(cli, args)
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout[res.stdout.index("{"):])


def _nu(t_c):
    """ASTM D341 through (40 C, 150) and (100 C, 14.5) mm2/s."""
    w = [math.log10(math.log10(v + 0.7)) for v in (150.0, 14.5)]
    lt = [math.log10(t + 273.15) for t in (40.0, 100.0)]
    slope = (w[1] - w[0]) / (lt[1] - lt[0])
    return 10.0 ** (10.0 ** (w[0] + slope * (math.log10(t_c + 273.15) - lt[0]))) - 0.7


def _nu1(n, dm):
    return 45000.0 * n ** -0.83 * dm ** -0.5 if n < 1000.0 else 4500.0 * n ** -0.5 * dm ** -0.5


def _a_iso(kind, kappa, x):
    """ISO 281:2007 eq. (8)-(13), x = e_C C_u / P, kappa in [0.1, 4]."""
    branch = 0 if kappa < 0.4 else (1 if kappa < 1.0 else 2)
    if kind == "ball":
        c, e = [(2.2649, 0.054381), (1.9987, 0.19087), (1.9987, 0.071739)][branch]
        inner = 1.0 - (2.5671 - c / kappa ** e) ** 0.83 * x ** (1.0 / 3.0)
        return min(50.0, 0.1 * inner ** -9.3)
    c, e = [(1.3993, 0.054381), (1.2348, 0.19087), (1.2348, 0.071739)][branch]
    inner = 1.0 - (1.5859 - c / kappa ** e) * x ** 0.4
    return min(50.0, 0.1 * inner ** -9.185)


def _expected(design_b, j, ratio, kind, c_n, cu_n, dm, e_c, a1, c0_n, x0, y0):
    p = 3.0 if kind == "ball" else 10.0 / 3.0
    loads = [design_b["equivalent_load_N"] * t / 600.0 for t in TORQUES]
    speeds = [n / ratio for n in SPEEDS]
    revs = [60.0 * n * h for n, h in zip(speeds, HOURS, strict=True)]
    p_eq = (sum(u * q ** p for u, q in zip(revs, loads, strict=True)) / sum(revs)) ** (1.0 / p)
    nu = _nu(65.0)
    kappas = [nu / _nu1(n, dm) for n in speeds]
    a_isos = [_a_iso(kind, min(k, 4.0), e_c * cu_n / q) for k, q in zip(kappas, loads, strict=True)]
    l_nm = sum(revs) / sum(u / (a1 * a * (c_n / q) ** p) for u, a, q in zip(revs, a_isos, loads, strict=True))
    n_mean = sum(revs) / (60.0 * sum(HOURS))
    fr, fa = design_b["radial_N"] * 1.5, abs(design_b["axial_N"]) * 1.5  # the 900 N m point
    s0 = c0_n / max(fr, x0 * fr + y0 * fa)
    l10 = (c_n / p_eq) ** p
    return {"revolutions": sum(revs), "equivalent_load_N": p_eq, "L10_Mrev": l10,
            "L10_h": l10 * 1e6 / (60.0 * n_mean), "kappa_points": kappas, "kappa": min(kappas),
            "a_ISO_points": a_isos, "a_1": a1, "L_nm_Mrev": l_nm, "L_nm_h": l_nm * 1e6 / (60.0 * n_mean),
            "a_ISO": l_nm / (a1 * l10), "static_safety": s0}


def test_duty_modified_life_and_static_safety_by_hand(tmp_path):
    design = _run(tmp_path, "design")["bearings"]
    life = _run(tmp_path, "life")["life"]["bearings"]
    cases = [
        (0, 1.0, "ball", 20e3, 500.0, 46.0, 0.3, 0.64, 11e3, 0.6, 0.5),
        (3, 3.0, "roller", 60e3, 7e3, 110.0, 0.4, 0.25, 55e3, 0.5, 0.8),
    ]
    for j, *args in cases:
        want = _expected(design[j], j, *args)
        for key, value in want.items():
            # rtol 1e-9: the same closed forms; ASTM D341 carried in double precision both ways
            assert_allclose(life[j][key], value, rtol=1e-9, err_msg=f"bearing {j} {key}")


def test_design_kappa_and_a_iso_by_hand(tmp_path):
    b = _run(tmp_path, "design")["bearings"]
    # bearing 0 at 1450 r/min (n >= 1000 branch), kappa in [1, 4]: the ball's third branch
    kappa = _nu(65.0) / (4500.0 / math.sqrt(1450.0 * 46.0))
    assert 1.0 <= kappa <= 4.0
    assert_allclose(b[0]["kappa"], kappa, rtol=1e-9)
    a = _a_iso("ball", kappa, 0.3 * 500.0 / b[0]["equivalent_load_N"])
    assert_allclose(b[0]["a_ISO"], a, rtol=1e-9)
    assert_allclose(b[0]["L_nm_Mrev"], 0.64 * a * b[0]["L10_Mrev"], rtol=1e-9)
    # bearing 3 at 483.3 r/min (n < 1000 branch)
    kappa = _nu(65.0) / (45000.0 * (1450.0 / 3.0) ** -0.83 / math.sqrt(110.0))
    assert_allclose(b[3]["kappa"], kappa, rtol=1e-9)
    assert_allclose(b[3]["a_1"], 0.25, rtol=0)


def test_series_history_gives_the_same_bearing_duty(tmp_path):
    """The same three levels as a measured history (each row holds until the next): equal revolutions and loads,
    so the same p-mean, L10 and L_nm as the [[duty]] tables, order aside."""
    path = tmp_path / "duty.toml"
    path.write_text(SCENE)
    series = tmp_path / "h.csv"
    series.write_text("time_s,torque_Nm,speed_rpm\n0,600,1450\n3600000,300,900\n14400000,900,600\n16200000,900,600\n")
    res = CliRunner().invoke(cli, ["life", str(path), "--static", "--series", str(series), "--format", "json"])
    assert res.exit_code == 0, res.output
    got = json.loads(res.stdout[res.stdout.index("{"):])["life"]["bearings"]
    want = _run(tmp_path, "life")["life"]["bearings"]
    for j in range(6):
        for key in ("revolutions", "equivalent_load_N", "L10_Mrev", "L10_h"):
            # rtol 1e-12: the same levels summed in another order
            assert_allclose(got[j][key], want[j][key], rtol=1e-12, err_msg=f"bearing {j} {key}")
    assert_allclose(got[0]["L_nm_Mrev"], want[0]["L_nm_Mrev"], rtol=1e-12)


def test_reversed_point_recomputes_the_reactions(tmp_path):
    """A point at -300 N m: F_t and F_a change sign, F_r still separates the wheels, so the reactions are not
    those of +300 N m. Bearing 0 (pinion 1 at x = 40 between 0 and 100, right hand, cw): on the pinion
    (-F_a, -F_r, +F_t) at (40, r_1, 0): R_Bz = -0.4 F_t, R_By = (0.4 F_r - F_a r_1 / 100), F_a on bearing 0."""
    path = tmp_path / "duty.toml"
    path.write_text(SCENE.replace("torque_Nm = 300", "torque_Nm = -300"))
    res = CliRunner().invoke(cli, ["life", str(path), "--static", "--format", "json"])
    assert res.exit_code == 0, res.output
    b = json.loads(res.stdout[res.stdout.index("{"):])["life"]["bearings"][0]
    beta = math.radians(15.0)
    d1 = 2.0 * 20 / math.cos(beta)
    f_t = 2.0 * 300e3 / 9.0 / d1
    f_r = f_t * math.tan(math.atan(math.tan(math.radians(20.0)) / math.cos(beta)))
    f_a = f_t * math.tan(beta)
    rb_y, rb_z = (0.4 * f_r - f_a * d1 / 2.0 / 100.0), -0.4 * f_t
    fr = math.hypot(f_r - rb_y, -f_t - rb_z)
    assert f_a / fr > 0.3  # beyond e: P = X F_r + Y F_a
    # rtol 1e-9: closed-form statics both ways
    assert_allclose(b["loads_N"][1], 0.56 * fr + 1.5 * f_a, rtol=1e-9)
