"""The mesh's right-hand-side hook (``rhs_force``): the force and the damping power of a phase-free row, the two
numbers the generated Python right-hand side reads of it. Against a hand calculation of the IMPACT and viscous laws,
bit for bit against the full law over both flanks, the backlash and the exponents the law takes apart, and in the
generated ``rhs``: called for phase-free meshes only, with the numbers of the right-hand side that calls the full
law."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gearcli.model import DriveSpec, LoadSpec, MeshSpec, ModelSpec, TorsionalModel, elements
from gearcli.model.elements import N_PARAM, mesh

CB = math.cos(math.radians(13.0))
K = 3.0e9  # N/m^e
C = 5.0e4  # Ns/m, reached at the full damping depth
D_FULL = 1e-4  # m


def _row(exponent: float, half_gap_m: float, damping: float, viscous: float | None) -> np.ndarray:
    P = np.zeros(N_PARAM)
    P[mesh.I_CB], P[mesh.I_CB2], P[mesh.I_K], P[mesh.I_E] = CB, CB * CB, K, exponent
    P[mesh.I_C], P[mesh.I_INVD], P[mesh.I_DC] = damping, 1.0 / D_FULL, 6.0 * damping / D_FULL
    P[mesh.I_HALF], P[mesh.I_D], P[mesh.I_Z] = half_gap_m, D_FULL, 17.0
    if viscous is not None:
        P[mesh.I_VIS], P[mesh.I_CV] = 1.0, viscous
    return tuple(P.tolist())  # as the generated code holds it


def test_the_impact_law_by_hand():
    """Hertz (e = 1.5) with the IMPACT ramp: F = cb (K p^1.5 + C s^2 (3 - 2 s) p'), s = p / d, p = cb delta - g/2,
    p' = cb delta'; the damping power c(p) p'^2. On the back flank every sign turns; in the gap nothing acts."""
    half = 1e-5
    P = _row(1.5, half, C, None)
    for delta, rate in ((5.0e-5, 0.2), (-7.0e-5, -0.1), (1.2e-4, -0.05)):
        sign = 1.0 if delta > 0 else -1.0
        p = sign * CB * delta - half
        pd = sign * CB * rate
        s = min(p / D_FULL, 1.0)
        c = C * s * s * (3.0 - 2.0 * s)
        normal = K * p ** 1.5 + c * pd
        F, power = mesh.rhs_force(P, delta, rate)
        assert F == pytest.approx(sign * CB * max(normal, 0.0), rel=1e-12)
        assert power == pytest.approx(c * pd * pd if normal > 0.0 else -K * p ** 1.5 * pd, rel=1e-12)
    assert mesh.rhs_force(P, 0.5 * half / CB, 0.3) == (0.0, 0.0)  # inside the backlash


def test_the_viscous_law_by_hand():
    """The viscous damper acts in the gap too: F = c_v delta' there, cb K p + c_v delta' on a flank (e = 1);
    its power c_v delta'^2."""
    cv = 3.0e3
    P = _row(1.0, 2e-5, 0.0, cv)
    assert mesh.rhs_force(P, 0.0, 0.4) == pytest.approx((cv * 0.4, cv * 0.16), rel=1e-15)
    delta = 9e-5
    F, power = mesh.rhs_force(P, delta, -0.3)
    assert F == pytest.approx(CB * K * (CB * delta - 2e-5) + cv * -0.3, rel=1e-12)
    assert power == pytest.approx(cv * 0.09, rel=1e-12)


states = st.lists(st.tuples(st.floats(-2e-4, 2e-4), st.floats(-0.5, 0.5)), min_size=1, max_size=40)


@settings(max_examples=80, deadline=None)
@given(states, st.sampled_from((1.0, 1.5, 2.0, 1.3, 2.5)), st.sampled_from((0.0, 2e-5)), st.sampled_from((0.0, 5e4)),
       st.sampled_from((None, 0.0, 3e3)))
def test_the_laws_force_and_damping_power_to_the_bit(pairs, exponent, half_gap, damping, viscous):
    P = _row(exponent, half_gap, damping, viscous)
    for d, dd in pairs:
        full = mesh.force(P, d, dd, 0.0, 0.0)
        assert mesh.rhs_force(P, d, dd) == (full[0], full[5])


def _mesh(**kw) -> MeshSpec:
    base = dict(base_radius_pinion_m=0.05, base_radius_gear_m=0.17, base_helix_angle_rad=math.radians(12.0),
                transverse_pressure_angle_rad=math.radians(20.5), helix_angle_rad=math.radians(12.7),
                stiffness_N_m_e=3.0e10, exponent=1.5, damping_Ns_m=4.0e4, full_damping_m=1.0e-4,
                contact_ratio=1.55, overlap_ratio=0.8, pinion_teeth=19, normal_module_m=0.005)
    return MeshSpec(**{**base, **kw})


def test_the_generated_rhs_calls_it_for_phase_free_meshes_with_the_same_numbers(monkeypatch):
    """Three meshes: Hertz with the IMPACT ramp and backlash, linear viscous, time-varying (phased: the full law).
    The rhs keeps, bit for bit, the numbers of the rhs generated without the hook."""
    spec = ModelSpec((_mesh(backlash_m=3e-5), _mesh(exponent=1.0, stiffness_N_m_e=4e8, damping_ratio=0.05),
                      _mesh(time_varying=True)), (0.4, 6.0, 30.0, 150.0),
                     DriveSpec("speed", 50.0, 0.1, 0.0), LoadSpec(800.0, 0.05))
    hooked = TorsionalModel(spec)
    source = hooked.source
    assert "_rhs0(_P0, d0, dd0)" in source and "_rhs1(_P1, d1, dd1)" in source
    assert "_rhs2" not in source and "= _force2(" in source
    hooked_rhs = hooked.rhs  # generated now, with the hook (the functions are made on first use)
    assert "_rhs0" in hooked_rhs.__code__.co_names
    monkeypatch.setattr(elements, "RHS_HOOK", "no_such_hook")
    plain = TorsionalModel(spec)
    assert "_rhs" not in plain.source
    rng = np.random.default_rng(7)
    lay = hooked.layout
    for _ in range(200):
        y = hooked.initial_state()
        for c in range(lay.n_conn):
            y[lay.state.delta(c)] = rng.uniform(-1.5e-4, 1.5e-4)
        for i in lay.free_bodies:
            y[lay.state.omega(i)] = rng.uniform(-60.0, 60.0)
        t = float(rng.uniform(0.0, 0.3))
        np.testing.assert_array_equal(hooked_rhs(t, y), plain.rhs(t, y))


def test_an_element_without_the_hook_keeps_the_full_law():
    from gearcli.model.elements import spring

    assert not hasattr(spring, elements.RHS_HOOK)


def test_the_generated_rhs_feeds_the_laws_floats(monkeypatch):
    """scipy's stages pass the time as a numpy scalar: the rhs takes it as a float, so the drive's motion, the
    deflection rates and the laws compute on floats (the same doubles, faster) rather than on numpy scalars."""
    seen = []
    real = mesh.rhs_force

    def spy(P, d, dd):
        seen.append((type(d), type(dd)))
        return real(P, d, dd)

    monkeypatch.setattr(mesh, "rhs_force", spy)
    spec = ModelSpec((_mesh(), _mesh(base_radius_pinion_m=0.07)), (0.4, 6.0, 30.0), DriveSpec("speed", 50.0, 0.1, 0.0),
                     LoadSpec(800.0, 0.05))
    model = TorsionalModel(spec)
    y = model.initial_state()
    f = model.rhs(np.float64(0.05), y)  # in the drive's ramp: its speed and acceleration depend on t
    assert len(seen) == 2 and all(a is float and b is float for a, b in seen)
    np.testing.assert_array_equal(f, model.rhs(0.05, y))
