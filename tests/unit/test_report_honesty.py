"""Acceptance: the error the report gives for the file's own settings is honest.

The report measures the default-settings run against its reference (DOP853 at a tight rtol). Here
the same run's error is measured independently, against a tight run of a different, implicit method
(Radau at rtol 1e-10) computed in this test, with the error formulas written out again. The two
must agree within a factor of 3; where the report says "below reference resolution", the
independent error must be small too (within 3x the reference's stated uncertainty), which checks the
resolution claim instead of comparing two numbers that are both noise.

The scene is the seed reducer cut to 0.25 s (ramps end at 0.18 s) so the test stays fast.
"""

from __future__ import annotations

from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SEED = ROOT / "configs" / "concrete_mixer.toml"
FACTOR = 3.0

import gearcli.simulate as simulate  # noqa: E402  an import error is a failure, never a skip

assert hasattr(simulate, "run_simulation")


@pytest.fixture(scope="module")
def scene():
    from gearcli.config import load_design
    from gearcli.design import compute_design

    cfg = load_design(str(SEED), ["simulation.duration_s=0.25"]).design
    return cfg, compute_design(cfg)


def independent_errors(run, truth) -> dict[str, float]:
    """|Δ| / |truth| for the window-mean output speed, the worst stage's mean F_t and peak |F_t|."""
    speed = abs(run.output_speed_deg_s - truth.output_speed_deg_s) / abs(truth.output_speed_deg_s)
    mean = max(abs(a.tangential_N.mean - b.tangential_N.mean) / abs(b.tangential_N.mean)
               for a, b in zip(run.stages, truth.stages, strict=True))
    peak = max(abs(a.peak_tangential_N - b.peak_tangential_N) / abs(b.peak_tangential_N)
               for a, b in zip(run.stages, truth.stages, strict=True))
    return {"speed": speed, "mean_force": mean, "peak_force": peak}


def test_reported_error_of_the_default_settings_is_honest(scene):
    from gearcli.report import LadderSpec, build_report
    from gearcli.simulate import run_simulation

    cfg, design = scene
    assert cfg.simulation.method == "auto" and cfg.simulation.rtol == 1e-6  # the defaults
    report = build_report(cfg, design, spec=LadderSpec(rtols=(1e-6,)))
    reported = report.accuracy.file_run
    uncertainty = report.accuracy.reference.uncertainty

    default_run = run_simulation(cfg, design, want_series=False)
    truth = run_simulation(cfg, design, method="Radau", rtol=1e-10, want_series=False)
    measured = independent_errors(default_run, truth)

    for q, independent in measured.items():
        ours = reported.error(q)
        if reported.below_reference_resolution[q]:
            # both are below what the reference can resolve: check the resolution claim instead
            assert independent <= FACTOR * uncertainty, (q, independent, uncertainty)
        else:
            assert ours / FACTOR <= independent <= ours * FACTOR, (q, ours, independent)
