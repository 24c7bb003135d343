"""What a sweep's points share, session 14 (issue 33 item 3): the resonance check's near modes kept with the chain's
eigenproblem (a mode without its crossings reads no speed) against the modes worked out cold at every point, and
against the modal analysis's own; speeds on one chain, its connectors renamed, its bodies' damping changed."""

from __future__ import annotations

from pathlib import Path

import pytest

from gearcli import api
from gearcli.model import TorsionalModel
from gearcli.model import modes as modes_mod

ROOT = Path(__file__).resolve().parents[2]


def _layout(name: str, *sets: str):
    loaded, design = api.load_and_design(str(ROOT / "configs" / f"{name}.toml"), list(sets))
    return TorsionalModel(api.model_spec(loaded.design, design)).layout


def _cold(name: str, *sets: str) -> list:
    modes_mod._CHAINS.clear()  # the eigenproblem, and with it the near modes kept with it
    return modes_mod.resonances(_layout(name, *sets), "clamped_input")


@pytest.mark.parametrize("name", ["concrete_mixer", "fan_drive", "wind_turbine_gearbox"])
def test_the_near_modes_kept_for_a_chains_points_are_each_points_own(name):
    # one chain (the speed moves no tangent of a speed drive's chain), orders meeting different modes at each speed
    speeds = (150.0, 450.0, 900.0, 150.0, 2400.0) if name == "concrete_mixer" else (300.0, 900.0, 1500.0, 300.0)
    drive = () if name == "concrete_mixer" else ('input.drive="speed"',)
    cold = [_cold(name, *drive, f"input.speed_rpm={rpm!r}") for rpm in speeds]
    modes_mod._CHAINS.clear()
    warm = [modes_mod.resonances(_layout(name, *drive, f"input.speed_rpm={rpm!r}"), "clamped_input") for rpm in speeds]
    assert warm == cold
    if name == "concrete_mixer":
        assert cold[0] and cold[0] == cold[3]  # 150 rpm meets modes (the comparison is not of empty lists only)


def test_the_near_modes_follow_the_bodies_damping_and_the_connectors_names():
    """The same chain with another load law (the bodies' damping: other damping ratios) and the analysis's own modes:
    the kept modes are never another point's."""
    sets = ("input.speed_rpm=150.0",)
    modes_mod._CHAINS.clear()
    plain = modes_mod.resonances(_layout("concrete_mixer", *sets), "clamped_input")
    fan = modes_mod.resonances(_layout("concrete_mixer", *sets, "load.speed_exponent=2"), "clamped_input")
    assert fan == _cold("concrete_mixer", *sets, "load.speed_exponent=2")
    assert plain == _cold("concrete_mixer", *sets)
    lay = _layout("concrete_mixer", *sets)
    modes_mod.modal_analysis(lay, "clamped_input")  # the analysis made first: the long way, every mode
    assert modes_mod.resonances(lay, "clamped_input") == plain
    assert [r.damping_ratio for r in fan] != [r.damping_ratio for r in plain]


def _mesh_spec(static_N: list[float], backlash_m: float = 1e-4):
    import math

    from gearcli.model import DriveSpec, LoadSpec, MeshSpec, ModelSpec

    deg = math.pi / 180.0
    meshes = tuple(MeshSpec(base_radius_pinion_m=0.06, base_radius_gear_m=0.15, base_helix_angle_rad=10 * deg,
                            transverse_pressure_angle_rad=20.3 * deg, helix_angle_rad=10.6 * deg,
                            stiffness_N_m_e=2e8, exponent=1.5, damping_Ns_m=5e4, full_damping_m=1e-4,
                            contact_ratio=1.6, overlap_ratio=0.0, pinion_teeth=20, damping_ratio=0.05,
                            static_tangential_N=f, backlash_m=backlash_m) for f in static_N)
    return ModelSpec(meshes, (0.3,) * (len(meshes) + 1), DriveSpec("speed", 50.0), LoadSpec(300.0))


@pytest.mark.parametrize("periodic", [False, True])
def test_the_contact_check_on_the_windows_extremes_is_the_check_on_its_samples(periodic):
    """Penetration windows on either flank, touching 0 (and -0.0), crossing it, inside the backlash, and a window
    with a NaN (its reductions then numpy's: the samples decide): the same warnings, with and without the window
    reductions."""
    import numpy as np

    from gearcli import diagnostics as dg
    from gearcli.simulate import stats

    losses = []
    t = np.linspace(0.0, 1.0, 401)
    mask = t >= 0.4
    rng = np.random.default_rng(5)
    base = 1e-5 * (1.0 + 0.2 * rng.standard_normal(t.size))
    windows = [base, -base, np.where(t > 0.7, 0.0, base), np.where(t > 0.7, -0.0, base), base - 1.2e-5,
               -(base - 1.2e-5), np.zeros_like(t), np.where(t > 0.9, np.nan, base)]
    for signs in ([1.0, 1.0, -1.0], [-1.0, 1.0, 1.0], [1.0, -1.0, 1.0], [0.0, 1.0, -1.0]):
        for start in range(0, len(windows), 3):
            pens = [windows[(start + j) % len(windows)] for j in range(3)]
            spec = _mesh_spec([1000.0 * s for s in signs])
            per_stage = [(1e3 * p, 0.3 * p, 0.1 * p, p * 1e3, p * 1e6) for p in pens]
            reduced = stats.window_reductions(t, mask, per_stage, [m.static_tangential_N for m in spec.meshes],
                                              periodic)
            assert reduced is not None
            static = np.full(3, 5e-6)
            want = stats.contact_warnings(spec, mask, pens, static)
            got = stats.contact_warnings(spec, mask, pens, static, reduced)
            assert [(d.code, d.message, d.data) for d in got] == [(d.code, d.message, d.data) for d in want]
            losses.append(sum(d.code == dg.CONTACT_LOSS for d in want))
    assert 0 < sum(losses) < 3 * len(losses)  # stages that keep contact and stages that lose it, on either flank


@pytest.mark.parametrize("name", ["concrete_mixer", "mixer_planetary_motor", "wind_turbine_gearbox"])
def test_a_stages_tangential_force_on_a_float_is_tooth_forces_own(name):
    import numpy as np

    from gearcli.model.outputs import tangential_force_N, tooth_forces

    lay = _layout(name)
    forces = np.random.default_rng(3).normal(0.0, 1e5, 200)
    forces[:3] = (0.0, -0.0, 1e-300)
    for k in range(len(lay.spec.meshes)):
        want = tooth_forces(lay, k, forces)[0]
        np.testing.assert_array_equal([tangential_force_N(lay, k, f) for f in forces.tolist()], want)


@pytest.mark.parametrize("name", ["concrete_mixer", "concrete_mixer_te", "mixer_planetary_motor"])
@pytest.mark.parametrize("periodic", [False, True])
def test_the_stages_rows_in_one_array_are_the_series_and_their_reductions(name, periodic):
    """outputs.stage_rows (five rows a stage in one array) against tooth_forces and the units' scalings, bit for bit,
    and the window reductions copied from it against those stacked from the stages' series (a contiguous window and
    a window with a hole: a mask, not a slice)."""
    import numpy as np

    from gearcli.model import outputs
    from gearcli.simulate import stats

    model = TorsionalModel(api.model_spec(*_spec(name)))
    lay = model.layout
    t = np.linspace(0.0, 0.3, 301)
    rng = np.random.default_rng(17)
    Y = np.repeat(model.initial_state()[:, None], t.size, axis=1)
    Y[lay.state.deflections] = model.deflection_scales()[:, None] * rng.uniform(-0.5, 2.0, (lay.n_conn, t.size))
    s = outputs.sample(lay, t, Y)
    rows = outputs.stage_rows(lay, s.meshes)
    per_stage = []
    for k, ms in enumerate(s.meshes):
        ft, fr, fa = outputs.tooth_forces(lay, k, ms.line_force_N)
        want = (ft, fr, fa, ms.penetration_m * 1e3, ms.dte_m * 1e6)
        np.testing.assert_array_equal(rows[5 * k: 5 * k + 5], np.stack(want))
        per_stage.append(want)
    statics = [m.static_tangential_N for m in model.spec.meshes]
    for mask in (t >= 0.1, (t >= 0.1) & ((t < 0.2) | (t > 0.22))):
        stacked = stats.window_reductions(t, mask, per_stage, statics, periodic)
        copied = stats.window_reductions(t, mask, per_stage, statics, periodic, rows)
        assert stacked is not None and copied is not None
        assert np.array_equal(np.arange(t.size)[stacked.sel], np.arange(t.size)[copied.sel])  # the same samples
        for a, b in zip(stacked[:-2], copied[:-2], strict=True):  # every array, every element: equal
            np.testing.assert_array_equal(a, b)
            assert a.dtype == b.dtype
        assert all(x.flags.c_contiguous for x in (*stacked[:3], *copied[:3]))  # the times and rows the pass reads
        for a, b in zip(stacked.contact, copied.contact, strict=True):
            np.testing.assert_array_equal(a, b)


def _spec(name: str):
    loaded, design = api.load_and_design(str(ROOT / "configs" / f"{name}.toml"))
    return loaded.design, design
