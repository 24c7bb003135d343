"""The mesh law's eight numbers for the default Hertzian contact (e = 1.5, constant stiffness) against the IMPACT
law written out by hand: F_n = K p^1.5 + STEP(p, 0, 0, d, C) p', clamped at 0, on either flank beyond half the
backlash; the law computes this case's elastic term in place (the Python right-hand side's hot path), so its
force, slopes and powers are checked here, where the ramp is partial, full and where the damper would pull."""

from __future__ import annotations

import math

import pytest

from gearcli.model.elements import N_PARAM, mesh

CB = math.cos(math.radians(13.0))
K = 3.0e9  # N/m^1.5
C = 5.0e4  # N s/m, reached at the full damping depth D
D = 1e-4
HALF = 2e-5


def _row(damping: float = C) -> tuple[float, ...]:
    P = [0.0] * N_PARAM
    P[mesh.I_CB], P[mesh.I_CB2], P[mesh.I_K], P[mesh.I_E] = CB, CB * CB, K, 1.5
    P[mesh.I_C], P[mesh.I_INVD], P[mesh.I_DC] = damping, 1.0 / D, 6.0 * damping / D
    P[mesh.I_HALF], P[mesh.I_D] = HALF, D
    return tuple(P)


def _by_hand(q: float, qd: float, damping: float = C) -> tuple[float, ...]:
    """(F, dF/dq, dF/dq', dF/dphi, 0, damping power, time-varying spring power, 0) from the IMPACT law."""
    h = CB * q
    if abs(h) <= HALF:
        return (0.0,) * 8
    sign = 1.0 if h > 0 else -1.0
    p, pd = abs(h) - HALF, sign * CB * qd  # penetration beyond the gap and its rate
    s = min(p / D, 1.0)
    c = damping * s * s * (3 - 2 * s)  # STEP(p, 0, 0, D, C)
    dc = 6 * damping * s * (1 - s) / D if s < 1.0 else 0.0
    fe = K * p ** 1.5
    fn = fe + c * pd
    if fn <= 0.0:  # the damper would pull the teeth together: no force, the damper cancels the spring
        return 0.0, 0.0, 0.0, 0.0, 0.0, -fe * pd, 0.0, 0.0
    return (sign * CB * fn, CB * CB * (1.5 * K * math.sqrt(p) + dc * pd), CB * CB * c, 0.0, 0.0, (fn - fe) * pd,
            0.0, 0.0)


@pytest.mark.parametrize("q", [3e-5, 6e-5, 1.5e-4, -6e-5, -1.5e-4])  # partial and full damping, both flanks
@pytest.mark.parametrize("qd", [0.0, 2e-3, -2e-3, -0.5])  # -0.5: the clamp on the drive flank
@pytest.mark.parametrize("damping", [C, 0.0])
def test_the_hertzian_law_is_the_impact_law(q, qd, damping):
    got = mesh.law(_row(damping), q, qd, 0.0)
    want = _by_hand(q, qd, damping)
    assert got == pytest.approx(want, rel=1e-12, abs=1e-9)
    assert mesh.force(_row(damping), q, qd, 0.0, 0.0) == got  # no transmission error: force is the law


def test_inside_the_backlash_there_is_no_force():
    assert mesh.law(_row(), 1e-5, 0.3, 0.0) == (0.0,) * 8
