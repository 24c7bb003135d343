"""A speed sweep keeps a speed-dependent load on its law: the load's torque key is its torque at the file's speed
n_0, so a point at n carries T_0 (n / n_0)^p (fan and pump affinity laws, ISO 13348 / ISO 9906), not T_0 at every
speed (the field test: a fan drive swept 500-1450 rpm gave stage 1 F_t = 3035 N at every row).

Reference by hand: one lossless spur stage 20/40 (m = 3 mm, x = 0: r_gear = 60 mm), a prescribed input speed, no
excitation, so each settled row's window-mean F_t is the static force T_L(n) / r_gear exactly (the equilibrium).
"""

from __future__ import annotations

import csv
import io
import math

from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

SCENE = """
[[stage]]
normal_module_mm = 3
normal_pressure_angle_deg = 20
pinion = {{ teeth = 20, face_width_mm = 30, hand = "spur" }}
gear   = {{ teeth = 40, face_width_mm = 30, hand = "spur" }}
[contact]
damping_ratio = 0.1
[input]
speed_rpm = 1200
ramp_s = 0.02
[load]
{load}
speed_exponent = {p}
ramp_s = 0.02
[simulation]
duration_s = 0.2
steps = 400
"""
R_GEAR = 0.5 * 3e-3 * 40  # m


def _sweep(tmp_path, load, p, *vary):
    path = tmp_path / "fan.toml"
    path.write_text(SCENE.format(load=load, p=p))
    res = CliRunner().invoke(cli, ["sweep", str(path), *vary, "--jobs", "1", "-q", "-o", "-"])
    assert res.exit_code == 0, res.output
    return list(csv.DictReader(io.StringIO(res.stdout)))


def test_a_fan_load_follows_the_square_of_the_speed(tmp_path):
    rows = _sweep(tmp_path, "torque_Nm = 200", 2, "--vary", "input.speed_rpm=600,1200,1800")
    for r in rows:
        n = float(r["input.speed_rpm"])
        t_load = 200.0 * (n / 1200.0) ** 2  # N·m: 50, 200, 450
        # the settled equilibrium reproduces the static force to the solver's tolerance (rtol 1e-6)
        assert_allclose(float(r["stage1_tangential_N_mean"]), t_load / R_GEAR, rtol=1e-5)


def test_a_linear_load_a_power_key_and_a_varied_torque_scale_alike(tmp_path):
    rows = _sweep(tmp_path, "torque_Nm = 200", 1, "--vary", "load.torque_Nm=100,300", "--vary",
                  "input.speed_rpm=600,1800")
    for r in rows:  # the varied torque is the load's torque at the file's 1200 rpm
        t_load = float(r["load.torque_Nm"]) * float(r["input.speed_rpm"]) / 1200.0
        assert_allclose(float(r["stage1_tangential_N_mean"]), t_load / R_GEAR, rtol=1e-5)
    # power at the nominal output speed (600 rpm at the gear): 12.566 kW is 200 N·m there; P ∝ n³ on a fan
    rows = _sweep(tmp_path, "power_kW = 12.566370614359172", 2, "--vary", "input.speed_rpm=600,1800")
    for r in rows:
        assert_allclose(float(r["stage1_tangential_N_mean"]),
                        200.0 * (float(r["input.speed_rpm"]) / 1200.0) ** 2 / R_GEAR, rtol=1e-5)


def test_a_constant_load_is_the_same_torque_at_every_speed_given_by_torque_or_by_power(tmp_path):
    for load in ("torque_Nm = 200", "power_kW = 12.566370614359172"):  # 200 N·m at the file's 600 rpm output
        rows = _sweep(tmp_path, load, 0, "--vary", "input.speed_rpm=600,1800")
        for r in rows:
            assert_allclose(float(r["stage1_tangential_N_mean"]), 200.0 / R_GEAR, rtol=1e-5)


def _iso_k_n_N_mm(f_t_N: float) -> float:
    """ISO 6336-1 k_n = c_γα b (spur: cos β_b = 1) of the scene's 20/40 m 3 b 30 stage at the static force F_t, by
    hand from DESIGN section 3: q' polynomial (x = 0), C_M 0.8, C_R 1, C_B 0.975, the load correction below
    100 N/mm, c_γα = c' (0.75 ε_α + 0.25)."""
    m, b, alpha = 3.0, 30.0, math.radians(20.0)
    r1, r2 = 30.0, 60.0
    rb1, rb2 = r1 * math.cos(alpha), r2 * math.cos(alpha)
    eps_a = (math.sqrt((r1 + m) ** 2 - rb1**2) + math.sqrt((r2 + m) ** 2 - rb2**2) - (r1 + r2) * math.sin(alpha)) / (
        math.pi * m * math.cos(alpha))
    c_prime = 0.8 * 0.975 / (0.04723 + 0.15551 / 20 + 0.25791 / 40) * min(1.0, f_t_N / b / 100.0) ** 0.25
    return c_prime * (0.75 * eps_a + 0.25) * b * 1e3


def test_a_fan_loads_mesh_law_is_calibrated_at_each_points_own_load(tmp_path):
    """DESIGN section 13: K follows the static load of each sweep point; with a fan law that load is T_0 (n/n_0)^2
    (section 9), so the default law (iso6336, e = 1.5) settles at h_0 = e F_n / k_n(F_t) of that torque: the row's
    window-mean DTE (spur: q = h) in µm. A K calibrated at the file's 200 N·m instead would give (F_n / K_0)^(2/3)."""
    rows = _sweep(tmp_path, "torque_Nm = 200", 2, "--vary", "input.speed_rpm=600,1800")
    k0 = _iso_k_n_N_mm(200.0 / R_GEAR)
    big_k0 = (200.0 / R_GEAR / math.cos(math.radians(20.0))) / (1.5 * 200.0 / R_GEAR / math.cos(math.radians(20.0))
                                                                  / k0) ** 1.5
    for r in rows:
        f_t = 200.0 * (float(r["input.speed_rpm"]) / 1200.0) ** 2 / R_GEAR  # 833 N (27.8 N/mm: corrected), 7500 N
        f_n = f_t / math.cos(math.radians(20.0))
        h0_um = 1.5 * f_n / _iso_k_n_N_mm(f_t) * 1e3
        assert_allclose(float(r["stage1_dte_um_mean"]), h0_um, rtol=1e-5)
        assert abs((f_n / big_k0) ** (1 / 1.5) * 1e3 / h0_um - 1) > 0.05  # the test tells the two apart


def test_a_load_varied_in_another_unit_or_with_its_exponent_stays_the_points_own(tmp_path):
    """A point's load is the one its own keys give, whichever unit they use: a file that says `torque_Nm` swept with
    `--vary load.torque_Nmm` (or `load.power_kW`) and the speed runs each point at T_0 (n/n_0)^p of the varied value
    (field test: every row ran at the file's torque, the varied one silently replaced by the law's own key), and a
    varied `load.speed_exponent` is the point's p (a fan's file swept at p = 0 is a constant torque; a constant
    torque's file swept at p = 2 a fan). By hand: the settled equilibrium's F_t = T_L(n) / r_gear."""
    rows = _sweep(tmp_path, "torque_Nm = 200", 2, "--vary", "load.torque_Nmm=1e5,3e5", "--vary",
                  "input.speed_rpm=600,1800")
    for r in rows:  # 100 and 300 N·m at 1200 rpm: 25, 225, 75, 675 N·m
        t_load = float(r["load.torque_Nmm"]) * 1e-3 * (float(r["input.speed_rpm"]) / 1200.0) ** 2
        assert_allclose(float(r["stage1_tangential_N_mean"]), t_load / R_GEAR, rtol=1e-5)
    # 6.2832 kW at the file's 600 rpm output is 100 N·m there; a power key goes as n^(p+1), its torque as n^p
    rows = _sweep(tmp_path, "torque_Nm = 200", 1, "--vary", "load.power_kW=6.283185307179586", "--vary",
                  "input.speed_rpm=600,1800")
    for r in rows:
        assert_allclose(float(r["stage1_tangential_N_mean"]),
                        100.0 * float(r["input.speed_rpm"]) / 1200.0 / R_GEAR, rtol=1e-5)
    for p_file in (0, 2):
        rows = _sweep(tmp_path, "torque_Nm = 200", p_file, "--vary", "load.speed_exponent=0,2", "--vary",
                      "input.speed_rpm=600,1800")
        for r in rows:
            p = int(r["load.speed_exponent"])
            assert_allclose(float(r["stage1_tangential_N_mean"]),
                            200.0 * (float(r["input.speed_rpm"]) / 1200.0) ** p / R_GEAR, rtol=1e-5)


def test_a_point_whose_law_puts_the_load_out_of_bounds_says_the_law_did(tmp_path):
    # power_kW = 600 at 1200 rpm on a fan law (P ∝ n³): at 20000 rpm the law gives 600 x (20000/1200)³ = 2.78e6 kW,
    # beyond the schema's 1e6. The row failed with "load.power_kW: must be ≤ 1000000, got 2777777.7", a key the user
    # never set; it now says the file's load was scaled to the point's speed on its law, with the value it set.
    path = tmp_path / "fan.toml"
    path.write_text(SCENE.format(load="power_kW = 600", p=2))
    res = CliRunner().invoke(cli, ["sweep", str(path), "--vary", "input.speed_rpm=20000", "--jobs", "1", "-q",
                                   "-o", "-"])
    assert res.exit_code == 1, res.output
    (row,) = list(csv.DictReader(io.StringIO(res.stdout)))
    assert row["status"] == "failed"
    by_hand = 600.0 * (20000.0 / 1200.0) ** 3
    assert row["message"].startswith("load.power_kW: must be ≤ 1000000")
    assert "speed on its speed law" in row["message"]
    assert_allclose(float(row["message"].rsplit("load.power_kW=", 1)[1].rstrip(")")), by_hand, rtol=1e-12)
