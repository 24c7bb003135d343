"""The calibrated mesh law (DESIGN sections 13, 2, 4, 6) on an engineer's own scenes, against hand calculations.

Independent references written out here (no gearcli number is taken as an expected value):
- ISO 21771 geometry for x = 0: m_t = m_n / cos beta, tan alpha_t = tan alpha_n / cos beta, d = z m_t,
  d_b = d cos alpha_t, d_a = d + 2 m_n, tan beta_b = tan beta cos alpha_t,
  eps_alpha = (sqrt(r_a1^2 - r_b1^2) + sqrt(r_a2^2 - r_b2^2) - a sin alpha_t) / (pi m_t cos alpha_t).
- ISO 6336-1 method B: z_n = z / (cos^2 beta_b cos beta), q' = C1 + C2/z_n1 + C3/z_n2 (x = 0), c'_th = 1/q',
  c' = c'_th C_M C_R C_B cos beta (C_M 0.8, C_R 1, C_B = [1 + 0.5 (1.2 - 1.25)] [1 - 0.02 (20 - alpha_n)]), times
  (F_t / b / 100)^0.25 below 100 N/mm (F_t floored at 1 N per mm of face width, docs/physics.md); c_gamma_alpha =
  c' (0.75 eps_alpha + 0.25); k_n = c_gamma_alpha b / cos^2 beta_b (N/mm), b the smaller face width.
- The law F_n = K h^e, "iso6336": e K h0^(e-1) = k_n at F_n0 = K h0^e, i.e. h0 = e F_n0 / k_n, K = F_n0 / h0^e;
  "hertz": K = 4/3 sqrt(R) E*, 1/R = 1/r_1 + 1/r_2 (pitch radii), 1/E* = 2 (1 - nu^2) / E; k_lin = e K h0^(e-1)
  at h0 = (F_n0 / K)^(1/e).
- The linear model at the operating point (DESIGN section 13): transverse mesh stiffness k_lin cos^2 beta_b on
  delta = r_bp theta_p - r_bg theta_g; viscous c = 2 zeta sqrt(k_lin m_e) on delta' with m_e = 1 / sum r^2/J (a
  speed-driven body infinitely heavy; DESIGN section 6, docs/physics.md); a coupling's k and c; a table motor's slip
  damping -dT/dw, the slope of its table segment at the operating speed where the table meets the reflected load;
  the load law T_ref (w / w_n)^p: its damping p T_ref w^(p-1) / w_n^p at the operating speed. Eigenvalues by scipy.
- A numerical Jacobian (central differences) of the right-hand side ``simulate`` integrates, at the static operating
  point built here from the hand deflections (the right-hand side must vanish there: static equilibrium).
"""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest
import scipy.linalg
from numpy.testing import assert_allclose

from gearcli import api
from gearcli.model import TorsionalModel
from tests.reference.calib_hand import (
    PLANETARY,
    SCENES,
    _damped,
    _design,
    _hand_linear,
    _hand_meshes,
    _hand_planetary,
    _law,
    _load_scale,
    _operating_state,
)


@pytest.mark.parametrize("name", SCENES)
def test_iso_stiffness_and_law_coefficient_by_hand(name):
    doc = SCENES[name]
    cfg, design = _design(doc)
    for k, (st, hand) in enumerate(zip(design.stages, _hand_meshes(doc), strict=True)):
        law = _law(doc, k)
        assert_allclose(st.contact_ratio_transverse, hand["eps_a"], rtol=1e-12)
        assert_allclose(st.iso6336_single_pair_stiffness_N_mm_um, hand["c_single"], rtol=1e-12)
        assert_allclose(st.iso6336_mesh_stiffness_N_mm_um, hand["c_ga"], rtol=1e-12)
        ms = st.mesh_stiffness
        assert ms.law == law["stiffness"] and ms.exponent == law["exponent"]
        assert_allclose([ms.K, ms.linearised_N_mm, ms.iso_N_mm], [hand["K"], hand["k_lin"], hand["k_n"]], rtol=1e-11,
                        err_msg=f"stage {k + 1}")  # closed forms, round-off only
        if law["stiffness"] == "iso6336":  # the tangent at the (floored) static load is ISO's, for any exponent
            e = law["exponent"]
            assert_allclose(e * ms.K * hand["h0_mm"] ** (e - 1), hand["k_n"], rtol=1e-11)


@pytest.mark.parametrize("name", SCENES)
def test_modes_are_the_hand_linear_model(name):
    """Undamped frequencies of J^-1 K (scipy.linalg.eigvals) and damping ratios -Re(lambda)/|lambda| of the damped
    state matrix, at both boundaries, against ``api.modes``."""
    doc = SCENES[name]
    cfg, design = _design(doc)
    J, K, C, _, _, _ = _hand_linear(doc)
    got = {a.boundary: a for a in api.modes(cfg, design)}
    for boundary, keep in (("free", slice(0, None)), ("clamped_input", slice(1, None))):
        Jb, Kb, Cb = J[keep], K[keep, keep], C[keep, keep]
        # a lossy chain's K = L^T diag(k) R is not symmetric: the generalised eigenvalues of (K, J), real here
        w2 = np.sort(scipy.linalg.eigvals(Kb, np.diag(Jb)).real)
        f_hand = np.sqrt(np.clip(w2, 0, None)) / (2 * math.pi)
        elastic = [m for m in got[boundary].modes if not m.rigid]
        f_hand = f_hand[f_hand > 1e-6 * f_hand.max()]
        assert_allclose([m.frequency_Hz for m in elastic], f_hand, rtol=1e-8, err_msg=boundary)
        lam = [z for z in _damped(Jb, Kb, Cb) if z.imag > 0]
        for m in elastic:  # the damped eigenvalue nearest in frequency
            z = min(lam, key=lambda z, f=m.frequency_Hz: abs(abs(z) / (2 * math.pi) - f))
            assert_allclose(m.damping_ratio, -z.real / abs(z), rtol=1e-6, err_msg=f"{boundary} mode {m.number}")


@pytest.mark.parametrize("name", ["two_helical", "table_load", "lossy", "lossy_reversed", "coupled_speed", "three_mixed",
                                  "huge_helical"])
def test_simulate_rhs_jacobian_has_the_modes_eigenvalues(name):
    """Central differences of simulate's right-hand side at the operating point: its eigenvalues are the hand
    model's damped eigenvalues (the boundary the drive imposes), and the right-hand side vanishes there."""
    doc = SCENES[name]
    cfg, design = _design(doc)
    model = TorsionalModel(api.model_spec(cfg, design))
    st = model.layout.state
    y0 = _operating_state(doc, model)
    t = 5.0  # past every ramp
    dyn = st.mechanical
    f0 = np.asarray(model.rhs(t, y0))[dyn]
    scale = np.abs(y0[dyn]) + 1e-9
    # static equilibrium: every acceleration vanishes to round-off against the static torques' own size
    acc = f0[st.speeds]
    J, K, C, driven, _, rpm_in = _hand_linear(doc, at_operating_load=True)
    keep = slice(0 if driven is None else 1, None)
    torque_scale = np.abs(K[keep, keep]).max() * np.abs(y0[st.deflections]).max() / J[keep].min()
    assert np.all(np.abs(acc) < 1e-9 * torque_scale), acc
    n = st.n_mechanical
    jac = np.empty((n, n))
    for j in range(n):
        h = 1e-6 * scale[j]
        yp, ym = y0.copy(), y0.copy()
        yp[j] += h
        ym[j] -= h
        jac[:, j] = (np.asarray(model.rhs(t, yp))[dyn] - np.asarray(model.rhs(t, ym))[dyn]) / (2 * h)
    lam_num = np.linalg.eigvals(jac)
    lam_hand = _damped(J[keep], K[keep, keep], C[keep, keep])
    lam_hand = sorted(lam_hand, key=abs)[len(lam_hand) - n:]  # a free chain's rigid angle: one zero fewer
    for z in lam_hand:
        near = min(lam_num, key=lambda w, z=z: abs(w - z))
        assert abs(near - z) <= 1e-5 * max(abs(z), 1.0), (z, near)
    # and the modes are these eigenvalues (the boundary the drive imposes) where the operating load is the design's
    # static load (a speed drive); a motor meeting a speed-dependent load off its nominal speed carries the load law's
    # torque there, which modes do not linearise at (its meshes at the design's static load: the report's note)
    boundary = "free" if driven is None else "clamped_input"
    got = {a.boundary: a for a in api.modes(cfg, design)}[boundary]
    same_load = _load_scale(doc, rpm_in) == 1.0
    for m in (m for m in got.modes if not m.rigid):
        z = min((w for w in lam_num if w.imag > 0), key=lambda w, f=m.frequency_Hz: abs(abs(w) / (2 * math.pi) - f))
        # |lambda| is the undamped frequency up to the damping's coupling of the modes (non-proportional: ~zeta^2)
        assert_allclose(m.frequency_Hz, abs(z) / (2 * math.pi), rtol=5e-3 if same_load else 1e-2)
        assert_allclose(m.damping_ratio, -z.real / abs(z), rtol=1e-4 if same_load else 2e-2,
                        err_msg=f"mode {m.number}")


@pytest.mark.parametrize("member", ["sun", "carrier"])
@pytest.mark.parametrize("torque", [9000.0, -9000.0])
def test_lossy_planetary_meshes_linearise_to_iso_either_way(member, torque):
    """A lossy planetary (stage efficiency 0.96) under a forward and a reversed load, sun- or carrier-driven, on the
    calibrated law (e = 1.3): every planet mesh is linearised (modes, at the model's static forces) at ISO's k_n by
    hand (spur: k_n = c_gamma_alpha b; F_t / b > 100 N/mm on both meshes, so no low-load factor), and the design
    reports that tangent. The sun–planet mesh's design force is already its driving side's (the planet's when the
    planet drives the sun): calibrating at it over the efficiency once more left the mesh 0.96^(0.3/1.3) = 0.9906
    times as stiff as ISO under a reversed load."""
    doc = copy.deepcopy(PLANETARY)
    doc["stage"][0].pop("mesh")
    doc["stage"][0].update({"efficiency": 0.96, "input": member})
    doc["load"]["torque_Nm"] = torque
    cfg, design = _design(doc)
    st = design.stages[0]
    hand = _hand_planetary()
    for name, law in (("sun_planet", st.mesh_stiffness), ("planet_ring", st.planetary.planet_ring.mesh_stiffness)):
        assert law.law == "iso6336"
        assert_allclose([law.iso_N_mm, law.linearised_N_mm], hand[name]["k_n"], rtol=1e-12, err_msg=name)
    for a in api.modes(cfg, design):
        for name, label in (("sun_planet", "sun mesh"), ("planet_ring", "ring mesh")):
            k = [s for c, s in zip(a.connectors, a.stiffness, strict=True) if c.endswith(label)]
            assert len(k) == 3
            assert_allclose(k, hand[name]["k_n"] * 1000.0, rtol=1e-9, err_msg=f"{a.boundary} {name}")
