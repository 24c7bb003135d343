"""A torque drive against a fan load approaches its operating speed on the rigid-body mode the load law damps,
tau = J_eff / c_eff; the linearised chain also has the train's neutral angle mode, an eigenvalue at the eigensolver's
noise (seen: -4e-10 1/s). That noise was taken for the slowest mode: the window was called "not settled" by a mode
of "time constant 2.41e+09 s, longer than the window", with no settle time, where the 0.41 s mode explains the
approach and says when it is settled.

Hand reference (one helical stage 21/83, m_n 3, beta 14 deg, eta 0.985; input 0.012 kg m^2, load 1.5 kg m^2; the
wheels as steel discs of their pitch diameters and face widths): the drive gives 25 N m where the load needs
80 / (i eta) at the nominal 1500 rpm, so the train settles at n = 1500 sqrt(25 i eta / 80) = 1654.49 rpm; there the
fan's dT/dw at the output is 2 T_L / w_out, reflected to the input / (i^2 eta), against J_eff = J_in + J_1 +
(J_2 + J_L) / (i^2 eta): tau = 0.412 s.
"""

from __future__ import annotations

import json
import math
import re

import numpy as np
from click.testing import CliRunner

from gearcli.cli import cli
from gearcli.simulate.settle import Settling, _speed_approach
from tests.reference.test_report_motor_theory import SCENE as MOTOR_SCENE

# the motor-theory scene's stage, materials and load, its run 3 s long, on a torque drive and with a fan load
SCENE = MOTOR_SCENE.split("[input]")[0].replace("duration_s = 1.2", "duration_s = 3.0").replace(
    "load = { torque_Nm = 80,", "load = { torque_Nm = 80, speed_exponent = 2,") + """[input]
drive = "torque"
speed_rpm = 1500
torque_Nm = 25
inertia_kg_m2 = 0.012
coupling_stiffness_Nm_rad = 1.5e4
coupling_damping_Nms_rad = 2
"""
assert "speed_exponent = 2" in SCENE and "duration_s = 3.0" in SCENE

I, ETA = 83 / 21, 0.985


def _hand() -> tuple[float, float]:
    """(operating speed rpm, rigid-mode time constant s) of the scene, by hand."""
    g = 25.0 * I * ETA / 80.0  # the load at the operating point over the nominal
    n = 1500.0 * math.sqrt(g)
    w_out = n * math.pi / 30.0 / I
    c_in = 2.0 * 80.0 * g / w_out / (I * I * ETA)
    disc = [7850 * math.pi * b * d**4 / 32 for d, b in ((21 * 3e-3 / math.cos(math.radians(14)), 0.045),
                                                         (83 * 3e-3 / math.cos(math.radians(14)), 0.040))]
    j_eff = 0.012 + disc[0] + (disc[1] + 1.5) / (I * I * ETA)
    return n, j_eff / c_in


def test_the_approach_is_named_by_the_load_laws_mode_not_the_neutral_one(tmp_path):
    path = tmp_path / "fan.toml"
    path.write_text(SCENE, encoding="utf-8")
    out = tmp_path / "s.json"
    res = CliRunner().invoke(cli, ["simulate", str(path), "--format", "json", "-o", str(out), "-q"])
    assert res.exit_code in (0, 1), res.output
    doc = json.loads(out.read_text(encoding="utf-8"))
    msg = next(w["message"] for w in doc["warnings"] if w["code"] == "window_not_settled")
    n, tau = _hand()
    stated = [float(x) for x in re.findall(r"time constant ([0-9.e+-]+) s", msg)]
    assert stated and all(abs(x - tau) <= 0.03 * tau for x in stated), (msg, tau)
    about = float(re.search(r"about ([0-9.]+) rpm", msg).group(1))
    assert abs(about - n) <= 1.0, (about, n)
    assert doc["summary"]["steady"]["settle_time_s"] is not None  # the fit says when it is settled


def _approach(t, w_op=100.0, b=3.0, sigma=2.4, slope=0.0):
    return w_op + b * np.exp(-sigma * (t - t[0])) + slope * (t - t[0])


def test_a_noise_eigenvalue_is_neutral_and_never_a_time_constant():
    t = np.linspace(0.6, 3.0, 2001)
    lam = np.array([-4e-10, -2.4, -50 + 3e4j, -50 - 3e4j])
    got = _speed_approach(t, _approach(t), lam, (0.6, 3.0), Settling(True, 0.0))
    assert not got.settled and got.settle_time_s is not None
    assert abs(got.transient_fraction - 0.03) < 1e-6  # b / w_op of the fitted decay
    assert "time constant 0.417 s" in got.cause
    # a speed creeping on the neutral mode alone (a balanced drive): the drift across the window names it
    got = _speed_approach(t, _approach(t, b=0.0, slope=1.0), lam[[0, 2, 3]], (0.6, 3.0), Settling(True, 0.0))
    assert not got.settled and "neutral" in got.cause and "e+09" not in got.cause
    assert got.settle_time_s is None  # no decay to fit: no settle time
    # only the neutral mode, and no drift: settled
    got = _speed_approach(t, _approach(t, b=0.0), lam[[0, 2, 3]], (0.6, 3.0), Settling(True, 0.0))
    assert got.settled


def test_reports_theory_is_the_torque_drives_balance(tmp_path):
    """`report`'s theory for this torque drive (tr18a's theory point, its torque-drive half): the input speed at the
    balance, 1654.49 rpm, and F_t = T_in / r_1 (at the balance the drive's torque is what the load takes), where the
    nominal point's F_t is the load's 80 N m / (i eta) / r_1."""
    from gearcli import api

    path = tmp_path / "fan.toml"
    path.write_text(SCENE, encoding="utf-8")
    loaded = api.load(str(path), [])
    rep = api.report_file(loaded, api.design(loaded), quick=True)
    n, _ = _hand()
    rows = {(r.stage, r.quantity): r for r in rep.comparison}
    assert rep.theory_point is not None and rep.theory_point.drive == "torque"
    assert abs(rows[(None, "input_speed_deg_s")].theory - 6.0 * n) <= 1e-6 * 6.0 * n
    r1 = 21 * 3e-3 / math.cos(math.radians(14)) / 2
    assert abs(rows[(1, "tangential_N")].theory - 25.0 / r1) <= 1e-7 * 25.0 / r1
    assert abs(rows[(1, "tangential_N")].error_percent) < 0.1  # the lengthened, settled run meets it
