"""The Campbell diagram of a load x speed grid says at which load it is drawn.

`gearcli sweep --vary load.torque_Nm=300,1340 --vary input.speed_rpm=... --plots DIR` draws one Campbell diagram,
at the other keys' first values that design (here 300 N m). Its title said only "linearised at full load", so the
modes drawn at 300 N m (mode 1 at 725 Hz: ISO 6336-1's mesh stiffness falls below F_t/b = 100 N/mm) read as the
file's full load, 1340 N m (871 Hz): the crossings 17 % off in speed. The title now names the point it shows.

By hand, the two-stage reducer below with its input speed-driven (clamped): shafts 2 (gear 1 + pinion 2) and 3
(gear 2) as solid discs of pitch diameter, J = rho pi b d^4 / 32; each mesh a spring c_gamma_alpha b along its
transverse line of action (ISO 6336-1's mesh stiffness at that load, from `gearcli design --set`, checked against
ISO elsewhere) on base radii r_b = d cos(alpha_t) / 2; the gear side of each mesh driven with eta = 0.98 of the
force (the stage efficiency in the dynamics, docs/physics.md): K = -sum L_j k_j G_j^T with
G_1 = (-r_b,g1, 0), L_1 = (eta r_b,g1, 0), G_2 = (r_b,p2, -r_b,g2), L_2 = (-r_b,p2, eta r_b,g2); f = sqrt(eig(M^-1 K)) / 2 pi.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner

from gearcli.cli import cli

SCENE = """
title = "two helical stages, TE on stage 1"
[materials.steel]
density_kg_m3 = 7850
youngs_modulus_MPa = 2.06e5
poisson_ratio = 0.3
[[stage]]
normal_module_mm = 3
normal_pressure_angle_deg = 20
helix_angle_deg = 12
efficiency = 0.98
pinion = { teeth = 19, face_width_mm = 50, hand = "left",  material = "steel", profile_shift = 0.30 }
gear   = { teeth = 75, face_width_mm = 45, hand = "right", material = "steel", profile_shift = -0.0108 }
mesh = { transmission_error_um = [3.0] }
[[stage]]
normal_module_mm = 5
normal_pressure_angle_deg = 20
helix_angle_deg = 12
efficiency = 0.98
pinion = { teeth = 19, face_width_mm = 80, hand = "right", material = "steel", profile_shift = 0.35 }
gear   = { teeth = 68, face_width_mm = 75, hand = "left",  material = "steel", profile_shift = 0.20 }
[input]
speed_rpm = 1450
ramp_s = 0.05
[load]
torque_Nm = 1340
ramp_s = 0.05
[simulation]
duration_s = 0.1
steps = 500
"""


def hand_modes_Hz(c_gamma_alpha_N_mm_um: tuple[float, float], b1_mm: float = 45.0) -> np.ndarray:
    """Clamped-input natural frequencies of the two free shafts, by hand (module docstring); ``b1_mm`` stage 1's
    gear width (the mesh's face width while it is under the pinion's 50 mm, and the gear's disc inertia)."""
    rho, eta = 7850.0, 0.98
    cos_b = math.cos(math.radians(12.0))
    alpha_t = math.atan(math.tan(math.radians(20.0)) / cos_b)

    def d_m(mn: float, z: int) -> float:  # pitch diameter, m
        return mn * z / cos_b / 1e3

    def disc(mn: float, z: int, b_mm: float) -> float:
        return math.pi * rho * (b_mm / 1e3) * d_m(mn, z) ** 4 / 32.0

    J2, J3 = disc(3, 75, b1_mm) + disc(5, 19, 80), disc(5, 68, 75)
    rg1, rp2, rg2 = (d_m(mn, z) / 2 * math.cos(alpha_t) for mn, z in ((3, 75), (5, 19), (5, 68)))
    k1, k2 = (c * 1e3 * 1e3 * b for c, b in zip(c_gamma_alpha_N_mm_um, (b1_mm, 75.0), strict=True))  # N/m, b the narrower
    G1, L1 = np.array([-rg1, 0.0]), np.array([eta * rg1, 0.0])
    G2, L2 = np.array([rp2, -rg2]), np.array([-rp2, eta * rg2])
    K = -(np.outer(L1, k1 * G1) + np.outer(L2, k2 * G2))
    lam = np.linalg.eigvals(np.linalg.solve(np.diag([J2, J3]), K))
    return np.sort(np.sqrt(lam.real)) / (2 * math.pi)


def c_gamma_alpha(scene, torque_Nm: float) -> tuple[float, float]:
    res = CliRunner().invoke(cli, ["design", str(scene), "--format", "json", "-q", "--set", f"load.torque_Nm={torque_Nm}"])
    assert res.exit_code == 0, res.output
    stages = json.loads(res.stdout)["stages"]
    return stages[0]["iso6336_mesh_stiffness_N_mm_um"], stages[1]["iso6336_mesh_stiffness_N_mm_um"]


def test_a_grids_campbell_diagram_is_drawn_at_the_first_load_and_says_so(tmp_path):
    from gearcli.api import design_case
    from gearcli.io.sweep_plots import _campbell
    from gearcli.sweep.modes import sweep_campbell
    from gearcli.sweep.spec import spec_from_options
    from gearcli.sweep.worker import Scene

    scene = tmp_path / "reducer.toml"
    scene.write_text(SCENE, encoding="utf-8")
    spec = spec_from_options(("load.torque_Nm=300,1340", "input.speed_rpm=1000,1400,1800"), (), None, "lhs", None, None)
    got = sweep_campbell(spec, Scene(SCENE.encode(), "reducer.toml"), design_case, lambda cfg: ("rpm", "Nm"))
    assert got is not None
    assert got.at == ("load.torque_Nm=300",)
    drawn = np.array(sorted(m.frequency_Hz for m in got.data.modes if not m.rigid))
    at_300, at_1340 = hand_modes_Hz(c_gamma_alpha(scene, 300)), hand_modes_Hz(c_gamma_alpha(scene, 1340))
    # the linear model is the hand one exactly (iso6336 calibrates the law's tangent to ISO's k_n at each load)
    np.testing.assert_allclose(drawn, at_300, rtol=1e-6)
    assert abs(at_1340[0] / at_300[0] - 1.0) > 0.1  # the loads are told apart: 871 Hz vs 725 Hz
    fig = _campbell(got)
    assert "at load.torque_Nm=300" in fig._suptitle.get_text()


@pytest.mark.parametrize("vary", [("input.speed_rpm=1000,1400",)])
def test_a_speed_only_sweep_keeps_its_plain_title(vary):
    from gearcli.api import design_case
    from gearcli.io.sweep_plots import _campbell
    from gearcli.sweep.modes import sweep_campbell
    from gearcli.sweep.spec import spec_from_options
    from gearcli.sweep.worker import Scene

    got = sweep_campbell(spec_from_options(vary, (), None, "lhs", None, None), Scene(SCENE.encode(), "r.toml"),
                         design_case, lambda cfg: ("rpm", "Nm"))
    assert got is not None and got.at == ()
    assert _campbell(got)._suptitle.get_text() == "Campbell diagram"


def test_a_tolerance_studys_campbell_diagram_is_drawn_at_a_sample_and_says_so(tmp_path):
    """A speed sweep with --random keys (tr28e): the diagram was drawn at the file's values (gear 1 45 mm wide),
    which no sample held (drawn from 20-30 mm), and its title named none of them; it is now drawn at the first
    sample, as a grid's other keys are at their first value, and its title names the sample."""
    from gearcli.api import design_case
    from gearcli.io.sweep_plots import _campbell
    from gearcli.sweep.modes import sweep_campbell
    from gearcli.sweep.spec import spec_from_options
    from gearcli.sweep.worker import Scene

    scene = tmp_path / "reducer.toml"
    scene.write_text(SCENE, encoding="utf-8")
    spec = spec_from_options(("input.speed_rpm=1000,1400,1800",), ("stage[0].gear.face_width_mm=uniform(20,30)",),
                             4, "lhs", 5, None)
    b = spec.branches()[0][0].values[1][1]  # the first sample's gear width
    assert isinstance(b, float) and 20.0 <= b < 30.0
    got = sweep_campbell(spec, Scene(SCENE.encode(), "reducer.toml"), design_case, lambda cfg: ("rpm", "Nm"))
    assert got is not None
    assert got.at == (f"stage[0].gear.face_width_mm={b!r}",)
    res = CliRunner().invoke(cli, ["design", str(scene), "--format", "json", "-q", "--set",
                                   f"stage.0.gear.face_width_mm={b!r}"])
    assert res.exit_code == 0, res.output
    c = tuple(s["iso6336_mesh_stiffness_N_mm_um"] for s in json.loads(res.stdout)["stages"])
    drawn = np.array(sorted(m.frequency_Hz for m in got.data.modes if not m.rigid))
    np.testing.assert_allclose(drawn, hand_modes_Hz(c, b), rtol=1e-6)
    assert abs(drawn[0] / hand_modes_Hz(c_gamma_alpha(scene, 1340))[0] - 1.0) > 0.03  # not the file's 45 mm gear
    assert f"at stage[0].gear.face_width_mm={b!r}" in _campbell(got)._suptitle.get_text()


def test_a_speed_that_is_no_number_fails_its_row_and_the_plots_are_drawn(tmp_path):
    """``--vary input.speed_rpm=1000,fast`` (tr28e; a typo such as ``1000,1400:2`` makes a text too): the text's row
    is a failed one and the sweep goes on (docs/sweeps.md), but ``--plots`` sorted the speeds as numbers and ended
    the command with an internal error (ValueError: could not convert string to float), no figure written. The
    Campbell diagram now leaves the text out, as it leaves out a speed whose design fails."""
    pytest.importorskip("matplotlib")
    from gearcli.api import design_case
    from gearcli.sweep.modes import sweep_campbell
    from gearcli.sweep.spec import spec_from_options
    from gearcli.sweep.worker import Scene

    scene, plots = tmp_path / "reducer.toml", tmp_path / "plots"
    scene.write_text(SCENE, encoding="utf-8")
    res = CliRunner().invoke(cli, ["-q", "sweep", str(scene), "--vary", "input.speed_rpm=1000,fast", "--jobs", "1",
                                   "--set", "simulation.duration_s=0.03", "-o", str(tmp_path / "s.csv"),
                                   "--plots", str(plots)])
    assert res.exit_code == 1 and "internal error" not in res.output, res.output  # 1: a failed row
    assert (plots / "campbell.png").exists() and (plots / "response_input_speed_rpm.png").exists()
    got = sweep_campbell(spec_from_options(("input.speed_rpm=1000,fast",), (), None, "lhs", None, None),
                         Scene(SCENE.encode(), "reducer.toml"), design_case, lambda cfg: ("rpm", "Nm"))
    assert got is not None and got.swept_rpm == (1000.0,)
    drawn = np.array(sorted(m.frequency_Hz for m in got.data.modes if not m.rigid))
    np.testing.assert_allclose(drawn, hand_modes_Hz(c_gamma_alpha(scene, 1340)), rtol=1e-6)  # at the file's load
