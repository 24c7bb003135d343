"""Honest statistics (docs/performance.md): every window statistic of every stage force of a default run
is within 1e-3 (of the mean) of a converged reference, or the run warns ``statistics_unresolved`` for it;
a converged run carries no such warning.

The reference is the same scene at rtol 1e-10 (the run's method; its own error is below 1e-7 of the mean
on these scenes, measured against rtol 1e-11). The full sweep over configs/ and configs/extreme/ is
benchmarks/bench_accuracy.py (table in README); this test runs a subset that covers the estimate's cases
(check pass from the window start and from t = 0, tight and loose, resolved and warned, DOP853 and
Radau) within the CI budget.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from gearcli import diagnostics as dg
from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.simulate import run_simulation
from gearcli.simulate.estimate import TARGET

ROOT = Path(__file__).resolve().parents[2]
QUANTITIES = ("mean", "min", "max", "std")
SCENES = (
    "configs/concrete_mixer.toml",  # the seed: lightly damped, checked from t = 0 (loose check), resolved
    "configs/industrial_two_stage.toml",  # damped: checked from the window (tight check); auto: Radau
    "configs/concrete_mixer_loose_rtol.toml",  # rtol 1e-4: unresolved, warned
    "configs/extreme/load_reversal.toml",  # errors of the reversal survive into the window: warned
    "configs/extreme/stiff_linear_100x.toml",
    "configs/extreme/five_stages.toml",
    "configs/extreme/heavy_damping.toml",  # Radau
    "configs/extreme/stiff_linear_10000x.toml",  # Radau stepping over an undamped 18 kHz mesh mode
)


# the reference where rtol 1e-10 with the run's own method is too slow for CI: DOP853 at rtol 1e-8 (the
# 18 kHz mode resolved; agrees with Radau at rtol 1e-10 to 5e-4 of the mean, measured)
REFERENCE = {"configs/extreme/stiff_linear_10000x.toml": ("DOP853", 1e-8)}


def _scene(rel: str):
    cfg = load_design(str(ROOT / rel), []).design
    return cfg, compute_design(cfg)


def _unresolved(sim, codes=(dg.STATISTICS_UNRESOLVED,)) -> dict[int, set[str]]:
    out: dict[int, set[str]] = {}
    for d in sim.diagnostics:
        if d.code in codes:
            out.setdefault(d.data["stage"], set()).update(d.data["statistics"])
    return out


@pytest.mark.parametrize("rel", SCENES)
def test_every_statistic_resolved_or_warned(rel):
    cfg, design = _scene(rel)
    sim = run_simulation(cfg, design, want_series=False)
    method, rtol = REFERENCE.get(rel, (sim.solver.method, 1e-10))
    ref = run_simulation(cfg, design, method=method, rtol=rtol, want_series=False, error_estimate=False,
                         max_nfev=5_000_000)
    warned = _unresolved(sim)
    for s, r in zip(sim.stages, ref.stages, strict=True):
        assert s.error_estimate is not None
        scale = abs(r.tangential_N.mean)
        for q in QUANTITIES:
            error = abs(getattr(s.tangential_N, q) - getattr(r.tangential_N, q)) / scale
            if error > TARGET:
                assert q in warned.get(s.index, set()), (rel, s.index, q, error)
                assert s.error_estimate.suggested_rtol is not None
                assert not s.error_estimate.resolved
        # the warnings name what the JSON says is unresolved, and only that: the solver's (statistics_unresolved)
        # and the output sampling's share of min and max (statistics_undersampled, docs/numerics.md)
        both = _unresolved(sim, (dg.STATISTICS_UNRESOLVED, dg.STATISTICS_UNDERSAMPLED))
        assert set(s.error_estimate.unresolved) == both.get(s.index, set())


@pytest.mark.parametrize("rel", ("configs/concrete_mixer.toml", "configs/industrial_two_stage.toml",
                                 "configs/extreme/load_reversal.toml"))
def test_converged_run_carries_no_warning(rel):
    cfg, design = _scene(rel)
    sim = run_simulation(cfg, design, rtol=1e-9, want_series=False)
    assert not dg.has(sim.diagnostics, dg.STATISTICS_UNRESOLVED), sim.warnings
    # the solver's share resolved; what is left unresolved is the output sampling's, which a tighter rtol cannot
    # change (the seed's stage 1 max: docs/numerics.md "The output sampling"), and it is warned
    sampled = _unresolved(sim, (dg.STATISTICS_UNDERSAMPLED,))
    for s in sim.stages:
        e = s.error_estimate
        assert e is not None and all(e.relative[q] <= e.target_relative for q in ("min", "max", "std", "spectrum"))
        assert e.relative["mean"] <= e.mean_target_relative
        assert set(e.unresolved) == sampled.get(s.index, set())


def test_suggested_rtol_resolves_the_warning():
    """Following the rtol the warning names removes it (load_reversal at rtol 1e-5: stages 1-3 warned), within two
    suggestions: the error of a sampled extreme is not monotonic in rtol (stage 2's min was 0.04 N off the rtol 1e-10
    reference at 1e-6 and 7.4 N off at 1e-7, each within its run's estimate), so one suggestion may land on a run
    that names a tighter one; and every run warns of what misses its target against that reference."""
    cfg, design = _scene("configs/extreme/load_reversal.toml")
    ref = run_simulation(cfg, design, rtol=1e-10, want_series=False, error_estimate=False, max_nfev=5_000_000)
    sim = run_simulation(cfg, design, rtol=1e-5, want_series=False)
    suggestions = [d.data["rtol"] for d in sim.diagnostics if d.code == dg.STATISTICS_UNRESOLVED]
    assert suggestions, "this scene is expected to warn at rtol 1e-5"
    for _ in range(3):
        for s, r in zip(sim.stages, ref.stages, strict=True):  # what it misses beyond its target, it warns of
            e, x = s.error_estimate, s.tangential_N
            for q in ("min", "max", "std"):
                if abs(getattr(x, q) - getattr(r.tangential_N, q)) > e.target_relative * abs(r.tangential_N.mean):
                    assert q in e.unresolved, (s.index, q)
        if not suggestions:
            break
        sim = run_simulation(cfg, design, rtol=min(suggestions), want_series=False)
        suggestions = [d.data["rtol"] for d in sim.diagnostics if d.code == dg.STATISTICS_UNRESOLVED]
    assert not suggestions, sim.warnings


def test_estimate_off_leaves_no_estimate():
    cfg, design = _scene("configs/concrete_mixer.toml")
    sim = run_simulation(cfg, design, want_series=False, error_estimate=False)
    assert sim.solver.check_pass is None and all(s.error_estimate is None for s in sim.stages)
