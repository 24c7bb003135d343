"""Phased meshes anywhere in a train mixed from planetary and parallel stages (the wind-turbine-like gearbox:
planetary 19/17/56, planetary 18/36/93, both carrier-driven with the ring held, then the 95:24 helical stage).

Every mesh takes its phase from the angle of its own input body. A body the tree of two-body connectors does
not reach (a planetary's output member) gets its angle from the kinematics of the planet meshes that join it
to its input member: with the ring held and the carrier driving, theta_sun = (1 + z_r/z_s) theta_carrier
(Willis) when the meshes are undeflected. So a transmission error on the parallel stage excites it at
z_pinion x its shaft's speed, n_3 = n_rotor (1 + 56/19) (1 + 93/18) (Willis by hand, both stages), and one on
the second planetary's meshes at z_s (n_sun - n_carrier) of that stage.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from gearcli.config.load import load_design
from gearcli.design import compute_design
from gearcli.io.channels import named
from gearcli.model.equations import TorsionalModel
from gearcli.scene import spec_from_design
from gearcli.simulate import run_simulation

GEARBOX = "configs/wind_turbine_gearbox.toml"
N_ROTOR_HZ = 12.127 / 60.0
N2_HZ = N_ROTOR_HZ * (1 + 56 / 19)  # stage 1 sun = stage 2 carrier
N3_HZ = N2_HZ * (1 + 93 / 18)  # stage 2 sun = the parallel stage's 95-tooth pinion
WINDOW_S = 0.3


def _load(*settings: str):
    return load_design(GEARBOX, list(settings)).design


def _run(*settings: str):
    cfg = _load("simulation.duration_s=0.6", "simulation.steps=12000", f"simulation.window_start_s={WINDOW_S}",
                *settings)
    return run_simulation(cfg, compute_design(cfg))


def _peak_hz(sim, channel: str, band=(0.0, math.inf)) -> float:
    """The frequency of the largest spectral line of a channel over the window within ``band`` (Hz) (Hann
    window, the DFT zero-padded to ~2 mHz bins, so a clean line is located far inside its 3 Hz resolution)."""
    t = sim.time_s
    x = named(sim)[channel][t >= WINDOW_S]
    x = (x - x.mean()) * np.hanning(x.size)
    n = 1 << 21
    spec = np.abs(np.fft.rfft(x, n))
    f = np.fft.rfftfreq(n, t[1] - t[0])
    inside = (f >= band[0]) & (f <= band[1])
    return float(f[inside][np.argmax(spec[inside])])


def test_the_output_member_angle_follows_willis():
    """The rigid-body angles the rows give (every deflection zero, theta_rotor = 1): theta_out = (1 + z_r/z_s)
    theta_in per stage, and the parallel stage's pinion turns with the second sun."""
    lay = TorsionalModel(spec_from_design(cfg := _load(), compute_design(cfg))).layout
    theta = [1.0] + [math.nan] * (lay.n_bodies - 1)
    for b in range(1, lay.n_bodies):
        c = lay.tree[b]
        if c >= 0:
            x = lay.connectors[c]
            theta[b] = x.ra * theta[x.a] / x.rb
        elif b in lay.angle_rows:
            row = lay.angle_rows[b]
            theta[b] = sum(k * theta[j] for j, k in row.bodies) + row.constant
    suns = [b for b, body in enumerate(lay.bodies) if body.label in ("shaft 2", "shaft 3")]
    assert suns and all(lay.tree[b] < 0 for b in suns)  # no two-body connector reaches a sun
    assert_allclose([theta[b] for b in suns], [1 + 56 / 19, (1 + 56 / 19) * (1 + 93 / 18)], rtol=1e-12)
    parallel = lay.connectors[lay.stage_conn[2]]
    assert parallel.a == suns[1]
    assert_allclose(theta[-1], N3_HZ / N_ROTOR_HZ * 95 / 24, rtol=1e-12)  # the generator shaft


@pytest.mark.parametrize("engine", ["python", "compiled"])
def test_a_transmission_error_after_two_planetary_stages_excites_at_its_own_mesh_frequency(engine):
    if engine == "compiled":
        pytest.importorskip("numba")
    sim = _run("stage.2.mesh.transmission_error_um=[2.0]", f"simulation.engine={engine}")
    assert sim.solver.engine == engine
    # the largest line within -20 % / +25 % of the mesh frequency (under the default ISO law the ramp also rings
    # the train's 45.5 Hz mode, 0.55 % damped, far below the TE's line)
    f_mesh = 95 * N3_HZ
    assert_allclose(_peak_hz(sim, "stage3_tangential_N", (0.8 * f_mesh, 1.25 * f_mesh)), f_mesh, rtol=2e-5)
    assert sim.energy.residual_relative < 1e-6


def test_compiled_and_python_agree_after_the_planetary_stages():
    pytest.importorskip("numba")
    py = _run("stage.2.mesh.transmission_error_um=[2.0]", "simulation.engine=python", "simulation.method=DOP853")
    cc = _run("stage.2.mesh.transmission_error_um=[2.0]", "simulation.engine=compiled", "simulation.method=DOP853")
    a, b = named(py)["stage3_tangential_N"], named(cc)["stage3_tangential_N"]
    assert_allclose(b, a, rtol=0, atol=1e-6 * np.abs(a).max())


def test_a_transmission_error_on_the_second_planetary_excites_at_its_mesh_frequency():
    """The second planetary's meshes are phased on its carrier, itself the first stage's output member (an
    internal error before): mesh frequency z_s |n_sun - n_carrier| = 18 (N3 - N2), the largest line within
    -20 % / +25 % of it (the ramp rings the train's 27 Hz mode and its harmonic far above the TE's response)."""
    sim = _run("stage.1.mesh.transmission_error_um=[2.0]")
    f_mesh = 18 * (N3_HZ - N2_HZ)
    assert math.isclose(f_mesh, 93 * N2_HZ, rel_tol=1e-12)  # = z_r n_carrier with the ring held
    band = (0.8 * f_mesh, 1.25 * f_mesh)
    # within 2e-3 (0.15 Hz, 5 % of the window's 3 Hz resolution): the leakage of the ringing mode's harmonics moves
    # the line's maximum by a few hundredths of a hertz (0.04 Hz once the planets' masses were their bodies')
    assert_allclose(_peak_hz(sim, "stage2_planet1_sun_tangential_N", band), f_mesh, rtol=2e-3)
    # the line is the TE's: without it the band holds no line there
    base = _run()
    assert abs(_peak_hz(base, "stage2_planet1_sun_tangential_N", band) / f_mesh - 1) > 5e-3


def test_jacobians_with_angles_from_the_planet_kinematics():
    """The phase of the parallel mesh and of the second planetary's meshes depends on the planet meshes'
    deflections through the output members' angle rows: the generated Jacobian against central differences,
    and the compiled kernel's against the generated one, at states along a run."""
    import sys
    from pathlib import Path

    from gearcli.simulate.solver import integrate

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "unit"))
    from test_model_equations import fd_jacobian

    # the seed's Hertz stiffness (the scene's law before the default became ISO's): with ISO's stiffer planet
    # meshes the central differences themselves carry ~2e-6 of noise at these states
    cfg = _load("stage.1.mesh.transmission_error_um=[2.0]", "stage.2.mesh.transmission_error_um=[3.0]",
                "stage.2.mesh.time_varying=true", "contact.damping_ratio=0.1", "contact.stiffness=hertz")
    model = TorsionalModel(spec_from_design(cfg, compute_design(cfg)))
    lay = model.layout
    assert {c for row in lay.angle_rows.values() for c, _ in row.deflections}  # the rows read deflections
    t_eval = np.array([0.25, 0.3, 0.35])
    run = integrate(model, np.linspace(0.0, 0.35, 8), "DOP853", 1e-8)
    ys = run.y[:, -3:]
    for j, t in enumerate(t_eval):
        y = ys[:, j]
        Ja, Jf = model.jac(float(t), y), fd_jacobian(model, float(t), y)
        scale = np.abs(Jf).max(axis=1, keepdims=True) + 1e-300
        assert_allclose(Ja / scale, Jf / scale, atol=1e-6)
        # the generator shaft meets only the parallel mesh: its acceleration depends on a stage-1 planet mesh's
        # deflection through that mesh's phase alone
        generator = lay.i_omega(lay.n_bodies - 1)
        assert Ja[generator, 0] != 0.0 and abs(Ja[generator, 0] - Jf[generator, 0]) <= 1e-6 * abs(Jf[generator]).max()
    pytest.importorskip("numba")
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "engine"))
    from test_radau import assert_kernel_jacobian

    from gearcli import engine

    assert_kernel_jacobian(engine.load(quiet=True).kernel, model, np.linspace(0.0, 0.35, 8)[-3:], ys, rtol=1e-12)
