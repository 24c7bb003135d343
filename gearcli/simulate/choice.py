"""``method = "auto"``: explicit or implicit, from the linearised stiffness of the scene.

The model is linearised (:func:`gearcli.model.linearise`) twice: at full static load (the reported
natural frequencies) and at the larger of the static and the rigid-body run-up force of each mesh,
with a time-varying stiffness at its stiffest phase (a Hertz mesh stiffens with its load, so the run-up
sets the largest eigenvalue). The stiffness indicator is ``max|lambda| T`` over both, T the run length.

An explicit method needs at least ``max|lambda| T / R`` steps to stay stable, R the size of its
stability region along the direction of the eigenvalue; the mesh modes are lightly damped, so that
direction is near the imaginary axis, where R = 6.0 for DOP853 (12 evaluations per step) and only
1-3 for RK45 (6 per step): DOP853 is the cheaper explicit method per unit of stability and the more
accurate one (benchmarks/bench_simulate.py). The implicit Radau IIA (order 5, L-stable, analytic
Jacobian) costs a roughly fixed ~1-4e4 evaluation-equivalents on these scenes whatever the stiffness,
because its steps follow accuracy, not stability. The break-even measured on the seed reducer and its
stiff variants (configs/stiff_linear_mesh.toml, and stiffer ones in the benchmark) lies at
``max|lambda| T`` of about 1e4, i.e. ~2e4 explicit evaluations: auto picks DOP853 up to
``STIFFNESS_LIMIT`` and Radau above it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearcli.model import Layout, Linearisation, ModelSpec, linearise
from gearcli.model.linear import peak_rigid_forces, static_forces
from gearcli.simulate.methods import AUTO, EXPLICIT, EXPLICIT_METHOD, IMPLICIT_METHOD, method

STIFFNESS_LIMIT = 1.0e4  # max|lambda| T above which "auto" integrates implicitly
__all__ = ["EXPLICIT", "EXPLICIT_METHOD", "IMPLICIT_METHOD", "STIFFNESS_LIMIT", "Choice", "choose_method"]


@dataclass(frozen=True)
class Choice:
    method: str
    requested: str
    reason: str
    indicator: float  # max|lambda| T
    stiffness_ratio: float  # max|lambda| / min|lambda|
    at_full_load: Linearisation
    at_operating_point: Linearisation
    stiffest_mesh: int  # 0-based stage of the mesh with the highest single-mesh frequency
    spec: ModelSpec
    layout: Layout

    @property
    def natural_frequencies_Hz(self) -> tuple[float, ...]:
        """Undamped natural frequencies to report: at full load, or at the run-up load when a connector
        has no stiffness at full load (an unloaded Hertzian mesh); zero modes left out."""
        unloaded = bool(np.any(self.at_full_load.stiffness == 0.0))
        lin = self.at_operating_point if unloaded else self.at_full_load
        return tuple(float(f) for f in lin.natural_frequencies_Hz if f > 0)

    @property
    def boundary(self) -> str:
        """The boundary condition of the reported frequencies: a speed drive holds the input body."""
        return "clamped_input" if self.layout.speed_drive else "free"

    def explicit_evaluations(self, name: str = EXPLICIT_METHOD) -> float:
        """Fewest right-hand-side evaluations an explicit method needs for stability alone."""
        m = method(name)
        return m.evals_per_step * self.indicator / m.stability_radius


def _stiffest_mesh(lin: Linearisation, lay: Layout) -> int:
    """The mesh whose own mode (its stiffness against the two inertias it joins) is fastest."""
    own = []
    for c in lay.stage_conn:
        x = lay.connectors[c]
        mobility = (x.ra**2 / lay.inertias[x.a] if lay.i_omega(x.a) is not None else 0.0) \
            + x.rb**2 / lay.inertias[x.b]
        own.append(lin.stiffness[c] * mobility)
    return int(np.argmax(own))


def choose_method(spec: ModelSpec, duration_s: float, requested: str) -> Choice:
    """The method to run and why (``requested`` other than "auto" is kept, with the indicator)."""
    lay = Layout.of(spec)
    static = static_forces(lay)
    full = linearise(lay, static)
    operating = np.maximum(np.abs(static), peak_rigid_forces(lay, duration_s))
    op = linearise(lay, operating, stiffest_phase=True)
    lam = max(full.max_abs_eigenvalue, op.max_abs_eigenvalue)
    low = min((x for x in (full.min_abs_eigenvalue, op.min_abs_eigenvalue) if x > 0), default=0.0)
    indicator = lam * duration_s
    ratio = lam / low if low > 0 else math.inf
    summary = f"max|λ|·T = {indicator:.3g}"
    if requested != AUTO:
        chosen, reason = requested, f"as requested ({summary})"
    elif indicator <= STIFFNESS_LIMIT:
        chosen = EXPLICIT_METHOD
        reason = f"{summary} ≤ {STIFFNESS_LIMIT:.0e}: explicit {chosen}"
    else:
        chosen = IMPLICIT_METHOD
        reason = f"{summary} > {STIFFNESS_LIMIT:.0e}: implicit {chosen} with the analytic Jacobian"
    return Choice(chosen, requested, reason, indicator, ratio, full, op, _stiffest_mesh(op, lay), spec, lay)



def unit_costs(spec: ModelSpec, repeat: int = 200) -> dict[str, float]:
    """Microseconds per right-hand side, per Jacobian and per LU pair (Radau factors one real and one
    complex matrix of the state's size) of the scene, measured (benchmarks/bench_auto.py)."""
    import time

    import scipy.linalg

    from gearcli.model import TorsionalModel

    model = TorsionalModel(spec)
    y = model.initial_state()
    y = y + 1e-9 * np.arange(y.size)
    jac = np.asarray(model.jac(0.1, y), dtype=float)

    def per_call(fn) -> float:
        fn()
        t0 = time.perf_counter()
        for _ in range(repeat):
            fn()
        return (time.perf_counter() - t0) / repeat * 1e6

    eye = np.eye(y.size)
    return {"rhs": per_call(lambda: model.rhs(0.1, y)), "jac": per_call(lambda: model.jac(0.1, y)),
            "lu_pair": per_call(lambda: (scipy.linalg.lu_factor(eye - 0.1 * jac, check_finite=False),
                                         scipy.linalg.lu_factor((1 + 1j) * eye - 0.1 * jac, check_finite=False))),
            "n_states": float(y.size)}
