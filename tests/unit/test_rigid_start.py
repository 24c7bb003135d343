"""The rigid-body start behind ``summary.start.peak_over_rigid`` (issue 30 item 5): the tool's rigid DOL start
against an independent solve_ivp of the rigid drivetrain written here (the same motor curve, the extended Kloss
form of docs/physics.md, and the same load law), and the cause the ``peak_over_rigid`` warning names."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from numpy.testing import assert_allclose
from scipy.integrate import solve_ivp

from gearcli import api
from gearcli.core.channels import Channel
from gearcli.model.assembly import Layout
from gearcli.scene import spec_from_design
from gearcli.simulate import rigid_start
from tests.reference.step_scene import STEP_SCENE

ROOT = Path(__file__).resolve().parents[2]
DOL = str(ROOT / "configs" / "motor_direct_start.toml")
# lossless stages (the rigid estimate's losses are the statics'), a load proportional to speed from zero
LOSSLESS = ("stage.0.efficiency=1.0", "stage.1.efficiency=1.0", "load.speed_exponent=1")
RPM = 2 * math.pi / 60


def _case(*sets: str):
    loaded = api.load(DOL, list(sets))
    design = api.design(loaded)
    return loaded.design, design, Layout.of(spec_from_design(loaded.design, design))


def _kloss(m, w: float) -> float:
    """The extended Kloss torque of the nameplate curve at speed w (docs/physics.md), written out."""
    s = (m.synchronous_speed_rad_s - w) / m.synchronous_speed_rad_s
    tb, sb, a = m.breakdown_torque_Nm, m.breakdown_slip, m.kloss_a
    return 2 * tb * (1 + a * sb) * s * sb / (s * s + sb * sb + 2 * a * sb * sb * abs(s))


def test_rigid_dol_start_matches_an_independent_integration():
    cfg, _, lay = _case(*LOSSLESS)
    motor = lay.drive.motor
    J = np.array([b.inertia for b in lay.bodies])
    rho = np.array([b.ratio for b in lay.bodies])
    j_total = float(J @ rho**2)  # every inertia reflected to the motor
    w_n = cfg.input.speed_rpm * RPM * rho[-1]  # the load's nominal speed: its torque is given there
    t_ref = cfg.load.torque_Nm

    def load(w_motor: float) -> float:
        return t_ref * (w_motor * rho[-1]) / w_n

    def rhs(t, y):
        return [(_kloss(motor, y[0]) - rho[-1] * load(y[0])) / j_total]

    T = 1.5
    t = np.linspace(0.0, T, 1501)
    sol = solve_ivp(rhs, (0.0, T), [0.0], t_eval=t, method="Radau", rtol=1e-10, atol=1e-10)
    w = sol.y[0]
    alpha = np.array([rhs(0.0, [x])[0] for x in w])
    got = rigid_start.integrate(lay, T, samples=t.size)
    assert_allclose(got.speed_rad_s, w, rtol=1e-6, atol=1e-6 * w.max())
    # the mesh force from the torque transmitted through the stage: the inertia reaction of everything downstream
    # of the driven gear plus the load, F_bt = T / r_b, F_t = F_bt cos(alpha_t)
    meshes = [lay.connectors[c] for c in lay.stage_conn]
    for k, x in enumerate(meshes):
        b = x.bodies[1]
        torque = float(J[b:] @ rho[b:] ** 2) / rho[b] * alpha + np.array([load(v) for v in w]) * rho[-1] / rho[b]
        ft = torque / x.radii[1] * math.cos(lay.spec.meshes[k].transverse_pressure_angle_rad)
        assert_allclose(got.tangential_N[k], ft, rtol=1e-5, atol=1e-6 * np.abs(ft).max())
        assert_allclose(np.abs(got.tangential_N[k]).max(), np.abs(ft).max(), rtol=1e-5)
    # the start is not a load step: the load is zero at standstill, the motor's torque accelerates the inertia
    assert abs(load(0.0)) == 0.0 and alpha[0] > 0


def test_simulate_summary_start_compares_with_the_rigid_start():
    cfg, design, lay = _case(*LOSSLESS)
    result = api.simulate(cfg, design)
    start = result.extra["start"]
    rigid = rigid_start.integrate(lay, float(result.time_s[-1]))
    for k, st in enumerate(result.stages):
        rigid_peak = rigid.peak_tangential_N[k]
        assert_allclose(start["rigid_peak_N"][k], rigid_peak, rtol=1e-12)
        # the peak of the continuous rigid start: at or above the largest of its output samples, and close to it
        # on this smooth DOL start (a star-delta switch-over is not: tests/reference/test_starts_rigid_engineer.py)
        sampled = float(np.abs(rigid.tangential_N[k]).max())
        assert sampled * (1 - 1e-12) <= rigid_peak <= sampled * (1 + 1e-3)
        assert_allclose(start["peak_over_rigid"][k], st.peak_tangential_N / rigid_peak, rtol=1e-12)
        # an elastic drivetrain answers the DOL torque step with at most about twice the rigid force
        assert 1.0 < start["peak_over_rigid"][k] < 2.2


def _warnings(cfg, design, lay, ratio: float = 1.0):
    result = api.simulate(cfg, design)
    forces = [result.series[Channel("tangential_force", f"stage{k + 1}")] for k in range(len(result.stages))]
    return rigid_start.start_summary(lay, "free" if not lay.speed_drive else "clamped_input", result.time_s, forces,
                                     result.window_s, ratio)[1]


def test_the_warning_names_the_motor_not_a_load_step_that_does_not_exist():
    cfg, design, lay = _case(*LOSSLESS)
    diags = _warnings(cfg, design, lay)  # threshold 1: the cause is named for every stage
    assert diags
    for d in diags:
        assert "locked-rotor torque" in d.message and "breakdown torque" in d.message
        assert "step at t = 0" not in d.message and "numerical artefact" not in d.message


def test_the_swinging_mode_of_a_ramped_start_is_named():
    # configs/motor_duty_starts.toml's drum on its coupling (a ~5 Hz mode) under a prescribed 0.5 s speed ramp and a
    # 0.5 s load ramp: no step, no motor, no excitation; the mode that swings is named, nothing else
    loaded = api.load(str(ROOT / "configs" / "motor_duty_starts.toml"),
                      ['input.drive="speed"', "input.ramp_s=0.5", "load.ramp_s=0.5"])
    design = api.design(loaded)
    lay = Layout.of(spec_from_design(loaded.design, design))
    diags = _warnings(loaded.design, design, lay, ratio=1.0)
    assert len(diags) == 2
    # by hand: the drum (900 kg m^2) on the load coupling (9.8e5 N m/rad) in series with the motor coupling
    # (2e4 N m/rad) seen from the output through i = 74/19 x 92/18, the clamped input of a speed drive
    ratio = 74 / 19 * 92 / 18
    k_eff = 1.0 / (1.0 / 9.8e5 + 1.0 / (2.0e4 * ratio**2))
    f_hand = math.sqrt(k_eff / 900.0) / (2 * math.pi)
    for d in diags:
        assert "numerical artefact" not in d.message and "violent impact" not in d.message
        assert "step at t = 0" not in d.message and "resonance passage" not in d.message
        assert "swings with" in d.message and "load coupling" in d.message
        # the gears' own inertia on the drum side is left out of the hand figure: within 5 %
        assert_allclose(d.data["swing_Hz"], f_hand, rtol=0.05)


def test_simulate_json_has_summary_start():
    import json

    from click.testing import CliRunner

    from gearcli.cli import cli

    res = CliRunner().invoke(cli, ["simulate", DOL, "--format", "json"])
    assert res.exit_code == 0, res.output
    summary = json.loads(res.stdout)["summary"]
    start = summary["start"]
    assert set(start) == {"peak_over_rigid", "rigid_peak_N"}
    for k, st in enumerate(summary["stages"]):
        assert_allclose(start["peak_over_rigid"][k] * start["rigid_peak_N"][k], st["peak_tangential_N"], rtol=1e-12)
    assert summary["steady"]["settled"] is True  # the 15 kW motor's start is over long before the window


def test_a_start_peak_held_by_the_transmission_error_at_t0_names_it():
    """configs/industrial_two_stage.toml with a 4 µm first-harmonic TE and a light load (150 N·m): every body starts
    at rest at zero angle (DESIGN section 4), so each mesh starts compressed by e(0) = 4 µm on its back flank, and its
    force at t = 0 is the law's at that penetration: F_n = K (e(0) cos β_b)^e (the file's linear iso6336 law, e = 1:
    K = k_n in N/mm), F_t = F_n cos β_b cos α_t, before anything turns (no speed yet: no damping force). That peak is the initial state's, not the start's dynamics:
    the warning names the TE, not a mode swinging or a gentler ramp."""
    cfg = api.load(str(ROOT / "configs" / "industrial_two_stage.toml"),
                   ["contact.transmission_error_um=[4]", "load.torque_Nm=150"])
    design = api.design(cfg)
    sim = api.simulate(cfg.design, design)
    warned = [d for d in sim.diagnostics if d.code == "peak_over_rigid"]
    assert len(warned) == 2
    for k, (st, d) in enumerate(zip(design.stages, warned, strict=True)):
        beta_b, alpha_t = math.radians(st.base_helix_angle_deg), math.radians(st.transverse_pressure_angle_deg)
        f_n = st.mesh_stiffness.K * (4e-3 * math.cos(beta_b)) ** st.mesh_stiffness.exponent
        f_t0 = f_n * math.cos(beta_b) * math.cos(alpha_t)
        assert_allclose(sim.stages[k].peak_tangential_N, f_t0, rtol=1e-6)
        assert sim.stages[k].peak_time_s == 0.0
        assert "transmission error e(0) = 4 µm" in d.message and "swings" not in d.message, d.message
    assert rigid_start.initial_te_um(Layout.of(spec_from_design(cfg.design, design)), 0) == 4.0


def test_a_hertz_mesh_pre_stressed_by_its_te_is_blamed_on_the_te_and_the_advice_removes_it():
    """configs/industrial_two_stage.toml with the Hertz law (e = 1.5), a light load (150 N·m) and a 30 µm TE on stage 2
    only. Every body starts at rest at zero angle, so stage 2 starts compressed by e(0) = 30 µm: by hand its force at
    t = 0 is F_n = K (e(0) cos β_b)^1.5, F_t(0) = F_n cos β_b cos α_t (no speed yet: no damping force), the run's
    peak. Released, the pre-stress loads stage 1 (no TE of its own) within one period of the lowest mode. Both
    warnings blame the TE pre-stress and advise what acts on it (a TE that is 0 at t = 0, the steady window), not a
    ramp, a swinging mode or "a numerical artefact" (stage 1's warning said the latter). The advice holds: with the
    TE's phase at 90°, e(0) = cos 90° = 0, nothing is compressed at t = 0 (F_t(0) = 0 on both stages) and neither
    start peak reaches the warning's 2x the rigid-body start."""
    sets = ["stage.1.mesh.transmission_error_um=[30]", "load.torque_Nm=150", "contact.stiffness=hertz",
            "contact.exponent=1.5"]
    cfg = api.load(str(ROOT / "configs" / "industrial_two_stage.toml"), sets)
    design = api.design(cfg)
    sim = api.simulate(cfg.design, design)
    st = design.stages[1]
    beta_b, alpha_t = math.radians(st.base_helix_angle_deg), math.radians(st.transverse_pressure_angle_deg)
    assert st.mesh_stiffness.law == "hertz" and st.mesh_stiffness.exponent == 1.5
    f_t0 = st.mesh_stiffness.K * (30e-3 * math.cos(beta_b)) ** 1.5 * math.cos(beta_b) * math.cos(alpha_t)
    assert_allclose(sim.stages[1].peak_tangential_N, f_t0, rtol=1e-6)  # the law at the initial penetration
    assert sim.stages[1].peak_time_s == 0.0
    clamped = next(a for a in api.modes(cfg.design, design) if a.boundary == "clamped_input")  # a speed drive
    lowest_Hz = min(m.frequency_Hz for m in clamped.modes if not m.rigid)
    assert 0.0 < sim.stages[0].peak_time_s <= 1.0 / lowest_Hz  # stage 1's peak: the pre-stress released
    warned = {d.data["stage"]: d.message for d in sim.diagnostics if d.code == "peak_over_rigid"}
    assert set(warned) == {1, 2}
    assert f"transmission error e(0) = 30 µm (every body starts at rest at zero angle), {f_t0:.5g} N at t = 0" \
        in warned[2]
    assert "pre-stressed by the stage 2 mesh's transmission error e(0) = 30 µm" in warned[1]
    for message in warned.values():
        assert "transmission_error_phase_deg = 90" in message and "simulation.window_start_s" in message
        for wrong in ("ramp_s >", "longer ramps", "gentler", "swings with", "numerical artefact"):
            assert wrong not in message, (wrong, message)
    phased = api.load(str(ROOT / "configs" / "industrial_two_stage.toml"),
                      [*sets, "stage.1.mesh.transmission_error_phase_deg=[90]"])
    again = api.simulate(phased.design, api.design(phased))
    start, before = again.extra["start"], sim.extra["start"]
    assert start["rigid_peak_N"] == before["rigid_peak_N"]  # the same rigid start: the TE is no part of it
    f0 = [again.series[Channel("tangential_force", f"stage{k}")][0] for k in (1, 2)]
    assert_allclose(f0, [0.0, 0.0], atol=1e-9)  # nothing compressed at t = 0 (the law at zero penetration)
    assert max(start["peak_over_rigid"]) < 2.0
    assert not [d for d in again.diagnostics if d.code == "peak_over_rigid"]


def test_the_swing_amplitude_is_the_swing_at_the_peak_not_its_average_over_the_start(tmp_path):
    # A speed-driven pinion (rigid speed from t = 0) and a free gear loaded by a step: one degree of freedom,
    # m_e q'' + c q' + k q = F_s, from q = 0 at rest. The mesh's total force f = k q + c q' (F_t = f cos alpha_t)
    # by hand: f / F_s - 1 = -exp(-zeta w t) (cos w_d t - zeta / sqrt(1 - zeta^2) sin w_d t), so the force swings
    # about the rigid (static) force with the envelope F_s exp(-zeta w t) / sqrt(1 - zeta^2); its peak, at
    # t = pi / w_d, is F_s (1 + exp(-zeta pi / sqrt(1 - zeta^2))). The warning's amplitude must be that swing near
    # the peak (2 periods from t = 0, where the peak lies), not its mean over the 0.02 s start (~0.2 of it).
    path = tmp_path / "step.toml"
    path.write_text(STEP_SCENE)
    loaded = api.load(str(path), [])
    design = api.design(loaded)
    lay = Layout.of(spec_from_design(loaded.design, design))
    diags = _warnings(loaded.design, design, lay, ratio=1.0)
    assert len(diags) == 1
    alpha = math.radians(20.0)
    r_bg = 0.5 * 40 * 4e-3 * math.cos(alpha)
    m_e = 0.05 / r_bg**2  # the pinion's speed is prescribed: m_e = J_g / r_bg^2
    k, zeta = 3e8, 0.05
    w = math.sqrt(k / m_e)
    w_d = w * math.sqrt(1 - zeta**2)
    f_s = 200.0 / r_bg * math.cos(alpha)  # static F_t = 2500 N
    assert_allclose(diags[0].data["swing_Hz"], w / (2 * math.pi), rtol=1e-3)
    # the closed-form deviation projected on the mode over the same two periods from t = 0, its mean removed
    t = np.linspace(0.0, 2 * (2 * math.pi / w), 4001)
    x = -f_s * np.exp(-zeta * w * t) * (np.cos(w_d * t) - zeta / math.sqrt(1 - zeta**2) * np.sin(w_d * t))
    x -= x.mean()
    expected = 2 * abs(np.trapezoid(x * np.exp(-1j * w * t), t)) / t[-1]
    # the tool projects the 25 us output samples (~43 per period): 2 % for the sampled sum and the window's edges
    assert_allclose(diags[0].data["swing_amplitude_N"], expected, rtol=0.02)
    overshoot = f_s * math.exp(-zeta * math.pi / math.sqrt(1 - zeta**2))
    assert 0.8 * overshoot < diags[0].data["swing_amplitude_N"] <= 1.05 * overshoot / math.sqrt(1 - zeta**2)


def test_a_swing_through_zero_force_is_measured_signed_and_a_peak_in_the_window_is_not_the_starts(tmp_path):
    # The step scene's layout (a 926.8 Hz mesh mode, static F_t 2500 N) with forces written here: the rigid
    # (static) force plus a swing of 3x it that decays over 10 ms, so the mesh force runs through zero (-2 F_s ..
    # 4 F_s). The swing's amplitude over two periods from t = 0 (where its peak lies) is, by hand,
    # 3 F_s tau / (2 T) (1 - exp(-2 T / tau)); |F| would fold the negative half-waves and lose some of it.
    path = tmp_path / "step.toml"
    path.write_text(STEP_SCENE)
    loaded = api.load(str(path), [])
    design = api.design(loaded)
    lay = Layout.of(spec_from_design(loaded.design, design))
    f_s = 200.0 / 0.080  # T_L / r_g
    f_n = math.sqrt(3e8 / (0.05 / (0.080 * math.cos(math.radians(20.0))) ** 2)) / (2 * math.pi)
    t = np.linspace(0.0, 0.1, 40001)
    tau = 0.01
    force = f_s + 3 * f_s * np.exp(-t / tau) * np.sin(2 * math.pi * f_n * t)
    _, diags = rigid_start.start_summary(lay, "clamped_input", t, [force], (0.02, 0.1), 1.0)
    (d,) = diags
    two_periods = 2 / f_n
    want = 3 * f_s * tau / two_periods * (1 - math.exp(-two_periods / tau))
    assert_allclose(d.data["swing_Hz"], f_n, rtol=1e-3)
    assert_allclose(d.data["swing_amplitude_N"], want, rtol=0.02)
    # the same force growing through the window (an undamped resonance): the run's peak lies in the window, where the
    # statistics carry it; the start's causes (a step, a swinging mode, an artefact) do not explain it
    growing = f_s + 3 * f_s * (t / 0.1) * np.sin(2 * math.pi * f_n * t)
    _, diags = rigid_start.start_summary(lay, "clamped_input", t, [growing], (0.02, 0.1), 1.0)
    (d,) = diags
    assert "peak lies in the statistics window" in d.message
    assert "numerical artefact" not in d.message and d.data["swing_Hz"] is None
    # a steady forced response (a transmission error near a mode) of constant amplitude from the start: the run's
    # peak falls in the start, but the window reaches it too: the response in operation, no start swing nor its advice
    steady = f_s + 3 * f_s * np.sin(2 * math.pi * 1.1 * f_n * t)
    _, diags = rigid_start.start_summary(lay, "clamped_input", t, [steady], (0.02, 0.1), 1.0)
    (d,) = diags
    assert d.data["swing_Hz"] is None and "response in operation" in d.message
    assert "lowers it" not in d.message and "numerical artefact" not in d.message


_FAN_TORQUE_DRIVE = """
title = "a helical stage, a balanced torque drive and a fan load"
[materials.steel]
density_kg_m3 = 7800
youngs_modulus_MPa = 2.07e5
poisson_ratio = 0.3
[[stage]]
normal_module_mm = 3
normal_pressure_angle_deg = 20
helix_angle_deg = 20
pinion = { teeth = 23, face_width_mm = 30, hand = "left", material = "steel", inertia_kg_m2 = 0.003 }
gear   = { teeth = 47, face_width_mm = 30, hand = "right", material = "steel", inertia_kg_m2 = 0.03 }
[input]
drive = "torque"
torque_Nm = 300
speed_rpm = 1000
ramp_s = 0.02
[load]
torque_Nm = 613.0434782608696
speed_exponent = 2
ramp_s = 0.02
[simulation]
duration_s = 0.1
"""


def test_a_torque_drives_rigid_start_runs_from_the_nominal_speed_the_simulation_starts_at(tmp_path):
    # the simulation starts a torque drive's train at its nominal speed (docs/design-file.md), so must the rigid
    # estimate: from there the balanced drive (300 N m x 47/23 = the fan's 613 N m at the nominal speed, both ramped
    # alike) never accelerates, and the mesh carries the load's ramp, F_t = T_L STEP(t) / r_g. From rest (as it was)
    # the fan's torque is ~0 while the drive accelerates the train, and the estimate was another run than the one
    # simulated.
    path = tmp_path / "fan.toml"
    path.write_text(_FAN_TORQUE_DRIVE)
    loaded = api.load(str(path), [])
    lay = Layout.of(spec_from_design(loaded.design, api.design(loaded)))
    got = rigid_start.integrate(lay, 0.1, samples=1001)
    w_n = 1000 * RPM
    assert_allclose(got.speed_rad_s, w_n, rtol=1e-6)
    r_g = 0.5 * 47 * 3e-3 / math.cos(math.radians(20.0))
    s = np.clip(got.time_s / 0.02, 0.0, 1.0)
    ft = 613.0434782608696 * s * s * (3 - 2 * s) / r_g
    assert_allclose(got.tangential_N[0], ft, rtol=1e-5, atol=1e-6 * ft.max())
