"""A load table (``[load] torque_speed``) read past its last speed: the design, a duty point's scaled table and the
model take it the same way, its last segment extended (docs/physics.md; the model's table law,
``gearcli.model.elements.machine``).

The defect: the design (``DesignFile``'s torque at the nominal output speed) and ``gearcli.life.duty.with_load_table``
(the reference a point's table is scaled by) read the table with ``numpy.interp``, which holds the last torque
constant past the last speed, while the model extends the last segment. A fan table measured up to 163 rpm and a
point at 165.36 rpm of the output: the design rated 7800 N·m where the run carried 7957 N·m (2 % more force in every
window than the design's static force), and the duty point of 8000 N·m ran at 8161 N·m: an unexcited model's
"dynamic" spectrum stood 2.0 % above its static force (K_v 1.0201) and rated the point at a load it was not given.

Reference (by hand): T(n) = T_a + (T_b − T_a)(n − n_a)/(n_b − n_a) on the last segment (n_a, T_a)–(n_b, T_b) for
n > n_b; the output speed n_in z_1/z_2; F_t = T / r_2 at the gear's reference circle (spur, no shift).
"""

from __future__ import annotations

import json
import math

from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli import api
from gearcli.cli import cli
from gearcli.life.duty import DutyPoint, with_load_table

Z1, Z2, M_N = 23, 71, 4.0
TABLE = [[0.0, 600.0], [20.0, 1200.0], [40.0, 2000.0], [48.0, 2600.0]]  # output rpm, N m: a fan's, to 48 rpm
N_IN, T_POINT = 160.0, 2700.0  # 160 rpm in: 51.83 rpm out, past the table's last speed

SCENE = f"""
title = "a fan past its measured table"

[[stage]]
normal_module_mm = {M_N}
accuracy_grade = 6
pinion = {{ teeth = {Z1}, face_width_mm = 50, material = "carb", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 16 }}
gear = {{ teeth = {Z2}, face_width_mm = 48, material = "carb", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 16 }}

[materials]
carb = {{ treatment = "case_carburized", contact_fatigue_limit_MPa = 1500, bending_fatigue_limit_MPa = 430, density_kg_m3 = 7800, youngs_modulus_MPa = 207000, poisson_ratio = 0.3 }}

[input]
speed_rpm = {N_IN}
ramp_s = 0.1

[load]
torque_speed = {TABLE}
ramp_s = 0.1

[lubricant]
viscosity_40C_mm2_s = 220

[rating]
required_life_h = 1000

[[duty]]
name = "overspeed"
hours = 1000
torque_Nm = {T_POINT}
speed_rpm = {N_IN}
"""


def _extended(n_out: float) -> float:
    """The table's torque past its last speed: its last segment extended."""
    (n_a, t_a), (n_b, t_b) = TABLE[-2], TABLE[-1]
    assert n_out > n_b
    return t_a + (t_b - t_a) * (n_out - n_a) / (n_b - n_a)


N_OUT = N_IN * Z1 / Z2


def test_the_design_reads_the_table_past_its_last_speed_as_the_model_does(tmp_path) -> None:
    path = tmp_path / "fan.toml"
    path.write_text(SCENE)
    st = api.load_and_design(str(path))[1].stages[0]
    assert_allclose(st.gear.torque_Nmm / 1e3, _extended(N_OUT), rtol=1e-12)  # was 2600, the last torque held
    assert_allclose(st.static_force_N.tangential, _extended(N_OUT) * 1e3 / (M_N * Z2 / 2), rtol=1e-12)


def test_a_point_s_table_gives_the_point_s_torque_at_its_speed(tmp_path) -> None:
    path = tmp_path / "fan.toml"
    path.write_text(SCENE)
    cfg = api.load(str(path)).design
    (point,) = with_load_table(cfg, [DutyPoint("overspeed", 1000.0, T_POINT, N_IN)])
    (text,) = [s for s in point.sets if s.startswith("load.torque_speed=")]
    scaled = json.loads(text.split("=", 1)[1])
    scale = T_POINT / _extended(N_OUT)
    assert_allclose(scaled, [[n, t * scale] for n, t in TABLE], rtol=1e-12)  # was scaled by T_POINT / 2600
    (n_a, t_a), (n_b, t_b) = scaled[-2:]
    assert_allclose(t_a + (t_b - t_a) * (N_OUT - n_a) / (n_b - n_a), T_POINT, rtol=1e-12)


def test_the_point_s_run_carries_the_point_s_torque(tmp_path) -> None:
    """End to end: the unexcited run's engagements meet the point's own force (K_v 1, not 1.02)."""
    path = tmp_path / "fan.toml"
    path.write_text(SCENE)
    res = CliRunner().invoke(cli, ["life", str(path), "--format", "json", "-q"])
    assert res.exit_code == 0, res.output
    (point,) = json.loads(res.stdout)["life"]["points"]
    assert_allclose(point["K_v"], [1.0], atol=1e-6)
    bins = json.loads(res.stdout)["life"]["stages"][0]["gear"]["pitting"]["bins"]
    f_t = T_POINT * 1e3 / (M_N * Z2 / 2)
    assert_allclose(max(b["force_N"] for b in bins), f_t, rtol=1e-6)
    assert math.isclose(sum(b["cycles"] for b in bins), 1000 * 60 * N_OUT, rel_tol=1e-12)
