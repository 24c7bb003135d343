"""The periodic steady state and the mesh response on real scenes, against independent references.

Scene: configs/backlash_oscillator.toml (one helical stage, 17/53 teeth, m_n 25 mm, beta 9 deg, 180 rpm,
2000 N m load) made linear: exponent 1, K = 1e6 N/mm along the normal, full damping from 1 um of
penetration on (so the damping is the constant C = 50 N s/mm while the teeth touch), no backlash unless
a test sets it. With time-varying stiffness this is a linear, damped, time-periodic oscillator: its steady
state is period-1 at the mesh period 60 / (17 x 180) s. References: a long fixed-window run over whole
periods (the same equations, no period search), the static deflection by hand, conservation of energy.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_allclose

from gearcli import diagnostics as dg
from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.io.channels import named
from gearcli.simulate import run_simulation
from gearcli.simulate.results import REGIME_DOUBLE_SIDED, REGIME_NO_IMPACT, REGIME_SINGLE_SIDED

CONFIGS = Path(__file__).resolve().parents[2] / "configs"
OSCILLATOR = CONFIGS / "backlash_oscillator.toml"
LINEAR = ["stage.0.backlash_mm=0", "contact.exponent=1", "contact.stiffness=1e6",
          "contact.full_damping_penetration_mm=0.001"]
MESH_PERIOD_S = 60.0 / (17 * 180)  # 17 pinion teeth at 180 rpm


def run(path: Path, *sets: str, want_series: bool = False):
    cfg = load_design(str(path), list(sets)).design
    return run_simulation(cfg, compute_design(cfg), want_series=want_series)


RTOL = 1e-8
# What the periodic search promises: boundary states within rtol |y| + atol, the deflection's atol raised to
# rtol x pitch-line speeds / fastest natural angular frequency (gearcli.simulate.periodic.poincare_atol):
# 2 x 3.8 m/s x 1e-8 / (2 pi 113 Hz) = 1.1e-10 m, 3.3e-5 of the 3.25 um static deflection (1e-4 with margin)
PROMISE = 1e-4


@pytest.fixture(scope="module")
def periodic():
    return run(OSCILLATOR, *LINEAR, "simulation.steady=periodic", "simulation.duration_s=3", f"simulation.rtol={RTOL}",
               want_series=True)


def test_periodic_run_finds_the_mesh_period_and_converges(periodic):
    st = periodic.steady
    assert st.mode == "periodic" and st.converged and st.periodicity == "period-1"
    assert_allclose(st.period_s, MESH_PERIOD_S, rtol=1e-12)
    assert st.residual <= 1.0 and 4 <= st.periods_to_converge < st.cap_periods
    # statistics over whole periods: the window spans window_periods periods exactly
    w0, w1 = periodic.window_s
    assert_allclose((w1 - w0) / MESH_PERIOD_S, st.window_periods, rtol=1e-9)
    assert w0 >= 0.3  # past the ramps
    assert not dg.has(periodic.diagnostics, dg.NOT_PERIODIC)


def test_periodic_statistics_agree_with_a_long_window_over_whole_periods(periodic):
    # reference: a plain window run (no period search), its statistics computed here over 20 whole mesh
    # periods from t = 2 s (well past the periodic run's convergence), 400 samples per period, the closing
    # sample left out
    start, n_periods, per = 2.0, 20, 400
    duration = start + n_periods * MESH_PERIOD_S
    ref = run(OSCILLATOR, *LINEAR, f"simulation.duration_s={duration!r}", f"simulation.rtol={RTOL}",
              f"simulation.steps={round(duration / MESH_PERIOD_S * per)}", want_series=True)
    t = ref.time_s
    mask = (t >= start - 1e-9) & (t < duration - 0.5 * MESH_PERIOD_S / per)
    assert mask.sum() == n_periods * per
    ft, q = named(ref)["stage1_tangential_N"][mask], named(ref)["stage1_dte_um"][mask]
    a = periodic.stages[0]
    assert_allclose(a.tangential_N.mean, ft.mean(), rtol=PROMISE)
    assert_allclose(a.dte_um.mean, q.mean(), rtol=PROMISE)
    # the fluctuation (~5 % of the mean) to the same absolute error
    assert_allclose(a.tangential_N.std, ft.std(), atol=PROMISE * ft.mean())
    assert_allclose(a.dte_um.rms, q.std(), atol=PROMISE * q.mean())
    # extremes: the stiffness has kinks (the contact-line length is piecewise linear), so a sampled extreme can
    # miss the true one by half the largest change between neighbouring samples, on either grid
    pw = named(periodic)["stage1_tangential_N"][(periodic.time_s >= periodic.window_s[0] - 1e-9)]
    grids = 0.5 * (np.max(np.abs(np.diff(ft))) + np.max(np.abs(np.diff(pw))))
    assert grids < 0.02 * (ft.max() - ft.min())  # the bound stays tight: under 2 % of the swing
    assert_allclose([a.tangential_N.min, a.tangential_N.max], [ft.min(), ft.max()], atol=grids + PROMISE * ft.mean())
    assert a.contact_loss_fraction == 0.0 and a.regime == REGIME_NO_IMPACT


def test_energy_balance_closes_over_the_run_up_and_the_periods(periodic):
    # the run is integrated in pieces (run-up, search, statistics periods); the work quadratures continue
    # through them, so input work = load work + damping + kinetic and elastic changes still holds
    assert periodic.energy.residual_relative < 1e-5


def _static_deflection_um(backlash_mm: float) -> float:
    """delta = F_bt / (cos^2(beta_b) K) + j / (2 cos(beta_b)) along the transverse line of action.

    F_t = T / (d_2 / 2), d_2 = z_2 m_n / cos(beta); F_bt = F_t / cos(alpha_t), tan(alpha_t) = tan(alpha_n) / cos(beta);
    sin(beta_b) = sin(beta) cos(alpha_n) (ISO 21771); the normal approach is cos(beta_b) delta and carries
    F_n = F_bt / cos(beta_b) = K p, p the approach beyond the half gap j/2."""
    beta, alpha_n = math.radians(9), math.radians(20)
    d2 = 53 * 25e-3 / math.cos(beta)
    ft = 2000.0 / (d2 / 2)
    alpha_t = math.atan(math.tan(alpha_n) / math.cos(beta))
    cb = math.cos(math.asin(math.sin(beta) * math.cos(alpha_n)))
    k = 1e6 * 1e3  # 1e6 N/mm -> N/m
    return (ft / math.cos(alpha_t) / (cb * cb * k) + backlash_mm * 1e-3 / (2 * cb)) * 1e6


@pytest.mark.parametrize("backlash_mm", [0.0, 0.5])
def test_mean_dte_is_the_static_deflection_plus_half_the_backlash(backlash_mm):
    # constant stiffness: nothing excites the mesh, the steady state is the loaded equilibrium
    sim = run(OSCILLATOR, *LINEAR, "contact.time_varying=false", f"stage.0.backlash_mm={backlash_mm}",
              "simulation.steady=periodic", "simulation.duration_s=4", f"simulation.rtol={RTOL}")
    s = sim.stages[0]
    assert sim.steady.converged and sim.steady.periodicity == "period-1"
    expected = _static_deflection_um(backlash_mm)
    assert_allclose(s.dte_um.mean, expected, rtol=PROMISE)
    assert s.dte_um.rms < PROMISE * expected
    assert s.regime == REGIME_NO_IMPACT and s.contact_loss_fraction == 0.0


def test_dte_channel_is_the_deflection_in_um(periodic):
    # until transmission error is modelled q = delta: the DTE exceeds the penetration along the line of
    # action by nothing when there is no gap (penetration is cos(beta_b) delta, in mm)
    cb = math.cos(math.asin(math.sin(math.radians(9)) * math.cos(math.radians(20))))
    q = named(periodic)["stage1_dte_um"]
    pen = named(periodic)["stage1_penetration_mm"]
    assert_allclose(q * 1e-6 * cb, pen * 1e-3, rtol=1e-12, atol=1e-15)


def test_short_search_is_reported_not_periodic_with_a_warning():
    # the backlash oscillator as given settles slowly (brute force: more than its 35 mesh periods before the
    # 1 s end); shooting needs fewer, but not the 5 periods a 0.4 s run leaves after its 0.3 s ramps
    sim = run(OSCILLATOR, "simulation.steady=periodic", "simulation.duration_s=0.4")
    st = sim.steady
    assert not st.converged and st.periodicity == "none" and st.method == "brute force"
    assert st.cap_periods == math.floor((0.4 - 0.3) / MESH_PERIOD_S)
    assert st.periods_to_converge <= st.cap_periods + st.window_periods  # the statistics periods integrated again
    assert dg.has(sim.diagnostics, dg.NOT_PERIODIC) and dg.has(sim.diagnostics, dg.SHOOTING_FALLBACK)
    assert any("duration_s" in w for w in sim.warnings)


def test_contact_loss_and_regimes_on_the_catalogue_scenes():
    # a loaded mesh never lifts off; the unloaded, undamped rattle hits both flanks (its file's comment:
    # "every mesh crosses the gap and hits BOTH flanks in the steady window")
    rattle = run(CONFIGS / "extreme" / "rattle_zero_load.toml")
    for s in rattle.stages:
        assert s.contact_loss_fraction > 0.0 and s.back_flank_fraction > 0.0
        assert s.regime == REGIME_DOUBLE_SIDED
        assert s.contact_loss_fraction + s.back_flank_fraction <= 1.0 + 1e-12
    seed = run(CONFIGS / "concrete_mixer.toml")
    assert all(s.contact_loss_fraction == 0.0 and s.regime == REGIME_NO_IMPACT for s in seed.stages)
    # stage 1 of the time-varying mixer lifts off its drive flank for ~1 % of the window (its file's comment)
    tv = run(CONFIGS / "mixer_time_varying_backlash.toml")
    assert tv.stages[0].regime == REGIME_SINGLE_SIDED
    assert 0.0 < tv.stages[0].contact_loss_fraction < 0.05 and tv.stages[0].back_flank_fraction == 0.0


# ------------------------------------------------------------------ subharmonic: parametric resonance
def _floquet_multipliers(rpm: float) -> np.ndarray:
    """Multipliers over one mesh period of the in-contact mesh of configs/periodic_linear_mesh.toml, from
    the Hill equation m_e x'' + c x' + k(phi(t)) x = 0 integrated here with scipy (no gearcli dynamics):
    m_e = J_2 / r_b2^2 (the pinion's speed is prescribed: infinitely heavy), k = K cos^2(beta_b) L/L_mean,
    c = C cos^2(beta_b) (full damping), phi = z_1 n t / 60 mesh cycles."""
    from scipy.integrate import solve_ivp

    from gearcli.model.contact_lines import contact_length_factor

    cfg = load_design(str(CONFIGS / "periodic_linear_mesh.toml"), []).design
    design = compute_design(cfg)
    st = design.stages[0]
    m_e = design.shafts[1].inertia_kg_m2 / (st.gear.base_diameter_mm / 2e3) ** 2
    cb2 = math.cos(math.radians(st.base_helix_angle_deg)) ** 2
    k, c = 1e9 * cb2, 50e3 * cb2
    mesh_hz = 17 * rpm / 60

    def rhs(t, y):
        g = contact_length_factor(mesh_hz * t, st.contact_ratio_transverse, st.overlap_ratio)
        return [y[1], -(c * y[1] + k * g * y[0]) / m_e]

    cols = [solve_ivp(rhs, (0.0, 1 / mesh_hz), y0, rtol=1e-11, atol=1e-14, max_step=1e-2 / mesh_hz).y[:, -1]
            for y0 in ([1.0, 0.0], [0.0, 1.0])]
    return np.linalg.eigvals(np.column_stack(cols))


def test_principal_parametric_resonance_gives_the_period_2_response():
    # Hill/Floquet: at 800 rpm (mesh 227 Hz, about twice the 113 Hz mode) the in-contact mesh is unstable
    # with a real multiplier below -1 (band ~770-830 rpm): the vibration grows at half the mesh frequency
    # until the teeth separate, and the backlash bounds it: a period-2 response. At 180 rpm every multiplier
    # lies inside the unit circle (the period-1 scene above). Mid-band, not at its edge: near the edge (815 rpm)
    # the period-2 orbit has a second multiplier near +1, Newton's M - I is near-singular, and whether the
    # shooting converges there turns on the BLAS kernel's rounding (measured: 50 periods with one, a failed
    # shooting with the other).
    mu = _floquet_multipliers(800.0)
    assert np.min(mu.real) < -1.0 and np.all(np.abs(mu.imag) < 1e-9)
    assert np.all(np.abs(_floquet_multipliers(180.0)) < 1.0)
    sim = run(CONFIGS / "periodic_linear_mesh.toml", "stage.0.backlash_mm=0.5", "input.speed_rpm=800",
              "simulation.duration_s=4", want_series=True)
    st = sim.steady
    assert st.converged and st.periodicity == "period-2" and st.window_periods == 2
    assert dg.has(sim.diagnostics, dg.SUBHARMONIC)
    # the response itself carries half the mesh frequency: its coefficient over the two periods is large
    from gearcli.report.spectrum import order_amplitude

    t = sim.time_s
    w = (t >= sim.window_s[0] - 1e-12) & (t < sim.window_s[1] - 1e-9)
    half = order_amplitude(t[w], named(sim)["stage1_dte_um"][w], 17 * 800 / 120, whole_periods=True)
    assert half > 0.1 * sim.stages[0].dte_um.rms
    # the teeth separate each cycle but never reach the back flank
    assert sim.stages[0].regime == REGIME_SINGLE_SIDED
