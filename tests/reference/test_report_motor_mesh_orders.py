"""`gearcli report`'s mesh lines for a motor drive: where the motor runs, not at its nameplate speed.

Scene: tests/reference/test_report_motor_theory.py's single helical stage (z 21/83) on a 7.5 kW two-pole induction
motor, direct start, 80 N·m at the output, with a 5 µm first-harmonic transmission error on the mesh. The motor
carries 80 / (i η) = 20.55 N·m, less than its rated 24.36 N·m, and runs at 2951.83 rpm (the extended Kloss curve of
docs/physics.md crossed with the reflected load, rebuilt by hand in that test), not at `[input] speed_rpm = 2940`:
the mesh turns at 21 x 2951.83 / 60 = 1033.14 Hz, not 1029 Hz. The report took its spectrum's mesh frequency and
mesh orders at 1029 Hz, 4 bins of its settled 0.96 s window off the line, where the Hann-weighted projection of F_t
read 0.04 N of the line's 88.4 N. Reference here: the line's amplitude by least squares (cos, sin, mean, trend)
at the hand-computed frequency over the same window samples.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from gearcli import api
from gearcli.core.channels import Channel
from tests.reference.test_report_motor_theory import SCENE, Z1, kloss_operating_point

TE_SCENE = SCENE.replace('gear   = { teeth = 83, face_width_mm = 40, hand = "right", material = "st" }',
                         'gear   = { teeth = 83, face_width_mm = 40, hand = "right", material = "st" }\n'
                         'mesh   = { transmission_error_um = [5.0] }').replace("steps = 3000", "steps = 12000")


@pytest.fixture(scope="module")
def rep(tmp_path_factory):
    assert TE_SCENE != SCENE
    path = tmp_path_factory.mktemp("motor_te") / "motor_te.toml"
    path.write_text(TE_SCENE, encoding="utf-8")
    loaded = api.load(str(path))
    return api.report_file(loaded, api.design(loaded), quick=True)


def _line_amplitude(t: np.ndarray, x: np.ndarray, f_Hz: float) -> float:
    """Amplitude of the sinusoid at f_Hz in x(t), by least squares beside a mean and a linear trend."""
    a = np.column_stack([np.cos(2 * math.pi * f_Hz * t), np.sin(2 * math.pi * f_Hz * t), np.ones_like(t), t - t[0]])
    c = np.linalg.lstsq(a, x, rcond=None)[0]
    return float(math.hypot(c[0], c[1]))


def test_mesh_frequency_is_the_motors_operating_point(rep):
    n_motor, _ = kloss_operating_point(0)
    f_mesh = Z1 * n_motor / 60.0  # 1033.14 Hz (1029 Hz at the nameplate's 2940 rpm)
    sp = rep.stages[0].spectrum
    assert_allclose(sp.mesh_frequency_Hz, f_mesh, rtol=2e-5)
    assert_allclose(sp.mesh_orders[0].frequency_Hz, f_mesh, rtol=2e-5)
    assert sp.matches == "mesh frequency"


def test_first_mesh_order_is_the_lines_amplitude(rep):
    n_motor, _ = kloss_operating_point(0)
    f_mesh = Z1 * n_motor / 60.0
    sim = rep.simulation
    t = np.asarray(sim.time_s)
    mask = (t >= sim.window_s[0] - 1e-9) & (t <= sim.window_s[1] + 1e-9)
    force = np.asarray(sim.series[Channel("tangential_force", "stage1")])[mask]
    reference = _line_amplitude(t[mask], force, f_mesh)
    assert reference > 1.0  # the TE drives a line of some newtons
    assert_allclose(rep.stages[0].spectrum.mesh_orders[0].tangential_N, reference, rtol=1e-3)
