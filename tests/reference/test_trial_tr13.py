"""Trial tr13: scenes of a first-time user's own, against hand calculations written here.

A spur 11/400 stage (m_n 1 mm, b 10 mm) behind a speed drive, a linear ISO-calibrated mesh (exponent 1,
ζ = 0.02), 20 N·m on the output and a 0.05 µm first-harmonic transmission error, run at the mesh's natural
frequency. By hand:

- F_t = T_out / (i r_1) = 20 N·m / (400/11 · 5.5 mm) = 100 N;
- ISO 6336-1: z_n = z (spur), q′ = 0.04723 + 0.15551/11 + 0.25791/400, c′ = (1/q′) 0.8 · 0.975 · (F_t/b / 100)^0.25
  (F_t/b = 10 N/mm < 100), ε_α from the tip circles, c_γα = c′ (0.75 ε_α + 0.25), k = c_γα b (spur: k_n = k_t);
- the gear alone moves (the pinion's speed is prescribed): m_e = J_g / r_b2², ω_n = √(k / m_e);
- at r = 1 the steady response to a base excitation E: the mesh force's dynamic part is
  k E √(1 + (2ζ)²) / (2ζ) along the line of action, F_t = F_bt cos α_t; it exceeds the static 100 N, so the
  force reverses: without backlash the back flank takes it at once, nothing is crossed and nothing strikes.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

Z1, Z2, MN, B, J_G = 11, 400, 1.0, 10.0, 1e-2
ALPHA = math.radians(20.0)
TORQUE_NM, E_UM, ZETA = 20.0, 0.05, 0.02


def _hand() -> tuple[float, float, float]:
    """(static F_t in N, mesh stiffness k in N/m, natural frequency in Hz), by hand."""
    r1, r2 = Z1 * MN / 2, Z2 * MN / 2  # mm
    ft = TORQUE_NM * 1e3 / (Z2 / Z1) / r1
    rb1, rb2 = r1 * math.cos(ALPHA), r2 * math.cos(ALPHA)
    a = r1 + r2
    eps = (math.sqrt((r1 + MN) ** 2 - rb1**2) + math.sqrt((r2 + MN) ** 2 - rb2**2) - a * math.sin(ALPHA)) / (
        math.pi * MN * math.cos(ALPHA))
    q = 0.04723 + 0.15551 / Z1 + 0.25791 / Z2
    c1 = (1 / q) * 0.8 * 0.975 * (ft / B / 100) ** 0.25
    k = c1 * (0.75 * eps + 0.25) * B * 1e6  # N/(mm um) * mm -> N/m
    m_e = J_G / (rb2 * 1e-3) ** 2
    return ft, k, math.sqrt(k / m_e) / (2 * math.pi)


def _scene(tmp_path: Path, speed_rpm: float, backlash_mm: float = 0.0, e_um: float = E_UM) -> Path:
    path = tmp_path / "reversal.toml"
    path.write_text(f"""
title = "tr13 zero-backlash force reversal"
[[stage]]
normal_module_mm = {MN}
backlash_mm = {backlash_mm}
pinion = {{ teeth = {Z1}, face_width_mm = {B}, inertia_kg_m2 = 1e-7 }}
gear = {{ teeth = {Z2}, face_width_mm = {B}, inertia_kg_m2 = {J_G} }}
[contact]
stiffness = "iso6336"
exponent = 1.0
damping_ratio = {ZETA}
transmission_error_um = [{e_um}]
[input]
speed_rpm = {speed_rpm}
[load]
torque_Nm = {TORQUE_NM}
[simulation]
duration_s = 0.06
window_start_s = 0.04
""")
    return path


def test_zero_backlash_force_reversal_at_resonance_is_no_impact(tmp_path):
    ft, k, fn = _hand()
    assert_allclose(ft, 100.0, rtol=1e-12)
    rpm = fn * 60 / Z1  # the mesh frequency on the natural frequency: r = 1
    out = CliRunner().invoke(cli, ["simulate", str(_scene(tmp_path, rpm)), "--format", "json", "-q"])
    assert out.exit_code == 0, out.output
    doc = json.loads(out.stdout)
    assert_allclose(doc["summary"]["natural_frequencies_Hz"][0], fn, rtol=1e-6)
    st = doc["summary"]["stages"][0]
    amplitude = k * E_UM * 1e-6 * math.sqrt(1 + (2 * ZETA) ** 2) / (2 * ZETA) * math.cos(ALPHA)  # of F_t
    assert amplitude > ft  # the force reverses
    # the window (from 0.04 s: 19 time constants 1/(ζ ω_n) after the start) is settled to exp(-19) ~ 1e-8
    assert_allclose(st["tangential_N"]["max"], ft + amplitude, rtol=2e-3)
    assert_allclose(st["tangential_N"]["min"], ft - amplitude, rtol=2e-2)
    # time on the back flank: where 100 + A sin < 0, a fraction acos(100 / A) / π of the period
    assert_allclose(st["back_flank_fraction"], math.acos(ft / amplitude) / math.pi, atol=0.01)
    assert st["contact_loss_fraction"] == 0.0
    # no gap to cross: no impact (the contact_loss warning says the force reverses, and says "no impact")
    assert st["regime"] == "no impact"
    assert "contact_loss" in [w["code"] for w in doc["warnings"]]


def test_the_same_reversal_across_a_backlash_is_double_sided(tmp_path):
    _, _, fn = _hand()
    # a 0.5 µm gap and 10 times the excitation (the gap's softening keeps 0.05 µm on the drive flank): the teeth
    # leave the drive flank, cross the gap and strike the back one
    path = _scene(tmp_path, fn * 60 / Z1, backlash_mm=0.0005, e_um=10 * E_UM)
    out = CliRunner().invoke(cli, ["simulate", str(path), "--format", "json", "-q"])
    assert out.exit_code == 0, out.output
    st = json.loads(out.stdout)["summary"]["stages"][0]
    assert st["back_flank_fraction"] > 0.0 and st["contact_loss_fraction"] > 0.0
    assert st["regime"] == "double-sided impact"


def test_a_start_that_cannot_finish_within_the_run_says_so(tmp_path):
    """A 30 kW four-pole DOL motor (breakdown 2.8 T_r) on a 4 kg m² flywheel: by hand, the start to 98 % of the
    synchronous speed takes at least J ω / T_b (the largest torque the curve gives, nothing resisting), far beyond
    a 0.4 s run: the warning must say the start does not finish within the run, not that it "reaches" it."""
    t_rated = 30e3 / (1470 * math.pi / 30)
    bound_s = 4.0 * 0.98 * 1470 * math.pi / 30 / (2.8 * t_rated)
    assert bound_s > 1.0  # 1.1 s (0.98 of the rated speed, below the operating one): more than twice the run
    path = tmp_path / "flywheel.toml"
    path.write_text("""
title = "tr13 flywheel start"
[[stage]]
normal_module_mm = 3
helix_angle_deg = 15
pinion = { teeth = 20, face_width_mm = 50, hand = "left" }
gear = { teeth = 80, face_width_mm = 45, hand = "right" }
[input]
speed_rpm = 1470
drive = "motor"
motor = { rated_power_kW = 30, rated_speed_rpm = 1470, synchronous_speed_rpm = 1500, breakdown_torque_ratio = 2.8, locked_rotor_torque_ratio = 2.5 }
starting = "direct"
inertia_kg_m2 = 4.0
coupling_stiffness_Nm_rad = 2e4
coupling_damping_Nms_rad = 10
[load]
torque_Nm = 1.0
[simulation]
duration_s = 0.4
""")
    out = CliRunner().invoke(cli, ["simulate", str(path), "--format", "json", "-q"])
    assert out.exit_code == 0, out.output
    doc = json.loads(out.stdout)
    assert doc["summary"]["start_time_s"] is None
    (msg,) = [w["message"] for w in doc["warnings"] if w["code"] == "start_not_settled"]
    assert "does not reach 98 % of its operating speed within the run (to 0.4 s)" in msg, msg


def test_a_planet_pin_bearing_on_a_stage_that_does_not_exist_says_so(tmp_path):
    """planet_stage = 3 on a two-stage parallel train named "stage 3 is not a planetary stage": there is no stage 3."""
    path = tmp_path / "two.toml"
    path.write_text("""
[[stage]]
normal_module_mm = 3
pinion = { teeth = 20, face_width_mm = 40, axial_position_mm = 100 }
gear = { teeth = 60, face_width_mm = 40, axial_position_mm = 100 }
[[stage]]
normal_module_mm = 4
pinion = { teeth = 20, face_width_mm = 50, axial_position_mm = 200 }
gear = { teeth = 60, face_width_mm = 50, axial_position_mm = 200 }
[input]
speed_rpm = 1000
[load]
torque_Nm = 500
[[bearing]]
planet_stage = 1
position_mm = 50
dynamic_load_rating_kN = 50
kind = "roller"
locating = true
[[bearing]]
planet_stage = 1
position_mm = 150
dynamic_load_rating_kN = 50
kind = "roller"
""")
    for k, expected in ((1, "stage 1 is not a planetary stage"), (3, "stage 3 does not exist: this train has stages 1 to 2")):
        res = CliRunner().invoke(cli, ["design", str(path), "--set", f"bearing.0.planet_stage={k}",
                                       "--set", f"bearing.1.planet_stage={k}"])
        assert res.exit_code == 2, res.output
        assert "bearing[0].planet_stage" in res.stderr and expected in res.stderr, res.stderr
        assert "Traceback" not in res.stderr


INCREASER = """
title = "tr13 speed increaser 97/23, beta 30"
[[stage]]
normal_module_mm = 2.5
helix_angle_deg = 30
pinion = { teeth = 97, face_width_mm = 40, hand = "right" }
gear   = { teeth = 23, face_width_mm = 42, hand = "left" }
[contact]
exponent = 1.0
transmission_error_um = [0.2]
[input]
speed_rpm = 3000
ramp_s = 0.05
[load]
torque_Nm = 50
ramp_s = 0.05
[simulation]
duration_s = 0.2
"""


def test_sweep_points_calibrate_the_mesh_at_their_own_load(tmp_path):
    """A speed increaser (the 97-tooth wheel drives the 23-tooth one at 3000 rpm, β = 30°) with 0.2 µm of TE, swept
    over the output torque: each point's ISO mesh stiffness has its own load correction (F_t/b < 100 N/mm at 20 and
    50 N·m, none at 200 N·m), so its natural frequency, hence its response at the 4850 Hz mesh frequency, moves with
    the load. By hand per point: c′ = (1/q′) 0.8 · 0.975 · cos β · min(1, F_t/b/100)^0.25 with ISO's index 1 the
    smaller wheel, k_t = c′ (0.75 ε_α + 0.25) b, m_e = J_g / r_b2² (the driving wheel's speed is prescribed; J_g the
    23-tooth pitch disc of its own 42 mm face, the default steel of 7800 kg/m³), modal ζ = 0.05 / cos β_b, and the base-excitation response
    max F_t = F_t + k_t E r² √(1 + (2ζr)²) / |1 − r² + 2iζr| cos α_t."""
    path = tmp_path / "increaser.toml"
    path.write_text(INCREASER)
    out = CliRunner().invoke(cli, ["sweep", str(path), "--vary", "load.torque_Nm=20,50,200", "--format", "json", "-q"])
    assert out.exit_code == 0, out.output
    doc = json.loads(out.stdout)
    rows = doc["rows"] if isinstance(doc, dict) else doc
    mn, an, b = 2.5, math.radians(20), math.radians(30)
    at = math.atan(math.tan(an) / math.cos(b))
    bb = math.atan(math.tan(b) * math.cos(at))
    mt = mn / math.cos(b)
    d1, d2 = 97 * mt, 23 * mt
    rb1, rb2 = d1 / 2 * math.cos(at), d2 / 2 * math.cos(at)
    a = (d1 + d2) / 2
    eps = (math.sqrt((d1 / 2 + mn) ** 2 - rb1**2) + math.sqrt((d2 / 2 + mn) ** 2 - rb2**2) - a * math.sin(at)) / (
        math.pi * mt * math.cos(at))
    cbb = math.cos(bb)
    zn = [z / (cbb**2 * math.cos(b)) for z in (23, 97)]
    q = 0.04723 + 0.15551 / zn[0] + 0.25791 / zn[1]
    m_e = 7800 * math.pi * 0.042 * (d2 * 1e-3) ** 4 / 32 / (rb2 * 1e-3) ** 2
    zeta = 0.05 / cbb
    assert len(rows) == 3
    for row in rows:
        torque = row["load.torque_Nm"]
        ft = torque * 1e3 / (d2 / 2)
        kt = (1 / q) * 0.8 * 0.975 * math.cos(b) * min(1.0, ft / 40 / 100) ** 0.25 * (0.75 * eps + 0.25) * 40 * 1e6
        r = 97 * 3000 / 60 / (math.sqrt(kt / m_e) / (2 * math.pi))
        amp = kt * 0.2e-6 * r**2 * math.sqrt(1 + (2 * zeta * r) ** 2) / math.hypot(1 - r**2, 2 * zeta * r) * math.cos(at)
        assert_allclose(row["stage1_tangential_N_max"], ft + amp, rtol=1e-4, err_msg=f"{torque} N·m")


HOIST = """
title = "tr13 hoist 30 kW star-delta"
[[stage]]
normal_module_mm = 3
helix_angle_deg = 15
efficiency = 0.98
pinion = { teeth = 20, face_width_mm = 50, hand = "left" }
gear   = { teeth = 80, face_width_mm = 45, hand = "right" }
[[stage]]
normal_module_mm = 5
helix_angle_deg = 10
efficiency = 0.98
pinion = { teeth = 18, face_width_mm = 90, hand = "right" }
gear   = { teeth = 90, face_width_mm = 85, hand = "left" }
[input]
speed_rpm = 1470
drive = "motor"
motor = { rated_power_kW = 30, rated_speed_rpm = 1470, synchronous_speed_rpm = 1500, breakdown_torque_ratio = 2.8, locked_rotor_torque_ratio = 2.5 }
starting = "star_delta"
switch_speed_rpm = 1400
inertia_kg_m2 = 0.25
coupling_stiffness_Nm_rad = 1.2e4
coupling_damping_Nms_rad = 8
[load]
torque_Nm = 3000
[simulation]
duration_s = 1.0
"""


def test_set_starting_compares_starts_on_a_star_delta_file(tmp_path):
    """`--set input.starting=direct` on a star-delta file was exit 2 ("switch_speed_rpm: not a parameter of starting =
    direct"), and no --set can remove a key: comparing starts needed an edited file. By hand: T_r = 30 kW / 1470 rpm
    = 194.9 N·m; the load reflected to the motor 3000 / 20 / 0.98² = 156.2 N·m; in star a third of the curve, whose
    breakdown 2.8 T_r / 3 = 181.9 N·m leaves it stalled below the 1400 rpm switch-over (design says so), while
    direct-on-line starts from 2.5 T_r = 487 N·m; the rigid drivetrain then needs at least
    J_eq 0.98 ω_s / (T_b − T_L) to reach 98 % of its speed."""
    path = tmp_path / "hoist.toml"
    path.write_text(HOIST)
    t_r = 30e3 / (1470 * math.pi / 30)
    t_load = 3000 / 20 / 0.98**2
    assert 2.8 * t_r / 3 < t_load * 1.2 and 2.5 * t_r > 3 * t_load
    star = CliRunner().invoke(cli, ["design", str(path), "--format", "json"])
    assert star.exit_code == 0, star.output
    assert any(w.get("check") == "motor_cannot_start" for w in json.loads(star.stdout)["warnings"])
    out = CliRunner().invoke(cli, ["simulate", str(path), "--set", "input.starting=direct", "--format", "json", "-q"])
    assert out.exit_code == 0, out.output
    doc = json.loads(out.stdout)
    assert not [w for w in doc["warnings"] if w["code"] in ("motor_stalls", "start_not_settled")]
    def disc(z: int, mn: float, beta_deg: float, b_mm: float) -> float:  # solid steel disc of the pitch diameter
        return 7800 * math.pi * b_mm * 1e-3 * (z * mn / math.cos(math.radians(beta_deg)) * 1e-3) ** 4 / 32

    j_down = disc(20, 3, 15, 50) + (disc(80, 3, 15, 45) + disc(18, 5, 10, 90)) / 16 + disc(90, 5, 10, 85) / 400
    j_eq = 0.25 + j_down / 0.98**2  # the rotor, and the train behind its losses (f = 1/η)
    lower = j_eq * 0.98 * 1500 * math.pi / 30 / (2.8 * t_r - t_load)
    assert lower < doc["summary"]["start_time_s"] < 1.0
    # a sweep over the starting method: every point its own method's parameters
    sw = CliRunner().invoke(cli, ["sweep", str(path), "--vary", "input.starting=direct,star_delta", "--set",
                                  "input.switch_speed_rpm=1200", "--format", "json", "-q"])
    assert sw.exit_code == 0, sw.output
    rows = json.loads(sw.stdout)["rows"]
    assert [r["status"] for r in rows] == ["ok", "ok"], rows
