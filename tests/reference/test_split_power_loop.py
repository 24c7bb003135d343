"""A split-power train: a second power path from shaft 1 to shaft 3 beside two spur stages, built through the
general topology (DESIGN section 11: a connector names the bodies it joins; the design file itself is a chain, so the
loop is added in code, `ModelSpec.elements`, as docs/api.md shows).

The train: spur 20/40 (m 3) then 20/50 (m 4), linear meshes of 5e5 N/mm (transverse: spur), stated inertias, input
speed-driven at 1000 rpm, 1000 N m on shaft 3, both STEP-ramped over 50 ms. The second path is a torsional spring
k_e = 2e4 N m/rad with levers (1, i), i = 5 the train's ratio: its twist theta_1 - i theta_3 vanishes on the rigid
motion, so it carries torque only through the meshes' compliance, as a parallel gear path would.

References, by hand:
- the static split of a statically indeterminate loop: both paths see the same twist theta_1 - i theta_3; the
  chain's compliance at shaft 1 C_A = 1/(r_b1p^2 k) + (r_b1g/(r_b1p r_b2p))^2/k, the spring's C_B = 1/k_e, so the
  chain carries C_B/(C_A + C_B) of the input torque T_L/i;
- the modes: K = k g_1 g_1^T + k g_2 g_2^T + k_e g_e g_e^T (g_1 = [r_b1p, -r_b1g, 0], g_2 = [0, r_b2p, -r_b2g],
  g_e = [1, 0, -i]), J = diag(J_1, J_2, J_3), scipy.linalg.eigh;
- the energy balance closes (input = load + dissipation + kinetic + potential).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.linalg import eigh

from gearcli import api
from gearcli.model.assembly import Layout
from gearcli.model.modes import modal_analysis
from gearcli.model.spec import SpringSpec

SCENE = """
title = "two spur stages, linear meshes"
[materials.steel]
density_kg_m3 = 7850
youngs_modulus_MPa = 206000
poisson_ratio = 0.3

[contact]
stiffness = 5e5
exponent = 1
damping_ratio = 0.05

[[stage]]
normal_module_mm = 3
pinion = { teeth = 20, face_width_mm = 30, material = "steel", inertia_kg_m2 = 0.001 }
gear   = { teeth = 40, face_width_mm = 30, material = "steel", inertia_kg_m2 = 0.01 }

[[stage]]
normal_module_mm = 4
pinion = { teeth = 20, face_width_mm = 40, material = "steel", inertia_kg_m2 = 0.004 }
gear   = { teeth = 50, face_width_mm = 40, material = "steel", inertia_kg_m2 = 0.2 }

[input]
speed_rpm = 1000
ramp_s = 0.05

[load]
torque_Nm = 1000
ramp_s = 0.05
"""
K = 5e8  # N/m
K_E = 2e4  # N m/rad
RATIO = 2.0 * 2.5
T_L = 1000.0
ALPHA = math.radians(20)
RB1P, RB1G, RB2P, RB2G = (z * m / 2e3 * math.cos(ALPHA) for z, m in ((20, 3), (40, 3), (20, 4), (50, 4)))


@pytest.fixture(scope="module")
def specs(tmp_path_factory):
    path = tmp_path_factory.mktemp("loop") / "train.toml"
    path.write_text(SCENE, encoding="utf-8")
    loaded, design = api.load_and_design(str(path))
    chain = api.model_spec(loaded.design, design)
    loop = dataclasses.replace(chain, elements=(
        api.ElementSpec("spring", (0, 2), (1.0, RATIO), SpringSpec(K_E, 0.0), "second power path"),))
    return chain, loop


def test_the_loop_splits_the_load_by_the_paths_compliances(specs):
    chain, loop = specs
    c_a = 1 / (RB1P**2 * K) + (RB1G / (RB1P * RB2P)) ** 2 / K
    c_b = 1 / K_E
    share = c_b / (c_a + c_b)  # 0.8594: the meshes' path is the stiffer
    t_1 = T_L / RATIO
    want_chain = [t_1 / RB1P * math.cos(ALPHA), t_1 * RB1G / (RB1P * RB2P) * math.cos(ALPHA)]  # F_t = F_bt cos a
    for spec, part in ((chain, 1.0), (loop, share)):
        run = api.simulate_spec(spec, duration_s=0.3, steps=300, method="auto", rtol=1e-8)
        # the window keeps a decaying start transient: 1e-6
        assert_allclose([s.tangential_N.mean for s in run.stages], [part * f for f in want_chain], rtol=1e-6)
        assert abs(run.energy.residual_relative) < 1e-9
        assert_allclose(run.output_speed_deg_s / run.input_speed_deg_s, 1 / RATIO, rtol=1e-7)


def test_the_loop_s_modes_against_a_hand_assembled_eigenproblem(specs):
    _, loop = specs
    k = (K * np.outer([RB1P, -RB1G, 0], [RB1P, -RB1G, 0]) + K * np.outer([0, RB2P, -RB2G], [0, RB2P, -RB2G])
         + K_E * np.outer([1, 0, -RATIO], [1, 0, -RATIO]))
    m = np.diag([0.001, 0.01 + 0.004, 0.2])
    free = np.sqrt(np.abs(eigh(k, m, eigvals_only=True))) / (2 * math.pi)
    clamped = np.sqrt(eigh(k[1:, 1:], m[1:, 1:], eigvals_only=True)) / (2 * math.pi)
    lay = Layout.of(loop)
    got_clamped = [x.frequency_Hz for x in modal_analysis(lay, "clamped_input", duration_s=0.3).modes]
    got_free = [x.frequency_Hz for x in modal_analysis(lay, "free", duration_s=0.3).modes]
    assert_allclose(got_clamped, clamped, rtol=1e-9)
    assert_allclose(got_free[1:], free[1:], rtol=1e-9)
    assert got_free[0] == 0.0
