"""The compiled DOP853 against scipy's DOP853 on the same right-hand side: same accepted steps, same
evaluations, same samples (issue 15's acceptance). The reference is scipy's own solver class stepped over
the same segments (the ramp ends), independent of gearcli's solver loop and of the kernel."""

from __future__ import annotations

import glob
from functools import cache
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("numba")

from gearcli import engine  # noqa: E402
from gearcli.config import load_design  # noqa: E402
from gearcli.design import compute_design  # noqa: E402
from gearcli.scene import build_model  # noqa: E402
from gearcli.simulate.choice import choose_method  # noqa: E402
from gearcli.simulate.solver import breakpoints  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
FILES = sorted(glob.glob(str(ROOT / "configs" / "*.toml")) + glob.glob(str(ROOT / "configs" / "extreme" / "*.toml")))


@cache
def scene(path: str):
    cfg = load_design(path, []).design
    model = build_model(cfg, compute_design(cfg))
    return cfg, model


def non_stiff(path: str) -> bool:
    cfg, model = scene(path)
    return choose_method(model.spec, cfg.simulation.duration_s, "auto").method == "DOP853"


def scipy_dop853(model, t_eval, rtol, atol, method="DOP853", max_step=np.inf, y0=None):
    """scipy.integrate.DOP853 (or RK45) over the run's segments: (samples, accepted step times, nfev)."""
    import scipy.integrate

    DOP853 = getattr(scipy.integrate, method)

    y, t = (model.initial_state() if y0 is None else y0), 0.0
    out = np.full((y.size, t_eval.size), np.nan)
    done = int(np.searchsorted(t_eval, 0.0, side="right"))
    out[:, :done] = y[:, None]
    times, nfev = [], 0
    for t_end in breakpoints(model, float(t_eval[-1])):
        s = DOP853(model.rhs, t, y, t_end, rtol=rtol, atol=atol, max_step=max_step)
        while s.status == "running":
            s.step()
            assert s.status != "failed"
            times.append(s.t)
            upto = int(np.searchsorted(t_eval, s.t, side="right"))
            if upto > done:
                out[:, done:upto] = s.dense_output()(t_eval[done:upto])
                done = upto
        nfev += s.nfev
        t, y = s.t, s.y
    return out, np.array(times), nfev


def compiled_dop853(model, t_eval, rtol, atol, max_nfev=10**8, method="DOP853", max_step=None, y0=None):
    k = engine.load(quiet=True).kernel
    n = model.n_states
    trace = np.full(10**6, np.nan)
    wpar = np.zeros(5)
    if max_step is not None:  # the full parameter vector, its budget checks never due, the ceiling in its slot
        from gearcli.engine.guards import WP_EVERY, WP_MAX_STEP

        wpar = np.zeros(WP_MAX_STEP + 1)
        wpar[WP_EVERY], wpar[WP_MAX_STEP] = 1e15, max_step
    out, counters, floats, _ = getattr(k, method.lower())(engine.pack(model.arrays),
                                        model.initial_state() if y0 is None else y0, t_eval,
                                        np.array(breakpoints(model, float(t_eval[-1]))),
                                        np.array(np.broadcast_to(rtol, (n,)), dtype=float),
                                        np.array(np.broadcast_to(atol, (n,)), dtype=float), np.int64(max_nfev),
                                        np.int64(0), wpar, trace)
    nfev, steps, status, _ = (int(v) for v in counters)
    return out, trace[:steps], nfev, status


def assert_same(ref, got, samples_rtol=1e-9):
    out_r, times_r, nfev_r = ref
    out_c, times_c, nfev_c, status = got
    assert status == 0
    assert nfev_c == nfev_r
    assert times_c.size == times_r.size
    np.testing.assert_array_equal(times_c, times_r)  # the same accepted steps, to the bit
    scale = np.maximum(np.max(np.abs(out_r), axis=1, keepdims=True), 1e-300)
    assert np.max(np.abs(out_c - out_r) / scale) <= samples_rtol


@pytest.mark.parametrize("path", FILES, ids=lambda p: Path(p).stem)
def test_same_steps_as_scipy(path):
    if not non_stiff(path):
        pytest.skip("stiff: auto integrates it with Radau (not the compiled DOP853's job)")
    cfg, model = scene(path)
    rtol = cfg.simulation.rtol
    t_eval = np.linspace(0.0, cfg.simulation.duration_s, cfg.simulation.steps + 1)
    atol = model.atol(rtol)
    assert_same(scipy_dop853(model, t_eval, rtol, atol), compiled_dop853(model, t_eval, rtol, atol))


@pytest.mark.parametrize("method", ["DOP853", "RK45"])
def test_same_steps_as_scipy_under_a_step_ceiling(method):
    """scipy's ``max_step`` (the initial step and every step clamped to it) and the kernel's ``wpar[WP_MAX_STEP]``:
    the same accepted steps, none longer than the ceiling, on the seed's run-up with a ceiling well below the steps
    it takes without one."""
    cfg, model = scene(str(ROOT / "configs" / "concrete_mixer.toml"))
    rtol, ceiling = 1e-6, 4e-4
    t_eval = np.linspace(0.0, 0.3, 601)
    atol = model.atol(rtol)
    ref = scipy_dop853(model, t_eval, rtol, atol, method, max_step=ceiling)
    assert np.max(np.diff(np.concatenate(([0.0], ref[1])))) <= ceiling * (1 + 1e-12)
    assert ref[1].size >= 0.3 / ceiling  # the ceiling bound: the free run's steps are longer (cf. the seed's 285)
    assert_same(ref, compiled_dop853(model, t_eval, rtol, atol, method=method, max_step=ceiling))


def test_per_component_tolerance_vectors():
    """rtol and atol as vectors (a per-state tolerance policy): still scipy's steps."""
    cfg, model = scene(str(ROOT / "configs" / "concrete_mixer.toml"))
    lay = model.layout
    rtol = np.full(model.n_states, 1e-6)
    rtol[lay.n_conn:lay.i_quad] = 3e-7  # tighter on the speeds
    atol = model.atol(1e-6)
    atol[:lay.n_conn] *= 0.5
    t_eval = np.linspace(0.0, cfg.simulation.duration_s, 501)
    assert_same(scipy_dop853(model, t_eval, rtol, atol), compiled_dop853(model, t_eval, rtol, atol))


def test_engines_agree_through_integrate_including_budget_stop():
    """gearcli's solver loop on both engines: the same run, and the same stop when the budget runs out."""
    from gearcli.simulate.solver import STATUS_BUDGET, integrate

    cfg, model = scene(str(ROOT / "configs" / "concrete_mixer.toml"))
    t_eval = np.linspace(0.0, cfg.simulation.duration_s, cfg.simulation.steps + 1)
    py = integrate(model, t_eval, "DOP853", 1e-6)
    cc = integrate(model, t_eval, "DOP853", 1e-6, engine="compiled")
    assert (cc.engine, py.engine) == ("compiled", "python")
    assert (cc.nfev, cc.steps, cc.status) == (py.nfev, py.steps, 0)
    np.testing.assert_array_equal(cc.y, py.y)
    py = integrate(model, t_eval, "DOP853", 1e-6, max_nfev=2000)
    cc = integrate(model, t_eval, "DOP853", 1e-6, max_nfev=2000, engine="compiled")
    assert py.status == cc.status == STATUS_BUDGET
    assert (cc.nfev, cc.steps, cc.t_fail, cc.message) == (py.nfev, py.steps, py.t_fail, py.message)
    np.testing.assert_array_equal(np.isnan(cc.y), np.isnan(py.y))


def test_energy_watch_sees_the_same_stored_energy():
    """The kernel's stored energy (kinetic + constant-stiffness elastic + work on time-varying springs) is
    the energy watch's, at states along a run with time-varying stiffness and backlash."""
    from gearcli.simulate.guards import EnergyWatch
    from gearcli.simulate.solver import integrate

    cfg, model = scene(str(ROOT / "configs" / "mixer_time_varying_backlash.toml"))
    t_eval = np.linspace(0.0, cfg.simulation.duration_s, 41)
    run = integrate(model, t_eval, "DOP853", 1e-6, engine="compiled")
    watch = EnergyWatch(model, model.initial_state())
    k = engine.load(quiet=True).kernel
    packed = engine.pack(model.arrays)
    for j in range(1, t_eval.size, 5):
        y = np.ascontiguousarray(run.y[:, j])
        assert k.stored_energy(float(t_eval[j]), y, packed) == pytest.approx(watch._stored(float(t_eval[j]), y),
                                                                              rel=1e-12)


@pytest.mark.parametrize("name", ["concrete_mixer", "mixer_time_varying_backlash", "concrete_mixer_drivetrain",
                                  "backlash_oscillator"])
def test_output_channels_compiled_are_the_element_laws_to_the_bit(name, monkeypatch):
    """With the kernel loaded, the channels' forces, energies and penetrations come from the compiled element
    laws: the same numbers as the Python laws, bit for bit (back flank, gap, clamp and tv meshes included)."""
    from gearcli.model import outputs
    from gearcli.simulate.solver import integrate

    cfg, model = scene(str(ROOT / "configs" / f"{name}.toml"))
    t_eval = np.linspace(0.0, cfg.simulation.duration_s, 801)
    run = integrate(model, t_eval, "DOP853", 1e-6, engine="compiled")
    engine.load(quiet=True)
    fast = outputs.sample(model.layout, run.t, run.y)
    monkeypatch.setattr(outputs, "_loaded_kernel", lambda: None)
    slow = outputs.sample(model.layout, run.t, run.y)
    for a, b in zip(fast.connectors, slow.connectors, strict=True):
        np.testing.assert_array_equal(a.force, b.force)
        np.testing.assert_array_equal(a.potential_J, b.potential_J)
        np.testing.assert_array_equal(a.penetration_m, b.penetration_m)


@pytest.mark.parametrize("name", ["concrete_mixer", "backlash_oscillator", "mixer_time_varying_backlash",
                                  "concrete_mixer_drivetrain", "extreme/rattle_zero_load"])
def test_rk45_same_steps_as_scipy(name):
    """The compiled RK45: scipy's accepted steps and nfev; samples to the last bits (its quartic interpolant
    is summed in a loop, not through BLAS)."""
    cfg, model = scene(str(ROOT / "configs" / f"{name}.toml"))
    rtol = cfg.simulation.rtol
    t_eval = np.linspace(0.0, cfg.simulation.duration_s, cfg.simulation.steps + 1)
    atol = model.atol(rtol)
    assert_same(scipy_dop853(model, t_eval, rtol, atol, "RK45"),
                compiled_dop853(model, t_eval, rtol, atol, method="RK45"), samples_rtol=1e-12)
