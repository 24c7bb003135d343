"""A sweep point's post-processing shortcuts (issue 33 item 3) give the numbers of the long way, bit for bit: the
equilibrium's constant statistics period sampled once and repeated against every sample sampled, and the resonance
check that leaves the modal analysis out where no order lies near a mode against the analysis itself; a STEP
ramp's rates without its angle, the layout's cached flags and a variant's copied data against their definitions."""

from __future__ import annotations

from dataclasses import fields
from pathlib import Path

import numpy as np
import pytest

from gearcli import api
from gearcli.model import TorsionalModel
from gearcli.model import modes as modes_mod
from gearcli.model.outputs import ConnectorSeries, sample
from gearcli.simulate import equilibrium

ROOT = Path(__file__).resolve().parents[2]
# unexcited, speed-driven scenes (their steady state is the equilibrium): Hertz meshes, couplings and a motor
# inertia, a planetary stage, lossy meshes with a speed-dependent load law, an unloaded rattling train
SCENES = ("concrete_mixer", "concrete_mixer_drivetrain", "planetary_stage", "lossy_reducer",
          "extreme/rattle_zero_load")


def _model(name: str, *sets: str) -> TorsionalModel:
    loaded, design = api.load_and_design(str(ROOT / "configs" / f"{name}.toml"), list(sets))
    return TorsionalModel(api.model_spec(loaded.design, design))


def _record(model: TorsionalModel, head: int = 300, period: int = 200, seed: int = 5):
    """A run-up of ``head`` samples (states scattered about the static deflections and nominal speeds) to past the
    ramps, then ``period + 1`` samples of one constant dynamic state with the work quadratures growing: the shape
    of :func:`gearcli.simulate.equilibrium.steady_period`'s run."""
    lay = model.layout
    st = lay.state
    rng = np.random.default_rng(seed)
    t_end = max(lay.drive.ramp_s, lay.load.ramp_s) + 0.01
    t = np.concatenate([np.linspace(0.0, t_end, head, endpoint=False), t_end + 0.02 * np.arange(period + 1) / period])
    y = model.initial_state()
    y[st.deflections] = model.deflection_scales() * rng.uniform(-0.5, 2.0, lay.n_conn)
    Y = np.repeat(y[:, None], t.size, axis=1)
    Y[:st.n_mechanical, :head] *= 1.0 + 0.05 * rng.standard_normal((st.n_mechanical, head))
    q = st.quadratures
    Y[q, head:] = rng.uniform(1.0, 2.0, (len(range(*q.indices(st.n_states))), 1)) * (t[head:] - t[head])
    return t, Y, head


def _same(a, b, energy_from: int = 0) -> None:
    """``a`` is ``b`` bit for bit, but for the stored energy before ``energy_from``, which ``a`` leaves out (NaN)."""
    assert np.array_equal(a.time_s, b.time_s) and np.array_equal(a.omega_rad_s, b.omega_rad_s)
    assert a.theta_rad is None and b.theta_rad is None
    assert np.array_equal(np.broadcast_to(a.input_torque_Nm, a.time_s.shape), b.input_torque_Nm)
    assert np.array_equal(np.broadcast_to(a.load_torque_Nm, a.time_s.shape), b.load_torque_Nm)
    for ca, cb in zip(a.connectors, b.connectors, strict=True):
        for f in fields(ConnectorSeries):
            x, y = getattr(ca, f.name), getattr(cb, f.name)
            if f.name == "potential_J":  # not evaluated before the energy balance's first sample
                assert np.isnan(x[:energy_from]).all() and np.isfinite(y).all()
                x, y = x[energy_from:], y[energy_from:]
            assert np.array_equal(x, y), f.name


@pytest.mark.parametrize("name", SCENES)
def test_the_constant_period_sampled_once_is_every_sample_sampled(name, laws):
    model = _model(name)
    assert equilibrium.applies(model) and not model.layout.needs_angles
    t, Y, head = _record(model)
    whole, short = sample(model.layout, t, Y), equilibrium.sampled(model.layout, t, Y, head)
    _same(short, whole, head)  # the run-up's stored energy left out: the balance starts at the period
    # the energy balance reads the period's first and last samples: the same
    assert model.energy(short.tail(head), Y[:, head:]) == model.energy(whole.tail(head), Y[:, head:])


@pytest.mark.parametrize("name", SCENES)
def test_the_period_sampled_once_without_the_torques_is_the_rest_of_every_sample_sampled(name, laws):
    """A run that keeps no series and has no motor reads neither torque: the speeds and every connector's series of
    the shortcut without them are those of the whole sampling with them, and the torques are left empty."""
    model = _model(name)
    t, Y, head = _record(model)
    whole, brief = sample(model.layout, t, Y), equilibrium.sampled(model.layout, t, Y, head, torques=False)
    assert brief.input_torque_Nm.size == 0 and brief.load_torque_Nm.size == 0
    assert np.array_equal(brief.time_s, whole.time_s) and np.array_equal(brief.omega_rad_s, whole.omega_rad_s)
    for cb, cw in zip(brief.connectors, whole.connectors, strict=True):
        for f in fields(ConnectorSeries):
            x, y = getattr(cb, f.name), getattr(cw, f.name)
            if f.name == "potential_J":  # not evaluated before the energy balance's first sample
                x, y = x[head:], y[head:]
            assert np.array_equal(x, y), f.name


def test_a_period_that_is_not_constant_is_sampled_whole(monkeypatch):
    model = _model("concrete_mixer")
    t, Y, head = _record(model)
    Y[0, -1] *= 1.0 + 1e-12  # one deflection moves by a rounding: no longer the one state
    calls = []
    real = equilibrium.sample
    monkeypatch.setattr(equilibrium, "sample", lambda *a, **k: calls.append(a[1].size) or real(*a, **k))
    _same(equilibrium.sampled(model.layout, t, Y, head), real(model.layout, t, Y))
    assert calls == [t.size]
    calls.clear()
    before = model.layout.drive.ramp_s
    t2, Y2, _ = _record(model)
    equilibrium.sampled(model.layout, t2, Y2, 10)  # a "period" starting inside the ramps: sampled whole
    assert before > t2[10] and calls == [t2.size]


@pytest.mark.parametrize("name", [*SCENES, "extreme/zero_damping", "extreme/five_stages", "wind_turbine_gearbox"])
@pytest.mark.parametrize("rpm", [None, 150.0, 900.0, 2400.0])
def test_the_resonance_check_without_the_analysis_finds_what_the_analysis_finds(name, rpm):
    sets = () if rpm is None else (f"input.speed_rpm={rpm!r}",)
    model = _model(name, *sets)
    quick = modes_mod.resonances(model.layout, "clamped_input")
    fresh = _model(name, *sets).layout
    modes_mod.modal_analysis(fresh, "clamped_input")  # the analysis made first: the long way
    assert quick == modes_mod.resonances(fresh, "clamped_input")


def test_the_resonance_check_still_warns_where_an_order_meets_a_mode():
    # the seed at 150 rpm: its mesh orders meet three modes (the comparison above is not of empty lists only)
    found = modes_mod.resonances(_model("concrete_mixer", "input.speed_rpm=150.0").layout, "clamped_input")
    assert len(found) == 3 and all("resonance: the stage" in r.message or "shaft" in r.message for r in found)


@pytest.mark.parametrize("periodic", [False, True])
@pytest.mark.parametrize("holes", [False, True])
def test_every_stage_at_once_has_the_statistics_of_one_stage_at_a_time(periodic, holes):
    from dataclasses import replace

    from gearcli.simulate import stats

    rng = np.random.default_rng(11)
    t = np.linspace(0.0, 0.5, 2001)
    mask = stats.window_mask(t, (0.244, 0.5))
    if holes:
        mask[1700:1710] = False  # a window that is not one slice: read through the mask
    statics = [4.2e4, -1.3e3, 0.0, 7.0e2]
    per_stage = []
    for k, static in enumerate(statics):
        ft = static + 3e3 * rng.standard_normal(t.size) * (k + 1)
        ft = np.abs(ft) if k == 3 else ft  # stage 4 never on its back flank
        ft[rng.uniform(size=t.size) < 0.05 * k] = 0.0  # contact lost now and then (none in stage 1)
        pen = ft * 1e-5
        pen[rng.uniform(size=t.size) < 0.03 * (k in (1, 2))] = -1e-3  # the back flank struck (stages 2, 3)
        per_stage.append((ft, 0.36 * ft, 0.2 * ft, pen, 1e2 * rng.standard_normal(t.size)))
    simulated = [4.1e4, None, 0.0, 6.5e2]
    extra = {"type": ["parallel", "parallel", "belt", "parallel"], "error_estimate": [None, None, None, None]}
    together = stats.stages_dynamics(t, mask, per_stage, statics, periodic=periodic, simulated_static_N=simulated,
                                     **extra)
    alone = [replace(stats.stage_dynamics(k, t, mask, *p[:4], statics[k], p[4], periodic=periodic,
                                          simulated_static_N=simulated[k]), type=extra["type"][k])
             for k, p in enumerate(per_stage)]
    assert together == alone  # dataclass equality: every float the same
    assert [s.regime for s in together] == ["no impact", "double-sided impact", "double-sided impact",
                                            "single-sided impact"]
    for a, b in zip(together, alone, strict=True):  # and of the same types (JSON writes floats)
        assert type(a.contact_loss_fraction) is type(b.contact_loss_fraction) is float
        assert type(a.tangential_N.std) is float and type(a.dte_um.rms) is float


def test_what_a_sweeps_points_share_gives_each_point_its_own_numbers():
    """The memos a speed sweep's points share (the full-load linearisation, the modal damping ratios, the
    eigenproblem of the chain, the structural rank, the method choice's modal data: each keyed by its exact inputs) against every point worked out
    cold, the memos emptied before it: the same statistics and warnings, bit for bit."""
    from gearcli.model import damping, linear
    from gearcli.simulate import choice, shooting
    from gearcli.sweep.worker import Scene

    memos = (linear._LINEARISED, damping._RATIOS, modes_mod._CHAINS, shooting._RANKS, choice._CHAIN_MODES)
    seed = ROOT / "configs" / "concrete_mixer.toml"
    scene = Scene(seed.read_bytes(), str(seed), ("simulation.engine=python",), 3)

    def points(cold: bool):
        out = []
        for rpm in (150.0, 600.0, 900.0):  # 150 and 900 rpm: orders near modes (the resonance warnings)
            if cold:
                for memo in memos:
                    memo.clear()
            r = api.evaluate_point(scene, (f"input.speed_rpm={rpm!r}",)).result
            out.append((r.stages, r.warnings, r.natural_frequencies_Hz, r.steady, r.energy, r.extra))
        return out

    cold = points(True)
    assert any("resonance" in w for _, warnings, *_ in cold for w in warnings)
    assert points(False) == cold


def test_a_ramps_rates_are_its_motions_without_the_angle():
    """``ramp_rates`` (the rigid chain, the rigid start and a body motion without angles take it) gives the speed and
    acceleration of ``ramp_motion`` bit for bit, and the STEP ramp's closed form: at T/2 the speed v/2 and the
    largest acceleration 1.5 v/T (d/dt of v s^2 (3 - 2 s) = 6 v s (1 - s) / T at s = 1/2); past T the speed v,
    no acceleration; a ramp of 0 s the full speed from t = 0."""
    from gearcli.model.step import ramp_motion, ramp_rates

    v, T = 62.83, 0.18
    t = np.linspace(0.0, 0.3, 601)
    for ramp_s in (T, 0.0):
        w, a = ramp_rates(t, ramp_s, v)
        _, w_all, a_all = ramp_motion(t, ramp_s, v)
        assert np.array_equal(w, w_all) and np.array_equal(a, a_all)
    # the speed's round-off: v s^2 (3 - 2 s) at s = 1/2 is exact in binary, the acceleration one rounding of 6 v / 4T
    assert ramp_rates(T / 2, T, v) == pytest.approx((v / 2, 1.5 * v / T), rel=1e-15)
    assert ramp_rates(0.25, T, v) == (v, 0.0)
    assert ramp_rates(0.1, 0.0, v) == (v, 0.0)


@pytest.mark.parametrize("name", ["concrete_mixer", "planetary_stage", "lossy_reducer", "concrete_mixer_te",
                                  "motor_direct_start"])
def test_the_cached_flags_are_the_fields_functions(name):
    """The layout's and connectors' flags kept per instance (functions of frozen fields) equal their definitions
    worked out anew from the elements' laws."""
    lay = _model(name).layout
    for x in lay.connectors:
        el, P = x.element, x.params
        assert (x.phased, x.excited, x.time_varying, x.damped) == (el.phased(P), el.excited(P), el.time_varying(P),
                                                                   el.damped(P))
        assert x.levers == tuple(s * r for s, r in zip(el.SIGNS, x.radii, strict=True))
    assert lay.needs_angles == (any(el.phased(x.params) for x in lay.connectors for el in [x.element])
                                or bool(lay.ripple))
    assert lay.inertias == tuple(b.inertia for b in lay.bodies)
    assert lay.n_lossy == sum(x.lossy for x in lay.connectors)
    assert lay.stage_conn == tuple(c for c, x in enumerate(lay.connectors) if x.role in ("mesh", "stage"))


def test_a_variants_data_is_a_deep_copy_of_the_parsed_file():
    """``load_variant`` copies the file's parsed TOML as a plain tree (tables and arrays new, leaves shared): equal
    to ``copy.deepcopy``'s, and an override applied to one variant leaves the next variant and the parsed file as
    they were."""
    import copy

    from gearcli.config import load as load_mod

    raw = (ROOT / "configs" / "planetary_duty.toml").read_bytes()
    parsed = load_mod._parsed(raw, "planetary_duty.toml")
    before = copy.deepcopy(parsed)
    mine = load_mod._copied(parsed)
    assert mine == before

    def containers(x, out):
        if isinstance(x, (dict, list)):
            out.append(id(x))
            for v in (x.values() if isinstance(x, dict) else x):
                containers(v, out)
        return out

    assert not set(containers(mine, [])) & set(containers(parsed, []))  # no table or array shared
    plain = load_mod.load_variant(raw, "planetary_duty.toml", ())
    varied = load_mod.load_variant(raw, "planetary_duty.toml", ("input.speed_rpm=900",))
    again = load_mod.load_variant(raw, "planetary_duty.toml", ())
    assert parsed == before
    assert varied.input.speed_rad_s_value == pytest.approx(900.0 * 2.0 * np.pi / 60.0, rel=1e-12)  # rpm -> rad/s
    assert again == plain and again.input.speed_rad_s_value != varied.input.speed_rad_s_value
