"""Motor, speed-dependent load and mesh losses against closed forms and an independent rigid-body integration.

- the extended Kloss curve passes through the nameplate's rated, breakdown (a maximum) and locked-rotor points;
- a flat motor curve against a constant load starts in t = J dw / (T_m - T_L) (rigid chain, closed form);
- the fan drive (table motor, quadratic load, lossy reducer) settles where the table meets the load reflected
  through the reducer, T_L / (i eta), and starts in the time a rigid-body integration of the same curves
  (scipy, written here from the curves alone) gives;
- a lossy, well-damped reducer's window mean F_t equals the design's static F_t (which include the losses).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.io.channels import named
from gearcli.model.elements import machine
from gearcli.model.spec import MotorSpec
from gearcli.scene import spec_from_design
from gearcli.simulate.run import run_simulation

ROOT = Path(__file__).resolve().parents[2]
RPM = 2 * math.pi / 60


def load_design_file(path: Path, sets: tuple[str, ...] = ()):
    return load_design(str(path), sets).design


# ------------------------------------------------------------------------------------------- Kloss
@pytest.mark.parametrize(("kb", "kl", "n_r"), [(2.8, 2.3, 1470.0), (2.2, 1.6, 1440.0), (3.2, 2.9, 1485.0)])
def test_kloss_curve_through_the_nameplate(kb, kl, n_r):
    p_w, n_s = 55e3, 1500.0
    m = MotorSpec.nameplate(p_w, n_r * RPM, n_s * RPM, kb, kl)
    t_r = p_w / (n_r * RPM)  # rated torque P / w
    assert m.curve(n_r * RPM) == pytest.approx(t_r, rel=1e-9)  # rated point
    assert m.curve(0.0) == pytest.approx(kl * t_r, rel=1e-9)  # locked rotor (s = 1)
    w_b = (1.0 - m.breakdown_slip) * n_s * RPM
    assert m.curve(w_b) == pytest.approx(kb * t_r, rel=1e-12)  # breakdown torque at the breakdown slip ...
    dw = 1e-4 * n_s * RPM
    assert m.curve(w_b - dw) < m.curve(w_b) > m.curve(w_b + dw)  # ... and it is the maximum
    grid = np.linspace(0.0, n_s * RPM, 20001)
    assert max(m.curve(w) for w in grid) == pytest.approx(kb * t_r, rel=1e-6)
    assert m.curve(n_s * RPM) == 0.0  # no torque at synchronous speed


def test_plain_kloss_when_the_locked_rotor_point_is_kloss_own():
    """a = 0 is Kloss's formula: with T_lr taken from it the fit returns a = 0 and s_b = s_r (k + sqrt(k^2 - 1))."""
    kb, sr = 2.5, 0.03
    sb = sr * (kb + math.sqrt(kb * kb - 1.0))
    kl = 2.0 * kb / (1.0 / sb + sb)
    sb_fit, a = machine.kloss_fit(1.0, kb, kl, sr)
    assert sb_fit == pytest.approx(sb, rel=1e-9)
    assert abs(a) < 1e-8


# --------------------------------------------------------------------------------- constant-torque start
def test_flat_motor_curve_start_time_is_j_dw_over_net_torque(tmp_path):
    """A table motor that is flat (T_m) up to near synchronous speed against a constant load T_L on a rigid
    chain: w rises linearly, t(98 % of w_op) = J_eq 0.98 w_op / (T_m - T_L / i), J_eq the inertias reflected
    to the motor shaft."""
    text = (ROOT / "configs/industrial_two_stage.toml").read_text()
    text = text.replace("efficiency = 0.98\n", "")
    text = text[:text.index("[input]")] + """[input]
speed_rpm = 1450
drive = "motor"
motor = { torque_speed = [[0, 150], [1490, 150], [1500, 0]] }

[load]
torque_Nm = 700

[simulation]
duration_s = 1.5
steps = 6000
"""
    path = tmp_path / "flat.toml"
    path.write_text(text)
    cfg = load_design_file(path)
    design = compute_design(cfg)
    res = run_simulation(cfg, design)
    spec = spec_from_design(cfg, design)
    ratio = design.total_ratio
    rho = [1.0, 19 / 75, 19 / 75 * 19 / 68]  # shaft speeds over the input's (z ratios)
    j_eq = sum(j * r * r for j, r in zip(spec.inertias_kg_m2, rho, strict=True))
    t_l = 700.0 / ratio
    w_op = (1490 + 10 * (150 - t_l) / 150) * RPM  # where the last segment (1490, 150)-(1500, 0) meets T_L / i
    motor = res.extra["motor"]
    assert motor["operating_point_rpm"] == pytest.approx(w_op / RPM, abs=1e-6)
    t_start = j_eq * 0.98 * w_op / (150.0 - t_l)
    assert motor["start_time_s"] == pytest.approx(t_start, rel=2e-3)  # sampling at 0.25 ms, elastic meshes


# ------------------------------------------------------------------------------------------------ fan
def _fan_rigid_start(cfg, design, spec) -> tuple[float, float]:
    """Operating speed and start time of the fan drive as one rigid body, from the table and the fan law
    alone: J_eq w' = T_table(w) - T_fan(w / i) / (i eta). The torque that accelerates a body behind a mesh
    passes through that mesh too, so each inertia counts reflected and divided by the efficiencies before it:
    J_eq = sum_k J_k rho_k^2 / prod_{meshes before k} eta."""
    table = np.array(cfg.input.motor.torque_speed, float)
    i = design.total_ratio
    eta = math.prod(s.efficiency for s in cfg.stage)
    t_nom, w_nom_out = cfg.load.torque_Nm, cfg.input.speed_rad_s_value / i

    def motor(w):
        return float(np.interp(w / RPM, table[:, 0], table[:, 1]))

    def load(w):
        return t_nom * (w / i / w_nom_out) ** 2 / (i * eta)

    w_op = brentq(lambda w: motor(w) - load(w), 1400 * RPM, 1500 * RPM, xtol=1e-12)
    rho = [1.0, 19 / 75, 19 / 75 * 19 / 68]
    etas = [1.0, cfg.stage[0].efficiency, eta]  # the efficiencies before each reducer shaft
    j_eq = cfg.input.inertia_kg_m2 + sum(j * r * r / e for j, r, e in zip(spec.inertias_kg_m2, rho, etas, strict=True)) \
        + cfg.load.inertia_kg_m2 * rho[-1] ** 2 / eta
    hit = lambda t, y: y[0] - 0.98 * w_op  # noqa: E731
    hit.terminal = True
    sol = solve_ivp(lambda t, y: [(motor(y[0]) - load(y[0])) / j_eq], (0, 5), [0.0], events=hit, rtol=1e-10,
                    atol=1e-10, max_step=1e-3)
    return w_op, float(sol.t_events[0][0])


def test_fan_drive_operating_speed_and_start_time():
    path = ROOT / "configs/fan_drive.toml"
    cfg = load_design_file(path)
    design = compute_design(cfg)
    res = run_simulation(cfg, design)
    w_op, t_start = _fan_rigid_start(cfg, design, spec_from_design(cfg, design))
    motor = res.extra["motor"]
    assert motor["operating_point_rpm"] == pytest.approx(w_op / RPM, abs=0.1)  # the curves' crossing
    assert motor["operating_speed_rpm"] == pytest.approx(w_op / RPM, abs=0.1)  # the simulation's window mean
    assert motor["start_time_s"] == pytest.approx(t_start, rel=0.03)  # elastic couplings and meshes vs rigid
    assert not [d for d in res.diagnostics if d.code in ("motor_stalls", "start_not_settled")]
    assert res.solver.energy_residual < 1e-6
    from gearcli.io.serialize import simulation_dict

    summary = simulation_dict(res)["summary"]  # the JSON contract's keys
    assert summary["start_time_s"] == motor["start_time_s"] and summary["operating_slip"] == motor["operating_slip"]
    assert summary["operating_slip"] == pytest.approx(1.0 - w_op / (1500 * RPM), abs=0.1 / 1500)
    assert {"motor_torque_Nm", "motor_speed_rpm"} <= set(named(res))


def test_fan_drive_four_times_the_load_warns_about_the_motor():
    cfg = load_design_file(ROOT / "configs/fan_drive.toml", ("load.torque_Nm=4800",))
    res = run_simulation(cfg, compute_design(cfg))
    assert [d for d in res.diagnostics if d.code == "motor_stalls"]


# --------------------------------------------------------------------------------------------- losses
def test_lossy_reducer_window_means_equal_the_design_static_forces():
    path = ROOT / "configs/industrial_two_stage.toml"
    cfg = load_design_file(path)
    design = compute_design(cfg)
    assert all(s.efficiency == 0.98 for s in cfg.stage)
    res = run_simulation(cfg, design)
    for st, dyn in zip(design.stages, res.stages, strict=True):
        assert dyn.tangential_N.mean == pytest.approx(st.static_force_N.tangential, rel=1e-3)
    assert res.solver.energy_residual < 1e-9
    assert res.energy.damping_loss_J > 0


# ------------------------------------------------------------------------------------- starting methods
def _nameplate(**start) -> MotorSpec:
    return MotorSpec.nameplate(15e3, 1460 * RPM, 1500 * RPM, 2.8, 2.3, **start)


def test_starting_methods_scale_the_curve_as_stated():
    direct = _nameplate()
    t_r = 15e3 / (1460 * RPM)
    # star-delta: a third of the torque (phase voltage / sqrt 3, torque ~ V^2) below the switch-over band
    sd = _nameplate(starting="star_delta", start_parameters=(1300 * RPM, 0.0))
    for n in (0.0, 600.0, 1280.0):
        assert sd.torque(0.0, n * RPM) == pytest.approx(direct.curve(n * RPM) / 3.0, rel=1e-12)
    assert sd.torque(0.0, 1300 * RPM) == pytest.approx(direct.curve(1300 * RPM), rel=1e-12)
    # soft start: torque ~ V^2, from u0^2 at t = 0 to the full curve after the ramp
    soft = _nameplate(starting="soft_start", start_parameters=(2.0, 0.4))
    assert soft.torque(0.0, 0.0) == pytest.approx(0.16 * 2.3 * t_r, rel=1e-9)
    assert soft.torque(1.0, 0.0) == pytest.approx((0.4 + 0.6 * 0.5) ** 2 * 2.3 * t_r, rel=1e-9)  # STEP(1/2) = 1/2
    assert soft.torque(2.5, 1460 * RPM) == pytest.approx(t_r, rel=1e-9)
    # VFD: the curve moves with the synchronous speed at constant slip speed; at half the ramp (STEP = 1/2) the
    # rated slip speed 40 rpm below 750 rpm gives the rated torque
    vfd = _nameplate(starting="vfd", start_parameters=(4.0, 0.0))
    assert vfd.torque(2.0, (750 - 40) * RPM) == pytest.approx(t_r, rel=1e-9)
    assert vfd.torque(0.0, 0.0) == 0.0
    limited = _nameplate(starting="vfd", start_parameters=(4.0, 1.5 * t_r))
    assert limited.torque(10.0, 1300 * RPM) == pytest.approx(1.5 * t_r, rel=1e-3)  # the limit (curve > 2.5 T_r)
    assert limited.torque(10.0, 1460 * RPM) == pytest.approx(t_r, rel=1e-3)  # below it: the curve


def test_a_speed_ramp_beyond_the_breakdown_torque_warns(tmp_path):
    """The industrial reducer speed-driven to 1450 rpm in 5 ms with a 15 kW motor described: the run-up of
    the rigid chain alone needs J_eq w / (ramp / 1.5) (STEP's peak acceleration 1.5 w / T) plus the load."""
    path = ROOT / "configs/industrial_two_stage.toml"
    motor = ('input.motor={rated_power_kW=15, rated_speed_rpm=1460, synchronous_speed_rpm=1500, '
             'breakdown_torque_ratio=2.8, locked_rotor_torque_ratio=2.3}')
    cfg = load_design_file(path, (motor, "input.ramp_s=0.005", "simulation.duration_s=0.2"))
    design = compute_design(cfg)
    res = run_simulation(cfg, design)
    spec = spec_from_design(cfg, design)
    rho = [1.0, 19 / 75, 19 / 75 * 19 / 68]
    j_eq = sum(j * r * r for j, r in zip(spec.inertias_kg_m2, rho, strict=True))
    assert j_eq * 1.5 * 1450 * RPM / 0.005 > 2.8 * 15e3 / (1460 * RPM)  # the closed form says it must warn
    warned = [d for d in res.diagnostics if d.code == "ramp_over_breakdown"]
    assert warned and warned[0].data["torque_Nm"] > warned[0].data["breakdown_torque_Nm"]
    assert "motor_torque_Nm" in named(res) and "motor_speed_rpm" in named(res)
    calm = run_simulation(*(lambda c: (c, compute_design(c)))(load_design_file(path, (motor,))))
    assert not [d for d in calm.diagnostics if d.code == "ramp_over_breakdown"]  # 0.2 s is within the motor


def test_an_unsettled_start_warns():
    cfg = load_design_file(ROOT / "configs/fan_drive.toml", ("simulation.window_start_s=0.1",))
    res = run_simulation(cfg, compute_design(cfg))
    assert [d for d in res.diagnostics if d.code == "start_not_settled"]
