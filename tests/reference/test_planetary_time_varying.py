"""Time-varying contact-line stiffness on planet meshes, phased from the geometry.

Scene (as tests/reference/test_planetary_dynamics.py): three identical, equally spaced planets, m_n 4,
x = 0, the sun speed-driven at 300 rpm, the ring held, the carrier loaded with 400 N m; linear meshes with
viscous damping; helix 12 deg (overlap ratio 0.66: the contact-line length varies continuously, so the
integration meets no stiffness steps); ``mesh.time_varying`` on every planet mesh.

Hand model (cyclic symmetry, Parker & Lin, J. Mech. Des. 126, 2004): planet j's meshes run z_s psi_j / 2 pi
(sun) and -z_r psi_j / 2 pi (ring) mesh cycles from planet 1's, the same shift for both since (z_s + z_r)/N
is an integer. Turning the planet numbering by one is then a time shift of z_s/N mesh periods, so in the
periodic steady state F_{j+1}(t) = F_j(t + T_m z_s / N) and the planets' summed sun-mesh force has the
line h of the mesh frequency only where h z_s / N is an integer: with z_s = 24 (in phase) every line of the
sum is N times one planet's; with z_s = 25 (sequential) lines 1 and 2 cancel and line 3 is N times one
planet's. Each planet's mean force equals T_sun / (N r_w) (identical planets share equally).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from gearcli.config.schema import DesignFile
from gearcli.design import compute_design
from gearcli.io.channels import named
from gearcli.model.planet_phasing import sun_ring_contact_phase_cycles
from gearcli.simulate import run_simulation

M_N, N, T_LOAD, SUN_HZ, HELIX = 4.0, 3, 400.0, 5.0, 12.0


def _run(z_s: int, z_p: int, z_r: int, engine: str = "auto", duration_s: float = 0.4, method: str = "auto"):
    doc = {"stage": [{"type": "planetary", "normal_module_mm": M_N, "helix_angle_deg": HELIX, "sun": {"teeth": z_s, "face_width_mm": 40.0, "hand": "left"},
                      "planet": {"teeth": z_p, "face_width_mm": 40.0, "count": N, "hand": "right"},
                      "ring": {"teeth": z_r, "face_width_mm": 40.0}, "carrier": {"inertia_kg_m2": 0.8},
                      "fixed": "ring", "input": "sun", "mesh": {"time_varying": True}}],
           "contact": {"stiffness": "iso6336", "exponent": 1.0, "damping_ratio": 0.2},
           "input": {"speed_rpm": 60 * SUN_HZ, "ramp_s": 0.05}, "load": {"torque_Nm": T_LOAD, "ramp_s": 0.05},
           "simulation": {"duration_s": duration_s, "steps": int(10000 * duration_s), "window_start_s": 0.2,
                          "rtol": 1e-9, "engine": engine, "method": method}}
    cfg = DesignFile.model_validate(doc)
    return run_simulation(cfg, compute_design(cfg))


def _lines(sim, z_s: int, z_r: int) -> tuple[list[float], dict[int, tuple[float, float]]]:
    """Each planet's mean sun-mesh F_t, and per harmonic h of the mesh frequency (|line of planet 1|, |line of
    the sum over planets|) over the last 20 mesh periods."""
    f_mesh = z_s * (SUN_HZ - SUN_HZ / (1 + z_r / z_s))
    t = sim.time_s
    w = t >= t[-1] - 20 / f_mesh
    F = [named(sim)[f"stage1_planet{j + 1}_sun_tangential_N"][w] for j in range(N)]
    total = sum(F)
    out = {}
    for h in (1, 2, 3):
        e = np.exp(-2j * math.pi * h * f_mesh * t[w])
        out[h] = (abs(np.mean((F[0] - F[0].mean()) * e)), abs(np.mean((total - total.mean()) * e)))
    return [abs(f.mean()) for f in F], out


@pytest.fixture(scope="module")
def in_phase():
    return _run(24, 30, 84)


@pytest.fixture(scope="module")
def sequential():
    return _run(25, 29, 83)


@pytest.mark.parametrize(("name", "z_s", "z_r"), [("in_phase", 24, 84), ("sequential", 25, 83)])
def test_identical_planets_share_the_mean_load(request, name, z_s, z_r):
    sim = request.getfixturevalue(name)
    means, _ = _lines(sim, z_s, z_r)
    t_sun = T_LOAD / (1 + z_r / z_s)
    m_t = M_N / math.cos(math.radians(HELIX))
    assert_allclose(means, t_sun / (N * 0.5e-3 * z_s * m_t), rtol=1e-3)  # x = 0: r_w = z_s m_t / 2


def test_in_phase_planets_add_every_line(in_phase):
    _, lines = _lines(in_phase, 24, 84)
    for one, total in lines.values():
        assert one > 0.01  # N: the varying contact-line length excites every line
        assert_allclose(total / one, N, rtol=1e-6)


def test_sequential_phasing_cancels_the_summed_sun_force_at_the_mesh_frequency(sequential):
    _, lines = _lines(sequential, 25, 83)
    for h in (1, 2):  # h z_s / N not an integer: cancelled
        one, total = lines[h]
        assert one > 1.0  # N: each planet carries a strong line
        assert total < 1e-3 * one
    assert lines[3][1] > 100 * max(lines[1][1], lines[2][1])  # 3 z_s / N integer: the planets add


def test_compiled_engine_matches_python_with_planet_contact_lines():
    pytest.importorskip("numba")
    # the method auto takes here, pinned: an auto run may change course once it overruns its prediction (3.7x on
    # Python here), and where that happens depends on the machine's load, not on the engines compared
    py = _run(25, 29, 83, engine="python", duration_s=0.25, method="DOP853")
    cc = _run(25, 29, 83, engine="compiled", duration_s=0.25, method="DOP853")
    assert cc.solver.engine == "compiled" and cc.solver.method == py.solver.method
    for j in range(N):
        a = named(py)[f"stage1_planet{j + 1}_sun_tangential_N"]
        b = named(cc)[f"stage1_planet{j + 1}_sun_tangential_N"]
        assert_allclose(b, a, rtol=0, atol=1e-6 * np.abs(a).max())


def _phase(z_p: int, x_p: float = 0.0, sun_drives: bool = True) -> float:
    alpha = math.radians(20.0)
    r = {"s": 48.0, "p": 60.0, "r": 168.0}  # m = 4: z 24 / 30 / 84, standard centre distances
    return sun_ring_contact_phase_cycles(
        planet_teeth=z_p, planet_profile_shift=x_p, normal_pressure_angle_rad=alpha,
        transverse_pressure_angle_rad=alpha, alpha_w_sun_rad=alpha, alpha_w_ring_rad=alpha,
        r_b_sun=r["s"] * math.cos(alpha), r_b_planet=r["p"] * math.cos(alpha), r_b_ring=r["r"] * math.cos(alpha),
        r_a_sun=r["s"] + 4.0, r_a_planet=r["p"] + 4.0, r_a_ring=r["r"] - 4.0,
        base_pitch=math.pi * 4.0 * math.cos(alpha), sun_drives=sun_drives)


def test_sun_ring_phase_parity_of_the_planet():
    """Parker & Lin's parity rule at standard geometry (x = 0, working angles = 20 deg): between the sun-side and
    the ring-side pitch-point contacts an even planet turns half a mesh cycle more than an odd one (a tooth
    opposite a tooth against a tooth opposite a space); the approach parts are the same for both."""
    assert_allclose(math.remainder(_phase(30) - _phase(29) - 0.5, 1.0), 0.0, atol=1e-12)
    # a profile shift x moves the planet's flanks by 2 x tan(alpha_n) / pi cycles apart
    assert_allclose(math.remainder(_phase(30, 0.1) - _phase(30) - 0.2 * math.tan(math.radians(20)) / math.pi, 1.0),
                    0.0, atol=1e-12)


def _involute(a: float) -> float:
    return math.tan(a) - a


def _phase_by_construction(st, sun_drives: bool) -> float:
    """x_ring - x_sun (mod 1) of planet 1 from the involute flanks themselves, in the carrier's frame: the planet
    at its centre turned by phi = 0.3 rad; a flank of tooth k stands at the polar angle phi + 2 pi k / z_p +- psi(r),
    psi(r) = psi_b - inv(alpha(r)). The '+' flanks (towards the sun at polar angle pi) unwind clockwise from
    beta_k = phi + 2 pi k/z_p + psi_b: each meets the sun's line of action (tangent to the planet's base circle at
    tau_s, the line through the sun-side pitch point) at r_b (beta_k - tau_s) from the tangent point; the '-'
    flanks meet the ring's line (tangent at tau_r) at r_b (tau_r - beta'_k), beta'_k = phi + 2 pi k/z_p - psi_b.
    Each contact's phase is its distance from the start of its path (the driven member's tip) in base pitches."""
    p = st.planetary
    z_p = p.planet.teeth
    a_n, a_t = math.radians(st.normal_pressure_angle_deg), math.radians(st.transverse_pressure_angle_deg)
    a_ws, a_wr = math.radians(st.working_pressure_angle_deg), math.radians(p.planet_ring.working_pressure_angle_deg)
    rb_s, rb_p, rb_r = (0.5 * g.base_diameter_mm for g in (p.sun, p.planet, p.ring))
    ra_s, ra_p, ra_r = (0.5 * g.tip_diameter_mm for g in (p.sun, p.planet, p.ring))
    p_b = 2 * math.pi * rb_p / z_p
    psi_b = (0.5 * math.pi + 2 * p.planet.profile_shift * math.tan(a_n)) / z_p + _involute(a_t)
    # the '+' flank through the sun pitch point (polar angle pi): beta - inv(a_ws) = pi, tangent at beta - tan(a_ws)
    tau_s = math.pi + _involute(a_ws) - math.tan(a_ws)
    # the '-' flank through the ring pitch point (polar angle 0): beta' + inv(a_wr) = 0, tangent at beta' + tan(a_wr)
    tau_r = -_involute(a_wr) + math.tan(a_wr)
    phi = 0.3
    s_sun = rb_p * ((phi + psi_b - tau_s) % (2 * math.pi / z_p))  # one contact's distance from T_s (mod p_b)
    s_ring = rb_p * ((tau_r - phi + psi_b) % (2 * math.pi / z_p))
    planet_tip = math.sqrt(ra_p**2 - rb_p**2)  # from the planet's tangent point, on both lines
    sun_tip = (rb_s + rb_p) * math.tan(a_ws) - math.sqrt(ra_s**2 - rb_s**2)
    ring_tip = math.sqrt(ra_r**2 - rb_r**2) - (rb_r - rb_p) * math.tan(a_wr)
    if sun_drives:  # the planet turns clockwise (phi falling): sun contacts run towards T_s, ring contacts away
        x_sun, x_ring = (planet_tip - s_sun) / p_b, (s_ring - ring_tip) / p_b
    else:
        x_sun, x_ring = (s_sun - sun_tip) / p_b, (planet_tip - s_ring) / p_b
    return (x_ring - x_sun) % 1.0


def test_sun_ring_phase_against_the_involute_construction():
    """The closed form (gearcli.model.planet_phasing) against the flanks built point by point, on the NREL
    stage (x_p = 0.8021: working pressure angles 24.9 deg on the sun mesh, 20.4 deg on the ring mesh), both
    senses of power flow."""
    from gearcli.config.load import load_design
    from gearcli.model.planet_phasing import stage_contact_phase_cycles

    cfg = load_design("configs/planetary_stage.toml", []).design
    st = compute_design(cfg).stages[0]
    p = st.planetary
    assert abs(st.working_pressure_angle_deg - p.planet_ring.working_pressure_angle_deg) > 1.0
    for drives in (True, False):
        value = stage_contact_phase_cycles(st, drives)
        assert_allclose(math.remainder(value - _phase_by_construction(st, drives), 1.0), 0.0, atol=1e-9)
