"""Issue 33 item 2: an ``auto`` run whose prediction fails changes course from the state it has reached, and its
numbers stay those of a run at the requested tolerance (gearcli.simulate.course)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.model import TorsionalModel
from gearcli.scene import spec_from_design
from gearcli.simulate import choice as choice_mod
from gearcli.simulate import course, run_simulation
from tests.reference.step_scene import feather_gear

ROOT = Path(__file__).resolve().parents[2]
STIFF = ROOT / "configs" / "stiff_linear_mesh.toml"  # a very stiff linear mesh: DOP853 needs ~1.1e5 evaluations


def _case(*sets: str):
    cfg = load_design(str(STIFF), ["simulation.engine=python", *sets]).design
    return cfg, compute_design(cfg)


def _hide_stiffness(monkeypatch) -> None:
    """The cost model no longer sees the scene's stiffness: DOP853's stability need (max|lambda| T) is predicted
    10^4 times too small, so auto takes DOP853 on a scene that needs Radau."""
    real = choice_mod.predicted_costs

    def hidden(indicator, *args, **kwargs):
        return real(indicator * 1e-4, *args, **kwargs)

    monkeypatch.setattr(choice_mod, "predicted_costs", hidden)
    monkeypatch.setattr(choice_mod, "_explicit_refused", lambda indicator: False)


def test_a_hidden_stiffness_makes_auto_change_course_from_the_state_reached(monkeypatch):
    _hide_stiffness(monkeypatch)
    calls: list[tuple[float, str, np.ndarray | None, np.ndarray | None]] = []
    real_integrate = course.integrate

    def spy(model, t_eval, method, rtol, **kw):
        run = real_integrate(model, t_eval, method, rtol, **kw)
        calls.append((float(kw.get("t0", 0.0)), method, kw.get("y0"), run.y_end))
        return run

    monkeypatch.setattr(course, "integrate", spy)
    cfg, design = _case()
    got = run_simulation(cfg, design, want_series=False)
    sv = got.solver
    assert sv.requested_method == "auto"
    (change,) = sv.course_changes
    assert change["from"] == "DOP853 (python)" and change["to"] == "Radau (python)"
    at = float(change["at_s"])
    assert 0.0 < at < cfg.simulation.duration_s
    # continued from the state reached, not from t = 0: the second piece starts where the first stopped, from
    # the very state the first one's solver held there
    first, second = calls[0], calls[1]
    assert first[0] == 0.0 and first[1] == "DOP853" and second[1] == "Radau"
    assert second[0] == at and first[3] is not None
    np.testing.assert_array_equal(second[2], first[3])  # bit for bit
    assert sv.method == "Radau" and sv.prediction is not None
    # what the whole run spent is far below DOP853's whole run (~1.1e5 evaluations, measured: 114,592)
    assert sv.nfev < 50_000
    # the numbers: window means within the run's own target (1e-4 of the mean force, gearcli.simulate.estimate)
    # of an independent reference, Radau at rtol 1e-10 from t = 0 without course changes
    ref = run_simulation(*_case("simulation.method=Radau", "simulation.rtol=1e-10"), want_series=False,
                         error_estimate=False)
    for a, b in zip(got.stages, ref.stages, strict=True):
        scale = abs(b.tangential_N.mean)
        np.testing.assert_allclose(a.tangential_N.mean, b.tangential_N.mean, rtol=1e-4,
                                   err_msg="window mean beyond the run's target (1e-4 of the mean)")
        # the amplitude statistics within the run's 1e-3 target of the mean force
        assert abs(a.tangential_N.max - b.tangential_N.max) <= 1e-3 * scale
        assert abs(a.tangential_N.min - b.tangential_N.min) <= 1e-3 * scale
    assert not [d for d in got.diagnostics if d.code == "statistics_unresolved"]


def test_a_requested_method_never_changes_course(monkeypatch):
    _hide_stiffness(monkeypatch)
    cfg, design = _case("simulation.method=DOP853", "simulation.duration_s=0.05", "simulation.steps=200")
    got = run_simulation(cfg, design, want_series=False, error_estimate=False)
    assert got.solver.course_changes == () and got.solver.method == "DOP853"


def test_a_run_within_its_prediction_keeps_its_course():
    cfg, design = _case()
    got = run_simulation(cfg, design, want_series=False, error_estimate=False)
    assert got.solver.course_changes == ()
    p = got.solver.prediction
    assert p is not None and set(p) == {"nfev", "price_us_per_eval", "wall_s"}
    from gearcli.core.cost import RUN_FIXED_S

    fixed = RUN_FIXED_S[got.solver.engine]
    assert p["wall_s"] == pytest.approx(fixed + p["nfev"] * p["price_us_per_eval"] * 1e-6, rel=1e-12)


_FEATHER_GEAR = feather_gear()  # a 1e-9 kg m^2 gear: a 6.6 MHz mesh mode


def test_auto_does_not_leave_radau_for_an_explicit_run_its_budget_cannot_pay(tmp_path):
    # m_e = J_g / r_bg^2 = 1e-9 / 0.0752^2 = 1.8e-7 kg on k = 3e8 N/m: a 6.6 MHz mesh mode, max|lambda| = 4.1e7 1/s.
    # The load step rings it from t = 0; Radau resolves the ringing (~10 us at zeta = 0.05) in more evaluations than
    # its prediction, and its pace through that transient, extrapolated, made auto switch to DOP853, whose stability
    # alone needs ~2.6 x 4.1e7 x 0.1 s = 1.1e7 evaluations: over the run's budget (5e6), so the run failed (exit 1)
    # at t = 0.043 s where Radau alone finishes in ~1e4 evaluations.
    path = tmp_path / "feather.toml"
    path.write_text(_FEATHER_GEAR)
    cfg = load_design(str(path)).design
    got = run_simulation(cfg, compute_design(cfg), want_series=False)
    assert got.solver.method == "Radau"
    assert not [c for c in got.solver.course_changes if c["to"].startswith("DOP853")]
    # the quasi-static limit by hand: the gear carries the load alone, F_t = T_L / r_bg cos(alpha_t) = T_L / r_g
    f_t = 200.0 / 0.080
    np.testing.assert_allclose(got.stages[0].tangential_N.mean, f_t, rtol=1e-4)
    assert abs(got.stages[0].tangential_N.max - f_t) <= 1e-3 * f_t  # the ringing died out long before the window


def test_decide_passes_over_an_option_its_budget_cannot_pay():
    cfg, design = _case()
    model = TorsionalModel(spec_from_design(cfg, design))
    ch = choice_mod.choose_method(model.spec, cfg.simulation.duration_s, "auto", layout=model.layout)
    y = model.initial_state()
    spent = course.Spent("Radau", "python", 100_000, 0.0, 1e-3, y)  # a pace that makes DOP853 look cheaper
    t_end = cfg.simulation.duration_s
    got = course.decide(model, ch, spent, t_end, set(), "python")
    assert got is not None and got[0] == "DOP853"
    # DOP853's need for the rest, 2.6 max|lambda| (T - t), over what the budget has left: not taken
    assert course.decide(model, ch, spent, t_end, set(), "python", nfev_left=10.0) is None


def test_a_compiled_piece_stopped_by_its_limit_after_its_last_sample_is_a_finished_run(monkeypatch):
    # The compiled kernel checks its evaluation limit after each step: a piece whose last step both filled the last
    # output sample and crossed the limit returns the budget's status with every sample in place. The run is
    # complete; it ended in "Radau stopped at t = 0.3 s of 0.3 s: more than 26774 right-hand-side evaluations"
    # (exit 1; configs/extreme/rattle_zero_load.toml with the ISO law after a course change, found by a fuzz).
    from gearcli.simulate.solver import STATUS_BUDGET, STATUS_FINISHED, Integration

    cfg, design = _case()
    model = TorsionalModel(spec_from_design(cfg, design))
    ch = choice_mod.choose_method(model.spec, cfg.simulation.duration_s, "auto", layout=model.layout)
    y0 = model.initial_state()
    caps: list[int] = []

    def kernel_like(model, t_piece, method, rtol, *, y0=None, t0=0.0, max_nfev, engine, course=None, progress=None):
        caps.append(max_nfev)
        y = np.repeat(np.asarray(y0, dtype=float)[:, None], t_piece.size, axis=1)  # every sample filled
        return Integration(t_piece, y, method, rtol, np.full(y.shape[0], 1e-9), max_nfev + 1, 0, 0, 10, 0.0,
                           STATUS_BUDGET, f"more than {max_nfev} right-hand-side evaluations", float(t_piece[-1]),
                           engine="compiled")

    monkeypatch.setattr(course, "integrate", kernel_like)
    t_eval = np.linspace(0.0, cfg.simulation.duration_s, 11)
    run, changes = course.integrate_auto(model, t_eval, ch, 1e-6, "compiled", requested_engine="auto", y0=y0,
                                         max_nfev=10**7)
    assert len(caps) == 1 and caps[0] < 10**7  # the piece ran under its course limit, not the run's budget
    assert run.status == STATUS_FINISHED and changes == []  # nothing left to decide: no course change recorded
    assert np.all(np.isfinite(run.y)) and run.t_fail == t_eval[-1]


def test_a_run_that_spends_its_budget_over_several_pieces_names_the_whole_budget(monkeypatch):
    # A run stopped at its course limit that goes on (or changes course) and then spends the rest of its budget
    # said "more than 184713 right-hand-side evaluations" (the last piece's rest) after 5,000,023 in all
    # (configs/extreme/load_reversal.toml with a 1e14 contact law, found by a fuzz): the message names the run's
    # budget, which its evaluations exceed.
    from gearcli.simulate.solver import STATUS_BUDGET, Integration

    cfg, design = _case()
    model = TorsionalModel(spec_from_design(cfg, design))
    ch = choice_mod.choose_method(model.spec, cfg.simulation.duration_s, "auto", layout=model.layout)
    y0 = model.initial_state()

    def kernel_like(model, t_piece, method, rtol, *, y0=None, t0=0.0, max_nfev, engine, course=None, progress=None):
        y = np.full((np.asarray(y0).size, t_piece.size), np.nan)
        half = max(2, t_piece.size // 2) if t_piece.size > 2 else 1  # the first half filled, then the limit
        y[:, :half] = np.asarray(y0, dtype=float)[:, None]
        return Integration(t_piece, y, method, rtol, np.full(y.shape[0], 1e-9), max_nfev + 1, 0, 0, 10, 0.0,
                           STATUS_BUDGET, f"more than {max_nfev} right-hand-side evaluations",
                           float(t_piece[half - 1]), engine="compiled")

    monkeypatch.setattr(course, "integrate", kernel_like)
    t_eval = np.linspace(0.0, cfg.simulation.duration_s, 41)
    budget = 10**6
    run, _ = course.integrate_auto(model, t_eval, ch, 1e-6, "compiled", requested_engine="auto", y0=y0,
                                   max_nfev=budget)
    assert run.status == STATUS_BUDGET and run.nfev > budget
    assert run.message == f"more than {budget} right-hand-side evaluations"
