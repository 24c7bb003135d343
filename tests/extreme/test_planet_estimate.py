"""The error estimate of a planetary stage covers every planet's sun mesh, not only planet 1's (the stage's
channels): its dynamic factor, run-up factor and run peak are its most loaded planet's, and an error there was
neither estimated nor warned (a position error loading planet 2 2.2x, DOP853 at rtol 1e-4: planet 2's window max
5.95 N off, the dynamic factor 2.2909 against 2.2881 converged, no warning; at rtol 3e-4 a spike made the run peak
6961 N against 4880 N, a run-up factor 3.34 against 2.34, and only planet 1's 2.8 N was named).

Scene (written here): a planetary reducer, sun 24 (input, 1500 rpm), 4 planets 36, ring 96 held, carrier out with
1500 N·m (ratio 1 + 96/24 = 5; per planet F_t = 1500 / 5 / 4 / 0.036 m = 2083.3 N by hand), m 3 mm, b 40 mm, 1 µm of
1x TE on every mesh, planet position errors [0, 8, 0, -3] µm. Reference: DOP853 at rtol 1e-11 (agrees with the same
at 1e-13 on scipy to 1e-12 of the peak).
"""

from __future__ import annotations

import pytest

from gearcli import api
from gearcli.simulate import run_simulation

SCENE = """
title = "planetary, unequal sharing"
[materials.steel]
density_kg_m3 = 7850
youngs_modulus_MPa = 2.1e5
poisson_ratio = 0.3
[[stage]]
type = "planetary"
normal_module_mm = 3
normal_pressure_angle_deg = 20
sun    = { teeth = 24, face_width_mm = 40, material = "steel" }
planet = { teeth = 36, face_width_mm = 40, count = 4, material = "steel", position_error_um = [0, 8, 0, -3] }
ring   = { teeth = 96, face_width_mm = 40, material = "steel" }
carrier = { inertia_kg_m2 = 0.5 }
fixed = "ring"
input = "sun"
[contact]
transmission_error_um = [1.0]
[input]
speed_rpm = 1500
ramp_s = 0.1
[load]
torque_Nm = 1500
ramp_s = 0.1
[simulation]
duration_s = 0.5
steps = 4000
method = "DOP853"
"""


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    path = tmp_path_factory.mktemp("planet_estimate") / "planet.toml"
    path.write_text(SCENE, encoding="utf-8")
    loaded = api.load(str(path))
    design = api.design(loaded)
    ref = run_simulation(loaded.design, design, rtol=1e-11, error_estimate=False, want_series=False)
    return loaded, design, ref


@pytest.mark.slow
# rtols where the scene has something to warn about: 1e-4 did until the ring meshes' errors took their phase against
# the sun meshes' (session 15), which left planet 2 within 1.2e-4 of the reference there; 2e-4 did until the method
# choice linearised the planets at their settled shares (session 16: the dynamic factor 0.96e-3 off, peak 0.49e-3)
@pytest.mark.parametrize("rtol", [3e-4, 6e-4, 1e-3])
def test_the_estimate_bounds_every_planets_error_and_the_factors_taken_from_them(runs, rtol):
    loaded, design, ref = runs
    assert abs(design.stages[0].static_force_N.tangential - 1500e3 / 5 / 4 / 36.0) < 1e-6  # the hand force
    run = run_simulation(loaded.design, design, rtol=rtol)
    st, rs = run.stages[0], ref.stages[0]
    est = st.error_estimate
    assert est is not None
    worst = {q: max(abs(getattr(p.sun.tangential_N, q) - getattr(o.sun.tangential_N, q))
                    for p, o in zip(st.planets, rs.planets, strict=True)) for q in ("min", "max", "std")}
    for q, true in worst.items():
        # the estimate (N) of the stage covers its worst planet: first order, a few % either side of the truth
        assert getattr(est.tangential_N, q) >= 0.8 * true, (q, getattr(est.tangential_N, q), true)
    # the dynamic factor is the most loaded planet's window max over the static force: off by more than the target
    # (1e-3), it must be named unresolved
    dk = abs(st.dynamic_factor - rs.dynamic_factor) / rs.dynamic_factor
    if dk > 1e-3:
        assert "max" in est.unresolved or "min" in est.unresolved, (dk, est.unresolved)
    # the run peak (most loaded planet's, whole run): off by more than 1e-3 of itself, peak_unresolved names it
    dp = abs(st.peak_tangential_N - rs.peak_tangential_N) / rs.peak_tangential_N
    codes = {d.code for d in run.diagnostics}
    if dp > 1e-3:
        assert "peak_unresolved" in codes or "peak_undersampled" in codes, (dp, sorted(codes))
    assert dk > 1e-3 or dp > 1e-3  # the premise of this scene at these rtols: something to warn about


@pytest.mark.slow
def test_the_peaks_sampling_warning_reads_the_planet_the_stage_peak_comes_from(runs):
    """``peak_undersampled`` judges the run peak the stage prints (its most loaded planet's, here planet 2: +8 µm of
    position error), not planet 1's channels: before, at 700 samples it named planet 1's peak and estimated 6.6 N
    where the planet-2 peak the run printed was 18.8 N below the one sampled 16x finer."""
    loaded = api.load(runs[0].source, ["simulation.steps=700"])
    run = run_simulation(loaded.design, api.design(loaded))
    st = run.stages[0]
    by_planet = [max(abs(p.sun.tangential_N.max), abs(p.sun.tangential_N.min)) for p in st.planets]
    assert max(range(4), key=lambda j: by_planet[j]) == 1  # planet 2 carries most (window), as the hand says
    warned = [d for d in run.diagnostics if d.code == "peak_undersampled"]
    assert warned, "700 samples over 0.5 s miss the run peak by more than 1e-3 (18.8 N of 4880 N)"
    for d in warned:
        assert d.data["peak_N"] == pytest.approx(st.peak_tangential_N, rel=1e-12)
