"""Radau on a time-varying contact length (gearcli/simulate/solver.py, ``contact_step``): the stiffness of a spur
pair steps between one and two tooth pairs, and an implicit method's three collocation nodes may all fall on one
side of a step. A spur pair at 6 rpm (2 Hz mesh, mode 1.8 kHz: quasi-static) was stepped over in 0.5 s steps that
never met the single-pair stretch: the window mean F_t came out 1293.6 N against the static 1428.6 N (9.5 % low)
and the gear's deflection never doubled there. The reference is the hand calculation: over whole mesh periods the
mean tooth force carries the load, F_t = T_L / r_2 = 100 N m / 70 mm; the deflection in the single-pair stretch is
twice the double-pair one (K L(phi) / L_mean with L = 1 and 2 pairs).
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner

from gearcli.cli import cli
from gearcli.model.contact_lines import shortest_stretch

SCENE = (
    'title = "quasi-static spur pair, time-varying contact length"\n'
    "stage = [{ normal_module_mm = 4, normal_pressure_angle_deg = 20, "
    "pinion = { teeth = 20, face_width_mm = 30, inertia_kg_m2 = 0.002 }, "
    "gear = { teeth = 35, face_width_mm = 30, inertia_kg_m2 = 0.01 } }]\n"
    "contact = { stiffness = 3e5, exponent = 1, damping_ratio = 0.1, time_varying = true }\n"
    "input = { speed_rpm = 6, ramp_s = 0.05 }\nload = { torque_Nm = 100, ramp_s = 0.05 }\n"
    # the window 0.2 .. 2.2 s holds 4 whole mesh periods of 0.5 s (20 teeth at 6 rpm)
    "simulation = { duration_s = 2.2, steps = 22000, window_start_s = 0.2, method = \"Radau\" }\n")
STATIC_N = 100.0 / 0.070  # T_L / r_2, r_2 = 35 x 4 mm / 2


@pytest.mark.parametrize(("eps_alpha", "eps_beta", "stretch"), [
    (1.62, 0.0, 0.38),  # spur: two-pair stretch 0.62, single-pair 0.38 of a cycle
    (1.95, 0.0, 0.05),
    (1.6, 0.3, 0.1),  # kinks at 0, 0.4, 0.3, 0.7: stretches 0.3, 0.1, 0.3, 0.3
    (1.5, 1.0, 1.0),  # an integer overlap ratio: L constant
])
def test_the_shortest_stretch_between_the_kinks_of_the_contact_length(eps_alpha, eps_beta, stretch):
    assert shortest_stretch(eps_alpha, eps_beta) == pytest.approx(stretch, abs=1e-12)


@pytest.mark.parametrize("engine_name", ["python", "compiled"])
def test_radau_meets_every_single_pair_stretch_of_a_slow_spur_pair(tmp_path, engine_name):
    if engine_name == "compiled":
        pytest.importorskip("numba")
    path = tmp_path / "slow_spur.toml"
    path.write_text(SCENE)
    res = CliRunner().invoke(cli, ["simulate", str(path), "--format", "json", "--series", "-q",
                                   "--set", f'simulation.engine="{engine_name}"'])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    assert doc["solver"]["method"] == "Radau"
    mean = doc["summary"]["stages"][0]["tangential_N"]["mean"]
    assert abs(mean - STATIC_N) <= 2e-4 * STATIC_N  # was 1293.6 N
    s = doc["series"]
    t, dte = np.array(s["time_s"]), np.array(s["stage1_dte_um"])
    window = dte[(t >= 0.2) & (t <= 2.2)]
    # the deflection in the single-pair stretch is twice the double-pair one: both levels are met every period
    low, high = np.percentile(window, 10), np.percentile(window, 90)
    assert high == pytest.approx(2.0 * low, rel=1e-3)
