"""Two planetary stages in a row keep the losses of the second in the first's reference force.

A lossy planetary straight after another one (21/30/81 x3 then 40/20/80 x5, both ring held and sun driven,
eta 0.98 and 0.97): the first stage's sun–planet force is the output torque brought back through *both* stages'
ratios and efficiencies, by hand

    T_sun,2 = T_L / (i_2 eta_2),   T_sun,1 = T_sun,2 / (i_1 eta_1),   F_t,k = T_sun,k / (N_k r_s,k),
    i_k = 1 + z_r,k / z_s,k  (Willis, ring held),

and an unexcited settled run's window is flat at those forces, so its dynamic factor (max |F_t| over the static
F_t of the losses the simulation models, DESIGN §8) is 1 and the iso6336 law's tangent at the run's static load
is ISO's k_n (DESIGN §13). The first stage's reference used to miss the second stage's 1/eta (0.98 low: a
dynamic factor of 1.0204 on a flat window, and the linearised stiffness 0.98^(1/3) off ISO's).
"""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

M1, M2 = 3.0, 4.0
Z1 = (21, 30, 81)
Z2 = (40, 20, 80)
N1, N2 = 3, 5
ETA1, ETA2 = 0.98, 0.97
T_L = 3000.0  # N m on the second carrier


def stage(m: float, z: tuple[int, int, int], count: int, eta: float, b: float) -> str:
    """A spur planetary stage, ring held, sun driven."""
    return (f'[[stage]]\ntype = "planetary"\nnormal_module_mm = {m}\nefficiency = {eta}\n'
            f"sun = {{ teeth = {z[0]}, face_width_mm = {b} }}\n"
            f"planet = {{ teeth = {z[1]}, face_width_mm = {b - 2}, count = {count} }}\n"
            f"ring = {{ teeth = {z[2]}, face_width_mm = {b - 2} }}\n"
            'fixed = "ring"\ninput = "sun"\n')


SCENE = ('title = "two planetaries in a row"\n' + stage(M1, Z1, N1, ETA1, 40) + stage(M2, Z2, N2, ETA2, 70)
         + f"[input]\nspeed_rpm = 1480\nramp_s = 0.1\n[load]\ntorque_Nm = {T_L}\nramp_s = 0.1\n"
         "[simulation]\nduration_s = 0.4\nsteps = 800\n")


def hand_sun_forces_N() -> list[float]:
    i1, i2 = 1 + Z1[2] / Z1[0], 1 + Z2[2] / Z2[0]
    t_sun2 = T_L / (i2 * ETA2)
    t_sun1 = t_sun2 / (i1 * ETA1)
    r_s1, r_s2 = M1 * Z1[0] / 2 / 1000, M2 * Z2[0] / 2 / 1000  # spur: m_t = m_n, m
    return [t_sun1 / (N1 * r_s1), t_sun2 / (N2 * r_s2)]


@pytest.fixture(scope="module")
def summary(tmp_path_factory):
    path = tmp_path_factory.mktemp("pp") / "pp.toml"
    path.write_text(SCENE)
    res = CliRunner().invoke(cli, ["simulate", str(path), "--format", "json", "-q"], catch_exceptions=False)
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)["summary"]


def test_the_static_reference_carries_both_stages_losses(summary):
    hand = hand_sun_forces_N()
    ref = [st["simulated_static_tangential_N"] for st in summary["stages"]]
    assert_allclose(ref, hand, rtol=1e-9)
    assert_allclose([st["static_tangential_N"] for st in summary["stages"]], hand, rtol=1e-9)


def test_a_flat_window_has_dynamic_factor_one(summary):
    hand = hand_sun_forces_N()
    for st, f in zip(summary["stages"], hand, strict=True):
        assert_allclose(st["tangential_N"]["mean"], f, rtol=1e-6)  # the conservation of the mean
        assert_allclose(st["dynamic_factor"], 1.0, atol=1e-6)


def test_the_law_is_linearised_at_the_runs_static_load(summary):
    for st in summary["stages"]:
        ms = st["mesh_stiffness"]
        assert_allclose(ms["linearised_N_mm"], ms["iso_N_mm"], rtol=1e-9)
