"""A duty point on a table load (``[load] torque_speed``, the driven machine's characteristic) keeps the table's
shape, scaled to the point's torque at the point's nominal output speed, as a speed law keeps its exponent.

The defect: each point is the base file with ``--set load.torque_Nm=…``, and a torque key replaces the table (one
torque key), so every point of a mixer with a measured characteristic ran against a constant torque: a start from
rest met the full torque at standstill (a 200 kW mixer's run-up took 5.1 s for 3.3 s, its start classes a sun
pitting damage of 2e-6 for 1e-11), and a motor settled where its curve meets a constant load, not the machine's.

Reference (by hand, docs/physics.md "Motor and load characteristics"): the extended Kloss curve of the nameplate
meets the scaled table reflected to the motor, T_L(n/i) / (i η), at the operating speed; the window's force is the
table's torque there, so the point's largest class force over its static force at the point's torque is
T_L(n_op/i) / T_point (the old constant torque gave exactly 1). The point's K_v refers to the load the run applies
(simulate's dynamic factor, since 2026-12-01): 1 on this unexcited, settled window."""

from __future__ import annotations

import json
import math

from numpy.testing import assert_allclose

from gearcli import api

P_R, N_R, N_S, K_B, K_L = 15.0, 1460.0, 1500.0, 2.8, 2.2  # the nameplate
TABLE = [[0.0, 50.0], [300.0, 200.0], [500.0, 600.0]]  # output rpm, N m
Z1, Z2, ETA = 21, 67, 0.98
T_POINT, N_POINT = 250.0, 1460.0

SCENE = f"""
title = "table-load mixer, one helical stage"
materials.steel = {{ density_kg_m3 = 7850, youngs_modulus_MPa = 206000, poisson_ratio = 0.3, treatment = "case_carburized", contact_fatigue_limit_MPa = 1500, bending_fatigue_limit_MPa = 500 }}
lubricant = {{ viscosity_40C_mm2_s = 220 }}
rating = {{ required_life_h = 1000 }}
input = {{ speed_rpm = {N_R}, drive = "motor", starting = "direct", inertia_kg_m2 = 0.08, coupling_stiffness_Nm_rad = 3000, coupling_damping_Nms_rad = 1, motor = {{ rated_power_kW = {P_R}, rated_speed_rpm = {N_R}, synchronous_speed_rpm = {N_S}, breakdown_torque_ratio = {K_B}, locked_rotor_torque_ratio = {K_L} }} }}
load = {{ torque_speed = {TABLE}, inertia_kg_m2 = 5, coupling_stiffness_Nm_rad = 2e5, coupling_damping_Nms_rad = 50 }}
[[stage]]
pinion = {{ teeth = {Z1}, face_width_mm = 40, hand = "left", material = "steel", flank_roughness_Rz_um = 3, root_roughness_Rz_um = 10 }}
normal_module_mm = 3
gear = {{ teeth = {Z2}, face_width_mm = 38, hand = "right", material = "steel", flank_roughness_Rz_um = 3, root_roughness_Rz_um = 10 }}
helix_angle_deg = 12
accuracy_grade = 6
efficiency = {ETA}
[[duty]]
name = "batch"
hours = 1000
torque_Nm = {T_POINT}
speed_rpm = {N_POINT}
starts = 10
"""


def _table(speed: float, scale: float = 1.0) -> float:
    """The table's torque at an output speed (linear between its points)."""
    for (n0, t0), (n1, t1) in zip(TABLE, TABLE[1:], strict=False):
        if speed <= n1:
            return scale * (t0 + (t1 - t0) * (speed - n0) / (n1 - n0))
    raise AssertionError(speed)


def _kloss():
    """T(n) of the extended Kloss curve through the nameplate's rated, breakdown and locked-rotor points."""
    t_r = P_R * 1e3 / (N_R * math.pi / 30)
    t_b, s_r = K_B * t_r, 1 - N_R / N_S

    def curve(s, sb, a):
        return 2 * t_b * (1 + a * sb) * s * sb / (s * s + sb * sb + 2 * a * sb * sb * abs(s))

    def a_of(sb):  # T(1) = K_L T_r, linear in a
        return (K_L * t_r * (1 + sb * sb) - 2 * t_b * sb) / (2 * t_b * sb * sb - 2 * K_L * t_r * sb * sb)

    lo, hi = s_r * 1.0001, 0.9999
    for _ in range(200):  # s_b from the rated point by bisection
        mid = 0.5 * (lo + hi)
        if (curve(s_r, lo, a_of(lo)) - t_r) * (curve(s_r, mid, a_of(mid)) - t_r) <= 0:
            hi = mid
        else:
            lo = mid
    sb = 0.5 * (lo + hi)
    return lambda n: curve(1 - n / N_S, sb, a_of(sb))


def test_the_point_keeps_the_table_scaled_to_its_torque(tmp_path):
    from gearcli.life.duty import DutyPoint, with_load_table

    path = tmp_path / "m.toml"
    path.write_text(SCENE, encoding="utf-8")
    cfg = api.load(str(path)).design
    (point,) = with_load_table(cfg, [DutyPoint("batch", 1000.0, T_POINT, N_POINT)])
    i = Z2 / Z1
    scale = T_POINT / _table(N_POINT / i)
    own = api.load(str(path), point.overrides()).design
    assert own.load.torque_Nm is None
    assert_allclose(own.load.torque_speed, [[n, t * scale] for n, t in TABLE], rtol=1e-15)
    assert_allclose(own.load.torque_Nm_value, T_POINT, rtol=1e-12)  # the design's static load: the point's torque
    idle = with_load_table(cfg, [DutyPoint("idle", 10.0, 0.0, N_POINT)])[0]
    assert idle.sets == ()  # idling: no load, the constant zero torque


def test_a_motor_point_settles_where_its_curve_meets_the_table(tmp_path):
    from click.testing import CliRunner

    from gearcli.cli import cli

    path = tmp_path / "m.toml"
    path.write_text(SCENE, encoding="utf-8")
    res = CliRunner().invoke(cli, ["life", str(path), "--format", "json", "-q"])
    assert res.exit_code == 0, res.output
    (point,) = json.loads(res.stdout)["life"]["points"]
    i = Z2 / Z1
    scale = T_POINT / _table(N_POINT / i)
    motor = _kloss()
    lo, hi = 0.8 * N_S, N_S * (1 - 1e-9)  # the operating speed: the motor's curve meets the reflected table
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if motor(mid) - _table(mid / i, scale) / (i * ETA) > 0:
            lo = mid
        else:
            hi = mid
    load_factor = _table(0.5 * (lo + hi) / i, scale) / T_POINT
    assert load_factor > 1.005  # the motor runs above the point's speed into a rising characteristic
    r_1 = Z1 * 3.0 / math.cos(math.radians(12.0)) / 2.0 / 1e3  # pinion pitch radius [m] (m_n 3 mm, β 12°)
    static_N = T_POINT / (i * ETA) / r_1  # the point's static F_t at its torque, by hand
    bins = json.loads(res.stdout)["life"]["stages"][0]["pinion"]["pitting"]["bins"]
    window = [b["force_N"] for b in bins if b["point"] == "batch"]  # not its start's classes ("batch (start)")
    assert_allclose(max(window) / static_N, load_factor, rtol=2e-4)
    assert_allclose(point["K_v"][0], 1.0, atol=5e-4)  # over the static force of the load the run applies
