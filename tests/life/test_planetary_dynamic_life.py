"""``gearcli life`` (the dynamic route) on a planetary stage against kinematics, the static route and the hand
model of load sharing (docs/life.md, "Planetary stages: the dynamic route").

Scene: sun 24 (driven), three planets 30, ring 84 (held), m_n 4, spur, x = 0, linear meshes (exponent 1,
ISO 6336-1 stiffness) with 20 % damping, ramps of 0.05 s, no excitation: the tests/reference/test_planetary_dynamics.py
scene with materials and a rating, over two duty points.

- Kinematics (Willis, ring held): n_c = n_s / (1 + z_r/z_s); a sun tooth meets the N planets once each per turn
  relative to the carrier (n_s − n_c), a planet tooth the sun once per planet turn n_p = (n_s − n_c) z_s / z_p,
  a ring tooth the N planets once each per relative turn n_c. Load cycles over a point: hours × 60 × that
  speed × those contacts, the static route's. Engagements counted in the window of T_w seconds: z n T_w / 60 per
  mesh, less the partial first and last cycle.
- Identical planets without excitation: every engagement meets the static force, so the dynamic damage equals
  the static route's with K_v = 1 and K_gamma = 1 (the simulation shares the load itself); with a transmission
  error it is larger (the issue's rule: never less).
- A position error e on planet 1 (along its sun mesh's line of action): sun and ring mesh act in series,
  k_eq = k_sp k_rp / (k_sp + k_rp), and F_1 = F_mean + k_eq e (1 − 1/N) cos(alpha_t) (tangential); the ring mesh of
  a planet carries its sun mesh's force (moment balance). Planet 1's damage follows from its rating stress at
  F_1 on the ISO 6336-2/-3 curves written out below: ISO 6336-2/-3's sigma_H = sigma_H0 √(K_v K_Hβ K_Hα) with
  sigma_H0 ∝ √F, sigma_F = sigma_F0 K_v K_Fβ K_Fα with sigma_F0 ∝ F, the load factors at F_1's own line load (ISO
  6336-6: each load level with its own factors; the mesh's design at F_1 / F_mean times the point's torque).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from gearcli import api

Z_S, Z_P, Z_R, N, M_N = 24, 30, 84, 3, 4.0
POINTS = (("full", 2000.0, 3000.0, 300.0), ("part", 6000.0, 1500.0, 200.0))  # name, hours, torque (carrier), rpm
ZNT = ((1e5, 1.6), (5e7, 1.0), (1e10, 0.85))  # ISO 6336-2:2006 Table 2, case-carburized (normal quality)
YNT = ((1e3, 2.5), (3e6, 1.0), (1e10, 0.85))  # ISO 6336-3:2006 Table 3, case-carburized

SCENE = f"""
[materials.steel]
density_kg_m3 = 7830
youngs_modulus_MPa = 206000
poisson_ratio = 0.3
treatment = "case_carburized"
contact_fatigue_limit_MPa = 1500
bending_fatigue_limit_MPa = 430

[[stage]]
type = "planetary"
normal_module_mm = {M_N}
accuracy_grade = 6
sun = {{ teeth = {Z_S}, face_width_mm = 40, flank_roughness_Rz_um = 4, root_roughness_Rz_um = 20 }}
planet = {{ teeth = {Z_P}, face_width_mm = 40, count = {N}, flank_roughness_Rz_um = 4, root_roughness_Rz_um = 20 }}
ring = {{ teeth = {Z_R}, face_width_mm = 40, flank_roughness_Rz_um = 4, root_roughness_Rz_um = 20 }}
carrier = {{ inertia_kg_m2 = 0.8 }}
fixed = "ring"
input = "sun"

[contact]
stiffness = "iso6336"
exponent = 1.0
damping_ratio = 0.2

[lubricant]
viscosity_40C_mm2_s = 220
viscosity_100C_mm2_s = 19
temperature_C = 70

[input]
speed_rpm = 300
ramp_s = 0.05

[load]
torque_Nm = 3000
ramp_s = 0.05

[rating]
required_life_h = 20000
load_sharing_factor = 1.15

[simulation]
duration_s = 0.3
rtol = 1e-9
""" + "".join(f"""
[[duty]]
name = "{name}"
hours = {hours}
torque_Nm = {torque}
speed_rpm = {rpm}
""" for name, hours, torque, rpm in POINTS)

MEMBERS = ("pinion", "gear", "ring", "planet_ring_side")


def _speeds(rpm: float) -> dict[str, float]:
    """Each member's speed loading its teeth (rpm relative to the carrier) and its contacts per turn."""
    n_c = rpm / (1 + Z_R / Z_S)
    return {"pinion": (rpm - n_c) * N, "gear": (rpm - n_c) * Z_S / Z_P, "ring": n_c * N,
            "planet_ring_side": (rpm - n_c) * Z_S / Z_P}


def _life(tmp_path, *sets: str, static: bool = False):
    path = tmp_path / "planetary_life.toml"
    path.write_text(SCENE)
    return api.life(api.prepare_life(str(path), sets), static=static)


def _mode(result, member: str, mode: str):
    st = result.stages[0]
    return st.planet_root if member == "planet_root" else getattr(getattr(st, member), mode)


@pytest.fixture(scope="module")
def equal(tmp_path_factory):
    """Identical planets, K_gamma = 1: the simulated planets share equally and nothing is added."""
    return _life(tmp_path_factory.mktemp("equal"), "rating.load_sharing_factor=1.0")


@pytest.fixture(scope="module")
def static_kv1_kgamma(tmp_path_factory):
    """The static route with K_v = 1 and the file's K_gamma 1.15 (the issue's reference spectrum)."""
    return _life(tmp_path_factory.mktemp("static_kg"), "rating.dynamic_factor=1.0", static=True)


@pytest.fixture(scope="module")
def static_kv1(tmp_path_factory):
    """The static route with K_v = 1 and K_gamma = 1 (identical planets share equally)."""
    return _life(tmp_path_factory.mktemp("static"), "rating.dynamic_factor=1.0", "rating.load_sharing_factor=1.0",
                 static=True)


def _cycles_to_failure(ratio: float, nodes) -> float:
    """Invert factor = y_a (N_a / N)^q on the branch the stress ratio falls on."""
    (n0, y0), (n1, y1), (n2, y2) = nodes
    if ratio >= y1:
        return n0 * (y0 / ratio) ** (math.log(n1 / n0) / math.log(y0 / y1))
    return n1 * (y1 / ratio) ** (math.log(n2 / n1) / math.log(y1 / y2))


def test_load_cycles_per_member_are_the_kinematic_ones(equal):
    assert equal.route == "dynamic"
    for member in MEMBERS:
        for mode in ("pitting", "bending"):
            ml = _mode(equal, member, mode)
            for name, hours, _, rpm in POINTS:
                cycles = sum(b.cycles for b in ml.bins if b.point == name)
                assert_allclose(cycles, hours * 60 * _speeds(rpm)[member], rtol=1e-12)


def test_engagements_counted_in_the_window_follow_the_relative_speeds(equal):
    """The sun's count is the N meshes' together: N z_s (n_s − n_c) T_w / 60, to a mesh cycle per mesh."""
    for p, (_, _, _, rpm) in zip(equal.points, POINTS, strict=True):
        t0, t1 = p.solver["window_s"]
        per_mesh = Z_S * (_speeds(rpm)["pinion"] / N) * (t1 - t0) / 60.0
        assert per_mesh >= 40 * (1 - 1e-9)  # the route's minimum window of the mesh frequency
        assert abs(p.mesh_cycles[0] - N * per_mesh) <= 2 * N


def test_each_mesh_counts_its_own_engagements(tmp_path):
    """The ring's spectrum counts the N ring meshes on the ring's angle relative to the carrier (z_r teeth), a
    planet's on its own meshes: z_p cycles per planet turn, the same engagements as z_s per sun turn."""
    from gearcli.life import spectra
    from gearcli.simulate import run_simulation

    path = tmp_path / "p.toml"
    path.write_text(SCENE)
    loaded = api.load(str(path), ("simulation.duration_s=0.6", "simulation.steps=8000"))
    cfg = loaded.design
    design = api.design(loaded)
    res = run_simulation(cfg, design, want_series=True)
    ld = spectra.dynamic_loads(res, design)[0]
    t_w = res.window_s[1] - res.window_s[0]
    speeds = _speeds(300.0)
    assert ld.planetary is not None and len(ld.planetary.planet_sun) == N
    assert abs(ld.planetary.ring.mesh_cycles - Z_R * speeds["ring"] * t_w / 60) <= 2 * N
    assert abs(ld.mesh_cycles - Z_S * speeds["pinion"] * t_w / 60) <= 2 * N
    for own in (*ld.planetary.planet_sun, *ld.planetary.planet_ring):
        assert abs(own.mesh_cycles - Z_P * speeds["gear"] * t_w / 60) <= 2


def test_identical_planets_without_excitation_match_the_static_spectrum_with_kv_1(equal, static_kv1):
    """Every engagement meets the static force: the same damage (and never less)."""
    for member in (*MEMBERS, "planet_root"):
        for mode in ("pitting", "bending"):
            if member == "planet_root" and mode == "pitting":
                continue
            dyn, sta = _mode(equal, member, mode), _mode(static_kv1, member, mode)
            assert dyn.damage >= sta.damage * (1 - 1e-9), (member, mode)
            assert_allclose(dyn.damage, sta.damage, rtol=1e-6)
            assert_allclose(max(b.force_N for b in dyn.bins), max(b.force_N for b in sta.bins), rtol=1e-8)
    assert equal.points[0].K_v[0] == pytest.approx(1.0, abs=1e-8)
    assert not [w for w in equal.warnings if "load_sharing_factor" in w]


def test_identical_planets_keep_the_files_load_sharing_factor(tmp_path, static_kv1_kgamma):
    """Identical simulated planets share equally, so the file's K_gamma (an allowance for the unequal sharing the
    model does not see) stays on the planet meshes' stresses: the damage equals the static spectrum's with K_v = 1
    and the same K_gamma, never less; said once per run."""
    kept = _life(tmp_path)
    for member in (*MEMBERS, "planet_root"):
        for mode in ("pitting", "bending"):
            if member == "planet_root" and mode == "pitting":
                continue
            dyn, sta = _mode(kept, member, mode), _mode(static_kv1_kgamma, member, mode)
            assert dyn.damage >= sta.damage * (1 - 1e-9), (member, mode)
            assert_allclose(dyn.damage, sta.damage, rtol=1e-6)
    sharing = [w for w in kept.warnings if "load_sharing_factor = 1.15 stays" in w]
    assert len(sharing) == 1  # said once per run, not per point


def test_an_excited_stage_never_reports_less_damage_than_the_static_spectrum(tmp_path, static_kv1_kgamma):
    dyn = _life(tmp_path, "stage[0].mesh.transmission_error_um=[5.0]")
    assert dyn.points[0].K_v[0] > 1.002  # the excitation rings the meshes
    for member in (*MEMBERS, "planet_root"):
        for mode in ("pitting", "bending"):
            if member == "planet_root" and mode == "pitting":
                continue
            assert _mode(dyn, member, mode).damage > _mode(static_kv1_kgamma, member, mode).damage, (member, mode)


@pytest.mark.parametrize("error_um", [5.0])
def test_a_planet_position_error_loads_that_planet_as_the_hand_model_says(tmp_path, equal, error_um):
    res = _life(tmp_path, f"stage[0].planet.position_error_um=[{error_um}, 0.0, 0.0]")
    # the position errors share the load in the simulation: the file's K_gamma 1.15 is replaced, said once
    assert len([w for w in res.warnings if "load_sharing_factor = 1.15 is not applied" in w]) == 1
    path = tmp_path / "d.toml"
    path.write_text(SCENE)
    designs = {}
    for name, _, torque, rpm in POINTS:
        loaded = api.load(str(path), (f"input.speed_rpm={rpm}", f"load.torque_Nm={torque}",
                                      "load.application_factor=1.0"))
        designs[name] = api.design(loaded).stages[0]

    def rated(name: str, ratio: float):
        """The point's stage as life rates it (K_A = K_v = 1, K_gamma = 1: the run shares the load), at ``ratio``
        times its torque: ISO's load factors of that line load."""
        torque, rpm = next((t, r) for n, _, t, r in POINTS if n == name)
        loaded = api.load(str(path), (f"input.speed_rpm={rpm}", f"load.torque_Nm={torque * ratio!r}",
                                      "load.application_factor=1.0", "rating.dynamic_factor=1.0",
                                      "rating.load_sharing_factor=1.0"))
        st = api.design(loaded).stages[0]
        return st.rating if member in ("gear", "pinion") else st.planetary.planet_ring.rating

    def factors(r, mode: str) -> float:
        return r.K_Hbeta * r.K_Halpha if mode == "pitting" else r.K_Fbeta * r.K_Falpha

    def extra(name: str) -> float:
        """Planet 1's extra tangential force (N) at a point: the meshes' ISO 6336-1 stiffness of the point's load."""
        ds = designs[name]
        k_sp = ds.iso6336_mesh_stiffness_N_mm_um * ds.face_width_mm * 1e6  # N/m along the line of action
        k_rp = ds.planetary.planet_ring.iso6336_mesh_stiffness_N_mm_um * ds.planetary.planet_ring.face_width_mm * 1e6
        k_eq = k_sp * k_rp / (k_sp + k_rp)
        return k_eq * error_um * 1e-6 * (1 - 1 / N) * math.cos(math.radians(20.0))
    for member, mode, nodes in (("gear", "pitting", ZNT), ("gear", "bending", YNT),
                                ("planet_ring_side", "pitting", ZNT), ("planet_ring_side", "bending", YNT)):
        dyn, base = _mode(res, member, mode), _mode(equal, member, mode)
        assert dyn.planet == 1  # the most loaded planet is reported
        hand = 0.0
        for name, hours, _, rpm in POINTS:
            b = next(x for x in base.bins if x.point == name)  # identical planets: the rating's stress at F_mean
            f_1 = b.force_N + extra(name)
            ratio = f_1 / b.force_N
            held = ratio * factors(rated(name, ratio), mode) / factors(rated(name, 1.0), mode)
            stress = b.stress_MPa * (math.sqrt(held) if mode == "pitting" else held)
            assert_allclose(max(x.force_N for x in dyn.bins if x.point == name), f_1, rtol=1e-6)
            hand += hours * 60 * _speeds(rpm)[member] / _cycles_to_failure(stress / b.endurance_MPa, nodes)
        assert dyn.damage > 1.5 * base.damage  # direction, and a sizeable effect (+29 % and +50 % force)
        assert_allclose(dyn.damage, hand, rtol=1e-4)  # a linear, steady scene: the hand model is its statics
    assert res.stages[0].planet_root.planet == 1 and _mode(res, "ring", "pitting").planet is None
    # the sun and the ring meet every planet: the extra on planet 1 is taken from planets 2 and 3
    sun = _mode(res, "pinion", "pitting")
    forces = np.array([b.force_N for b in sun.bins if b.point == "full"])
    assert_allclose(forces.max(), designs["full"].static_force_N.tangential + extra("full"), rtol=1e-6)
    assert_allclose(forces.min(), designs["full"].static_force_N.tangential - extra("full") / 2, rtol=1e-6)
    assert sun.damage > _mode(equal, "pinion", "pitting").damage


MIXED = """
[materials.steel]
density_kg_m3 = 7830
youngs_modulus_MPa = 206000
poisson_ratio = 0.3
treatment = "case_carburized"
contact_fatigue_limit_MPa = 1500
bending_fatigue_limit_MPa = 430

[[stage]]
normal_module_mm = 3
helix_angle_deg = 12
accuracy_grade = 6
pinion = { teeth = 20, face_width_mm = 40, hand = "left", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 20 }
gear = { teeth = 60, face_width_mm = 40, hand = "right", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 20 }

[[stage]]
type = "planetary"
normal_module_mm = 4
accuracy_grade = 6
sun = { teeth = 24, face_width_mm = 40, flank_roughness_Rz_um = 4, root_roughness_Rz_um = 20 }
planet = { teeth = 30, face_width_mm = 40, count = 3, flank_roughness_Rz_um = 4, root_roughness_Rz_um = 20 }
ring = { teeth = 84, face_width_mm = 40, flank_roughness_Rz_um = 4, root_roughness_Rz_um = 20 }
carrier = { inertia_kg_m2 = 0.8 }
fixed = "FIXED"
input = "INPUT"

[contact]
stiffness = "iso6336"
exponent = 1.0
damping_ratio = 0.2

[lubricant]
viscosity_40C_mm2_s = 220
viscosity_100C_mm2_s = 19
temperature_C = 70

[input]
speed_rpm = 1500
ramp_s = 0.05

[load]
torque_Nm = 2000
ramp_s = 0.05

[rating]
required_life_h = 20000

[simulation]
duration_s = 0.3
rtol = 1e-9

[[duty]]
name = "only"
hours = 1000
torque_Nm = 2000
speed_rpm = 1500
"""


@pytest.mark.parametrize(("fixed", "driven"), [("carrier", "sun"), ("sun", "ring")])
def test_a_planetary_stage_after_a_parallel_one_counts_relative_to_its_carrier(tmp_path, fixed, driven):
    """Stage 2 planetary, driven by the parallel stage (1500 rpm × 20/60 = 500 rpm on its input member), with the
    carrier held (the ring turns at −n_s z_s/z_r: the sun's relative speed is n_s) or the sun held (the ring drives,
    n_c = n_r z_r / (z_s + z_r): the sun's relative speed is n_c). Willis by hand; the stage's counted engagements
    and load cycles follow, and its damage is not below the static spectrum's with K_v = 1."""
    path = tmp_path / "mixed.toml"
    path.write_text(MIXED.replace("FIXED", fixed).replace("INPUT", driven))
    dyn = api.life(api.prepare_life(str(path)))
    sta = api.life(api.prepare_life(str(path), ("rating.dynamic_factor=1.0",)), static=True)
    n_in = 1500.0 * 20 / 60
    if fixed == "carrier":
        sun_rel, ring_rel = n_in, n_in * Z_S / Z_R
    else:
        sun_rel = n_in * Z_R / (Z_S + Z_R)  # the carrier's speed n_c, the sun still
        ring_rel = n_in - sun_rel  # the ring turns at n_in
    p = dyn.points[0]
    t0, t1 = p.solver["window_s"]
    assert abs(p.mesh_cycles[1] - N * Z_S * sun_rel * (t1 - t0) / 60) <= 2 * N
    st = dyn.stages[1]
    assert_allclose(sum(b.cycles for b in st.pinion.pitting.bins), 1000 * 60 * sun_rel * N, rtol=1e-12)
    assert_allclose(sum(b.cycles for b in st.ring.pitting.bins), 1000 * 60 * ring_rel * N, rtol=1e-12)
    assert_allclose(sum(b.cycles for b in st.gear.bending.bins), 1000 * 60 * sun_rel * Z_S / Z_P, rtol=1e-12)
    for k in (0, 1):
        for member in ("pinion", "gear", *(("ring", "planet_ring_side") if k == 1 else ())):
            for mode in ("pitting", "bending"):
                d_dyn = getattr(getattr(dyn.stages[k], member), mode).damage
                d_sta = getattr(getattr(sta.stages[k], member), mode).damage
                assert d_dyn >= d_sta * (1 - 1e-9), (k, member, mode)
