"""The error estimate of a run that changed course (``auto``: Radau, then DOP853 from the state reached) against a
converged reference: the check pass integrates with the run's last method, which on a lightly damped scene is far
less accurate at the run's rtol than the method that ran first, so at rtol / 10 the check carried an error as large
as the run's (window max: run 6.5 N off, check 8.5 N off, their difference 1.6 N: 5.3e-4 of the mean estimated,
2.1e-3 true, unwarned). It now runs at rtol / 100 after a course change (docs/numerics.md, "Honest statistics").

Scene (written here): one helical stage 25/77, m_n 2.5 mm, 3000 rpm prescribed, 300 N·m on a 0.4 kg·m² drum behind a
5e4 N·m/rad coupling with 2 N·m·s/rad (a 56 Hz mode with ζ < 1 %, still ringing ±3.6 kN through the window), mesh
damping ratio 0.005; the flanks unload 2 % of the window (a non-smooth force law: DOP853's error does not fall as
rtol there). Reference: DOP853 at rtol 1e-11, which agrees with DOP853 at 1e-12 and Radau at 1e-10 to 2e-5 N.
"""

from __future__ import annotations

import pytest

from gearcli import api
from gearcli.simulate import run_simulation
from gearcli.simulate.estimate import Plan, plan, tight_rtol

SCENE = """
title = "lightly damped drum behind one stage"
[materials.steel]
density_kg_m3 = 7850
youngs_modulus_MPa = 2.1e5
poisson_ratio = 0.3
[[stage]]
normal_module_mm = 2.5
normal_pressure_angle_deg = 20
helix_angle_deg = 10
pinion = { teeth = 25, face_width_mm = 30, hand = "left",  material = "steel" }
gear   = { teeth = 77, face_width_mm = 28, hand = "right", material = "steel" }
[contact]
damping_ratio = 0.005
[input]
speed_rpm = 3000
ramp_s = 0.05
[load]
torque_Nm = 300
ramp_s = 0.05
inertia_kg_m2 = 0.4
coupling_stiffness_Nm_rad = 5.0e4
coupling_damping_Nms_rad = 2
[simulation]
duration_s = 0.6
steps = 6000
rtol = 1e-4
"""


def test_a_mixed_run_is_checked_one_decade_tighter_and_always_by_the_tight_pass():
    from types import SimpleNamespace

    import numpy as np

    assert tight_rtol(1e-4) == pytest.approx(1e-5)
    assert tight_rtol(1e-4, mixed=True) == pytest.approx(1e-6)
    assert tight_rtol(1e-12, mixed=True) == pytest.approx(1e-13)  # the schema's floor
    # a scene without oscillating modes (the check starts at the window) whose span is most of the run: one method
    # gets the loose pass (2 x rtol, estimate twice the difference), a mixed run the tight one at rtol / 100
    none = SimpleNamespace(eigenvalues=np.zeros(0))
    choice = SimpleNamespace(at_full_load=none, at_operating_point=none, indicator=1.0)
    t = np.linspace(0.0, 1.0, 101)
    single = plan(t, 1e-4, choice, (0.05, 1.0))  # type: ignore[arg-type]
    assert single.rtol == pytest.approx(2e-4) and single.scale == 2.0
    mixed = plan(t, 1e-4, choice, (0.05, 1.0), mixed=True)  # type: ignore[arg-type]
    # the tight pass's difference is (1 - 100^-0.6) of the run's error at the slowest measured convergence
    assert isinstance(mixed, Plan) and mixed.rtol == pytest.approx(1e-6)
    assert mixed.scale == pytest.approx(1.0 / (1.0 - 0.01 ** 0.6), rel=1e-12)  # 1.067


@pytest.mark.slow
def test_the_estimate_of_a_run_that_changed_course_bounds_its_true_error(tmp_path, monkeypatch):
    # the course change made deterministic: auto's limit at 15000 evaluations, its CPU-time limit out of play (on the
    # command line this scene changed course from Radau to DOP853 at 0.32-0.39 s, 20500-21200 evaluations, by time)
    from gearcli.simulate import course
    from gearcli.simulate.solver import CourseLimit

    monkeypatch.setattr(course, "limit", lambda *a, **k: CourseLimit(15000.0, float("inf")))
    path = tmp_path / "light.toml"
    path.write_text(SCENE, encoding="utf-8")
    loaded = api.load(str(path))
    design = api.design(loaded)
    run = api.simulate(loaded.design, design)
    assert [c["to"].split()[0] for c in run.solver.course_changes] == ["DOP853"], run.solver.course_changes
    ref = run_simulation(loaded.design, design, method="DOP853", rtol=1e-11, error_estimate=False, want_series=False)
    st, rs = run.stages[0], ref.stages[0]
    est = st.error_estimate
    assert est is not None
    mean = abs(rs.tangential_N.mean)
    for q in ("min", "max", "std"):
        true = abs(getattr(st.tangential_N, q) - getattr(rs.tangential_N, q)) / mean
        # honest: the solver's estimate is not far below the truth, and a statistic off by more than the target is
        # named unresolved (the check at rtol / 10 estimated the max 4x low and left it unnamed)
        assert est.relative[q] >= 0.8 * true, (q, est.relative[q], true)
        if true > 1e-3:
            assert q in est.unresolved, (q, true, est.unresolved)
