"""`gearcli report`'s theory for a motor drive: the motor's operating point, recomputed by hand.

Scene: one helical stage (m_n 3 mm, z 21/83, β 14°, η 0.985) on a 7.5 kW two-pole induction motor (3000 rpm
synchronous, rated 2940 rpm, breakdown 3.0, locked rotor 2.5 x rated torque), direct start, 80 N·m at the output. The
motor does not run at its rated 2940 rpm: it carries 80 / (i η) = 20.55 N·m < T_r = 24.36 N·m and slips less. The
extended Kloss curve of docs/physics.md is rebuilt here from the nameplate (a from the locked-rotor point, s_b from
the rated point) and crossed with the reflected load by a root finder: 2951.83 rpm with a constant load, and with a
quadratic (fan) load T_L (n/n_0)^2 a little lower and at a larger torque. The report's theory must be that steady
state, so the error column shows the simulation's departure from it (before: +0.40 % in every speed, and +0.77 % in
F_t for the fan load, all of it the motor's slip, not the simulation).
"""

from __future__ import annotations

import math

import pytest
from numpy.testing import assert_allclose
from scipy.optimize import brentq

from gearcli import api

SCENE = """
title = "one helical stage on an induction motor, direct start"
materials.st = { density_kg_m3 = 7850, youngs_modulus_MPa = 2.1e5, poisson_ratio = 0.3 }
simulation = { duration_s = 1.2, steps = 3000 }
load = { torque_Nm = 80, inertia_kg_m2 = 1.5, coupling_stiffness_Nm_rad = 6e4, coupling_damping_Nms_rad = 20 }
[[stage]]
normal_module_mm = 3
normal_pressure_angle_deg = 20
helix_angle_deg = 14
efficiency = 0.985
pinion = { teeth = 21, face_width_mm = 45, hand = "left",  material = "st" }
gear   = { teeth = 83, face_width_mm = 40, hand = "right", material = "st" }
[input]
motor = { rated_power_kW = 7.5, rated_speed_rpm = 2940, synchronous_speed_rpm = 3000, breakdown_torque_ratio = 3.0, locked_rotor_torque_ratio = 2.5 }
drive = "motor"
starting = "direct"
speed_rpm = 2940
inertia_kg_m2 = 0.012
coupling_stiffness_Nm_rad = 1.5e4
coupling_damping_Nms_rad = 2
"""

Z1, Z2, ETA, M_N, BETA, ALPHA_N = 21, 83, 0.985, 3.0, math.radians(14.0), math.radians(20.0)
N_S, N_R, P_R, K_B, K_L, T_OUT = 3000.0, 2940.0, 7500.0, 3.0, 2.5, 80.0


def kloss_operating_point(exponent: int) -> tuple[float, float]:
    """Motor speed [rpm] and output torque [N·m] where the extended Kloss curve meets the reflected load."""
    t_r, s_r = P_R / (N_R * math.pi / 30.0), 1.0 - N_R / N_S

    def a_of(sb: float) -> float:  # the curve through the locked-rotor point T(1) = k_l T_r (linear in a)
        return (K_L * (1 + sb * sb) - 2 * K_B * sb) / (2 * sb * sb * (K_B - K_L))

    def torque(s: float, sb: float) -> float:
        a = a_of(sb)
        return 2 * K_B * t_r * (1 + a * sb) * s * sb / (s * s + sb * sb + 2 * a * sb * sb * abs(s))

    sb = brentq(lambda sb: torque(s_r, sb) - t_r, s_r * 1.0001, 0.999)  # through the rated point
    i = Z2 / Z1
    n_out0 = N_R / i  # the load's torque is given at the nominal output speed

    def load_out(n_motor: float) -> float:
        return T_OUT * (n_motor / i / n_out0) ** exponent

    s = brentq(lambda s: torque(s, sb) - load_out(N_S * (1 - s)) / (i * ETA), 1e-9, sb)
    return N_S * (1 - s), load_out(N_S * (1 - s))


@pytest.fixture(scope="module", params=[0, 2])
def case(request, tmp_path_factory):
    path = tmp_path_factory.mktemp("motor") / "motor.toml"
    path.write_text(SCENE, encoding="utf-8")
    loaded = api.load(str(path), [f"load.speed_exponent={request.param}"])
    return request.param, api.report_file(loaded, api.design(loaded), quick=True)


def _rows(rep) -> dict:
    return {(r.stage, r.quantity): r for r in rep.comparison}


def test_theory_speeds_are_the_motors_operating_point(case):
    exponent, rep = case
    n_motor, _ = kloss_operating_point(exponent)
    assert n_motor > N_R + 5.0  # lighter than rated: the motor slips less than its nameplate (no tautology)
    rows = _rows(rep)
    assert_allclose(rows[(None, "input_speed_deg_s")].theory, 6.0 * n_motor, rtol=1e-7)
    assert_allclose(rows[(None, "output_speed_deg_s")].theory, 6.0 * n_motor * Z1 / Z2, rtol=1e-7)
    assert_allclose(rows[(1, "output_speed_deg_s")].theory, 6.0 * n_motor * Z1 / Z2, rtol=1e-7)
    # the settled simulation meets it (its window mean; before, the error column read +0.40 %: the slip)
    for key in ((None, "input_speed_deg_s"), (None, "output_speed_deg_s")):
        assert abs(rows[key].error_percent) < 0.01
    assert rep.theory_point is not None and rep.theory_point.drive == "motor"


def test_theory_forces_are_at_the_operating_load(case):
    exponent, rep = case
    _, t_out = kloss_operating_point(exponent)
    d1 = Z1 * M_N / math.cos(BETA)  # pinion pitch diameter [mm]
    alpha_t = math.atan(math.tan(ALPHA_N) / math.cos(BETA))
    f_t = t_out * 1e3 / (Z2 / Z1 * ETA) / (d1 / 2)  # T_pinion / r_1, the pinion torque with the mesh's loss
    rows = _rows(rep)
    assert_allclose(rows[(1, "tangential_N")].theory, f_t, rtol=1e-7)
    assert_allclose(rows[(1, "radial_N")].theory, f_t * math.tan(alpha_t), rtol=1e-7)
    assert_allclose(rows[(1, "axial_N")].theory, f_t * math.tan(BETA), rtol=1e-7)
    assert abs(rows[(1, "tangential_N")].error_percent) < 0.02  # the fan load's +0.77 % was the slip, not the run
