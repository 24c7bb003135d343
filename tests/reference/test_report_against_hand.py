"""`gearcli report` on a scene of its own, every compared number recomputed by hand or from the run's own series.

Scene: two helical stages (m_n 3 / 5 mm, z 21/67 and 18/61, β 14° / 12°), 1200 rpm prescribed at the input, 2500 N·m
at the output, ISO 6336 default mesh law; a static transmission error on stage 1 only (3 µm at 1x, 1 µm at 2x the
mesh frequency). Stage 1's mesh frequency is z_1 n / 60 = 21 · 20 = 420 Hz; its 2x line (840 Hz) lies near the first
mode (~967 Hz, dominated by stage 2's mesh), so stage 2's force is dominated by stage 1's 2x line, not by a line of
its own (stage 2's mesh frequency: 18 · 20 · 21/67 = 112.8 Hz).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from gearcli import api
from gearcli.core.channels import Channel
from gearcli.report.spectrum import name_peak

SCENE = """
title = "two stages, TE on stage 1"
[materials.steel]
density_kg_m3 = 7850
youngs_modulus_MPa = 2.1e5
poisson_ratio = 0.3
[[stage]]
normal_module_mm = 3
normal_pressure_angle_deg = 20
helix_angle_deg = 14
pinion = { teeth = 21, face_width_mm = 40, hand = "left",  material = "steel" }
gear   = { teeth = 67, face_width_mm = 38, hand = "right", material = "steel" }
mesh   = { transmission_error_um = [3.0, 1.0], transmission_error_phase_deg = [90, -90] }
[[stage]]
normal_module_mm = 5
normal_pressure_angle_deg = 20
helix_angle_deg = 12
pinion = { teeth = 18, face_width_mm = 70, hand = "right", material = "steel" }
gear   = { teeth = 61, face_width_mm = 66, hand = "left",  material = "steel" }
[input]
speed_rpm = 1200
ramp_s = 0.05
[load]
torque_Nm = 2500
ramp_s = 0.05
[simulation]
duration_s = 0.25
steps = 5000
"""


def test_name_peak_names_another_stages_mesh_line_and_keeps_its_own_first():
    # hand lines: this stage 112.8 Hz (x1, x2 225.7, x3 338.5), stage 1 420 Hz (x2 840, x3 1260), mode 967 Hz
    others = [(1, 420.0)]
    assert name_peak(839.1, 3.6, 112.8, (967.3,), others) == "stage 1 mesh harmonic 2"
    assert name_peak(421.0, 3.6, 112.8, (967.3,), others) == "stage 1 mesh frequency"
    assert name_peak(965.0, 3.6, 112.8, (967.3,), others) == "natural frequency 1"
    # a line shared by this stage (3x 112.8 = 338.4 Hz) and another (its 1x) is named as this stage's own
    assert name_peak(338.4, 3.6, 112.8, (), [(1, 338.4)]) == "mesh harmonic 3"
    assert name_peak(600.0, 3.6, 112.8, (967.3,), others) == "none"
    assert name_peak(839.1, 3.6, 112.8, (967.3,)) == "none"  # without the other stages: as before


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    path = tmp_path_factory.mktemp("report_hand") / "two_stage_te.toml"
    path.write_text(SCENE, encoding="utf-8")
    loaded = api.load(str(path))
    return api.report_file(loaded, api.design(loaded), quick=True)


def test_static_forces_are_the_hand_calculation_and_the_means_are_the_series_integral(report):
    # hand: T_out = 2500 N·m on gear 4 (r = m_n z / (2 cos β)); shaft 2 carries T_out z3 / z4 (η = 1)
    r4 = 5.0 * 61 / (2 * math.cos(math.radians(12)))  # 155.91 mm
    r2 = 3.0 * 67 / (2 * math.cos(math.radians(14)))  # 103.58 mm
    ft = {1: 2500e3 * 18 / 61 / r2, 2: 2500e3 / r4}  # 7122.3 N, 16035.2 N
    alpha_t = {k: math.atan(math.tan(math.radians(20)) / math.cos(math.radians(b))) for k, b in ((1, 14), (2, 12))}
    rows = {(r.stage, r.quantity): r for r in report.comparison}
    sim = report.simulation
    t = sim.time_s
    w0, w1 = sim.window_s
    m = (t >= w0 - 1e-12) & (t <= w1 + 1e-12)
    for k in (1, 2):
        assert_allclose(rows[(k, "tangential_N")].theory, ft[k], rtol=1e-9)  # closed form above
        assert_allclose(rows[(k, "radial_N")].theory, ft[k] * math.tan(alpha_t[k]), rtol=1e-9)
        f = sim.series[Channel("tangential_force", f"stage{k}")]
        mean = np.trapezoid(f[m], t[m]) / (t[m][-1] - t[m][0])  # the window's integral mean, independently
        assert_allclose(rows[(k, "tangential_N")].simulated, mean, rtol=1e-12)
        assert_allclose(rows[(k, "tangential_N")].error_percent, 100 * (mean - ft[k]) / ft[k], rtol=1e-9)
        st = next(s for s in report.stages if s.stage == k)
        # dynamic factor: window max |F_t| / static; run-up factor: whole-run max |F_t| / static (DESIGN §12)
        assert_allclose(st.dynamic_factor, np.abs(f[m]).max() / ft[k], rtol=1e-9)
        assert_allclose(st.runup_factor, np.abs(f).max() / ft[k], rtol=1e-9)
    # ratio row: the design's z2/z1 · z4/z3
    assert_allclose(rows[(None, "ratio")].theory, 67 / 21 * 61 / 18, rtol=1e-12)


def test_a_peak_on_stage_1s_line_is_named_so_in_stage_2s_spectrum(report):
    f1 = 21 * 1200 / 60  # 420 Hz, stage 1's mesh frequency by hand
    s1, s2 = (next(s for s in report.stages if s.stage == k).spectrum for k in (1, 2))
    # stage 2's force: its largest line within a resolution bin of 2 f1 (840 Hz), which none of its own lines is near
    assert abs(s2.peak_frequency_Hz - 2 * f1) <= s2.resolution_Hz
    assert abs(s2.mesh_frequency_Hz - 18 * 20 * 21 / 67) < 1e-9
    assert s2.matches == "stage 1 mesh harmonic 2"
    assert s1.matches == "mesh harmonic 2"  # stage 1's own line keeps its own name


def test_the_resonance_warnings_gain_is_what_the_run_shows_at_that_resonance(tmp_path):
    """The modal prediction (amplification = participation / 2ζ, a linear eigen-analysis) against the nonlinear run:
    the same train with 0.3 µm of 1x TE on stage 1 only (small: the mesh never unloads), driven at the speed where
    stage 1's mesh frequency meets mode 1 (~967 Hz: z_1 n / 60 = f_1 at n = 60 f_1 / 21). The run's 1x amplitude of
    stage 1's F_t over the blocked error force — k e along the line of action, F_t = k e cos² β_b cos α_wt by hand —
    is the resonant gain the warning predicts."""
    base = SCENE.replace("transmission_error_um = [3.0, 1.0], transmission_error_phase_deg = [90, -90]",
                         "transmission_error_um = [0.3], transmission_error_phase_deg = [90]")
    path = tmp_path / "probe.toml"
    path.write_text(base, encoding="utf-8")
    loaded = api.load(str(path))
    design = api.design(loaded)
    clamped = next(m for m in api.modes(loaded.design, design) if m.boundary == "clamped_input")  # a speed drive
    f1 = clamped.modes[0].frequency_Hz
    speed = 60.0 * f1 / 21
    path.write_text(base.replace("speed_rpm = 1200", f"speed_rpm = {speed:.6f}"), encoding="utf-8")
    loaded = api.load(str(path))
    design = api.design(loaded)
    rep = api.report_file(loaded, design, quick=True)
    warned = [d for d in rep.diagnostics if d.code == "resonance" and d.data.get("excitation") == "stage 1 mesh 1x"]
    assert len(warned) == 1
    gain = warned[0].data["amplification"]
    st = design.stages[0]
    k = st.mesh_stiffness.linearised_N_mm  # N/mm, the linearised ISO mesh stiffness (the modal analysis's k)
    blocked_ft = k * 0.3e-3 * math.cos(math.radians(st.base_helix_angle_deg)) ** 2 \
        * math.cos(math.radians(st.working_pressure_angle_deg))
    sim = rep.simulation.stages[0]
    assert sim.contact_loss_fraction == 0.0  # linear: the prediction's premise
    amp = next(o for o in rep.stages[0].spectrum.mesh_orders if o.order == 1).tangential_N
    # 0.25 % apart on this scene; the modal gain neglects the other mode's share and the TE's own quasi-static force
    assert_allclose(amp / blocked_ft, gain, rtol=0.02)


def test_the_report_json_names_the_contact_law_the_run_integrates(report):
    """The report's design section gives each stage's contact law (default: ISO 6336-1 calibrated, K such that
    e K h0^(e-1) = k_n = c_γα b / cos² β_b), not only the Hertz line contact's K, which the default law does not use."""
    from gearcli.io.report_json import report_dict

    st = report_dict(report)["design"]["stages"][0]
    ms = st["mesh_stiffness"]
    d = report.design.stages[0]
    k_n = d.iso6336_mesh_stiffness_N_mm_um * 1e3 * d.face_width_mm / math.cos(math.radians(d.base_helix_angle_deg)) ** 2
    assert ms["law"] == "iso6336" and ms["exponent"] == 1.5
    assert_allclose(ms["linearised_N_mm"], k_n, rtol=1e-9)  # the hand k_n
    assert_allclose(1.5 * ms["K"] * ms["static_approach_mm"] ** 0.5, k_n, rtol=1e-9)  # the law's tangent at h0
    assert ms["K"] != pytest.approx(st["hertz_stiffness_N_mm1_5"], rel=0.1)  # a different number: both needed
