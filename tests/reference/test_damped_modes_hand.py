"""The damped modes a run reports (``extra["damped_modes"]``: the frequencies at which the linearised chain rings,
which ``report`` names a force spectrum's peak by when the undamped modes miss it) against a hand-assembled
two-degree-of-freedom model.

Scene (tr12b): one spur stage 20/60, m_n 3, b 30, its pinion held by the speed drive (600 rpm), the gear (0.05
kg m²) on an undamped linear mesh (exponent 1, damping_ratio 0: k = ISO's k_n), a drum of 2 kg m² on a 2e4 N·m/rad
coupling, and a load proportional to speed (2000 N·m at 200 rpm): a viscous damper c = T0/ω0 = 95.5 N·m·s/rad on the
drum, to ground. Hand model: J_g θg'' = −k r_bg² θg − k_c (θg − θd), J_d θd'' = k_c (θg − θd) − c θd'. Its drum mode
rings at f_d = 13.5 Hz with ζ ≈ 0.24, 3 % below its undamped 13.9 Hz: a report that knew only the undamped
frequencies named such a ringing "none" (a DOL conveyor's drum against its motor's slip damping: 8.9 Hz against an
undamped free 13.8 Hz).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.testing import assert_allclose

from gearcli import api
from gearcli.report.spectrum import name_peak

SCENE = """
contact = { exponent = 1.0, damping_ratio = 0 }
input = { speed_rpm = 600, ramp_s = 0.05 }
load = { torque_Nm = 2000, speed_exponent = 1, ramp_s = 0.05, inertia_kg_m2 = 2.0, coupling_stiffness_Nm_rad = 2.0e4 }
simulation = { duration_s = 0.2, steps = 400 }
[[stage]]
normal_module_mm = 3
pinion.teeth = 20
pinion.face_width_mm = 30
pinion.inertia_kg_m2 = 0.001
gear.teeth = 60
gear.face_width_mm = 30
gear.inertia_kg_m2 = 0.05
"""


def test_damped_modes_are_the_hand_models_eigenvalues(tmp_path):
    path = tmp_path / "drum.toml"
    path.write_text(SCENE)
    loaded, design = api.load_and_design(str(path), [])
    run = api.simulate(loaded.design, design)
    st = design.stages[0]
    k_mesh = st.mesh_stiffness.linearised_N_mm * 1000.0  # N/m along the line of action (spur: transverse)
    r_bg = st.gear.base_diameter_mm / 2000.0
    c = 2000.0 / (200.0 * math.pi / 30.0)  # dT/dω of the load law at the nominal output speed
    M = np.diag([0.05, 2.0])
    K = np.array([[k_mesh * r_bg ** 2 + 2.0e4, -2.0e4], [-2.0e4, 2.0e4]])
    C = np.array([[0.0, 0.0], [0.0, c]])
    A = np.block([[np.zeros((2, 2)), np.eye(2)], [-np.linalg.solve(M, K), -np.linalg.solve(M, C)]])
    lam = [z for z in np.linalg.eigvals(A) if z.imag > 0]
    hand = sorted((z.imag / (2 * math.pi), -z.real / abs(z)) for z in lam)
    assert_allclose(run.extra["damped_modes"], hand, rtol=1e-6)
    # the drum mode rings 3 % below its undamped frequency, as the docstring says
    drum_fd, drum_zeta = hand[0]
    undamped = run.natural_frequencies_Hz[0]
    assert_allclose(drum_fd / undamped, math.sqrt(1 - drum_zeta ** 2), rtol=0.01)
    assert drum_fd < 0.98 * undamped


def test_a_peak_is_named_by_a_damped_mode_only_where_no_undamped_line_matches():
    # a ringing at 8.9 Hz in a train whose undamped modes are 13.8 and 122.8 Hz (resolution 0.42 Hz: ±0.84 Hz)
    damped = [(8.9, 0.13), (120.5, 0.14)]
    assert name_peak(8.75, 0.42, 468.7, [13.8, 122.8], [], damped) == "damped mode 8.9 Hz (ζ 0.13)"
    assert name_peak(120.6, 0.42, 468.7, [13.8, 122.8], [], damped) == "damped mode 120.5 Hz (ζ 0.14)"
    # an undamped line (or a mesh line) that matches keeps its name, however near a damped mode is
    assert name_peak(122.4, 0.42, 468.7, [13.8, 122.8], [], [(122.3, 0.01)]) == "natural frequency 2"
    assert name_peak(468.5, 0.42, 468.7, [13.8, 122.8], [], [(468.6, 0.05)]) == "mesh frequency"
    # without damped modes, as before
    assert name_peak(8.75, 0.42, 468.7, [13.8, 122.8]) == "none"
