"""A sweep point's post-processing shortcuts of the tenth session (issue 33 item 3) give the numbers of the long way,
bit for bit: the method choice's excited vibration from the chain's memoised modal data against the loop it replaced
(written out here), the resonance check on the method choice's full-load tangents against the check on its own, the
energy watch's one-sample energy against the sampled energies at that state, and the rigid start's peak search
through ``fminbound`` against ``minimize_scalar(method="bounded")``."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from gearcli import api
from gearcli.model import TorsionalModel, outputs
from gearcli.model import modes as modes_mod
from gearcli.simulate import choice as choice_mod
from gearcli.simulate import rigid_start

ROOT = Path(__file__).resolve().parents[2]
# Hertz meshes behind a speed drive (the seed), couplings and a motor inertia, a planetary stage, lossy meshes with a
# load law, an unloaded rattling train (a Hertz mesh without stiffness at full load), time-varying meshes with a
# transmission error, a torque-driven motor start
SCENES = ("concrete_mixer", "concrete_mixer_drivetrain", "planetary_stage", "lossy_reducer",
          "extreme/rattle_zero_load", "concrete_mixer_te", "motor_direct_start")


def _model(name: str, *sets: str) -> TorsionalModel:
    loaded, design = api.load_and_design(str(ROOT / "configs" / f"{name}.toml"), list(sets))
    return TorsionalModel(api.model_spec(loaded.design, design))


def _loop(spec, lay, lin, duration_s: float, rtol: float) -> float:
    """The excited vibration P as ``vibration_radians`` worked it out before its modal data were memoised: the
    chain's eigenproblem solved anew, every mode in ascending order (module text of gearcli.simulate.choice)."""
    first = 1 if lay.speed_drive else 0
    if lay.n_bodies - first < 1:
        return 0.0
    R = choice_mod.speed_map(lay, range(first, lay.n_bodies))
    J = np.asarray(lay.inertias[first:], dtype=float)
    inv_sqrt = 1.0 / np.sqrt(J)
    exciting = np.array([x.element.self_exciting(x.params) for x in lay.connectors], dtype=bool)
    k, c = np.asarray(lin.stiffness, dtype=float), np.asarray(lin.damping, dtype=float)
    w2, u = np.linalg.eigh(inv_sqrt[:, None] * (R.T @ (k[:, None] * R)) * inv_sqrt[None, :])
    phi = inv_sqrt[:, None] * u
    top = max(float(np.max(np.abs(w2))), np.finfo(float).tiny)
    best = 0.0
    for j in range(w2.size):
        if w2[j] <= 1e-9 * top:
            continue
        omega = math.sqrt(w2[j])
        d = R @ phi[:, j]
        strain = k * d**2
        share = float(strain[exciting].sum() / strain.sum()) if strain.sum() > 0 else 0.0
        if share < choice_mod.SELF_EXCITING_SHARE and choice_mod._ramp_excitation(spec, omega) < rtol:
            continue
        sigma = float(c @ d**2) / (2.0 * float(J @ phi[:, j] ** 2))
        span = duration_s if sigma <= 0 else min(duration_s, choice_mod.DECAY_TIMES / sigma)
        best = max(best, omega * span)
    return best


@pytest.mark.parametrize("name", SCENES)
def test_the_excited_vibration_from_the_memoised_modes_is_the_loops(name):
    choice_mod._CHAIN_MODES.clear()
    found = []
    for rpm in (300.0, 900.0, 1500.0):  # the same chain at three speeds: the memo's entry is shared from the second
        model = _model(name, f"input.speed_rpm={rpm!r}") if "motor" not in name else _model(name)
        spec, lay = model.spec, model.layout
        ch = choice_mod.choose_method(spec, 0.5, "auto", 1e-6, layout=lay)
        lin = ch.at_operating_point if bool(np.any(ch.at_full_load.stiffness == 0.0)) else ch.at_full_load
        for duration_s, rtol in ((0.5, 1e-6), (4.0, 1e-3), (0.01, 1e-9)):
            got = choice_mod.vibration_radians(spec, lay, lin, duration_s, rtol)
            assert got == _loop(spec, lay, lin, duration_s, rtol)  # equal, not close: it prices the run
            found.append(got)
    assert any(v > 0 for v in found)  # the comparison is not of zeros only


@pytest.mark.parametrize("name", SCENES)
@pytest.mark.parametrize("rpm", [150.0, 900.0])
def test_the_resonance_check_on_the_choices_tangents_is_the_check_on_its_own(name, rpm):
    sets = () if "motor" in name else (f"input.speed_rpm={rpm!r}",)
    model = _model(name, *sets)
    lay = model.layout
    ch = choice_mod.choose_method(model.spec, 0.5, "auto", 1e-6, layout=lay)
    full = (ch.at_full_load.stiffness, ch.at_full_load.damping)
    quick = modes_mod.resonances(lay, ch.boundary, full_load=full)
    modes_mod._CHAINS.clear()
    fresh = _model(name, *sets).layout  # its own tangents, its own eigenproblem
    assert quick == modes_mod.resonances(fresh, ch.boundary)
    k, cd = modes_mod.connector_tangents(fresh, 1.0)
    if not np.any(full[0] == 0.0):  # the premise: the same tangents, bit for bit
        assert np.array_equal(k, full[0]) and np.array_equal(cd, full[1])
    else:  # an unloaded Hertzian mesh: the check takes the run-up's tangents of its own
        assert np.any(k != full[0])


def test_the_resonance_check_on_the_choices_tangents_still_warns():
    # the seed at 150 rpm: its mesh orders meet three modes (the comparison above is not of empty lists only)
    model = _model("concrete_mixer", "input.speed_rpm=150.0")
    ch = choice_mod.choose_method(model.spec, 0.5, "auto", 1e-6, layout=model.layout)
    found = modes_mod.resonances(model.layout, ch.boundary,
                                 full_load=(ch.at_full_load.stiffness, ch.at_full_load.damping))
    assert len(found) == 3


@pytest.mark.parametrize("name", SCENES)
def test_the_energy_watchs_one_sample_energy_is_the_sampled_energys(name, laws):
    """``stored_energy`` at one state: the kinetic energy plus every constant-stiffness connector's stored energy,
    the sums ``sample`` and the energy balance make of that one sample (the same laws, the same order)."""
    model = _model(name)
    lay = model.layout
    rng = np.random.default_rng(3)
    for t in (0.0, 0.07, 2.0):  # at rest, in the ramps, past them
        y = model.initial_state()
        y[lay.state.deflections] = model.deflection_scales() * rng.uniform(-0.5, 2.0, lay.n_conn)
        s = outputs.sample(lay, np.array([t]), y[:, None])
        expected = float(outputs.kinetic_energy(lay, s.omega_rad_s)[0]) \
            + float(outputs.potential_energy(lay, s, time_varying=False)[0])
        assert outputs.stored_energy(lay, t, y) == expected
        assert expected > 0.0


@pytest.mark.parametrize(("name", "sets"), [("concrete_mixer", ()), ("fan_drive", ()), ("mixer_planetary_motor", ()),
                                            ("concrete_mixer", ("load.ramp_s=0",))])
def test_the_peak_search_is_minimize_scalars_bounded_search(monkeypatch, name, sets):
    """The rigid start's refined peaks through ``fminbound`` equal those of ``minimize_scalar(method="bounded")``
    with the same tolerance (the search the peaks were refined by before), every stage, every digit."""
    import scipy.optimize as so

    from gearcli.model.assembly import Layout
    from gearcli.scene import spec_from_design

    loaded = api.load(str(ROOT / "configs" / f"{name}.toml"), list(sets))
    lay = Layout.of(spec_from_design(loaded.design, api.design(loaded)))
    now = rigid_start.integrate(lay, 0.5).peak_tangential_N
    searches = []

    def minimize_scalars(func, x1, x2, xtol, full_output, disp):
        assert full_output and disp == 0
        res = so.minimize_scalar(func, bounds=(x1, x2), method="bounded", options={"xatol": xtol})
        searches.append(res.nfev)
        return res.x, res.fun, res.status, res.nfev

    monkeypatch.setattr(so, "fminbound", minimize_scalars)
    before = rigid_start.integrate(lay, 0.5).peak_tangential_N
    assert len(searches) == len(now) and all(n > 3 for n in searches)  # a search per stage, several evaluations each
    assert now == before
