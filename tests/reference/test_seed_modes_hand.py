"""`gearcli modes` on the seed reducer (Table 1 of the seed paper) against a hand linear model: the file's own law
(configs/concrete_mixer.toml: the paper's point-contact Hertz law with its IMPACT damping) and the law this round's
defaults give the same geometry (DESIGN section 13: no `[contact]`, the ISO 6336-1-calibrated tangent, 5 % viscous
damping). No gearcli number is taken as an expected value; the figures quoted in docs/errata.md are these.

Hand model (SI inside):
- ISO 21771, x = 0: m_t = m_n / cos beta, tan alpha_t = tan alpha_n / cos beta, d = z m_t, r_b = d cos alpha_t / 2,
  d_a = d + 2 m_n, tan beta_b = tan beta cos alpha_t, eps_alpha from the tip circles; b the smaller face width.
- Loads: T_out = 5310 N m on gear 6, brought back through the ratios (no losses); F_t = T_p / r_p,
  F_n = F_t / (cos alpha_n cos beta).
- Inertias: solid steel discs of pitch diameter and face width, J = pi rho b d^4 / 32 (DESIGN section 2); shaft 1 =
  pinion 1 (speed-driven: clamped for `clamped_input`), shaft 2 = gear 2 + pinion 3, shaft 3 = gear 4 + pinion 5,
  shaft 4 = gear 6.
- Hertz: 1/R = 1/r_1 + 1/r_2 (pitch radii), 1/E* = 2 (1 - nu^2) / E, K = 4/3 sqrt(R) E*; h0 = (F_n / K)^(2/3),
  normal tangent k = 1.5 K sqrt(h0); IMPACT damping at h0: c_n = C s^2 (3 - 2 s), s = h0 / d.
- ISO 6336-1 method B: z_n = z / (cos^2 beta_b cos beta), q' = C1 + C2/z_n1 + C3/z_n2, c' = (1/q') C_M C_R C_B cos beta
  (0.8, 1, 0.975) x (F_t / b / 100)^0.25 (F_t / b is 10-26 N/mm here), c_gamma_alpha = c' (0.75 eps_alpha + 0.25),
  k_n = c_gamma_alpha b / cos^2 beta_b; the calibrated law's tangent at the static load is k_n, its K = F_n / h0^1.5
  with h0 = 1.5 F_n / k_n.
- Along delta = r_bp theta_p - r_bg theta_g: stiffness k cos^2 beta_b; the IMPACT damping c_n cos^2 beta_b; the
  viscous law's c = 2 zeta sqrt(k m_e) on delta' (docs/physics.md: k the normal tangent, so the modal ratio of a
  helical mesh is zeta / cos beta_b), m_e = 1 / sum r^2 / J, the speed-driven pinion 1 infinitely heavy.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from modal_hand import _add, _damped, _elastic, _run, _undamped_Hz
from numpy.testing import assert_allclose

TABLE1 = ((12.0, 12.0, 21, 51, 190.0, 180.0), (18.0, 11.0, 17, 50, 250.0, 240.0), (25.0, 9.0, 17, 53, 320.0, 310.0))
ALPHA_N, RHO, E_MPA, NU, T_OUT_NM = 20.0, 7800.0, 2.07e5, 0.29, 5310.0
C_IMPACT, D_IMPACT, ZETA = 50.0, 0.1, 0.05  # N s/mm, mm; the default viscous ratio
Q = (0.04723, 0.15551, 0.25791)  # ISO 6336-1 C1, C2, C3 (x = 0)
ERRATA = (Path(__file__).resolve().parents[2] / "docs" / "errata.md").read_text(encoding="utf-8")


def _stage(m_n: float, beta_deg: float, z1: int, z2: int, b1: float, b2: float, torque_out_Nmm: float) -> dict:
    """One stage by hand; ``torque_out_Nmm`` is the torque on its gear."""
    beta, alpha_n = math.radians(beta_deg), math.radians(ALPHA_N)
    m_t = m_n / math.cos(beta)
    alpha_t = math.atan(math.tan(alpha_n) / math.cos(beta))
    d1, d2 = z1 * m_t, z2 * m_t
    rb1, rb2 = d1 * math.cos(alpha_t) / 2, d2 * math.cos(alpha_t) / 2
    beta_b = math.atan(math.tan(beta) * math.cos(alpha_t))
    a = (d1 + d2) / 2
    eps_a = (math.sqrt((d1 / 2 + m_n) ** 2 - rb1**2) + math.sqrt((d2 / 2 + m_n) ** 2 - rb2**2)
             - a * math.sin(alpha_t)) / (math.pi * m_t * math.cos(alpha_t))
    b = min(b1, b2)
    f_t = torque_out_Nmm * z1 / z2 / (d1 / 2)
    f_n = f_t / (math.cos(alpha_n) * math.cos(beta))
    e_star = E_MPA / (2 * (1 - NU**2))
    k_hertz = 4 / 3 * math.sqrt(1 / (2 / d1 + 2 / d2)) * e_star
    h_hertz = (f_n / k_hertz) ** (2 / 3)
    zn = [z / (math.cos(beta_b) ** 2 * math.cos(beta)) for z in (z1, z2)]
    c_prime = (1 / (Q[0] + Q[1] / zn[0] + Q[2] / zn[1]) * 0.8 * 1.0 * 0.975 * math.cos(beta)
               * min(1.0, f_t / b / 100) ** 0.25)
    k_n = c_prime * (0.75 * eps_a + 0.25) * b * 1e3 / math.cos(beta_b) ** 2  # N/mm
    s = h_hertz / D_IMPACT
    return {"rb": (rb1 / 1e3, rb2 / 1e3), "cos2": math.cos(beta_b) ** 2, "f_t": f_t, "f_n": f_n,
            "J": tuple(math.pi * RHO * w * 1e-3 * (d * 1e-3) ** 4 / 32 for w, d in ((b1, d1), (b2, d2))),
            "hertz": {"K": k_hertz, "tangent": 1.5 * k_hertz * math.sqrt(h_hertz),
                      "c_n": C_IMPACT * s * s * (3 - 2 * s)},
            "iso": {"K": f_n / (1.5 * f_n / k_n) ** 1.5, "tangent": k_n}}


def _train() -> tuple[list[dict], np.ndarray]:
    stages, torque = [], T_OUT_NM * 1e3
    for m_n, beta, z1, z2, b1, b2 in reversed(TABLE1):
        stages.insert(0, _stage(m_n, beta, z1, z2, b1, b2, torque))
        torque *= z1 / z2
    J = [stages[0]["J"][0]] + [stages[k]["J"][1] + stages[k + 1]["J"][0] for k in range(2)] + [stages[2]["J"][1]]
    return stages, np.array(J)


def _hand_modes(law: str, clamped: bool) -> tuple[np.ndarray, list[complex]]:
    stages, J = _train()
    K, C = np.zeros((4, 4)), np.zeros((4, 4))
    for k, st in enumerate(stages):
        lever = {k: st["rb"][0], k + 1: -st["rb"][1]}
        k_t = st[law]["tangent"] * 1e3 * st["cos2"]  # N/m on delta
        _add(K, lever, k_t)
        if law == "hertz":
            c_t = st["hertz"]["c_n"] * 1e3 * st["cos2"]
        else:
            mobility = (0.0 if k == 0 else st["rb"][0] ** 2 / J[k]) + st["rb"][1] ** 2 / J[k + 1]
            c_t = 2 * ZETA * math.sqrt(st["iso"]["tangent"] * 1e3 / mobility)
        _add(C, lever, c_t)
    keep = slice(1, None) if clamped else slice(None)
    J, K, C = J[keep], K[keep, keep], C[keep, keep]
    return _undamped_Hz(J, K), _damped(J, K, C)


def _seed_file(law: str) -> str:
    text = ('title = "seed reducer, hand modes"\n[materials.steel]\ndensity_kg_m3 = 7800\n'
            "youngs_modulus_MPa = 2.07e5\npoisson_ratio = 0.29\n")
    hands = (("left", "right"), ("right", "left"), ("left", "right"))
    for (m_n, beta, z1, z2, b1, b2), (h1, h2) in zip(TABLE1, hands, strict=True):
        text += (f"[[stage]]\nnormal_module_mm = {m_n}\nnormal_pressure_angle_deg = 20\nhelix_angle_deg = {beta}\n"
                 f'pinion = {{ teeth = {z1}, face_width_mm = {b1}, hand = "{h1}", material = "steel" }}\n'
                 f'gear = {{ teeth = {z2}, face_width_mm = {b2}, hand = "{h2}", material = "steel" }}\n')
    if law == "hertz":  # the paper's section 3.3 law, as configs/concrete_mixer.toml states it
        text += ('[contact]\nstiffness = "hertz"\nexponent = 1.5\n'
                 f"damping_Ns_mm = {C_IMPACT}\nfull_damping_penetration_mm = {D_IMPACT}\n")
    return text + ("[input]\nspeed_deg_s = 3600\nramp_s = 0.18\n[load]\ntorque_Nmm = 5.31e6\nramp_s = 0.18\n"
                   "[simulation]\nduration_s = 0.5\n")


def _quoted(values, fmt: str, sep: str = " / ") -> str:
    return sep.join(format(v, fmt) for v in values)


def test_hand_figures_are_the_errata_pages():
    """The hand model's own numbers (stage 1, the modes and their damping), as docs/errata.md quotes them."""
    stages, J = _train()
    s1 = stages[0]
    assert_allclose([s1["f_t"], s1["f_n"]], [1851.098, 2013.906], rtol=1e-6)
    assert_allclose([s1["hertz"]["K"], s1["hertz"]["tangent"]], [1.439239e6, 2.414680e5], rtol=1e-6)
    assert_allclose([s1["iso"]["K"], s1["iso"]["tangent"]], [3.438471e7, 2.003002e6], rtol=1e-6)
    assert_allclose(J, [0.6409626, 22.93071, 138.2650, 768.8471], rtol=1e-6)
    # the paper's pitch radii and R (section 3.3), corrected: r = m_n z / (2 cos 12 deg)
    r1, r2 = 12 * 21 / (2 * math.cos(math.radians(12))), 12 * 51 / (2 * math.cos(math.radians(12)))
    assert f"{r1:.2f} mm, {r2:.2f} mm, R {r1 * r2 / (r1 + r2):.2f} mm" in ERRATA
    for law in ("hertz", "iso"):
        ms = s1[law]
        assert f"{ms['K']:.3e}".replace("e+0", "e") in ERRATA and f"{ms['tangent']:.3e}".replace("e+0", "e") in ERRATA
        h0 = s1["f_n"] / ms["K"]
        assert f"{1e3 * h0 ** (2 / 3):.{2 if law == 'hertz' else 3}f} µm" in ERRATA
        for clamped in (True, False):
            f, lam = _hand_modes(law, clamped)
            assert _quoted(f[f > 1e-3], ".1f") in ERRATA, (law, clamped)
        zeta = [-100 * z.real / abs(z) for z in _hand_modes(law, True)[1]]
        assert _quoted(zeta, ".2f" if law == "hertz" else ".1f") + " %" in ERRATA, law
    assert_allclose(_hand_modes("hertz", True)[0], [58.010, 112.441, 184.115], rtol=1e-5)
    assert_allclose(_hand_modes("iso", True)[0], [170.177, 330.107, 534.827], rtol=1e-5)


def test_default_law_steady_means_balance_the_load(tmp_path):
    """Under the defaults the seed's steady window (0.244-0.5 s) barely rings (5 % viscous damping): each stage's
    mean F_t is its static T_p / r_p to the window's transient share (the 170 Hz mode's, ~1e-4), as errata.md says."""
    d = _run(tmp_path, _seed_file("iso"), "simulate")
    stages, _ = _train()
    means = [st["tangential_N"]["mean"] for st in d["summary"]["stages"]]
    assert_allclose(means, [st["f_t"] for st in stages], rtol=3e-4)
    assert f"{means[0]:.1f} N ({100 * (means[0] / stages[0]['f_t'] - 1):+.2f} %)".replace("-", "−") in ERRATA


@pytest.mark.parametrize("law", ["hertz", "iso"])
def test_seed_modes_are_the_hand_linear_model(tmp_path, law):
    d = _run(tmp_path, _seed_file(law), "modes")
    stages, _ = _train()
    for k, mesh in enumerate(d["meshes"]):
        ms = mesh["mesh_stiffness"]
        assert ms["law"] == ("hertz" if law == "hertz" else "iso6336")
        assert_allclose([ms["K"], ms["linearised_N_mm"], ms["iso_N_mm"]],
                        [stages[k][law]["K"], stages[k][law]["tangent"], stages[k]["iso"]["tangent"]], rtol=1e-9)
    for boundary, clamped in (("clamped_input", True), ("free", False)):
        f_hand, lam = _hand_modes(law, clamped)
        got = _elastic(d, boundary)
        f_hand = f_hand[f_hand > 1e-3]  # the free train's rigid mode
        assert_allclose([m["frequency_Hz"] for m in got], f_hand, rtol=1e-9)
        # damped: -Re(lambda) / |lambda| of the hand state matrix (light damping: the modes keep their order)
        assert_allclose([m["damping_ratio"] for m in got], [-z.real / abs(z) for z in lam], rtol=1e-6)
