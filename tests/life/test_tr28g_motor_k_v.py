"""`gearcli life`'s dynamic K_v of a motor-driven point refers to the load the run applies, as simulate's dynamic factor.

Scene: tests/reference/test_report_motor_theory.py's single helical stage (z 21/83, m_n 3, β 14°, η 0.985) on a 7.5 kW
two-pole induction motor, direct start, with a fan load (speed_exponent 2) of 80 N·m at the nominal output speed, and
one duty point at that torque and the nameplate's 2940 rpm. No excitation: the settled window is the equilibrium, so
every engagement meets the steady force and the dynamic factor is 1 (DESIGN §8: max |F_t| over the static F_t at the
simulated load). The motor does not run at 2940 rpm but where its extended Kloss curve meets the reflected fan load
(rebuilt by hand in that test's ``kloss_operating_point``), ~0.4 % faster, where the fan's torque is (n / n_0)² of
80 N·m: the class force is F_t = T_L (n / n_0)² / (i η) / r_1 by hand. Over the point's design force (at 2940 rpm)
the life's K_v read (n / n_0)² = 1.008 on that quiet window, where `simulate` says 1.
"""

from __future__ import annotations

import math

import pytest
from numpy.testing import assert_allclose

from gearcli import api
from tests.reference.test_report_motor_theory import BETA, ETA, M_N, N_R, SCENE, T_OUT, Z1, Z2, kloss_operating_point

LIFE_SCENE = SCENE.replace(
    "materials.st = { density_kg_m3 = 7850, youngs_modulus_MPa = 2.1e5, poisson_ratio = 0.3 }",
    'materials.st = { density_kg_m3 = 7850, youngs_modulus_MPa = 2.1e5, poisson_ratio = 0.3, treatment = "case_carburized", '
    "contact_fatigue_limit_MPa = 1500, bending_fatigue_limit_MPa = 500 }\n"
    "lubricant = { viscosity_40C_mm2_s = 220 }\n"
    "rating = { required_life_h = 1000 }",
).replace("efficiency = 0.985", "efficiency = 0.985\naccuracy_grade = 6").replace(
    'material = "st" }', 'material = "st", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 12 }') + """
[[duty]]
name = "fan"
hours = 1000
torque_Nm = 80
speed_rpm = 2940
"""


@pytest.fixture(scope="module")
def life(tmp_path_factory):
    assert "treatment" in LIFE_SCENE and "accuracy_grade" in LIFE_SCENE
    path = tmp_path_factory.mktemp("motor_life") / "motor_life.toml"
    path.write_text(LIFE_SCENE, encoding="utf-8")
    return api.life(api.prepare_life(str(path), ["load.speed_exponent=2"]))


def _hand_force_N() -> float:
    n_motor, load_out = kloss_operating_point(2)  # the fan's torque at the motor's speed
    assert load_out > T_OUT * 1.005 and n_motor > N_R  # the motor runs ~0.4 % fast: the fan carries ~0.8 % more
    r_1 = Z1 * M_N / math.cos(BETA) / 2.0 / 1e3  # pinion pitch radius [m]
    return load_out / (Z2 / Z1) / ETA / r_1


def test_the_class_force_is_the_fans_torque_at_the_motors_speed(life):
    bins = life.stages[0].pinion.pitting.bins
    assert_allclose(max(b.force_N for b in bins), _hand_force_N(), rtol=2e-4)


def test_a_quiet_window_has_k_v_one(life):
    # the window settled to its 1 % criterion: a residual ringing of ~1e-4 of the force (the fan law moved 8e-3)
    assert_allclose(life.points[0].K_v[0], 1.0, atol=5e-4)
