"""`gearcli simulate`, the static deflection, the mesh laws' reported tangents and stiffness_not_iso on the own scenes
of tests/reference/modal_hand.py against hand calculations: a free decay fitted independently, a TE's forced
response from the hand transfer function, h0 = e F_n0 / k_n, the rigid-body limit, the Hertz law, the 25 % warning,
the iso6336 law's 1 N/mm calibration floor, per-point calibration in a sweep."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner
from modal_hand import (
    ALPHA_N,
    BETA,
    J_G,
    M_N,
    T_LOAD,
    Z1,
    Z2,
    B,
    _base_radius_m,
    _cos_beta_b,
    _damped,
    _elastic,
    _lone_gear,
    _planetary,
    _planetary_hand,
    _run,
    _single,
    _single_hand,
    _static_normal_force_N,
    _undamped_Hz,
)
from numpy.testing import assert_allclose

from gearcli.cli import cli


def test_simulated_free_vibration_against_the_hand_model(tmp_path):
    """A 10 ms start leaves the gear ringing at +-13 % of the static force; the window after it is a free decay of the
    default Hertzian law (e = 1.5, linearised at the static load). An independent least-squares fit of
    F0 + A exp(-sigma t) cos(w_d t + psi) to the simulated F_t gives sigma = zeta_m w_n and w_d = w_n sqrt(1 - zeta_m^2),
    zeta_m = zeta / cos beta_b, w_n^2 = k_t r_bg^2 / J_G; F0 the static F_t = 2 T / d of the gear (DESIGN section 4:
    F_t = F_bt cos alpha_t, the reference circle). The run's ringing record names the same mode."""
    from scipy.optimize import curve_fit

    zeta, t0 = 0.005, 0.012
    text = _lone_gear(f"[contact]\ndamping_ratio = {zeta}\n",
                      f"duration_s = 0.05\nwindow_start_s = {t0}\nsteps = 20000\nrtol = 1e-9")
    text = text.replace("ramp_s = 0.02", "ramp_s = 0.01")
    cga = _run(tmp_path, text, "design")["stages"][0]["iso6336_mesh_stiffness_N_mm_um"]
    out = _run(tmp_path, text, "simulate", "--series")
    rg, cbb = _base_radius_m(Z2, M_N, ALPHA_N, BETA), _cos_beta_b(ALPHA_N, BETA)
    w_n = math.sqrt(cga * B * 1e6 * rg**2 / J_G)
    zeta_m = zeta / cbb
    sigma, w_d = zeta_m * w_n, w_n * math.sqrt(1 - zeta_m**2)
    d_gear = Z2 * M_N / math.cos(math.radians(BETA)) / 1000
    F_static = 2 * T_LOAD / d_gear
    assert_allclose(out["summary"]["natural_frequencies_Hz"], [w_n / (2 * math.pi)], rtol=1e-9)
    st = out["summary"]["stages"][0]
    assert_allclose(st["static_tangential_N"], F_static, rtol=1e-9)
    # the mean of a decay over a window that is not whole periods: up to A / (w_d T_window) = 363 / (11545 * 0.038) N
    assert_allclose(st["tangential_N"]["mean"], F_static, atol=1.0)
    t = np.asarray(out["series"]["time_s"])
    F = np.asarray(out["series"]["stage1_tangential_N"])
    keep = t >= t0
    t, F = t[keep] - t0, F[keep]

    def model(t, A, s, w, psi, F0):
        return F0 + A * np.exp(-s * t) * np.cos(w * t + psi)

    fits = []
    for psi in np.linspace(0.0, 2 * math.pi, 8, endpoint=False):
        p, _ = curve_fit(model, t, F, p0=[300.0, 50.0, w_n, psi, F_static], maxfev=20000)
        fits.append((float(np.sum((model(t, *p) - F) ** 2)), p))
    p = min(fits, key=lambda f: f[0])[1]
    assert abs(p[0]) > 0.05 * F_static  # it rings: the test has something to fit
    assert_allclose(p[1], sigma, rtol=2e-3)  # linear decay rate; the Hertzian law's amplitude effect is O(a^2)
    assert_allclose(p[2], w_d, rtol=5e-4)  # the Hertzian law softens +-13 % swings by ~1e-4
    assert_allclose(p[4], F_static, rtol=1e-4)
    ring = next(w for w in out["warnings"] if w.get("mode_frequency_Hz"))
    assert_allclose(ring["mode_frequency_Hz"], w_d / (2 * math.pi), rtol=1e-6)
    # it settles where the fitted envelope falls to 1 % of the static force: t0 + ln(a0 / 0.01 F) / sigma
    assert_allclose(ring["settle_time_s"], t0 + math.log(abs(p[0]) / (0.01 * F_static)) / sigma, rtol=0.02)


@pytest.mark.parametrize("exponent", [1.0, 1.5, 2.0])
def test_static_deflection_is_e_times_iso(tmp_path, exponent):
    """h0 = e F_n0 / k_n (docs/physics.md), in design, modes and the settled simulated penetration."""
    text = _lone_gear(f"[contact]\nexponent = {exponent}\ndamping_ratio = 0.3\n", "duration_s = 0.06")
    design = _run(tmp_path, text, "design")
    st = design["stages"][0]
    k_n = st["iso6336_mesh_stiffness_N_mm_um"] * B * 1e3 / _cos_beta_b(ALPHA_N, BETA) ** 2  # N/mm
    h0 = exponent * _static_normal_force_N() / k_n
    assert_allclose(st["static_force_N"]["normal"], _static_normal_force_N(), rtol=1e-9)
    assert_allclose(st["mesh_stiffness"]["static_approach_mm"], h0, rtol=1e-9)
    assert_allclose(_run(tmp_path, text, "modes")["meshes"][0]["mesh_stiffness"]["static_approach_mm"], h0, rtol=1e-9)
    sim = _run(tmp_path, text, "simulate")["summary"]["stages"][0]
    assert_allclose(sim["penetration_mm"]["mean"], h0, rtol=1e-5)  # settled at 30 % damping
    assert_allclose(sim["tangential_N"]["mean"], 2 * T_LOAD / (Z2 * M_N / math.cos(math.radians(BETA)) / 1000),
                    rtol=1e-6)


def test_rigid_body_limit(tmp_path):
    """A mesh 1300 times ISO's: the output turns at input / i, F_t is the static 2 T / d, the mode is at
    sqrt(K cos^2 beta_b r_bg^2 / J_G), and stiffness_not_iso says so."""
    K = 1e9  # N/mm, e = 1
    text = _lone_gear(f"[contact]\nstiffness = {K}\nexponent = 1.0\ndamping_ratio = 0.1\n", "duration_s = 0.06")
    out = _run(tmp_path, text, "simulate")
    s = out["summary"]
    assert_allclose(s["output_speed_rpm"], 1500 * Z1 / Z2, rtol=1e-9)
    assert_allclose(s["ratio"], Z2 / Z1, rtol=1e-9)
    st = s["stages"][0]
    assert_allclose(st["tangential_N"]["mean"], 2 * T_LOAD / (Z2 * M_N / math.cos(math.radians(BETA)) / 1000),
                    rtol=1e-9)
    assert st["tangential_N"]["std"] < 1e-6 * st["tangential_N"]["mean"]
    rg, cbb = _base_radius_m(Z2, M_N, ALPHA_N, BETA), _cos_beta_b(ALPHA_N, BETA)
    assert_allclose(s["natural_frequencies_Hz"], [math.sqrt(K * 1e3 * cbb**2 * rg**2 / J_G) / (2 * math.pi)],
                    rtol=1e-9)
    assert_allclose(st["penetration_mm"]["mean"], _static_normal_force_N() / K, rtol=1e-6)
    assert st["mesh_stiffness"]["law"] == "given"
    assert [w["code"] for w in out["warnings"]].count("stiffness_not_iso") == 1


def test_hertz_law_is_four_thirds_sqrt_r_e_star_and_warned(tmp_path):
    """stiffness = "hertz": K = 4/3 sqrt(R) E*, E* = E / (2 (1 - nu^2)) for two steel wheels, linearised
    e K h0^(e-1) with h0 = (F_n0 / K)^(1/e): 75 % below ISO's k_n, warned the same in design, modes and simulate."""
    text = _lone_gear('[contact]\nstiffness = "hertz"\n', "duration_s = 0.06")
    design = _run(tmp_path, text, "design")
    st = design["stages"][0]
    e_star = 2.1e5 / (2 * (1 - 0.3**2))
    K = 4 / 3 * math.sqrt(st["equivalent_radius_mm"]) * e_star
    F = _static_normal_force_N()
    lin = 1.5 * K * (F / K) ** (1 / 3)
    k_n = st["iso6336_mesh_stiffness_N_mm_um"] * B * 1e3 / _cos_beta_b(ALPHA_N, BETA) ** 2
    for cmd, ms in (("design", st["mesh_stiffness"]),
                    ("modes", (m := _run(tmp_path, text, "modes"))["meshes"][0]["mesh_stiffness"]),
                    ("simulate", (s := _run(tmp_path, text, "simulate"))["summary"]["stages"][0]["mesh_stiffness"])):
        assert ms["law"] == "hertz", cmd
        assert_allclose([ms["K"], ms["linearised_N_mm"], ms["iso_N_mm"], ms["static_approach_mm"]],
                        [K, lin, k_n, (F / K) ** (2 / 3)], rtol=1e-9, err_msg=cmd)
    for out in (design, m, s):
        (w,) = [w for w in out["warnings"] if w["code"] == "stiffness_not_iso"]
        assert_allclose(w["departure"], lin / k_n - 1, rtol=1e-9)
        assert lin / k_n - 1 < -0.7


@pytest.mark.parametrize(("exponent", "ratio", "warned"),
                         [(1.0, 1.24, False), (1.0, 1.26, True), (1.0, 0.76, False), (1.0, 0.74, True),
                          (1.5, 1.24, False), (1.5, 1.26, True), (1.5, 0.76, False), (1.5, 0.74, True)])
def test_stiffness_not_iso_fires_beyond_25_percent(tmp_path, exponent, ratio, warned):
    """A given K whose tangent at F_n0 is `ratio` times k_n: K = (ratio k_n / e)^e / F_n0^(e-1)."""
    probe = _run(tmp_path, _lone_gear("", "duration_s = 0.06"), "design")["stages"][0]
    k_n = probe["iso6336_mesh_stiffness_N_mm_um"] * B * 1e3 / _cos_beta_b(ALPHA_N, BETA) ** 2
    F = _static_normal_force_N()
    K = (ratio * k_n / exponent) ** exponent / F ** (exponent - 1)
    text = _lone_gear(f"[contact]\nstiffness = {K!r}\nexponent = {exponent}\n", "duration_s = 0.06")
    for cmd in ("design", "modes"):
        out = _run(tmp_path, text, cmd)
        ms = (out["stages"][0] if cmd == "design" else out["meshes"][0])["mesh_stiffness"]
        assert_allclose(ms["linearised_N_mm"] / ms["iso_N_mm"], ratio, rtol=1e-9, err_msg=cmd)
        assert any(w["code"] == "stiffness_not_iso" for w in out["warnings"]) is warned, cmd


@pytest.mark.parametrize("torque", [0.0, 1e-3, 1.0])
def test_lightly_loaded_train_linearises_at_the_calibration_floor(tmp_path, torque):
    """Below 1 N/mm of face width the iso6336 law is calibrated at that floor (docs/physics.md): its tangent is
    ISO's k_n there, and design reports linearised_N_mm = k_n. modes and simulate linearised the law at the real
    static load instead: 1 N m gave the mesh mode 1588 Hz (-21 %), 1e-3 N m 548 Hz (-73 %) and 0 N m 4142 Hz (+106 %,
    a 1 um approach) against 2015 Hz of the hand model with k_n, and simulate reported linearised_N_mm 158138 and
    15814 N/mm beside design's 256714. Now all of them are the linear ISO model at the floor, continuous in the load."""
    text = _single().replace(f"torque_Nm = {T_LOAD}", f"torque_Nm = {torque}")
    design = _run(tmp_path, text, "design")
    cga = design["stages"][0]["iso6336_mesh_stiffness_N_mm_um"]
    J, K, C, k_n = _single_hand(cga, 0.05)
    assert_allclose(design["stages"][0]["mesh_stiffness"]["linearised_N_mm"], k_n / 1000, rtol=1e-9)
    out = _run(tmp_path, text, "modes")
    assert_allclose(out["meshes"][0]["mesh_stiffness"]["linearised_N_mm"], k_n / 1000, rtol=1e-9)
    lam = _damped(J, K, C)
    tool = _elastic(out, "free")
    assert_allclose([m["frequency_Hz"] for m in tool], _undamped_Hz(J, K)[1:], rtol=1e-8)
    assert_allclose([m["damping_ratio"] for m in tool], [-z.real / abs(z) for z in lam], rtol=1e-6)
    sim = _run(tmp_path, text.replace("duration_s = 0.4", "duration_s = 0.15"), "simulate")["summary"]
    assert_allclose(sim["stages"][0]["mesh_stiffness"]["linearised_N_mm"], k_n / 1000, rtol=1e-9)
    assert_allclose(sim["natural_frequencies_Hz"], _undamped_Hz(J[1:], K[1:, 1:]), rtol=1e-8)  # the motor held


def test_lightly_loaded_planetary_linearises_at_the_calibration_floor(tmp_path):
    """The same for both planet meshes (each at its own floor): a 0.1 N m sun load against the hand model."""
    text = _planetary().replace("torque_Nm = 100", "torque_Nm = 0.1")
    st = _run(tmp_path, text, "design")["stages"][0]
    cga = {m["name"]: m["iso6336_mesh_stiffness_N_mm_um"] for m in st["meshes"]}
    k_sp, k_pr = cga["sun_planet"] * 30e6, cga["planet_ring"] * 30e6
    out = _run(tmp_path, text, "modes")
    for ms in out["meshes"]:
        assert_allclose(ms["mesh_stiffness"]["linearised_N_mm"], ms["mesh_stiffness"]["iso_N_mm"], rtol=1e-9)
    J, K, C = _planetary_hand(k_sp, k_pr, 0.05)
    tool = _elastic(out, "clamped_input")
    assert_allclose([m["frequency_Hz"] for m in tool], _undamped_Hz(J[:4], K[:4, :4]), rtol=1e-8)
    assert_allclose([m["damping_ratio"] for m in tool], [-z.real / abs(z) for z in _damped(J[:4], K[:4, :4],
                                                                                          C[:4, :4])], rtol=1e-6)


def test_transmission_error_response_against_the_hand_transfer_function(tmp_path):
    """A 1 um first-harmonic TE at the mesh frequency z_p n_p = 525 Hz on the lone gear (linear law): with u the
    dynamic deflection, m_e u'' + c (u' - e') + k_t (u - e) = 0, so q = u - e = e m_e w^2 / (k_t - m_e w^2 + i w c)
    and F_bt = (k_t + i w c) q; the window's F_t std is |F_bt| cos alpha_t / sqrt 2, the DTE rms |q| / sqrt 2."""
    text = _lone_gear("[contact]\nexponent = 1.0\ndamping_ratio = 0.05\ntransmission_error_um = [1.0]\n",
                      "duration_s = 0.12\nwindow_start_s = 0.08\nsteps = 8000\nrtol = 1e-9")
    cga = _run(tmp_path, text, "design")["stages"][0]["iso6336_mesh_stiffness_N_mm_um"]
    st = _run(tmp_path, text, "simulate")["summary"]["stages"][0]
    rg, cbb = _base_radius_m(Z2, M_N, ALPHA_N, BETA), _cos_beta_b(ALPHA_N, BETA)
    k_t = cga * B * 1e6
    m_e = J_G / rg**2
    c = 2 * 0.05 * math.sqrt(k_t / cbb**2 * m_e)
    w = 2 * math.pi * Z1 * 1500 / 60
    q = 1e-6 * m_e * w**2 / complex(k_t - m_e * w**2, w * c)
    F = abs(complex(k_t, w * c) * q)
    alpha_t = math.atan(math.tan(math.radians(ALPHA_N)) / math.cos(math.radians(BETA)))
    # 40 ms of window after 60 ms of settling at 5 % damping (w_n zeta t ~ 35 decay lengths): steady to < 1e-4
    assert_allclose(st["tangential_N"]["std"], F * math.cos(alpha_t) / math.sqrt(2), rtol=5e-4)
    assert_allclose(st["dte_um"]["rms"], abs(q) * 1e6 / math.sqrt(2), rtol=5e-4)


def test_planetary_simulate_reports_both_mesh_laws(tmp_path):
    """DESIGN section 13: simulate gives every mesh's mesh_stiffness; a planetary stage's planet–ring law is
    ``planet_ring_mesh_stiffness`` beside the sun–planet mesh's ``mesh_stiffness`` (it had none). A planet carries
    r_bp F_sp = r_bp F_pr (spur, lossless): both meshes F_n0 = T_sun / (N r_bs), h0 = e F_n0 / k_n each."""
    text = _planetary()
    st = _run(tmp_path, text, "design")["stages"][0]
    cga = {m["name"]: m["iso6336_mesh_stiffness_N_mm_um"] for m in st["meshes"]}
    sim = _run(tmp_path, text, "simulate")["summary"]["stages"][0]
    F_n0 = 100.0 / (3 * 21 * 3.0 / 2 * math.cos(math.radians(20.0)) / 1000)
    for key, name in (("mesh_stiffness", "sun_planet"), ("planet_ring_mesh_stiffness", "planet_ring")):
        k_n = cga[name] * 30 * 1e3  # N/mm, spur
        ms = sim[key]
        assert ms["law"] == "iso6336" and ms["exponent"] == 1.5
        assert_allclose([ms["linearised_N_mm"], ms["iso_N_mm"], ms["static_approach_mm"]],
                        [k_n, k_n, 1.5 * F_n0 / k_n], rtol=1e-9, err_msg=key)


def test_sweep_points_calibrate_at_their_own_load(tmp_path):
    """DESIGN section 13: K follows each sweep point's static load, so each point's mean DTE is its own
    h0 / cos beta_b = e F_n0 / (k_n cos beta_b), k_n from that point's c_gamma_alpha (ISO's low-load factor moves it)."""
    import csv

    text = _lone_gear("[contact]\ndamping_ratio = 0.3\n", "duration_s = 0.08\nwindow_start_s = 0.06")
    scene = tmp_path / "scene.toml"
    scene.write_text(text, encoding="utf-8")
    out = tmp_path / "sweep.csv"
    res = CliRunner().invoke(cli, ["sweep", str(scene), "--vary", "load.torque_Nm=150,600", "--jobs", "1",
                                   "-o", str(out)])
    assert res.exit_code == 0, res.output
    rows = list(csv.DictReader(line for line in out.read_text().splitlines() if not line.startswith("#")))
    cbb = _cos_beta_b(ALPHA_N, BETA)
    assert len(rows) == 2
    for row in rows:
        torque = float(row["load.torque_Nm"])
        res = CliRunner().invoke(cli, ["design", str(scene), "--set", f"load.torque_Nm={torque}", "--format", "json"])
        cga = json.loads(res.stdout)["stages"][0]["iso6336_mesh_stiffness_N_mm_um"]
        k_n = cga * B * 1e3 / cbb**2
        F_n0 = torque / _base_radius_m(Z2, M_N, ALPHA_N, BETA) / cbb
        assert_allclose(float(row["stage1_dte_um_mean"]), 1.5 * F_n0 / k_n / cbb * 1000, rtol=1e-6)


@pytest.mark.parametrize("torque", [0.0, 1.0])
def test_hertz_law_below_the_floor_reports_its_own_tangent(tmp_path, torque):
    """A Hertz law needs no calibration floor: design and modes reported its tangent at 1 N/mm of face width
    (45201 N/mm, h0 1.5 um) where simulate reported it at the static load (1 N m: 27844 N/mm, h0 0.57 um; 0 N m: 0).
    All three now give e K h0^(e-1) with h0 = (F_n0 / K)^(1/e) at the static F_n0, and warn the same departure."""
    text = _lone_gear('[contact]\nstiffness = "hertz"\n', "duration_s = 0.06").replace(
        f"torque_Nm = {T_LOAD}", f"torque_Nm = {torque}")
    st = _run(tmp_path, text, "design")["stages"][0]
    K = st["hertz_stiffness_N_mm1_5"]
    F = torque / _base_radius_m(Z2, M_N, ALPHA_N, BETA) / _cos_beta_b(ALPHA_N, BETA)
    h0 = (F / K) ** (2 / 3)
    lin = 1.5 * K * h0**0.5
    docs = {"design": (d := _run(tmp_path, text, "design"), d["stages"][0]["mesh_stiffness"]),
            "modes": (m := _run(tmp_path, text, "modes"), m["meshes"][0]["mesh_stiffness"]),
            "simulate": (s := _run(tmp_path, text, "simulate"), s["summary"]["stages"][0]["mesh_stiffness"])}
    for cmd, (doc, ms) in docs.items():
        assert_allclose([ms["static_approach_mm"], ms["linearised_N_mm"]], [h0, lin], rtol=1e-9, atol=1e-12,
                        err_msg=cmd)
        (w,) = [w for w in doc["warnings"] if w["code"] == "stiffness_not_iso"]
        assert_allclose(w["departure"], lin / ms["iso_N_mm"] - 1, rtol=1e-9, err_msg=cmd)

