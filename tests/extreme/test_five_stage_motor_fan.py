"""A five-stage reducer started direct-on-line by an induction motor on a fan load, checked by hand (trial tr19c).

Scene (written here): configs/extreme/five_stages.toml's gears with the default mesh law (ISO 6336-1 calibrated,
viscous damping ratio 0.05), a 6 um transmission error on every mesh, a 15 kW / 1460 rpm motor (Kloss curve) behind
a soft 3000 N m/rad coupling and a fan load of 3500 N m at the nominal output speed (speed_exponent = 2). The motor
settles at its own slip, not at the nameplate speed, so the load torque is the fan law's at the speed reached.

Hand reference (independent of the simulation's force laws): with the simulated window-mean input speed n, the
fan's torque T_L = 3500 (n / 1460)^2 N m; the rigid train carries it back to every pinion, T_k = T_L / prod_{j>=k} i_j
(i_j = z_gear / z_pinion, no losses), and the pinion's pitch radius r_k = z m_n / (2 cos beta) gives the static
tangential force F_t,k = T_k / r_k. The window mean of every stage's F_t must equal it within the mean's target
(1e-4): measured 2.6e-5 on stage 1 (2715.81 N against 2715.74 N by hand), the rest below 1e-5. The motor-side
figures are checked the same way: the window-mean input torque times the ratio is the fan torque at that speed.
"""

from __future__ import annotations

import math

import pytest

from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.simulate import run_simulation

# (m_n mm, beta deg, z_pinion, z_gear) as in configs/extreme/five_stages.toml
STAGES = ((3, 15, 20, 41), (4, 14, 19, 40), (6, 13, 18, 39), (8, 12, 17, 37), (12, 10, 17, 35))
FACES = ((40, 38), (55, 52), (80, 76), (110, 105), (160, 150))
HANDS = (("left", "right"), ("right", "left"))
NOMINAL_RPM = 1460.0
FAN_NM = 3500.0


def _scene() -> str:
    parts = ['title = "five stages, DOL motor, fan load"']
    for k, ((mn, beta, zp, zg), (bp, bg)) in enumerate(zip(STAGES, FACES, strict=True)):
        hp, hg = HANDS[k % 2]
        parts.append(f"""[[stage]]
normal_module_mm = {mn}
normal_pressure_angle_deg = 20
helix_angle_deg = {beta}
pinion = {{ teeth = {zp}, face_width_mm = {bp}, hand = "{hp}" }}
gear   = {{ teeth = {zg}, face_width_mm = {bg}, hand = "{hg}" }}""")
    parts.append(f"""[contact]
transmission_error_um = [6]
[input]
speed_rpm = {NOMINAL_RPM}
drive = "motor"
motor = {{ rated_power_kW = 15, rated_speed_rpm = {NOMINAL_RPM}, synchronous_speed_rpm = 1500, breakdown_torque_ratio = 2.8, locked_rotor_torque_ratio = 2.3 }}
starting = "direct"
inertia_kg_m2 = 0.09
coupling_stiffness_Nm_rad = 3000
coupling_damping_Nms_rad = 0.5
[load]
torque_Nm = {FAN_NM}
speed_exponent = 2
[simulation]
duration_s = 1.0
steps = 4000
method = "DOP853"
""")
    return "\n".join(parts)


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    path = tmp_path_factory.mktemp("tr19c") / "five_motor_fan.toml"
    path.write_text(_scene())
    cfg = load_design(str(path), []).design
    return run_simulation(cfg, compute_design(cfg), want_series=False)


def test_window_mean_forces_are_the_fan_torque_at_the_speed_reached(run):
    n_in = run.input_speed_deg_s / 6.0  # rpm
    assert 1460.0 < n_in < 1500.0  # a motor at its slip, between nameplate and synchronous speed
    load_Nm = FAN_NM * (n_in / NOMINAL_RPM) ** 2
    for k, (mn, beta, zp, _zg) in enumerate(STAGES):
        ratio_after = math.prod(zg / zp for (_m, _b, zp, zg) in STAGES[k:])
        r_k_m = zp * mn / (2.0 * math.cos(math.radians(beta))) / 1000.0
        hand_N = load_Nm / ratio_after / r_k_m
        assert run.stages[k].tangential_N.mean == pytest.approx(hand_N, rel=1e-4), f"stage {k + 1}"


def test_the_train_ratio_and_the_motor_torque_follow_the_rigid_train(run):
    total = math.prod(zg / zp for (_m, _b, zp, zg) in STAGES)
    # the window-mean speed ratio also carries the deflections' change over the window as the fan load still creeps
    # up with the speed (1.6e-5 here): within 1e-4
    assert run.ratio == pytest.approx(total, rel=1e-4)
    n_in = run.input_speed_deg_s / 6.0
    motor = run.extra["motor"]
    assert motor["mean_torque_Nm"] * total == pytest.approx(FAN_NM * (n_in / NOMINAL_RPM) ** 2, rel=1e-4)
