"""The life trial's own duties on one helical stage (tests/life/trial_duties.py), every damage sum and life
checked by hand: cycles per class from speed x hours x contacts, N_i from the ISO 6336-2/-3 S-N curve written out
below, D = sum n_i / N_i, life = sum hours / D. The class stresses are read from ``gearcli design`` at the point's
torque and speed with K_A = 1 (docs/life.md: "exactly what gearcli design ... prints"), an independent command.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli
from gearcli.life.duty import DutyPoint
from gearcli.life.starts import StartData
from gearcli.life.verdicts import starts_warning
from tests.life.trial_duties import MOTOR_DRIVE, SPEED_DRIVE, write

# ISO 6336-2:2006 Table 2 (Z_NT, case-carburized, no pitting permitted) and ISO 6336-3:2006 Table 3 (Y_NT, Eh
# root): static node, knee, 0.85 at 1e10 (normal quality; the "iso" variant continues that last slope)
ZNT = ((1e5, 1.6), (5e7, 1.0), (1e10, 0.85))
YNT = ((1e3, 2.5), (3e6, 1.0), (1e10, 0.85))
RATIO = 67 / 21  # the gear's teeth meet the pinion's 21/67 times per pinion turn


def _n_to_failure(nodes, stress: float, knee_stress: float) -> float:
    """N = N_a (y_a / y)^k on the segment that holds y = stress / knee stress (the finite line continued above the
    static node, the long-life line below the knee)."""
    (n0, y0), (n1, y1), (n2, y2) = nodes
    y = stress / knee_stress
    if y >= y1:
        return n1 * (y1 / y) ** (math.log(n1 / n0) / math.log(y0 / y1))
    return n1 * (y1 / y) ** (math.log(n2 / n1) / math.log(y1 / y2))


def _run(*args: str, code: int = 0):
    res = CliRunner().invoke(cli, ["-q", *args])
    assert res.exit_code == code, res.output
    return res


def _life(path: Path, *extra: str) -> dict:
    return json.loads(_run("life", str(path), "--format", "json", *extra).stdout)


def _rating(path: Path, torque_Nm: float, speed_rpm: float, *extra: str) -> dict:
    """``gearcli design`` of the file at the point's torque and speed, K_A = 1: the stage's rating."""
    doc = json.loads(_run("design", str(path), "--format", "json", "--set", f"load.torque_Nm={torque_Nm!r}",
                          "--set", f"input.speed_rpm={speed_rpm!r}", "--set", "load.application_factor=1",
                          *extra).stdout)
    return doc["stages"][0]["rating"]


def _hand_damage(path: Path, points: list[dict], member: str, mode: str) -> tuple[list[float], list[float]]:
    """(cycles, cycles to failure) per static-route class by hand."""
    cycles, to_failure = [], []
    for p in points:
        r = _rating(path, p["torque_Nm"], p["speed_rpm"])[member]
        if mode == "pitting":
            stress, knee, nodes = r["sigma_H_MPa"], r["sigma_HG_MPa"] / r["Z_NT"], ZNT
        else:
            stress, knee, nodes = r["sigma_F_MPa"], r["sigma_FG_MPa"] / r["Y_NT"], YNT
        turns = p["hours"] * 60.0 * p["speed_rpm"] * (1.0 if member == "pinion" else 1.0 / RATIO)
        cycles.append(turns)
        to_failure.append(_n_to_failure(nodes, stress, knee))
    return cycles, to_failure


def test_a_duty_of_one_point_is_the_plain_rating(tmp_path):
    """One point over the required life (10 000 h at 2000 N.m): the life's spectrum safety on stress is the
    rating's S_H and S_F at K_A = 1 (one class: D(s) = 1 where sigma s meets the curve at n, the rating's N_L), and
    the rating at a required life equal to the life found has S_H = 1."""
    path = write(tmp_path / "one.toml", SPEED_DRIVE, {"name": "only", "hours": 10000.0, "torque_Nm": 2000.0,
                                                      "speed_rpm": 1460.0})
    life = _life(path, "--static")["life"]
    rating = _rating(path, 2000.0, 1460.0)
    for member in ("pinion", "gear"):
        r = rating[member]
        # the rating's load cycles: N_L = 60 n t (one contact per turn)
        assert_allclose(r["load_cycles"], 10000 * 60 * 1460 / (1.0 if member == "pinion" else RATIO), rtol=1e-12)
        for mode, safety in (("pitting", "S_H"), ("bending", "S_F")):
            ml = life["stages"][0][member][mode]
            n, nf = _hand_damage(path, life["points"], member, mode)
            assert_allclose(ml["bins"][0]["cycles"], n[0], rtol=1e-12)
            assert_allclose(ml["bins"][0]["cycles_to_failure"], nf[0], rtol=1e-9)
            assert_allclose(ml["damage"], n[0] / nf[0], rtol=1e-9)
            assert_allclose(ml["stress_safety"], r[safety], rtol=1e-8, err_msg=f"{member} {mode}")
    pinion = life["stages"][0]["pinion"]["pitting"]
    assert pinion["damage"] > 1.0 and not pinion["below_endurance"]  # S_H = 0.9997 < 1: D = 1.009
    assert_allclose(pinion["life_h"], 10000.0 / pinion["damage"], rtol=1e-12)
    again = _rating(path, 2000.0, 1460.0, "--set", f"rating.required_life_h={pinion['life_h']!r}")
    assert_allclose(again["pinion"]["S_H"], 1.0, rtol=1e-9)
    # the verdict: the pinion's flank does not last the duty (S_H 0.9997 below the minimum 1.0, D = 1.009); every
    # other member and mode does (gear flank S_H 1.049, roots S_F 1.82 and 1.84 above 1.4)
    verdicts = [w for w in _life(path, "--static")["warnings"] if w["code"] == "life_safety_low"]
    assert [(w["member"], w["mode"]) for w in verdicts] == [("pinion", "pitting")]
    assert_allclose([verdicts[0]["stress_safety"], verdicts[0]["damage"], verdicts[0]["life_h"]],
                    [pinion["stress_safety"], pinion["damage"], pinion["life_h"]], rtol=1e-12)
    assert verdicts[0]["min_safety"] == 1.0 and verdicts[0]["hours"] == 10000.0
    # a minimum below 1 (0.9): the safety passes it, but D = 1.009 still fails the duty, and says so
    low_min = _life(path, "--static", "--set", "rating.min_safety_pitting=0.9")["warnings"]
    said = [w for w in low_min if w["code"] == "life_safety_low"]
    assert len(said) == 1 and said[0]["min_safety"] == 0.9 and "fails within the duty" in said[0]["message"]


SPECTRUM = [
    # a jam far above the static strength (sigma_H 2440 MPa > 1.6 x the knee's 1496 MPa)
    {"name": "jam", "hours": 0.2, "torque_Nm": 7000.0, "speed_rpm": 1460.0},
    {"name": "normal", "hours": 9000.0, "torque_Nm": 1500.0, "speed_rpm": 1460.0},
    # a bin given in power: T = P / omega_out at the output speed 2900 rpm x 21/67
    {"name": "fast light", "hours": 999.8, "power_kW": 100.0, "speed_rpm": 2900.0},
]


def test_a_spectrum_in_torque_and_power_with_a_class_beyond_the_static_strength(tmp_path):
    path = write(tmp_path / "spectrum.toml", SPEED_DRIVE, *SPECTRUM)
    doc = _life(path, "--static")
    life = doc["life"]
    t_power = 100e3 / (2900.0 * 2 * math.pi / 60 / RATIO)  # 1050.58 N.m
    assert_allclose([p["torque_Nm"] for p in life["points"]], [7000.0, 1500.0, t_power], rtol=1e-12)
    hours = 0.2 + 9000.0 + 999.8
    assert_allclose(life["hours"], hours, rtol=1e-15)
    for member in ("pinion", "gear"):
        for mode in ("pitting", "bending"):
            ml = life["stages"][0][member][mode]
            n, nf = _hand_damage(path, life["points"], member, mode)
            assert_allclose([b["cycles"] for b in ml["bins"]], n, rtol=1e-12)
            assert_allclose([b["cycles_to_failure"] for b in ml["bins"]], nf, rtol=1e-9)
            d = sum(a / b for a, b in zip(n, nf, strict=True))
            assert_allclose(ml["damage"], d, rtol=1e-9)
            assert_allclose(ml["life_h"], hours / d, rtol=1e-9)
    # the jam's 17 520 pinion cycles meet the flank beyond its static node (fewer than 1e5 cycles to failure, the
    # finite slope continued): warned for pitting; the root's jam class (1.57x its knee) stays above its static
    # node of 1e3 cycles
    beyond = [(w["member"], w["mode"]) for w in doc["warnings"] if w["code"] == "beyond_static_strength"]
    assert beyond == [("pinion", "pitting"), ("gear", "pitting")]
    jam = life["stages"][0]["pinion"]["pitting"]["bins"][0]
    assert jam["cycles_to_failure"] < 1e5 and life["stages"][0]["pinion"]["bending"]["bins"][0]["cycles_to_failure"] > 1e3


def test_hours_as_fractions_scale_the_damage_not_the_life(tmp_path):
    """Time shares that do not sum to 1 (0.0475 + 0.57 + 0.3325 = 0.95): D is over the shares' own hours, the life
    in hours and the safety are those of the same duty given in hours (every cycle count scales with one factor)."""
    hours = [(500.0, 0.0475), (6000.0, 0.57), (3500.0, 0.3325)]
    pts = [{"name": f"p{i}", "hours": h, "torque_Nm": t, "speed_rpm": 1460.0}
           for i, ((h, _), t) in enumerate(zip(hours, (2600.0, 1800.0, 900.0), strict=True))]
    full = _life(write(tmp_path / "hours.toml", SPEED_DRIVE, *pts), "--static")["life"]
    share = _life(write(tmp_path / "shares.toml", SPEED_DRIVE,
                        *[{**p, "hours": f} for p, (_, f) in zip(pts, hours, strict=True)]), "--static")["life"]
    scale = 10000.0 / 0.95
    for member in ("pinion", "gear"):
        for mode in ("pitting", "bending"):
            a, b = full["stages"][0][member][mode], share["stages"][0][member][mode]
            assert_allclose(a["damage"], b["damage"] * scale, rtol=1e-9)
            if a["life_h"] is not None:
                assert_allclose(a["life_h"], b["life_h"], rtol=1e-9)
    # the time shares are not the required life (10 000 h): the safety is over 0.95 h, and a warning says so
    said = [w for w in _life(tmp_path / "shares.toml", "--static")["warnings"] if w["code"] == "duty"]
    assert len(said) == 1 and said[0]["hours"] == pytest.approx(0.95) and said[0]["required_life_h"] == 10000.0
    assert not [w for w in _life(tmp_path / "hours.toml", "--static")["warnings"] if w["code"] == "duty"]
    assert_allclose(share["stages"][0]["pinion"]["pitting"]["load_multiplier"], 3.4176, rtol=1e-4)  # over 0.95 h
    assert_allclose(full["stages"][0]["pinion"]["pitting"]["load_multiplier"], 0.96507, rtol=1e-4)  # over 10 000 h
    # the heavy point dominates the pinion's flank: 500 h at 2600 N.m do more damage than 6000 h at 1800 N.m
    bins = full["stages"][0]["pinion"]["pitting"]["bins"]
    assert bins[0]["damage"] > 0.8 * full["stages"][0]["pinion"]["pitting"]["damage"]


def test_a_reversed_point_counts_by_magnitude_and_reverses_the_bearing_reactions(tmp_path):
    """A crane hoist: 5000 h hoisting at +1500 N.m, 5000 h lowering with the motor braking (-1500 N.m). The teeth
    count the reversed point by magnitude (docs/life.md, "Limits"), so the damage is the same as with two hoisting
    points; the gear shaft's bearings see the axial force's moment reversed: by hand below."""
    crane = write(tmp_path / "crane.toml", SPEED_DRIVE,
                  {"name": "hoist", "hours": 5000.0, "torque_Nm": 1500.0, "speed_rpm": 1460.0},
                  {"name": "lower", "hours": 5000.0, "torque_Nm": -1500.0, "speed_rpm": 1460.0})
    same = write(tmp_path / "same.toml", SPEED_DRIVE,
                 {"name": "hoist", "hours": 5000.0, "torque_Nm": 1500.0, "speed_rpm": 1460.0},
                 {"name": "lower", "hours": 5000.0, "torque_Nm": 1500.0, "speed_rpm": 1460.0})
    doc, ref = _life(crane, "--static"), _life(same, "--static")
    for member in ("pinion", "gear"):
        for mode in ("pitting", "bending"):
            assert_allclose(doc["life"]["stages"][0][member][mode]["damage"],
                            ref["life"]["stages"][0][member][mode]["damage"], rtol=1e-12)
    assert [w["code"] for w in doc["warnings"]] == ["duty"] and "lower (duty[1])" in doc["warnings"][0]["message"]
    # gear shaft by hand: gear at x = 80 between bearings at 0 and 160; r = m_n z / cos(beta) / 2
    r = 3 * 67 / math.cos(math.radians(12)) / 2
    ft = 1500e3 / r
    fr = ft * math.tan(math.radians(20)) / math.cos(math.radians(12))
    fa = ft * math.tan(math.radians(12))
    lever = fa * r / 160.0  # the axial force's moment, taken by the bearing pair
    near, far = math.hypot(ft / 2, fr / 2 - lever), math.hypot(ft / 2, fr / 2 + lever)

    def p_locating(f_r: float) -> float:  # bearing 3: locating roller, e 0.4, X 0.4, Y 1.5
        return f_r if fa / f_r <= 0.4 else 0.4 * f_r + 1.5 * fa

    b3, b4 = doc["life"]["bearings"][2], doc["life"]["bearings"][3]
    # one sense puts the lighter reaction on the locating bearing at x = 0, the other the heavier one
    assert_allclose(sorted(b3["loads_N"]), sorted([p_locating(near), p_locating(far)]), rtol=1e-9)
    assert_allclose(sorted(b4["loads_N"]), sorted([near, far]), rtol=1e-9)
    p = 10.0 / 3.0  # equal revolutions at the two points: P = (mean P_i^p)^(1/p)
    assert_allclose(b3["equivalent_load_N"], (0.5 * sum(x**p for x in b3["loads_N"])) ** (1 / p), rtol=1e-12)
    revs = 10000 * 60 * 1460 / RATIO
    assert_allclose(b3["L10_Mrev"], (90e3 / b3["equivalent_load_N"]) ** p, rtol=1e-12)
    assert_allclose(b3["L10_h"], b3["L10_Mrev"] * 1e6 / (revs / 10000), rtol=1e-12)


@pytest.mark.parametrize(("edit", "key"), [
    (lambda t: t.replace("hours = 0.2", "hours = -0.2"), "duty[0].hours"),
    (lambda t: t.replace("hours = 0.2", "hours = nan"), "duty[0].hours"),
    (lambda t: t.replace("hours = 0.2\n", ""), "duty[0].hours"),
    (lambda t: t.replace('name = "normal"', 'name = "normal"\nset = { "stage[1].gear.teeth" = 70 }'),
     "duty[1]: set: stage[1].gear.teeth"),  # a gear of its own at one point: refused (tr10c), as a bearing's
    (lambda t: t.replace("speed_rpm = 2900.0", "speed_rpm = inf"), "duty[2].speed_rpm"),
])
def test_hostile_duty_values_are_exit_2_naming_the_key_and_leave_no_output(tmp_path, edit, key):
    path = write(tmp_path / "duty.toml", SPEED_DRIVE, *SPECTRUM)
    path.write_text(edit(path.read_text()))
    out = tmp_path / "life.json"
    res = _run("life", str(path), "--static", "-o", str(out), code=2)
    assert key in res.output and str(path) in res.output and "Traceback" not in res.output
    assert not out.exists() and list(tmp_path.iterdir()) == [path]


def _series(path: Path, *sets: str) -> tuple[np.ndarray, np.ndarray]:
    """time and input speed (rpm) of ``gearcli simulate`` of the file."""
    res = _run("simulate", str(path), "--format", "csv", *[a for s in sets for a in ("--set", s)])
    lines = [ln for ln in res.stdout.splitlines() if ln and not ln.startswith("#")]
    header = lines[0].split(",")
    rows = np.array([[float(x) for x in ln.split(",")] for ln in lines[1:]])
    return rows[:, header.index("time_s")], rows[:, header.index("shaft1_speed_rpm")]


def test_a_conveyor_start_longer_than_the_run_is_counted_whole(tmp_path):
    """A DOL conveyor whose loaded start (about 2.5 s to 98 % of its speed) outlasts the file's 2 s run: the life
    route lengthens the run until its window is settled, so the start is counted whole, N times, and the steady
    classes are the running drive's. (Before: the motor that had not reached its speed within the run gave the
    settle test no time to move the window to, the window [0.4, 2] s still accelerating at a mean 686 rpm was taken
    as 8000 h of running with K_v 3.3, and the start counted 0.69 input revolutions instead of 47.)"""
    points = ({"name": "loaded", "hours": 8000.0, "torque_Nm": 380.0, "speed_rpm": 1460.0, "starts": 240000},
              {"name": "empty", "hours": 2000.0, "torque_Nm": 100.0, "speed_rpm": 1490.0, "starts": 60000})
    path = write(tmp_path / "conveyor.toml", MOTOR_DRIVE, *points)
    doc = _life(path)
    assert not [w for w in doc["warnings"] if w["code"] in ("motor_speed_mismatch", "start_not_settled",
                                                            "window_not_settled", "duty")], doc["warnings"]
    t, rpm = _series(path, "load.torque_Nm=380", "simulation.duration_s=6", "simulation.steps=12000")
    t98 = t[np.argmax(rpm >= 0.98 * rpm[-1])]  # the loaded start reaches 98 % of its speed here (about 2.5 s)
    assert t98 > 2.0
    loaded = doc["life"]["points"][0]
    assert loaded["settled"] is True and max(loaded["K_v"]) < 1.05
    start = loaded["start"]
    assert start["span_s"][1] == pytest.approx(loaded["solver"]["window_s"][0]) and start["span_s"][1] > t98
    # the start's input revolutions: the simulated speed integrated over the start's span (an independent run of
    # the same point from rest; its own output grid, so to the sampling's accuracy)
    upto = t <= start["span_s"][1]
    assert_allclose(start["input_revolutions"], np.trapezoid(rpm[upto], t[upto]) / 60.0, rtol=2e-3)
    # its classes: starts x revolutions x the member's turns per input turn (one contact per turn)
    for member, turns in (("pinion", 1.0), ("gear", 1.0 / RATIO)):
        bins = doc["life"]["stages"][0][member]["pitting"]["bins"]
        assert_allclose(sum(b["cycles"] for b in bins if b["point"] == "loaded (start)"),
                        240000 * start["input_revolutions"] * turns, rtol=1e-9)
        assert_allclose(sum(b["cycles"] for b in bins if b["point"] == "loaded"), 8000 * 60 * 1460 * turns,
                        rtol=1e-9)


@pytest.mark.parametrize("c_kN", [40.0, 120.0])
def test_a_bearing_outlived_by_its_duty_is_warned(tmp_path, c_kN):
    """The input shaft's locating ball bearing over the one-point duty (10 000 h at 1460 rpm), by hand: L10 = (C/P)^3
    million revolutions, L10h = L10 / (60 n); with C = 40 kN it lasts (40/12.2)^3 = 35 Mrev, 402 h: warned; with
    C = 120 kN, 1.1e4 h: not."""
    path = write(tmp_path / "one.toml", SPEED_DRIVE, {"name": "only", "hours": 10000.0, "torque_Nm": 2000.0,
                                                      "speed_rpm": 1460.0})
    doc = _life(path, "--static", "--set", f"bearing[0].dynamic_load_rating_kN={c_kN!r}")
    b = doc["life"]["bearings"][0]
    l10_h = (c_kN * 1e3 / b["equivalent_load_N"]) ** 3 * 1e6 / (60 * 1460)
    assert_allclose(b["L10_h"], l10_h, rtol=1e-12)
    said = [w for w in doc["warnings"] if w["code"] == "bearing_life_short" and "over the duty" in w["message"]]
    assert (l10_h < 10000.0) == bool(said)
    if said:
        assert said[0]["bearing"] == 1 and said[0]["life"] == "L10"
        assert_allclose(said[0]["life_h"], l10_h, rtol=1e-12)


def test_a_recorded_history_shorter_than_the_required_life_is_warned_with_its_scale(tmp_path):
    """A 2.5 h record (--series) against the required 10 000 h: the damage and safety are the record's; the warning
    names the history and the factor 4000 that scales its time to the required life. Scaled by it, the record's
    classes carry 4000 times the cycles (the life in hours stays) and the warning is gone."""
    path = write(tmp_path / "base.toml", SPEED_DRIVE)
    rows = [(0.0, 1000.0, 1460.0), (3600.0, 2000.0, 1460.0), (7200.0, 1500.0, 1460.0), (9000.0, 0.0, 0.0)]
    record, scaled = tmp_path / "record.csv", tmp_path / "scaled.csv"
    for f, k in ((record, 1.0), (scaled, 4000.0)):
        f.write_text("time_s,torque_Nm,speed_rpm\n" + "".join(f"{t * k!r},{q!r},{n!r}\n" for t, q, n in rows))
    short = _life(path, "--static", "--series", str(record))
    said = [w for w in short["warnings"] if w["code"] == "duty"]
    assert len(said) == 1 and str(record) in said[0]["message"] and "by 4000" in said[0]["message"]
    assert said[0]["hours"] == pytest.approx(2.5)
    full = _life(path, "--static", "--series", str(scaled))
    assert not [w for w in full["warnings"] if w["code"] == "duty"]
    a, b = full["life"]["stages"][0]["pinion"]["pitting"], short["life"]["stages"][0]["pinion"]["pitting"]
    assert_allclose(a["damage"], 4000.0 * b["damage"], rtol=1e-9)
    assert_allclose(a["life_h"], b["life_h"], rtol=1e-9)


def test_more_starts_than_the_hours_hold_are_warned():
    """240 000 starts of 3.19 s each (from rest to the settled window) take 240000 x 3.19 / 3600 = 212.67 h: over
    a point of 10 h that is a typo, warned; over 8000 h (30 starts an hour), not."""
    start = StartData(240000, (0.0, 3.19), [], 46.8, (19087.0,))
    typo = DutyPoint("loaded belt", 10.0, 380.0, 1460.0, key="duty[0]", starts=240000)
    said = starts_warning(typo, start)
    assert len(said) == 1 and said[0].code == "duty" and "duty[0]" in said[0].message
    assert_allclose(said[0].data["starts_h"], 240000 * 3.19 / 3600.0, rtol=1e-12)
    assert not starts_warning(DutyPoint("loaded belt", 8000.0, 380.0, 1460.0, key="duty[0]", starts=240000), start)
    assert not starts_warning(typo, None)
