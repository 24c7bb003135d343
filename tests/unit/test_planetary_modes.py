"""Modes of a planetary stage (ring held) against closed forms and against an eigenproblem assembled by hand.

The torsional model of a planetary with a held ring (Lin & Parker, J. Vib. Acoust. 121, 1999, the purely
rotational model): bodies carrier, N planets, sun (absolute angles); along each planet's sun mesh
delta = r_bs th_s + r_bp th_p - (r_bs + r_bp) th_c, along its ring mesh delta = -r_bp th_p - (r_br - r_bp) th_c;
the carrier carries the planets' translation N m_p r_c^2. Its modes fall into two families:

- planet modes, N - 1 fold: the planets turn against each other (sum of planet angles 0), sun and carrier at
  rest, omega^2 = (k_sp + k_rp) r_bp^2 / J_p;
- rotational modes: every planet alike; the 3 x 3 problem over (th_c, th_p, th_s) with N times one planet's
  meshes (free: one rigid-body mode at 0 Hz and two more; input held: a 2 x 2 problem, closed form below).

The mesh law is linear (exponent 1, ISO 6336-1 stiffness c_gamma_alpha b per mesh): the tangent stiffness is the
design's number, independent of load.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from gearcli.config.schema import DesignFile
from gearcli.design import compute_design
from gearcli.model.assembly import Layout
from gearcli.model.modes import modal_analysis
from gearcli.scene import spec_from_design

N = 4


def _scene(planets: int = N, fixed: str = "ring", input_member: str = "carrier"):
    doc = {"stage": [{"type": "planetary", "normal_module_mm": 4.0,
                      "sun": {"teeth": 24, "face_width_mm": 40.0},
                      "planet": {"teeth": 30, "face_width_mm": 40.0, "count": planets},
                      "ring": {"teeth": 84, "face_width_mm": 40.0},
                      "carrier": {"inertia_kg_m2": 0.8}, "fixed": fixed, "input": input_member}],
           "contact": {"stiffness": "iso6336", "exponent": 1.0},
           "input": {"speed_rpm": 300.0}, "load": {"torque_Nm": 400.0}}
    cfg = DesignFile.model_validate(doc)
    design = compute_design(cfg)
    return design.stages[0], Layout.of(spec_from_design(cfg, design))


def _numbers(st, lay):
    p = st.planetary
    k_sp = st.iso6336_mesh_stiffness_N_mm_um * st.face_width_mm * 1e9 / 1e3  # N/(mm um) * mm -> N/m
    k_rp = p.planet_ring.iso6336_mesh_stiffness_N_mm_um * p.planet_ring.face_width_mm * 1e6
    r_bs, r_bp, r_br = (0.5e-3 * g.base_diameter_mm for g in (p.sun, p.planet, p.ring))
    return p, k_sp, k_rp, r_bs, r_bp, r_br


def test_mesh_stiffness_is_the_design_number():
    st, lay = _scene()
    _, k_sp, k_rp, *_ = _numbers(st, lay)
    ana = modal_analysis(lay, "free")
    for label, k in zip(ana.connectors, ana.stiffness, strict=True):
        assert_allclose(k, k_sp if "sun mesh" in label else k_rp, rtol=1e-12)


@pytest.mark.parametrize("boundary", ["clamped_input", "free"])
def test_planet_mode_is_n_minus_1_fold_at_the_closed_form(boundary):
    st, lay = _scene()
    p, k_sp, k_rp, r_bs, r_bp, r_br = _numbers(st, lay)
    w2 = (k_sp + k_rp) * r_bp ** 2 / p.planet.inertia_kg_m2
    f_planet = math.sqrt(w2) / (2 * math.pi)
    modes = modal_analysis(lay, boundary).modes
    found = [m for m in modes if abs(m.frequency_Hz - f_planet) < 1e-9 * f_planet]
    assert len(found) == N - 1
    planets = [i for i, b in enumerate(lay.bodies) if "planet" in b.label]
    others = [i for i in range(len(lay.bodies)) if i not in planets]
    for m in found:  # sun and carrier at rest, the planets' angles sum to zero
        assert_allclose([m.shape[i] for i in others], 0.0, atol=1e-9)
        assert abs(sum(m.shape[i] for i in planets)) < 1e-9


def _hand_matrices(st, lay, clamp_carrier: bool):
    """K and M over (carrier, planets..., sun) assembled here from the levers of the module docstring."""
    p, k_sp, k_rp, r_bs, r_bp, r_br = _numbers(st, lay)
    n = N + 2
    K = np.zeros((n, n))
    for j in range(N):
        v_s = np.zeros(n)
        v_s[[0, 1 + j, n - 1]] = (-(r_bs + r_bp), r_bp, r_bs)
        v_r = np.zeros(n)
        v_r[[0, 1 + j]] = (-(r_br - r_bp), -r_bp)
        K += k_sp * np.outer(v_s, v_s) + k_rp * np.outer(v_r, v_r)
    r_c = 0.5e-3 * (p.sun.pitch_diameter_mm + p.planet.pitch_diameter_mm)  # x = 0: r_c = a = (d_s + d_p)/2
    m_p = 7800 * math.pi / 4 * (p.planet.pitch_diameter_mm * 1e-3) ** 2 * 40e-3
    J = np.array([0.8 + N * m_p * r_c ** 2] + [p.planet.inertia_kg_m2] * N + [p.sun.inertia_kg_m2])
    if clamp_carrier:
        K, J = K[1:, 1:], J[1:]
    w2 = np.linalg.eigvals(np.linalg.solve(np.diag(J), K)).real
    return np.sort(np.sqrt(np.clip(w2, 0, None)) / (2 * math.pi)), J


@pytest.mark.parametrize("boundary", ["clamped_input", "free"])
def test_every_mode_against_the_eigenproblem_assembled_by_hand(boundary):
    st, lay = _scene()
    hand, J = _hand_matrices(st, lay, clamp_carrier=boundary == "clamped_input")
    assert_allclose(sorted(lay.inertias[1 if boundary == "clamped_input" else 0:]), sorted(J), rtol=1e-12)
    got = [m.frequency_Hz for m in modal_analysis(lay, boundary).modes]
    assert_allclose(got, hand, rtol=1e-9, atol=1e-9)


def test_rotational_modes_with_the_carrier_held_closed_form():
    """Carrier held: the in-phase planets and the sun, a 2 x 2 problem. Per planet the sun mesh couples
    (th_p, th_s) with (r_bp, r_bs), the ring mesh holds th_p with r_bp:
    K = N [[(k_sp + k_rp) r_bp^2, k_sp r_bp r_bs], [k_sp r_bp r_bs, k_sp r_bs^2]], M = diag(N J_p, J_s);
    omega^2 = (tr ± sqrt(tr^2 - 4 det)) / 2 of M^-1 K."""
    st, lay = _scene()
    p, k_sp, k_rp, r_bs, r_bp, _ = _numbers(st, lay)
    J_p, J_s = p.planet.inertia_kg_m2, p.sun.inertia_kg_m2
    a = (k_sp + k_rp) * r_bp ** 2 / J_p
    d = N * k_sp * r_bs ** 2 / J_s
    tr, det = a + d, (k_sp + k_rp) * r_bp ** 2 * N * k_sp * r_bs ** 2 / (J_p * J_s) - (
        N * k_sp * r_bp * r_bs) ** 2 / (N * J_p * J_s)
    w2 = [(tr - math.sqrt(tr * tr - 4 * det)) / 2, (tr + math.sqrt(tr * tr - 4 * det)) / 2]
    expected = sorted([math.sqrt(w) / (2 * math.pi) for w in w2] + [math.sqrt(a) / (2 * math.pi)] * (N - 1))
    got = [m.frequency_Hz for m in modal_analysis(lay, "clamped_input").modes]
    assert_allclose(got, expected, rtol=1e-9)


def test_free_boundary_has_the_rigid_mode_of_willis_kinematics():
    st, lay = _scene()
    rigid = modal_analysis(lay, "free").modes[0]
    assert rigid.rigid and rigid.frequency_Hz == 0.0
    p = st.planetary
    speeds = {b.label: b.ratio for b in lay.bodies}
    # the rigid shape is the bodies' kinematic ratios (carrier 1, sun 1 + z_r/z_s, planets (r_c w_c - r_bs w_s)/r_bp)
    scale = rigid.shape[0] / speeds["shaft 1"]
    assert_allclose(np.array(rigid.shape) / scale, [b.ratio for b in lay.bodies], rtol=1e-9)
    assert_allclose(speeds["shaft 2"], 1 + 84 / 24, rtol=1e-12)
    assert_allclose(p.ratio, 1 / (1 + 84 / 24), rtol=1e-12)
