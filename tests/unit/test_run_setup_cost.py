"""A run's set-up computes the same numbers the long way does (issue 33): the rigid chain's peak forces of a model
without ramps (a continued sweep point's) from one sample against the 801 samples, the linearisation's eigenvalue
bounds kept against fresh ones, a model's state scales kept against fresh ones, two models in a row, and a continued
start state (set without the cold start it overwrites) against the rule by hand."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_allclose

from gearcli.model import TorsionalModel
from gearcli.model.linear import linearise, peak_rigid_forces, rigid_forces, static_forces

SEED = Path(__file__).resolve().parents[2] / "configs" / "concrete_mixer.toml"
NO_RAMPS = ("input.ramp_s=0.0", "load.ramp_s=0.0")


def _model(*overrides: str, path: Path = SEED) -> TorsionalModel:
    from gearcli import api

    loaded, design = api.load_and_design(str(path), overrides)
    return TorsionalModel(api.model_spec(loaded.design, design))


@pytest.fixture(scope="module")
def models() -> dict[str, TorsionalModel]:
    return {"ramped": _model(), "continued": _model(*NO_RAMPS, "input.speed_rpm=1100"),
            "heavier": _model(*NO_RAMPS, "load.torque_Nmm=9e6")}


def test_without_ramps_the_peak_rigid_forces_are_the_static_load_path(models):
    # no ramp: no run-up acceleration, the load acts in full from t = 0, so every connector of the rigid chain
    # carries its static force all along: the peak over the span is that force, the 801 samples' own maximum
    for name in ("continued", "heavier"):
        lay = models[name].layout
        peak = peak_rigid_forces(lay, 3.0)
        whole = np.max(np.abs(rigid_forces(lay, np.linspace(0.0, 3.0, 801))), axis=1)
        assert np.array_equal(peak, whole)
        assert_allclose(peak, np.abs(static_forces(lay)), rtol=1e-12)
    # the heavier load's chain carries 9e6 / 5.31e6 times the forces: the key is the layout's own
    ratio = models["heavier"].spec.load.torque_Nm / models["continued"].spec.load.torque_Nm
    assert_allclose(peak_rigid_forces(models["heavier"].layout, 3.0),
                    ratio * peak_rigid_forces(models["continued"].layout, 3.0), rtol=1e-12)


def test_with_ramps_the_run_up_adds_its_inertia_forces(models):
    # a ramped run-up accelerates the chain: its peak exceeds the static forces, found over the samples as before
    lay = models["ramped"].layout
    peak = peak_rigid_forces(lay, 3.0)
    end = max(lay.drive.ramp_s, lay.load.ramp_s)
    assert np.array_equal(peak, np.max(np.abs(rigid_forces(lay, np.linspace(0.0, end, 801))), axis=1))
    assert np.all(peak >= np.abs(static_forces(lay)) * (1.0 - 1e-12))


def test_the_eigenvalue_bounds_are_those_of_each_linearisation(models):
    # two different chains' linearisations in a row: each keeps its own bounds, those of its eigenvalues
    for name in ("continued", "heavier", "continued"):
        lay = models[name].layout
        lin = linearise(lay, np.abs(static_forces(lay)))
        mags = np.abs(lin.eigenvalues)
        assert lin.max_abs_eigenvalue == float(mags.max())
        assert lin.min_abs_eigenvalue == float(mags[mags > 0].min())
        assert lin.max_abs_eigenvalue == lin.max_abs_eigenvalue  # (kept: read again)


def test_the_tolerances_scale_each_models_own_states(models):
    # atol = rtol x the state's scale: a mesh's static deflection (its force over its stiffness, floored), a body's
    # nominal speed; two models of other loads and speeds in a row, each at two tolerances
    for name in ("continued", "heavier", "ramped", "continued"):
        model = models[name]
        st = model.layout.state
        for rtol in (1e-6, 1e-8):
            atol = model.atol(rtol)
            assert np.array_equal(atol[st.deflections], rtol * model.deflection_scales())
            assert np.array_equal(atol[st.speeds], rtol * model.speed_scales_rad_s())
    slow, fast = models["ramped"], models["continued"]  # 1100 rpm against the seed's own input speed
    ratio = fast.spec.drive.speed_rad_s / slow.spec.drive.speed_rad_s
    assert_allclose(fast.atol(1e-6)[fast.layout.state.speeds], ratio * slow.atol(1e-6)[slow.layout.state.speeds],
                    rtol=1e-12)
    lay = models["heavier"].layout
    heavier, lighter = models["heavier"].atol(1e-6), models["continued"].atol(1e-6)
    assert np.all(heavier[lay.state.deflections] > lighter[lay.state.deflections])  # more load, more deflection



@pytest.mark.parametrize("scene", ["seed", "planetary"])
def test_a_continued_state_keeps_the_deflections_and_moves_the_rigid_speeds(scene, tmp_path):
    # the docstring's rule by hand: each deflection as the previous run left it, each free body's speed its new
    # rigid speed plus its vibration about the old one, the quadratures 0; a planetary with a position error (whose
    # cold start is its rest deflections, not 0) keeps the previous deflections too
    if scene == "seed":
        prev, new = _model(*NO_RAMPS), _model(*NO_RAMPS, "input.speed_rpm=1100")
    else:
        from tests.reference import test_planetary_worst_planet as worst  # a 5 um position error on planet 2

        path = tmp_path / "planetary.toml"
        path.write_text(worst.SCENE)
        prev, new = _model(*NO_RAMPS, path=path), _model(*NO_RAMPS, "input.speed_rpm=450", path=path)
        assert np.any(new.initial_state()[new.layout.state.deflections] != 0.0)  # the position error's rest state
    lay, st = new.layout, new.layout.state
    rng = np.random.default_rng(7)
    y_prev = rng.uniform(-1.0, 1.0, st.n_states)
    y = new.continue_state(y_prev, prev, 0.0)
    assert np.array_equal(y[st.deflections], y_prev[st.deflections])
    w_prev, w_new = prev.spec.drive.speed_rad_s, new.spec.drive.speed_rad_s
    for i in lay.free_bodies:
        ratio = lay.bodies[i].ratio
        assert_allclose(y[st.omega(i)], ratio * w_new + (y_prev[st.omega(i)] - ratio * w_prev), rtol=0, atol=1e-12)
    assert np.all(y[st.quadratures] == 0.0)


def test_the_energy_scale_is_each_chains_own_and_follows_a_replaced_law(models, monkeypatch):
    # the scale is the rigid chain's kinetic energy at speed plus each connector's energy at its static force; the
    # latter is kept by the element's laws, parameters and force: computed afresh (memo emptied) and kept (filled by
    # the other chains first) it is the same, chain by chain
    from gearcli.simulate import guards

    fresh = {}
    for name in models:
        guards._STATIC_POTENTIALS.clear()
        fresh[name] = guards._nominal_scale(models[name].layout)
    for name in ("heavier", "continued", "ramped", "heavier"):
        assert guards._nominal_scale(models[name].layout) == fresh[name]
    def kinetic(lay) -> float:  # of the rigid chain at its nominal speed, by hand
        return 0.5 * sum(J * (b.ratio * lay.drive.speed_rad_s) ** 2 for J, b in zip(lay.inertias, lay.bodies,
                                                                                strict=True))

    elastic = {name: fresh[name] - kinetic(models[name].layout) for name in models}
    assert elastic["heavier"] > 1.5 * elastic["continued"] > 0.0  # 9e6 against 5.31e6 N mm: more load, more energy
    assert elastic["ramped"] == pytest.approx(elastic["continued"], rel=1e-12)  # the same load at another speed
    # a law replaced (twice the potential) is another key: the elastic part doubles, the kinetic part stays
    lay = models["continued"].layout
    law = lay.connectors[0].element
    potential = law.potential
    monkeypatch.setattr(law, "potential", lambda P, d, phase: 2.0 * potential(P, d, phase))
    assert_allclose(guards._nominal_scale(lay) - kinetic(lay), 2.0 * elastic["continued"], rtol=1e-9)
