"""A torque drive whose torque the load does not balance at the nominal speed is said (design check
``torque_drive_balance``), with where the train goes, checked by hand and against the simulated train.

Scene: one spur stage 20/40 (ratio u = 2, lossless), a torque drive, a fan-type load T_L (n / n_0)^2 with
T_L = 100 N·m at the nominal output speed (n_0 = 1500 rpm at the input). The load needs T_req = T_L / u = 50 N·m
at the input. With T_in = 60 N·m the rigid train settles where T_in = T_req (n / n_0)^2:
n* = 1500 √(60 / 50) = 1643.17 rpm. With a constant load (p = 0) nothing balances it: it accelerates.
"""

from __future__ import annotations

import math
from pathlib import Path

from numpy.testing import assert_allclose

from gearcli import api

SCENE = """
title = "torque drive against a fan load"
[[stage]]
normal_module_mm = 3
normal_pressure_angle_deg = 20
pinion = {{ teeth = 20, face_width_mm = 20, hand = "spur", inertia_kg_m2 = 0.002 }}
gear   = {{ teeth = 40, face_width_mm = 20, hand = "spur", inertia_kg_m2 = 0.02 }}
[input]
drive = "torque"
speed_rpm = 1500
torque_Nm = {t_in}
[load]
torque_Nm = 100
speed_exponent = {p}
[simulation]
duration_s = 0.6
steps = 1200
"""


def _balance(tmp_path, t_in, p, sets=()):
    path = tmp_path / "fan.toml"
    path.write_text(SCENE.format(t_in=t_in, p=p))
    loaded, design = api.load_and_design(str(path), list(sets))
    found = [d for d in design.diagnostics if d.data.get("check") == "torque_drive_balance"]
    return loaded, design, found


def test_a_balanced_torque_drive_is_not_warned(tmp_path):
    _, design, found = _balance(tmp_path, 50.0, 2)
    assert_allclose(design.input_torque_Nmm, 50e3, rtol=1e-12)  # T_L / u, lossless
    assert found == []
    _, _, found = _balance(tmp_path, 50.4, 0)  # 0.8 %: within the 1 % tolerance
    assert found == []


def test_an_unbalanced_torque_drive_names_the_speed_the_fan_load_settles_at(tmp_path):
    _, _, found = _balance(tmp_path, 60.0, 2)
    assert len(found) == 1
    settle = 1500.0 * math.sqrt(60.0 / 50.0)  # by hand: 1643.17 rpm
    assert "settles at 1643.2 rpm" in found[0].message, found[0].message
    assert found[0].data["required_input_torque_Nm"] == 50.0 and found[0].data["input_torque_Nm"] == 60.0
    # the simulated train goes there: the mean input speed over the last 0.2 s (the rigid train's time
    # constant J_eff n_0 / (2 T_req) = (0.002 + 0.02 / 4) 157 / 100 = 11 ms, so 0.4 s is ~36 of them)
    loaded, design, _ = _balance(tmp_path, 60.0, 2, ["simulation.window_start_s=0.4"])
    result = api.simulate(loaded.design, design)
    assert_allclose(result.input_speed_deg_s / 6.0, settle, rtol=1e-4)  # °/s to rpm; mesh vibration only
    assert any("torque_drive_balance" == w.data.get("check") for w in result.diagnostics)


def test_a_constant_load_cannot_balance_it(tmp_path):
    _, _, found = _balance(tmp_path, 60.0, 0)
    assert len(found) == 1 and "accelerates for the whole run" in found[0].message
    _, _, found = _balance(tmp_path, 40.0, 0)
    assert len(found) == 1 and "decelerates" in found[0].message



def _layout(tmp_path, t_in, p, load="torque_Nm = 100\nspeed_exponent = {p}"):
    from gearcli.model.assembly import Layout
    from gearcli.scene import spec_from_design
    path = tmp_path / "fan.toml"
    path.write_text(SCENE.format(t_in=t_in, p=p).replace("torque_Nm = 100\nspeed_exponent = " + str(p),
                                                         load.format(p=p)))
    loaded, design = api.load_and_design(str(path), [])
    return Layout.of(spec_from_design(loaded.design, design))


def test_the_operating_speed_of_a_torque_drive_is_where_it_balances_the_load(tmp_path):
    """Where the linearisation (modes, the ringing fits) and the periodic search's mesh period take the train:
    the drive's balance with the load, not ``speed_rpm`` (was: the nominal speed, so ``steady = "periodic"``
    sought a period 4.9 % short on a fan driven 10 % under its nominal torque, and never converged)."""
    from gearcli.model.damping import operating_speed_rad_s
    from gearcli.simulate.periodic import steady_input_speed_rad_s
    rpm = math.pi / 30.0
    # by hand: T_in = T_req (n / n_0)^p with T_req = 50 N·m: p = 2 -> 1500 sqrt(1.2), p = 1 -> 1500 * 1.2
    for t_in, p, n in ((60.0, 2, 1500.0 * math.sqrt(1.2)), (60.0, 1, 1800.0), (40.0, 2, 1500.0 * math.sqrt(0.8))):
        lay = _layout(tmp_path, t_in, p)
        assert_allclose(operating_speed_rad_s(lay) / rpm, n, rtol=1e-12)
        assert_allclose(steady_input_speed_rad_s(lay) / rpm, n, rtol=1e-12)
    # a constant load balances nowhere: the nominal speed stays the reference
    lay = _layout(tmp_path, 60.0, 0)
    assert operating_speed_rad_s(lay) == 1500.0 * rpm
    # a table load (output rpm, N·m), linear between its points: T_L(n_out) = 20 + 0.1 n_out; T_in = 60 N·m
    # balances it where T_L = 2 * 60 = 120 N·m: n_out = 1000, n_in = 2000 rpm
    lay = _layout(tmp_path, 60.0, 0, "torque_speed = [[0, 20], [2000, 220]]")
    assert_allclose(operating_speed_rad_s(lay) / rpm, 2000.0, rtol=1e-6)


def test_the_rigid_mode_of_a_torque_driven_fan_decays_at_the_load_slope_where_it_settles(tmp_path):
    """The free chain's real (rigid-body) eigenvalue is -d / J_eff, d the fan's dT/dw at the speed the train settles
    at (by hand: the output at w* = 0.5 * 1643.17 rpm = 86.04 rad/s, w_0 = 78.54 rad/s, d = 2 T_L w* / w_0^2 =
    2.790 N·m·s/rad; J_eff = 0.02 + 0.002 * 2^2 = 0.028 kg·m²: -99.6 /s). At the nominal speed's slope (the old
    linearisation) it read -90.9 /s, 9.5 % slow, and the ringing fits and modes took that."""
    from gearcli.model.linear import damped_eigenvalues, static_forces
    lay = _layout(tmp_path, 60.0, 2)
    w0, w_star = 750.0 * math.pi / 30.0, 0.5 * 1500.0 * math.sqrt(1.2) * math.pi / 30.0
    hand = -(2.0 * 100.0 * w_star / w0**2) / (0.02 + 0.002 * 4.0)
    lam = damped_eigenvalues(lay, static_forces(lay))
    real = [z.real for z in lam if abs(z.imag) < 1e-9 and abs(z.real) > 1e-6]
    assert len(real) == 1
    assert_allclose(real[0], hand, rtol=1e-3)  # the mesh's compliance moves it by ~(w_rigid / w_mesh)^2 only


def test_a_table_load_that_meets_the_drive_names_where_the_train_settles(tmp_path):
    """A rising ``torque_speed`` table balances a torque drive as a speed law does (was: "nothing balances the
    difference ... accelerates for the whole run", while the run settled). By hand: T_L(n_out) = 20 + 0.1 n_out
    (95 N·m at the nominal 750 rpm, 47.5 N·m at the input); T_in = 60 N·m meets T_L = 120 N·m at n_out = 1000 rpm
    (input 2000 rpm), T_in = 30 N·m meets 60 N·m at 400 rpm (input 800); 5 N·m (10 N·m < the table's least 20)
    meets it nowhere: the train decelerates to rest, where the table's 20 N·m at standstill holds it."""
    path = tmp_path / "table.toml"
    for t_in, words in ((60.0, "meets it at 1000 rpm of the output, so the train settles at 2000 rpm"),
                        (30.0, "meets it at 400 rpm of the output, so the train settles at 800 rpm"),
                        (5.0, "slows down to rest, where the load's torque_speed table holds it")):
        path.write_text(SCENE.format(t_in=t_in, p=0).replace("torque_Nm = 100\nspeed_exponent = 0",
                                                             "torque_speed = [[0, 20], [2000, 220]]"))
        _, design = api.load_and_design(str(path), [])
        found = [d for d in design.diagnostics if d.data.get("check") == "torque_drive_balance"]
        assert len(found) == 1 and words in found[0].message, found[0].message
    # the simulated train goes there (the rigid time constant J_eff / (dT/dw) = 0.028 / (0.1 * 30 / pi) ~ 29 ms)
    path.write_text(SCENE.format(t_in=60.0, p=0).replace("torque_Nm = 100\nspeed_exponent = 0",
                                                         "torque_speed = [[0, 20], [2000, 220]]"))
    loaded, design = api.load_and_design(str(path), ["simulation.window_start_s=0.4"])
    result = api.simulate(loaded.design, design)
    assert_allclose(result.input_speed_deg_s / 6.0, 2000.0, rtol=1e-4)


def test_a_reversed_constant_load_says_which_way_the_train_goes(tmp_path):
    """Against a reversed (driving) constant load the train's fate follows the sign of the net torque T_in - T_req,
    not the two magnitudes (was: "decelerates (and reverses)" for T_in = -40 N·m against T_req = -50 N·m, while
    the train speeds up, and "accelerates" for -60 N·m, while it slows down and reverses). By hand, lossless,
    T_req = T_L / u = -100 / 2 = -50 N·m at the input; the rigid train J_eff = 0.002 + 0.02 / 2^2 = 0.007 kg·m²
    speeds up at a = (T_in - T_req) / J_eff, so over the window [t0, t1] its mean input speed is
    w_0 + a (t0 + t1) / 2 (1500 rpm at t = 0, the torque drive's start)."""
    rpm = math.pi / 30.0
    for t_in, words in ((-40.0, "accelerates for the whole run"), (-60.0, "decelerates (and reverses)")):
        path = tmp_path / "reversed.toml"
        path.write_text(SCENE.format(t_in=t_in, p=0).replace("torque_Nm = 100\n", "torque_Nm = -100\n")
                        .replace("duration_s = 0.6", "duration_s = 0.2"))
        loaded, design = api.load_and_design(str(path), [])
        found = [d for d in design.diagnostics if d.data.get("check") == "torque_drive_balance"]
        assert len(found) == 1 and words in found[0].message, found[0].message
        assert_allclose(found[0].data["required_input_torque_Nm"], -50.0, rtol=1e-12)
        result = api.simulate(loaded.design, design)
        t0, t1 = result.window_s
        a = (t_in + 50.0) / (0.002 + 0.02 / 4.0)
        hand = 1500.0 + a * 0.5 * (t0 + t1) / rpm
        assert_allclose(result.input_speed_deg_s / 6.0, hand, rtol=2e-3)  # the mesh's compliance only
        assert (result.input_speed_deg_s / 6.0 - 1500.0) * (t_in + 50.0) > 0.0


OVERHAULING = [[0, -150], [1000, -40], [2000, 0]]  # output rpm, N·m: a load that drives the train below 2000 rpm


def _overhauling(tmp_path, t_in, sets=()):
    path = tmp_path / "overhauling.toml"
    path.write_text(SCENE.format(t_in=t_in, p=0).replace("normal_pressure_angle_deg = 20\n",
                                                         "normal_pressure_angle_deg = 20\nefficiency = 0.9\n")
                    .replace("torque_Nm = 100\nspeed_exponent = 0", f"torque_speed = {OVERHAULING}"))
    loaded, design = api.load_and_design(str(path), list(sets))
    found = [d for d in design.diagnostics if d.data.get("check") == "torque_drive_balance"]
    return loaded, design, found


def test_a_torque_drive_against_an_overhauling_table_settles_where_the_losses_say(tmp_path):
    """A table load that drives the train (negative torque) balances a torque drive where the table meets the drive's
    torque carried through the losses in the power flow's direction, found in the way the train moves. By hand
    (u = 2, eta = 0.9, nominal 750 rpm at the output where the table gives -67.5 N·m, so T_req = -67.5 eta / u =
    -30.375 N·m): T_in = -10 N·m brakes the load's power flowing back, T_L = T_in u / eta = -22.22 N·m, met on the
    second segment at 1444.4 rpm (input 2888.9 rpm), above the nominal speed since T_in > T_req; T_in = +10 N·m
    drives the train forward, T_L = T_in u eta = +18 N·m, met on the last segment extended at 2450 rpm (input
    4900). Was 1161.6 rpm (sought downwards, the first segment extended) and 2555.6 rpm (the load's scale taken
    through the nominal losses), and the model took speed_rpm for a negative drive torque, so the run's static
    F_t reference (dynamic factor) was the nominal load's: 0.33x where the drive ran at its balance."""
    from gearcli.model.assembly import Layout
    from gearcli.model.damping import operating_speed_rad_s
    from gearcli.scene import spec_from_design
    rpm = math.pi / 30.0
    for t_in, n_out in ((-10.0, 1000.0 + 1000.0 * (40.0 - 10.0 * 2.0 / 0.9) / 40.0), (10.0, 2000.0 + 10.0 * 2.0 * 0.9 / 0.04)):
        loaded, design, found = _overhauling(tmp_path, t_in)
        assert len(found) == 1, [d.message for d in design.diagnostics]
        assert_allclose(found[0].data["required_input_torque_Nm"], -67.5 * 0.9 / 2.0, rtol=1e-12)
        assert f"meets it at {n_out:.5g} rpm of the output, so the train settles at {2.0 * n_out:.5g} rpm" \
            in found[0].message, found[0].message
        lay = Layout.of(spec_from_design(loaded.design, design))
        assert_allclose(operating_speed_rad_s(lay) / rpm, 2.0 * n_out, rtol=1e-9)


def test_the_dynamic_factor_refers_to_the_load_where_the_drive_settles_on_an_overhauling_table(tmp_path):
    """The run's static F_t reference (``simulated_static_tangential_N``, the dynamic factor's) is the load where the
    torque drive settles, with the losses in that load's power flow. By hand (r_p = 3 * 20 / 2 = 30 mm): T_in =
    +10 N·m drives the train forward at its balance, F_t = T_in / r_p = 333.33 N (the nominal load, -67.5 N·m,
    flows back: scaled with its losses the reference read eta x that, 300 N, a dynamic factor of 1.111 on a steady
    run); T_in = -10 N·m brakes the power flowing back, the gear drives and the pinion gets eta of the law's force:
    F_t = T_in / (eta r_p) = -370.37 N (was the nominal load's -1125 N, a dynamic factor of 0.33). The loaded flank
    is the one the operating load presses: at +10 N·m the drive flank carries the whole window (F_t > 0 throughout),
    which read as the nominal load's back flank lost in 100 % of the samples (``contact_loss``, back-flank fraction 1)."""
    for t_in, hand in ((10.0, 10.0 / 0.030), (-10.0, -10.0 / (0.9 * 0.030))):
        loaded, design, _ = _overhauling(tmp_path, t_in, ["simulation.duration_s=1.2", "simulation.steps=1200",
                                                          "simulation.window_start_s=0.8"])
        result = api.simulate(loaded.design, design)
        stage = result.stages[0]
        assert_allclose(stage.simulated_static_tangential_N, hand, rtol=1e-9)
        assert_allclose(stage.tangential_N.mean, hand, rtol=1e-4)  # settled: tau = J_eff / (dT/dw) ~ 0.08 s
        assert_allclose(stage.dynamic_factor, 1.0, atol=1e-3)
        assert stage.tangential_N.min * hand > 0.0 and stage.tangential_N.max * hand > 0.0  # one flank throughout
        assert stage.back_flank_fraction == 0.0 and stage.contact_loss_fraction == 0.0
        assert not [d for d in result.diagnostics if d.code == "contact_loss"]
        # report's theory at the operating point: F_t by hand, F_r = F_t tan 20° (spur) (was 300 N at +10 N·m: -11 %)
        from gearcli.model.assembly import Layout
        from gearcli.report.build import theory_point
        from gearcli.report.compare import comparison_rows
        from gearcli.scene import spec_from_design
        rows = comparison_rows(design, result, theory_point(Layout.of(spec_from_design(loaded.design, design)), design))
        theory = {r.quantity: r.theory for r in rows if r.stage == 1}
        assert_allclose([theory["tangential_N"], theory["radial_N"]], [hand, hand * math.tan(math.radians(20.0))],
                        rtol=1e-9)


def test_a_negative_drive_torque_against_a_speed_law_settles_backwards(tmp_path):
    """A speed law odd in speed brakes the train turning backwards: T_in = -30 N·m against the fan's T_req = 50 N·m
    (module scene) settles at -1500 sqrt(30 / 50) = -1161.9 rpm (p = 2), -1500 x 30 / 50 = -900 rpm (p = 1), by
    hand (the rigid train's T_in = T_req (n / n_0) |n / n_0|^(p-1)); a zero drive torque lets the load brake it
    towards rest, which a law falling with the speed never reaches. Was "decelerates (and reverses) for the whole
    run" for all three."""
    for t_in, p, words in ((-30.0, 2, f"settles at {-1500.0 * math.sqrt(0.6):.5g} rpm"), (-30.0, 1, "settles at -900 rpm"),
                           (0.0, 2, "brakes the train towards rest")):
        _, _, found = _balance(tmp_path, t_in, p)
        assert len(found) == 1 and words in found[0].message and "reverses) for" not in found[0].message, \
            found[0].message


def test_a_planetary_stage_s_static_reference_takes_the_other_flow_s_losses(tmp_path):
    """configs/mixer_planetary_motor.toml (planetary 18/45/108 x 3, ring held, sun in, eta 0.98; helical 17/121, eta
    0.985) on a torque drive of 30 N·m against an overhauling table, -30 kN·m at rest to +2 kN·m at 40 rpm: the
    nominal 29.8 rpm reads -3100 N·m (power flowing back), the balance (by hand, T_L = T_in i eta at 38.886 rpm) is
    forward. The sun drives its three planets there: F_t = T_in / (3 r_s) = 30 / (3 x 0.027) = 370.37 N, which the
    run's window mean gives (370.33 N over 10-12 s); the reference took the planet mesh's own loss for the nominal
    reversed flow, 359.88 N (a dynamic factor of 1.029 on a steady run)."""
    from gearcli.model import TorsionalModel
    from gearcli.model.damping import operating_speed_rad_s
    from gearcli.simulate.run import simulated_static_tangential_N
    text = (Path(__file__).resolve().parents[2] / "configs" / "mixer_planetary_motor.toml").read_text()
    path = tmp_path / "mixer.toml"
    path.write_text(text.replace("speed_exponent = 1 ", "# "))
    loaded, design = api.load_and_design(str(path), [
        "input.drive=torque", "input.torque_Nm=30", "load.torque_speed=[[0, -30000], [20, -8000], [40, 2000]]"])
    model = TorsionalModel(api.model_spec(loaded.design, design))
    ratio = 7.0 * 121.0 / 17.0
    n_out = 20.0 + 20.0 * (30.0 * ratio * 0.98 * 0.985 + 8000.0) / 10000.0  # the table's second segment
    assert_allclose(operating_speed_rad_s(model.layout) / ratio * 30.0 / math.pi, n_out, rtol=1e-6)
    sun, _ = simulated_static_tangential_N(model)
    assert_allclose(sun, 30.0 / (3 * 0.027), rtol=1e-9)
    # report's theory there (the run need not settle for it): F_t and F_r = F_t tan 20° (spur) by hand (was 349.19 N)
    from gearcli.report.build import theory_point
    from gearcli.report.compare import comparison_rows
    short = api.load_and_design(str(path), ["input.drive=torque", "input.torque_Nm=30", "simulation.duration_s=0.05",
                                            "simulation.steps=100", "load.torque_speed=[[0, -30000], [20, -8000], [40, 2000]]"])
    result = api.simulate(short[0].design, short[1])
    rows = comparison_rows(short[1], result, theory_point(model.layout, short[1]))
    theory = {r.quantity: r.theory for r in rows if r.stage == 1}
    assert_allclose([theory["tangential_N"], theory["radial_N"]],
                    [30.0 / (3 * 0.027), 30.0 / (3 * 0.027) * math.tan(math.radians(20.0))], rtol=1e-9)


def test_a_drive_below_a_table_s_breakaway_leaves_the_train_held_at_rest(tmp_path):
    """A table that resists at rest (its first point, turning with the rotation) holds the train once a drive short
    of the load has let it slow down: it stops and does not reverse. By hand (u = 2, eta = 0.9): the table 400 N·m
    at rest, 212.5 N·m at the nominal 750 rpm (T_req = 212.5 / (u eta) = 118.06 N·m), never below 150 N·m; T_in =
    50 N·m balances T_in u eta = 90 N·m at the output, which the table never comes down to: held at rest (the run
    creeps at 1.8 rpm, the table's tanh over 0.5 % of the nominal speed). Was "decelerates (and reverses)"."""
    path = tmp_path / "held.toml"
    path.write_text(SCENE.format(t_in=50.0, p=0).replace("normal_pressure_angle_deg = 20\n",
                                                          "normal_pressure_angle_deg = 20\nefficiency = 0.9\n")
                    .replace("torque_Nm = 100\nspeed_exponent = 0", "torque_speed = [[0, 400], [1000, 150], [2000, 300]]"))
    _, design = api.load_and_design(str(path), [])
    found = [d for d in design.diagnostics if d.data.get("check") == "torque_drive_balance"]
    assert len(found) == 1 and "reverses" not in found[0].message.replace("does not reverse", ""), found[0].message
    assert_allclose(found[0].data["required_input_torque_Nm"], 212.5 / (2.0 * 0.9), rtol=1e-12)
    assert "stays at rest" in found[0].message and f"{50.0 * 2.0 * 0.9:.5g} N·m the drive balances" in found[0].message
