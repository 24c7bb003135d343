"""Guard rails of the integration (gearcli/simulate/guards.py, solver.py): every way a run can go wrong
ends in a SimulationError (exit 1) that names the cause and the fix, decided from the solver's status,
never in NaN output or a traceback; and the fixes found with the extreme catalogue stay fixed.
"""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest
from catalogue import ROOT, SCENES, SCENES_DIR
from click.testing import CliRunner
from handcalc import Train, read
from numpy.testing import assert_allclose

from gearcli import diagnostics as dg
from gearcli.cli import cli
from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.errors import SimulationError
from gearcli.io.channels import named
from gearcli.model import DriveSpec, LoadSpec, MeshSpec, ModelSpec, TorsionalModel
from gearcli.scene import spec_from_design
from gearcli.simulate import run_simulation, simulate_model
from gearcli.simulate.choice import choose_method
from gearcli.simulate.guards import CAP, FLOOR, force_noise, nfev_budget
from gearcli.simulate.run import check
from gearcli.simulate.solver import STATUS_FAILED, breakpoints, integrate


def scene(name: str, overrides=()):
    loaded = load_design(str(SCENES_DIR / f"{name}.toml"), list(overrides))
    return loaded.design, compute_design(loaded.design)


def one_stage_model() -> TorsionalModel:
    """A small linear undamped stage under a speed drive (0.1 s ramps): w_n ~ 1.3 kHz, cheap to run."""
    mesh = MeshSpec(base_radius_pinion_m=0.06, base_radius_gear_m=0.15, base_helix_angle_rad=0.17,
                    transverse_pressure_angle_rad=0.355, helix_angle_rad=0.18, stiffness_N_m_e=2e8, exponent=1.0,
                    damping_Ns_m=0.0, full_damping_m=1e-4, normal_module_m=0.004, static_tangential_N=1900.0)
    return TorsionalModel(ModelSpec((mesh,), (0.3, 2.5), DriveSpec("speed", 50.0, 0.1), LoadSpec(300.0, 0.1)))


def sabotage(model: TorsionalModel, extra) -> TorsionalModel:
    """The model with ``extra(t, y, dydt)`` applied to its right-hand side (the gear's speed row)."""
    rhs, row = model.rhs, model.layout.i_omega(1)

    def wrapped(t, y):
        d = rhs(t, y)
        d[row] = extra(t, y, d)
        return d

    model.rhs = wrapped
    return model


# ------------------------------------------------------------------------ restart at the ramp ends
def test_breakpoints_are_the_ramp_ends_inside_the_run():
    model = one_stage_model()
    assert breakpoints(model, 0.5) == [0.1, 0.5]  # input and load ramps both end at 0.1 s
    assert breakpoints(model, 0.05) == [0.05]  # a ramp that outlasts the run is no breakpoint


@pytest.mark.parametrize("rtol", [1e-6, 1e-7])
def test_radau_across_the_ramp_end_follows_the_rigid_body_force(rtol):
    # 10,000x stiff linear meshes: the train is rigid to ~1e-9 m, so F_t(t) must follow the hand-calculated
    # rigid-body force (load plus run-up inertia) at every sample; the true ringing is ~1 % of the static
    # force (DOP853 at rtol 1e-10: std 15 N of 1851 N). Before the solver restarted at the ramp end, Radau
    # missed it by 100 % (rtol 1e-6) and rang by 60 % (rtol 1e-7) after t = 0.18 s.
    cfg, design = scene("stiff_linear_10000x")
    sim = run_simulation(cfg, design, method="Radau", rtol=rtol)
    train = Train(read(SCENES_DIR / "stiff_linear_10000x.toml"))
    for k in range(3):
        dev = np.abs(named(sim)[f"stage{k + 1}_tangential_N"] - train.rigid_tangential_N(k, sim.time_s))
        assert dev.max() < 0.02 * train.static_tangential_N(k), (k, dev.max())
    assert sim.energy.residual_relative < 1e-6  # quadratures under error control: no false energy warning
    # no other warning than the law's (a given linear K 10,000x the seed's is ~1,000x ISO's mesh stiffness: the
    # design's stiffness_not_iso on every stage); at rtol 1e-6 Radau's 51 steps cannot show
    # the ~1 % ringing, and the run says so per stage (docs/numerics.md "Honest statistics"); at 1e-7 its steps are fine
    # enough not to be flagged
    run = [d for d in sim.diagnostics if d.code != dg.STIFFNESS_NOT_ISO]
    assert {d.code for d in run} <= {dg.STATISTICS_UNRESOLVED}, sim.warnings
    assert len(run) == (3 if rtol == 1e-6 else 0), sim.warnings


# ------------------------------------------------------------------------------------------ budget
def test_budget_scales_with_the_scene_between_floor_and_cap():
    assert nfev_budget(1.0, 1e-6) == FLOOR  # a short soft run is never stopped early
    assert nfev_budget(1e12, 1e-6) == CAP
    assert nfev_budget(1e3, 1e-6) == 10 * 30 * 1e3
    assert_allclose(nfev_budget(1e3, 1e-11) / nfev_budget(1e3, 1e-6), 10.0, rtol=1e-6)  # (1e5)^(1/5)


def test_the_budget_is_ten_times_the_prediction_where_an_excitation_costs_more_than_the_stiffness():
    # the stiffness term of 1e3 max|lambda| T at rtol 1e-6: 30 x 1e3; a prediction of 1e5 evaluations (an
    # excitation to follow): 10 x 1e5; a prediction below the stiffness term leaves it; the cap holds
    assert nfev_budget(1e3, 1e-6, predicted=1e5) == 10 * 1e5
    assert nfev_budget(1e3, 1e-6, predicted=1e3) == 10 * 30 * 1e3
    assert nfev_budget(1e3, 1e-6, predicted=1e7) == CAP


def test_a_fast_load_fluctuation_is_not_stopped_by_the_stiffness_budget():
    # a 100 kHz, 100 % load fluctuation over 0.3 s: 2 pi 1e5 x 0.3 = 1.9e5 rad of excitation to follow, ~7e5
    # evaluations, over the 300 x max|lambda| T (2.0e3: 6.1e5) its stiffness alone allowed: the run stopped with
    # "check the contact law"; its budget is now ten times its prediction. Over whole fluctuation periods the load
    # averages to its nominal torque: stage 1's window-mean F_t is the static one, to the run's error estimate.
    loaded = load_design(str(ROOT / "configs" / "industrial_two_stage_rated.toml"),
                         ["simulation.duration_s=0.3", "stage.0.normal_module_mm=8",
                          "load.fluctuation=[{amplitude_percent=100, frequency_Hz=1e5}]"])
    design = compute_design(loaded.design)
    sim = run_simulation(loaded.design, design, want_series=False)
    assert sim.solver.status == 0
    assert sim.solver.nfev > 300 * sim.extra["stiffness_indicator"]  # beyond the stiffness-only budget
    st = sim.stages[0]
    err = st.error_estimate.tangential_N.mean if st.error_estimate is not None else 0.0
    static = design.stages[0].static_force_N.tangential
    assert abs(st.tangential_N.mean - static) <= max(3 * err, 2e-3 * static)


def test_every_catalogue_scene_stays_within_a_third_of_its_budget():
    # the budget must never stop a legitimate run: each scene's nfev ceiling (~3x its measured cost, and
    # enforced by the catalogue test) lies within the scene's budget
    for s in SCENES:
        cfg, design = scene(s.name)
        choice = choose_method(spec_from_design(cfg, design), cfg.simulation.duration_s, "auto")
        assert s.nfev_ceiling <= nfev_budget(choice.indicator, cfg.simulation.rtol), s.name


def test_the_costliest_measured_combination_finishes_within_its_budget():
    # Radau at rtol 1e-9 on time-varying stiffness with backlash: ~87 evaluations per unit of max|lambda| T,
    # the most of any method x rtol measured (benchmarks/bench_simulate.py ladder); its budget allows 10x
    # 30 x 4 = 1200 per unit
    loaded = load_design(str(ROOT / "configs" / "mixer_time_varying_backlash.toml"), [])
    sim = run_simulation(loaded.design, compute_design(loaded.design), method="Radau", rtol=1e-9, want_series=False)
    assert sim.solver.status == 0
    assert sim.solver.nfev * 3 < nfev_budget(sim.extra["stiffness_indicator"], 1e-9)


def test_a_run_over_budget_stops_with_the_cause():
    model = sabotage(one_stage_model(), lambda t, y, d: d[1])
    with pytest.raises(SimulationError, match=r"stopped at t = .*more than 2000 right-hand-side evaluations"):
        simulate_model(model, duration_s=0.5, steps=50, method="RK45", max_nfev=2000)


# ------------------------------------------------------------------ explicit method on a stiff scene
@pytest.mark.parametrize("method", ["RK45", "DOP853"])
def test_explicit_method_on_an_extremely_stiff_scene_is_refused_before_it_starts(method):
    # 1e-6 vs 1e4 kg m^2: max|lambda| T = 7.5e9; stability alone would take 1e10 evaluations (hours)
    cfg, design = scene("unequal_inertias")
    with pytest.raises(SimulationError) as err:  # refused up front (the message below), not ground through
        run_simulation(cfg, design, method=method)
    msg = str(err.value)
    # its fastest eigenvalue is a decay (the stage 1 mesh's damping against the 1e-6 kg m^2 shaft), not a vibration
    assert f'method = "{method}" cannot integrate this scene: its fastest motion is a decay' in msg
    assert "mesh stage 1's damping against the light inertias it joins makes it" in msg
    assert "stiffer than an explicit method affords" in msg and 'use method = "Radau"' in msg
    assert err.value.exit_code == 1


def _dop853_refusal(path) -> str:
    """The message of DOP853's up-front refusal of the design file at ``path``."""
    cfg = load_design(str(path)).design
    with pytest.raises(SimulationError) as err:
        run_simulation(cfg, compute_design(cfg), method="DOP853")
    return str(err.value)


def test_a_refusal_set_by_a_damper_on_a_light_body_names_the_damper_not_a_mesh(tmp_path):
    # a 2e-6 kg m^2 gear on a 5 N m s/rad load coupling to a 0.5 kg m^2 drum: the coupling's damper alone decays
    # the gear's motion at c / J = 2.5e6 1/s, four times faster than the mesh mode (1e5 N/mm against 1e-6 and
    # 2e-6 kg m^2: sqrt(k (r1^2/J1 + r2^2/J2)) = 6.0e5 rad/s); an explicit method's steps are set by that decay,
    # and the refusal said "mesh stage 1 makes it ... stiffer" (highest mode 96 kHz), which no mesh change cures
    path = tmp_path / "damper.toml"
    path.write_text(
        'title = "damper on a light gear"\n'
        "stage = [{ normal_module_mm = 4, normal_pressure_angle_deg = 20, "
        "pinion = { teeth = 20, face_width_mm = 30, inertia_kg_m2 = 1e-6 }, "
        "gear = { teeth = 35, face_width_mm = 30, inertia_kg_m2 = 2e-6 } }]\n"
        "contact = { stiffness = 1e5, exponent = 1, damping_ratio = 0.05 }\n"
        "input = { drive = \"torque\", speed_rpm = 1000, torque_Nm = 5.714285714285714, ramp_s = 0.01 }\n"
        "load = { torque_Nm = 10, ramp_s = 0.01, inertia_kg_m2 = 0.5, coupling_stiffness_Nm_rad = 2e4, "
        "coupling_damping_Nms_rad = 5 }\n"
        "simulation = { duration_s = 0.3, steps = 3000 }\n")
    msg = _dop853_refusal(path)
    assert "the load coupling's damping against the light inertias it joins makes it" in msg
    assert "mesh stage 1 makes it" not in msg
    rate = float(msg.split("a decay at ")[1].split(" 1/s")[0])
    assert abs(rate - 5.0 / 2e-6) <= 0.05 * 5.0 / 2e-6  # c / J of the gear, to the mesh's and drum's share


def test_a_refusal_set_by_a_stiff_shaft_on_a_light_pinion_names_the_shaft_not_a_mesh(tmp_path):
    # trial tr28b: stage 1's gear (0.25 kg m^2) joined to stage 2's pinion (1e-4 kg m^2) by a 2e10 N m/rad shaft.
    # By hand the shaft's own mode is sqrt(k (1/J_g1 + 1/J_p2)) / 2 pi = 2.2512e6 Hz, the stage 2 mesh's
    # sqrt(K cos^2 beta_b (r_b1^2/J_p2 + r_b2^2/J_g2)) / 2 pi ~ 1.8e4 Hz (K 5e8 N/m, r_b1 = 51.1 mm): the refusal said
    # "mesh stage 2 makes it 7.1e+02x stiffer", the one element whose change would not cure it
    path = tmp_path / "stiff_shaft.toml"
    path.write_text(
        'title = "stiff shaft on a light pinion"\n'
        "[[stage]]\nnormal_module_mm = 4\nnormal_pressure_angle_deg = 20\nhelix_angle_deg = 10\n"
        'pinion = { teeth = 22, face_width_mm = 50, hand = "left", inertia_kg_m2 = 0.003 }\n'
        'gear = { teeth = 67, face_width_mm = 48, hand = "right", inertia_kg_m2 = 0.25 }\n'
        "shaft = { stiffness_Nm_rad = 2.0e10, damping_Nms_rad = 5 }\n"
        "[[stage]]\nnormal_module_mm = 6\nnormal_pressure_angle_deg = 20\nhelix_angle_deg = 8\n"
        'pinion = { teeth = 18, face_width_mm = 80, hand = "right", inertia_kg_m2 = 1e-4 }\n'
        'gear = { teeth = 59, face_width_mm = 76, hand = "left", inertia_kg_m2 = 2.5 }\n'
        "[contact]\nstiffness = 5e5\nexponent = 1\ndamping_ratio = 0.05\n"
        "[input]\nspeed_rpm = 980\nramp_s = 0.15\n[load]\ntorque_Nm = 4000\nramp_s = 0.15\n"
        "[simulation]\nduration_s = 0.5\nsteps = 5000\n")
    msg = _dop853_refusal(path)
    assert "shaft 2 makes it" in msg and "mesh stage 2 makes it" not in msg, msg
    shaft_Hz = math.sqrt(2.0e10 * (1 / 0.25 + 1 / 1e-4)) / (2 * math.pi)
    highest = float(msg.split("highest mode ")[1].split(" Hz")[0])
    assert abs(highest / shaft_Hz - 1) < 0.01, (highest, shaft_Hz)  # the mode the refusal names is the shaft's
    at = math.atan(math.tan(math.radians(20)) / math.cos(math.radians(8)))
    rb1, rb2 = (z * 6 / math.cos(math.radians(8)) / 2 * math.cos(at) * 1e-3 for z in (18, 59))
    cb = math.cos(math.atan(math.tan(math.radians(8)) * math.cos(at)))
    mesh_Hz = math.sqrt(5e8 * cb**2 * (rb1**2 / 1e-4 + rb2**2 / 2.5)) / (2 * math.pi)
    assert shaft_Hz > 100 * mesh_Hz  # by hand: the shaft, not the mesh, sets the explicit step


def test_refusal_through_the_cli_is_exit_1_one_line_and_no_file(tmp_path):
    out = tmp_path / "out.csv"
    out.write_text("previous\n")
    res = CliRunner().invoke(cli, ["simulate", str(SCENES_DIR / "unequal_inertias.toml"), "-o", str(out),
                                   "--set", 'simulation.method="DOP853"'])
    assert res.exit_code == 1
    assert "Traceback" not in res.output
    # the design's warnings first (its point-contact law is far from ISO's stiffness), then the one error line
    (error,) = [line for line in res.stderr.splitlines() if not line.startswith("warning: ")]
    # the failed run names its file first, as every message does (docs/output.md, "Exit codes")
    assert error.startswith(f'gearcli: {SCENES_DIR / "unequal_inertias.toml"}: method = "DOP853" cannot integrate')
    assert 'use method = "Radau"' in res.stderr
    assert out.read_text() == "previous\n" and sorted(p.name for p in tmp_path.iterdir()) == ["out.csv"]


# ---------------------------------------------------------------------------- divergence and NaN
@pytest.mark.parametrize("method", ["DOP853", "Radau"])
def test_energy_created_from_nothing_stops_the_run_early(method):
    # negative damping on the mesh, c = 20 kN s/m (the gear is pushed along the deflection rate delta' = d[0]:
    # J_g w_g' gains -c r_bg delta' instead of +c r_bg delta'): the vibration grows like exp(c t / 2m),
    # m = J_g / r_bg^2 = 111 kg, an e-fold every ~11 ms; the mechanical energy outgrows the net work of
    # drive and load, and the watch stops the run long before NaN
    model = sabotage(one_stage_model(), lambda t, y, d: d[1] - 2e4 * 0.15 * d[0] / 2.5)
    with pytest.raises(SimulationError, match="the solution is unstable: the energy in the gear train grew") as err:
        simulate_model(model, duration_s=0.3, steps=300, method=method)
    t_stop = float(str(err.value).split("stopped at t = ")[1].split(" s")[0])
    assert t_stop < 0.15


@pytest.mark.parametrize("method", ["DOP853", "Radau", "BDF"])
@pytest.mark.parametrize("bad", [math.nan, 1e308])
def test_non_finite_or_overflowing_right_hand_side_is_a_clean_error(method, bad):
    # NaN is caught in the right-hand-side wrapper ("diverged"); a finite 1e308 overflows inside Radau's
    # Newton solve (its LU raises ValueError from inside scipy: "diverged") or makes BDF's step collapse
    model = sabotage(one_stage_model(), lambda t, y, d: bad if t > 0.05 else d[1])
    with pytest.raises(SimulationError, match=r"stopped at t = 0\.0[45]\d* s .*(diverged|step size collapsed)"):
        simulate_model(model, duration_s=0.3, steps=300, method=method)


def test_step_size_collapse_is_judged_by_status():
    # a finite-time singularity (1/(0.1 - t)^2) with the energy watch off: the solver reports failure
    # (status -1); check() turns that status, not the message text, into the error
    model = sabotage(one_stage_model(), lambda t, y, d: d[1] + 1.0 / (0.1 - t) ** 2 if t < 0.1 else 1e300)
    run = integrate(model, np.linspace(0, 0.3, 301), "RK45", 1e-6, watch_energy=False)
    assert run.status == STATUS_FAILED and np.isnan(run.y[:, -1]).all() and run.t_fail < 0.1
    with pytest.raises(SimulationError, match="step size collapsed"):
        check(run, choose_method(model.spec, 0.3, "RK45"), 0.3)


# ----------------------------------------------------------------------------------------- warnings
def test_forced_methods_that_cannot_resolve_a_very_stiff_mesh_force_are_warned():
    # 10,000x stiff linear meshes: a speed error at rtol 1e-6 is worth ~19 % of stage 1's static force
    # through the mesh impedance sqrt(k m); BDF forced here strays ~85 % from the rigid-body force
    cfg, design = scene("stiff_linear_10000x")
    choice = choose_method(spec_from_design(cfg, design), 0.5, "BDF")
    k_d = choice.at_full_load.stiffness_N_m[0]
    m = design.shafts[1].inertia_kg_m2 / (design.stages[0].gear.base_diameter_mm / 2e3) ** 2
    v_tol = 1e-6 * 2 * (design.stages[0].pinion.base_diameter_mm / 2e3) * math.radians(3600)
    f_bt = abs(choice.at_full_load.line_forces_N[0])
    assert_allclose(force_noise(choice, 1e-6)[0], v_tol * math.sqrt(k_d * m) / f_bt, rtol=1e-9)
    res = CliRunner().invoke(cli, ["simulate", str(SCENES_DIR / "stiff_linear_10000x.toml"), "--format", "json",
                                   "--set", 'simulation.method="LSODA"', "--set", "simulation.duration_s=0.2"])
    assert res.exit_code == 0 and "LSODA may show spurious force noise" in res.stderr
    auto = CliRunner().invoke(cli, ["simulate", str(SCENES_DIR / "stiff_linear_10000x.toml"), "--format", "json"])
    assert auto.exit_code == 0 and "spurious" not in auto.stderr  # Radau damps what it cannot resolve


def test_physically_doubtful_scenes_are_warned():
    # (a) penetration beyond 10 % of m_n: configs/extreme/overload.toml (catalogue check)
    # (b) a transient beyond the full-damping depth: the seed at 10x speed (static 0.0125 mm < d = 0.1 mm)
    res = CliRunner().invoke(cli, ["simulate", str(SCENES_DIR / "high_speed.toml"), "--format", "json"])
    assert res.exit_code == 0 and "beyond the full-damping depth 0.1 mm" in res.stderr
    # (c) a low contact ratio reaches the user of `simulate` too (design checks; eps_alpha < 1 cannot be
    # reached with full-depth teeth of 5+ teeth here, so the < 1.2 sibling stands in for the path)
    res = CliRunner().invoke(cli, ["simulate", str(SCENES_DIR / "one_stage.toml"), "--format", "json",
                                   "--set", "stage.0.helix_angle_deg=0", "--set", 'stage.0.pinion.hand="spur"',
                                   "--set", 'stage.0.gear.hand="spur"', "--set", "stage.0.normal_pressure_angle_deg=35",
                                   "--set", "stage.0.pinion.teeth=8", "--set", "stage.0.gear.teeth=9"])
    assert res.exit_code == 0 and "transverse contact ratio ε_α = 1.159 < 1.2" in res.stderr


# ------------------------------------------------------------------------------ steps and memory
def test_steps_over_the_cap_are_refused_with_exit_2(tmp_path):
    out = tmp_path / "out.csv"
    res = CliRunner().invoke(cli, ["simulate", str(ROOT / "configs" / "concrete_mixer.toml"), "-o", str(out),
                                   "--set", "simulation.steps=3000000"])
    assert res.exit_code == 2
    assert "simulation.steps" in res.stderr and "2000000" in res.stderr and "Traceback" not in res.output
    assert not out.exists()


@pytest.mark.slow
def test_steps_at_the_cap_run_in_bounded_memory():
    # 2,000,000 steps (the schema's cap): the solver keeps no dense solution (samples are taken step by
    # step), so memory is the output: 2e6 samples x (10 states + 17 channels + per-mesh intermediates).
    # Measured peak RSS 0.86 GB for JSON (1.5 GB writing the 430 MB CSV); the bound leaves 2x headroom
    # and sits far below a CI runner's 7 GB.
    code = ("import resource, sys\nfrom gearcli.cli import main\nsys.argv = ['gearcli'] + sys.argv[1:]\n"
            "try:\n    main()\nexcept SystemExit as e:\n"
            "    print('RSS_KB', resource.getrusage(resource.RUSAGE_SELF).ru_maxrss, file=sys.stderr)\n    raise\n")
    res = subprocess.run([sys.executable, "-c", code, "simulate", str(ROOT / "configs" / "concrete_mixer.toml"),
                          "--set", "simulation.steps=2000000", "--format", "json"], capture_output=True, text=True,
                         timeout=120)
    assert res.returncode == 0, res.stderr
    rss_gb = int(res.stderr.split("RSS_KB ")[1].split()[0]) / 1024**2
    assert rss_gb < 1.7, rss_gb


def test_an_auto_run_stopped_on_a_stiff_scene_is_not_told_to_use_auto():
    # auto took DOP853 on a 1e14 N/mm^1.5 law (max|lambda| T 4.9e5, predicted cheaper than Radau's 4.5e6) and
    # spent its budget; the hint said 'use method = "Radau" (or "auto")' to a run that was auto and whose Radau
    # spends the same budget as well (exit 1 at t = 0.14 s): it names Radau's prediction and the fixes that remain
    from dataclasses import replace as _replace

    from gearcli.simulate.solver import STATUS_BUDGET, Integration

    cfg, design = scene("load_reversal", ["simulation.duration_s=0.3", "stage.0.backlash_mm=0",
                                          "stage.0.gear.teeth=13", "contact.stiffness=1e14"])
    model = TorsionalModel(spec_from_design(cfg, design))
    auto = choose_method(model.spec, 0.3, "auto", layout=model.layout)
    assert auto.method == "DOP853"  # the cost model's choice on this scene (1.6e6 against Radau's 4.5e6)
    stopped = Integration(np.zeros(2), np.zeros((model.initial_state().size, 2)), "DOP853", 1e-6, np.ones(1), 5_000_023,
                          0, 0, 10, 1.0, STATUS_BUDGET, "more than 5000000 right-hand-side evaluations", 0.15)
    with pytest.raises(SimulationError) as got:
        check(stopped, auto, 0.3)
    msg = str(got.value)
    assert 'or "auto"' not in msg and "shorten simulation.duration_s" in msg
    assert f"Radau was predicted to need {auto.predicted_evals[1]:.2g} evaluations" in msg
    requested = _replace(auto, requested="DOP853")
    with pytest.raises(SimulationError, match=r'use method = "Radau" \(or "auto"\)'):
        check(stopped, requested, 0.3)


def _chain_modes(J, rows):
    """Hand-assembled undamped modes of a torsional chain: J the free bodies' inertias, rows (levers, k) per
    connector; returns the frequencies (Hz, ascending) and each connector's share of each mode's strain energy."""
    J = np.asarray(J, dtype=float)
    L = np.array([r[0] for r in rows], dtype=float)
    k = np.array([r[1] for r in rows], dtype=float)
    S = 1.0 / np.sqrt(J)
    w2, V = np.linalg.eigh(S[:, None] * (L.T @ np.diag(k) @ L) * S[None, :])
    phi = S[:, None] * V  # body angles per mode
    energy = k[:, None] * (L @ phi) ** 2
    return np.sqrt(w2) / (2 * np.pi), energy / energy.sum(axis=0)


@pytest.mark.parametrize("case", ["shaft", "input coupling"])
def test_an_explicit_refusal_names_the_coupling_or_shaft_that_makes_the_scene_stiff(tmp_path, case):
    # the refusal said "mesh stage 1 makes it ... stiffer" whatever element held the fastest mode: a 1e9 N m/rad
    # shaft between two 4e5 N/mm spur meshes (its own mode 65.6 kHz), or a 1e11 N m/rad input coupling on a
    # 1.25e-3 kg m^2 pinion (1.33 MHz), where no mesh change cures the stiffness
    rb = [20 * 4 * math.cos(math.radians(20)) / 2e3, 60 * 4 * math.cos(math.radians(20)) / 2e3,
          18 * 6 * math.cos(math.radians(20)) / 2e3, 72 * 6 * math.cos(math.radians(20)) / 2e3]
    km = 4e8  # 4e5 N/mm, linear, spur: the transverse stiffness along delta
    shaft = case == "shaft"
    k_shaft, k_in = (1e9, 1e3) if shaft else (None, 1e11)
    text = ('title = "stiff element"\n'
            "[[stage]]\nnormal_module_mm = 4\npinion = { teeth = 20, face_width_mm = 40, inertia_kg_m2 = 1.25e-3 }\n"
            "gear = { teeth = 60, face_width_mm = 40, inertia_kg_m2 = 0.1 }\n"
            + (f"[stage.shaft]\nstiffness_Nm_rad = {k_shaft:g}\n" if shaft else "")
            + "[[stage]]\nnormal_module_mm = 6\npinion = { teeth = 18, face_width_mm = 60, inertia_kg_m2 = 6.25e-3 }\n"
            "gear = { teeth = 72, face_width_mm = 60, inertia_kg_m2 = 1.6 }\n"
            "[contact]\nstiffness = 4e5\nexponent = 1\ndamping_ratio = 0.02\n"
            f"[input]\nspeed_rpm = 1500\nramp_s = 0.1\ninertia_kg_m2 = 0.2\ncoupling_stiffness_Nm_rad = {k_in:g}\n"
            "[load]\ntorque_Nm = 800\nramp_s = 0.1\ninertia_kg_m2 = 50\ncoupling_stiffness_Nm_rad = 2e4\n"
            "[simulation]\nduration_s = 1.0\nsteps = 4000\n")
    path = tmp_path / "stiff.toml"
    path.write_text(text)
    # the speed drive holds the motor: free bodies pinion 1, gear 1 (+ pinion 2 on a rigid shaft), pinion 2 on a
    # flexible one, gear 2, drum; connectors along the chain (levers: base radii, 1 for a spring)
    if shaft:
        J = [1.25e-3, 0.1, 6.25e-3, 1.6, 50.0]
        rows = [([-1, 0, 0, 0, 0], k_in), ([rb[0], -rb[1], 0, 0, 0], km), ([0, 1, -1, 0, 0], k_shaft),
                ([0, 0, rb[2], -rb[3], 0], km), ([0, 0, 0, 1, -1], 2e4)]
        stiff, name = 2, "shaft 2"
    else:
        J = [1.25e-3, 0.1 + 6.25e-3, 1.6, 50.0]
        rows = [([-1, 0, 0, 0], k_in), ([rb[0], -rb[1], 0, 0], km), ([0, rb[2], -rb[3], 0], km), ([0, 0, 1, -1], 2e4)]
        stiff, name = 0, "the input coupling"
    f, share = _chain_modes(J, rows)
    assert int(np.argmax(share[:, -1])) == stiff and share[stiff, -1] > 0.99  # the fastest mode is that element's
    cfg = load_design(str(path)).design
    method = "RK45" if shaft else "DOP853"
    with pytest.raises(SimulationError) as err:
        run_simulation(cfg, compute_design(cfg), method=method)
    msg = str(err.value)
    assert f'method = "{method}" cannot integrate this scene: {name} makes it' in msg
    assert "mesh stage" not in msg
    stated = float(msg.split("highest mode ")[1].split(" Hz")[0])
    assert abs(stated - f[-1]) <= 5e-3 * f[-1]  # printed to 3 digits


def _exact_chain_forces(J, L, k, w, ramp, TL, T, n):
    """Connector forces of an undamped linear chain whose body 0 follows the STEP speed ramp to w and whose last body
    carries the STEP-ramped load torque TL (same ramp), from rest: exact, by matrix exponentials on the state
    augmented with the polynomial basis (1, t, ..., t^4) of the ramp's forcing (an independent reference)."""
    from scipy.linalg import expm

    J, L, k = np.asarray(J, float), np.asarray(L, float), np.asarray(k, float)
    K = L.T @ np.diag(k) @ L
    m = J.size - 1
    D = np.diag(np.arange(1.0, 5.0), -1)  # d/dt of (1, t, t^2, t^3, t^4)

    def system(theta0, load):  # theta0(t), load(t) as polynomial coefficients
        A = np.zeros((2 * m + 5, 2 * m + 5))
        A[:m, m:2 * m] = np.eye(m)
        A[m:2 * m, :m] = -K[1:, 1:] / J[1:, None]
        F = -np.outer(K[1:, 0], theta0)
        F[-1] -= load
        A[m:2 * m, 2 * m:] = F / J[1:, None]
        A[2 * m:, 2 * m:] = D
        return A

    up = system(np.array([0, 0, 0, w / ramp**2, -w / (2 * ramp**3)]), np.array([0, 0, 3 * TL / ramp**2, -2 * TL / ramp**3, 0]))
    on = system(np.array([-w * ramp / 2, w, 0, 0, 0]), np.array([TL, 0, 0, 0, 0]))
    t = np.linspace(0.0, T, n + 1)
    x = np.zeros(2 * m + 5)
    x[2 * m] = 1.0
    out = np.zeros((t.size, k.size))
    for i in range(1, t.size):
        a, b = t[i - 1], t[i]
        x = expm(up * (min(b, ramp) - a)) @ x if a < ramp else x
        x = expm(on * (b - max(a, ramp))) @ x if b > ramp else x
        x[2 * m:] = b ** np.arange(5)
        s = min(b / ramp, 1.0)
        theta0 = w * ramp * (s**3 - s**4 / 2) if b < ramp else w * ramp / 2 + w * (b - ramp)
        out[i] = k * (L @ np.concatenate([[theta0], x[:m]]))
    return t, out


def test_an_explicit_run_at_its_stability_limit_is_not_warned_of_force_noise_it_does_not_make(tmp_path):
    # DOP853 at rtol 1e-2 on two undamped 4e5 N/mm spur meshes between a motor and a drum on soft couplings: the speed
    # tolerance's a-priori force noise (guards.force_noise) is 1.2x stage 1's force, and the run was warned so; but its
    # steps are capped at its stability limit on the 3.6 kHz mode, and its window statistics are within 1e-6 of the
    # exact linear solution (the warning was 1e5 times too large; BDF and LSODA keep theirs)
    rb = [z * m * math.cos(math.radians(20)) / 2e3 for z, m in ((20, 4), (60, 4), (18, 6), (72, 6))]
    path = tmp_path / "chain.toml"
    path.write_text(
        'title = "undamped chain"\n'
        "[[stage]]\nnormal_module_mm = 4\npinion = { teeth = 20, face_width_mm = 40, inertia_kg_m2 = 1.25e-3 }\n"
        "gear = { teeth = 60, face_width_mm = 40, inertia_kg_m2 = 0.1 }\n"
        "[[stage]]\nnormal_module_mm = 6\npinion = { teeth = 18, face_width_mm = 60, inertia_kg_m2 = 6.25e-3 }\n"
        "gear = { teeth = 72, face_width_mm = 60, inertia_kg_m2 = 1.6 }\n"
        "[contact]\nstiffness = 4e5\nexponent = 1\ndamping_ratio = 0\n"
        "[input]\nspeed_rpm = 1500\nramp_s = 0.1\ninertia_kg_m2 = 0.2\ncoupling_stiffness_Nm_rad = 1e3\n"
        "[load]\ntorque_Nm = 800\nramp_s = 0.1\ninertia_kg_m2 = 50\ncoupling_stiffness_Nm_rad = 2e4\n"
        '[simulation]\nduration_s = 1.0\nsteps = 4000\nrtol = 0.01\nmethod = "DOP853"\n')
    cfg = load_design(str(path)).design
    design = compute_design(cfg)
    choice = choose_method(spec_from_design(cfg, design), 1.0, "DOP853")
    assert force_noise(choice, 1e-2)[0] > 1.0  # the a-priori figure: over 100 % of the force
    sim = run_simulation(cfg, design, want_series=False)
    assert not [d for d in sim.diagnostics if d.code == dg.FORCE_NOISE]
    # bodies: motor (follows the profile), pinion 1, gear 1 with pinion 2, gear 2, drum
    J = [0.2, 1.25e-3, 0.1 + 6.25e-3, 1.6, 50.0]
    L = [[1, -1, 0, 0, 0], [0, rb[0], -rb[1], 0, 0], [0, 0, rb[2], -rb[3], 0], [0, 0, 0, 1, -1]]
    t, F = _exact_chain_forces(J, L, [1e3, 4e8, 4e8, 2e4], 1500 * math.pi / 30, 0.1, 800.0, 1.0, 4000)
    static = 800 * (18 / 72) * (20 / 60) / 0.040  # stage 1's static F_t: the pinion torque over its pitch radius, N
    inside = t >= sim.window_s[0] - 1e-12
    ft = F[inside, 1] * math.cos(math.radians(20))
    got = sim.stages[0].tangential_N
    assert max(abs(got.min - ft.min()), abs(got.max - ft.max())) < 1e-6 * static
