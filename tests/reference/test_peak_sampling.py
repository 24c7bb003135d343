"""The run's peak |F_t| (``peak_tangential_N``, ``runup_factor``) is taken over the output samples: a start's peak
between two samples is missed, and the run must say so (DESIGN section 7). Checked on a load step whose peak is
known in closed form: a speed-driven pinion, a free gear, a linear viscous mesh (one degree of freedom,
m_e q'' + c q' + k q = F_s from rest), where the mesh force f = k q + c q' is
F_s (1 - exp(-zeta w t) (cos w_d t - zeta / sqrt(1 - zeta^2) sin w_d t))."""

from __future__ import annotations

import math

import numpy as np
from numpy.testing import assert_allclose

from gearcli import api
from tests.reference.step_scene import STEP_SCENE as SCENE


def _closed_form_peak() -> float:
    alpha = math.radians(20.0)
    r_bg = 0.5 * 40 * 4e-3 * math.cos(alpha)
    m_e = 0.05 / r_bg**2
    k, zeta = 3e8, 0.05
    w = math.sqrt(k / m_e)  # 926.8 Hz
    w_d = w * math.sqrt(1 - zeta**2)
    f_s = 200.0 / 0.080  # F_t = T_L / r_g = 2500 N
    t = np.linspace(0.0, 2 * math.pi / w, 200001)  # the first period holds the largest overshoot
    f = f_s * (1 - np.exp(-zeta * w * t) * (np.cos(w_d * t) - zeta / math.sqrt(1 - zeta**2) * np.sin(w_d * t)))
    return float(f.max())  # 4646.9 N at t = 0.523 ms


def _run(tmp_path, steps: int):
    path = tmp_path / "step.toml"
    path.write_text(SCENE)
    loaded = api.load(str(path), [f"simulation.steps={steps}"])
    return api.simulate(loaded.design, api.design(loaded))


def test_a_peak_between_the_samples_is_warned_with_the_steps_that_resolve_it(tmp_path):
    peak = _closed_form_peak()
    coarse = _run(tmp_path, 400)  # 250 us samples, 4.3 a period: the sampled peak misses 0.4 %
    got = coarse.stages[0].peak_tangential_N
    assert peak - got > 1e-3 * peak
    (w,) = [d for d in coarse.diagnostics if d.code == "peak_undersampled"]
    assert w.data["stage"] == 1 and w.data["steps"] > 400
    assert w.data["estimated_error_N"] >= peak - got  # the estimate covers the true miss (19 N)
    fine = _run(tmp_path, 4000)  # 25 us samples
    assert not [d for d in fine.diagnostics if d.code == "peak_undersampled"]
    assert_allclose(fine.stages[0].peak_tangential_N, peak, rtol=1e-3)
    assert_allclose(fine.stages[0].runup_factor, peak / 2500.0, rtol=1e-3)
