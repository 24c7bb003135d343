"""An aliased excitation biases the window mean too: the warning names it, and the bound covers the miss.

tr20c: a TE-forced linear mesh oscillator at resonance (data/linear_te_resonance.toml, damping ratio 0.01, steady
amplitude A = 4.7e4 N about the static 9333 N), run as a fixed window of 1 s sampled 990 times: the 999.2 Hz response
shows in the samples as its 9.2 Hz alias, and the trapezoid rule integrates that slow sinusoid over its 7.4 periods in
the window. The window mean came out 10433 N; `statistics_undersampled` named min, max and std only, and the mean's
sampling estimate (Richardson, which sees the same alias at both spacings) was 0.03 N.

Independent reference, the closed form: the steady response is a sinusoid of amplitude
A = sqrt(k^2 + (c Omega)^2) |q| cos(alpha) about the static F_0 = T_L / r, so the true window mean lies within the
partial-period bound A / (pi n) of F_0 (n = 783 periods of 999.2 Hz in the window: 19 N).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

from click.testing import CliRunner
from te_oscillator import mesh_hz, orbit

from gearcli.cli import cli

SCENE = Path(__file__).parent / "data" / "linear_te_resonance.toml"


def _run(steps: int) -> dict:
    res = CliRunner().invoke(cli, ["simulate", str(SCENE), "--format", "json", "-q", "--set", "simulation.steady=window",
                                   "--set", "simulation.duration_s=1.0", "--set", f"simulation.steps={steps}"])
    assert res.exit_code == 0, res.stderr
    return json.loads(res.stdout)


def _static_and_bound(window_s: float) -> tuple[float, float]:
    """F_0 and A / (pi n): how far the true window mean may lie from it (module text)."""
    static, amplitude, _ = orbit(0.01, 2398.2)
    return static, amplitude / (math.pi * mesh_hz(2398.2) * window_s)


def _undersampled(doc: dict) -> list[list[str]]:
    return [w["statistics"] for w in doc["warnings"] if w["code"] == "statistics_undersampled"]


def test_an_aliased_mean_is_named_and_bounded():
    doc = _run(990)
    (t0, t1) = doc["summary"]["window_s"]
    static, partial = _static_and_bound(t1 - t0)
    stage = doc["summary"]["stages"][0]
    miss = abs(stage["tangential_N"]["mean"] - static) - partial  # beyond what the true window mean may differ
    assert miss > 1e-2 * static  # the samples' mean is far off ...
    assert stage["sampling_error"]["aliased"] is not None
    assert stage["sampling_error"]["mean_N"] >= miss  # ... the bound covers it ...
    assert any("mean" in s for s in _undersampled(doc))  # ... and the warning names the mean
    assert "mean" in stage["error_estimate"]["unresolved"]
    steps = stage["sampling_error"]["aliased"]["steps"]
    fine = _run(steps)  # the suggested sampling: the mean is the true one, and not named
    assert abs(fine["summary"]["stages"][0]["tangential_N"]["mean"] - static) <= partial
    assert not any("mean" in s for s in _undersampled(fine))
