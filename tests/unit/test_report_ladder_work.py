"""What the accuracy study runs, and what it does not run twice.

- The file's own run is its settings' rung when it is that rung's run (the same method, rtol, window and
  engine): checked against a fresh run of the rung made here, number for number, on the seed.
- The sibling swap (a method auto resolves to is replaced on the ladder by its family sibling) follows what
  auto resolved to on the ladder's own rungs, not the file's run (whose settle test may have lengthened it),
  and never swaps in a sibling the ladder's engine cannot run (BDF beside a compiled ladder).
- The explicit reference pair (DOP853 1e-12 checked by Radau 1e-10) holds up to a stiffness that scales with
  what the engine running it saves over scipy.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest
from test_report_fakes import FakeSolver, fake_design, fake_simulation

from gearcli.report import LadderSpec, accuracy_study
from gearcli.report.accuracy import ladder_methods, relative_errors
from gearcli.report.build import same_as_rung
from gearcli.report.result import RunMetrics
from gearcli.simulate.results import SteadyState

ROOT = Path(__file__).resolve().parents[2]
SEED = ROOT / "configs" / "concrete_mixer.toml"
COMPILED = ("RK45", "DOP853", "Radau")


# ------------------------------------------------------------------------------------ sibling swap
def test_no_sibling_the_ladders_engine_cannot_run():
    assert ladder_methods(("auto", "DOP853", "Radau"), "Radau", COMPILED) == ("auto", "DOP853", "Radau")
    assert ladder_methods(("auto", "DOP853", "Radau"), "DOP853", COMPILED) == ("auto", "RK45", "Radau")
    assert ladder_methods(("auto", "DOP853", "Radau"), "Radau", None) == ("auto", "DOP853", "BDF")


class _AutoByRtol(FakeSolver):
    """auto resolves to Radau at rtol >= 1e-7 and to DOP853 below (as on configs/stiff_linear_mesh.toml)."""

    def __call__(self, method: str, rtol: float):
        self.auto = "Radau" if rtol >= 1e-7 else "DOP853"
        return super().__call__(method, rtol)


def test_the_swap_follows_auto_on_the_ladders_own_rungs_not_the_files_run():
    design = fake_design()
    # the file's run resolved to Radau (say, lengthened by its settle test); the ladder's auto rungs to DOP853
    study = accuracy_study(FakeSolver(design, auto="DOP853"), file_method="auto", file_rtol=1e-6,
                           auto_choice="Radau", spec=LadderSpec(rtols=(1e-3, 1e-6)))
    assert {r.method for r in study.runs} == {"auto", "RK45", "Radau"}
    assert {r.method_used for r in study.runs if r.method == "auto"} == {"DOP853"}


@pytest.mark.parametrize("engine_methods, expected", [(None, {"auto", "DOP853", "BDF"}),
                                                      (COMPILED, {"auto", "DOP853", "Radau"})])
def test_the_swap_takes_what_auto_chose_on_most_rungs(engine_methods, expected):
    solver = _AutoByRtol(fake_design())
    study = accuracy_study(solver, file_method="auto", file_rtol=1e-6, spec=LadderSpec(rtols=(1e-3, 1e-6, 1e-9)),
                           engine_methods=engine_methods)
    assert [r.method_used for r in study.runs if r.method == "auto"] == ["Radau", "Radau", "DOP853"]
    assert {r.method for r in study.runs} == expected
    assert len(solver.calls) == 2 + 3 * 3  # the reference pair and three methods of three rungs, none twice


# ------------------------------------------------------------------------------------ reference pair
def test_the_explicit_reference_holds_to_a_stiffness_scaled_by_the_engines_speedup():
    spec = LadderSpec()  # explicit_reference_limit 2e5 on scipy
    assert spec.reference_pair(1e6) == (("Radau", 1e-11), ("BDF", 1e-10))
    assert spec.reference_pair(4e5, explicit_speedup=12.8) == (("DOP853", 1e-12), ("Radau", 1e-10))
    assert spec.reference_pair(3e6, explicit_speedup=12.8) == (("Radau", 1e-11), ("BDF", 1e-10))
    # whatever the speed-up, not where DOP853's stability alone would exceed the explicit budget (1e6 evaluations,
    # which refuses the run): 12 stages a step over a stability radius of about 6 put that at max|λ|·T ≈ 5e5
    assert spec.reference_pair(1e6, explicit_speedup=12.8) == (("Radau", 1e-11), ("BDF", 1e-10))
    assert spec.reference_pair(1e5, explicit_speedup=0.5) == (("DOP853", 1e-12), ("Radau", 1e-10))  # never < 1x


# ------------------------------------------------------------------------------- the file's run shared
class _Cfg:
    def __init__(self, method="auto", rtol=1e-6, engine="auto"):
        self.method, self.rtol, self.engine = method, rtol, engine


def _sim(engine="compiled", rtol=1e-6, requested="auto", settle_runs=0, course=()):
    sim = fake_simulation(fake_design(), method="DOP853", rtol=rtol)
    solver = dataclasses.replace(sim.solver, requested_method=requested, engine=engine, course_changes=course)
    steady = SteadyState("window", None, None, None, None, None, settle_runs=settle_runs)
    return dataclasses.replace(sim, solver=solver, steady=steady)


def test_the_files_run_is_its_rung_only_when_it_is_that_run():
    assert same_as_rung(_sim(), _Cfg())
    assert same_as_rung(_sim(engine="python"), _Cfg(engine="python"))
    assert not same_as_rung(_sim(rtol=1e-7), _Cfg())  # auto tightened the file's rtol
    assert not same_as_rung(_sim(settle_runs=1), _Cfg())  # the settle test lengthened the run
    assert not same_as_rung(_sim(engine="python"), _Cfg())  # outside the batch auto kept scipy; a rung would not
    assert not same_as_rung(_sim(course=({"at_s": 0.1},)), _Cfg())
    assert not same_as_rung(_sim(requested="DOP853"), _Cfg())


@pytest.fixture(scope="module")
def seed():
    from gearcli.config import load_design
    from gearcli.design import compute_design

    cfg = load_design(str(SEED)).design
    return cfg, compute_design(cfg)


def _study_counting_runs(monkeypatch, cfg, design):
    import gearcli.report.build as build

    calls = []
    real = build.run_simulation

    def counting(*args, **kwargs):
        calls.append((kwargs.get("method"), kwargs.get("rtol")))
        return real(*args, **kwargs)

    monkeypatch.setattr(build, "run_simulation", counting)
    report = build.build_report(cfg, design, spec=LadderSpec(rtols=(1e-6,)))
    return report, calls


def test_the_files_run_stands_for_its_rung_number_for_number(seed, monkeypatch):
    from gearcli.simulate import run_simulation

    pytest.importorskip("numba")  # without the compiled engine the file's auto run may keep scipy, a rung not
    cfg, design = seed
    report, calls = _study_counting_runs(monkeypatch, cfg, design)
    assert report.simulation.steady.settle_runs == 0  # the seed's window is kept: the file's run is the rung's
    assert ("auto", 1e-6) not in calls and len(calls) == 1 + 2 + 2  # own run, reference pair, RK45 and Radau
    shared = report.accuracy.file_run
    # the rung's own run, made here as the ladder makes its rungs: the same integration, so the same numbers
    fresh = run_simulation(cfg, design, method="auto", rtol=1e-6, want_series=False, error_estimate=False,
                           diagnose=False)
    assert (shared.method_used, shared.nfev, shared.steps, shared.engine) == (
        fresh.solver.method, fresh.solver.nfev, fresh.solver.steps, fresh.solver.engine)
    errors = relative_errors(RunMetrics.of(fresh), report.accuracy.reference.metrics)
    assert (shared.error_speed, shared.error_mean_force, shared.error_peak_force) == (
        errors["speed"], errors["mean_force"], errors["peak_force"])


def test_a_lengthened_files_run_leaves_its_rung_to_run(monkeypatch):
    from gearcli.config import load_design
    from gearcli.design import compute_design

    cfg = load_design(str(SEED), ["simulation.duration_s=0.25"]).design  # its window rings: a settle re-run
    report, calls = _study_counting_runs(monkeypatch, cfg, compute_design(cfg))
    assert report.simulation.steady.settle_runs >= 1
    assert ("auto", 1e-6) in calls
    assert report.accuracy.file_run.nfev != report.simulation.solver.nfev


def test_a_ladder_rung_skips_the_start_and_motor_summaries():
    """The rungs are read for their statistics and counters only: a motor scene's rung leaves out the motor's and
    the start-up's summaries (~50 ms a rung on configs/motor_soft_start.toml), with the same statistics."""
    from gearcli.config import load_design
    from gearcli.design import compute_design
    from gearcli.simulate import run_simulation

    cfg = load_design(str(ROOT / "configs" / "motor_soft_start.toml")).design
    design = compute_design(cfg)
    full = run_simulation(cfg, design, want_series=False, error_estimate=False)
    bare = run_simulation(cfg, design, want_series=False, error_estimate=False, diagnose=False)
    assert "motor" in (full.extra or {}) and not {"motor", "start"} & set(bare.extra or {})
    assert full.solver.nfev == bare.solver.nfev and RunMetrics.of(full) == RunMetrics.of(bare)
