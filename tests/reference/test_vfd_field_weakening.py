"""A frequency converter above its motor's base speed (trial tr20d): field weakening, against hand figures.

A converter's output voltage is capped at the motor's rated voltage, reached at the rated frequency (the
nameplate's synchronous speed n_B). Above it V/f, the flux, falls as n_B / n_s and the torque at a given slip
speed as its square: the curve is k T(Δ) with k = (n_B / n_s)², the breakdown slip speed unchanged (textbook
equivalent circuit, stator resistance neglected), and the motor's continuous rating is its rated power
(the constant-power range): T_cont = P_r / ω_r' at the speed ω_r' where the supply puts the rated slip.
Before, the model kept constant V/f at any frequency: a 50 Hz motor on 60 Hz had its full breakdown torque,
and at twice its base speed it carried loads it cannot.

Scene: tests/reference/data/motor_poles/conveyor_6pole_37kW.toml (37 kW, 985 rpm, 1000 rpm synchronous, T_b/T_r
2.5, T_l/T_r 2.0; one 63/21 stage, η 0.98; a constant 632 N·m drum torque) on a VFD. Hand: the extended Kloss
curve of docs/physics.md, fitted here by brentq on s_b with a from the locked-rotor point (linear in a); the
supply n_s' = n_s + (speed_rpm − n_r) (docs/physics.md); the operating point by brentq.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose
from scipy.optimize import brentq

from gearcli.cli import cli

CONVEYOR = Path(__file__).parent / "data" / "motor_poles" / "conveyor_6pole_37kW.toml"
RPM = math.pi / 30.0
P_R, N_R, N_S, KB, KL = 37e3, 985.0, 1000.0, 2.5, 2.0
T_R = P_R / (N_R * RPM)  # 358.70 N m
RATIO, ETA = 63 / 21, 0.98


def _kloss(s: float, sb: float, a: float) -> float:
    return 2 * KB * T_R * (1 + a * sb) * s * sb / (s * s + sb * sb + 2 * a * sb * sb * abs(s))


def _a_of(sb: float) -> float:
    # T(1) = k_l T_r: 2 k_b (1 + a s_b) s_b = k_l (1 + s_b² + 2 a s_b²), linear in a
    return (KL * (1 + sb * sb) - 2 * KB * sb) / (2 * KB * sb * sb - 2 * KL * sb * sb)


S_R = 1 - N_R / N_S
SB = brentq(lambda sb: _kloss(S_R, sb, _a_of(sb)) - T_R, S_R * 1.0001, 0.9999, xtol=1e-15)
A = _a_of(SB)


def _curve(n_supply: float, n: float) -> float:
    """The motor's torque at n rpm on a supply of synchronous speed n_supply: the nameplate's curve in slip speed,
    scaled by (n_B / n_supply)² above the base speed n_B = N_S."""
    k = min(1.0, (N_S / n_supply) ** 2)
    return k * _kloss((n_supply - n) / N_S, SB, A)


def _invoke(command: str, *sets: str) -> dict:
    args = ["-q", command, str(CONVEYOR), "--format", "json", "--set", 'input.starting="vfd"',
            "--set", "input.ramp_s=3"]
    for s in sets:
        args += ["--set", s]
    res = CliRunner().invoke(cli, args)
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def _checks(doc: dict, check: str) -> list[dict]:
    return [w for w in doc["warnings"] if w.get("check") == check or w["code"] == check]


def test_the_hand_curve_passes_the_nameplate_points():
    assert _kloss(S_R, SB, A) == pytest.approx(T_R, rel=1e-10)
    assert _kloss(1.0, SB, A) == pytest.approx(KL * T_R, rel=1e-10)
    assert _kloss(SB, SB, A) == pytest.approx(KB * T_R, rel=1e-10)


def test_a_vfd_at_60_hz_on_a_50_hz_motor_runs_where_its_weakened_curve_meets_the_load():
    # speed_rpm 1185: supply 1200 rpm synchronous (60 Hz on a 1000 rpm six-pole 50 Hz motor), k = (1000/1200)²
    n_supply = N_S + 1185.0 - N_R
    load = 632.0 / (RATIO * ETA)  # 214.97 N m at the motor
    n_op = brentq(lambda n: _curve(n_supply, n) - load, n_supply - SB * N_S, n_supply - 1e-9, xtol=1e-11)
    n_vf = brentq(lambda n: _kloss((n_supply - n) / N_S, SB, A) - load, n_supply - SB * N_S, n_supply - 1e-9)
    assert n_op < n_vf - 4.0  # 1.44x the slip speed of constant V/f: 1187.0 rpm, not 1191.0
    doc = _invoke("simulate", "input.speed_rpm=1185")
    motor = doc["summary"]["motor"]
    assert motor["synchronous_speed_rpm"] == pytest.approx(n_supply, rel=1e-12)
    assert motor["operating_point_rpm"] == pytest.approx(n_op, abs=1e-6)
    assert motor["operating_speed_rpm"] == pytest.approx(n_op, abs=0.05)  # the window's mean: the 140 kg m² drum


def test_the_motor_torque_follows_the_weakened_curve_through_the_ramp():
    # the series: at each sample the supply's synchronous speed is n_s' STEP(t / 3 s), the curve scaled by
    # (n_B / n_s(t))² once n_s(t) passes the base speed (no limit: the torque is the bare curve)
    res = CliRunner().invoke(cli, ["-q", "simulate", str(CONVEYOR), "--format", "json", "--series",
                                   "--set", 'input.starting="vfd"', "--set", "input.ramp_s=3",
                                   "--set", "input.speed_rpm=1385"])
    assert res.exit_code == 0, res.output
    series = json.loads(res.stdout)["series"]
    t = np.asarray(series["time_s"])
    n = np.asarray(series["motor_speed_rpm"])
    tq = np.asarray(series["motor_torque_Nm"])
    x = np.clip(t / 3.0, 0.0, 1.0)
    n_s = (N_S + 1385.0 - N_R) * x * x * (3 - 2 * x)
    hand = np.array([_curve(ns, ni) if ns > 0 else 0.0 for ns, ni in zip(n_s, n, strict=True)])
    assert_allclose(tq, hand, rtol=1e-7, atol=1e-6)
    above = n_s > N_S
    assert above.sum() > 100 and (tq[above] < _kloss((n_s[above] - n[above]) / N_S, SB, A)).all()


def test_above_the_base_speed_the_rating_is_the_rated_power():
    # 950 N m on the drum: 323.1 N m at the motor, below its rated torque 358.7 N m (no warning at 985 rpm) but
    # above the rated power at 1185 rpm, P_r / (1185 rpm) = 298.16 N m: 1.084x
    load = 950.0 / (RATIO * ETA)
    assert _checks(_invoke("design", "load.torque_Nm=950", "input.speed_rpm=985"), "motor_overloaded") == []
    found = _checks(_invoke("design", "load.torque_Nm=950", "input.speed_rpm=1185"), "motor_overloaded")
    assert len(found) == 1
    cont = P_R / (1185.0 * RPM)
    assert found[0]["rated_torque_Nm"] == pytest.approx(cont, rel=1e-12)
    assert found[0]["overload_ratio"] == pytest.approx(load / cont, rel=1e-3)  # at the operating point's load
    assert "field weakening" in found[0]["message"]


def test_at_twice_its_base_speed_the_motor_cannot_carry_what_it_carries_at_base():
    # supply 2200 rpm: breakdown k T_b = (1000/2200)² 2.5 x 358.7 = 185.3 N m, below the 214.97 N m load
    load = 632.0 / (RATIO * ETA)
    assert (N_S / 2200.0) ** 2 * KB * T_R < load
    doc = _invoke("design", "input.speed_rpm=2185")
    found = _checks(doc, "motor_cannot_start")
    assert len(found) == 1, doc["warnings"]
    weakened = (N_S / 2200.0) ** 2 * KB * T_R  # 185.3 N m
    assert "weakens the field" in found[0]["message"] and f"= {weakened:.4g} N·m" in found[0]["message"]
    assert not _checks(_invoke("design", "input.speed_rpm=1185"), "motor_cannot_start")
