"""Motor drives, speed-dependent loads and lossy meshes: the generated Jacobian against central differences
(the regularised laws are smooth where the integrators step), the compiled kernel's right-hand side and
Jacobian against the generated ones, and a compiled run against scipy's."""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

import numpy as np
import pytest

from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.io.channels import named
from gearcli.model import TorsionalModel
from gearcli.scene import spec_from_design

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tests" / "unit"))
from test_model_equations import fd_jacobian  # noqa: E402

SCENES = {
    "fan_table_motor_quadratic_lossy": ("configs/fan_drive.toml", ()),
    "kloss_star_delta": ("configs/motor_star_delta.toml", ()),
    "kloss_soft_start": ("configs/motor_soft_start.toml", ()),
    "kloss_vfd_limited_linear_load": ("configs/motor_vfd.toml", ("load.speed_exponent=1",)),
    "lossy_speed_drive": ("configs/lossy_reducer.toml", ()),
    "load_table": ("configs/fan_drive.toml", ()),
}


def _model(name: str) -> TorsionalModel:
    path, sets = SCENES[name]
    file = ROOT / path
    if name == "load_table":  # the fan as a measured table (breakaway torque at standstill) instead of the law
        text = file.read_text().replace("torque_Nm = 1200\nspeed_exponent = 2\n",
                                        "torque_speed = [[0, 80], [40, 260], [80, 760], [110, 1380]]\n")
        assert "torque_speed = [[0, 80]" in text
        file = Path(tempfile.mkdtemp()) / "load_table.toml"
        file.write_text(text)
    try:
        cfg = load_design(str(file), sets).design
    finally:
        if name == "load_table":
            file.unlink()
    return TorsionalModel(spec_from_design(cfg, compute_design(cfg)))


def _states(model: TorsionalModel, rng) -> list[tuple[float, np.ndarray]]:
    """States at rest, mid-start and at speed, with loaded, unloaded and reversed meshes (power flowing
    either way through the lossy ones), at times inside and after the start ramps."""
    lay = model.layout
    out = []
    scales = model.deflection_scales()
    speeds = model.speed_scales_rad_s()
    for t, frac, sign in ((0.05, 0.3, 1.0), (0.4, 0.9, 1.0), (2.5, 1.0, -1.0), (0.7, 0.6, 0.3)):
        y = model.initial_state()
        y[:lay.n_conn] = sign * scales * (1.0 + 0.2 * rng.standard_normal(lay.n_conn))
        first = lay.n_conn
        y[first:first + len(lay.free_bodies)] = frac * speeds * (1.0 + 0.01 * rng.standard_normal(len(speeds)))
        out.append((t, y))
    return out


@pytest.mark.parametrize("name", SCENES)
def test_generated_jacobian_matches_central_differences(name):
    model = _model(name)
    rng = np.random.default_rng(3)
    for t, y in _states(model, rng):
        J = model.jac(t, y)
        F = fd_jacobian(model, t, y)
        np.testing.assert_allclose(J, F, rtol=2e-4, atol=2e-6 * np.abs(F).max())


@pytest.mark.parametrize("name", SCENES)
def test_kernel_equals_generated(name):
    from gearcli import engine

    pytest.importorskip("numba")
    kernel = engine.load(quiet=True).kernel
    model = _model(name)
    packed = engine.pack(model.arrays)
    assert not engine.unsupported(model.arrays, "DOP853")
    for t, y in _states(model, np.random.default_rng(5)):
        np.testing.assert_array_equal(kernel.evaluate(packed, t, y), model.rhs(t, y))  # bit for bit
        a = model.jac(t, y)
        np.testing.assert_allclose(kernel.evaluate_jacobian(packed, t, y), a, rtol=1e-12, atol=1e-14 * np.abs(a).max())


def test_compiled_run_equals_scipy_on_the_fan_drive():
    """DOP853 on both engines: the kernel takes scipy's steps (same evaluations, same samples)."""
    pytest.importorskip("numba")
    from gearcli.simulate.run import simulate_model

    model = _model("fan_table_motor_quadratic_lossy")
    runs = [simulate_model(model, duration_s=0.6, steps=600, method="DOP853", rtol=1e-6, engine=e,
                           error_estimate=False) for e in ("python", "compiled")]
    assert runs[1].solver.engine == "compiled"
    assert runs[0].solver.nfev == runs[1].solver.nfev
    for k in named(runs[0]):
        np.testing.assert_allclose(named(runs[1])[k], named(runs[0])[k], rtol=1e-12,
                                   atol=1e-12 * np.abs(named(runs[0])[k]).max(), err_msg=k)
