"""A speed sweep through a resonance of a two-stage helical reducer with a motor rotor on a coupling.

The scene (written for this test, not a shipped config): stage 1 21/67, m_n 2.5, beta 15 deg, x1 = 0.25, b 40/36;
stage 2 20/61, m_n 4, beta 12 deg, x1 = 0.3, b 60/55; steel discs; a motor rotor (0.05 kg m^2) on a coupling of
5000 N m/rad and 0.2 N m s/rad; a 4 um first-harmonic transmission error on stage 1; 600 N m constant load.

By hand (rigid meshes, the speed-driven motor clamped): solid discs J = rho pi b d_m^4 / 32 with
d_m ~ d + 2 m_n x - 0.25 m_n (d = z m_n / cos beta; the mean of tip and root diameters of an ISO 53 rack profile),
J_e = J_p1 + (J_g1 + J_p2) / i1^2 + J_g2 / (i1 i2)^2 = 4.634e-3 kg m^2, f = sqrt(k / J_e) / 2 pi = 165.3 Hz,
crossed by the stage-1 mesh order 21 n / 60 at n = 472 rpm. The meshes' compliance (1.6 % of the mode's strain
energy) lowers it by about 1 %: `gearcli modes` must lie within 2 % of the hand figure, and the dynamic factor
and the F_t std of the speed sweep must peak there (the vertex of the parabola through the three highest points).
"""

from __future__ import annotations

import csv
import io
import json
import math

import pytest
from click.testing import CliRunner

from gearcli.cli import cli

SCENE = """
title = "two-stage helical, motor rotor on a coupling, TE on stage 1"
[materials.steel]
density_kg_m3 = 7850
youngs_modulus_MPa = 2.06e5
poisson_ratio = 0.3
[[stage]]
normal_module_mm = 2.5
normal_pressure_angle_deg = 20
helix_angle_deg = 15
pinion = { teeth = 21, face_width_mm = 40, hand = "left",  material = "steel", profile_shift = 0.25 }
gear   = { teeth = 67, face_width_mm = 36, hand = "right", material = "steel" }
mesh = { transmission_error_um = [4.0] }
[[stage]]
normal_module_mm = 4
normal_pressure_angle_deg = 20
helix_angle_deg = 12
pinion = { teeth = 20, face_width_mm = 60, hand = "right", material = "steel", profile_shift = 0.3 }
gear   = { teeth = 61, face_width_mm = 55, hand = "left",  material = "steel" }
[input]
speed_rpm = 1000
ramp_s = 0.05
inertia_kg_m2 = 0.05
coupling_stiffness_Nm_rad = 5000
coupling_damping_Nms_rad = 0.2
[load]
torque_Nm = 600
ramp_s = 0.05
[simulation]
duration_s = 0.15
steps = 2000
"""


def _disc(z: int, m: float, beta_deg: float, x: float, b_mm: float) -> float:
    d = z * m / math.cos(math.radians(beta_deg))
    d_m = d + 2 * m * x - 0.25 * m
    return 7850 * math.pi * b_mm * 1e-3 * (d_m * 1e-3) ** 4 / 32


def hand_frequency_Hz() -> float:
    i1, i2 = 67 / 21, 61 / 20
    j_e = _disc(21, 2.5, 15, 0.25, 40) + (_disc(67, 2.5, 15, 0, 36) + _disc(20, 4, 12, 0.3, 60)) / i1**2 \
        + _disc(61, 4, 12, 0, 55) / (i1 * i2) ** 2
    return math.sqrt(5000 / j_e) / (2 * math.pi)


@pytest.fixture(scope="module")
def scene(tmp_path_factory):
    path = tmp_path_factory.mktemp("resonance") / "two_stage_motor_te.toml"
    path.write_text(SCENE)
    return path


def _rows(text: str) -> list[dict]:
    return list(csv.DictReader(io.StringIO("".join(line for line in text.splitlines(True) if not line.startswith("#")))))


def test_the_dynamic_factor_peaks_where_the_mesh_order_meets_the_coupling_mode(scene, tmp_path):
    assert hand_frequency_Hz() == pytest.approx(165.3, abs=0.1)  # the figure in the docstring
    res = CliRunner().invoke(cli, ["modes", str(scene), "--format", "json"])
    assert res.exit_code == 0, res.stderr
    f_modes = json.loads(res.stdout)["boundaries"]["clamped_input"][0]["frequency_Hz"]
    assert f_modes == pytest.approx(hand_frequency_Hz(), rel=0.02)  # mesh compliance: about 1 % below rigid
    out = tmp_path / "speed.csv"
    res = CliRunner().invoke(cli, ["sweep", str(scene), "--vary", "input.speed_rpm=440:500:7", "--jobs", "1",
                                   "--set", 'simulation.steady="periodic"', "-o", str(out)])
    assert res.exit_code == 0, res.stderr
    rows = _rows(out.read_text())
    speeds = [float(r["input.speed_rpm"]) for r in rows]
    assert speeds == [440, 450, 460, 470, 480, 490, 500]
    for column in ("stage1_tangential_N_std", "stage1_dynamic_factor"):
        y = [float(r[column]) for r in rows]
        k = max(range(1, len(y) - 1), key=y.__getitem__)
        assert y[k] == max(y)
        vertex = speeds[k] + 10 * (y[k - 1] - y[k + 1]) / (2 * (y[k - 1] - 2 * y[k] + y[k + 1]))
        assert vertex == pytest.approx(60 * f_modes / 21, rel=0.01), column  # within a quarter of a 10 rpm step
        assert vertex == pytest.approx(60 * hand_frequency_Hz() / 21, rel=0.025), column


def test_a_steep_linear_flank_swept_down_is_not_marked_as_a_jump(scene):
    # 460 -> 440 rpm continued: the DTE rms falls by 60 % (a linear resonance's flank, no contact loss); the
    # refinement must follow the branch to 440 rpm instead of reporting that it ends just below 460 rpm
    res = CliRunner().invoke(cli, ["sweep", str(scene), "--vary", "input.speed_rpm=440,460", "--direction", "down",
                                   "--jobs", "1"])
    assert res.exit_code == 0, res.stderr
    rows = _rows(res.stdout)
    assert [(r["input.speed_rpm"], r["direction"]) for r in rows] == [("460", "down"), ("440", "down")]
    assert float(rows[1]["stage1_dte_um_rms"]) < 0.6 * float(rows[0]["stage1_dte_um_rms"])
    assert all(float(r["stage1_contact_loss_fraction"]) == 0.0 for r in rows)
    assert not any("jump" in r["message"] for r in rows), rows[1]["message"]


@pytest.mark.slow  # ~7 s: a continued sweep over the resonance
def test_a_continued_point_is_not_judged_as_a_start_from_rest(scene):
    # 5000 -> 50000 N m/rad continued: the point starts from the previous point's state with the ramps off (the
    # sweep's rule), so summary.start (a start from rest against the rigid start) does not apply to it
    res = CliRunner().invoke(cli, ["sweep", str(scene), "--vary", "input.coupling_stiffness_Nm_rad=5000,50000",
                                   "--direction", "up", "--jobs", "1"])
    assert res.exit_code == 0, res.stderr
    rows = _rows(res.stdout)
    assert not any("start's peak" in r["message"] or "ramp_s" in r["message"] for r in rows), rows[1]["message"]
    # by hand: F_t1 = T_L / (i1 i2) / r_1 = 600 / (67/21 * 61/20) / (21 * 2.5 / cos 15 deg / 2000) = 2268.9 N
    f_t = 600 / (67 / 21 * 61 / 20) / (21 * 2.5 / math.cos(math.radians(15)) / 2000)
    assert [float(r["stage1_tangential_N_mean"]) for r in rows] == pytest.approx([f_t, f_t], rel=2e-3)


RANDOM = ["--samples", "6", "--random", "stage.0.mesh.transmission_error_um.0=normal(4,0.8)",
          "--random", "load.torque_Nm=uniform(500,700)", "--set", "simulation.duration_s=0.1"]


def _without_wall(rows: list[dict]) -> list[dict]:
    return [{k: v for k, v in r.items() if k != "wall_s"} for r in rows]


def test_a_tolerance_study_draws_the_documented_latin_hypercube_and_runs_alike_everywhere(scene, tmp_path):
    """The drawn seed is said and recorded; the draws are scipy's LatinHypercube(seed=default_rng(seed)) mapped by
    the inverse CDFs (docs/sweeps.md), one per stratum; each row's F_t mean is its own torque's, by hand; --jobs 1,
    --jobs 2 and a Dask cluster on the loopback give the same rows bit for bit (but wall_s)."""
    import numpy as np
    from scipy.stats import norm, qmc

    distributed = pytest.importorskip("distributed")
    one = tmp_path / "one.csv"
    res = CliRunner().invoke(cli, ["sweep", str(scene), *RANDOM, "--jobs", "1", "-o", str(one)])
    assert res.exit_code == 0, res.stderr
    header = json.loads(one.read_text().splitlines()[0][len("# gearcli sweep: "):])
    seed = header["sweep"]["seed"]
    assert f"samples drawn with --seed {seed}" in res.stderr
    rows = _rows(one.read_text())
    u = qmc.LatinHypercube(d=2, seed=np.random.default_rng(seed)).random(6)
    te = np.array([float(r["stage.0.mesh.transmission_error_um.0"]) for r in rows])
    torque = np.array([float(r["load.torque_Nm"]) for r in rows])
    np.testing.assert_array_equal(te, norm.ppf(u[:, 0], loc=4, scale=0.8))
    np.testing.assert_array_equal(torque, 500 + 200 * u[:, 1])
    assert sorted(np.floor(norm.cdf(te, 4, 0.8) * 6).astype(int)) == list(range(6))  # one per stratum
    assert sorted(np.floor((torque - 500) / 200 * 6).astype(int)) == list(range(6))
    r_1 = 21 * 2.5 / math.cos(math.radians(15)) / 2000
    np.testing.assert_allclose([float(r["stage1_tangential_N_mean"]) for r in rows],
                               torque / (67 / 21 * 61 / 20) / r_1, rtol=2e-3)  # window mean, lossless
    two = tmp_path / "two.csv"
    res = CliRunner().invoke(cli, ["sweep", str(scene), *RANDOM, "--seed", str(seed), "--jobs", "2", "-o", str(two)])
    assert res.exit_code == 0, res.stderr
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False, host="127.0.0.1",
                                  protocol="tcp://", dashboard_address=None) as cluster:
        assert cluster.scheduler_address.startswith("tcp://127.0.0.1:")
        dask = tmp_path / "dask.csv"
        res = CliRunner().invoke(cli, ["sweep", str(scene), *RANDOM, "--seed", str(seed), "--scheduler",
                                       cluster.scheduler_address, "-o", str(dask)])
        assert res.exit_code == 0, res.stderr
    first = one.read_text().splitlines()[0]
    assert two.read_text().splitlines()[0] == dask.read_text().splitlines()[0] == first
    assert _without_wall(_rows(two.read_text())) == _without_wall(rows) == _without_wall(_rows(dask.read_text()))


def test_plots_of_a_speed_sweep_with_a_failed_speed_leave_it_out_and_exit_1(scene, tmp_path):
    # 0 rpm is below the file's bounds: its row fails (exit 1), and the Campbell diagram is drawn from the others
    # instead of failing the whole command with exit 2 after the rows were written
    from gearcli.api import design_case
    from gearcli.sweep.modes import campbell
    from gearcli.sweep.worker import Scene

    points = campbell(Scene(SCENE.encode(), "scene.toml"), "input.speed_rpm", [0, 400], design_case)
    assert len(points) == 1 and points[0].value == 400 and points[0].input_rpm == pytest.approx(400, rel=1e-12)
    # by hand: stage 1 meshes at 21 x 400 / 60 = 140 Hz, stage 2 at 20 x (400 x 21/67) / 60 = 41.79 Hz
    assert points[0].mesh_Hz == pytest.approx((140.0, 20 * 400 * 21 / 67 / 60), rel=1e-9)
    assert points[0].natural_Hz[0] == pytest.approx(hand_frequency_Hz(), rel=0.02)
    plots = tmp_path / "p"
    res = CliRunner().invoke(cli, ["sweep", str(scene), "--vary", "input.speed_rpm=0,400", "--jobs", "1",
                                   "--set", "simulation.duration_s=0.1", "--plots", str(plots)])
    assert res.exit_code == 1, res.stderr
    assert "2 points, 1 failed" in res.stderr and "Traceback" not in res.stderr
    assert sorted(p.name for p in plots.iterdir()) == ["campbell.png", "response_input_speed_rpm.png"]


@pytest.mark.parametrize("vary", [("input.speed_rpm=400,500", "contact.time_varying=true,false"),
                                  ("stage.0.pinion.teeth=3,21", "input.speed_rpm=400,500")])
def test_the_campbell_diagram_holds_the_other_axes_at_a_value_that_designs(vary):
    # a boolean axis is set as TOML (true, not Python's True); an axis before the speed's is held too, at its
    # first value that designs (teeth = 3 is a failed row, 21 the file's)
    from gearcli.api import design_case
    from gearcli.sweep.modes import sweep_campbell
    from gearcli.sweep.spec import spec_from_options
    from gearcli.sweep.worker import Scene

    spec = spec_from_options(vary, (), None, "lhs", None, None)
    got = sweep_campbell(spec, Scene(SCENE.encode(), "scene.toml"), design_case, lambda cfg: ("rpm", "Nm"))
    assert got is not None
    assert got.swept_rpm == pytest.approx((400.0, 500.0), rel=1e-12)
