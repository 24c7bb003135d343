"""The calibrated mesh law (DESIGN sections 3, 4, 13) on trial tr24g's scenes, against hand calculations written here
(no gearcli number is an expected value):

- ISO 21771 geometry with profile shifts: inv a_wt = inv a_t + 2 tan a_n (x1 + x2) / (z1 + z2), a_w = a cos a_t /
  cos a_wt, tip alteration k = (a_w - a) / m_n - (x1 + x2) (k <= 0 shortens both tips), d_a = d + 2 m_n (h_a* + x + k);
  an internal ring (ISO's signed x_r): inv a_wt = inv a_t + 2 tan a_n (x_p + x_r) / (z_p - z_r), d_ar = d_r - 2 m_n
  (h_a* + x_r); eps_alpha = (sqrt(r_a1^2 - r_b1^2) +- sqrt(r_a2^2 - r_b2^2) -+ a_w sin a_wt) / (pi m_t cos a_t).
- ISO 6336-1 method B: z_n = z / (cos^2 beta_b cos beta), index 1 the wheel with fewer teeth, q' = C1 + C2/z_n1 +
  C3/z_n2 + C4 x1 + C5 x1/z_n1 + C6 x2 + C7 x2/z_n2 + C8 x1^2 + C9 x2^2 (an internal mesh: z_n2 = infinity, x2 = x_r),
  c' = C_M C_R C_B cos beta / q' (C_M 0.8, C_R 1, C_B = [1 + 0.5 (1.2 - h_fP*)] [1 - 0.02 (20 - a_n)]) times
  (F_t K_A / b / 100)^0.25 below 100 N/mm, c_gamma_alpha = c' (0.75 eps_alpha + 0.25), k_n = c_gamma_alpha b /
  cos^2 beta_b, b the smaller face width; the default law (e = 1.5) has K = k_n^e / (e^e F_n^(e-1)).
- The linear torsional model at the operating point: transverse stiffness c_gamma_alpha b on each line of action; a
  planet's sun mesh r_bs (th_s - th_c) - r_bp (th_c - psi), its ring mesh r_bp (th_c - psi) + r_br (th_r - th_c)
  (psi the planet's absolute angle, a held member's angle 0); eigenvalues by scipy.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.linalg
import scipy.optimize
import tomli_w
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

C = (0.04723, 0.15551, 0.25791, -0.00635, -0.11654, -0.00193, -0.24188, 0.00529, 0.00182)
STEEL = {"density_kg_m3": 7850.0, "youngs_modulus_MPa": 2.1e5, "poisson_ratio": 0.3}
# a spur planetary whose planet has fewer teeth than its sun (ISO's wheel 1 of the sun-planet mesh is the planet),
# every member shifted, the ring's shift set for concentricity (a_w 61.0695 mm on both meshes)
ZS, ZP, ZR, XS, XP, XR, MN, AN, N = 31, 17, 65, 0.2, 0.25, -0.7, 2.5, 22.0, 3
BS, BP, BR, JS, JP, MP, JR, JC = 40.0, 38.0, 42.0, 0.01, 0.0015, 0.9, 0.3, 0.08
LOAD_NM = 600.0


def _planetary(fixed: str) -> dict:
    stage = {"type": "planetary", "normal_module_mm": MN, "normal_pressure_angle_deg": AN, "fixed": fixed,
             "sun": {"teeth": ZS, "face_width_mm": BS, "profile_shift": XS, "inertia_kg_m2": JS},
             "planet": {"teeth": ZP, "face_width_mm": BP, "profile_shift": XP, "count": N, "inertia_kg_m2": JP,
                        "mass_kg": MP},
             "ring": {"teeth": ZR, "face_width_mm": BR, "profile_shift": XR, "inertia_kg_m2": JR}}
    if fixed == "ring":
        stage["carrier"] = {"inertia_kg_m2": JC}
    return {"materials": {"steel": STEEL}, "stage": [stage], "input": {"speed_rpm": 1000.0, "ramp_s": 0.02},
            "load": {"torque_Nm": LOAD_NM, "ramp_s": 0.02}}


def _inv(a: float) -> float:
    return math.tan(a) - a


def _inv_inverse(v: float) -> float:
    return scipy.optimize.brentq(lambda a: _inv(a) - v, 1e-6, 1.5, xtol=1e-15, rtol=1e-15)


def _q(zn1: float, zn2: float, x1: float, x2: float) -> float:
    return (C[0] + C[1] / zn1 + C[2] / zn2 + C[3] * x1 + C[4] * x1 / zn1 + C[5] * x2 + C[6] * x2 / zn2
            + C[7] * x1 ** 2 + C[8] * x2 ** 2)


def _meshes(torque_sun_Nm: float) -> dict:
    """Both meshes of the spur planetary by hand (beta = 0: z_n = z, F_n = F_t / cos a_n)."""
    an = math.radians(AN)
    d = {z: z * MN for z in (ZS, ZP, ZR)}
    rb = {z: 0.5 * d[z] * math.cos(an) for z in (ZS, ZP, ZR)}
    awt = _inv_inverse(_inv(an) + 2 * math.tan(an) * (XS + XP) / (ZS + ZP))
    a_w = 0.5 * (d[ZS] + d[ZP]) * math.cos(an) / math.cos(awt)
    k = (a_w - 0.5 * (d[ZS] + d[ZP])) / MN - (XS + XP)
    ra_s, ra_p = 0.5 * d[ZS] + MN * (1 + XS + k), 0.5 * d[ZP] + MN * (1 + XP + k)
    ra_r = 0.5 * d[ZR] - MN * (1 + XR)
    awt_r = _inv_inverse(_inv(an) + 2 * math.tan(an) * (XP + XR) / (ZP - ZR))
    pbt = math.pi * MN * math.cos(an)
    eps_sp = (math.sqrt(ra_s ** 2 - rb[ZS] ** 2) + math.sqrt(ra_p ** 2 - rb[ZP] ** 2) - a_w * math.sin(awt)) / pbt
    eps_pr = (math.sqrt(ra_p ** 2 - rb[ZP] ** 2) - math.sqrt(ra_r ** 2 - rb[ZR] ** 2) + a_w * math.sin(awt_r)) / pbt
    f_t = torque_sun_Nm * 1000.0 / N / (0.5 * d[ZS])
    b = min(BS, BP)  # both meshes: the planet's 38 mm
    low = min(f_t / b / 100.0, 1.0) ** 0.25
    c_b = (1 + 0.5 * (1.2 - 1.25)) * (1 - 0.02 * (20.0 - AN))
    out = {}
    for name, q, eps in (("sun_planet", _q(ZP, ZS, XP, XS), eps_sp), ("planet_ring", _q(ZP, math.inf, XP, XR), eps_pr)):
        c1 = 0.8 * c_b / q * low
        c_ga = c1 * (0.75 * eps + 0.25)
        k_n = c_ga * b * 1000.0
        f_n = f_t / math.cos(an)
        out[name] = {"eps": eps, "c1": c1, "c_ga": c_ga, "k_n": k_n, "K": k_n ** 1.5 / (1.5 ** 1.5 * f_n ** 0.5)}
    return {"meshes": out, "a_w": a_w, "rb": rb, "f_t": f_t}


def _write(tmp_path, doc):
    path = tmp_path / "scene.toml"
    path.write_text(tomli_w.dumps(doc), encoding="utf-8")
    return path


def _json(tmp_path, doc, command):
    import json

    res = CliRunner().invoke(cli, [command, str(_write(tmp_path, doc)), "--format", "json", "-q"])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def test_shifted_planetary_meshes_iso_stiffness_and_law_by_hand(tmp_path):
    """c', c_gamma_alpha and the default law's K of both meshes of a shifted planetary whose planet is ISO's wheel 1
    (17 < 31 teeth) and whose internal mesh takes z_n2 = infinity: to 1e-12."""
    hand = _meshes(LOAD_NM / (1 + ZR / ZS))
    stage = _json(tmp_path, _planetary("ring"), "design")["stages"][0]
    for mesh in stage["meshes"]:
        h = hand["meshes"][mesh["name"]]
        assert_allclose(mesh["static_force_N"]["tangential"], hand["f_t"], rtol=1e-12)
        assert_allclose([mesh["contact_ratio_transverse"], mesh["iso6336_single_pair_stiffness_N_mm_um"],
                         mesh["iso6336_mesh_stiffness_N_mm_um"]], [h["eps"], h["c1"], h["c_ga"]], rtol=1e-12,
                        err_msg=mesh["name"])
        law = mesh["mesh_stiffness"]
        assert_allclose([law["K"], law["linearised_N_mm"], law["iso_N_mm"]], [h["K"], h["k_n"], h["k_n"]], rtol=1e-11,
                        err_msg=mesh["name"])


def test_design_table_gives_the_planet_ring_law_by_hand(tmp_path):
    """The design table gives the planet–ring mesh's law beside its c' and c_gamma_alpha, as the loads table gives the
    sun–planet mesh's: K, the tangent the models use and ISO's k_n, each by hand to 4 digits (the table had the
    planet–ring c' and c_gamma_alpha only: its calibration was in the JSON alone)."""
    hand = _meshes(LOAD_NM / (1 + ZR / ZS))["meshes"]["planet_ring"]
    res = CliRunner().invoke(cli, ["design", str(_write(tmp_path, _planetary("ring"))), "--format", "table", "-q"],
                             terminal_width=200)
    assert res.exit_code == 0, res.output
    lines = {line.split("│")[1].strip(): line.split("│")[2].strip() for line in res.stdout.splitlines()
             if line.count("│") == 3}
    assert lines["planet–ring law K [N/mm^e] / tangent / ISO k_n [N/mm]"] == (
        f"{hand['K']:.4g} / {hand['k_n']:.4g} / {hand['k_n']:.4g}")


@pytest.mark.parametrize("fixed", ["ring", "carrier"])
def test_planetary_modes_are_the_hand_model_at_iso_stiffness(tmp_path, fixed):
    """Natural frequencies of the speed-driven sun (clamped) and of the free train: the ring held (carrier output,
    its inertia with the planets' N m_p r_c^2) and the carrier held (a star: ring output), to 1e-9 (the rigid
    mode to 1e-3 Hz: the hand eigensolver's zero is roundoff)."""
    torque_sun = LOAD_NM / (1 + ZR / ZS) if fixed == "ring" else LOAD_NM / (ZR / ZS)
    hand = _meshes(torque_sun)
    rb = {z: r / 1000.0 for z, r in hand["rb"].items()}
    k_sp, k_pr = (hand["meshes"][m]["c_ga"] * min(BS, BP) * 1e6 for m in ("sun_planet", "planet_ring"))
    r_c = hand["a_w"] / 1000.0
    # coordinates: sun, carrier or ring (the output), planets 1..N
    n = 2 + N
    K = np.zeros((n, n))
    for j in range(N):
        sun, ring = np.zeros(n), np.zeros(n)
        if fixed == "ring":  # th_r = 0, output th_c
            sun[[0, 1, 2 + j]] = rb[ZS], -rb[ZS] - rb[ZP], rb[ZP]
            ring[[1, 2 + j]] = rb[ZP] - rb[ZR], -rb[ZP]
        else:  # th_c = 0, output th_r
            sun[[0, 2 + j]] = rb[ZS], rb[ZP]
            ring[[1, 2 + j]] = rb[ZR], -rb[ZP]
        K += k_sp * np.outer(sun, sun) + k_pr * np.outer(ring, ring)
    J_out = JC + N * MP * r_c ** 2 if fixed == "ring" else JR
    M = np.diag([JS, J_out] + [JP] * N)
    modes = _json(tmp_path, _planetary(fixed), "modes")["boundaries"]
    for boundary, keep in (("clamped_input", list(range(1, n))), ("free", list(range(n)))):
        w2 = scipy.linalg.eigh(K[np.ix_(keep, keep)], M[np.ix_(keep, keep)], eigvals_only=True)
        f = np.sqrt(np.clip(w2, 0.0, None)) / (2 * math.pi)
        got = [m["frequency_Hz"] for m in modes[boundary]]
        assert_allclose(got, f, rtol=1e-9, atol=1e-3, err_msg=f"{fixed} held, {boundary}")
