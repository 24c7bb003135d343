"""The tr10c trial's starts: the hoist stage of tests/life/test_tr10c_hoist.py driven by a 45 kW DOL motor through a
coupling, a drum on another, 600,000 starts over the full-load point's 6000 h (100 starts an hour), and a planetary
stage (sun 24 / planet 36 / ring 96, four planets, ring held, sun driving) whose cycles per carrier revolution are
counted by hand. Checked against independent figures:

- the start's span and input revolutions against ``gearcli simulate`` of the same point (same duration, samples and
  engine as the life's run): the trapezoid of the input shaft's speed over [0, window start], and its peak |F_t|;
- a member's start cycles = starts x input revolutions x (member speed / input speed) x contacts per turn;
- a start class's stress = ``gearcli design`` at the class's force (ISO 6336 at K_v = 1, K_A = 1, the class's load);
- the bearings' revolutions and ISO 281 equivalent load over the duty and its starts (P^p weighted by revolutions);
- the planetary stage: per hour the sun meets N planets (n_s - n_c) times a minute, a planet flank (n_s - n_c)
  z_s / z_p, the ring N (n_r - n_c): per carrier revolution 16, 2.667 and 4 here.
"""

from __future__ import annotations

import csv
import io
import json
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli
from tests.life.test_tr10c_hoist import HOIST

MOTOR = HOIST.split("[input]")[0] + """
[contact]
stiffness = "iso6336"
exponent = 1.0
damping_ratio = 0.05

[input]
speed_rpm = 1480
drive = "motor"
motor = { rated_power_kW = 45, rated_speed_rpm = 1475, synchronous_speed_rpm = 1500, breakdown_torque_ratio = 2.8, locked_rotor_torque_ratio = 2.2 }
starting = "direct"
inertia_kg_m2 = 0.3
coupling_stiffness_Nm_rad = 1.5e4
coupling_damping_Nms_rad = 4

[load]
torque_Nm = 1000
inertia_kg_m2 = 25
coupling_stiffness_Nm_rad = 2.0e5
coupling_damping_Nms_rad = 60

[lubricant]
viscosity_40C_mm2_s = 150
viscosity_100C_mm2_s = 15
temperature_C = 65
contamination = "normal"

[rating]
required_life_h = 10000

[simulation]
duration_s = 1.5
steps = 3000

[[duty]]
name = "full"
hours = 6000
torque_Nm = 1000
speed_rpm = 1480
starts = 600000

[[duty]]
name = "part"
hours = 4000
torque_Nm = 400
speed_rpm = 1480
""" + "[[bearing]]" + HOIST.split("[[bearing]]", 1)[1]

STARTS = 600000
RATIO = 23 / 71


def _run(*args: str, code: int = 0):
    res = CliRunner().invoke(cli, ["-q", *args])
    assert res.exit_code == code, res.output
    return res


@pytest.fixture(scope="module")
def motor(tmp_path_factory) -> tuple[Path, dict]:
    path = tmp_path_factory.mktemp("motor") / "motor.toml"
    path.write_text(MOTOR, encoding="utf-8")
    return path, json.loads(_run("life", str(path), "--format", "json").stdout)


def test_start_span_and_revolutions_match_a_one_shot_run(motor):
    path, doc = motor
    full = doc["life"]["points"][0]
    start, solver = full["start"], full["solver"]
    assert start["count"] == STARTS and full["settled"] is True
    t0, t1 = start["span_s"]
    assert t0 == 0.0 and t1 == solver["window_s"][0]
    assert solver["duration_s"] > 1.5  # the file's 1.5 s run was lengthened to settle the window
    res = _run("simulate", str(path), "--set", "load.torque_Nm=1000", "--set", "input.speed_rpm=1480", "--set",
               "load.application_factor=1", "--set", "rating.dynamic_factor=1", "--set",
               f"simulation.duration_s={solver['duration_s']!r}", "--set",
               f"simulation.steps={solver['output_samples'] - 1}", "--set", f"simulation.engine={solver['engine']}",
               "--set", f"simulation.window_start_s={t1!r}", "--format", "csv")
    lines = [ln for ln in res.stdout.splitlines() if ln and not ln.startswith("#")]
    rows = list(csv.DictReader(io.StringIO("\n".join(lines))))
    t = np.array([float(r["time_s"]) for r in rows])
    w = np.abs([float(r["shaft1_speed_rpm"]) for r in rows]) / 60.0  # rev/s, by magnitude: a rocking shaft meshes too
    ft = np.array([float(r["stage1_tangential_N"]) for r in rows])
    m = t <= t1 + 1e-12
    revs = float(np.sum(0.5 * (w[m][1:] + w[m][:-1]) * np.diff(t[m])))
    # the same samples (the final, lengthened run's: `output_samples` was the first run's, 108,929 of 188,695, and
    # a re-run with it sampled another grid, 8e-5 off), the same trapezoid; the CSV's 10 digits
    assert_allclose(start["input_revolutions"], revs, rtol=1e-8)
    assert_allclose(start["peak_tangential_N"][0], np.max(np.abs(ft[m])), rtol=1e-8)
    # a DOL start peaks well above the steady force (9184.5 N at 1000 N m): the start is counted in its own classes
    assert start["peak_tangential_N"][0] > 3.0 * 9184.48


def test_start_cycles_and_class_stress_by_hand(motor):
    path, doc = motor
    life = doc["life"]
    start = life["points"][0]["start"]
    revs = start["input_revolutions"]
    for member, ratio in (("pinion", 1.0), ("gear", RATIO)):
        for mode in ("pitting", "bending"):
            bins = [b for b in life["stages"][0][member][mode]["bins"] if b["point"] == "full (start)"]
            assert_allclose(sum(b["cycles"] for b in bins), STARTS * revs * ratio, rtol=1e-12)
            assert_allclose(sum(b["damage"] for b in bins), start["damage"][0][member][mode], rtol=1e-12)
            steady = [b for b in life["stages"][0][member][mode]["bins"] if b["point"] == "full"]
            assert_allclose(sum(b["cycles"] for b in steady), 6000 * 60 * 1480 * ratio, rtol=1e-12)
    # the top start class is rated as `gearcli design` rates the pair at its force (K_A = K_v = 1)
    top = max((b for b in life["stages"][0]["pinion"]["pitting"]["bins"] if b["point"] == "full (start)"),
              key=lambda b: b["force_N"])
    torque = top["force_N"] / 9184.484513932448 * 1000.0  # F_t = T / r_g: the hoist's 9184.48 N at 1000 N m
    rating = json.loads(_run("design", str(path), "--format", "json", "--set", f"load.torque_Nm={torque!r}",
                             "--set", "input.speed_rpm=1480", "--set", "load.application_factor=1",
                             "--set", "rating.dynamic_factor=1").stdout)["stages"][0]["rating"]["pinion"]
    assert_allclose(top["stress_MPa"], rating["sigma_H_MPa"], rtol=1e-9)


def test_bearings_count_the_starts(motor):
    _, doc = motor
    life = doc["life"]
    start = life["points"][0]["start"]
    for j, b in enumerate(life["bearings"]):
        ratio = 1.0 if b["shaft"] == 1 else RATIO
        revs = [6000 * 60 * 1480 * ratio, 4000 * 60 * 1480 * ratio, STARTS * start["input_revolutions"] * ratio]
        assert_allclose(b["revolutions"], sum(revs), rtol=1e-12)
        p = 3.0 if b["kind"] == "ball" else 10 / 3
        loads = [*b["loads_N"], start["bearings"][j]["equivalent_load_N"]]
        p_eq = (sum(x ** p * n for x, n in zip(loads, revs, strict=True)) / sum(revs)) ** (1 / p)
        assert_allclose(b["equivalent_load_N"], p_eq, rtol=1e-12)
        if b.get("static_load_rating_kN"):
            # s_0 at the largest P_0 of the points and the start (no static factors: P_0 = F_r)
            peak = max(start["bearings"][j]["peak_radial_N"], b["static_equivalent_load_N"])
            assert_allclose(b["static_safety"], b["static_load_rating_kN"] * 1e3 / peak, rtol=1e-12)
            assert b["static_equivalent_load_N"] == pytest.approx(start["bearings"][j]["peak_radial_N"], rel=1e-12)


PLANETARY = """
title = "tr10c planetary: sun input, ring held, 4 planets"

[materials.case]
density_kg_m3 = 7850
youngs_modulus_MPa = 206000
poisson_ratio = 0.3
treatment = "case_carburized"
contact_fatigue_limit_MPa = 1450
bending_fatigue_limit_MPa = 420

[materials.nitr]
density_kg_m3 = 7850
youngs_modulus_MPa = 206000
poisson_ratio = 0.3
treatment = "nitrided"
contact_fatigue_limit_MPa = 1200
bending_fatigue_limit_MPa = 380

[[stage]]
type = "planetary"
normal_module_mm = 3
normal_pressure_angle_deg = 20
accuracy_grade = 6
sun    = { teeth = 24, face_width_mm = 40, material = "case", flank_roughness_Rz_um = 3, root_roughness_Rz_um = 12 }
planet = { teeth = 36, face_width_mm = 40, count = 4, material = "case", flank_roughness_Rz_um = 3, root_roughness_Rz_um = 12 }
ring   = { teeth = 96, face_width_mm = 40, material = "nitr", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 16 }
fixed = "ring"
input = "sun"

[lubricant]
viscosity_40C_mm2_s = 150
viscosity_100C_mm2_s = 15
temperature_C = 65

[input]
speed_rpm = 1000
ramp_s = 0.05

[load]
torque_Nm = 2500
ramp_s = 0.05

[rating]
required_life_h = 10000
load_sharing_factor = 1.15

[simulation]
duration_s = 0.3
steps = 1200

[[duty]]
name = "rated"
hours = 7000
torque_Nm = 2500
speed_rpm = 1000
starts = 1000

[[duty]]
name = "light"
hours = 3000
torque_Nm = 800
speed_rpm = 1500
"""

N_PLANETS, Z_S, Z_P, Z_R = 4, 24, 36, 96


def _per_minute(n_sun: float) -> dict[str, float]:
    """Contacts per minute of each member at sun speed n_sun, ring held (Willis: n_c = n_s z_s / (z_s + z_r))."""
    n_c = n_sun * Z_S / (Z_S + Z_R)
    rel = n_sun - n_c
    flank = rel * Z_S / Z_P  # the planet's turns relative to the carrier: each flank once per turn
    return {"pinion": rel * N_PLANETS, "gear": flank, "planet_ring_side": flank, "ring": n_c * N_PLANETS}


@pytest.mark.parametrize("route", ["--static", "dynamic"])
def test_planetary_cycles_per_carrier_revolution(tmp_path, route):
    path = tmp_path / "planetary.toml"
    path.write_text(PLANETARY, encoding="utf-8")
    args = ("--static",) if route == "--static" else ()
    life = json.loads(_run("life", str(path), *args, "--format", "json").stdout)["life"]
    # per carrier revolution: the sun meets 4 x 4 = 16 planet passes, a planet flank 96/36 = 2.667, the ring 4
    per_carrier = {m: v / (1000 * Z_S / (Z_S + Z_R)) for m, v in _per_minute(1000.0).items()}
    assert_allclose([per_carrier[m] for m in ("pinion", "gear", "ring")], [16.0, Z_R / Z_P, 4.0], rtol=1e-12)
    st = life["stages"][0]
    for member in ("pinion", "gear", "ring", "planet_ring_side"):
        for mode in ("pitting", "bending"):
            bins = st[member][mode]["bins"]
            for name, hours, n_sun in (("rated", 7000, 1000.0), ("light", 3000, 1500.0)):
                got = sum(b["cycles"] for b in bins if b["point"] == name)
                assert_allclose(got, hours * 60 * _per_minute(n_sun)[member], rtol=1e-12)
            if route == "dynamic":  # 1000 starts from rest, each of start["input_revolutions"] turns of the sun
                start = life["points"][0]["start"]
                got = sum(b["cycles"] for b in bins if b["point"] == "rated (start)")
                want = 1000 * start["input_revolutions"] * _per_minute(1.0)[member]
                assert_allclose(got, want, rtol=1e-12)
    if route == "dynamic":
        # ramps of 0.05 s to 1000 rpm (S-shaped, mean half the speed) then 0.05 s at speed: 1.25 sun turns
        assert_allclose(life["points"][0]["start"]["input_revolutions"], 1000 / 60 * (0.025 + 0.05), rtol=1e-6)


def test_starts_under_a_periodic_steady_state_are_counted_from_rest(motor, tmp_path):
    """With [simulation] steady = "periodic" the run keeps the periodic state only, no run from rest: the full-load
    point's 600,000 starts had nothing to count and `life` stopped, exit 2, "the steady window holds no whole mesh
    cycle; lengthen simulation.duration_s" (which does not help). A point with starts now runs from rest with its
    window settled, as the window route does (its start identical to it), and says so; a point without starts keeps
    the periodic state."""
    _, window_doc = motor
    path = tmp_path / "periodic.toml"
    path.write_text(MOTOR.replace("steps = 3000\n", 'steps = 3000\nsteady = "periodic"\n'), encoding="utf-8")
    doc = json.loads(_run("life", str(path), "--format", "json").stdout)
    full, part = doc["life"]["points"]
    ref = window_doc["life"]["points"][0]["start"]
    assert full["start"]["count"] == STARTS
    assert_allclose(full["start"]["input_revolutions"], ref["input_revolutions"], rtol=1e-12)
    assert full["start"]["damage"] == ref["damage"]  # the same run from rest, the same classes
    said = [w for w in doc["warnings"] if w["code"] == "duty" and "run from rest" in w["message"]]
    assert len(said) == 1 and said[0]["message"].startswith("duty point full:") and "periodic" in said[0]["message"]
    # the point without starts: its window is one period of the periodic state (an equilibrium: one mesh period) at
    # the motor's operating point, where the nameplate's Kloss curve (fitted by hand, tests/reference/
    # test_motor_trial_tr10f.py) carries the part load's 400 N m x 23/71 (one stage, no losses): brentq, ~1490.8 rpm
    from scipy.optimize import brentq

    from tests.reference.test_motor_trial_tr10f import RPM, Nameplate

    plate = Nameplate(45.0, 1475, 1500, 2.8, 2.2)
    w_op = brentq(lambda w: plate.torque(w) - 400.0 * RATIO, (1 - plate.sb) * 1500 * RPM, 1500 * RPM, xtol=1e-12)
    assert 1480 < w_op / RPM < 1500
    assert part["start"] is None
    assert_allclose(part["solver"]["window_s"][1] - part["solver"]["window_s"][0], 2 * np.pi / (w_op * 23), rtol=1e-7)
