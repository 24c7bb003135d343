"""The dynamic factor a run measures, whatever the standard rates with it: max(1, steady-window max |F_t| over the
static F_t) per mesh (docs/output.md, ``dynamic_factor``); a standard's ``rate_simulation`` rates at it."""

from __future__ import annotations


def simulated_dynamic_factor(tangential_N, static_tangential_N: float) -> float:
    """K_v from a run: max(1, steady-window max |F_t| / |static F_t|), ``tangential_N`` the window's statistics
    (min, max) of F_t; 1 when the static force is 0 (no load to amplify)."""
    if static_tangential_N == 0.0:
        return 1.0
    peak = max(abs(tangential_N.max), abs(tangential_N.min))
    return max(1.0, peak / abs(static_tangential_N))


def stage_simulated_k_v(sd) -> float:
    """K_v of one simulated stage (``StageDynamics``): max(1, its window max |F_t| over the static F_t of the
    losses the run models, i.e. its ``dynamic_factor``; the design's static F_t where the run has none). A
    planetary stage's: the largest over its planets' sun meshes."""
    static = sd.simulated_static_tangential_N
    static = sd.static_tangential_N if static is None else static
    k_v = simulated_dynamic_factor(sd.tangential_N, static)
    for p in getattr(sd, "planets", ()):
        k_v = max(k_v, simulated_dynamic_factor(p.sun.tangential_N, static))
    return k_v


def ring_simulated_k_v(sd, stage) -> float:
    """K_v of a planetary stage's planet–ring meshes: the largest over its planets of the window max |F_t| over
    the ring mesh's static F_t (the sun mesh's static of the run, times the design's ring/sun force ratio)."""
    p = stage.planetary
    static = sd.simulated_static_tangential_N
    static = sd.static_tangential_N if static is None else static
    if stage.static_force_N.tangential != 0.0:
        static = static * p.planet_ring.static_force_N.tangential / stage.static_force_N.tangential
    return max((simulated_dynamic_factor(q.ring.tangential_N, static) for q in sd.planets), default=1.0)
