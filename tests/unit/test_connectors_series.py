"""The output sampling's one compiled call for every connector (``gearcli.engine.kernel.connectors_series``, the law
arguments made inside it) against the elements' own scalar laws in Python (the reference the compiled laws are
checked against) and, bit for bit, against the compiled laws called a connector at a time; its repeated constant tail
(``sample``'s ``constant_from``) against every sample evaluated. Scenes: phased and excited meshes (transmission
error, time-varying stiffness), couplings, three-body planet meshes and a motor drive."""

from __future__ import annotations

from dataclasses import fields
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("numba")

from gearcli import api, engine  # noqa: E402
from gearcli.model import TorsionalModel, outputs  # noqa: E402
from gearcli.model.outputs import ConnectorSeries, sample  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
SCENES = ("concrete_mixer_te", "conveyor", "mixer_time_varying_backlash", "mixer_planetary_motor",
          "concrete_mixer_drivetrain", "conveyor_motor")
NAMES = [f.name for f in fields(ConnectorSeries)]


@pytest.fixture(scope="module")
def kernel():
    if not engine.available():
        pytest.skip("the compiled engine is not installed")
    engine.load(quiet=True)
    return outputs._loaded_kernel()


def _scene(name: str, samples: int = 400, seed: int = 3):
    """The scene's model and ``samples`` states scattered about its static deflections and nominal speeds over its
    ramps and past them (angles, where the scene has an angle state, advancing)."""
    loaded, design = api.load_and_design(str(ROOT / "configs" / f"{name}.toml"), [])
    model = TorsionalModel(api.model_spec(loaded.design, design))
    lay = model.layout
    rng = np.random.default_rng(seed)
    t = np.linspace(0.0, 2.0 * max(lay.drive.ramp_s, lay.load.ramp_s, 0.05), samples)
    y = model.initial_state()
    y[lay.state.deflections] = model.deflection_scales() * rng.uniform(-0.5, 2.0, lay.n_conn)
    Y = np.repeat(y[:, None], t.size, axis=1)
    n = lay.state.n_mechanical
    Y[:n] *= 1.0 + 0.05 * rng.standard_normal((n, t.size))
    if lay.state.i_theta is not None:
        Y[lay.state.i_theta] = rng.uniform(0.0, 50.0) * t
    return lay, t, Y


def _one_at_a_time(lay, t, Y, energy_from: int = 0, compiled: bool = True):
    """Every connector's series by ``outputs._connector_series``, one call each (compiled laws or scalar ones)."""
    omega, theta, _ = outputs.body_motion(lay, t, Y)
    kernel = outputs._loaded_kernel() if compiled else None
    return [outputs._connector_series(lay, c, Y, omega, theta, kernel, energy_from) for c in range(lay.n_conn)]


@pytest.mark.parametrize("name", SCENES)
def test_one_call_for_every_connector_is_each_connectors_own_call_bit_for_bit(name, kernel):
    lay, t, Y = _scene(name)
    assert outputs._compiled_all(lay, kernel)
    got = sample(lay, t, Y, energy_from=7)
    for c, (a, b) in enumerate(zip(got.connectors, _one_at_a_time(lay, t, Y, 7), strict=True)):
        for f in NAMES:
            assert np.array_equal(getattr(a, f), getattr(b, f), equal_nan=True), (c, f)


@pytest.mark.parametrize("name", SCENES)
def test_the_models_arrays_as_the_connector_rows_give_the_same_series(name, kernel):
    """``sample(..., arrays=model.arrays)``: the compiled call's rows read from the model's arrays (parameter rows
    zero-padded to N_PARAM, a spring's shorter row too) give each connector's own call's numbers bit for bit, on a
    fresh layout (no rows kept from a call without them); and on a second model in a row, its own numbers."""
    lay, t, Y = _scene(name)
    for model in (TorsionalModel(lay.spec), TorsionalModel(lay.spec)):
        arrays = model.arrays
        assert "_series_rows" not in model.layout.__dict__
        got = sample(model.layout, t, Y, energy_from=5, arrays=arrays)
        assert model.layout.__dict__["_series_rows"][1] is arrays.conn_param  # read, not built again
        for c, (a, b) in enumerate(zip(got.connectors, _one_at_a_time(model.layout, t, Y, 5), strict=True)):
            for f in NAMES:
                assert np.array_equal(getattr(a, f), getattr(b, f), equal_nan=True), (c, f)
    other, t2, Y2 = _scene("conveyor" if name != "conveyor" else "concrete_mixer_te")
    model = TorsionalModel(other.spec)
    got = sample(model.layout, t2, Y2, arrays=model.arrays)  # another scene's model next: its own rows
    for c, (a, b) in enumerate(zip(got.connectors, _one_at_a_time(other, t2, Y2), strict=True)):
        for f in NAMES:
            assert np.array_equal(getattr(a, f), getattr(b, f), equal_nan=True), (c, f)


@pytest.mark.parametrize("name", SCENES)
def test_one_call_for_every_connector_is_the_elements_scalar_laws(name, kernel):
    """The independent reference: each element's force, energy and channels in Python, sample by sample."""
    lay, t, Y = _scene(name, samples=120)
    got = sample(lay, t, Y)
    for c, (a, b) in enumerate(zip(got.connectors, _one_at_a_time(lay, t, Y, compiled=False), strict=True)):
        for f in NAMES:
            x, y = getattr(a, f), getattr(b, f)
            np.testing.assert_allclose(x, y, rtol=1e-12, atol=1e-12 * max(1.0, float(np.max(np.abs(y)))),
                                       err_msg=f"connector {c} {f}")
    assert any(np.any(cs.force != 0.0) for cs in got.connectors)  # the scene is loaded: no trivial zeros compared


@pytest.mark.parametrize("laws", ["compiled", "python"], indirect=True)
@pytest.mark.parametrize("name", ["concrete_mixer", "planetary_stage", "concrete_mixer_drivetrain"])
def test_a_constant_tail_evaluated_once_is_every_sample_evaluated(name, laws):
    """``constant_from``: the state held from sample k on gives, at every later sample, what evaluating it gives."""
    lay, t, Y = _scene(name)
    k = 250
    Y[:, k + 1:] = Y[:, k:k + 1]
    for torques in (True, False):
        held, whole = sample(lay, t, Y, torques=torques, energy_from=k, constant_from=k), \
            sample(lay, t, Y, torques=torques, energy_from=k)
        assert np.array_equal(held.omega_rad_s, whole.omega_rad_s)
        assert np.array_equal(held.input_torque_Nm, whole.input_torque_Nm)
        assert np.array_equal(held.load_torque_Nm, whole.load_torque_Nm)
        for a, b in zip(held.connectors, whole.connectors, strict=True):
            for f in NAMES:
                assert np.array_equal(getattr(a, f), getattr(b, f), equal_nan=True), f
                assert getattr(a, f).shape == t.shape


@pytest.mark.parametrize("name", SCENES)
def test_a_law_at_every_sample_is_the_law_sample_by_sample(name, kernel):
    """``conn_forces`` and ``conn_channels`` (the sampling's laws at every sample, the kind chosen once) against the
    element's own scalar law in Python at each sample (the independent reference, to round-off) and, bit for bit,
    against the one-sample dispatch ``conn_force`` / ``conn_channel`` the kernel called at each sample before."""
    from gearcli.engine import kernel as k  # lazy: imports numba (the fixture has loaded it)

    lay, t, Y = _scene(name, samples=150)
    omega, theta, _ = outputs.body_motion(lay, t, Y)
    seen, loaded = set(), False
    for c, x in enumerate(lay.connectors):
        d, dd, phi, wphi = (np.ascontiguousarray(v, dtype=float) for v in outputs._law_arguments(lay, c, Y, omega, theta))
        P = np.asarray(x.params, dtype=float)
        got = np.full(d.size, np.nan)
        k.conn_forces(x.kind, P, d, dd, phi, wphi, got)
        one = [k.conn_force(x.kind, P, d[j], dd[j], phi[j], wphi[j])[0] for j in range(d.size)]
        assert np.array_equal(got, np.array(one)), c
        ref = np.array([x.element.force(P, d[j], dd[j], phi[j], wphi[j])[0] for j in range(d.size)])
        np.testing.assert_allclose(got, ref, rtol=1e-12, atol=1e-12 * max(1.0, float(np.max(np.abs(ref)))))
        for i in range(len(x.element.CHANNELS)):
            chan = np.full(d.size, np.nan)
            k.conn_channels(x.kind, P, i, d, phi, chan)
            assert np.array_equal(chan, np.array([k.conn_channel(x.kind, P, i, d[j], phi[j]) for j in range(d.size)]))
            ref = np.array([x.element.channel(P, i, d[j], phi[j]) for j in range(d.size)])
            np.testing.assert_allclose(chan, ref, rtol=1e-12, atol=1e-12 * max(1.0, float(np.max(np.abs(ref)))))
        seen.add(x.kind)
        loaded = loaded or bool(np.any(got != 0.0))
    assert seen and loaded  # connectors checked, with forces that are not all zero
