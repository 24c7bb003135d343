"""The subcritical resonance bands of ISO 6336-1's N = n1/n_E1 (gearcli.design.resonance): the main range
(N_S, 1.15] divided by j = 2 and 3. Below N_S = 2 x 1.15 / 3 = 0.767 the bands overlap, and an N in both is
near both resonances: its 2nd and its 3rd harmonic both fall in the main range."""

from __future__ import annotations

import math

import pytest

from gearcli.design.checks import resonance_text
from gearcli.design.resonance import lower_main_resonance_limit, subharmonic_orders


def _harmonics_in_main_range(n: float, n_s: float) -> tuple[int, ...]:
    # by hand: the j-th harmonic of the mesh frequency excites the resonance when j N lies in (N_S, 1.15]
    return tuple(j for j in (2, 3) if n_s < j * n <= 1.15)


@pytest.mark.parametrize(("n", "n_s"), [(0.292, 0.5828), (0.35, 0.85), (0.5, 0.85), (0.2, 0.85), (0.3, 0.6)])
def test_the_orders_are_the_harmonics_in_the_main_range(n, n_s):
    assert subharmonic_orders(n, n_s) == _harmonics_in_main_range(n, n_s)


def test_a_light_load_ratio_in_both_bands_is_named_near_both():
    # a helical pair at 5.59 N/mm line load: N_S = 0.5 + 0.35 sqrt(5.59 / 100) = 0.5828 (ISO 6336-1 eq. 11)
    n_s = lower_main_resonance_limit(5.59)
    assert math.isclose(n_s, 0.5 + 0.35 * math.sqrt(0.0559), rel_tol=1e-12)
    text = resonance_text("stage 1: N = 0.292", 0.292, n_s, "subcritical")
    assert text is not None
    assert "N = 1/2" in text and "N = 1/3" in text and "second and third harmonics" in text
    # it used to name 1/2 only, the first band tried, though 0.292 lies nearer 1/3
    only = resonance_text("stage 1: N = 0.35", 0.35, 0.85, "subcritical")
    assert only is not None and "N = 1/3" in only and "N = 1/2" not in only and "third harmonic can" in only
