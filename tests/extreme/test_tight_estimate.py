"""The tight check pass's estimate is not below the run's error (gearcli/simulate/estimate.py, "Tolerance").

Scene: one helical stage (m_n 4, 20/60 teeth, beta 15 deg) under the ISO-calibrated Hertzian mesh with no damping
at all, 1500 rpm, 300 N m: after the 0.05 s ramps the mesh rings undamped at ~600 Hz for the whole window. The
reference is the same scene at rtol / 1000 with DOP853 (its own estimate of its error is below 1e-6 of
the mean). RK45 converges at q ~ 0.8 in rtol, so the bare difference to a pass at rtol / 10 is only 1 - 10^-0.8 =
0.84 of the run's error: before the fix a min 1.15e-3 of the mean off was estimated 0.97e-3 and called resolved.
The static force, an independent check of the window mean: F_t = T / r = 300e3 N mm / (4 x 60 / cos 15 deg / 2).
"""

from __future__ import annotations

import math

import pytest

from gearcli import diagnostics as dg
from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.simulate import run_simulation
from gearcli.simulate.estimate import TARGET

SCENE = """
title = "undamped ISO mesh ringing through the window"

[[stage]]
normal_module_mm = 4
normal_pressure_angle_deg = 20
helix_angle_deg = 15
pinion = { teeth = 20, face_width_mm = 40, hand = "left" }
gear   = { teeth = 60, face_width_mm = 38, hand = "right" }

[contact]
damping_ratio = 0

[input]
speed_rpm = 1500
ramp_s = 0.05

[load]
torque_Nm = 300
ramp_s = 0.05

[simulation]
duration_s = 0.2
steps = 400
engine = "python"
"""

# where the min and max land just beyond the 1e-3 target (2.77 N and 2.87 N against 2.415 N): before the fix RK45
# estimated 2.33 N (0.84x) and BDF 2.28 N (0.80x), both "resolved"; now 3.12 N and 3.04 N, warned
CASES = (("RK45", 7e-7), ("BDF", 8e-8))


@pytest.mark.slow
@pytest.mark.parametrize(("method", "rtol"), CASES)
def test_estimate_is_not_below_the_true_error(tmp_path, method, rtol):
    path = tmp_path / "undamped.toml"
    path.write_text(SCENE, encoding="utf-8")
    cfg = load_design(str(path), []).design
    design = compute_design(cfg)
    run = run_simulation(cfg, design, method=method, rtol=rtol, want_series=False)
    ref = run_simulation(cfg, design, method="DOP853", rtol=rtol / 1000, want_series=False,
                         error_estimate=False, max_nfev=5_000_000)
    r_pitch_mm = 4 * 60 / math.cos(math.radians(15)) / 2
    # the window mean rings about the static force (Hertzian asymmetry shifts it by ~5e-5)
    assert ref.stages[0].tangential_N.mean == pytest.approx(300e3 / r_pitch_mm, rel=2e-4)
    s, r = run.stages[0], ref.stages[0]
    e = s.error_estimate
    assert e is not None
    scale = abs(r.tangential_N.mean)
    warned = {q for d in run.diagnostics if d.code == dg.STATISTICS_UNRESOLVED for q in d.data["statistics"]}
    for q in ("mean", "min", "max", "std"):
        true = abs(getattr(s.tangential_N, q) - getattr(r.tangential_N, q))
        # honest: the estimate is at least the error (the reference's own error is ~1e-3 of this one's)
        assert getattr(e.tangential_N, q) >= true, (q, getattr(e.tangential_N, q), true)
        # and not wildly above it (the scale 1.33 over a bare difference of 0.84x)
        assert getattr(e.tangential_N, q) <= 2.0 * true, (q, getattr(e.tangential_N, q), true)
        if q != "mean" and true > TARGET * scale:
            assert q in warned, (q, true / scale)
