"""A two-pole and a six-pole nameplate motor, their starting methods and their starts, against hand calculations
written here (independent of the library's fit, root finders and integrators).

Scenes (``data/motor_poles/``):
- ``pump_2pole_22kW.toml``: 22 kW, 2940 rpm, 3000 rpm synchronous, T_b/T_r 3.0, T_l/T_r 2.5, rotor 0.075 kg m²;
  one 63/21 stage (η 1); a centrifugal pump T = 180 N·m (n / 980 rpm)² at the output;
- ``conveyor_6pole_37kW.toml``: 37 kW, 985 rpm, 1000 rpm synchronous, T_b/T_r 2.5, T_l/T_r 2.0, rotor 0.8 kg m²;
  one 63/21 stage (η 0.98, pinion 0.02 and gear 0.9 kg m² given); a constant 632 N·m drum torque, drum 140 kg m².

Hand calculation:
- T_r = P / ω_r; the extended Kloss curve of docs/physics.md, T(s) = 2 T_b (1 + a s_b) s s_b / (s² + s_b² +
  2 a s_b² |s|), (s_b, a) from T(1) = k_l T_r and T(s_r) = T_r by scipy ``fsolve``;
- the starting methods as docs/physics.md states them: star T/3 below the switch band, soft start u(t)² T with
  u = u0 + (1 − u0) STEP(t, 0, 0, t_r, 1), the VFD's curve at constant slip speed with the smooth-minimum limit;
- the operating point where T_m = T_L,refl (Brent), the reflected load T_L(n/i) / (i η);
- the run-up of the rigid chain t = J_eq ∫_0^{0.98 ω_op} dω / (T_m − T_L,refl) (``quad``),
  J_eq = J_m + J_p + (J_g + J_drum) / (i² η);
- the energy balance from the output channels: W_in = ∫ T_m ω_m dt, W_load = ∫ T_L ω_drum dt (trapezoid) and the
  bodies' kinetic energy ½ Σ J ω² at the end.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq, fsolve

from gearcli.cli import cli
from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.io.channels import named
from gearcli.io.serialize import simulation_dict
from gearcli.simulate.run import run_simulation

DATA = Path(__file__).parent / "data" / "motor_poles"
PUMP, CONVEYOR = DATA / "pump_2pole_22kW.toml", DATA / "conveyor_6pole_37kW.toml"
RPM = math.pi / 30.0
I = 63 / 21


class Motor:
    """The hand curve of one nameplate."""

    def __init__(self, p_w: float, n_r: float, n_s: float, kb: float, kl: float) -> None:
        self.n_s, self.kb, self.kl = n_s, kb, kl
        self.t_r = p_w / (n_r * RPM)
        self.s_r = 1.0 - n_r / n_s
        sb, a = fsolve(lambda v: [self.kloss(1.0, *v) / self.t_r - kl, self.kloss(self.s_r, *v) / self.t_r - 1.0],
                       [0.1, 0.0], xtol=1e-13)
        self.sb, self.a = float(sb), float(a)

    def kloss(self, s: float, sb: float, a: float) -> float:
        return 2 * self.kb * self.t_r * (1 + a * sb) * s * sb / (s * s + sb * sb + 2 * a * sb * sb * abs(s))

    def at_rpm(self, n: float) -> float:
        return self.kloss(1.0 - n / self.n_s, self.sb, self.a)


TWO_POLE = Motor(22e3, 2940.0, 3000.0, 3.0, 2.5)
SIX_POLE = Motor(37e3, 985.0, 1000.0, 2.5, 2.0)


def _run(path: Path, *sets: str):
    cfg = load_design(str(path), sets).design
    res = run_simulation(cfg, compute_design(cfg))
    ch = {"time_s": res.time_s, **named(res)}
    ch.update({k.replace("_deg_s", "_rpm"): v / 6.0 for k, v in ch.items() if k.endswith("_speed_deg_s")})
    return res, ch, simulation_dict(res)


def _codes(doc: dict) -> set[str]:
    return {w["code"] for w in doc["warnings"]}


def _pump_reflected(n_motor: float) -> float:
    return 180.0 * (n_motor / 2940.0) ** 2 / I  # the pump's torque at n/i, over the ratio (η = 1)


def test_the_hand_curves_pass_the_nameplate_points_with_their_maximum_at_sb():
    for m in (TWO_POLE, SIX_POLE):
        assert m.kloss(m.s_r, m.sb, m.a) == pytest.approx(m.t_r, rel=1e-10)
        assert m.kloss(1.0, m.sb, m.a) == pytest.approx(m.kl * m.t_r, rel=1e-10)
        assert m.kloss(m.sb, m.sb, m.a) == pytest.approx(m.kb * m.t_r, rel=1e-10)
        h = 1e-5
        assert m.kloss(m.sb - h, m.sb, m.a) < m.kb * m.t_r > m.kloss(m.sb + h, m.sb, m.a)
    # T_r by hand: 22 kW at 2940 rpm is 71.457 N m, 37 kW at 985 rpm 358.70 N m
    assert TWO_POLE.t_r == pytest.approx(71.457, abs=1e-3)
    assert SIX_POLE.t_r == pytest.approx(358.70, abs=1e-2)


def test_two_pole_direct_start_follows_the_hand_curve_at_every_slip_and_settles_at_the_hand_point():
    res, ch, doc = _run(PUMP)
    n, tq = ch["motor_speed_rpm"], ch["motor_torque_Nm"]
    hand = np.array([TWO_POLE.at_rpm(x) for x in n])
    # the channel is the curve at the sampled speed: standstill (locked rotor 178.64 N m) to the operating point
    assert tq[0] == pytest.approx(2.5 * TWO_POLE.t_r, rel=1e-9)
    assert_allclose(tq, hand, rtol=1e-7, atol=1e-7 * TWO_POLE.t_r)  # fit and hand fit agree to ~1e-12
    assert n.min() <= 1.0 and n.max() > 2940.0  # the whole curve was swept, slip 1 to below the rated slip
    n_op = brentq(lambda x: TWO_POLE.at_rpm(x) - _pump_reflected(x), 2000.0, 3000.0 - 1e-9, xtol=1e-10)
    assert doc["summary"]["motor"]["operating_point_rpm"] == pytest.approx(n_op, abs=1e-6)  # 2951.63 rpm
    # the mean motor torque over the window is the reflected pump torque at the mean speed plus the window's
    # small acceleration: within 1 % (the start ends at 0.38 s, the window starts at 0.4 s)
    assert doc["summary"]["motor"]["mean_torque_Nm"] == pytest.approx(_pump_reflected(n_op), rel=0.01)


@pytest.mark.parametrize("how", ["star_delta", "soft_start"])
def test_star_and_soft_start_scale_the_hand_curve(how):
    sets = (('input.starting="star_delta"', "input.switch_speed_rpm=2700") if how == "star_delta" else
            ('input.starting="soft_start"', "input.voltage_ramp_s=0.8", "input.initial_voltage_fraction=0.5"))
    _, ch, _ = _run(PUMP, *sets)
    t, n, tq = ch["time_s"], ch["motor_speed_rpm"], ch["motor_torque_Nm"]
    curve = np.array([TWO_POLE.at_rpm(x) for x in n])
    if how == "star_delta":
        star, delta = n < 2700.0 - 30.0, n >= 2700.0  # the smoothstep band is 1 % of 3000 rpm below 2700
        assert star.sum() > 100 and delta.sum() > 100
        assert_allclose(tq[star], curve[star] / 3.0, rtol=1e-7)  # phase voltage / √3: a third of the torque
        assert_allclose(tq[delta], curve[delta], rtol=1e-7)
        assert tq[0] == pytest.approx(2.5 * TWO_POLE.t_r / 3.0, rel=1e-9)  # 59.55 N m
    else:
        x = np.clip(t / 0.8, 0.0, 1.0)
        u = 0.5 + 0.5 * x * x * (3 - 2 * x)
        assert_allclose(tq, u * u * curve, rtol=1e-7, atol=1e-9)
        assert tq[0] == pytest.approx(0.25 * 2.5 * TWO_POLE.t_r, rel=1e-9)  # u0² of the locked-rotor torque


@pytest.mark.parametrize("speed_rpm", [2940.0, 2500.0])
def test_vfd_follows_the_constant_v_over_f_curve_and_its_torque_limit(speed_rpm):
    _, ch, _ = _run(PUMP, 'input.starting="vfd"', "input.ramp_s=1.0", "input.torque_limit_Nm=100",
                    f"input.speed_rpm={speed_rpm}")
    t, n, tq = ch["time_s"], ch["motor_speed_rpm"], ch["motor_torque_Nm"]
    n_s = 3000.0 + speed_rpm - 2940.0  # the supply puts the rated slip speed below speed_rpm
    x = np.clip(t / 1.0, 0.0, 1.0)
    slip = (n_s * x * x * (3 - 2 * x) - n) / 3000.0  # the slip speed over the nameplate's synchronous speed
    curve = np.array([TWO_POLE.kloss(s, TWO_POLE.sb, TWO_POLE.a) for s in slip])
    lim, eps = 100.0, 2.0
    hand = 0.5 * (curve + lim - np.sqrt((curve - lim) ** 2 + eps * eps))
    assert_allclose(tq, hand, rtol=0, atol=1e-5)
    assert tq.max() < lim  # the limit holds (the smooth minimum stays below it)


def test_six_pole_conveyor_runs_up_in_the_hand_time_with_the_hand_energy_balance():
    m = SIX_POLE
    load = 632.0 / (I * 0.98)
    n_op = brentq(lambda x: m.at_rpm(x) - load, 700.0, 1000.0 - 1e-9, xtol=1e-10)  # 992.434 rpm
    j_eq = 0.8 + 0.02 + (0.9 + 140.0) / (I * I * 0.98)
    integral, _ = quad(lambda w: 1.0 / (m.at_rpm(w / RPM) - load), 0.0, 0.98 * n_op * RPM, limit=200)
    t_hand = j_eq * integral  # 2.887 s
    assert t_hand == pytest.approx(2.887, abs=1e-3)
    _, ch, doc = _run(CONVEYOR)
    s = doc["summary"]
    assert s["motor"]["operating_point_rpm"] == pytest.approx(n_op, abs=1e-6)
    # the couplings' and mesh's modes (> 5 Hz) are fast against the 2.9 s run-up: the rigid chain within 0.5 %
    assert s["start_time_s"] == pytest.approx(t_hand, rel=5e-3)
    assert "start_not_settled" in _codes(doc)  # the window starts at 2.4 s, before the start ends
    # the rigid start's peak: at the breakdown torque, the gear carries the drum side's inertia torque and the
    # load, F_t = ((T_b - T_L,refl) / J_eq (J_g + J_drum) / i + T_out) / (η r), r = the gear's pitch radius
    r = 63 * 4 / math.cos(math.radians(12)) / 2000.0
    rigid = ((m.kb * m.t_r - load) / j_eq * (0.9 + 140.0) / I + 632.0) / (0.98 * r)  # 20109.6 N
    assert s["start"]["rigid_peak_N"][0] == pytest.approx(rigid, rel=1e-4)  # the rigid run's samples near T_b
    t, wm, wd = ch["time_s"], ch["motor_speed_rpm"] * RPM, ch["drum_speed_rpm"] * RPM
    w_in = np.trapezoid(ch["motor_torque_Nm"] * wm, t)
    w_load = np.trapezoid(632.0 * wd, t)
    ke = 0.5 * (0.8 * wm[-1] ** 2 + 0.02 * (ch["shaft1_speed_rpm"][-1] * RPM) ** 2
                + 0.9 * (ch["shaft2_speed_rpm"][-1] * RPM) ** 2 + 140.0 * wd[-1] ** 2)
    e = doc["energy"]
    # trapezoid over 6000 samples of a smooth run-up: 1e-5; kinetic energy exact from the final speeds
    assert e["input_work_J"] == pytest.approx(w_in, rel=1e-5)
    assert e["load_work_J"] == pytest.approx(w_load, rel=1e-5)
    assert e["kinetic_change_J"] == pytest.approx(ke, rel=1e-8)
    # the mesh loss is (1 - η) of what the pinion passes on; with the couplings' dampers it is the rest
    assert e["damping_loss_J"] == pytest.approx(w_in - w_load - ke, rel=1e-3)
    assert 0.015 * w_load < e["damping_loss_J"] < 0.03 * w_in


@pytest.mark.parametrize(("load_nm", "starts"), [(2352.0, False), (3000.0, False), (2000.0, True)])
def test_six_pole_stall_threshold_is_the_locked_rotor_torque(load_nm, starts):
    """The curve's lowest torque from standstill up to its breakdown point is the locked-rotor torque 717.4 N m
    (a = 15.4 lifts the low-speed part): a reflected load above it (2352 N·m: 800 N·m; 3000 N·m: 1020 N·m, above
    even the breakdown torque 896.8 N·m) cannot start; below it (2000 N·m: 680 N·m) the motor starts. A stall is
    a warning (exit 0, docs/output.md), not an error."""
    assert (load_nm / (I * 0.98) < SIX_POLE.kl * SIX_POLE.t_r) is starts
    _, _, doc = _run(CONVEYOR, f"load.torque_Nm={load_nm}", "simulation.duration_s=1.0")
    assert ("motor_stalls" in _codes(doc)) is not starts
    res = CliRunner().invoke(cli, ["simulate", str(CONVEYOR), "--set", f"load.torque_Nm={load_nm}", "--set",
                                   "simulation.duration_s=0.5", "--format", "json", "-q"])
    assert res.exit_code == 0, res.output


def _star_delta_reversals(n: np.ndarray, switch_rpm: float, width_rpm: float) -> int:
    """By hand: the times the motor falls from above the band's lower edge to below it after first switching."""
    first = int(np.argmax(n >= switch_rpm))
    below = n[first:] < switch_rpm - width_rpm
    return int(np.count_nonzero(below[1:] & ~below[:-1]))


@pytest.mark.parametrize(("sets", "toggles"), [
    (("input.switch_speed_rpm=2", "simulation.duration_s=2.0", "simulation.window_start_s=1.5"), True),  # switched
    # at once: the swing back reverses it
    (("input.switch_speed_rpm=900", "load.torque_Nm=400", "simulation.duration_s=14.0", "simulation.steps=7000"),
     True),  # the delta torque step winds the coupling up; the rotor swings back below the band
])
def test_a_star_delta_motor_that_falls_back_into_star_is_warned(sets, toggles):
    """The model's star-delta switch is a function of speed (docs/physics.md); a real starter stays in delta. A
    rotor that swings back through the switch band toggles star and delta, with mesh forces a latched starter
    does not make (here up to 20x the static force); that is warned, with the count the speed channel shows."""
    _, ch, doc = _run(CONVEYOR, 'input.starting="star_delta"', *sets)
    switch = float(next(s for s in sets if s.startswith("input.switch")).split("=")[1])
    n, tq = ch["motor_speed_rpm"], ch["motor_torque_Nm"]
    count = _star_delta_reversals(n, switch, 10.0)
    assert (count > 0) is toggles
    # back in star: a third of the hand curve at the lowest speed after the switch
    first = int(np.argmax(n >= switch))
    k = first + int(np.argmin(n[first:]))
    assert tq[k] == pytest.approx(SIX_POLE.at_rpm(n[k]) / 3.0, rel=1e-7)
    warned = [w for w in doc["warnings"] if w["code"] == "star_delta_reswitch"]
    assert len(warned) == 1
    assert warned[0]["reswitches"] == count
    assert warned[0]["min_speed_after_switch_rpm"] == pytest.approx(n[k], rel=1e-12)
    # a start peak after the first fall back is named with it, not only with a load step's advice
    f = np.abs(ch["stage1_tangential_N"])
    i = int(np.argmax(f))
    if t_peak_in_start := bool(ch["time_s"][i] <= doc["summary"]["window_s"][0]):
        peak = [w for w in doc["warnings"] if w["code"] == "peak_over_rigid"]
        assert peak and "star_delta_reswitch" in peak[0]["message"]
    assert t_peak_in_start is (switch < 10.0)  # the 2 rpm scene's peak lies in its start (window from 1.5 s)


def test_a_clean_star_delta_start_is_not_warned():
    _, ch, doc = _run(PUMP, 'input.starting="star_delta"', "input.switch_speed_rpm=2700")
    assert _star_delta_reversals(ch["motor_speed_rpm"], 2700.0, 30.0) == 0
    assert "star_delta_reswitch" not in _codes(doc)


def _life(path: Path, starts: int, tmp_path: Path) -> dict:
    f = tmp_path / f"starts_{starts}.toml"
    f.write_text(path.read_text().replace("starts = 1000", f"starts = {starts}"))
    res = CliRunner().invoke(cli, ["life", str(f), "--format", "json", "-q"])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)["life"]


def test_life_counts_the_conveyor_start_n_times_with_the_simulated_peak_and_revolutions(tmp_path):
    path = DATA / "conveyor_6pole_starts.toml"
    none, some, many = (_life(path, n, tmp_path) for n in (0, 1000, 10000))
    start = some["points"][0]["start"]
    assert none["points"][0]["start"] is None
    assert start["count"] == 1000 and start["span_s"] == [0.0, 4.0]
    # the start simulated once: its revolutions of the input shaft are ∫ |n| dt of the same run (trapezoid on the
    # run's own samples; the shaft swings back briefly as the load torque meets the drum at rest, and a reverse
    # turn meshes as well), its peak the run's largest |F_t| before the window
    _, ch, _ = _run(path)
    t = ch["time_s"]
    m = t <= 4.0 + 1e-12
    assert start["input_revolutions"] == pytest.approx(np.trapezoid(np.abs(ch["shaft1_speed_rpm"][m]), t[m]) / 60.0, rel=1e-4)
    # life samples its point's run finer (per mesh cycle) than this file's 5000 steps: the peak between samples
    assert start["peak_tangential_N"][0] == pytest.approx(np.abs(ch["stage1_tangential_N"][m]).max(), rel=1e-3)
    # a DOL step of the locked-rotor torque on the elastic coupling: about twice the rigid chain's force at t = 0,
    # F = (T_lr - T_L,refl) (J_g + J_drum) / (J_eq r) + T_out / (η r) with r the gear's pitch radius
    r = 63 * 4 / math.cos(math.radians(12)) / 2000.0
    rigid0 = ((SIX_POLE.kl * SIX_POLE.t_r - 632.0 / (I * 0.98)) / (0.82 + 140.9 / (I * I * 0.98)) * 140.9 / I
              + 632.0) / (0.98 * r)
    assert 1.6 * rigid0 < start["peak_tangential_N"][0] < 2.1 * rigid0
    # the start's classes: N x its input revolutions x the member's turns per input turn (one contact a turn)
    for member, turns in (("pinion", 1.0), ("gear", 21 / 63)):
        for mode in ("pitting", "bending"):
            bins = [b for b in some["stages"][0][member][mode]["bins"] if b["point"] == "full (start)"]
            assert sum(b["cycles"] for b in bins) == pytest.approx(1000 * start["input_revolutions"] * turns, rel=1e-12)
            assert sum(b["damage"] for b in bins) == pytest.approx(start["damage"][0][member][mode], rel=1e-12)
    # N starts: N times one start's damage, on top of the running's
    for stage in range(1):
        for member in ("pinion", "gear"):
            for mode in ("pitting", "bending"):
                d0 = none["stages"][stage][member][mode]["damage"]
                d1, d2 = some["stages"][stage][member][mode]["damage"], many["stages"][stage][member][mode]["damage"]
                s1 = some["points"][0]["start"]["damage"][stage][member][mode]
                s2 = many["points"][0]["start"]["damage"][stage][member][mode]
                assert s2 == pytest.approx(10.0 * s1, rel=1e-9)
                assert d1 == pytest.approx(d0 + s1, rel=1e-9)
                assert d2 == pytest.approx(d0 + s2, rel=1e-9)


@pytest.mark.parametrize(("load_nm", "switch_rpm"), [(632.0, 985.0), (800.0, 900.0)])
def test_a_star_delta_motor_stuck_in_star_is_named_with_the_hand_numbers(load_nm, switch_rpm):
    """632 N·m: the star curve T/3 meets the reflected 215.0 N·m at the hand crossing (956.1 rpm), below the
    985 rpm switch-over: it never switches. 800 N·m: 272.1 N·m reflected against T_lr/3 = 239.1 N·m at standstill:
    it cannot start in star, though the delta curve would carry it."""
    load = load_nm / (I * 0.98)
    _, _, doc = _run(CONVEYOR, 'input.starting="star_delta"', f"input.switch_speed_rpm={switch_rpm}",
                     f"load.torque_Nm={load_nm}", "simulation.duration_s=1.0")
    stall = [w for w in doc["warnings"] if w["code"] == "motor_stalls"]
    assert len(stall) == 1
    if SIX_POLE.kl * SIX_POLE.t_r / 3.0 > load:
        n_star = brentq(lambda x: SIX_POLE.at_rpm(x) / 3.0 - load, 800.0, switch_rpm - 10.0, xtol=1e-10)
        assert stall[0]["stall_speed_rpm"] == pytest.approx(n_star, abs=1e-4)  # 956.10 rpm
        assert f"in star at {n_star:.5g} rpm" in stall[0]["message"] and "never switches to delta" in stall[0]["message"]
    else:
        assert stall[0]["stall_speed_rpm"] is None
        assert f"in star it gives {SIX_POLE.kl * SIX_POLE.t_r / 3.0:.4g} N·m" in stall[0]["message"]
        assert f"against {load:.4g} N·m" in stall[0]["message"]
    n_op = brentq(lambda x: SIX_POLE.at_rpm(x) - load, 800.0, 1000.0 - 1e-9, xtol=1e-10)
    assert stall[0]["operating_point_rpm"] == pytest.approx(n_op, abs=1e-4)  # the delta curve's, never reached


def _step(x: np.ndarray) -> np.ndarray:
    x = np.clip(x, 0.0, 1.0)
    return x * x * (3 - 2 * x)


@pytest.mark.parametrize(("ramp_s", "outruns"), [(1.0, True), (3.0, False), (12.0, False)])
def test_a_vfd_ramp_that_outruns_the_motor_is_warned(ramp_s, outruns):
    """The supply's synchronous speed 1000 rpm STEP(t/ramp_s) runs ahead of the rotor; past the breakdown slip speed
    s_b n_s = 242.3 rpm (hand fit) the motor is on the unstable side of its moving curve and falls out. 1 s for the
    16.8 kg m² conveyor: a rigid chain integrated here (solve_ivp) lags by more than that too; 3 s and 12 s not."""
    delta_b = SIX_POLE.sb * 1000.0
    assert delta_b == pytest.approx(242.3, abs=0.05)
    _, ch, doc = _run(CONVEYOR, 'input.starting="vfd"', f"input.ramp_s={ramp_s}",
                      f"simulation.duration_s={ramp_s + 3.0}")
    lag = 1000.0 * _step(ch["time_s"] / ramp_s) - ch["motor_speed_rpm"]
    warned = [w for w in doc["warnings"] if w["code"] == "ramp_over_breakdown"]
    assert bool(lag.max() > delta_b) is outruns
    assert bool(warned) is outruns
    if outruns:
        assert warned[0]["slip_speed_rpm"] == pytest.approx(lag.max(), rel=1e-9)
        assert warned[0]["breakdown_slip_speed_rpm"] == pytest.approx(delta_b, rel=1e-3)  # the 4001-point scan
    j_eq, load = 0.82 + 140.9 / (I * I * 0.98), 632.0 / (I * 0.98)

    def rhs(t, y):
        slip = (1000.0 * _step(np.array(t / ramp_s)) - y[0] / RPM) / 1000.0
        return [(SIX_POLE.kloss(float(slip), SIX_POLE.sb, SIX_POLE.a) - load) / j_eq]

    sol = solve_ivp(rhs, (0.0, ramp_s + 1.0), [0.0], max_step=0.002, rtol=1e-8)
    rigid_lag = 1000.0 * _step(sol.t / ramp_s) - sol.y[0] / RPM
    assert bool(rigid_lag.max() > delta_b) is outruns
