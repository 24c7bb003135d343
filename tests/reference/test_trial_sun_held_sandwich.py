"""An engineer's planetary trains unlike the shipped ones, checked by hand (trial session tr10e).

Scene H ("sandwich, sun held"): a helical parallel stage 21/63 (m_n 3, β 12°, η 0.985) drives the RING of a spur
planetary whose SUN is held (sun 40 / planets 20 / ring 80: a sun twice the planet, z_r = z_s + 2 z_p, m_n 4, b 50,
5 planets, (40 + 80)/5 = 24, η 0.97); the carrier drives a spur parallel stage 30/24 (m_n 5, η 1) to a 500 N·m load;
input 1500 rpm. Scene R: the same train with the carrier held and the sun driven (a star: ring backwards).
Scene A: the star alone, 4 planets, for a hand-assembled eigenproblem.

Every expected number below is a hand formula written out here (Willis, the textbook basic efficiency of the
arrangement, F_t = T/(N r), the contact ratio from the tip circles, the mesh frequency in the carrier's frame,
the load cycles per relative revolution); none is copied from the code's output.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import scipy.linalg
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

ZS, ZP, ZR, MN, B = 40, 20, 80, 4.0, 50.0
N_IN, T_OUT = 1500.0, 500.0
ETA1, ETA_P = 0.985, 0.97
ALPHA = math.radians(20.0)

RATED = """
[rating]
required_life_h = 1000
load_sharing_factor = 1.2

[lubricant]
viscosity_40C_mm2_s = 220
viscosity_100C_mm2_s = 19
temperature_C = 75

[materials.st]
density_kg_m3 = 7830
youngs_modulus_MPa = 206000
poisson_ratio = 0.3
treatment = "case_carburized"
contact_fatigue_limit_MPa = 1500
bending_fatigue_limit_MPa = 430

[[duty]]
name = "full"
hours = 1000
torque_Nm = 500
speed_rpm = 1500
"""


def scene(fixed: str = "sun", driven: str = "ring", count: int = 5, zp: int = ZP, zr: int = ZR,
          rated: bool = False) -> str:
    """Scene H (or R), the planetary varied; ``rated`` adds materials, roughness, a rating and a duty."""
    m = ', material = "st", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 16' if rated else ""
    grade = "accuracy_grade = 6" if rated else ""
    return f"""
title = "parallel, planetary, parallel"
[[stage]]
normal_module_mm = 3
{grade}
helix_angle_deg = 12
efficiency = {ETA1}
pinion = {{ teeth = 21, face_width_mm = 40, hand = "right"{m} }}
gear   = {{ teeth = 63, face_width_mm = 38, hand = "left"{m} }}

[[stage]]
type = "planetary"
normal_module_mm = {MN}
{grade}
efficiency = {ETA_P}
sun    = {{ teeth = {ZS}, face_width_mm = {B}{m} }}
planet = {{ teeth = {zp}, face_width_mm = {B}, count = {count}{m} }}
ring   = {{ teeth = {zr}, face_width_mm = {B}{m} }}
fixed = "{fixed}"
input = "{driven}"

[[stage]]
normal_module_mm = 5
{grade}
pinion = {{ teeth = 30, face_width_mm = 60{m} }}
gear   = {{ teeth = 24, face_width_mm = 60{m} }}

[input]
speed_rpm = {N_IN}

[load]
torque_Nm = {T_OUT}

[simulation]
duration_s = 0.3
steps = 1000
{RATED if rated else ""}
"""


def _run(tmp_path, text: str, *args: str, name: str = "train.toml"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return CliRunner().invoke(cli, [*args[:1], str(path), *args[1:]], catch_exceptions=False)


def _design(tmp_path, text: str) -> dict:
    res = _run(tmp_path, text, "design", "--format", "json", "-q")
    assert res.exit_code == 0, res.output
    return json.loads(res.output)


def _eps_external(z1: int, z2: int) -> float:
    r1, r2 = MN * z1 / 2, MN * z2 / 2
    a = r1 + r2
    return (math.sqrt((r1 + MN) ** 2 - (r1 * math.cos(ALPHA)) ** 2)
            + math.sqrt((r2 + MN) ** 2 - (r2 * math.cos(ALPHA)) ** 2) - a * math.sin(ALPHA)) / (math.pi * MN * math.cos(ALPHA))


def _eps_internal(zp: int, zr: int) -> float:
    """ε_α of an internal pair, x = 0: the planet's tip path less the ring's (its tip circle inside) plus a sin α."""
    rp, rr = MN * zp / 2, MN * zr / 2
    a = rr - rp
    return (math.sqrt((rp + MN) ** 2 - (rp * math.cos(ALPHA)) ** 2)
            - math.sqrt((rr - MN) ** 2 - (rr * math.cos(ALPHA)) ** 2) + a * math.sin(ALPHA)) / (math.pi * MN * math.cos(ALPHA))


def test_sun_held_ring_driven_books_by_hand(tmp_path):
    d = _design(tmp_path, scene())
    s1, sp, s3 = d["stages"]
    n_r = N_IN * 21 / 63                                  # 500 rpm: the ring, driven by stage 1's gear
    n_c = n_r * ZR / (ZR + ZS)                            # Willis with ω_s = 0: 333.33 rpm
    n_p_rel = (n_r - n_c) * ZR / ZP                       # the planet relative to the carrier: 666.67 rpm
    assert_allclose(sp["ratio"], 1 + ZS / ZR, rtol=1e-12)  # 1.5
    assert_allclose([sp["sun"]["speed_rpm"], sp["ring"]["speed_rpm"], sp["carrier"]["speed_rpm"],
                     sp["planet"]["speed_rpm"]], [0.0, n_r, n_c, n_p_rel], rtol=1e-12, atol=1e-9)
    assert_allclose(s3["pinion"]["speed_rpm"], n_c, rtol=1e-12)
    # the planet's absolute speed: ω_c + (ω_p − ω_c), the sun mesh: (ω_p − ω_c)/(ω_s − ω_c) = −z_s/z_p
    assert_allclose(n_c + (0 - n_c) * (-ZS / ZP), 1000.0, rtol=1e-12)
    # torques with losses: T_c = T_out/0.8 (η 1); the ring drives in the carrier's frame (ring at +166.7 rpm
    # relative, sun at −333.3): η = (1 + η_0 z_s/z_r)/(1 + z_s/z_r) -> η_0 = (1.5 η − 1)/0.5 = 0.91
    t_c = T_OUT * 30 / 24
    eta0 = ((1 + ZS / ZR) * ETA_P - 1) / (ZS / ZR)
    t_r = t_c / ((1 + ZS / ZR) * ETA_P)
    t_s = eta0 * t_r * ZS / ZR
    assert_allclose(sp["basic_efficiency"], eta0, rtol=1e-9)
    assert_allclose(sp["mesh_efficiency"], math.sqrt(eta0), rtol=1e-9)
    mb = sp["moment_balance_Nm"]
    assert_allclose([mb["ring"], mb["carrier"], mb["sun"]], [t_r, -t_c, t_c - t_r], rtol=1e-9)
    assert_allclose(t_s, t_c - t_r, rtol=1e-9)           # the held sun's reaction is what the losses leave
    # power in = power out + losses: P_r = P_c / η
    assert_allclose(t_r * n_r * ETA_P, t_c * n_c, rtol=1e-12)
    assert_allclose(s1["gear"]["torque_Nm"], t_r, rtol=1e-9)
    assert_allclose(s1["pinion"]["torque_Nm"], t_r / (3 * ETA1), rtol=1e-9)
    # forces per planet mesh: the ring drives, F_pr = T_r/(N r_r); the planet drives the sun: F_sp = η_m F_pr
    f_pr = t_r / (5 * MN * ZR / 2 / 1000)
    sun_mesh, ring_mesh = sp["meshes"]
    assert (sun_mesh["name"], ring_mesh["name"]) == ("sun_planet", "planet_ring")
    assert_allclose(ring_mesh["static_force_N"]["tangential"], f_pr, rtol=1e-9)
    assert_allclose(sun_mesh["static_force_N"]["tangential"], math.sqrt(eta0) * f_pr, rtol=1e-9)
    # and the sun side takes η_m of that: N η_m F_sp r_s is the sun's torque
    assert_allclose(5 * math.sqrt(eta0) * sun_mesh["static_force_N"]["tangential"] * MN * ZS / 2000, t_s, rtol=1e-9)
    # contact ratios from the tip circles; mesh frequency in the carrier's frame, z_s |n_s − n_c| = z_r |n_r − n_c|
    assert_allclose(sun_mesh["contact_ratio_transverse"], _eps_external(ZS, ZP), rtol=1e-9)
    assert_allclose(ring_mesh["contact_ratio_transverse"], _eps_internal(ZP, ZR), rtol=1e-9)
    assert_allclose(sun_mesh["contact_ratio_transverse"], 1.635186, atol=1e-6)   # printed figure of the hand calc
    assert_allclose(ring_mesh["contact_ratio_transverse"], 1.889681, atol=1e-6)
    f_mesh = ZS * n_c / 60
    assert_allclose([sun_mesh["mesh_frequency_Hz"], ring_mesh["mesh_frequency_Hz"]], [f_mesh, f_mesh], rtol=1e-12)
    assert_allclose(ZR * (n_r - n_c) / 60, f_mesh, rtol=1e-12)
    # the carrier carries the planets' translation N m_p r_c²; the planets' centres 2 a sin(36°) apart less d_a
    a = MN * (ZS + ZP) / 2
    assert_allclose(sp["carrier"]["planets_translational_inertia_kg_m2"],
                    5 * sp["planet"]["mass_kg"] * (a / 1000) ** 2, rtol=1e-12)
    assert_allclose(sp["tip_clearance_between_planets_mm"], 2 * a * math.sin(math.pi / 5) - MN * (ZP + 2), rtol=1e-9)


def test_star_ratio_speeds_and_torques_by_hand(tmp_path):
    d = _design(tmp_path, scene(fixed="carrier", driven="sun"))
    sp, s3 = d["stages"][1], d["stages"][2]
    n_s = N_IN * 21 / 63
    assert_allclose(sp["willis_ratio"], -ZR / ZS, rtol=1e-12)
    assert_allclose(sp["ratio"], ZR / ZS, rtol=1e-12)    # |ω_in/ω_out|, as a parallel stage's
    assert_allclose(sp["ring"]["speed_rpm"], -n_s * ZS / ZR, rtol=1e-12)   # the ring turns backwards
    assert_allclose(sp["carrier"]["speed_rpm"], 0.0, atol=1e-12)
    assert_allclose(s3["gear"]["speed_rpm"], n_s * ZS / ZR * 30 / 24, rtol=1e-12)
    # carrier held: the stage's efficiency is the basic one; T_s = T_r z_s/(z_r η)
    t_r = T_OUT * 30 / 24
    t_s = t_r * ZS / (ZR * ETA_P)
    assert_allclose(sp["basic_efficiency"], ETA_P, rtol=1e-9)
    assert_allclose([sp["moment_balance_Nm"][k] for k in ("sun", "ring", "carrier")],
                    [t_s, t_r, -(t_s + t_r)], rtol=1e-9)
    f_sp = t_s / (5 * MN * ZS / 2000)
    assert_allclose(sp["meshes"][0]["static_force_N"]["tangential"], f_sp, rtol=1e-9)
    assert_allclose(sp["meshes"][1]["static_force_N"]["tangential"], math.sqrt(ETA_P) * f_sp, rtol=1e-9)
    assert_allclose(sp["meshes"][0]["mesh_frequency_Hz"], ZS * n_s / 60, rtol=1e-12)


@pytest.mark.parametrize(("kwargs", "key", "words"), [
    ({"count": 0}, "stage[1].planet.count", "must be ≥ 1"),
    ({"count": 7}, "stage[1].planet.count", "(40 + 80)/7"),                    # 120/7 not whole
    ({"zr": 30}, "stage[1].ring.teeth", "must fit"),                              # a ring smaller than the sun
    ({"zr": 40}, "stage[1].ring.teeth", "must fit"),
])
def test_assembly_refusals_name_the_key(tmp_path, kwargs, key, words):
    res = _run(tmp_path, scene(**kwargs), "design")
    assert res.exit_code == 2
    assert key in res.output and words in res.output and "Traceback" not in res.output


def test_adjacency_figures(tmp_path):
    # a 25-tooth sun with five 35-tooth planets (ring 95, 120/5 = 24): a = 120 mm, the neighbours' centres
    # 2·120 sin 36° = 141.07 mm apart, less than the planet's tip diameter 4·37 = 148 mm: the planets collide.
    text = scene(zp=35, zr=110).replace(f"teeth = {ZS},", "teeth = 25,").replace("teeth = 110,", "teeth = 95,")
    res = _run(tmp_path, text, "design")
    assert res.exit_code == 2
    gap = 2 * 120 * math.sin(math.pi / 5)
    assert f"{gap:.4f} mm apart" in res.output and f"{148 - gap:.3f} mm" in res.output


def test_star_modes_against_hand_eigenproblem(tmp_path):
    text = f"""
title = "star alone"
[[stage]]
type = "planetary"
normal_module_mm = {MN}
sun    = {{ teeth = {ZS}, face_width_mm = {B} }}
planet = {{ teeth = {ZP}, face_width_mm = {B}, count = 4 }}
ring   = {{ teeth = {ZR}, face_width_mm = {B} }}
fixed = "carrier"
input = "sun"
[input]
speed_rpm = 1500
[load]
torque_Nm = 500
"""
    sp = _design(tmp_path, text)["stages"][0]
    res = _run(tmp_path, text, "modes", "--format", "json", "-q")
    assert res.exit_code == 0, res.output
    modes = json.loads(res.output)["boundaries"]
    ks, kr = (m["linearised_stiffness_N_mm"] * 1e3 for m in sp["meshes"])
    jp, jr, js = (sp[k]["inertia_kg_m2"] for k in ("planet", "ring", "sun"))
    rbs, rbp, rbr = (sp[k]["base_diameter_mm"] / 2000 for k in ("sun", "planet", "ring"))
    n = 4
    # coordinates [sun, planets..., ring]; carrier held: δ_s = r_bs θ_s + r_bp θ_p, δ_r = r_bp θ_p − r_br θ_r
    k_mat = np.zeros((n + 2, n + 2))
    for j in range(n):
        a = np.zeros(n + 2)
        a[0], a[1 + j] = rbs, rbp
        b = np.zeros(n + 2)
        b[1 + j], b[-1] = rbp, -rbr
        k_mat += ks * np.outer(a, a) + kr * np.outer(b, b)
    j_mat = np.diag([js] + [jp] * n + [jr])
    free = np.sqrt(np.abs(scipy.linalg.eigh(k_mat, j_mat, eigvals_only=True))) / (2 * np.pi)
    clamped = np.sqrt(scipy.linalg.eigh(k_mat[1:, 1:], j_mat[1:, 1:], eigvals_only=True)) / (2 * np.pi)
    # the planet modes, (N − 1)-fold: ω² = (k_s + k_r) r_bp² / J_p
    planet_mode = math.sqrt((ks + kr) * rbp ** 2 / jp) / (2 * math.pi)
    assert_allclose(sorted(clamped)[1:4], [planet_mode] * 3, rtol=1e-9)
    assert_allclose([m["frequency_Hz"] for m in modes["clamped_input"]], sorted(clamped), rtol=1e-8)
    assert_allclose([m["frequency_Hz"] for m in modes["free"]][1:], sorted(free)[1:], rtol=1e-8)


def test_life_cycles_per_member_by_hand(tmp_path):
    res = _run(tmp_path, scene(rated=True), "life", "--static", "--format", "json", "-q")
    assert res.exit_code == 0, res.output
    st = json.loads(res.output)["life"]["stages"][1]
    minutes = 1000 * 60
    n_c = 500 * ZR / (ZR + ZS)
    rel_s, rel_r = n_c, 500 - n_c                         # |n − n_c| of the sun and the ring
    rel_p = rel_s * ZS / ZP
    cycles = {k: sum(b["cycles"] for b in v["bins"]) for k, v in
              (("sun", st["sun"]["pitting"]), ("planet", st["planet"]["pitting"]), ("ring", st["ring"]["pitting"]),
               ("planet_root", st["planet_root"]["bending"]))}
    assert_allclose(cycles["sun"], 5 * rel_s * minutes, rtol=1e-9)        # N planets per relative turn
    assert_allclose(cycles["ring"], 5 * rel_r * minutes, rtol=1e-9)
    assert_allclose(cycles["planet"], rel_p * minutes, rtol=1e-9)         # one flank per relative turn
    assert_allclose(cycles["planet_root"], 2 * rel_p * minutes, rtol=1e-9)  # both meshes bend the root


def test_simulated_planet_means_against_statics(tmp_path):
    d = _design(tmp_path, scene(fixed="carrier", driven="sun"))
    f_sp, f_pr = (m["static_force_N"]["tangential"] for m in d["stages"][1]["meshes"])
    res = _run(tmp_path, scene(fixed="carrier", driven="sun"), "simulate", "--format", "json", "-q")
    assert res.exit_code == 0, res.output
    st = json.loads(res.output)["summary"]["stages"][1]
    assert len(st["planets"]) == 5
    # settled, unexcited, identical planets: every planet's mean equals the statics (the solver's tolerance)
    for p in st["planets"]:
        assert_allclose(p["sun"]["tangential_N"]["mean"], f_sp, rtol=1e-4)
        assert_allclose(p["ring"]["tangential_N"]["mean"], f_pr, rtol=1e-4)
    assert_allclose(st["load_sharing_factor"], 1.0, rtol=1e-6)


def test_sun_larger_than_planet_single_pair_factors_and_k_gamma(tmp_path):
    """The sun (40) is the larger wheel of its mesh: ISO 6336-2's single-pair factor belongs to each member's own
    inner point of single contact, so the planet (20) takes M = tan α_wt / √[(√(d_a1²/d_b1² − 1) − 2π/z1)
    (√(d_a2²/d_b2² − 1) − (ε_α − 1) 2π/z2)] with 1 the planet, and the sun's M < 1 gives Z_B = 1; σ_H scales with
    √K_γ through σ_H = Z_B σ_H0 √(K_A K_γ K_v K_Hβ K_Hα)."""
    text = scene(rated=True)
    d = _design(tmp_path, text)
    mesh = d["stages"][1]["meshes"][0]
    r = mesh["rating"]
    eps = mesh["contact_ratio_transverse"]
    assert_allclose(eps, _eps_external(ZS, ZP), rtol=1e-9)

    def m_factor(z1: int, z2: int) -> float:
        root = lambda z: math.sqrt(((z + 2) / (z * math.cos(ALPHA))) ** 2 - 1)  # noqa: E731  d_a/d_b at x = 0
        return math.tan(ALPHA) / math.sqrt((root(z1) - 2 * math.pi / z1) * (root(z2) - (eps - 1) * 2 * math.pi / z2))

    assert m_factor(ZS, ZP) < 1.0
    assert_allclose(r["pinion"]["Z_BD"], 1.0, rtol=1e-12)               # the sun
    assert_allclose(r["gear"]["Z_BD"], m_factor(ZP, ZS), rtol=1e-9)      # the planet: 1.06234
    assert_allclose(r["K_gamma"], 1.2, rtol=1e-12)
    # σ_H0 = Z_H Z_E Z_ε Z_β √(F_t/(d_1 b) (u + 1)/u), symmetric in which wheel is "1": 1/d_sun + 1/d_planet
    f_t = mesh["static_force_N"]["tangential"]
    s_h0 = r["Z_H"] * r["Z_E"] * r["Z_eps"] * r["Z_beta"] * math.sqrt(f_t / B * (1 / (MN * ZS) + 1 / (MN * ZP)))
    assert_allclose(r["sigma_H0_MPa"], s_h0, rtol=1e-9)
    assert_allclose(r["gear"]["sigma_H_MPa"], r["gear"]["Z_BD"] * s_h0 * math.sqrt(
        r["K_A"] * r["K_gamma"] * r["K_v"] * r["K_Hbeta"] * r["K_Halpha"]), rtol=1e-9)


def test_helical_shifted_concentric_by_hand(tmp_path):
    """β 15°, x_s 0.3, x_p 0.2: the sun–planet α_wt from inv α_wt = inv α_t + 2 (x_s + x_p) tan α_n/(z_s + z_p);
    the ring's x_r = −(x_s + 2 x_p) = −0.7 makes the internal pair's inv α_wt = inv α_t − 2 (x_p + x_r) tan α_n /
    (z_r − z_p) the same (z_r − z_p = z_s + z_p), so both centre distances agree (concentricity 0)."""
    text = scene().replace(f"normal_module_mm = {MN}\n", f"normal_module_mm = {MN}\nhelix_angle_deg = 15\n")
    text = text.replace(f"sun    = {{ teeth = {ZS}, face_width_mm = {B}",
                        f'sun    = {{ teeth = {ZS}, face_width_mm = {B}, hand = "right", profile_shift = 0.3')
    text = text.replace(f"planet = {{ teeth = {ZP}, face_width_mm = {B}, count = 5",
                        f'planet = {{ teeth = {ZP}, face_width_mm = {B}, count = 5, hand = "left", profile_shift = 0.2')
    text = text.replace(f"ring   = {{ teeth = {ZR}, face_width_mm = {B}",
                        f"ring   = {{ teeth = {ZR}, face_width_mm = {B}, profile_shift = -0.7")
    sp = _design(tmp_path, text)["stages"][1]
    beta = math.radians(15)
    at = math.atan(math.tan(ALPHA) / math.cos(beta))

    def inv(x: float) -> float:
        return math.tan(x) - x

    target = inv(at) + 2 * 0.5 * math.tan(ALPHA) / (ZS + ZP)
    lo, hi = at, math.radians(40)
    for _ in range(200):                                   # bisection for α_wt
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if inv(mid) < target else (lo, mid)
    awt = (lo + hi) / 2
    a_w = MN / math.cos(beta) * (ZS + ZP) / 2 * math.cos(at) / math.cos(awt)
    assert_allclose(awt, math.radians(22.830219628), rtol=1e-9)
    for mesh in sp["meshes"]:
        assert_allclose(mesh["working_pressure_angle_deg"], math.degrees(awt), rtol=1e-9)
        assert_allclose(mesh["center_distance_mm"], a_w, rtol=1e-9)
        assert_allclose(mesh["overlap_ratio"], B * math.sin(beta) / (math.pi * MN), rtol=1e-9)
    assert_allclose(sp["concentricity_mm"], 0.0, atol=1e-9)
    assert sp["ring"]["hand"] == "left"                    # the ring takes the planet's hand


def test_planetary_pair_warnings_name_sun_and_planet(tmp_path):
    """A 10-tooth planet (sun 100, ring 120, 20 planets: 220/20 = 11) is undercut: z_min = 2/sin²α = 17.10 and
    x_min = 1 − z sin²α / 2 = +0.415 (h_FfP* = 1, β = 0); the messages name the file's members (sun, planet, not
    the pair's pinion/gear), the JSON ``member`` stays the pair's (docs/output.md)."""
    text = (scene(fixed="carrier", driven="sun").replace(f"teeth = {ZS}, face_width_mm", "teeth = 100, face_width_mm")
            .replace(f"teeth = {ZP}, face_width_mm = {B}, count = 5", f"teeth = 10, face_width_mm = {B}, count = 20")
            .replace(f"teeth = {ZR},", "teeth = 120,")
            .replace(f"sun    = {{ teeth = 100, face_width_mm = {B}", f'sun    = {{ teeth = 100, face_width_mm = {B}, hand = "right"'))
    res = _run(tmp_path, text, "design", "--format", "json", "-o", str(tmp_path / "d.json"))
    assert res.exit_code == 0, res.output
    z_min = 2 / math.sin(ALPHA) ** 2
    x_min = 1 - 10 * math.sin(ALPHA) ** 2 / 2
    assert f"stage 2: planet z = 10 < z_min = {z_min:.1f}" in res.output and f"≥ {x_min:+.2f}" in res.output
    assert "the sun's tip meets the planet" in res.output
    assert 'hand given (sun "right")' in res.output
    assert "gear z =" not in res.output and "pinion's tip" not in res.output
    warnings = json.loads((tmp_path / "d.json").read_text(encoding="utf-8"))["warnings"]
    undercut = next(w for w in warnings if w.get("check") == "undercut")
    assert undercut["member"] == "gear" and undercut["teeth"] == 10
    # ISO 53 profile A's straight flank ends at h_FfP* = 0.99997 (not 1): z_min 3e-5 lower than 2/sin²α
    assert_allclose(undercut["min_teeth"], z_min, rtol=1e-4)


def test_planetary_safety_warnings_name_sun_and_planet(tmp_path):
    """Sixty times the load overloads the sun–planet mesh: its safety warnings name the sun (z = 40) and the
    planet (z = 20) as the file does; the JSON ``member`` stays the pair's pinion/gear (docs/output.md)."""
    text = scene(rated=True).replace(f"torque_Nm = {T_OUT}\n", "torque_Nm = 30000\n")
    res = _run(tmp_path, text, "design", "--format", "json", "-o", str(tmp_path / "d.json"))
    assert res.exit_code == 0, res.output
    assert "stage 2 sun (z = 40): pitting (flank) safety S_H" in res.output
    assert "stage 2 planet (z = 20): pitting (flank) safety S_H" in res.output
    assert "stage 2 pinion" not in res.output and "stage 2 gear" not in res.output
    warnings = json.loads((tmp_path / "d.json").read_text(encoding="utf-8"))["warnings"]
    low = [w for w in warnings if w.get("stage") == 2 and w.get("mode") == "pitting" and w.get("mesh") == "sun_planet"]
    assert {w["member"] for w in low} == {"pinion", "gear"}


def test_planetary_face_width_warning_names_the_planet(tmp_path):
    """b = 200 mm on the 80 mm planet (smaller than the 160 mm sun): b/d = 2.5 > 1.5 warns naming the planet."""
    text = scene().replace(f"face_width_mm = {B}", "face_width_mm = 200")
    res = _run(tmp_path, text, "design", "--format", "json", "-o", str(tmp_path / "d.json"))
    assert res.exit_code == 0, res.output
    assert f"stage 2: face width / smaller wheel's (the planet's) pitch diameter b/d1 = 200/{MN * ZP:g} = 2.5 > 1.5" \
        in res.output


def test_planetary_life_messages_and_tables_name_sun_and_planet(tmp_path):
    """Sixty times the load: the life's verdicts and its tables name the sun–planet mesh's members sun and planet
    (sun mesh), as its JSON's contract names do (``sun``, ``planet``); the JSON per-mesh keys stay."""
    text = scene(rated=True).replace(f"torque_Nm = {T_OUT}\n", "torque_Nm = 30000\n").replace(
        "torque_Nm = 500\nspeed_rpm = 1500", "torque_Nm = 30000\nspeed_rpm = 1500")
    res = _run(tmp_path, text, "life", "--static", "--format", "table")
    assert res.exit_code == 0, res.output
    assert "stage 2 sun pitting: spectrum safety S_H" in res.output
    assert "stage 2 planet (sun mesh) pitting" in res.output
    assert "stage 2 sun: load spectrum and Miner damage" in res.output
    assert "stage 2 pinion" not in res.output and "stage 2 gear" not in res.output
    assert "stage 1 pinion" in res.output                  # a parallel stage keeps its names
    res = _run(tmp_path, text, "life", "--static", "--format", "json", "-q")
    st = json.loads(res.output)["life"]["stages"][1]
    assert {"pinion", "gear", "sun", "planet", "ring", "planet_ring_side", "planet_root"} <= set(st)
