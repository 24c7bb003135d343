"""A planetary stage keeps its books (issue 30, item 3): its efficiency is lost in the planet
meshes, in the design and in the dynamics alike, and its moment balance T_sun + T_carrier + T_ring = 0 holds with
losses. Every expected number is a hand calculation written out here:

- the basic (carrier-held) efficiency eta_0 from the stage's power efficiency eta by the textbook formulas of each
  arrangement (u = z_r/z_s): sun in, ring held: eta = (1 + eta_0 u)/(1 + u); carrier in, ring held (the power
  flows ring -> sun in the carrier's frame): eta = (1 + u)/(1 + u/eta_0); carrier held, either way: eta = eta_0;
  sun held, ring in: eta = (u + eta_0)/(1 + u); sun held, carrier in: eta = eta_0 (1 + u)/(1 + eta_0 u);
- the torques of the mixer train (configs/mixer_planetary_motor.toml: planetary 18/45/108 x3, ring held, sun in,
  eta 0.98, then helical 17/121, eta 0.985): T_sun = T_L / (7 x 121/17 x 0.98 x 0.985), |T_ring| = eta_0 u T_sun,
  |T_carrier| = T_sun + |T_ring|;
- an unexcited, settled, motor-driven run: the window means of every mesh's F_t and of the input torque equal the
  design's static values (a law of conservation of the mean: the mean of the dynamic forces is the static
  balance). The mesh law is stated ([contact]), so these do not depend on the default law; the means are
  law-independent anyway.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli
from gearcli.design.planetary_balance import balance, mesh_efficiency

ROOT = Path(__file__).resolve().parents[2]
MIXER = str(ROOT / "configs" / "mixer_planetary_motor.toml")
Z_S, Z_P, Z_R = 18, 45, 108
U = Z_R / Z_S
ETA, ETA_2 = 0.98, 0.985
T_LOAD = 23172.0  # the tests' constant load (set below)
T_LOAD_FILE = 23195.46  # the file's: the motor's rated torque 482.29 N m x 49.82 x 0.98 x 0.985
RATIO = (1 + U) * 121 / 17


def run(*args):
    return CliRunner().invoke(cli, list(args), catch_exceptions=False)


def design_json(*sets):
    res = run("design", MIXER, "--format", "json", *sum((["--set", s] for s in sets), []))
    assert res.exit_code == 0, res.stderr
    return json.loads(res.stdout)


# ------------------------------------------------------------------------------------------ the balance
@pytest.mark.parametrize(("fixed", "driven", "stage_efficiency"), [
    ("ring", "sun", lambda e0: (1 + e0 * U) / (1 + U)),
    ("ring", "carrier", lambda e0: (1 + U) / (1 + U / e0)),
    ("carrier", "sun", lambda e0: e0),
    ("carrier", "ring", lambda e0: e0),
    ("sun", "ring", lambda e0: (U + e0) / (1 + U)),
    ("sun", "carrier", lambda e0: e0 * (1 + U) / (1 + e0 * U)),
])
def test_basic_efficiency_of_every_arrangement_by_the_textbook_formula(fixed, driven, stage_efficiency):
    eta_m = mesh_efficiency(Z_S, Z_R, fixed, driven, 0.97, "k")
    assert_allclose(stage_efficiency(eta_m ** 2), 0.97, rtol=1e-12)  # the bisection reaches the closed form
    b = balance(Z_S, Z_R, fixed, driven, eta_m)
    assert_allclose(sum(b.torques.values()), 0.0, atol=1e-14)  # the friction forces are internal
    assert b.torques[driven] > 0  # the driven member's external torque runs with it


def test_design_moment_balance_and_member_torques_by_hand():
    doc = design_json(f"load.torque_Nm={T_LOAD}")
    st = doc["stages"][0]
    eta_0 = ((1 + U) * ETA - 1) / U  # sun in, ring held
    t_sun = T_LOAD / (RATIO * ETA * ETA_2)  # N m, the motor's torque at the sun
    t_ring = eta_0 * U * t_sun
    t_carrier = t_sun + t_ring
    assert_allclose(st["basic_efficiency"], eta_0, rtol=1e-12)
    assert_allclose(st["mesh_efficiency"], math.sqrt(eta_0), rtol=1e-12)
    assert_allclose(doc["input_torque_Nmm"] / 1000, t_sun, rtol=1e-12)
    assert_allclose([st["sun"]["torque_Nm"], st["ring"]["torque_Nm"], st["carrier"]["torque_Nm"]],
                    [t_sun, t_ring, t_carrier], rtol=1e-12)
    assert_allclose(t_carrier, (1 + U) * ETA * t_sun, rtol=1e-12)  # the carrier: the stage's efficiency
    # |T_ring| = |T_carrier| - |T_sun| (the acceptance's form) and the signed balance
    assert_allclose(st["ring"]["torque_Nm"], st["carrier"]["torque_Nm"] - st["sun"]["torque_Nm"], rtol=1e-9)
    m = st["moment_balance_Nm"]
    assert m["sun"] > 0 > m["carrier"] and m["ring"] > 0  # signed in the sun's (input's) running sense
    assert abs(m["sun"] + m["carrier"] + m["ring"]) <= 1e-9 * abs(m["carrier"])
    # the lossless ring torque (z_r/z_s) T_sun was 1/eta_0 - 1 = 2.4 % off
    assert abs(st["ring"]["torque_Nm"] / (U * t_sun) - 1) > 0.02


def test_the_ring_mesh_carries_eta_m_times_the_sun_mesh_force():
    st = design_json()["stages"][0]
    sun, ring = (m["static_force_N"]["tangential"] for m in st["meshes"])
    eta_m = st["mesh_efficiency"]
    r_s = 0.5 * Z_S * 3.0  # mm, x = 0: pitch = working radius
    assert_allclose(sun, st["sun"]["torque_Nm"] * 1000 / (3 * r_s), rtol=1e-12)  # the sun drives: its side
    assert_allclose(ring, eta_m * sun, rtol=1e-12)
    # the ring's reaction over its planets: N r_r eta_m F_pr = |T_ring|
    assert_allclose(3 * 0.5 * Z_R * 3.0 * eta_m * ring / 1000, st["ring"]["torque_Nm"], rtol=1e-12)


def test_a_reversed_load_flows_back_through_the_same_meshes():
    """Load reversed: the power flows carrier -> sun, the ring drives in the carrier's frame, so the stage's
    efficiency is (1 + u) eta_0... written out: |T_carrier| = (1 + u/eta_0) |T_sun| and P_sun/P_carrier."""
    doc = design_json("load.torque_Nm=-20000", "load.speed_exponent=0")
    st = doc["stages"][0]
    eta_0 = ((1 + U) * ETA - 1) / U
    t_carrier = -20000.0 / (121 / 17) * ETA_2  # the helical stage, reversed: T_p = T_g eta / i
    t_sun = abs(t_carrier) / (1 + U / eta_0)
    assert_allclose(doc["input_torque_Nmm"] / 1000, -t_sun, rtol=1e-12)
    m = st["moment_balance_Nm"]
    assert abs(sum(m.values())) <= 1e-9 * abs(t_carrier)


# ------------------------------------------------------------------------------------------ the dynamics
SETTLED = (f"load.torque_Nm={T_LOAD}", "load.speed_exponent=0", "load.ramp_s=0.3", "load.coupling_damping_Nms_rad=7e4",
           "simulation.duration_s=4", "simulation.engine=python", "contact.stiffness=iso6336",
           "contact.exponent=1", "contact.damping_ratio=0.05")


def test_unexcited_motor_run_keeps_the_design_books(tmp_path):
    """Window means of every mesh (six planet meshes, the helical mesh) and the input torque equal `design`'s
    static values within 1e-4 (they were 1.44 % = 1 - eta low before the planet meshes lost power); the energy
    balance closes with the losses counted as dissipation."""
    sets = sum((["--set", s] for s in SETTLED), [])
    out = tmp_path / "sim.json"
    res = run("simulate", MIXER, "--format", "json", "-o", str(out), *sets)
    assert res.exit_code == 0, res.stderr
    sim = json.loads(out.read_text())
    des = design_json(*SETTLED)
    planetary, helical = sim["summary"]["stages"]
    f_sun, f_ring = (m["static_force_N"]["tangential"] for m in des["stages"][0]["meshes"])
    for p in planetary["planets"]:
        assert_allclose(abs(p["sun"]["tangential_N"]["mean"]), f_sun, rtol=1e-4)
        assert_allclose(abs(p["ring"]["tangential_N"]["mean"]), f_ring, rtol=1e-4)
    assert_allclose(abs(helical["tangential_N"]["mean"]), des["stages"][1]["static_force_N"]["tangential"], rtol=1e-4)
    assert_allclose(sim["summary"]["input_torque_Nm"], des["input_torque_Nmm"] / 1000, rtol=1e-4)
    assert sim["solver"]["energy_residual"] < 1e-6


def test_the_mesh_loss_dissipates_what_the_stage_loses(tmp_path):
    """Power in minus power out over the settled window equals the losses the stages' efficiencies give:
    P_in (1 - eta eta_2) with the mean input torque and speed of the run."""
    sets = sum((["--set", s] for s in SETTLED), [])
    out = tmp_path / "sim.json"
    res = run("simulate", MIXER, "--format", "json", "-o", str(out), *sets)
    assert res.exit_code == 0, res.stderr
    s = json.loads(out.read_text())["summary"]
    p_in = s["input_power_kW"]
    p_out = T_LOAD * s["output_speed_rpm"] * math.pi / 30 / 1000  # constant load torque at the output speed
    assert_allclose(p_out / p_in, ETA * ETA_2, rtol=1e-4)


def test_the_mixer_file_as_written_keeps_its_books(tmp_path):
    """configs/mixer_planetary_motor.toml unchanged (its load proportional to speed, its own [contact]-free law:
    means do not depend on the law): the load torque is set where the motor's rated point carries it, so the
    motor settles at the design's 1485 rpm and every mean equals the design's static value within 1e-4."""
    assert_allclose(T_LOAD_FILE / (RATIO * ETA * ETA_2), 75000 / (1485 * math.pi / 30), rtol=1e-6)
    out = tmp_path / "sim.json"
    res = run("simulate", MIXER, "--format", "json", "-o", str(out), "--set", "simulation.engine=python")
    assert res.exit_code == 0, res.stderr
    sim = json.loads(out.read_text())["summary"]
    des = design_json()
    f_sun, f_ring = (m["static_force_N"]["tangential"] for m in des["stages"][0]["meshes"])
    for p in sim["stages"][0]["planets"]:
        assert_allclose(abs(p["sun"]["tangential_N"]["mean"]), f_sun, rtol=1e-4)
        assert_allclose(abs(p["ring"]["tangential_N"]["mean"]), f_ring, rtol=1e-4)
    assert_allclose(abs(sim["stages"][1]["tangential_N"]["mean"]), des["stages"][1]["static_force_N"]["tangential"],
                    rtol=1e-4)
    assert_allclose(sim["input_torque_Nm"], des["input_torque_Nmm"] / 1000, rtol=1e-4)
