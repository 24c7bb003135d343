"""The explicit methods' step ceiling (docs/numerics.md, "The step ceiling"): a sweep point continued from its
neighbour's equilibrium starts at rest in every mode; without the ceiling DOP853 took its first steps 20x past its
stability limit there and its dense output swung by the amplified mode (a run-up factor of 5.4 reported for a run
that never leaves the static load)."""

from __future__ import annotations

import csv
import io
import math
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli
from gearcli.core.methods import method

ROOT = Path(__file__).resolve().parents[2]
SEED = ROOT / "configs" / "concrete_mixer.toml"


def _rows(text: str) -> list[dict[str, str]]:
    return list(csv.DictReader(io.StringIO("".join(line for line in text.splitlines(True)
                                                   if not line.startswith("#")))))


@pytest.mark.parametrize("engine", ["python", "compiled"])
def test_a_point_continued_from_equilibrium_stays_at_the_static_load(engine, tmp_path):
    if engine == "compiled":
        pytest.importorskip("numba")
    out = tmp_path / "up.csv"
    # 300 rpm starts cold (the file's ramps); 400 continues from 300's end and settles on its equilibrium; 500 then
    # starts exactly at rest: the seed's load is a constant torque and its drive a constant speed once the ramps are
    # gone, so the static deflections do not depend on the speed and nothing excites a mode
    res = CliRunner().invoke(cli, ["sweep", str(SEED), "--vary", "input.speed_rpm=300:500:3", "--direction", "up",
                                   "--set", f"simulation.engine={engine}", "--jobs", "1", "-o", str(out)])
    assert res.exit_code == 0, res.output
    rows = {float(r["input.speed_rpm"]): r for r in _rows(out.read_text())}
    at_rest = rows[500.0]
    assert at_rest["status"] == "ok"
    for k in (1, 2, 3):
        # no transient: the run's peak is the static force (to the run's tolerance, rtol 1e-6, with margin)
        assert_allclose(float(at_rest[f"stage{k}_runup_factor"]), 1.0, atol=1e-4)
        assert_allclose(float(at_rest[f"stage{k}_tangential_N_max"]), float(at_rest[f"stage{k}_tangential_N_mean"]),
                        rtol=1e-4)


def test_the_dop853_ceiling_is_its_stability_boundary_on_the_imaginary_axis():
    """The registry's radius, against |R(iy)| = 1 of DOP853's stability function, computed here from scipy's
    Butcher tableau: R(z) = 1 + z b^T (I - z A)^-1 1. The boundary is at y = 5.96; the radius sits inside it (it was
    6.0, where an undamped mode grows 7.7 % a step)."""
    from scipy.integrate._ivp import dop853_coefficients as c

    a, b = c.A[:12, :12], c.B

    def amplification(y: float) -> float:
        z = 1j * y
        return abs(1 + z * b @ np.linalg.solve(np.eye(12) - z * a, np.ones(12)))

    ys = np.linspace(0.5, 8.0, 3001)
    boundary = ys[np.argmax([amplification(y) > 1 + 1e-12 for y in ys])]
    radius = method("DOP853").stability_radius
    assert_allclose(radius, boundary, rtol=0.01)
    assert radius <= boundary and amplification(radius) <= 1.0
    assert amplification(6.0) > 1.07  # the radius it had
    assert amplification(20.0) > 1e6  # what a step 3x past it does to a mode at rest


def test_the_rk45_ceiling_is_inside_its_stability_boundary_on_the_imaginary_axis():
    """RK45's (Dormand-Prince 5(4), scipy's 5th-order weights) R(z) = 1 + z + z^2/2 + ... + z^5/120 + z^6/600 leaves
    the unit disc on the imaginary axis at y = 0.997, computed here from scipy's Butcher tableau; the ceiling was
    2.0, where an undamped mode at rest grows 3.2 % a step (e^32 over 1000 steps), unseen by the error estimate
    until it carries the tolerance. The radius sits within 1 % inside the boundary, where |R| <= 1."""
    from scipy.integrate._ivp.rk import RK45

    a = np.zeros((6, 6))
    a[:, :5] = RK45.A

    def amplification(y: float) -> float:
        z = 1j * y
        return abs(1 + z * RK45.B @ np.linalg.solve(np.eye(6) - z * a, np.ones(6)))

    ys = np.linspace(0.5, 4.0, 3501)
    boundary = ys[np.argmax([amplification(y) > 1 + 1e-12 for y in ys])]
    radius = method("RK45").stability_radius
    assert_allclose(radius, boundary, rtol=0.01)
    assert radius <= boundary and amplification(radius) <= 1.0
    # the closed form: the 6-stage 5th-order polynomial (its z^6 coefficient 1/600, not e^z's 1/720)
    assert_allclose(amplification(2.0), abs(sum((2j) ** k / math.factorial(k) for k in range(6)) + (2j) ** 6 / 600),
                    rtol=1e-12)
    assert amplification(2.0) > 1.03


def test_the_ceiling_is_the_radius_over_the_largest_eigenvalue_at_full_load():
    from gearcli.config import load_design
    from gearcli.design import compute_design
    from gearcli.model import linearise
    from gearcli.model.linear import static_forces
    from gearcli.scene import build_model
    from gearcli.simulate.solver import step_ceiling

    cfg = load_design(str(SEED), []).design
    model = build_model(cfg, compute_design(cfg))
    lay = model.layout
    lam = linearise(lay, static_forces(lay)).max_abs_eigenvalue
    assert_allclose(step_ceiling(model, "DOP853"), 5.95 / lam, rtol=1e-12)
    assert_allclose(step_ceiling(model, "RK45"), 0.99 / lam, rtol=1e-12)
    assert step_ceiling(model, "Radau") == math.inf
