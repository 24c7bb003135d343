"""A planetary stage in the time domain against kinematics, statics and a hand model of load sharing.

Scene: sun 24, three planets 30, ring 84 (held), m_n 4, spur, x = 0 (so the working pitch radii are the
reference ones), the sun speed-driven, the carrier carrying the load. Linear meshes (exponent 1, ISO 6336-1
stiffness c_gamma_alpha b) with viscous damping, ramps of 0.05 s, statistics over the last 0.1 s.

- Willis: omega_sun / omega_carrier = 1 + z_r / z_s (ring held), to 1e-6.
- Statics with identical planets: each planet's window-mean sun-mesh F_t = T_sun / (N r_w), T_sun = T_load /
  (1 + z_r/z_s) (lossless), to 1e-3; load-sharing factor 1.
- A position error e on planet 1 along its sun mesh: with the sun's motion prescribed and the carrier loaded,
  each planet's sun and ring meshes act in series, k_eq = k_sp k_rp / (k_sp + k_rp); planet equilibrium and the
  carrier's moment balance (sum of the planet forces fixed) give F_j = F_mean + k_eq (e_j - mean(e)), so the
  load-sharing factor is 1 + k_eq e (1 - 1/N) / F_mean (along the line of action; F_t scales every planet alike).
"""

from __future__ import annotations

import math

import pytest
from numpy.testing import assert_allclose

from gearcli.config.schema import DesignFile
from gearcli.design import compute_design
from gearcli.io.channels import named
from gearcli.simulate import run_simulation

Z_S, Z_P, Z_R, N, M_N = 24, 30, 84, 3, 4.0
T_LOAD = 400.0


def _run(errors_um=None, **sim):
    planet = {"teeth": Z_P, "face_width_mm": 40.0, "count": N}
    if errors_um is not None:
        planet["position_error_um"] = errors_um
    doc = {"stage": [{"type": "planetary", "normal_module_mm": M_N, "sun": {"teeth": Z_S, "face_width_mm": 40.0},
                      "planet": planet, "ring": {"teeth": Z_R, "face_width_mm": 40.0},
                      "carrier": {"inertia_kg_m2": 0.8}, "fixed": "ring", "input": "sun"}],
           "contact": {"stiffness": "iso6336", "exponent": 1.0, "damping_ratio": 0.2},
           "input": {"speed_rpm": 300.0, "ramp_s": 0.05}, "load": {"torque_Nm": T_LOAD, "ramp_s": 0.05},
           "simulation": {"duration_s": 0.3, "steps": 600, "window_start_s": 0.2, "rtol": 1e-9, **sim}}
    cfg = DesignFile.model_validate(doc)
    design = compute_design(cfg)
    return design, run_simulation(cfg, design, want_series=True)


@pytest.fixture(scope="module")
def equal():
    return _run()


def test_willis_ratio(equal):
    _, sim = equal
    assert_allclose(sim.ratio, 1 + Z_R / Z_S, rtol=1e-6)


def test_identical_planets_share_the_sun_torque_equally(equal):
    design, sim = equal
    st = sim.stages[0]
    assert len(st.planets) == N
    t_sun = T_LOAD / (1 + Z_R / Z_S)
    r_w = 0.5e-3 * design.stages[0].pinion.pitch_diameter_mm  # x = 0: r_w = r = z m / 2
    assert_allclose(r_w, 0.5e-3 * Z_S * M_N, rtol=1e-15)
    for p in st.planets:
        assert_allclose(abs(p.sun.tangential_N.mean), t_sun / (N * r_w), rtol=1e-3)
        assert_allclose(abs(p.ring.tangential_N.mean), t_sun / (N * r_w), rtol=1e-3)  # planet equilibrium
    assert_allclose(st.load_sharing_factor, 1.0, atol=1e-6)
    # the stage's own channels are planet 1's sun mesh
    assert_allclose(st.tangential_N.mean, st.planets[0].sun.tangential_N.mean, rtol=1e-12)
    assert "stage1_planet3_ring_tangential_N" in named(sim) and "stage1_planet2_sun_dte_um" in named(sim)


@pytest.mark.parametrize("error_um", [2.0, 5.0])
def test_a_planet_with_a_position_error_carries_more_as_the_hand_model_says(error_um):
    design, sim = _run([error_um, 0.0, 0.0])
    st, ds = sim.stages[0], design.stages[0]
    k_sp = ds.iso6336_mesh_stiffness_N_mm_um * ds.face_width_mm * 1e6  # N/(mm um) x mm -> N/m
    k_rp = ds.planetary.planet_ring.iso6336_mesh_stiffness_N_mm_um * ds.planetary.planet_ring.face_width_mm * 1e6
    k_eq = k_sp * k_rp / (k_sp + k_rp)
    t_sun = T_LOAD / (1 + Z_R / Z_S)
    f_mean_bt = t_sun / (N * 0.5e-3 * ds.pinion.base_diameter_mm)  # along the line of action
    e = error_um * 1e-6
    assert_allclose(st.load_sharing_factor, 1 + k_eq * e * (1 - 1 / N) / f_mean_bt, rtol=1e-3)
    # planets 2 and 3 each give up half of what planet 1 gains
    alpha_t = math.radians(20.0)
    extra = k_eq * e * (1 - 1 / N) * math.cos(alpha_t)
    assert_allclose(abs(st.planets[0].sun.tangential_N.mean), f_mean_bt * math.cos(alpha_t) + extra, rtol=1e-3)
    for p in st.planets[1:]:
        assert_allclose(abs(p.sun.tangential_N.mean), f_mean_bt * math.cos(alpha_t) - extra / 2, rtol=1e-3)


def test_a_planet_pushed_onto_its_back_flank_still_shares_by_the_sun_torque():
    """A 12 um error on planet 1 unloads planets 2 and 3 past zero (the hand model's F_mean - k_eq e / N < 0): with no
    backlash and linear meshes they go on along their back flanks, the same law, so F_j = F_mean + k_eq (e_j - mean e)
    still holds, signed. The mean planet is the sun torque's share F_mean, not the mean of the magnitudes."""
    error_um = 12.0
    design, sim = _run([error_um, 0.0, 0.0])
    st, ds = sim.stages[0], design.stages[0]
    k_sp = ds.iso6336_mesh_stiffness_N_mm_um * ds.face_width_mm * 1e6
    k_rp = ds.planetary.planet_ring.iso6336_mesh_stiffness_N_mm_um * ds.planetary.planet_ring.face_width_mm * 1e6
    k_eq = k_sp * k_rp / (k_sp + k_rp)
    f_mean_bt = T_LOAD / (1 + Z_R / Z_S) / (N * 0.5e-3 * ds.pinion.base_diameter_mm)
    gain = k_eq * error_um * 1e-6
    assert f_mean_bt - gain / N < -0.2 * f_mean_bt  # the scene is what the test is for: planets 2 and 3 reversed
    alpha_t = math.radians(20.0)
    signed = [p.sun.tangential_N.mean for p in st.planets]
    sense = math.copysign(1.0, signed[0])
    assert_allclose([sense * f for f in signed],
                    [(f_mean_bt + gain * (e - error_um / N) / error_um) * math.cos(alpha_t) for e in (error_um, 0, 0)],
                    rtol=1e-3)
    assert_allclose(st.load_sharing_factor, 1 + gain * (1 - 1 / N) / f_mean_bt, rtol=1e-3)


def test_the_compiled_engine_runs_the_planet_meshes_through_the_registry():
    """The three-body planet mesh is a registered compiled element: the kernel integrates the planetary and
    matches the Python engine (same method and tolerance; the two engines' step sequences differ only by
    rounding, so to the tolerance's order)."""
    pytest.importorskip("numba")
    from gearcli.model.elements import compiled_types

    assert "planet_mesh" in [et.name for et in compiled_types()]
    _, py = _run([5.0, 0.0, 0.0], engine="python", method="Radau")
    _, cc = _run([5.0, 0.0, 0.0], engine="compiled", method="Radau")
    assert cc.solver.engine == "compiled" and py.solver.engine == "python"
    assert_allclose(cc.stages[0].load_sharing_factor, py.stages[0].load_sharing_factor, rtol=1e-6)
    for a, b in zip(cc.stages[0].planets, py.stages[0].planets, strict=True):
        assert_allclose(a.sun.tangential_N.mean, b.sun.tangential_N.mean, rtol=1e-6)


def _phased_run(z_s: int, z_p: int, z_r: int):
    doc = {"stage": [{"type": "planetary", "normal_module_mm": M_N, "sun": {"teeth": z_s, "face_width_mm": 40.0},
                      "planet": {"teeth": z_p, "face_width_mm": 40.0, "count": N},
                      "ring": {"teeth": z_r, "face_width_mm": 40.0}, "carrier": {"inertia_kg_m2": 0.8},
                      "fixed": "ring", "input": "sun", "mesh": {"transmission_error_um": [2.0]}}],
           "contact": {"stiffness": "iso6336", "exponent": 1.0, "damping_ratio": 0.2},
           "input": {"speed_rpm": 300.0, "ramp_s": 0.05}, "load": {"torque_Nm": T_LOAD, "ramp_s": 0.05},
           "simulation": {"duration_s": 0.3, "steps": 3000, "window_start_s": 0.2, "rtol": 1e-9}}
    cfg = DesignFile.model_validate(doc)
    sim = run_simulation(cfg, compute_design(cfg))
    window = sim.time_s >= 0.2
    return sim, named(sim)["shaft2_speed_deg_s"][window]


def test_mesh_phasing_between_planets_follows_the_geometry():
    """Planet j (position psi_j = 2 pi j / N) meets the sun z_s psi_j / 2 pi mesh cycles after planet 1 and the
    ring -z_r psi_j / 2 pi (Parker & Lin, J. Mech. Des. 126, 2004): the first TE harmonic's phase per planet. A ring
    mesh runs besides gamma_rs cycles from its own planet's sun mesh (Parker & Lin's sun-ring phase, the contact
    lines' ``ring_contact_phase_cycles``), the same for every planet."""
    from gearcli.model.elements.mesh import I_CPH, I_TEP
    from gearcli.model.equations import TorsionalModel
    from gearcli.scene import spec_from_design

    z_s, z_p, z_r = 25, 29, 83
    doc = {"stage": [{"type": "planetary", "normal_module_mm": M_N, "sun": {"teeth": z_s, "face_width_mm": 40.0},
                      "planet": {"teeth": z_p, "face_width_mm": 40.0, "count": N},
                      "ring": {"teeth": z_r, "face_width_mm": 40.0}, "mesh": {"transmission_error_um": [2.0]}}],
           "input": {"speed_rpm": 300.0}, "load": {"torque_Nm": T_LOAD}}
    cfg = DesignFile.model_validate(doc)
    lay = TorsionalModel(spec_from_design(cfg, compute_design(cfg))).layout
    gamma_rs = lay.spec.stage_models[0].ring_contact_phase_cycles
    assert 0.0 < gamma_rs < 1.0  # these teeth put the ring's contact off the sun's
    for x in lay.connectors:
        z = z_s if x.gear == "sun" else -z_r
        expected = 2 * math.pi * z * x.planet / N  # 2 pi x (z psi_j / 2 pi), psi_j = 2 pi j / N
        expected += 2 * math.pi * gamma_rs if x.gear == "ring" else 0.0
        assert_allclose(math.remainder(x.params[I_TEP] - expected, 2 * math.pi), 0.0, atol=1e-12)
        # the error follows the mesh cycle the contact lines count: its first harmonic's phase is theirs, 2 pi x cycles
        assert_allclose(math.remainder(x.params[I_TEP] - 2 * math.pi * x.params[I_CPH], 2 * math.pi), 0.0, atol=1e-12)


def test_sequential_phasing_cancels_the_rotational_response():
    """With a first-harmonic TE on every planet mesh, the net torque the planets put on sun and carrier is
    sum_j e^(i 2 pi h z psi_j / 2 pi): N times one planet's when h z_s / N and h z_r / N are integers (in phase:
    24/3, 84/3), zero otherwise (sequentially phased: 25/3, 83/3). So the carrier's speed does not fluctuate at
    all in the linear torsional model with sequential phasing (only the planet modes respond), while in phase
    it does."""
    _, in_phase = _phased_run(24, 30, 84)
    seq, sequential = _phased_run(25, 29, 83)
    assert in_phase.std() > 0.1  # deg/s
    assert sequential.std() < 1e-6 * in_phase.std()  # cancelled to round-off (~1e-13 deg/s against ~0.5)
    assert max(p.sun.tangential_N.std for p in seq.stages[0].planets) > 1.0  # the planets themselves vibrate


@pytest.mark.parametrize(("fixed", "driven"), [("ring", "sun"), ("ring", "carrier"), ("carrier", "sun"),
                                               ("carrier", "ring"), ("sun", "ring"), ("sun", "carrier")])
def test_every_held_and_driven_member(fixed, driven):
    """Willis' ratio by hand for each arrangement (u = z_r/z_s): ring held 1 + u, carrier held u (the ring turns
    backwards), sun held (1 + u)/u; the output member's torque T_L gives the sun's by the moment balance
    (sun 1 : ring u : carrier 1 + u), and each planet's mean sun-mesh |F_t| = T_sun / (N r_s)."""
    u = Z_R / Z_S
    ratio = {("ring", "sun"): 1 + u, ("ring", "carrier"): 1 / (1 + u), ("carrier", "sun"): u,
             ("carrier", "ring"): 1 / u, ("sun", "ring"): (1 + u) / u, ("sun", "carrier"): u / (1 + u)}[(fixed, driven)]
    output = next(m for m in ("sun", "carrier", "ring") if m not in (fixed, driven))
    t_sun = T_LOAD / {"sun": 1.0, "ring": u, "carrier": 1 + u}[output]
    doc = {"stage": [{"type": "planetary", "normal_module_mm": M_N, "sun": {"teeth": Z_S, "face_width_mm": 40.0},
                      "planet": {"teeth": Z_P, "face_width_mm": 40.0, "count": N},
                      "ring": {"teeth": Z_R, "face_width_mm": 40.0}, "carrier": {"inertia_kg_m2": 0.8},
                      "fixed": fixed, "input": driven}],
           "contact": {"stiffness": "iso6336", "exponent": 1.0, "damping_ratio": 0.2},
           "input": {"speed_rpm": 300.0, "ramp_s": 0.05}, "load": {"torque_Nm": T_LOAD, "ramp_s": 0.05},
           "simulation": {"duration_s": 0.3, "steps": 600, "window_start_s": 0.2, "rtol": 1e-9}}
    cfg = DesignFile.model_validate(doc)
    design = compute_design(cfg)
    sim = run_simulation(cfg, design)
    assert_allclose(design.total_ratio, ratio, rtol=1e-12)
    assert_allclose(sim.ratio, ratio, rtol=1e-6)
    for p in sim.stages[0].planets:
        assert_allclose(abs(p.sun.tangential_N.mean), t_sun / (N * 0.5e-3 * Z_S * M_N), rtol=1e-3)
    assert_allclose(sim.stages[0].load_sharing_factor, 1.0, atol=1e-6)
    assert sim.energy.residual_relative < 1e-8
