"""The simulation wrapper: steady window, method choice, failures as errors (never NaN), warnings,
and the design-file path (torque drive, overrides)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_allclose

from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.errors import ConfigError, SimulationError
from gearcli.io.channels import named
from gearcli.model import DriveSpec, LoadSpec, MeshSpec, ModelSpec, TorsionalModel
from gearcli.simulate import run_simulation, simulate_model
from gearcli.simulate.choice import STIFFNESS_LIMIT, choose_method
from gearcli.simulate.run import check
from gearcli.simulate.solver import STATUS_BUDGET, STATUS_FAILED, STATUS_NONFINITE, Integration
from gearcli.simulate.stats import steady_window

SEED = Path(__file__).resolve().parents[2] / "configs" / "concrete_mixer.toml"


def mesh(**kw) -> MeshSpec:
    base = dict(base_radius_pinion_m=0.06, base_radius_gear_m=0.15, base_helix_angle_rad=0.17,
                transverse_pressure_angle_rad=0.355, helix_angle_rad=0.18, stiffness_N_m_e=2e8, exponent=1.0,
                damping_Ns_m=0.0, full_damping_m=1e-4, normal_module_m=0.004, static_tangential_N=1900.0)
    base.update(kw)
    return MeshSpec(**base)


DEFAULT_DRIVE = DriveSpec("speed", 50.0, 0.1)


def one_stage(k=2e8, load=300.0, drive=DEFAULT_DRIVE, load_ramp=0.1, **kw) -> ModelSpec:
    return ModelSpec((mesh(stiffness_N_m_e=k, **kw),), (0.3, 2.5), drive, LoadSpec(load, load_ramp))


def seed(overrides=()):
    loaded = load_design(str(SEED), list(overrides))
    return loaded.design, compute_design(loaded.design)


# ---------------------------------------------------------------------------------- steady window
def test_window_starts_after_the_slower_ramp_plus_a_fifth_of_the_rest():
    spec = ModelSpec((mesh(),), (0.3, 2.5), DriveSpec("speed", 50.0, 0.1), LoadSpec(300.0, 0.3))
    (lo, hi), warnings = steady_window(spec, 1.3, None)
    assert_allclose((lo, hi), (0.3 + 0.2 * 1.0, 1.3), rtol=1e-14)  # exact arithmetic up to rounding
    assert not warnings
    assert steady_window(spec, 1.3, 0.9)[0] == (0.9, 1.3)  # simulation.window_start_s overrides
    with pytest.raises(ValueError, match="window start"):  # the design file is checked by run_simulation
        steady_window(spec, 1.3, 1.3)
    (lo, _), warnings = steady_window(spec, 0.25, None)  # ramps outlast the run
    assert_allclose(lo, 0.2, rtol=1e-14)
    assert "not steady" in warnings[0].message


def test_window_start_beyond_the_run_is_a_config_error():
    with pytest.raises(ConfigError) as err:  # the loader refuses it, naming --set
        seed(["simulation.window_start_s=0.6"])
    assert err.value.key == "simulation.window_start_s" and err.value.exit_code == 2 and err.value.source == "--set"
    cfg, design = seed()  # and so does the run, for a design built without the loader
    cfg = cfg.model_copy(update={"simulation": cfg.simulation.model_copy(update={"window_start_s": 0.6})})
    with pytest.raises(ConfigError) as err:
        run_simulation(cfg, design)
    assert err.value.key == "simulation.window_start_s" and err.value.exit_code == 2


# --------------------------------------------------------------------------------- method choice
def test_auto_is_explicit_for_a_soft_scene_and_implicit_for_a_stiff_one():
    # one mesh, pinion speed-driven: w_n^2 = k cos^2(beta_b) r_bg^2 / J_g; indicator w_n T
    for k, expected in ((2e8, "DOP853"), (2e13, "Radau")):
        w_n = math.sqrt(k * math.cos(0.17) ** 2 * 0.15**2 / 2.5)
        choice = choose_method(one_stage(k=k), 1.0, "auto")
        assert_allclose(choice.indicator, w_n * 1.0, rtol=1e-9)  # undamped: |lambda| = w_n
        assert choice.method == expected and (choice.indicator > STIFFNESS_LIMIT) == (expected == "Radau")
        assert_allclose(choice.at_full_load.natural_frequencies_Hz, [w_n / (2 * math.pi)], rtol=1e-12)
    kept = choose_method(one_stage(), 1.0, "BDF")
    assert kept.method == "BDF" and kept.requested == "BDF" and kept.reason.startswith("as requested")


def test_hertz_stiffness_is_judged_at_the_runup_load():
    # e = 1.5: k_lin grows with the load as F^(1/3); the run-up (inertia) load sets the largest eigenvalue
    spec = ModelSpec((mesh(exponent=1.5, stiffness_N_m_e=4e10),), (0.3, 25.0), DriveSpec("speed", 50.0, 0.05),
                     LoadSpec(10.0, 0.05))
    choice = choose_method(spec, 0.5, "auto")
    assert choice.at_operating_point.max_abs_eigenvalue > 2 * choice.at_full_load.max_abs_eigenvalue


# ------------------------------------------------------------------------------------- failures
def test_explicit_method_on_a_stiff_scene_fails_with_the_fix_in_the_message():
    model = TorsionalModel(one_stage(k=2e13, damping_Ns_m=1e3))
    with pytest.raises(SimulationError, match=r'mesh stage 1 .*method = "Radau"') as err:
        simulate_model(model, duration_s=1.0, steps=100, method="RK45", max_nfev=20_000)
    assert err.value.exit_code == 1 and "stopped at t =" in str(err.value)


@pytest.mark.parametrize("status, needle", [(STATUS_NONFINITE, "diverged"), (STATUS_FAILED, "step size collapsed"),
                                            (STATUS_BUDGET, "evaluations")])
def test_every_failed_status_is_an_error(status, needle):
    choice = choose_method(one_stage(), 1.0, "Radau")
    y = np.full((6, 3), np.nan)
    run = Integration(np.linspace(0, 1, 3), y, "Radau", 1e-6, np.ones(6), 10, 1, 1, 3, 0.0, status,
                      "more than 10 right-hand-side evaluations", 0.4)
    with pytest.raises(SimulationError, match=needle):
        check(run, choice, 1.0)


def test_finished_run_with_nan_is_still_an_error():
    choice = choose_method(one_stage(), 1.0, "DOP853")
    y = np.zeros((6, 3))
    y[1, 2] = np.nan
    with pytest.raises(SimulationError, match="non-finite"):
        check(Integration(np.linspace(0, 1, 3), y, "DOP853", 1e-6, np.ones(6), 10, 0, 0, 3, 0.0, 0, "", 1.0), choice, 1.0)


# ------------------------------------------------------------------------------------- warnings
def test_a_lightly_loaded_mesh_that_rattles_is_reported():
    # linear undamped mesh, steady load 1 N m, released from 50x its static deflection: the loaded flank
    # unloads every period (the mesh vibrates through h = 0 onto its back flank)
    spec = one_stage(load=1.0, drive=DriveSpec("speed", 50.0, 0.0), load_ramp=0.0)
    model = TorsionalModel(spec)
    y0 = model.initial_state()
    y0[0] = 50 * 1.0 / (0.15 * 2e8 * math.cos(0.17) ** 2)
    sim = simulate_model(model, duration_s=0.2, steps=400, method="DOP853", y0=y0)
    assert any("loaded (drive) flank loses contact" in w for w in sim.warnings)
    assert np.any(named(sim)["stage1_penetration_mm"] < 0)  # the back flank carries the rebound


def test_efficiency_and_deep_penetration_are_reported():
    # static: F_bt = 300/0.15 = 2000 N, p0 = (F_bt / cos(beta_b) / K)^(2/3) = 1.6e-4 m; run-up: the gear
    # (20 rad/s, ramp 0.1 s) needs 2.5 x 1.5 x 20/0.1 = 750 N m more at T/2 -> F_bt ~ 6e3 N, p ~ 3.3e-4 m.
    # The full-damping depth 2.5e-4 m lies between: a transient exceeds it -> warning; 10 % of the 6 mm
    # module (0.6 mm) is not reached.
    def run(d):
        spec = ModelSpec((mesh(efficiency=0.97, exponent=1.5, stiffness_N_m_e=1e9, damping_Ns_m=1e3, full_damping_m=d,
                               normal_module_m=0.006),), (0.3, 2.5), DriveSpec("speed", 50.0, 0.1), LoadSpec(300.0, 0.1))
        return " | ".join(simulate_model(TorsionalModel(spec), duration_s=0.3, steps=300).warnings)

    text = run(2.5e-4)
    assert "not modelled" not in text  # stage efficiency acts in the dynamics now (no warning about it)
    assert "beyond the full-damping depth" in text
    assert "10 % of the normal module" not in text
    # a depth below the static approach is an Adams-style damping ramp set on purpose: no warning
    assert "beyond the full-damping depth" not in run(1e-5)


# ------------------------------------------------------------------------------ design-file path
def test_torque_drive_starts_at_nominal_speed_and_holds_it_when_balanced():
    # input torque = load / i (lossless): the rigid train neither speeds up nor slows down; the run starts
    # at the nominal speeds (rigid-body consistent), with both torques ramped over 0.18 s
    t_in = 5310.0 / (135150 / 6069)
    cfg, design = seed(['input.drive="torque"', f"input.torque_Nm={t_in!r}"])
    sim = run_simulation(cfg, design)
    w1 = named(sim)["shaft1_speed_deg_s"]
    assert_allclose(w1[0], 3600.0, rtol=1e-14)
    assert_allclose(sim.input_speed_deg_s, 3600.0, rtol=1e-3)  # mesh vibration only
    assert_allclose(named(sim)["input_torque_Nmm"][-1], t_in * 1e3, rtol=1e-14)  # the prescribed torque
    assert_allclose(sim.ratio, 135150 / 6069, rtol=1e-4)
    assert sim.solver.energy_residual < 1e-6


def test_time_varying_seed_accounts_for_parametric_work():
    cfg, design = seed(["contact.time_varying=true"])
    sim = run_simulation(cfg, design, want_series=False)
    assert sim.solver.energy_residual < 1e-5
    assert sim.extra["parametric_work_J"] != 0.0
    for stage in sim.stages:  # the mean still balances the load (0.5 % as for the seed)
        assert_allclose(stage.tangential_N.mean, stage.static_tangential_N, rtol=5e-3)


def test_natural_frequencies_of_an_unloaded_hertz_mesh_come_from_the_runup_load():
    # e = 1.5 and no load: k_lin = 0 at the static point; the reported frequencies are those at the run-up
    # (inertia) load instead, all positive. Rigid run-up force: J_g alpha_g / r_bg with alpha_g = 1.5 w_g/T
    spec = ModelSpec((mesh(exponent=1.5, stiffness_N_m_e=4e10),), (0.3, 2.5), DriveSpec("speed", 50.0, 0.1),
                     LoadSpec(0.0))
    choice = choose_method(spec, 0.5, "auto")
    f_bt = 2.5 * 1.5 * (50.0 * 0.06 / 0.15) / 0.1 / 0.15
    p = (f_bt / math.cos(0.17) / 4e10) ** (2 / 3)
    k_t = math.cos(0.17) ** 2 * 1.5 * 4e10 * math.sqrt(p)
    # (the peak at T/2 lies on the 801-point search grid, so only rounding separates the two)
    assert_allclose(choice.natural_frequencies_Hz, [math.sqrt(k_t * 0.15**2 / 2.5) / (2 * math.pi)], rtol=1e-9)


# ------------------------------------------------------------------------- auto's cost model (issue 10)
def test_ramp_excitation_closed_form():
    from gearcli.simulate.choice import _ramp_excitation

    spec = one_stage()  # drive and load STEP ramps of 0.1 s
    assert_allclose(_ramp_excitation(spec, 2000.0), 6.0 / (2000.0 * 0.1) ** 2, rtol=1e-12)
    instant = one_stage(drive=DriveSpec("speed", 50.0, 0.0))
    assert _ramp_excitation(instant, 2000.0) == 1.0


def test_vibration_radians_of_one_mesh_mode():
    """One mesh, clamped pinion: one mode, |lambda| = w_n and sigma = -Re(lambda) of the linearisation;
    an excited mode vibrates w_n min(T, 5/sigma) radians (undamped: w_n T)."""
    from gearcli.simulate.choice import vibration_radians

    for damping, T in ((0.0, 1.0), (2e3, 1.0)):
        spec = one_stage(damping_Ns_m=damping, full_damping_m=1e-9)
        choice = choose_method(spec, T, "auto")
        lam = choice.at_full_load.eigenvalues[np.argmax(choice.at_full_load.eigenvalues.imag)]
        w_n, sigma = abs(lam), -lam.real
        expected = w_n * (T if sigma <= 0 else min(T, 5.0 / sigma))
        assert_allclose(vibration_radians(spec, choice.layout, choice.at_full_load, T, 1e-6), expected, rtol=1e-6)
        assert_allclose(choice.vibration_rad, expected, rtol=1e-6)
    # a 1e5 x stiffer linear mesh ramped over 0.1 s: residual 6/(w_n T_r)^2 ~ 4e-9 < rtol, nothing to resolve
    stiff = choose_method(one_stage(k=2e13), 1.0, "auto")
    assert stiff.vibration_rad == 0.0 and stiff.method == "Radau"


def test_auto_keeps_dop853_for_a_long_lightly_damped_run_and_takes_radau_for_damped_meshes():
    """The two misjudgements of the old max|lambda| T threshold (measured in benchmarks/bench_auto.py): the
    seed for 10 s (Radau 3.6x slower than DOP853) and the damped industrial reducer (DOP853 2x slower)."""
    cfg, design = seed(["simulation.duration_s=10", "simulation.steps=40000"])
    from gearcli.scene import spec_from_design

    assert choose_method(spec_from_design(cfg, design), 10.0, "auto").method == "DOP853"
    loaded = load_design(str(SEED.parent / "industrial_two_stage.toml"), [])
    spec = spec_from_design(loaded.design, compute_design(loaded.design))
    assert choose_method(spec, 0.5, "auto").method == "Radau"


def test_a_run_without_diagnostics_has_the_same_statistics_and_no_window_checks():
    """simulate_model(diagnose=False), the report's accuracy ladder: the same run and statistics, without the
    ringing fit, the settle test and the resonance check (the seed rings through its window: with diagnostics it
    says so and its settle test finds the window unsettled)."""
    cfg = load_design(str(SEED), []).design
    design = compute_design(cfg)
    full = run_simulation(cfg, design, want_series=False, error_estimate=False)
    bare = run_simulation(cfg, design, want_series=False, error_estimate=False, diagnose=False)
    assert full.solver.nfev == bare.solver.nfev  # the same integration
    for a, b in zip(full.stages, bare.stages, strict=True):
        for q in ("mean", "min", "max", "std"):
            assert getattr(a.tangential_N, q) == getattr(b.tangential_N, q)  # the same samples, the same sums
    codes = {d.code for d in full.diagnostics}
    assert "window_ringing" in codes and full.steady.settled is False
    bare_codes = {d.code for d in bare.diagnostics}
    assert not bare_codes & {"window_ringing", "window_not_settled", "resonance"} and bare.steady.settled is None
